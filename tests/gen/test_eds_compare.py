"""The semantic EDS comparison (tools/odgen/eds_compare.py) that proves the
import round trips: equal meaning in another spelling is equal, and every
single change of an attribute CiA 306 defines is found."""
from __future__ import annotations

import subprocess
import sys

import pytest

from cia306 import read_eds
from conftest import ODGEN
from eds_compare import differences
from test_import_features import FEATURES


def diffs(a: str, b: str) -> list[str]:
    return differences(read_eds("a.eds", a), read_eds("b.eds", b))


@pytest.mark.parametrize("old, new", [
    ("DefaultValue=0x00020192", "DefaultValue=131474"),
    ("DefaultValue=0x00020192", "DefaultValue=0400622"),            # octal
    ("DefaultValue=0x80+$NODEID", "DefaultValue=$NODEID+128"),
    ("DefaultValue=$NODEID + 0x580", "DefaultValue=$nodeid+0x580"),
    ("LowLimit=0x8000", "LowLimit=-32768"),
    ("LowLimit=0x8000\n", ""),                                       # the type's bound
    ("DefaultValue=-2\n", "DefaultValue=0xFFFE\n"),                  # two's complement
    ("AccessType=rww", "AccessType=RWW"),
    ("ObjectType=0x7\nDataType=0x0006\nAccessType=ro\nPDOMapping=1",
     "DataType=0x0006\nAccessType=ro\nPDOMapping=0x1"),              # ObjectType VAR default
    ("AccessType=rw\nDefaultValue=0xFF\nPDOMapping=0\n", "AccessType=rw\nDefaultValue=255\n"),
    ("ObjFlags=0x1\nParameterValue", "ObjFlags=1\nParameterValue"),
    ("CreationTime=09:05AM", "CreationTime=9:05"),
    ("ModificationTime=11:59PM", "ModificationTime=23:59"),
    ("DefaultValue=1.5e3", "DefaultValue=1500.0"),
    ("DefaultValue=DEADBEEF", "DefaultValue=de ad be ef"),
    ("[6000Sub2]", "[6000sub2]"),
    ("Dummy0001=0\n", ""),
])
def test_same_meaning(old, new):
    assert old in FEATURES
    assert diffs(FEATURES, FEATURES.replace(old, new, 1)) == []


def test_compact_equals_expanded():
    base = FEATURES
    expanded = base.split("[2001]")[0] + """[2001]
ParameterName=Outputs
ObjectType=0x8
SubNumber=4
ObjFlags=0x1

[2001sub0]
ParameterName=NrOfObjects
ObjectType=0x7
DataType=0x0005
AccessType=ro
DefaultValue=3
PDOMapping=0

[2001sub1]
ParameterName=Left
DataType=0x0005
AccessType=rww
DefaultValue=8
PDOMapping=1
LowLimit=2
HighLimit=0x0C
Denotation=left lamp

[2001sub2]
ParameterName=Middle
DataType=0x0005
AccessType=rww
DefaultValue=8
PDOMapping=1
LowLimit=2
HighLimit=12
ParameterValue=9

[2001sub3]
ParameterName=Right
DataType=0x0005
AccessType=rww
DefaultValue=8
PDOMapping=1
LowLimit=2
HighLimit=12

[2001ObjectLinks]
ObjectLinks=2
1=0x2002
2=0x6000

[2002]""" + base.split("[2002]")[1]
    assert diffs(FEATURES, expanded) == []
    assert diffs(expanded, FEATURES) == []
    assert diffs(FEATURES, expanded.replace("ParameterName=Middle", "ParameterName=Centre"))


@pytest.mark.parametrize("old, new, found", [
    ("ParameterName=Device type", "ParameterName=Device Type", "ParameterName"),
    ("DataType=0x0003\nAccessType=ro\nDefaultValue=-40", "DataType=0x0004\nAccessType=ro\n"
     "DefaultValue=-40", "DataType"),
    ("ObjectType=0x2", "ObjectType=0x7", "ObjectType"),
    ("AccessType=const\nDefaultValue=2", "AccessType=ro\nDefaultValue=2", "AccessType"),
    ("DefaultValue=0x00020192", "DefaultValue=0x00020193", "DefaultValue"),
    ("DefaultValue=$NODEID+0x600", "DefaultValue=0x600", "DefaultValue"),
    ("DefaultValue=hello world", "DefaultValue=hello  world", "DefaultValue"),
    ("DefaultValue=-0x10", "DefaultValue=0x10", "DefaultValue"),
    ("DefaultValue=1.5e3", "DefaultValue=1.5e2", "DefaultValue"),
    ("DataType=0x0006\nAccessType=ro\nPDOMapping=1", "DataType=0x0006\nAccessType=ro\n"
     "PDOMapping=0", "PDOMapping"),
    ("LowLimit=-1000", "LowLimit=-999", "LowLimit"),
    ("HighLimit=0x7D", "HighLimit=0x7E", "HighLimit"),
    ("LowLimit=$NODEID", "LowLimit=0", "LowLimit"),
    ("ObjFlags=2", "ObjFlags=3", "ObjFlags"),
    ("ObjFlags=0x1\nParameterValue", "ParameterValue", "ObjFlags"),
    ("ParameterValue=0xA2", "ParameterValue=0xA3", "ParameterValue"),
    ("Denotation=wheel drive", "Denotation=wheel", "Denotation"),
    ("StorageLocation=ROM", "StorageLocation=RAM", "storagelocation 'ROM' -> 'RAM'"),
    ("Unit=mV\n", "", "unit 'mV' lost"),
    ("CompactSubObj=3", "CompactSubObj=4", "object 0x2001 sub 4: added"),
    ("2=Middle", "2=Centre", "ParameterName"),
    ("2=0x9", "2=0xA", "ParameterValue"),
    ("1=left lamp", "1=right lamp", "Denotation"),
    ("2=0x6000", "2=0x6001", "ObjectLinks"),
    ("[1200sub2]\nParameterName=COB-ID server to client\nObjectType=0x7\nDataType=0x0007\n"
     "AccessType=ro\nDefaultValue=$NODEID + 0x580\nPDOMapping=0\n", "", "sub 2: lost"),
    ("[2009]\nParameterName=Timestamp", "[200F]\nParameterName=Timestamp", "object 0x2009: lost"),
    ("Description=every CiA 306 feature\n", "", "[FileInfo]: description"),
    ("FileVersion=3", "FileVersion=4", "[FileInfo]: fileversion"),
    ("CreationDate=02-28-2024", "CreationDate=02-29-2024", "creationdate"),
    ("CreatedBy=test author", "CreatedBy=test", "createdby"),
    ("LastEDS=features.eds", "LastEDS=other.eds", "lasteds"),
    ("VendorNumber=0x0000ABCD", "VendorNumber=0x0000ABCE", "vendornumber"),
    ("BaudRate_800=1", "BaudRate_800=0", "baudrate_800"),
    ("CompactPDO=1", "CompactPDO=0", "compactpdo"),
    ("NrOfRXPDO=2", "NrOfRXPDO=1", "nrofrxpdo"),
    ("CANopenSafetySupported=0\n", "", "[deviceinfo]: canopensafetysupported '0' lost"),
    ("NodeID=0x22", "NodeID=0x23", "[DeviceComissioning]: nodeid"),
    ("Dummy0005=1", "Dummy0005=0", "Dummy0005"),
    ("Line1=first comment line", "Line1=first comment", "[Comments]"),
    ("Editor=by hand", "Editor=by machine", "[tools]: editor"),
    ("[Tools]\nEditor=by hand\nChecked=1\n", "", "[tools]: section lost"),
])
def test_every_change_is_found(old, new, found):
    assert old in FEATURES, old
    changed = FEATURES.replace(old, new, 1)
    d = diffs(FEATURES, changed)
    assert d, f"{old!r} -> {new!r} not found"
    assert any(found in x for x in d), d


def test_added_object_is_found():
    d = diffs(FEATURES, FEATURES + "\n[5000]\nParameterName=new\nDataType=0x0005\n"
              "AccessType=rw\n")
    assert d == ["object 0x5000: added"]


def test_command_line(tmp_path):
    a, b = tmp_path / "a.eds", tmp_path / "b.eds"
    a.write_text(FEATURES)
    b.write_text(FEATURES.replace("DefaultValue=0x00020192", "DefaultValue=131474"))
    r = subprocess.run([sys.executable, str(ODGEN), "compare", str(a), str(b)],
                       capture_output=True, text=True)
    assert r.returncode == 0 and r.stdout == ""
    assert "0 difference(s)" in r.stderr
    b.write_text(FEATURES.replace("DefaultValue=0x00020192", "DefaultValue=1"))
    r = subprocess.run([sys.executable, str(ODGEN), "compare", str(a), str(b)],
                       capture_output=True, text=True)
    assert r.returncode == 1
    assert r.stdout.strip() == "object 0x1000 sub 0: DefaultValue 131474 (0x20192) -> 1"
