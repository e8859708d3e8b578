"""(2) The EDS describes exactly the compiled C dictionary.

od_dump_<device> (tests/gen/od_dump.c, linked with the generated library
codev_<device> and the core) initialises node 5 and prints every entry and
sub-entry with data type, flags and the value read through co_od_read. Its
object list, data types, access types, PDO mapping, limits and values must
equal the EDS from the same build as python-canopen parses it for node 5
($NODEID resolved).
"""
from __future__ import annotations

import pytest

from compare import NODE_ID, compare, run_dump
from conftest import build_dir


@pytest.fixture
def built(device):
    bdir = build_dir()
    cname = device.stem.replace("-", "_")
    exe = bdir / "bin" / f"od_dump_{cname}"
    eds = bdir / "codev" / device.stem / f"{device.stem}.eds"
    if not exe.exists() or not eds.exists():
        pytest.fail(f"{exe} / {eds} missing: build the tree first "
                    f"(cmake --build {bdir}) or set CODEV_BUILD_DIR")
    dump = run_dump(exe)
    return eds, dump


def test_core_finds_its_objects(device, built):
    _, dump = built
    core = dump["core"]
    assert dump["node_id"] == NODE_ID
    # boot-up, then (set.nmt.boot_emcy) the EMCY 0x0000 of the end of initialisation
    boot_emcy = dump["set"]["nmt"]["boot_emcy"] != 0
    assert core["frames"] == 1 + boot_emcy and core["first_id"] == 0x700 + NODE_ID
    assert core["nmt"] == 0x7F
    if device.stem == "generic-301":
        assert core["hist_depth"] == 8 and core["n_hb_cons"] == 4
        for k in ("errreg", "emcy_cob", "hb_prod", "guard_time", "life_factor", "emcy_inhibit"):
            assert core[k] == 1, k
    assert 0 <= dump["comm_end"] <= dump["app_end"] <= dump["ram_size"]


def test_eds_equals_c_dictionary(built):
    eds_path, dump = built
    assert compare(eds_path, dump) > 50


def test_unicode_string_reads_whole_text(built):
    _, dump = built
    subs = [s for e in dump["entries"] for s in e["subs"]
            if s["type"] == 0x0B and s["ram"] and bytes.fromhex(s["ram"])[:2] != b"\0\0"]
    if not subs:
        pytest.skip("no UNICODE_STRING with a default")
    for s in subs:
        stored = bytes.fromhex(s["ram"])
        text = stored.decode("utf-16-le").split("\0")[0]
        assert s["abort"] == 0
        assert bytes.fromhex(s["value"]).decode("utf-16-le") == text
