"""Mistakes in a description stop the generator (and so the build) with
"<file>: error: object 0xIIII[ sub S]: <problem>" and exit code 1."""
from __future__ import annotations

import shutil
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

from conftest import ROOT, run_odgen

# A small valid device; each case appends objects to it.
BASE = """
[device]
name = "bad"
vendor_id = 0x1234
device_type = 0

[[object]]
index = 0x1001
name = "Error register"
type = "UNSIGNED8"
access = "ro"
pdo_mapping = true
"""

MAP32 = """
[[object]]
index = 0x2000
name = "Value"
type = "UNSIGNED32"
pdo_mapping = {mappable}
"""


def tpdo_map(*entries: int, index: int = 0x1A00) -> str:
    return textwrap.dedent(f"""
        [[object]]
        index = 0x{index:04X}
        name = "PDO mapping parameter"
        object = "RECORD"
        array = 8
        sub0 = {{ name = "Number of mapped objects", access = "rw", default = {len(entries)} }}
        element = {{ name = "Mapped object", type = "UNSIGNED32", access = "rw" }}
        defaults = [{", ".join(hex(e) for e in entries)}]
        """)


def generate(tmp_path: Path, text: str) -> tuple[Path, subprocess.CompletedProcess]:
    src = tmp_path / "bad.toml"
    src.write_text(BASE + textwrap.dedent(text))
    return src, run_odgen(src, tmp_path / "out")


def fails_with(tmp_path: Path, text: str, *needles: str) -> str:
    src, r = generate(tmp_path, text)
    assert r.returncode == 1, f"accepted:\n{text}"
    msg = r.stderr.strip()
    assert msg.startswith(f"{src}: error: "), msg
    for n in needles:
        assert n in msg, msg
    assert "Traceback" not in msg
    assert not (tmp_path / "out").exists(), "wrote products despite the error"
    return msg


def test_base_is_valid(tmp_path):
    _, r = generate(tmp_path, "")
    assert r.returncode == 0, r.stderr


# ----------------------------------------------------------- required cases

def test_duplicate_index(tmp_path):
    fails_with(tmp_path, MAP32.format(mappable="true") + MAP32.format(mappable="false"),
               "object 0x2000: duplicate index")


def test_duplicate_index_with_device_table(tmp_path):
    fails_with(tmp_path, """
        [[object]]
        index = 0x1018
        name = "Identity"
        subs = [{ sub = 1, name = "Vendor-ID", type = "UNSIGNED32", access = "ro" }]
        """, "object 0x1018: duplicate index", "[device] vendor_id")


def test_duplicate_sub_index(tmp_path):
    fails_with(tmp_path, """
        [[object]]
        index = 0x2001
        name = "Record"
        subs = [
          { sub = 1, name = "A", type = "UNSIGNED8" },
          { sub = 2, name = "B", type = "UNSIGNED8" },
          { sub = 1, name = "C", type = "UNSIGNED16" },
        ]
        """, "object 0x2001 sub 1: duplicate sub-index")


def test_default_out_of_limits(tmp_path):
    fails_with(tmp_path, """
        [[object]]
        index = 0x2002
        name = "Limited"
        type = "UNSIGNED16"
        default = 5
        low_limit = 10
        high_limit = 100
        """, "object 0x2002", "default 5 is out of limits [10, 100]")


def test_default_out_of_limits_in_record(tmp_path):
    fails_with(tmp_path, """
        [[object]]
        index = 0x2003
        name = "Record"
        subs = [{ sub = 2, name = "Speed", type = "INTEGER32", default = -200, low_limit = -100, high_limit = 100 }]
        """, "object 0x2003 sub 2", "default -200 is out of limits [-100, 100]")


def test_nodeid_default_out_of_limits(tmp_path):
    # $NODEID+0x10 reaches 0x8F for node 127
    fails_with(tmp_path, """
        [[object]]
        index = 0x2004
        name = "COB-ID"
        type = "UNSIGNED32"
        default = "$NODEID+0x10"
        high_limit = 0x7F
        """, "object 0x2004", "default $NODEID+16 is out of limits [0, 127]")


def test_default_does_not_fit_type(tmp_path):
    fails_with(tmp_path, """
        [[object]]
        index = 0x2005
        name = "Byte"
        type = "UNSIGNED8"
        default = 256
        """, "object 0x2005", "default 256 does not fit UNSIGNED8 [0, 255]")


def test_mapping_of_non_mappable_object(tmp_path):
    fails_with(tmp_path, MAP32.format(mappable="false") + tpdo_map(0x20000020),
               "object 0x1A00 sub 1", "maps 0x2000 sub 0", "not mappable into a TPDO")


def test_rpdo_mapping_of_tpdo_only_object(tmp_path):
    # 0x1001 is ro + pdo_mapping: TPDO only
    fails_with(tmp_path, tpdo_map(0x10010008, index=0x1600),
               "object 0x1600 sub 1", "maps 0x1001 sub 0", "not mappable into an RPDO")


def test_unknown_data_type(tmp_path):
    fails_with(tmp_path, """
        [[object]]
        index = 0x2006
        name = "Odd"
        type = "UNSIGNED12"
        """, "object 0x2006", "unknown data type 'UNSIGNED12'")


def test_unknown_data_type_in_array(tmp_path):
    fails_with(tmp_path, """
        [[object]]
        index = 0x2007
        name = "Odd array"
        array = 2
        element = { name = "x", type = "REAL16" }
        """, "object 0x2007 sub 1", "unknown data type 'REAL16'")


def test_mapping_longer_than_64_bits(tmp_path):
    fails_with(tmp_path, MAP32.format(mappable="true") + """
        [[object]]
        index = 0x2001
        name = "Value 2"
        type = "UNSIGNED32"
        pdo_mapping = true
        [[object]]
        index = 0x2002
        name = "Value 3"
        type = "UNSIGNED8"
        pdo_mapping = true
        """ + tpdo_map(0x20000020, 0x20010020, 0x20020008),
               "object 0x1A00", "default TPDO mapping is 72 bits long, more than 64")


# ------------------------------------------------------------ more mistakes

@pytest.mark.parametrize("text, needles", [
    (MAP32.format(mappable="true") + tpdo_map(0x20000010),
     ["object 0x1A00 sub 1", "with 16 bits; UNSIGNED32 has 32"]),
    (tpdo_map(0x30000008), ["object 0x1A00 sub 1", "maps 0x3000 sub 0, which does not exist"]),
    ("""
     [[object]]
     index = 0x2008
     name = "Typo"
     type = "UNSIGNED8"
     acess = "ro"
     """, ["object 0x2008", "unknown key(s) acess"]),
    ("""
     [[object]]
     index = 0x2009
     name = "String"
     type = "VISIBLE_STRING"
     size = 4
     default = "too long"
     """, ["object 0x2009", "default is 8 bytes, more than size 4"]),
    ("""
     [[object]]
     index = 0x200A
     name = "Real"
     type = "REAL32"
     low_limit = 0
     """, ["object 0x200A", "limits are only supported on integer types"]),
    ("""
     [[object]]
     index = 0x200B
     name = "Mapped string"
     type = "VISIBLE_STRING"
     size = 4
     pdo_mapping = true
     """, ["object 0x200B", "cannot be PDO-mapped"]),
], ids=["map-length", "map-missing", "unknown-key", "string-too-long", "real-limits",
        "map-string"])
def test_other_mistakes(tmp_path, text, needles):
    fails_with(tmp_path, text, *needles)


def test_unknown_option(tmp_path):
    src = tmp_path / "bad.toml"
    src.write_text(BASE.replace('device_type = 0', 'device_type = 0\noptions = ["NO_SUCH"]'))
    r = run_odgen(src, tmp_path / "out")
    assert r.returncode == 1
    assert "unknown option 'NO_SUCH'" in r.stderr and "SDO_NO_BLOCK" in r.stderr


def with_options(text: str, *opts: str) -> str:
    names = ", ".join(f'"{o}"' for o in opts)
    return BASE.replace('device_type = 0', f'device_type = 0\noptions = [{names}]') + \
        textwrap.dedent(text)


def test_map_bytes_needs_granularity_8(tmp_path):
    src = tmp_path / "bad.toml"
    src.write_text(with_options("[eds]\ngranularity = 1\n", "PDO_MAP_BYTES"))
    r = run_odgen(src, tmp_path / "out")
    assert r.returncode == 1
    assert "granularity: option PDO_MAP_BYTES maps whole bytes only" in r.stderr
    src.write_text(with_options("[eds]\ngranularity = 8\n", "PDO_MAP_BYTES"))
    assert run_odgen(src, tmp_path / "out").returncode == 0


def test_map_bytes_refuses_a_bit_dummy(tmp_path):
    rpdo = """
        [[object]]
        index = 0x1400
        name = "RPDO1 communication parameter"
        subs = [
          { sub = 1, name = "COB-ID", type = "UNSIGNED32", default = "$NODEID+0x200" },
          { sub = 2, name = "Transmission type", type = "UNSIGNED8", default = 255 },
        ]
        [eds]
        dummy_usage = [1]
        """ + tpdo_map(0x00010001, index=0x1600)
    src = tmp_path / "bad.toml"
    src.write_text(with_options(rpdo))
    assert run_odgen(src, tmp_path / "out").returncode == 0
    src.write_text(with_options(rpdo, "PDO_MAP_BYTES"))
    r = run_odgen(src, tmp_path / "out2")
    assert r.returncode == 1
    assert "object 0x1600 sub 1" in r.stderr and "PDO_MAP_BYTES" in r.stderr


def test_options_come_from_the_core_header():
    from model import core_options
    opts = core_options()
    assert opts["SDO_NO_BLOCK"] == 0x0080
    assert len(opts) >= 9


# -------------------------------------------------------- the build stops

@pytest.mark.skipif(shutil.which("cmake") is None, reason="cmake missing")
def test_build_stops_on_a_bad_description(tmp_path):
    """co_device() runs the generator at build time: the build fails and
    shows the message naming the file and the object."""
    proj = tmp_path / "proj"
    proj.mkdir()
    (proj / "bad.toml").write_text(BASE + MAP32.format(mappable="true") * 2)
    (proj / "CMakeLists.txt").write_text(textwrap.dedent(f"""
        cmake_minimum_required(VERSION 3.25)
        project(bad LANGUAGES C)
        add_library(costack INTERFACE)
        target_include_directories(costack INTERFACE "{ROOT}/stack/include")
        include("{ROOT}/cmake/codev.cmake")
        co_device(bad bad.toml)
        """))
    b = tmp_path / "b"
    r = subprocess.run(["cmake", "-S", str(proj), "-B", str(b), f"-DCO_PYTHON={sys.executable}"],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stdout + r.stderr
    r = subprocess.run(["cmake", "--build", str(b)], capture_output=True, text=True)
    out = r.stdout + r.stderr
    assert r.returncode != 0
    assert f"{proj / 'bad.toml'}: error: object 0x2000: duplicate index" in out, out


def tpdo_comm(index: int = 0x1800, cob_type: str = "UNSIGNED32", cob: int = 0x80000180) -> str:
    return textwrap.dedent(f"""
        [[object]]
        index = 0x{index:04X}
        name = "PDO communication parameter"
        subs = [
          {{ sub = 1, name = "COB-ID", type = "{cob_type}", default = {cob:#x} }},
          {{ sub = 2, name = "Transmission type", type = "UNSIGNED8", default = 255 }},
        ]
        """)


@pytest.mark.parametrize("text, needles", [
    (tpdo_map(0x10010008), ["0x1A00", "needs both", "0x1800"]),
    (tpdo_comm(), ["0x1800", "needs both", "0x1A00"]),
    (tpdo_comm(0x1801) + tpdo_map(0x10010008, index=0x1A01),
     ["0x1801", "without gaps", "0x1800 is missing"]),
    (tpdo_comm(cob_type="UNSIGNED16", cob=0x180) + tpdo_map(0x10010008), ["0x1800 sub 1", "UNSIGNED32"]),
])
def test_pdo_objects_that_are_no_pdo(tmp_path, text, needles):
    """Objects in the PDO ranges that make no PDO (a foreign EDS may have
    them) stay plain objects: the build goes on, with a warning naming them."""
    src, r = generate(tmp_path, text)
    assert r.returncode == 0, r.stderr
    msg = r.stderr.strip()
    assert msg.startswith(f"{src}: warning: "), msg
    for n in needles:
        assert n in msg, msg
    c = (tmp_path / "out" / "bad.c").read_text()
    assert ".n_rpdo = 0U," in c and ".n_tpdo = 0U," in c


def test_pdo_table_is_generated(tmp_path):
    src, r = generate(tmp_path, tpdo_comm() + tpdo_map(0x10010008))
    assert r.returncode == 0, r.stderr
    c = (tmp_path / "out" / "bad.c").read_text()
    assert "static const co_pdo_desc_t pdo[]" in c
    assert ".n_rpdo = 0U," in c and ".n_tpdo = 1U," in c


def test_pdo_parameters_apart_are_refused(tmp_path):
    """The core finds a PDO's parameters by one layout (co_pdo_desc_t: the
    mapping entries, their number and the transmission type one after the
    other); a PDO whose values cannot be laid out so (here its transmission
    type is not stored with the rest) is refused, naming it."""
    comm = tpdo_comm().replace('default = 255 }', 'default = 255, storage = "none" }')
    assert 'storage = "none"' in comm
    fails_with(tmp_path, comm + tpdo_map(0x10010008), "0x1800",
               "stored with the communication parameters")
    src, r = generate(tmp_path, tpdo_comm() + tpdo_map(0x10010008))
    assert r.returncode == 0, r.stderr


def mask_obj(index: int, hook: bool = False, subs: str | None = None) -> str:
    body = subs or ('array = 2\nelement = { type = "UNSIGNED32", access = "rw", '
                    'default = 0xFFFFFFFF }')
    return f"""
[[object]]
index = 0x{index:04X}
name = "TPDO change mask"
{body}
{'hook = true' if hook else ''}
"""


def test_tpdo_mask_table_is_generated(tmp_path):
    """[device] tpdo_mask names TPDO1's change mask (TPDO n's at + n); the C
    table holds where sub 1 of each lives."""
    src = tmp_path / "bad.toml"
    src.write_text(with_options(tpdo_comm() + tpdo_comm(0x1801, cob=0x80000280)
                                + tpdo_map(0x10010008) + tpdo_map(0x10010008, index=0x1A01)
                                + mask_obj(0x2100) + mask_obj(0x2101), "TPDO_MASK_255")
                   .replace('options = [', 'tpdo_mask = 0x2100\noptions = ['))
    r = run_odgen(src, tmp_path / "out")
    assert r.returncode == 0, r.stderr
    c = (tmp_path / "out" / "bad.c").read_text()
    assert "static const uint16_t tpdo_mask[] = {" in c
    assert "/* 0x2100 */" in c and "/* 0x2101 */" in c
    assert ".tpdo_mask = tpdo_mask," in c
    # without masks the field is NULL
    plain = tmp_path / "plain"
    plain.mkdir()
    _, r = generate(plain, tpdo_comm() + tpdo_map(0x10010008))
    assert r.returncode == 0, r.stderr
    assert ".tpdo_mask = NULL," in (plain / "out" / "bad.c").read_text()


@pytest.mark.parametrize("opts, mask, objs, needle", [
    (["TPDO_MASK_255"], None, "", "option TPDO_MASK_255 needs tpdo_mask"),
    ([], 0x2100, mask_obj(0x2100), "tpdo_mask is only used with option TPDO_MASK_254"),
    (["TPDO_MASK_254"], 0x1000, "", "tpdo_mask must be a manufacturer object"),
    (["TPDO_MASK_254"], 0x2100, "", "object 0x2100 ([device] tpdo_mask, TPDO1): missing"),
    (["TPDO_MASK_254"], 0x2100, mask_obj(0x2100, hook=True), "without a hook"),
    (["TPDO_MASK_254"], 0x2100,
     mask_obj(0x2100, subs='array = 2\nelement = { type = "UNSIGNED16" }'),
     "sub 1 and 2, UNSIGNED32"),
    (["TPDO_MASK_254"], 0x2100,
     mask_obj(0x2100, subs='subs = [{ sub = 1, name = "A", type = "UNSIGNED32" },\n'
                           '{ sub = 2, name = "B", type = "UNSIGNED32", storage = "none" }]'),
     "back to back"),
], ids=["option-without-index", "index-without-option", "not-manufacturer", "missing",
        "hooked", "not-u32", "not-adjacent"])
def test_tpdo_mask_mistakes(tmp_path, opts, mask, objs, needle):
    text = with_options(tpdo_comm() + tpdo_map(0x10010008) + objs, *opts)
    if mask is not None:
        text = text.replace("device_type = 0", f"device_type = 0\ntpdo_mask = {mask:#x}")
    src = tmp_path / "bad.toml"
    src.write_text(text)
    r = run_odgen(src, tmp_path / "out")
    assert r.returncode == 1, r.stderr
    assert needle in r.stderr, r.stderr


# ------------------------------------------- node-ID object, identity sub 0

NODEID_OBJ = """
[[object]]
index = 0x2000
name = "Node address"
type = "{type}"
default = 1
"""


def test_nodeid_object_is_generated(tmp_path):
    """[device] nodeid_object names the node-ID object: co_dev_t.nodeid_index."""
    src = tmp_path / "bad.toml"
    src.write_text((BASE + NODEID_OBJ.format(type="UNSIGNED8"))
                   .replace("device_type = 0", "device_type = 0\nnodeid_object = 0x2000"))
    r = run_odgen(src, tmp_path / "out")
    assert r.returncode == 0, r.stderr
    assert ".nodeid_index = 0x2000U," in (tmp_path / "out" / "bad.c").read_text()
    plain = tmp_path / "plain"
    plain.mkdir()
    _, r = generate(plain, "")
    assert ".nodeid_index = 0x0000U," in (plain / "out" / "bad.c").read_text()


@pytest.mark.parametrize("index, objs, needle", [
    (0x1000, "", "nodeid_object must be a manufacturer object"),
    (0x2000, "", "nodeid_object 0x2000: needs an UNSIGNED8"),
    (0x2000, NODEID_OBJ.format(type="UNSIGNED16"), "nodeid_object 0x2000: needs an UNSIGNED8"),
], ids=["not-manufacturer", "missing", "not-u8"])
def test_nodeid_object_mistakes(tmp_path, index, objs, needle):
    src = tmp_path / "bad.toml"
    src.write_text((BASE + objs).replace("device_type = 0",
                                         f"device_type = 0\nnodeid_object = {index:#x}"))
    r = run_odgen(src, tmp_path / "out")
    assert r.returncode == 1, r.stderr
    assert needle in r.stderr, r.stderr


@pytest.mark.parametrize("value, ok", [(1, True), (4, True), (0, False), (5, False)])
def test_identity_sub0(tmp_path, value, ok):
    """identity_sub0: 0x1018 sub 0 as the device documents it (1..4)."""
    src = tmp_path / "bad.toml"
    src.write_text(BASE.replace("device_type = 0", f"device_type = 0\nidentity_sub0 = {value}"))
    r = run_odgen(src, tmp_path / "out")
    assert (r.returncode == 0) == ok, r.stderr
    if ok:
        eds = (tmp_path / "out" / "bad.eds").read_text()
        assert f"DefaultValue={value}" in eds.split("[1018sub0]")[1].split("[")[0]


# ------------------------------------------- include and identity layout

def test_include_replaces_and_adds(tmp_path):
    """include = "base.toml": [device] keys and objects of the same index
    replace the base's, other objects are added."""
    (tmp_path / "base.toml").write_text(BASE + MAP32.format(mappable="true"))
    src = tmp_path / "variant.toml"
    src.write_text(textwrap.dedent("""
        include = "base.toml"

        [device]
        name = "variant"
        product_code = 0x42

        [[object]]
        index = 0x2000
        name = "Value"
        type = "UNSIGNED16"

        [[object]]
        index = 0x2001
        name = "More"
        type = "UNSIGNED8"
        """))
    r = run_odgen(src, tmp_path / "out")
    assert r.returncode == 0, r.stderr
    from model import load
    dev = load(src)
    assert dev.name == "variant" and dev.info["vendor_id"] == 0x1234
    assert dev.find(0x1018, 2).default == 0x42
    assert dev.find(0x2000, 0).type == "UNSIGNED16" and dev.find(0x2001, 0) is not None
    assert dev.find(0x1001, 0) is not None


@pytest.mark.parametrize("text, needles", [
    ('include = "missing.toml"\n', ["include 'missing.toml'", "cannot read"]),
    ('include = 5\n', ["include must name a description file"]),
], ids=["missing", "not-text"])
def test_include_mistakes(tmp_path, text, needles):
    src = tmp_path / "bad.toml"
    src.write_text(text + BASE)
    r = run_odgen(src, tmp_path / "out")
    assert r.returncode == 1
    for n in needles:
        assert n in r.stderr, r.stderr


def test_identity_vendor_at_sub0(tmp_path):
    """A device that documents 0x1018 with the vendor-ID in sub-index 0."""
    src = tmp_path / "ident.toml"
    src.write_text(BASE.replace('device_type = 0', 'device_type = 0\nproduct_code = 3\n'
                                'identity_layout = "vendor-at-sub0"'))
    r = run_odgen(src, tmp_path / "out")
    assert r.returncode == 0, r.stderr
    from model import load
    o = [o for o in load(src).objects if o.index == 0x1018][0]
    assert [(s.sub, s.name, s.type, s.default) for s in o.subs] == [
        (0, "Vendor-ID", "UNSIGNED32", 0x1234), (1, "Product code", "UNSIGNED32", 3),
        (2, "Revision number", "UNSIGNED32", 0)]
    src.write_text(BASE.replace('device_type = 0', 'device_type = 0\nserial = 1\n'
                                'identity_layout = "vendor-at-sub0"'))
    r = run_odgen(src, tmp_path / "out2")
    assert r.returncode == 1 and "has no serial" in r.stderr
    src.write_text(BASE.replace('device_type = 0', 'device_type = 0\nidentity_layout = "x"'))
    r = run_odgen(src, tmp_path / "out3")
    assert r.returncode == 1 and "identity_layout 'x'" in r.stderr


# ------------------------------------ the core's objects at their places

def test_core_object_of_another_type(tmp_path):
    # the core reads 0x1017 as an UNSIGNED16 at its place (co_node.h, CO_RAM_1017)
    fails_with(tmp_path, """
        [[object]]
        index = 0x1017
        name = "Producer heartbeat time"
        type = "UNSIGNED32"
        """, "object 0x1017 sub 0: the core reads it as UNSIGNED16, not UNSIGNED32")


def test_core_array_of_another_type(tmp_path):
    fails_with(tmp_path, """
        [[object]]
        index = 0x1016
        name = "Consumer heartbeat time"
        array = 2
        element = { name = "Consumer heartbeat time", type = "UNSIGNED16" }
        """, "object 0x1016 sub 1: the core reads it as UNSIGNED32, not UNSIGNED16")


def test_core_object_stored_elsewhere(tmp_path):
    # 0x1015 has its place in the communication parameters (stored), 0x1003's
    # count among the values not stored
    fails_with(tmp_path, """
        [[object]]
        index = 0x1015
        name = "Inhibit time EMCY"
        type = "UNSIGNED16"
        storage = "none"
        """, "object 0x1015 sub 0: the core has it with the communication parameters, "
             "not storage 'none'")
    fails_with(tmp_path, """
        [[object]]
        index = 0x1003
        name = "Pre-defined error field"
        array = 2
        storage = "comm"
        sub0 = { name = "Number of errors", access = "rw", default = 0 }
        element = { name = "Standard error field", type = "UNSIGNED32", access = "ro" }
        """, "object 0x1003 sub 0: the core has it with the values not stored, "
             "not storage 'comm'")


def test_core_history_without_its_count(tmp_path):
    # the core counts the errors of 0x1003 in sub 0: a value in RAM (not the
    # implicit const number of entries)
    fails_with(tmp_path, """
        [[object]]
        index = 0x1003
        name = "Pre-defined error field"
        array = 2
        element = { name = "Standard error field", type = "UNSIGNED32", access = "ro" }
        """, "object 0x1003: the core counts the errors in sub 0")


def test_too_many_mappable_objects(tmp_path):
    """A PDO mapping entry is 16 bits in the RAM image (co_od.h
    CO_OD_MAP_ENTRY): a reference into the device's table of mappable
    objects, which holds at most 1016 of them; one more is refused with the
    limit, and 1016 are fine."""
    def arrays(n_objects: int, last: int) -> str:
        out = ""
        for k in range(n_objects):
            out += textwrap.dedent(f"""
                [[object]]
                index = 0x{0x2100 + k:04X}
                name = "Inputs"
                object = "ARRAY"
                array = {254 if k < n_objects - 1 else last}
                element = {{ name = "Input", type = "UNSIGNED8", access = "ro", pdo_mapping = true }}
                """)
        return out
    pdo = tpdo_comm() + tpdo_map(0x10010008)
    # 0x1001:00 and the arrays' 4 x 254 entries: 1017
    fails_with(tmp_path, pdo + arrays(4, 254), "1017 mappable objects", "at most 1016")
    _, r = generate(tmp_path, pdo + arrays(4, 253))
    assert r.returncode == 0, r.stderr
