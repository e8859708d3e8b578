"""Every readable object of every device the daemon has (--list-devices),
read over SDO on vcan by python-canopen, holds the default the device's own
exported EDS gives for it (issue 5: the running device agrees with its EDS).

Each device runs with a parameter file (--storage), so 0x1010/0x1011 report
their save/restore capability as the EDS says. The only objects whose value
is not their EDS default are process values with a rule of their own, each
checked here against that rule:
  - 0x1003 sub 1..n: the error history has no entries yet (0x08000024);
  - generic-301 0x2024 "Uptime": seconds since start; 0x2300: the DOMAIN,
    empty until written;
  - CiA 402 statusword (0x6041 + 0x800 per axis): the state machine has
    started, so it shows Switch on disabled (the EDS default 0 would be
    Not ready to switch on, a state the drive leaves by itself).
"""
from __future__ import annotations

import subprocess
import sys
import time
from pathlib import Path

import canopen
import pytest

from conftest import AXES, DAEMON, lss_modes, start_device

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "gen"))
from compare import decode, eds_vars, expected  # noqa: E402  (tests/gen/compare.py)

NODE = 7
NO_DATA = 0x08000024


def devices() -> list[str]:
    out = subprocess.run([str(DAEMON), "--list-devices"], check=True, capture_output=True,
                         text=True).stdout
    return [line.split()[0] for line in out.splitlines() if line.strip()]


def readable(var) -> bool:
    return var.access_type in ("ro", "rw", "rwr", "rww", "const")


def is_statusword(device: str, od, index: int) -> bool:
    """0x6041 of a running axis (0x6041 + 0x800 n) of a CiA 402 device (not
    the device status word of a CiA 408 valve, device type 0x....0198)."""
    n, rest = divmod(index - 0x6041, 0x800)
    # a CiA 408 valve's status word is its own; a drive's 0x1000 need not say 402
    # (Kollmorgen prints 0x00002192, the AnaGate modules 0)
    cia402 = (od[0x1000].default & 0xFFFF) != 408
    return (cia402 and index >= 0x6041 and rest == 0 and n < AXES.get(device, 1)
            and 0x6040 in od)


@pytest.mark.parametrize("device", devices())
def test_every_readable_object_holds_its_eds_default(device, network, daemons, sniffer,
                                                     tmp_path):
    started = time.monotonic()
    node = start_device(device, NODE, network, daemons, sniffer, tmp_path,
                        "--storage", str(tmp_path / "params"))
    od = node.object_dictionary
    checked = 0
    wanted = sum(1 for var in eds_vars(od).values() if readable(var))
    for (index, sub), var in sorted(eds_vars(od).items()):
        where = f"{device} 0x{index:04X} sub {sub} ({var.name})"
        if not readable(var):
            continue
        try:
            data = node.sdo.upload(index, sub)
        except canopen.SdoAbortedError as e:
            assert index == 0x1003 and sub > 0 and e.code == NO_DATA, f"{where}: {e}"
            checked += 1
            continue
        if device == "generic-301" and (index, sub) == (0x2024, 0):
            assert 0 <= int.from_bytes(data, "little") <= time.monotonic() - started + 2, where
        elif device == "generic-301" and (index, sub) == (0x2300, 0):
            assert data == b"", where
        elif (index, sub) == (0x1018, 4) and lss_modes()[device] == "LSS-only":
            pass  # the instance's serial number: start_device gave it one (--serial)
        elif is_statusword(device, od, index):
            sw = int.from_bytes(data, "little")
            assert sw & 0x4F == 0x40, f"{where}: 0x{sw:04X} is not Switch on disabled"
        else:
            value = decode(var.data_type, data)
            if var.data_type == 0x0B:           # UNICODE_STRING: up to the terminator
                ends = [k for k in range(0, len(data), 2) if data[k:k + 2] == b"\0\0"]
                value = decode(0x0B, data[:ends[0]] if ends else data)
            want = expected(var, len(data))
            assert value == want, f"{where}: device {value!r}, EDS {want!r}"
        checked += 1
    assert checked == wanted >= 50, (checked, wanted)
