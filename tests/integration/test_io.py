"""CiA 401 I/O modules on vcan (issue 16), python-canopen as the master and
the daemon's control interface (--control, docs/linux.md) as the outside
world: `cia401` sets its outputs by RPDO and SDO, its loopback inputs come
back by TPDO only for changes the interrupt masks let through, an input set
through the control interface sends its TPDO, and the outputs take their
error values when the master's heartbeat stops; the AnaGate Digital IO
module (`anagate-dio`) with the digest's R-PDO3 / T-PDO4 vector.
"""
from __future__ import annotations

import socket
import threading
import time

from conftest import BOOT_TIMEOUT, start_device

NODE = 14
QUIET = 0.5   # s without a frame that would be a TPDO


class Control:
    """A client of canopen-device --control PATH."""

    def __init__(self, path, timeout: float = BOOT_TIMEOUT):
        end = time.monotonic() + timeout
        while True:
            try:
                self.s = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
                self.s.settimeout(5.0)
                self.s.connect(str(path))
                break
            except OSError:
                self.s.close()
                if time.monotonic() > end:
                    raise
                time.sleep(0.05)
        self.f = self.s.makefile("r")

    def __call__(self, line: str) -> str:
        self.s.sendall((line + "\n").encode())
        return self.f.readline().strip()

    def close(self):
        self.f.close()
        self.s.close()


def start_io(device, network, daemons, sniffer, tmp_path):
    sock = tmp_path / "ctl"
    node = start_device(device, NODE, network, daemons, sniffer, tmp_path, "--control", str(sock))
    return node, Control(sock)


def operational(node, sniffer, tpdo_cob: int, first: bytes):
    m = sniffer.mark()
    node.nmt.state = "OPERATIONAL"
    assert sniffer.wait_cob(tpdo_cob, 3.0, m, first) is not None, "no first TPDO"


def expect_tpdo(sniffer, cob: int, data: bytes, mark: int):
    f = sniffer.wait_cob(cob, 3.0, mark)
    assert f is not None, f"no TPDO {cob:03X}"
    assert f.data == data, f"{f} instead of {cob:03X} {data.hex(' ').upper()}"
    return f


def test_cia401_outputs_inputs_masks_control(network, daemons, sniffer, tmp_path):
    node, ctl = start_io("cia401", network, daemons, sniffer, tmp_path)
    tpdo1 = 0x180 + NODE
    try:
        assert ctl("help").startswith("ok ")
        assert ctl("nodes") == f"ok {NODE}:cia401"
        operational(node, sniffer, tpdo1, b"\x00\x00")
        # RPDO1 (python-canopen's PDO map, read from the device): outputs 1..16
        node.rpdo.read()
        node.tpdo.read()
        rpdo = node.rpdo[1]
        assert [(v.index, v.subindex) for v in rpdo] == [(0x6200, 1), (0x6200, 2)]
        rpdo[0].raw = 0x55
        rpdo[1].raw = 0xAA
        m = sniffer.mark()
        rpdo.transmit()
        expect_tpdo(sniffer, tpdo1, b"\x55\xAA", m)
        # python-canopen's TPDO1 map received it too (the inputs 1..16)
        end = time.monotonic() + 3.0
        while node.tpdo[1][1].raw != 0xAA and time.monotonic() < end:
            time.sleep(0.02)
        assert (node.tpdo[1][0].raw, node.tpdo[1][1].raw) == (0x55, 0xAA)
        # SDO: output 9..16
        m = sniffer.mark()
        node.sdo[0x6200][2].raw = 0x0F
        expect_tpdo(sniffer, tpdo1, b"\x55\x0F", m)
        # interrupt mask any change of block 1: only inputs 1..4
        node.sdo[0x6006][1].raw = 0x0F
        m = sniffer.mark()
        rpdo[1].raw = 0x0F      # as the SDO write left it
        rpdo[0].raw = 0x50      # inputs 1 and 3 fall: an interrupt
        rpdo.transmit()
        expect_tpdo(sniffer, tpdo1, b"\x50\x0F", m)
        m = sniffer.mark()
        rpdo[0].raw = 0x00      # inputs 5 and 7 fall: masked
        rpdo.transmit()
        time.sleep(QUIET)
        assert sniffer.since(m, tpdo1) == [], "a masked change sent the TPDO"
        assert ctl("get 0x6000 1") == "ok 0"   # the input changed all the same
        m = sniffer.mark()
        rpdo[0].raw = 0x01
        rpdo.transmit()
        expect_tpdo(sniffer, tpdo1, b"\x01\x0F", m)
        # an input set from outside through the control interface
        m = sniffer.mark()
        assert ctl("set 0x6000 2 0x81") == "ok"
        expect_tpdo(sniffer, tpdo1, b"\x01\x81", m)
        assert ctl(f"@{NODE} get 0x6000 2") == "ok 129"
        assert ctl("get 0x6401 1") == "ok 0"
        assert ctl("set 0x6401 1 -5") == "ok"
        assert ctl("get 0x6401 1") == "ok -5"
        assert ctl("get 0x1018 1") == "ok 0"
        assert ctl("set 0x7777 0 1") == "error 0x06020000"
        assert ctl("set 0x6000").startswith("error usage")
        assert ctl("@99 get 0x1000 0") == "error no node 99"
    finally:
        ctl.close()


def test_cia401_error_values_when_the_heartbeat_stops(network, daemons, sniffer, tmp_path):
    node, ctl = start_io("cia401", network, daemons, sniffer, tmp_path)
    tpdo1 = 0x180 + NODE
    master = 0x7F
    beating = threading.Event()
    beating.set()

    def heartbeat():
        while beating.is_set():
            sniffer.send(0x700 + master, b"\x05")
            time.sleep(0.05)

    t = threading.Thread(target=heartbeat, daemon=True)
    try:
        node.sdo[0x6207][1].raw = 0xA5          # error value of outputs 1..8
        node.sdo[0x6206][2].raw = 0x00          # outputs 9..16 keep their value
        node.sdo[0x1016][1].raw = (master << 16) | 300   # 300 ms
        t.start()
        operational(node, sniffer, tpdo1, b"\x00\x00")
        m = sniffer.mark()
        node.sdo[0x6200][1].raw = 0x0F
        node.sdo[0x6200][2].raw = 0x3C
        assert sniffer.wait_cob(tpdo1, 3.0, m, b"\x0F\x3C") is not None
        time.sleep(0.5)
        assert ctl("get 0x6000 1") == "ok 15"
        m = sniffer.mark()
        beating.clear()
        t.join()
        emcy = sniffer.wait_cob(0x80 + NODE, 3.0, m)
        assert emcy is not None and emcy.data[:2] == b"\x30\x81", "no EMCY 0x8130"
        # the physical outputs took the error values: the loopback shows them
        expect_tpdo(sniffer, tpdo1, b"\xA5\x3C", m)
        assert ctl("get 0x6000 1") == "ok 165"
        assert node.sdo[0x6200][1].raw == 0x0F   # the object keeps the master's value
    finally:
        beating.clear()
        ctl.close()


def test_anagate_dio_rpdo3_tpdo4(network, daemons, sniffer, tmp_path):
    node, ctl = start_io("anagate-dio", network, daemons, sniffer, tmp_path)
    tpdo4 = 0x480 + NODE
    try:
        operational(node, sniffer, tpdo4, b"\x00\x00")
        # digest 4.2: outputs 1 and 16 by R-PDO3
        m = sniffer.mark()
        sniffer.send(0x400 + NODE, b"\x01\x80")
        expect_tpdo(sniffer, tpdo4, b"\x01\x80", m)
        assert node.sdo.upload(0x8001, 0) == b"\x01"
        assert node.sdo.upload(0x8001, 1) == b"\x80"
        assert node.sdo.upload(0x8000, 1) == b"\x80"
        # R-PDO4 (Tabelle 38) and an input set from outside
        m = sniffer.mark()
        sniffer.send(0x500 + NODE, b"\x02\x00")
        expect_tpdo(sniffer, tpdo4, b"\x02\x00", m)
        m = sniffer.mark()
        assert ctl("set 0x8000 1 0x40") == "ok"
        expect_tpdo(sniffer, tpdo4, b"\x02\x40", m)
        assert node.sdo.upload(0x1018, 1) == b"\x10\x00\x00\x00"
    finally:
        ctl.close()
