"""A hostile bus (issue 19): a flood of foreign frames, a TX path that stays
blocked, SDO clients hammering the node, and a parameter save while the bus
is served.

Timing allowances are stated at each check, with the reason. The suite runs
the ASan build of the daemon, usually in a VM without KVM (QEMU TCG) on a
shared 2-core machine: the allowances cover scheduling delays of that
set-up, not a slower stack; each is far below what the fault they guard
against produces (a heartbeat skipped or 35 minutes late, a loop turning at
100 % CPU). On an emulated CPU the period bounds are skipped, visibly (the
guest is descheduled by the host for up to ~0.45 s, flood or not); what
does not depend on the host's scheduling is checked everywhere: the loop
does not spin, supervision timers run while nothing can be sent, the node
recovers, every SDO answer is right, every save is confirmed and lasts.
"""
from __future__ import annotations

import os
import re
import shutil
import subprocess
import threading
import time

import can
import pytest

from conftest import BOOT_TIMEOUT, IFACE, NODE_ID, SDO_TIMEOUT, u16, u32

# Timing under load needs a CPU that is not emulated: in the VM without KVM
# (QEMU TCG) on the shared host the guest is descheduled for up to 0.45 s,
# flood or not (measured: 10-50 % of a 20 ms heartbeat's beats lost with no
# flood at all). There the period bounds are skipped, visibly, after every
# other check of the test ran (no spin, no starved timer, supervision,
# recovery, answers); the periods are also shown frame by frame in the unit
# tests (test_hostile; test_store: heartbeats during an asynchronous save).
try:
    # model name "QEMU Virtual CPU ..." / "QEMU TCG CPU ..." (with KVM: the host's)
    with open("/proc/cpuinfo") as f:
        EMULATED_CPU = any(line.startswith("model name") and "QEMU" in line for line in f)
except OSError:
    EMULATED_CPU = False
TIMING_SKIP = ("the period bound (90 % of the frames due) needs a CPU that is not emulated "
               "(QEMU TCG guest descheduled up to 0.45 s); the other checks ran")

HB = 0x700 + NODE_ID
EMCY = 0x80 + NODE_ID
TPDO1 = 0x180 + NODE_ID
SYNC = 0x080
SAVE = u32(0x65766173)


class Watch:
    """A raw socket that receives only the given COB-IDs (kernel filters),
    so that a flood does not overrun it: frames with kernel time stamps."""

    def __init__(self, cobs):
        self.bus = can.Bus(interface="socketcan", channel=IFACE,
                           can_filters=[{"can_id": c, "can_mask": 0x7FF, "extended": False}
                                        for c in cobs])
        self.frames = []
        self.running = True
        self.thread = threading.Thread(target=self._run, daemon=True)
        self.thread.start()

    def _run(self):
        while self.running:
            try:
                m = self.bus.recv(0.05)
            except can.CanOperationError:
                time.sleep(0.01)   # the interface is down for a while
                continue
            if m is not None and not m.is_error_frame:
                self.frames.append((m.timestamp, m.arbitration_id, bytes(m.data)))

    def times(self, cob, since=0.0):
        return [t for t, c, _ in list(self.frames) if c == cob and t >= since]

    def close(self):
        self.running = False
        self.thread.join()
        self.bus.shutdown()


def intervals(ts):
    return [b - a for a, b in zip(ts, ts[1:])]


def flood(seconds: float):
    """Foreign frames at the full rate of a 1 Mbit/s bus for `seconds`:
    another node's TPDO (0x186, rejected by the node's quick filter) and a
    COB-ID that passes the filter but is no service of node 5 (0x485, TPDO4
    is not valid), each a burst of 4 frames every millisecond: 8000 frames/s,
    what a 1 Mbit/s bus carries at 100 % load (8-byte frames, ~125 us).

    Why not cangen -g 0 -i (as fast as vcan takes them): vcan has no
    arbitration, its queue is a FIFO that a flooder ignoring ENOBUFS keeps
    full, so the node's own frames wait for a free slot however fast the
    node is (measured: heartbeats up to 1.1 s late, the node's loop idle);
    on a real bus the flood could not exceed the bit rate and the CAN-ID
    would order the frames. The flooders stand for other devices on the bus:
    they get the CPU after the daemon (nice 19), as they would not share it
    on a real bus."""
    procs = [subprocess.Popen(["nice", "-n", "19", "cangen", IFACE, "-g", "1", "-c", "4", "-i",
                               "-I", cob, "-L", "8", "-D", "r"],
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
             for cob in ("186", "485")]
    time.sleep(seconds)
    for p in procs:
        p.terminate()
    for p in procs:
        p.wait(5)


@pytest.mark.skipif(shutil.which("cangen") is None, reason="cangen (can-utils) missing")
def test_foreign_flood_delays_no_heartbeat_and_no_sync_tpdo(node, sniffer):
    """Heartbeat 100 ms, SYNC produced by the node every 50 ms with TPDO1 on
    every SYNC; 3 s of foreign frames at full rate."""
    node.sdo.download(0x1017, 0, u16(100))
    node.sdo.download(0x1800, 1, u32(0x80000000 | TPDO1))
    node.sdo.download(0x1800, 2, b"\x01")                 # synchronous, every SYNC
    node.sdo.download(0x1800, 1, u32(TPDO1))
    node.sdo.download(0x1006, 0, u32(50000))              # 50 ms
    node.sdo.download(0x1005, 0, u32(0x40000000 | SYNC))  # this node produces SYNC
    node.nmt.state = "OPERATIONAL"
    sniffer.running = False   # the fixture's unfiltered socket is not for a flood
    w = Watch([HB, SYNC, TPDO1])
    try:
        time.sleep(0.5)
        t0 = time.time()
        flood(3.0)
        t1 = time.time()
        time.sleep(0.3)
    finally:
        w.close()
    hb = [t for t in w.times(HB) if t0 <= t <= t1]
    sy = [t for t in w.times(SYNC) if t0 <= t <= t1]
    tp = [t for t in w.times(TPDO1) if t0 <= t <= t1]
    # Due in the window: one heartbeat per 100 ms, one SYNC (and its TPDO1)
    # per 50 ms. The check is that the flood starves no timer: at least 90 %
    # of them go out (a timer starved by the flood loses them all; the core
    # never catches a late one up). The allowance is for the VM without KVM
    # on a shared host, whose guest is descheduled for up to ~0.45 s with or
    # without a flood (measured; a beat later than its period is lost); the
    # exact periods are checked frame by frame in the unit tests.
    due_hb = (t1 - t0) / 0.100
    due_sy = (t1 - t0) / 0.050
    print(f"flood {t1 - t0:.2f} s: {len(hb)} heartbeats ({due_hb:.1f} due), {len(sy)} SYNCs "
          f"({due_sy:.1f} due), {len(tp)} TPDOs; max intervals: heartbeat "
          f"{max(intervals(hb)):.3f} s, SYNC {max(intervals(sy)):.3f} s")
    # Everywhere: no timer is starved. Allowance 1 s between two heartbeats
    # or two SYNCs (10 and 20 periods): twice the longest deschedule of the
    # emulated guest measured on the shared host (0.45 s); a timer the flood
    # starves sends nothing at all for the 3 s. Every SYNC has its TPDO.
    assert len(hb) >= 2 and max(intervals(hb)) < 1.0, f"heartbeats during the flood: {hb}"
    assert len(sy) >= 2 and max(intervals(sy)) < 1.0, f"SYNCs during the flood: {sy}"
    assert len(tp) >= len(sy) - 1, f"{len(tp)} TPDOs for {len(sy)} SYNCs"
    if EMULATED_CPU:
        pytest.skip(TIMING_SKIP)
    assert len(hb) >= 0.9 * due_hb, f"{len(hb)} heartbeats of {due_hb:.1f} due"
    assert len(sy) >= 0.9 * due_sy, f"{len(sy)} SYNCs of {due_sy:.1f} due"
    assert len(tp) >= len(sy) - 1, f"{len(tp)} TPDOs for {len(sy)} SYNCs"


def _root() -> bool:
    return os.geteuid() == 0 and shutil.which("ip") is not None


def _ip_link(state: str):
    subprocess.run(["ip", "link", "set", IFACE, state], check=True)


def _cpu_ticks(pid: int) -> int:
    fields = open(f"/proc/{pid}/stat").read().rsplit(")", 1)[1].split()
    return int(fields[11]) + int(fields[12])   # utime + stime


def _sdo_write(sniffer, index: int, sub: int, data: bytes):
    """An expedited download by raw frames (no python-canopen network: its
    receive thread would not survive the interface going down)."""
    m = sniffer.mark()
    cmd = {1: 0x2F, 2: 0x2B, 4: 0x23}[len(data)]
    sniffer.send(0x600 + NODE_ID, bytes([cmd, index & 0xFF, index >> 8, sub]) +
                 data.ljust(4, b"\x00"))
    f = sniffer.wait_cob(0x580 + NODE_ID, SDO_TIMEOUT, m)
    assert f is not None and f.data[0] == 0x60, f"download 0x{index:04X}:{sub}: {f}"


@pytest.mark.skipif(not _root(), reason="needs root to take the interface down")
def test_tx_path_down_no_spin_timers_run_and_recover(daemons, sniffer):
    """The interface goes down for 1.5 s while the node has heartbeats to
    send and a heartbeat consumer running: the daemon backs off (no loop at
    100 % CPU), the consumer's timer runs out meanwhile (EMCY 0x8130 held
    back), and everything goes out when the interface is up again. (The
    test's own sockets may lose their receive threads to ENETDOWN: after
    the interface is back a fresh filtered socket watches.)"""
    m = sniffer.mark()
    d = daemons.start("--node-id", str(NODE_ID), "--log-level", "info")
    assert sniffer.wait_cob(HB, BOOT_TIMEOUT, m, b"\x00") is not None
    _sdo_write(sniffer, 0x1017, 0, u16(50))
    _sdo_write(sniffer, 0x1016, 1, u32(0x7E << 16 | 300))  # producer 0x7E, 300 ms
    sniffer.send(0x77E, b"\x05")                          # its first heartbeat
    time.sleep(0.2)
    w = Watch([HB, EMCY, 0x580 + NODE_ID])
    try:
        ticks0 = _cpu_ticks(d.proc.pid)
        _ip_link("down")
        try:
            time.sleep(1.5)
            ticks = _cpu_ticks(d.proc.pid) - ticks0
        finally:
            _ip_link("up")
        up = time.time()
        time.sleep(1.5)
        # 0x1001 by a raw SDO upload (python-canopen's receive thread may
        # have died with the interface)
        w.bus.send(can.Message(arbitration_id=0x600 + NODE_ID, is_extended_id=False,
                               data=bytes([0x40, 0x01, 0x10, 0, 0, 0, 0, 0])))
        time.sleep(0.5)
    finally:
        w.close()
    # Allowance: 1.5 s down cost at most 0.6 s of CPU (40 %): while blocked
    # the loop retries every 1 ms (the core's retry deadline) and each round
    # of the ASan daemon in a VM without KVM costs some 100 us; a loop that
    # polls a socket SocketCAN keeps writable costs the whole 1.5 s.
    hz = os.sysconf("SC_CLK_TCK")
    assert ticks <= 0.6 * hz, f"{ticks / hz:.2f} s CPU in 1.5 s with the interface down"
    # the consumer's timer ran while the interface was down: the error
    # register shows the communication error (its EMCY 0x8130 was raised
    # while nothing could go out; it waits in the EMCY queue and goes out
    # when the path takes frames again)
    sdo = [data for _, c, data in w.frames if c == 0x580 + NODE_ID]
    assert sdo and sdo[-1][:4] == bytes([0x4F, 0x01, 0x10, 0x00]), sdo
    assert sdo[-1][4] & 0x10, f"error register {sdo[-1][4]:#x}: no communication error"
    emcy = [data for t, c, data in w.frames if c == EMCY and t >= up - 0.1]
    assert all(e[:2] == bytes([0x30, 0x81]) for e in emcy[:1]), emcy
    # heartbeats resume: the one that waited first (those due while the
    # interface was down are that one), then one every 50 ms: 30 in 1.5 s
    # (at least 90 % where timing is checked)
    beats = w.times(HB, up - 0.1)
    assert beats, "no heartbeat after the interface came back"
    sched = [t for t in beats if t >= beats[0] + 0.01]
    print(f"{len(sched)} heartbeats in 1.5 s after the interface came back (30 due)")
    if not EMULATED_CPU:
        assert beats[0] - up < 0.1, "heartbeats did not resume at once"
        assert len(sched) >= 27, f"{len(sched)} heartbeats in 1.5 s after the interface came back"
    rc = d.stop()
    assert rc == 0
    rounds = int(re.search(r"after (\d+) loop rounds", d.stderr()).group(1))
    # a spinning loop turns >1 million times a second; backed off, about
    # 1000 rounds per second blocked plus one per frame and timer
    assert rounds < 20000, f"{rounds} loop rounds"


def test_two_clients_hammering_sdo_get_correct_answers(network, eds_path, daemons, sniffer):
    """Nodes 5 and 6 in one daemon process (one loop), each hammered by its
    own SDO client thread: expedited, segmented and block transfers back to
    back (60 per client), every answer checked."""
    nodes = []
    m = sniffer.mark()
    daemons.start("--node", "5", "--node", "6:generic-301")
    for nid in (5, 6):
        assert sniffer.wait_cob(0x700 + nid, BOOT_TIMEOUT, m, b"\x00") is not None
        nd = network.add_node(nid, str(eds_path))
        nd.sdo.RESPONSE_TIMEOUT = SDO_TIMEOUT
        nodes.append(nd)
    errors = []

    def client(nd, seed):
        try:
            for k in range(10):
                v = (seed * 1000 + k) & 0xFFFFFFFF
                nd.sdo.download(0x2102, 0, u32(v))
                assert nd.sdo.upload(0x2102, 0) == u32(v)
                name = nd.sdo.upload(0x1008, 0)
                assert name == b"generic-301", name
                blob = bytes((seed + k + i) & 0xFF for i in range(40))
                with nd.sdo.open(0x2300, 0, "wb", size=len(blob), block_transfer=(k % 2 == 0)) as fp:
                    fp.write(blob)
                with nd.sdo.open(0x2300, 0, "rb", block_transfer=(k % 2 == 1)) as fp:
                    assert fp.read() == blob
        except Exception as e:  # noqa: BLE001 - reported below with the node
            errors.append(f"node {nd.id}: {e!r}")

    threads = [threading.Thread(target=client, args=(nd, nd.id)) for nd in nodes]
    for t in threads:
        t.start()
    for t in threads:
        t.join(120)
    assert not errors, errors


def test_heartbeats_keep_their_period_during_saves(network, eds_path, daemons, sniffer, tmp_path):
    """0x1010 saves while the node produces a 20 ms heartbeat: the parameter
    file is written by the port's writer thread, the loop goes on; each save
    is confirmed, and the stored value is back after a restart."""
    params = tmp_path / "node5.params"
    n = network.add_node(NODE_ID, str(eds_path))
    n.sdo.RESPONSE_TIMEOUT = SDO_TIMEOUT
    m = sniffer.mark()
    d = daemons.start("--node-id", str(NODE_ID), "--storage", str(params))
    assert sniffer.wait_cob(HB, BOOT_TIMEOUT, m, b"\x00") is not None
    n.sdo.download(0x1017, 0, u16(20))
    time.sleep(0.3)
    t0 = time.time()
    for k in range(10):
        n.sdo.download(0x2102, 0, u32(0x1000 + k))
        n.sdo.download(0x1010, 1, SAVE)
    t1 = time.time()
    time.sleep(0.1)
    beats = [f.t for f in sniffer.since(m, HB) if t0 <= f.t <= t1]
    # 10 saves: the file has the node's size (two banks), not 64 KiB
    size = params.stat().st_size
    assert size < 4096, f"parameter file of {size} bytes"
    # At least 90 % of the heartbeats due while saving go out (the
    # allowance of the flood test, for the same reason: the guest is
    # descheduled by the shared host; measured max gap 25 ms on a quiet
    # host, up to 245 ms on a busy one). A loop blocked by each save's fsync
    # and rename would lose the beats of its duration in every save.
    gaps = intervals(beats)
    due = (t1 - t0) / 0.020
    print(f"{len(beats)} heartbeats during 10 saves in {t1 - t0:.2f} s ({due:.1f} due), "
          f"max gap {max(gaps) * 1000:.1f} ms")
    assert d.stop() == 0
    m = sniffer.mark()
    daemons.start("--node-id", str(NODE_ID), "--storage", str(params))
    assert sniffer.wait_cob(HB, BOOT_TIMEOUT, m, b"\x00") is not None
    assert n.sdo.upload(0x2102, 0) == u32(0x1009)
    if EMULATED_CPU:
        pytest.skip(TIMING_SKIP)
    assert len(beats) >= 0.9 * due, f"{len(beats)} heartbeats of {due:.1f} due during saves"
