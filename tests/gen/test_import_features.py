"""EDS import of every CiA 306 feature the foreign files do not show: a DCF
written for this test with ObjFlags, ObjectLinks, CompactSubObj with
[xxxxName]/[xxxxValue]/[xxxxDenotation], $NODEID on either side in defaults,
limits and ParameterValues, hex/decimal/octal and two's complement numbers,
DOMAIN objects with and without a default, every DeviceInfo entry, a dummy
in a default mapping, DeviceComissioning, [Comments], a section and keys
odgen has no name for, lower-case section names, UTF-8 text, CRLF line ends.
It round-trips without loss, also as python-canopen reads it, compiles to a
C dictionary that equals its EDS, and imports with --use-values as the
configured node."""
from __future__ import annotations

import shutil
import textwrap

import pytest

from cia306 import NodeRel, read_eds, value
from compare import compare, run_dump
from conftest import compile_dump, run_import, run_odgen
from model import load
from roundtrip import canopen_differences, round_trip, semantic_differences

FEATURES = """\
[FileInfo]
FileName=features.dcf
FileVersion=3
FileRevision=7
EDSVersion=4.0
Description=every CiA 306 feature
CreationTime=09:05AM
CreationDate=02-28-2024
CreatedBy=test author
ModificationTime=11:59PM
ModificationDate=03-01-2024
ModifiedBy=someone else
LastEDS=features.eds

[DeviceInfo]
VendorName=Test vendor
VendorNumber=0x0000ABCD
ProductName=Feature device
ProductNumber=0x1234
RevisionNumber=0x00020003
OrderCode=FD-1
BaudRate_10=0
BaudRate_20=0
BaudRate_50=1
BaudRate_125=1
BaudRate_250=1
BaudRate_500=1
BaudRate_800=1
BaudRate_1000=0
SimpleBootUpMaster=1
SimpleBootUpSlave=0
Granularity=0x4
DynamicChannelsSupported=1
CompactPDO=1
GroupMessaging=1
NrOfRXPDO=2
NrOfTXPDO=1
LSS_Supported=1
CANopenSafetySupported=0

[DeviceComissioning]
NodeID=0x22
NodeName=left wheel
Baudrate=250
NetNumber=1
NetworkName=line 1
CANopenManager=0
LSS_SerialNumber=0x1234

[DummyUsage]
Dummy0001=0
Dummy0002=1
Dummy0003=0
Dummy0004=0
Dummy0005=1
Dummy0006=0
Dummy0007=0

[Comments]
Lines=2
Line1=first comment line
Line2=  second, indented in the source

[Tools]
Editor=by hand
Checked=1

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
DefaultValue=0x00020192
PDOMapping=0
ObjFlags=0x1
ParameterValue=0x20192

[1001]
ParameterName=Error register
DataType=0x0005
AccessType=ro
PDOMapping=1

[1018]
ParameterName=Identity object
ObjectType=0x9
SubNumber=3
ObjFlags=2

[1018sub0]
ParameterName=Highest sub-index supported
ObjectType=0x7
DataType=0x0005
AccessType=const
DefaultValue=2
PDOMapping=0

[1018sub1]
ParameterName=Vendor-ID
ObjectType=0x7
DataType=0x0007
AccessType=ro
DefaultValue=0xABCD
PDOMapping=0

[1018Sub2]
ParameterName=Product code
ObjectType=0x7
DataType=0x0007
AccessType=ro
DefaultValue=4660
PDOMapping=0
Denotation=wheel drive

[OptionalObjects]
SupportedObjects=8
1=0x1014
2=0x1200
3=0x1400
4=0x1600
5=0x1A00
6=0x6000
7=0x600A
8=0x6010

[1014]
ParameterName=COB-ID EMCY
ObjectType=0x7
DataType=0x0007
AccessType=rw
DefaultValue=0x80+$NODEID
PDOMapping=0
ParameterValue=0xA2

[1200]
ParameterName=SDO server parameter
ObjectType=0x9
SubNumber=3

[1200sub0]
ParameterName=Highest sub-index supported
ObjectType=0x7
DataType=0x0005
AccessType=const
DefaultValue=2
PDOMapping=0

[1200sub1]
ParameterName=COB-ID client to server
ObjectType=0x7
DataType=0x0007
AccessType=ro
DefaultValue=$NODEID+0x600
PDOMapping=0

[1200sub2]
ParameterName=COB-ID server to client
ObjectType=0x7
DataType=0x0007
AccessType=ro
DefaultValue=$NODEID + 0x580
PDOMapping=0

[1400]
ParameterName=RPDO1 communication parameter
ObjectType=0x9
SubNumber=3

[1400sub0]
ParameterName=Highest sub-index supported
ObjectType=0x7
DataType=0x0005
AccessType=const
DefaultValue=2
PDOMapping=0

[1400sub1]
ParameterName=COB-ID used by RPDO
ObjectType=0x7
DataType=0x0007
AccessType=rw
DefaultValue=$NODEID+0x200
PDOMapping=0

[1400sub2]
ParameterName=Transmission type
ObjectType=0x7
DataType=0x0005
AccessType=rw
DefaultValue=0xFF
PDOMapping=0

[1600]
ParameterName=RPDO1 mapping parameter
ObjectType=0x8
SubNumber=3

[1600sub0]
ParameterName=Number of mapped objects
ObjectType=0x7
DataType=0x0005
AccessType=rw
DefaultValue=2
PDOMapping=0

[1600sub1]
ParameterName=Mapped object 1
ObjectType=0x7
DataType=0x0007
AccessType=rw
DefaultValue=0x20010108
PDOMapping=0

[1600sub2]
ParameterName=Mapped object 2
ObjectType=0x7
DataType=0x0007
AccessType=rw
DefaultValue=0x00050008
PDOMapping=0

[1A00]
ParameterName=TPDO1 mapping parameter
ObjectType=0x9
SubNumber=2

[1A00sub0]
ParameterName=Number of mapped objects
ObjectType=0x7
DataType=0x0005
AccessType=rw
DefaultValue=1
PDOMapping=0

[1A00sub1]
ParameterName=Mapped object 1
ObjectType=0x7
DataType=0x0007
AccessType=rw
DefaultValue=0x60000110
PDOMapping=0

[6000]
ParameterName=Inputs
ObjectType=0x8
SubNumber=3

[6000sub0]
ParameterName=Number of inputs
ObjectType=0x7
DataType=0x0005
AccessType=ro
DefaultValue=2
PDOMapping=0

[6000sub1]
ParameterName=Input 1
ObjectType=0x7
DataType=0x0006
AccessType=ro
PDOMapping=1

[6000Sub2]
ParameterName=Input 2
ObjectType=0x7
DataType=0x0006
AccessType=ro
PDOMapping=1

[600a]
ParameterName=Temperatur \u00b0C
ObjectType=0x7
DataType=0x0003
AccessType=ro
DefaultValue=-40
PDOMapping=1
LowLimit=-0x28
HighLimit=0x7D

[6010]
ParameterName=Text
ObjectType=0x7
DataType=0x000B
AccessType=const
DefaultValue=Gr\u00fc\u00dfe
PDOMapping=0

[ManufacturerObjects]
SupportedObjects=9
1=0x2001
2=0x2002
3=0x2003
4=0x2004
5=0x2005
6=0x2006
7=0x2007
8=0x2008
9=0x2009

[2001]
ParameterName=Outputs
ObjectType=0x8
DataType=0x0005
AccessType=rww
DefaultValue=010
PDOMapping=1
LowLimit=0x2
HighLimit=12
CompactSubObj=3
ObjFlags=0x1

[2001Name]
NrOfEntries=3
1=Left
2=Middle
3=Right

[2001Value]
NrOfEntries=1
2=0x9

[2001Denotation]
NrOfEntries=1
1=left lamp

[2001ObjectLinks]
ObjectLinks=2
1=0x2002
2=0x6000

[2002]
ParameterName=Signed values
ObjectType=0x9
SubNumber=3

[2002sub0]
ParameterName=Highest sub-index supported
ObjectType=0x7
DataType=0x0005
AccessType=const
DefaultValue=2
PDOMapping=0

[2002sub1]
ParameterName=Offset
ObjectType=0x7
DataType=0x0004
AccessType=rw
DefaultValue=-0x10
PDOMapping=0
LowLimit=-1000
HighLimit=0x3E8

[2002sub2]
ParameterName=Gain
ObjectType=0x7
DataType=0x0003
AccessType=rw
DefaultValue=-2
PDOMapping=0
LowLimit=0x8000
HighLimit=100

[2003]
ParameterName=Node-relative value
ObjectType=0x7
DataType=0x0006
AccessType=rw
DefaultValue=$NODEID
PDOMapping=0
LowLimit=$NODEID
HighLimit=0x100+$NODEID
ParameterValue=$NODEID+0x1

[2004]
ParameterName=Firmware
ObjectType=0x2
DataType=0x000F
AccessType=wo
PDOMapping=0

[2005]
ParameterName=Calibration
ObjectType=0x7
DataType=0x000F
AccessType=ro
DefaultValue=0102AB
PDOMapping=0

[2006]
ParameterName=Label
ObjectType=0x7
DataType=0x0009
AccessType=rw
DefaultValue=hello world
PDOMapping=0

[2007]
ParameterName=Key
ObjectType=0x7
DataType=0x000A
AccessType=ro
DefaultValue=DEADBEEF
PDOMapping=0

[2008]
ParameterName=Scale
ObjectType=0x7
DataType=0x0008
AccessType=rw
DefaultValue=1.5e3
PDOMapping=1
StorageLocation=ROM
Unit=mV

[2009]
ParameterName=Timestamp
ObjectType=0x7
DataType=0x000C
AccessType=rw
DefaultValue=0x000100000064
PDOMapping=0
"""


def write_features(tmp_path, text: str = FEATURES, name: str = "features.dcf", crlf=True):
    src = tmp_path / name
    src.write_bytes(text.replace("\n", "\r\n" if crlf else "\n").encode("utf-8"))
    return src


@pytest.fixture(scope="module")
def features(tmp_path_factory):
    work = tmp_path_factory.mktemp("features")
    src = write_features(work)
    r, out, dev = round_trip(src, work, "feature_dcf")
    return src, r, out, dev, (work / "feature_dcf.toml").read_text()


def test_reader_sees_every_feature(tmp_path):
    eds = read_eds(write_features(tmp_path))
    assert eds.warnings == []
    o = eds.objects[0x2001]
    assert o.compact == 3 and o.links == [0x2002, 0x6000] and o.obj_flags == "0x1"
    assert [s.name for s in o.subs.values()] == ["NrOfObjects", "Left", "Middle", "Right"]
    assert [s.param_value for s in o.subs.values()] == [None, None, "0x9", None]
    assert o.subs[1].denotation == "left lamp" and o.subs[2].default == "010"
    assert value(o.subs[2].default, 0x05) == 8                          # octal
    assert value(eds.objects[0x1014].subs[0].default, 7) == NodeRel(0x80)  # n+$NODEID
    assert value(eds.objects[0x2002].subs[2].low, 3) == -32768         # two's complement
    assert value(eds.objects[0x2002].subs[1].default, 4) == -16
    assert eds.objects[0x600A].name == "Temperatur \u00b0C"
    assert eds.objects[0x1018].subs[2].denotation == "wheel drive"
    assert eds.extra_keys == {"DeviceInfo": {"CANopenSafetySupported": "0"}}
    assert eds.file_info["LastEDS"] == "features.eds"
    assert list(eds.other) == ["Tools"]
    assert eds.comments == ["first comment line", "second, indented in the source"]


def test_round_trip_loses_nothing(features):
    src, r, out, dev, text = features
    assert r.stderr == ""
    assert semantic_differences(src, out) == []
    # python-canopen cannot read an octal number or a bare "$NODEID" (it reads
    # no default); odgen writes them as 8 and "$NODEID+0x0", which it reads
    assert canopen_differences(src, out, node_id=5) == [
        "0x2001 sub 1 default: None -> 8", "0x2001 sub 2 default: None -> 8",
        "0x2001 sub 3 default: None -> 8", "0x2003 sub 0 default: None -> 5"]
    assert canopen_differences(src, out, node_id=None) == [   # node-ID 0x22 from the DCF
        "0x2001 sub 1 default: None -> 8", "0x2001 sub 2 default: None -> 8",
        "0x2001 sub 3 default: None -> 8", "0x2003 sub 0 default: None -> 34"]
    assert not dev.eds_only


def test_description_states_the_features(features):
    src, r, out, dev, text = features
    for line in ('default = "$NODEID+0x80"', 'low_limit = "$NODEID+0x0"',
                 'high_limit = "$NODEID+0x100"', "compact = true", "links = [0x2002, 0x6000]",
                 "obj_flags = 0x1", "obj_flags = 0x2", 'denotation = "wheel drive"',
                 "parameter_value = 0xA2", "dummy_usage = [2, 5]", "[eds.sections.Tools]",
                 "[eds.sections.DeviceInfo]", "CANopenSafetySupported = \"0\"",
                 "compact_pdo = true", "nr_of_rxpdo = 2", "granularity = 4", "[dcf]",
                 'node_name = "left wheel"', 'eds_keys = { StorageLocation = "ROM", Unit = "mV" }',
                 "hookio = true", 'file_name = "features.dcf"', 'time = "09:05"',
                 'modified_time = "23:59"', 'eds_version' not in text and "",
                 "# sub 0: DOMAIN without a default: hook I/O"):
        assert line in text, line
    assert "VISIBLE_STRING capacity 32 bytes" in text
    o = next(o for o in dev.objects if o.index == 0x2001)
    assert o.compact and o.links == [0x2002, 0x6000] and o.obj_flags == 1
    assert [(s.name, s.default, s.parameter_value, s.denotation) for s in o.subs[1:]] == [
        ("Left", 8, None, "left lamp"), ("Middle", 8, 9, ""), ("Right", 8, None, "")]
    s = dev.find(0x2003, 0)
    assert (s.nodeid, s.default, s.low_nodeid, s.eds_low, s.high_nodeid, s.eds_high,
            s.pv_nodeid, s.parameter_value) == (True, 0, True, 0, True, 0x100, True, 1)
    assert (s.low, s.high) == (1, 0x17F)      # the C dictionary: the range over node-IDs
    assert dev.find(0x2004, 0).hookio and dev.find(0x2005, 0).default == bytes([1, 2, 0xAB])


def test_generated_eds_states_the_features(features):
    src, r, out, dev, text = features
    eds = out.read_text(encoding="utf-8")
    for line in ("CompactSubObj=3", "[2001Name]", "[2001Value]", "2=9", "[2001Denotation]",
                 "[2001ObjectLinks]", "ObjectLinks=2", "2=0x6000", "ObjFlags=0x1",
                 "DefaultValue=$NODEID+0x80", "LowLimit=$NODEID+0x0", "HighLimit=$NODEID+0x100",
                 "ParameterValue=$NODEID+0x1", "[DeviceComissioning]", "NodeID=34",
                 "[Tools]", "Editor=by hand", "LastEDS=features.eds", "CompactPDO=1",
                 "Dummy0002=1", "Dummy0005=1", "Line2=second, indented in the source",
                 "ParameterName=Temperatur \u00b0C", "DefaultValue=Gr\u00fc\u00dfe",
                 "Denotation=wheel drive", "StorageLocation=ROM", "FileName=features.dcf"):
        assert line in eds, line


@pytest.mark.skipif(shutil.which("cc") is None, reason="no C compiler")
def test_compiles_and_equals_its_eds(features):
    src, r, out, dev, text = features
    exe = compile_dump(out.parent, dev.cname)
    for node in (1, 0x22, 127):
        dump = run_dump(exe, node)
        assert compare(out, dump, node_id=node) >= 30
    # the node-relative limit: the C dictionary takes the range over all node-IDs
    s = next(s for e in run_dump(exe)["entries"] if e["index"] == 0x2003 for s in e["subs"])
    assert s["limit"] == [1, 0x17F]


def test_use_values(tmp_path):
    """--use-values: the description of a device configured like the DCF's node."""
    src = write_features(tmp_path)
    toml = tmp_path / "configured.toml"
    r = run_import(src, toml, "--use-values")
    assert r.returncode == 0, r.stderr
    text = toml.read_text()
    assert "\n[dcf]\n" not in text and "parameter_value =" not in text
    dev = load(toml)
    assert dev.dcf is None
    s = dev.find(0x1014, 0)     # 0xA2 is 0x80 + node-ID 0x22: stays relative
    assert s.nodeid and s.default == 0x80
    s = dev.find(0x2003, 0)     # $NODEID+1 as the value: relative too
    assert s.nodeid and s.default == 1
    o = next(o for o in dev.objects if o.index == 0x2001)
    assert not o.compact and [s.default for s in o.subs] == [3, 8, 9, 8]
    assert "CompactSubObj=3 written out" in text
    g = run_odgen(toml, tmp_path / "out")
    assert g.returncode == 0, g.stderr
    assert "ParameterValue" not in (tmp_path / "out" / "configured.eds").read_text()


def test_latin1_file(tmp_path):
    """Old vendor files are Latin-1: the text is read as such and kept."""
    src = tmp_path / "old.eds"
    text = FEATURES.replace("DefaultValue=Gr\u00fc\u00dfe", "DefaultValue=Hallo")
    src.write_bytes(text.encode("latin-1"))
    r, out, dev = round_trip(src, tmp_path, "old")
    assert semantic_differences(src, out) == []
    assert next(o for o in dev.objects if o.index == 0x600A).name == "Temperatur \u00b0C"


def test_sparse_compact_names(tmp_path):
    """[xxxxName] may name only some elements; the others keep <name><k>."""
    text = FEATURES.replace("[2001Name]\nNrOfEntries=3\n1=Left\n2=Middle\n3=Right\n",
                            "[2001Name]\nNrOfEntries=1\n3=Right\n")
    src = write_features(tmp_path, text)
    r, out, dev = round_trip(src, tmp_path, "sparse")
    assert semantic_differences(src, out) == []
    o = next(o for o in dev.objects if o.index == 0x2001)
    assert [s.name for s in o.subs] == ["NrOfObjects", "Outputs1", "Outputs2", "Right"]


def test_objects_the_c_dictionary_cannot_hold_stay_in_the_eds(tmp_path):
    extra = textwrap.dedent("""\
        [3000]
        ParameterName=Mapped string
        ObjectType=0x7
        DataType=0x0009
        AccessType=ro
        DefaultValue=abc
        PDOMapping=1

        [3001]
        ParameterName=Bad number
        ObjectType=0x7
        DataType=0x0005
        AccessType=rw
        DefaultValue=0x1G
        PDOMapping=0

        [3002]
        ParameterName=Too big
        ObjectType=0x7
        DataType=0x0005
        AccessType=rw
        DefaultValue=300
        PDOMapping=0

        [0040]
        ParameterName=A structure
        ObjectType=0x6
        SubNumber=2

        [0040sub0]
        ParameterName=Number of entries
        ObjectType=0x7
        DataType=0x0005
        AccessType=ro
        DefaultValue=1
        PDOMapping=0

        [0040sub1]
        ParameterName=first
        ObjectType=0x7
        DataType=0x0006
        AccessType=ro
        DefaultValue=0x10
        PDOMapping=0
        """)
    text = FEATURES.replace("[ManufacturerObjects]\nSupportedObjects=9\n",
                            "[ManufacturerObjects]\nSupportedObjects=12\n10=0x3000\n"
                            "11=0x3001\n12=0x3002\n") + "\n" + extra
    text = text.replace("SupportedObjects=8\n", "SupportedObjects=9\n9=0x0040\n", 1)
    src = write_features(tmp_path, text)
    r, out, dev = round_trip(src, tmp_path, "odd")
    assert semantic_differences(src, out) == []   # (python-canopen cannot read a DEFSTRUCT)
    reasons = {o.index: o.reason for o in dev.eds_only}
    assert set(reasons) == {0x0040, 0x3000, 0x3001, 0x3002}
    assert "cannot be PDO-mapped" in reasons[0x3000]
    assert "'0x1G' is not an integer" in reasons[0x3001]
    assert "'300' does not fit UNSIGNED8" in reasons[0x3002]
    assert "index below 0x1000" in reasons[0x0040]
    for index in reasons:
        assert f"object 0x{index:04X} kept as eds_only" in r.stderr
    md = (out.parent / "odd.md").read_text()
    assert "| 0x3001 | | **Bad number** | EDS only |" in md
