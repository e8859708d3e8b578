"""The CiA 402 devices on vcan, driven by python-canopen over SDO (issue 7):
each drive is enabled (shutdown, switch on, enable operation, each
statusword checked), makes a profile-position move to a target and reports
target reached there, and runs a homing that ends in homing attained.

Units are the device's own (see devices/<name>.c): the values below are a
move of a few revolutions of its simulated motor at a moderate speed.
AnaGate Motion modules have one mode only, the velocity ramp (no 0x6060,
0x607A or 0x6098 exist in their dictionaries, digest §3.6): every axis is
enabled and ramps to a speed until target reached, then back to rest.
"""
from __future__ import annotations

import sys
import time
from dataclasses import dataclass
from pathlib import Path

import pytest

from conftest import AXES, start_device

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "tools" / "demo"))
from cia402_master import Drive, state_of  # noqa: E402

NODE = 12


@dataclass
class Move:
    target: int          # 0x607A, position units
    velocity: int        # 0x6081, velocity units
    acceleration: int    # 0x6083 / 0x6084
    window: int          # accepted |actual - target| after target reached
    method: int          # 0x6098
    speeds: tuple[int, int] | None = None   # 0x6099:1/2 (None: the device's defaults)
    start: bool = False  # NMT start first (the controlword acts only in Operational)
    # the axis stops shortly after the reference (it brakes from homing speed
    # once the reference is found): |position - home offset| after homing
    home_window: int = 100
    setup: tuple = ()    # (index, sub, value, size) written before enabling


DRIVES = {
    # 4096 increments/rev; 10 rev at 5 rev/s; homing on the next index pulse
    "cia402": Move(40960, 20480, 40960, 2, 34, (8192, 2048)),
    # 2^20 increments/rev (PRBASE 20), scaled as in its D7.9 example to
    # 36000 um per revolution (0x6093); 2 rev at 1 rev/s; homing on the next
    # zero mark at 1 rev/s (0x6099 is limited to 65535 um/s)
    "kollmorgen-s300-s700": Move(72000, 36000, 72000, 2, 34, (36000, 36000),
                                 home_window=36000 // 10,
                                 setup=((0x6093, 1, 1 << 20, 4), (0x6093, 2, 36000, 4))),
    # velocities in rpm (4096 increments/rev): 10 rev at 300 rpm; its homing
    # mode 0 (method -24): next encoder zero pulse, positive
    "ssd-630": Move(40960, 300, 600, 8, -24),
    # 3000 increments/rev, rpm and 1/s^2; controlword only in Operational;
    # homing method 20 on its home switch (at 30000 increments): the edge is
    # found at 600 rpm and the axis brakes with 0x609A (50 1/s^2) behind it
    "faulhaber-mc": Move(30000, 300, 20, 10, 20, (600, 60), start=True, home_window=3100),
}

ANAGATE = sorted(d for d in AXES if d.startswith("anagate-motion"))


@pytest.mark.parametrize("device", sorted(DRIVES))
def test_enable_move_and_home(device, network, daemons, sniffer, tmp_path):
    mv = DRIVES[device]
    node = start_device(device, NODE, network, daemons, sniffer, tmp_path)
    if mv.start:
        node.nmt.state = "OPERATIONAL"
    log: list[str] = []
    d = Drive(node, 0, log.append)
    for index, sub, value, size in mv.setup:
        d.write(index, value, size, sub)
    sw = d.enable()
    assert state_of(sw) == "Operation enabled", log

    pos = d.pp_move(mv.target, mv.velocity, mv.acceleration)
    assert abs(pos - mv.target) <= mv.window, log
    sw = d.statusword()
    assert sw & (1 << 10) and state_of(sw) == "Operation enabled", f"0x{sw:04X}"
    time.sleep(0.2)                        # and it stays there
    assert abs(d.read(0x6064, signed=True) - mv.target) <= mv.window

    # back towards 0 by a second set-point, then home
    d.pp_move(mv.target // 4, mv.velocity, mv.acceleration)
    sw, home = d.homing(mv.method, mv.speeds)
    assert sw & (1 << 12) and not sw & (1 << 13), f"homing: 0x{sw:04X}"
    assert d.read(0x6061, signed=True) == 6
    # the reference became the home offset (0x607C, 0 by default): the axis
    # stands just past it, not where the move left it (target // 4)
    assert abs(home - d.read(0x607C, signed=True)) <= mv.home_window, log
    assert abs(home - mv.target // 4) > mv.home_window, log


@pytest.mark.parametrize("device", ANAGATE)
def test_anagate_axes_enable_and_ramp(device, network, daemons, sniffer, tmp_path):
    node = start_device(device, NODE, network, daemons, sniffer, tmp_path)
    for axis in range(AXES[device]):
        log: list[str] = []
        d = Drive(node, axis, log.append)
        assert state_of(d.enable()) == "Operation enabled", log
        d.write(0x6083, 200, 4)            # ramp time, ms per 1000 per mille
        d.write(0x6080, 500, 4)            # target speed, per mille
        sw = d.wait_sw("target speed reached", lambda s: s & (1 << 10), 3.0)
        assert state_of(sw) == "Operation enabled", f"axis {axis}: 0x{sw:04X}"
        d.write(0x6080, 0, 4)
        d.wait_sw("at rest", lambda s: s & (1 << 10), 3.0)
        d.control(0x0006)                  # shutdown: power stage off
        d.wait_sw("Ready to switch on", lambda s: s & 0x6F == 0x21)
