"""A malformed EDS stops the import with "error: <file>:<line>: <problem>"
(exit code 1, no description written); a well-formed file with an object the
C dictionary cannot hold imports with a warning naming file, line, object
and reason; the description keys the import added check their values."""
from __future__ import annotations

import re
import textwrap
from pathlib import Path

import pytest

from conftest import run_import, run_odgen

GOOD = """\
[FileInfo]
FileName=bad.eds
EDSVersion=4.0

[DeviceInfo]
VendorName=v
VendorNumber=1

[MandatoryObjects]
SupportedObjects=3
1=0x1000
2=0x1001
3=0x1018

[1000]
ParameterName=Device type
ObjectType=0x7
DataType=0x0007
AccessType=ro
DefaultValue=0
PDOMapping=0

[1001]
ParameterName=Error register
ObjectType=0x7
DataType=0x0005
AccessType=ro
PDOMapping=0

[1018]
ParameterName=Identity
ObjectType=0x9
SubNumber=2

[1018sub0]
ParameterName=Highest sub-index supported
ObjectType=0x7
DataType=0x0005
AccessType=const
DefaultValue=1
PDOMapping=0

[1018sub1]
ParameterName=Vendor-ID
ObjectType=0x7
DataType=0x0007
AccessType=ro
DefaultValue=1
PDOMapping=0
"""


def imports(tmp_path: Path, text: str):
    src = tmp_path / "bad.eds"
    src.write_text(text)
    toml = tmp_path / "bad.toml"
    return src, toml, run_import(src, toml)


def fails_with(tmp_path: Path, text: str, line: int | None, *needles: str) -> str:
    src, toml, r = imports(tmp_path, text)
    assert r.returncode == 1, f"accepted:\n{text}"
    msg = r.stderr.strip()
    assert "Traceback" not in msg
    prefix = f"error: {src}:{line}: " if line else f"error: {src}: "
    assert msg.startswith(prefix), msg
    for n in needles:
        assert n in msg, msg
    assert not toml.exists(), "wrote a description despite the error"
    return msg


def line_of(text: str, needle: str, nth: int = 1) -> int:
    lines = [k for k, x in enumerate(text.splitlines(), 1) if x == needle]
    return lines[nth - 1]


def test_good_file_imports(tmp_path):
    src, toml, r = imports(tmp_path, GOOD)
    assert r.returncode == 0, r.stderr
    assert r.stderr == ""
    g = run_odgen(toml, tmp_path / "out")
    assert g.returncode == 0, g.stderr


def test_line_that_is_not_key_value(tmp_path):
    text = GOOD.replace("AccessType=ro\nPDOMapping=0\n", "AccessType ro\nPDOMapping=0\n", 1)
    fails_with(tmp_path, text, line_of(text, "AccessType ro"),
               "expected 'key=value' or '[section]', got 'AccessType ro'")


def test_malformed_section_header(tmp_path):
    text = GOOD.replace("[1001]", "[1001")
    fails_with(tmp_path, text, line_of(text, "[1001"), "malformed section header '[1001'")


def test_section_given_twice(tmp_path):
    text = GOOD + "\n[1001]\nParameterName=again\n"
    fails_with(tmp_path, text, line_of(text, "[1001]", 2),
               f"section [1001] given twice (first at line {line_of(text, '[1001]')})")


def test_section_given_twice_in_other_case(tmp_path):
    text = GOOD + "\n[1018SUB1]\nParameterName=again\n"
    fails_with(tmp_path, text, line_of(text, "[1018SUB1]"), "section [1018SUB1] given twice")


def test_key_given_twice(tmp_path):
    text = GOOD.replace("DataType=0x0005\nAccessType=ro\n",
                        "DataType=0x0005\nDATATYPE=0x0006\nAccessType=ro\n", 1)
    fails_with(tmp_path, text, line_of(text, "DATATYPE=0x0006"),
               "key DATATYPE given twice in [1001] (first at line")


def test_key_before_first_section(tmp_path):
    fails_with(tmp_path, "EDSVersion=4.0\n" + GOOD, 1, "key 'EDSVersion' before the first [section]")


def test_no_device_info(tmp_path):
    text = GOOD.replace("[DeviceInfo]\nVendorName=v\nVendorNumber=1\n", "")
    fails_with(tmp_path, text, None, "no [DeviceInfo] section (CiA 306 requires it)")


def test_sub_entry_without_object(tmp_path):
    text = GOOD + "\n[2000sub1]\nParameterName=orphan\n"
    fails_with(tmp_path, text, line_of(text, "[2000sub1]"),
               "[2000sub1] belongs to object 0x2000, which has no [2000] section")


def test_var_with_sub_entries(tmp_path):
    text = GOOD + "\n[1001sub1]\nParameterName=stray\n"
    fails_with(tmp_path, text, line_of(text, "[1001sub1]"),
               "object 0x1001 is a VAR and has no sub-entries")


def test_object_without_parameter_name(tmp_path):
    text = GOOD.replace("ParameterName=Error register\n", "")
    fails_with(tmp_path, text, line_of(text, "[1001]"), "[1001] without ParameterName")


def test_var_without_data_type(tmp_path):
    text = GOOD.replace("DataType=0x0005\nAccessType=ro\nPDOMapping=0\n",
                        "AccessType=ro\nPDOMapping=0\n", 1)
    fails_with(tmp_path, text, line_of(text, "[1001]"), "[1001] without DataType")


def test_object_type_not_a_number(tmp_path):
    text = GOOD.replace("ObjectType=0x9", "ObjectType=RECORD")
    fails_with(tmp_path, text, line_of(text, "ObjectType=RECORD"),
               "[1018] ObjectType: 'RECORD' is not a number")


COMPACT = """
[2000]
ParameterName=Array
ObjectType=0x8
DataType=0x0005
AccessType=rw
PDOMapping=0
CompactSubObj=2
"""


def test_compact_and_sub_number(tmp_path):
    text = GOOD + COMPACT.replace("CompactSubObj=2", "CompactSubObj=2\nSubNumber=3")
    fails_with(tmp_path, text, line_of(text, "SubNumber=3"),
               "[2000] has both SubNumber and CompactSubObj")


def test_compact_with_sub_sections(tmp_path):
    text = GOOD + COMPACT + "\n[2000sub1]\nParameterName=x\n"
    fails_with(tmp_path, text, line_of(text, "[2000sub1]"),
               "object 0x2000 has CompactSubObj=2, so no sub-entry sections")


def test_compact_count_out_of_range(tmp_path):
    text = GOOD + COMPACT.replace("CompactSubObj=2", "CompactSubObj=0x100")
    fails_with(tmp_path, text, line_of(text, "CompactSubObj=0x100"),
               "[2000] CompactSubObj=256 must be 1..254")


def test_name_section_count_wrong(tmp_path):
    text = GOOD + COMPACT + "\n[2000Name]\nNrOfEntries=2\n1=first\n"
    fails_with(tmp_path, text, line_of(text, "NrOfEntries=2"),
               "[2000Name] NrOfEntries=2 but 1 entries")


def test_name_outside_the_array(tmp_path):
    text = GOOD + COMPACT + "\n[2000Name]\nNrOfEntries=1\n5=fifth\n"
    fails_with(tmp_path, text, None, "[2000Name] names sub-index 5, outside 1..2")


def test_comment_lines_missing(tmp_path):
    text = GOOD + "\n[Comments]\nLines=3\nLine1=a\nLine3=c\n"
    fails_with(tmp_path, text, line_of(text, "Lines=3"), "[Comments] Lines=3 but lines [1, 3]")


def test_object_list_entry_not_a_number(tmp_path):
    text = GOOD.replace("3=0x1018", "3=0x10X8")
    fails_with(tmp_path, text, line_of(text, "3=0x10X8"),
               "[MandatoryObjects] 3: '0x10X8' is not a number")


def test_missing_file(tmp_path):
    src = tmp_path / "nowhere.eds"
    r = run_import(src, tmp_path / "x.toml")
    assert r.returncode == 1
    assert r.stderr.strip() == f"error: {src}: cannot read: No such file or directory"


def test_oddities_are_kept(tmp_path):
    """Empty FileName/EDSVersion, keys with blanks, a comment line starting with
    ';', an unknown section: imported and written back unchanged."""
    from roundtrip import semantic_differences
    text = (GOOD.replace("FileName=bad.eds", "FileName=").replace("EDSVersion=4.0", "EDSVersion=")
            .replace("VendorNumber=1", "VendorNumber=1\nBaud Rate (kbit/s)=125")
            + "\n[Comments]\nLines=1\nLine1=;not a comment\n\n[Vendor Tool 2.0]\nx y=1\n"
            + "\n[ManufacturerObjects]\nSupportedObjects=1\n1=0x2000\n"
            + "\n[2000]\nParameterName=Odd key\nDataType=0x0005\nAccessType=rw\n"
            + "Max. value (V)=5\n")
    src, toml, r = imports(tmp_path, text)
    assert r.returncode == 0, r.stderr
    assert r.stderr == ""
    g = run_odgen(toml, tmp_path / "out")
    assert g.returncode == 0, g.stderr
    assert semantic_differences(src, tmp_path / "out" / "bad.eds") == []


# ------------------------------------------- objects odgen keeps verbatim

@pytest.mark.parametrize("section, reason", [
    ("DataType=0x0005\nAccessType=rw\nDefaultValue=0x100\n", "'0x100' does not fit UNSIGNED8"),
    ("DataType=0x0005\nAccessType=rw\nDefaultValue=five\n", "'five' is not an integer"),
    ("DataType=0x0005\nAccessType=readwrite\n", "AccessType 'readwrite' is not one of CiA 306's"),
    ("DataType=0x0005\nAccessType=rw\nPDOMapping=2\n", "PDOMapping '2' is out of range 0..1"),
    ("DataType=0x0017\nAccessType=rw\n", "data type 0x0017 is not a CiA 301 basic type"),
    ("DataType=0x0005\nAccessType=rw\nLowLimit=10\nHighLimit=5\n",
     "low_limit 10 is above high_limit 5"),
    ("DataType=0x0005\nAccessType=rw\nDefaultValue=1\nLowLimit=2\n",
     "default 1 is out of limits [2, 255]"),
    ("DataType=0x0005\nAccessType=rww\nPDOMapping=0\n", "access rww means PDO-mappable"),
    ("DataType=0x0008\nAccessType=rw\nHighLimit=1.5\n", "limit 1.5 is not an integer"),
    ("DataType=0x0005\nAccessType=rw\nObjFlags=x\n", "ObjFlags 'x' is not a number"),
], ids=["too-big", "not-a-number", "access", "pdo-mapping", "type", "limits", "out-of-limits",
        "rww-unmapped", "real-limit", "objflags"])
def test_object_kept_verbatim_with_a_warning(tmp_path, section, reason):
    text = (GOOD + "\n[ManufacturerObjects]\nSupportedObjects=1\n1=0x2000\n"
            + f"\n[2000]\nParameterName=Odd\nObjectType=0x7\n{section}")
    src, toml, r = imports(tmp_path, text)
    assert r.returncode == 0, r.stderr
    line = line_of(text, "[2000]")
    assert re.fullmatch(rf"warning: {re.escape(str(src))}:{line}: object 0x2000 kept as "
                        r"eds_only \(not in the C dictionary\): .*", r.stderr.strip()), r.stderr
    assert reason in r.stderr, r.stderr
    t = toml.read_text()
    assert "index = 0x2000\neds_only = " in t and reason in t
    g = run_odgen(toml, tmp_path / "out")
    assert g.returncode == 0, g.stderr
    eds = (tmp_path / "out" / "bad.eds").read_text()
    assert "[2000]\nParameterName=Odd\nObjectType=0x7\n" + section in eds


def test_mapping_of_an_eds_only_object(tmp_path):
    """A default PDO mapping of an object kept verbatim is kept verbatim too."""
    text = GOOD + textwrap.dedent("""
        [2000]
        ParameterName=Odd
        DataType=0x0017
        AccessType=ro
        PDOMapping=1

        [1A00]
        ParameterName=TPDO1 mapping
        ObjectType=0x9
        SubNumber=2

        [1A00sub0]
        ParameterName=Number of mapped objects
        DataType=0x0005
        AccessType=rw
        DefaultValue=1

        [1A00sub1]
        ParameterName=Mapped object 1
        DataType=0x0007
        AccessType=rw
        DefaultValue=0x20000020
        """)
    src, toml, r = imports(tmp_path, text)
    assert r.returncode == 0, r.stderr
    assert "object 0x1A00 kept as eds_only (not in the C dictionary): sub 1: default mapping " \
           "0x20000020 maps 0x2000 sub 0, which is eds_only" in r.stderr


# ------------------------------------------------ the description keys

BASE = """
[device]
name = "bad"
vendor_id = 1
device_type = 0

[[object]]
index = 0x1001
name = "Error register"
type = "UNSIGNED8"
access = "ro"
"""


@pytest.mark.parametrize("text, needles", [
    ("""
     [[object]]
     index = 0x2000
     name = "A"
     array = 2
     compact = true
     element = { type = "UNSIGNED8" }
     subs = []
     """, ["object 0x2000", "use either array = N or subs"]),
    ("""
     [[object]]
     index = 0x2000
     name = "A"
     object = "ARRAY"
     compact = true
     subs = [{ sub = 1, name = "a", type = "UNSIGNED8" }, { sub = 2, name = "b", type = "UNSIGNED16" }]
     """, ["object 0x2000", "the elements of an ARRAY share one data type"]),
    ("""
     [[object]]
     index = 0x2000
     name = "A"
     object = "RECORD"
     compact = true
     subs = [{ sub = 1, name = "a", type = "UNSIGNED8" }, { sub = 2, name = "b", type = "UNSIGNED8", default = 1 }]
     """, ["object 0x2000 sub 2: compact = true, but this element's type, access, PDO mapping, "
           "default or limits differ"]),
    ("""
     [[object]]
     index = 0x2000
     name = "A"
     object = "RECORD"
     compact = true
     subs = [{ sub = 0, name = "n", type = "UNSIGNED8", access = "const", default = 1 }, { sub = 1, name = "a", type = "UNSIGNED8" }]
     """, ["object 0x2000: compact = true: sub-index 0 must be the implied one (NrOfObjects"]),
    ("""
     [[object]]
     index = 0x2000
     name = "A"
     object = "RECORD"
     compact = true
     subs = [{ sub = 1, name = "a", type = "UNSIGNED8" }, { sub = 3, name = "c", type = "UNSIGNED8" }]
     """, ["object 0x2000: compact = true needs the sub-indices 1..N without gaps"]),
    ("""
     [[object]]
     index = 0x2000
     name = "V"
     type = "UNSIGNED8"
     compact = true
     """, ["object 0x2000: compact (CompactSubObj) is for an ARRAY or RECORD"]),
    ("""
     [[object]]
     index = 0x2000
     name = "V"
     type = "UNSIGNED8"
     eds_keys = { DefaultValue = "3" }
     """, ["object 0x2000 sub 0: eds_keys key DefaultValue is a CiA 306 key the description "
           "states itself"]),
    ("""
     [[object]]
     index = 0x2000
     name = "V"
     type = "UNSIGNED8"
     eds_keys = { Unit = 3 }
     """, ["object 0x2000 sub 0: eds_keys Unit must be text"]),
    ("""
     [[object]]
     index = 0x2000
     name = "V"
     type = "UNSIGNED8"
     obj_flags = -1
     """, ["object 0x2000 sub 0: obj_flags must be an UNSIGNED32"]),
    ("""
     [[object]]
     index = 0x2000
     name = "V"
     type = "UNSIGNED8"
     links = ["0x6000"]
     """, ["object 0x2000: links must be a list of indices"]),
    ("""
     [[object]]
     index = 0x2000
     name = "V"
     type = "UNSIGNED64"
     low_limit = "$NODEID+1"
     """, ["object 0x2000 sub 0: $NODEID limits need an 8/16/32-bit type"]),
    ("""
     [[object]]
     index = 0x2000
     name = "V"
     type = "UNSIGNED8"
     default = "$NODEID"
     high_limit = "$NODEID+0x10"
     low_limit = "$NODEID+0x1"
     """, ["object 0x2000 sub 0: default $NODEID+0 is out of limits [$NODEID+1, $NODEID+16]"]),
    ("""
     [[object]]
     index = 0x2000
     name = "V"
     type = "UNSIGNED8"
     low_limit = "$NODEID+0x90"
     """, ["object 0x2000 sub 0: limit $NODEID+144 does not fit UNSIGNED8 [0, 255]"]),
    ("""
     [[object]]
     index = 0x2000
     name = "V"
     type = "UNSIGNED8"
     parameter_value = 300
     """, ["object 0x2000 sub 0: parameter_value 300 does not fit UNSIGNED8"]),
    ("""
     [[object]]
     index = 0x2000
     eds_only = "because"
     [object.sections."2001"]
     ParameterName = "x"
     """, ['object 0x2000: eds_only needs sections, the first one "2000"']),
    ("""
     [[object]]
     index = 0x2000
     eds_only = "because"
     [object.sections."2000"]
     ParameterName = "x"
     [object.sections."2001sub1"]
     ParameterName = "y"
     """, ["object 0x2000: section '2001sub1' does not belong to object 2000"]),
    ("""
     [eds]
     dummy_usage = [8]
     """, ["[eds] dummy_usage must list data type indices 1..7"]),
    ("""
     [eds.sections.MandatoryObjects]
     SupportedObjects = "1"
     """, ["[eds.sections] 'MandatoryObjects': not a section the description may add"]),
    ("""
     [dcf]
     node_id = 128
     """, ["[dcf] node_id must be an integer 0..127"]),
    ("""
     [[object]]
     index = 0x1A00
     name = "TPDO1 mapping"
     object = "RECORD"
     subs = [{ sub = 0, name = "n", type = "UNSIGNED8", default = 1 }, { sub = 1, name = "m", type = "UNSIGNED32", default = 0x00050008 }]
     """, ["object 0x1A00 sub 1: default mapping 0x00050008 maps 0x0005 sub 0, a dummy entry "
           "[eds] dummy_usage does not allow"]),
], ids=["compact-array-and-subs", "compact-types", "compact-defaults", "compact-sub0",
        "compact-gap", "compact-var", "eds-keys-standard", "eds-keys-text", "obj-flags", "links",
        "nodeid-limit-64", "nodeid-out-of-limits", "nodeid-limit-fit", "parameter-value",
        "eds-only-first", "eds-only-foreign", "dummy-usage", "eds-sections-derived",
        "dcf-node-id", "dummy-mapping"])
def test_description_key_mistakes(tmp_path, text, needles):
    src = tmp_path / "bad.toml"
    body = textwrap.dedent(text)
    if body.lstrip().startswith("[eds") or body.lstrip().startswith("[dcf"):
        src.write_text(BASE.replace("[[object]]", body + "\n[[object]]", 1))
    else:
        src.write_text(BASE + body)
    r = run_odgen(src, tmp_path / "out")
    assert r.returncode == 1, src.read_text()
    msg = r.stderr.strip()
    assert msg.startswith(f"{src}: error: "), msg
    for n in needles:
        assert n in msg, msg
