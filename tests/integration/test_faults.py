"""Fault injection through the daemon's control interface (--control,
docs/linux.md), generic for every device, seen by a python-canopen master:
an EMCY raised and cleared, heartbeats stopped (the master's heartbeat wait
times out while SDO still answers) and resumed, and the node off the bus
for a while (silence, then back as after a bus-off: EMCY 0x8140 and its
EMCY 0x0000)."""
from __future__ import annotations

import time

import canopen
import pytest

from conftest import start_device
from test_io import Control

NODE = 0x1C
EMCY = 0x80 + NODE


@pytest.fixture
def dev(network, daemons, sniffer, tmp_path):
    sock = tmp_path / "ctl"
    node = start_device("generic-301", NODE, network, daemons, sniffer, tmp_path,
                        "--control", str(sock))
    ctl = Control(sock)
    yield node, ctl
    ctl.close()


def test_emcy_raised_and_cleared(dev, sniffer):
    node, ctl = dev
    m = sniffer.mark()
    assert ctl("emcy 0x5000 0x80 1 2 3 4 5") == "ok"
    f = sniffer.wait_cob(EMCY, 2.0, m)
    assert f is not None and f.data == bytes([0x00, 0x50, 0x81, 1, 2, 3, 4, 5]), f
    end = time.monotonic() + 2.0                          # python-canopen's EMCY consumer
    while not node.emcy.active and time.monotonic() < end:
        time.sleep(0.01)
    assert [(e.code, e.register, e.data) for e in node.emcy.active] == \
        [(0x5000, 0x81, bytes([1, 2, 3, 4, 5]))]
    assert int.from_bytes(node.sdo.upload(0x1001, 0), "little") == 0x81
    assert ctl("emcy clear 0x5000") == "ok"
    f = sniffer.wait(lambda f: f.id == EMCY and f.data[0:2] == b"\x00\x00", 2.0, m)
    assert f is not None and f.data == bytes(8), f
    assert int.from_bytes(node.sdo.upload(0x1001, 0), "little") == 0
    assert ctl("emcy clear 0x5000") == "error 0x5000 is not active"


def test_heartbeat_stopped_and_resumed(dev, sniffer):
    node, ctl = dev
    node.sdo.download(0x1017, 0, (50).to_bytes(2, "little"))
    node.nmt.wait_for_heartbeat(1.0)
    assert ctl("heartbeat stop") == "ok"
    time.sleep(0.1)
    m = sniffer.mark()
    with pytest.raises(canopen.nmt.NmtError):             # the master's consumer times out
        node.nmt.wait_for_heartbeat(0.3)
    assert node.sdo.upload(0x1017, 0) == (50).to_bytes(2, "little")   # alive on SDO
    assert not sniffer.since(m, 0x700 + NODE)
    assert ctl("heartbeat resume") == "ok"
    assert node.nmt.wait_for_heartbeat(1.0) == "PRE-OPERATIONAL"


def test_off_bus_and_back(dev, sniffer):
    node, ctl = dev
    node.sdo.download(0x1017, 0, (50).to_bytes(2, "little"))
    node.nmt.state = "OPERATIONAL"
    node.nmt.wait_for_heartbeat(1.0)
    assert ctl("offbus 1000") == "ok"
    m = sniffer.quiet_mark(0.1)                           # what was on the way before
    t_req = time.time()
    sniffer.send(0x600 + NODE, bytes([0x40, 0x00, 0x10, 0, 0, 0, 0, 0]))  # never seen
    time.sleep(0.2)
    assert [str(f) for f in sniffer.since(m) if f.id != 0x600 + NODE] == []   # silence
    f = sniffer.wait_cob(EMCY, 3.0, m)                    # back: 0x8140 first, then 0x0000
    assert f is not None and f.data == bytes([0x40, 0x81, 0x11, 0, 0, 0, 0, 0]), f
    assert f.t - t_req >= 0.25, f.t - t_req               # not before the time is up
    assert f is [x for x in sniffer.since(m) if x.id in (EMCY, 0x700 + NODE)][0]
    g = sniffer.wait(lambda x: x.id == EMCY and x.idx > f.idx, 2.0, f.idx)
    assert g is not None and g.data == bytes(8), g
    # generic-301 has no 0x1029 (error behaviour): it stays Operational
    assert node.nmt.wait_for_heartbeat(1.0) == "OPERATIONAL"
    assert not sniffer.since(m, 0x580 + NODE)             # the request was lost
    assert node.sdo.upload(0x1000, 0) == bytes(4)          # answered again
