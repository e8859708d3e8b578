"""The generator refuses a description that needs a service or option the
core build leaves out (--build NAME=VALUE, what co_device passes from the
core library's definitions), and accepts it when the build has it."""
from __future__ import annotations

import os
import re
import shutil
import subprocess
import textwrap
from pathlib import Path

import pytest

from conftest import ROOT, WARN, run_odgen

GENERIC = ROOT / "devices" / "generic-301.toml"       # 0x100C/0x100D, 0x1012, 0x1006
MINIMAL = ROOT / "targets" / "cortex-m" / "minimal-slave.toml"
LEAN = ROOT / "tests" / "unit" / "devices" / "lean-test.toml"
KOLLMORGEN = ROOT / "devices" / "kollmorgen-s300-s700.toml"  # SDO expedited only
FAULHABER = ROOT / "devices" / "faulhaber-mc.toml"  # 0x1029, [tpdo] change_detection = false
PDO_TEST = ROOT / "tests" / "unit" / "devices" / "pdo-test.toml"  # tpdo_mask


@pytest.mark.parametrize("option, needle", [
    ("CO_TIME=0", "TIME (object 0x1012) needs CO_TIME=1"),
    ("CO_SYNC_PRODUCER=0", "SYNC producer (object 0x1006) needs CO_SYNC_PRODUCER=1"),
    ("CO_NODE_GUARDING=0", "node guarding (object 0x100C, 0x100D) needs CO_NODE_GUARDING=1"),
    ("CO_SDO_BLOCK=0", "block SDO"),
])
def test_refused(tmp_path: Path, option: str, needle: str) -> None:
    r = run_odgen(GENERIC, tmp_path, "--c", f"--build={option}")
    assert r.returncode == 1
    assert needle in r.stderr
    assert not list(tmp_path.iterdir())  # nothing written


def test_error_behaviour(tmp_path: Path) -> None:
    r = run_odgen(FAULHABER, tmp_path, "--c", "--build=CO_ERROR_BEHAVIOUR=0")
    assert r.returncode == 1
    assert "error behaviour (object 0x1029) needs CO_ERROR_BEHAVIOUR=1" in r.stderr


def test_refused_names_every_missing_part(tmp_path: Path) -> None:
    r = run_odgen(GENERIC, tmp_path, "--c", "--build=CO_TIME=0,CO_NODE_GUARDING=0")
    assert r.returncode == 1
    assert "CO_TIME=1" in r.stderr and "CO_NODE_GUARDING=1" in r.stderr


def test_options_outside_the_build(tmp_path: Path) -> None:
    r = run_odgen(KOLLMORGEN, tmp_path, "--c", "--build=CO_PERSONALITY=0")
    assert r.returncode == 1
    assert "SDO_EXPEDITED_ONLY" in r.stderr and "CO_PERSONALITY" in r.stderr


def test_nodeid_object_outside_the_build(tmp_path: Path) -> None:
    # a node-ID object is a manufacturer's deviation: CO_PERSONALITY=0 has no code for it
    desc = tmp_path / "nodeid.toml"
    desc.write_text(LEAN.read_text(encoding="utf-8").replace(
        "[device]\n", "[device]\nnodeid_object = 0x2000\n", 1) +
        '\n[[object]]\nindex = 0x2000\nname = "Node-ID"\ntype = "UNSIGNED8"\n'
        'access = "rw"\ndefault = 5\n', encoding="utf-8")
    out = tmp_path / "out"
    r = run_odgen(desc, out, "--c", "--build=CO_PERSONALITY=0")
    assert r.returncode == 1
    assert "nodeid_object 0x2000" in r.stderr and "CO_PERSONALITY" in r.stderr
    assert run_odgen(desc, out, "--c", "--build=CO_PERSONALITY=1").returncode == 0


def test_no_block_is_no_deviation_without_block(tmp_path: Path) -> None:
    # [sdo] transfers without "block": a personality for a core with block
    # SDO, what a core without it does anyway (tools/bench-size's SEG set)
    seg = ROOT / "tests" / "perf" / "size-seg.toml"
    r = run_odgen(seg, tmp_path, "--c", "--build=CO_PERSONALITY=0,CO_SDO_BLOCK=1")
    assert r.returncode == 1 and "SDO_NO_BLOCK" in r.stderr
    assert run_odgen(seg, tmp_path, "--c",
                     "--build=CO_PERSONALITY=0,CO_SDO_BLOCK=0").returncode == 0


def test_accepted(tmp_path: Path) -> None:
    # what the device does not need may be left out
    assert run_odgen(LEAN, tmp_path, "--c",
                     "--build=CO_STORAGE=0;CO_TIME=0;CO_SYNC_PRODUCER=0;CO_ERROR_BEHAVIOUR=0;"
                     "CO_LIMITS=0;CO_PERSONALITY=0;CO_NODE_GUARDING=0").returncode == 0
    # the minimal slave has guarding: with it, its build's options pass
    assert run_odgen(MINIMAL, tmp_path, "--c",
                     "--build=CO_STORAGE=0,CO_TIME=0,CO_SYNC_PRODUCER=0,CO_ERROR_BEHAVIOUR=0,"
                     "CO_LIMITS=0,CO_PERSONALITY=0,CO_HB_CONSUMERS_MAX=4U").returncode == 0
    # a device that offers no block SDO is fine without it
    assert run_odgen(KOLLMORGEN, tmp_path, "--c", "--build=CO_SDO_BLOCK=0").returncode == 0
    # no build options: the full core
    assert run_odgen(GENERIC, tmp_path, "--c", "--build=").returncode == 0


def test_tpdo_rtr(tmp_path: Path) -> None:
    # a TPDO that defaults to an RTR-only type (252/253) needs CO_PDO_RTR;
    # the lean-test device's TPDO (type 1) does not
    text = LEAN.read_text(encoding="utf-8").replace(
        '{ sub = 2, name = "Transmission type", type = "UNSIGNED8", default = 1 }',
        '{ sub = 2, name = "Transmission type", type = "UNSIGNED8", default = 253 }')
    assert "default = 253" in text
    rtr = tmp_path / "rtr.toml"
    rtr.write_text(text, encoding="utf-8")
    out = tmp_path / "out"
    out.mkdir()
    r = run_odgen(rtr, out, "--c", "--build=CO_PDO_RTR=0")
    assert r.returncode == 1
    assert "TPDO transmission type 252/253 (0x1800) needs CO_PDO_RTR=1" in r.stderr
    assert run_odgen(rtr, out, "--c", "--build=").returncode == 0
    assert run_odgen(LEAN, out, "--c", "--build=CO_PDO_RTR=0").returncode == 0


def test_pdo_bitwise(tmp_path: Path) -> None:
    # a default mapping entry that is not a whole number of bytes (an object
    # is mapped whole: only a BOOLEAN dummy of 1 bit can be one) needs
    # CO_PDO_BITWISE; the lean-test device's entries (32 bits) do not
    text = LEAN.read_text(encoding="utf-8").replace(
        "defaults = [0x21000020]", "defaults = [0x00010001]").replace(
        'author = "canopen-stack"', 'author = "canopen-stack"\ndummy_usage = [1]')
    assert "0x00010001" in text and "dummy_usage" in text
    bits = tmp_path / "bits.toml"
    bits.write_text(text, encoding="utf-8")
    out = tmp_path / "out"
    out.mkdir()
    r = run_odgen(bits, out, "--c", "--build=CO_PDO_BITWISE=0")
    assert r.returncode == 1
    assert "a mapping length not a multiple of 8 (0x1600) needs CO_PDO_BITWISE=1" in r.stderr
    assert not list(out.iterdir())  # nothing written
    assert run_odgen(bits, out, "--c", "--build=").returncode == 0
    assert run_odgen(LEAN, out, "--c", "--build=CO_PDO_BITWISE=0").returncode == 0


def test_tpdo_change(tmp_path: Path) -> None:
    # the change masks (options TPDO_MASK_254/255 with [device] tpdo_mask)
    # and change detection switched off ([tpdo] change_detection = false)
    # are settings of the change detection, which CO_TPDO_CHANGE=0 leaves
    # out; the lean-test device has none of them
    r = run_odgen(PDO_TEST, tmp_path, "--c", "--build=CO_TPDO_CHANGE=0")
    assert r.returncode == 1
    assert ("TPDO change detection settings (TPDO_MASK_254, TPDO_MASK_255, tpdo_mask 0x2030) "
            "needs CO_TPDO_CHANGE=1 (this build: CO_TPDO_CHANGE=0)") in r.stderr
    assert not list(tmp_path.iterdir())  # nothing written
    r = run_odgen(FAULHABER, tmp_path, "--c", "--build=CO_TPDO_CHANGE=0")
    assert r.returncode == 1
    assert "TPDO change detection settings (TPDO_NO_CHANGE_DETECT) needs CO_TPDO_CHANGE=1" in r.stderr
    assert run_odgen(PDO_TEST, tmp_path, "--c", "--build=").returncode == 0
    assert run_odgen(FAULHABER, tmp_path, "--c", "--build=").returncode == 0
    assert run_odgen(LEAN, tmp_path, "--c", "--build=CO_TPDO_CHANGE=0").returncode == 0


def test_store_commands_without_storage(tmp_path: Path) -> None:
    # a core without CO_STORAGE: the commands of 0x1010 / 0x1011 read 0
    # whatever is written, so they take no RAM: one writable const 0 all of
    # them name (one row: a run of one const value, CO_OD_RUN), and the two
    # objects share one table; with storage each has
    # its RAM value (the capability the store service sets at every reset)
    seg = ROOT / "tests" / "perf" / "size-seg.toml"
    lean, full = tmp_path / "lean", tmp_path / "full"
    assert run_odgen(seg, lean, "--c", "--base", "d",
                     "--build=CO_STORAGE=0,CO_PERSONALITY=0,CO_SDO_BLOCK=0").returncode == 0
    assert run_odgen(seg, full, "--c", "--base", "d", "--build=CO_STORAGE=1").returncode == 0
    h, c = (lean / "d.h").read_text(), (lean / "d.c").read_text()
    assert "x1010_store_parameters" not in h and "x1011_restore" not in h
    assert c.count("(uint16_t)(CO_SUB_R | CO_SUB_W | CO_SUB_ROM), 4U, R(store_command_none)") == 1
    assert ("CO_OD_RUN(0x01U, 4U, (uint8_t)CO_UNSIGNED32, (uint16_t)(CO_SUB_R | CO_SUB_W | "
            "CO_SUB_ROM), 4U, R(store_command_none), 0U)") in c
    # (one row: sub-index 0, the number of entries, is implicit, CO_OD_TAG_SUB0)
    at = {i: re.search(rf"CO_OD_ENTRY_TAG\(0x{i}U, 1U, (\d+)U, 0U, .*CO_OD_TAG_SUB0", c)
          for i in ("1010", "1011")}
    assert at["1010"] and at["1011"] and at["1010"].group(1) == at["1011"].group(1)
    h = (full / "d.h").read_text()
    assert "uint32_t x1010_store_parameters[4];" in h and "x1011_restore" in h
    assert "store_command_none" not in (full / "d.c").read_text()


def test_pdo_block_padding_holds_bytes(tmp_path: Path) -> None:
    # the core's head of the image (co_node.h, CO_RAM_*: 0x1019 at 16, 0x1016
    # from 20) and a TPDO's block (a byte of padding after its SYNC start
    # value) have padding: one-byte communication values no block holds go
    # there, the head's first (the RAM image shrinks by those bytes; the
    # shared tables' offsets stay, the source checks them)
    desc = tmp_path / "d.toml"
    desc.write_text(f'include = "{ROOT / "tests" / "perf" / "size-seg.toml"}"\n' + "".join(
        f'\n[[object]]\nindex = 0x{i:04X}\nname = "Byte {i:04X}"\ntype = "UNSIGNED8"\n'
        f'access = "rw"\n' for i in (0x1F90, 0x1F91, 0x1F92, 0x1F93)))
    assert run_odgen(desc, tmp_path, "--c", "--base", "d", "--build=CO_STORAGE=1").returncode == 0
    h = [line.split(";")[0].strip() for line in (tmp_path / "d.h").read_text().splitlines()]
    at = h.index("uint8_t x1019_synchronous_counter_overflow_value")
    assert h[at + 1] == "uint8_t x1280_node_id_of_the_sdo_server"
    assert h[at + 2] == "uint8_t x1F90_byte_1f90"
    assert h[at + 3] == "uint8_t x1F91_byte_1f91"
    assert h[at + 4] == "uint32_t x1016_consumer_heartbeat_time[8]"
    at = h.index("uint8_t x1800_sync_start_value")
    assert h[at + 1] == "uint8_t x1F92_byte_1f92"
    assert h[at + 2] == "uint16_t x1800_inhibit_time"
    at = h.index("uint8_t x1801_sync_start_value")
    assert h[at + 1] == "uint8_t x1F93_byte_1f93"
    assert h[at + 2] == "uint16_t x1801_inhibit_time"
    assert "uint8_t x1802_sync_start_value" in h
    assert h[h.index("uint8_t x1802_sync_start_value") + 1] == "uint16_t x1802_inhibit_time"


def _compile(src: Path, *defines: str) -> "subprocess.CompletedProcess[str]":
    return subprocess.run(["cc", *WARN, "-c", *[f"-D{d}" for d in defines],
                           f"-I{ROOT / 'stack' / 'include'}", str(src), "-o", os.devnull],
                          capture_output=True, text=True, check=False)


@pytest.mark.skipif(shutil.which("cc") is None, reason="no C compiler")
@pytest.mark.parametrize("desc, base, lean_ok", [
    (KOLLMORGEN, "kollmorgen", False),                      # SDO expedited only
    (ROOT / "tests" / "perf" / "size-seg.toml", "seg", True),  # no block SDO only
])
def test_personality_guard_without_build(tmp_path: Path, desc: Path, base: str,
                                         lean_ok: bool) -> None:
    # generated without --build: co_dev_t has the personality (set) only in a
    # core with CO_PERSONALITY or CO_LSS; a core with neither refuses a device
    # that needs a deviation when its dictionary is compiled (#error), but
    # takes "no block SDO" when it has no block SDO itself
    assert run_odgen(desc, tmp_path, "--c", "--base", base).returncode == 0
    src = tmp_path / f"{base}.c"
    assert _compile(src).returncode == 0
    assert _compile(src, "CO_PERSONALITY=0", "CO_LSS=1").returncode == 0
    r = _compile(src, "CO_PERSONALITY=0", "CO_LSS=0", "CO_SDO_BLOCK=1")
    assert r.returncode != 0 and "needs CO_PERSONALITY=1" in r.stderr
    r = _compile(src, "CO_PERSONALITY=0", "CO_LSS=0", "CO_SDO_BLOCK=0")
    assert (r.returncode == 0) == lean_ok, r.stderr
    if not lean_ok:
        assert "needs CO_PERSONALITY=1" in r.stderr


def test_core_objects_at_their_places(tmp_path: Path) -> None:
    # the core's objects where co_node.h's CO_RAM_* says: the image starts
    # with 0x1005, 0x1007, 0x1014, 0x1015, 0x1017, 0x1019, then 0x1016 sub 1..;
    # the values not stored (app_end, a multiple of 4) with 0x1001, 0x1003
    # sub 0, then 0x1003 sub 1.. at app_end + 4; the source checks the places
    # at compile time (d_core_at). A device without them has zeros there
    # (fields of no object, no default), which the core reads as their
    # absence; the size of each is the object's.
    desc = tmp_path / "d.toml"
    desc.write_text(textwrap.dedent("""
        [device]
        name = "places"
        vendor_id = 0x1234
        device_type = 0

        [[object]]
        index = 0x1001
        name = "Error register"
        type = "UNSIGNED8"
        access = "ro"

        [[object]]
        index = 0x1017
        name = "Producer heartbeat time"
        type = "UNSIGNED16"
        default = 500

        [[object]]
        index = 0x2000
        name = "Value"
        type = "UNSIGNED8"
        default = 7
        """))
    assert run_odgen(desc, tmp_path, "--c", "--base", "d").returncode == 0
    h = [line.split(";")[0].strip() for line in (tmp_path / "d.h").read_text().splitlines()]
    ram = h[h.index("typedef struct d_ram {") + 1:h.index("} d_ram_t")]
    fields = [x for x in ram if x and not x.startswith("/*")]
    assert fields[:6] == ["uint32_t core_x1007", "uint16_t core_x1005", "uint16_t core_x1014",
                          "uint16_t core_x1015", "uint16_t x1017_producer_heartbeat_time",
                          "uint8_t core_x1019"]
    # (no 0x1016: the others right after the head; the values not stored
    # start with 0x1001 and the place of 0x1003 sub 0; app_end at a multiple
    # of 4 only for a 0x1003 history: none here)
    assert "uint8_t x2000_value" in fields[6:]
    at = ram.index("/* values not stored (restored to defaults at reset) */")
    assert ram[at + 1:at + 3] == ["uint8_t x1001_error_register", "uint8_t core_x1003"]
    c = (tmp_path / "d.c").read_text()
    assert "typedef char d_core_at[((F(core_x1007) == CO_RAM_1007) &&" in c
    assert "(F(core_x1003) == F(x1001_error_register) + CO_RAM_END_1003)" in c
    assert ".app_end = F(x1001_error_register)," in c
    # the zeros of the places are no default runs
    assert "core_x" not in c[c.index("static const uint8_t defaults[]"):c.index("};", c.index(
        "static const uint8_t defaults[]"))]
    # compiles against the core's header: the places hold
    src = tmp_path / "check.c"
    src.write_text(f'#include "{tmp_path / "d.c"}"\n')
    r = subprocess.run(["cc", *WARN, "-c", f"-I{ROOT / 'stack' / 'include'}", f"-I{tmp_path}",
                        str(src), "-o", os.devnull], capture_output=True, text=True, check=False)
    assert r.returncode == 0, r.stderr
