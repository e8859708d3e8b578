"""The CiA 408 valves (cia408, wandfluh-dsv) on the bus: python-canopen
brings each from INIT to DEVICE_MODE_ACTIVE, commands a set-point by RPDO
and sees the actual value follow (on the Wandfluh the TPDO right after each
RPDO, also when nothing changed), and sees NMT Stop force the fault
reaction (the EMCY 0x8100 when the node leaves Stopped) and the fault
reset; a fault of the simulated valve injected through the daemon's control
interface (--control: `set 0x2311 0 1`, co/co408_device.h) gives its EMCY
and the fault reaction, and the reset once it is repaired."""
from __future__ import annotations

import time

import pytest

from conftest import start_device
from test_io import Control

NODE = 0x21
VALVES = ("cia408", "wandfluh-dsv")


def sw_of(node) -> int:
    return int.from_bytes(node.sdo.upload(0x6041, 0), "little")


def wait_sw(node, pred, timeout: float = 3.0) -> int:
    end = time.monotonic() + timeout
    sw = sw_of(node)
    while not pred(sw) and time.monotonic() < end:
        time.sleep(0.01)
        sw = sw_of(node)
    return sw


def rpdo1(cw: int, sp: int) -> bytes:
    return cw.to_bytes(2, "little") + sp.to_bytes(2, "little", signed=True)


@pytest.mark.parametrize("device", VALVES)
def test_valve_active_by_rpdo_and_actual_follows(device, network, daemons, sniffer, tmp_path):
    node = start_device(device, NODE, network, daemons, sniffer, tmp_path)
    assert sw_of(node) == 0x0008                          # INIT
    node.sdo.download(0x604F, 0, bytes([0]))
    node.sdo.download(0x6042, 0, bytes([1]))
    node.sdo.download(0x6043, 0, bytes([1]))              # vpoc
    m = sniffer.mark()
    node.nmt.state = "OPERATIONAL"
    f = sniffer.wait_cob(0x180 + NODE, 2.0, m)              # the TPDO of the start: INIT
    assert f is not None and f.data[0:2] == b"\x08\x00", f
    m = sniffer.mark()
    sniffer.send(0x200 + NODE, rpdo1(0x0007, 8192))       # D, H, M and 50 %
    f = sniffer.wait(lambda f: f.id == 0x180 + NODE and f.data[0:2] == b"\x0F\x00", 2.0, m)
    assert f is not None, [str(x) for x in sniffer.since(m)]  # DEVICE_MODE_ACTIVE at once
    if device == "wandfluh-dsv":
        # type 255: the TPDO right after every RPDO, also when nothing changed
        for _ in range(3):
            m = sniffer.mark()
            sniffer.send(0x200 + NODE, rpdo1(0x0007, 8192))
            f = sniffer.wait_cob(0x180 + NODE, 1.0, m)
            assert f is not None and f.data == b"\x0F\x00", f
    else:
        # cia408: TPDO1 = status word + spool position (6301h): it follows
        deadline = time.monotonic() + 2.0
        spool = 0
        while time.monotonic() < deadline and not 8000 <= spool <= 8300:
            spool = int.from_bytes(node.sdo.upload(0x6301, 1), "little", signed=True)
            time.sleep(0.02)
        assert 8000 <= spool <= 8300, spool
        last = [f for f in sniffer.since(m, 0x180 + NODE)]
        assert last and int.from_bytes(last[-1].data[2:4], "little", signed=True) > 4000
    assert sw_of(node) == 0x000F
    m = sniffer.mark()
    sniffer.send(0x200 + NODE, rpdo1(0x0000, 0))          # TR_5, 6, 7: INIT
    # a TPDO of the moving spool may already be on its way when the RPDO
    # goes out: the first one with INIT, and no ACTIVE after it
    f = sniffer.wait(lambda f: f.id == 0x180 + NODE and f.data[0:2] == b"\x08\x00", 2.0, m)
    assert f is not None, [str(x) for x in sniffer.since(m)]
    time.sleep(0.1)
    later = [x for x in sniffer.since(m, 0x180 + NODE) if x.idx > f.idx]
    assert all(x.data[0:2] == b"\x08\x00" for x in later), [str(x) for x in later]


@pytest.mark.parametrize("device", VALVES)
def test_valve_nmt_stop_forces_fault(device, network, daemons, sniffer, tmp_path):
    node = start_device(device, NODE, network, daemons, sniffer, tmp_path)
    node.sdo.download(0x6040, 0, (0x0007).to_bytes(2, "little"))
    assert sw_of(node) == 0x000F
    node.nmt.state = "OPERATIONAL"
    time.sleep(0.05)
    m = sniffer.mark()
    node.nmt.state = "STOPPED"
    time.sleep(0.2)
    assert not sniffer.since(m, 0x80 + NODE), "an EMCY in Stopped"
    node.nmt.state = "PRE-OPERATIONAL"
    f = sniffer.wait_cob(0x80 + NODE, 2.0, m)
    assert f is not None and f.data == bytes([0x00, 0x81, 0x11, 0, 0, 0, 0, 0]), f
    assert wait_sw(node, lambda s: s == 0x0003) == 0x0003  # FAULT_HOLD (H was set)
    assert int.from_bytes(node.sdo.upload(0x1003, 1), "little") & 0xFFFF == 0x8100
    m = sniffer.mark()
    node.sdo.download(0x6040, 0, (0x0003).to_bytes(2, "little"))
    node.sdo.download(0x6040, 0, (0x000B).to_bytes(2, "little"))
    assert sw_of(node) == 0x000B                          # TR_11: HOLD
    f = sniffer.wait_cob(0x80 + NODE, 2.0, m)
    assert f is not None and f.data == bytes(8), f         # the error is over


@pytest.mark.parametrize("device", VALVES)
def test_valve_fault_injected_emcy_and_reset(device, network, daemons, sniffer, tmp_path):
    """Solenoid-1 cable break in DEVICE_MODE_ACTIVE: EMCY 0x2311 (register
    generic + current) and FAULT_HOLD; reset refused while the cause is
    there; repaired and reset (R rising): HOLD and EMCY 0x0000."""
    sock = tmp_path / "ctl"
    node = start_device(device, NODE, network, daemons, sniffer, tmp_path, "--control", str(sock))
    ctl = Control(sock)
    try:
        node.sdo.download(0x6040, 0, (0x0007).to_bytes(2, "little"))
        assert sw_of(node) == 0x000F
        m = sniffer.mark()
        assert ctl("set 0x2311 0 1") == "ok"                 # solenoid 1: cable break
        f = sniffer.wait_cob(0x80 + NODE, 2.0, m)
        assert f is not None and f.data == bytes([0x11, 0x23, 0x03, 0, 0, 0, 0, 0]), f
        assert wait_sw(node, lambda s: s == 0x0003) == 0x0003   # FAULT_HOLD (H set)
        assert int.from_bytes(node.sdo.upload(0x1001, 0), "little") == 0x03
        for cw in (0x0003, 0x000B):
            node.sdo.download(0x6040, 0, cw.to_bytes(2, "little"))
        assert sw_of(node) == 0x0003                         # the cause is still there
        assert ctl("set 0x2311 0 0") == "ok"                 # repaired
        time.sleep(0.05)
        m = sniffer.mark()
        for cw in (0x0003, 0x000B):
            node.sdo.download(0x6040, 0, cw.to_bytes(2, "little"))
        assert sw_of(node) == 0x000B                         # TR_11: HOLD
        f = sniffer.wait_cob(0x80 + NODE, 2.0, m)
        assert f is not None and f.data == bytes(8), f
        assert ctl("set 0x2311 0 7").startswith("error 0x06090030")
    finally:
        ctl.close()
