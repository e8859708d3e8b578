"""EDS import on EDS files written by others (tests/gen/foreign/README.md):
EDS -> description -> EDS loses nothing CiA 306 defines, read by our CiA 306
reader (tools/odgen/eds_compare.py) and by python-canopen; the imported
description compiles to a C dictionary that equals its EDS; a second round
trip changes nothing."""
from __future__ import annotations

import re
import shutil

import pytest

from cia306 import read_eds
from compare import compare, run_dump
from conftest import compile_dump, foreign
from roundtrip import canopen_differences, round_trip, semantic_differences

# file -> (objects, sub-entries, objects kept eds_only by the import)
FOREIGN = {
    "e35.eds": (211, 995, set()),
    "sample.eds": (40, 124, {0x1600, 0x1601, 0x1602, 0x1603, 0x1A00, 0x1A01, 0x1A02, 0x1A03,
                             0x2020, 0x3002, 0x3003, 0x3010}),
    "datatypes.eds": (24, 28, {0x2009, 0x200A, 0x200B, 0x200F}),
    "example.eds": (4, 10, set()),
}


@pytest.fixture(scope="module", params=sorted(FOREIGN), ids=[n[:-4] for n in sorted(FOREIGN)])
def imported(request, tmp_path_factory):
    name = request.param
    src = foreign(name)
    r, out, dev = round_trip(src, tmp_path_factory.mktemp(name[:-4]), name[:-4])
    return name, src, r, out, dev


def test_foreign_files_are_the_expected_ones():
    for name, (n_obj, n_sub, _) in FOREIGN.items():
        eds = read_eds(foreign(name))
        assert len(eds.objects) == n_obj, name
        assert sum(len(o.subs) for o in eds.objects.values()) == n_sub, name
    assert "Manufacturer" in foreign("e35.eds").read_text()
    assert "CreatedBy=objdictgen" in foreign("datatypes.eds").read_text()


def test_round_trip_loses_nothing(imported):
    name, src, r, out, dev = imported
    assert semantic_differences(src, out) == []
    # every object again, each either in the C dictionary or kept verbatim
    assert {o.index for o in dev.objects} | {o.index for o in dev.eds_only} == \
        set(read_eds(src).objects)


def test_round_trip_python_canopen_reads_the_same(imported):
    name, src, r, out, dev = imported
    assert canopen_differences(src, out, node_id=5) == []
    assert canopen_differences(src, out, node_id=None) == []


def test_eds_only_objects_are_reported(imported):
    name, src, r, out, dev = imported
    expected = FOREIGN[name][2]
    assert {o.index for o in dev.eds_only} == expected
    reported = {int(m, 16) for m in re.findall(r"object 0x([0-9A-F]{4}) kept as eds_only",
                                               r.stderr)}
    assert reported == expected
    for line in r.stderr.splitlines():
        assert line.startswith(f"warning: {src}"), line
        if "eds_only" in line:
            assert re.match(rf"warning: {re.escape(str(src))}:\d+: object 0x[0-9A-F]{{4}} kept "
                            r"as eds_only \(not in the C dictionary\): \S", line), line


@pytest.mark.skipif(shutil.which("cc") is None, reason="no C compiler")
def test_imported_description_compiles_and_equals_its_eds(imported):
    name, src, r, out, dev = imported
    exe = compile_dump(out.parent, dev.cname)
    n_values = compare(out, run_dump(exe), eds_only={o.index for o in dev.eds_only})
    n_subs = sum(len(o.subs) for o in dev.objects)
    assert n_values >= n_subs - sum(1 for o in dev.objects for s in o.subs if s.hookio)
    assert n_values > 0


def test_second_round_trip_is_a_fixed_point(imported, tmp_path):
    name, src, r, out, dev = imported
    work = tmp_path / "again"
    work.mkdir()
    _, out2, dev2 = round_trip(out, work, name[:-4])
    assert out2.read_bytes() == out.read_bytes()
    assert {o.index for o in dev2.eds_only} == {o.index for o in dev.eds_only}


# ---------------------------------------------------- what the imports hold

def toml_of(imported) -> str:
    name, src, r, out, dev = imported
    return (out.parent.parent / f"{name[:-4]}.toml").read_text()


def test_e35_real_drive(tmp_path):
    src = foreign("e35.eds")
    r, out, dev = round_trip(src, tmp_path, "e35")
    text = (tmp_path / "e35.toml").read_text()
    # a DCF-style EDS: ParameterValues kept for the EDS, defaults for the C dictionary
    s = dev.find(0x2000, 1)
    assert (s.default, s.parameter_value, s.eds_low, s.eds_high) == (None, 0x20, 1, 0x7F)
    cob = dev.find(0x1800, 1)
    assert cob.nodeid and cob.default == 0x40000180 and cob.parameter_value == 0x400001A0
    assert 'default = "$NODEID+0x40000180"' in text
    assert dev.eds["dummy_usage"] == [5, 6, 7]
    assert dev.eds["eds_version"] == "402"       # as the vendor wrote it
    assert dev.info["vendor_number"] == 101 and dev.info["lss"] is True
    assert dev.find(0x100A, 0).default == "2.4.13" and dev.find(0x100A, 0).rom
    assert not dev.eds_only
    # the source's own inconsistencies are reported, not copied
    assert "[ManufacturerObjects] SupportedObjects=105 does not match its 104 entries" in r.stderr
    assert "lists 0x6505, which has no section" in r.stderr
    eds = read_eds(out)
    assert eds.warnings == []


def test_sample_dcf(tmp_path):
    src = foreign("sample.eds")
    r, out, dev = round_trip(src, tmp_path, "sample")
    assert dev.dcf == {"node_id": 16, "node_name": "Some name", "baudrate": 500,
                       "net_number": 0, "lss_serial_number": 0}
    assert dev.eds["comments"] == ["|-------------|", "| Don't panic |", "|-------------|"]
    assert dev.eds["file_name"] == "test.dcf"
    assert dev.eds["sections"] == {"FileInfo": {"LastEDS": "test.dcf"}}
    # CompactSubObj with names, and without (names <ParameterName><k>)
    o = next(o for o in dev.objects if o.index == 0x3004)
    assert o.compact and [s.name for s in o.subs] == ["NrOfObjects"] + [
        f"Sensor Status {k}" for k in (1, 2, 3)]
    o = next(o for o in dev.objects if o.index == 0x3006)
    assert o.compact and len(o.subs) == 25 and o.subs[24].name == "Valve 1 % Open24"
    # signed limits given in two's complement
    assert (dev.find(0x3030, 0).eds_low, dev.find(0x3030, 0).eds_high) == (-2**31, -1)
    assert (dev.find(0x3040, 0).eds_low, dev.find(0x3040, 0).eds_high) == (-10, 10)
    # vendor keys python-canopen understands are kept verbatim
    assert dev.find(0x3050, 1).eds_keys == {"Factor": "0.1",
                                            "Description": "This is the a test description",
                                            "Unit": "mV"}
    reasons = {o.index: o.reason for o in dev.eds_only}
    assert "data type 0x0040 is not a CiA 301 basic type" in reasons[0x2020]
    assert "limit 4.5 is not an integer" in reasons[0x3002]
    assert "without sub-entries" in reasons[0x3003]
    assert "sub-index 0 of a RECORD is UNSIGNED8" in reasons[0x3010]
    assert "maps 0x6040 sub 0, which does not exist" in reasons[0x1600]
    assert "[1018] SubNumber=5 but 4 sub-entry sections" in r.stderr
    # the object lists of the output are complete again
    assert read_eds(out).warnings == []


def test_datatypes_every_basic_type(tmp_path):
    src = foreign("datatypes.eds")
    r, out, dev = round_trip(src, tmp_path, "datatypes")
    types = {s.type for o in dev.objects for s in o.subs}
    assert {"BOOLEAN", "INTEGER24", "INTEGER40", "INTEGER48", "INTEGER56", "UNSIGNED24",
            "UNSIGNED40", "UNSIGNED48", "UNSIGNED56", "REAL32", "REAL64", "INTEGER64",
            "UNSIGNED64"} <= types
    assert dev.find(0x2010, 0).default == -1
    # no 0x1000/0x1001 in the source: the description says so instead of inventing them
    text = (tmp_path / "datatypes.toml").read_text()
    assert "mandatory_objects = false" in text
    reasons = {o.index: o.reason for o in dev.eds_only}
    assert "cannot be PDO-mapped" in reasons[0x2009]
    assert "'@ABCD' is not hex bytes" in reasons[0x200F]
    # the UTF-8 UNICODE_STRING default survives (in the eds_only object, verbatim)
    assert "DefaultValue=abc\u2713" in out.read_text(encoding="utf-8")


def test_example_node_canopen(tmp_path):
    src = foreign("example.eds")
    r, out, dev = round_trip(src, tmp_path, "example")
    assert r.stderr == ""
    assert dev.info["vendor_name"] == "" and dev.info["baudrates"] == []
    assert dev.eds["time"] == "13:51" and dev.eds["modified_by"] == ""
    assert dev.eds["simple_boot_up_slave"] is False
    assert dev.find(0x1018, 0).access == "rw"
