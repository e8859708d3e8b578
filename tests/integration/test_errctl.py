"""Error control over vcan: heartbeat producer timing, heartbeat consumer
timeout EMCY, node guarding and life guarding (CiA 301 7.2.8.3.2)."""
from __future__ import annotations

import statistics
import time

from conftest import NODE_ID, u16, u32

HB = 0x700 + NODE_ID
EMCY = 0x80 + NODE_ID


def test_heartbeat_period_within_5_percent(node, sniffer):
    period = 0.5
    node.sdo.download(0x1017, 0, u16(int(period * 1000)))
    m = sniffer.mark()
    assert sniffer.wait_cob(HB, 2.0, m) is not None
    beats = []
    end = time.monotonic() + 4.0
    while len(beats) < 8 and time.monotonic() < end:
        f = sniffer.wait_cob(HB, 1.0, m)
        assert f is not None, "heartbeat missing"
        beats.append(f.t)
        m = f.idx + 1
    intervals = [b - a for a, b in zip(beats, beats[1:])]
    assert len(intervals) == 7
    for iv in intervals:
        assert abs(iv - period) <= 0.05 * period, f"interval {iv * 1000:.1f} ms"
    assert abs(statistics.mean(intervals) - period) <= 0.01 * period


def test_heartbeat_consumer_timeout_raises_emcy_8130(node, sniffer):
    producer = 0x7E
    node.sdo.download(0x1016, 1, u32(producer << 16 | 300))       # 300 ms
    # the master plays producer 0x7E for a while, then falls silent
    for _ in range(4):
        sniffer.send(0x700 + producer, b"\x05")
        time.sleep(0.1)
    m = sniffer.mark()
    last = time.monotonic()
    sniffer.send(0x700 + producer, b"\x05")
    f = sniffer.wait_cob(EMCY, 3.0, m)
    waited = time.monotonic() - last
    assert f is not None, "no EMCY"
    # code 0x8130, error register: generic + communication
    assert f.data == bytes([0x30, 0x81, 0x11, 0, 0, 0, 0, 0])
    assert 0.25 <= waited <= 1.0
    assert node.sdo.upload(0x1001, 0) == b"\x11"
    assert node.sdo.upload(0x1003, 0) == b"\x01"
    assert int.from_bytes(node.sdo.upload(0x1003, 1), "little") & 0xFFFF == 0x8130
    # the producer is back: the error ends with EMCY 0x0000
    m = sniffer.mark()
    sniffer.send(0x700 + producer, b"\x05")
    f = sniffer.wait_cob(EMCY, 2.0, m)
    assert f is not None and f.data == bytes(8)
    assert node.sdo.upload(0x1001, 0) == b"\x00"


def test_node_guarding_and_life_guarding(node, sniffer):
    # guard time 100 ms, life time factor 3: life time 300 ms
    node.sdo.download(0x100C, 0, u16(100))
    node.sdo.download(0x100D, 0, b"\x03")
    answers = []
    for _ in range(4):
        m = sniffer.mark()
        sniffer.send(HB, rtr=True, dlc=1)
        f = sniffer.wait(lambda f: f.id == HB and not f.rtr, 1.0, m)
        assert f is not None, "guarding request not answered"
        answers.append(f.data[0])
        time.sleep(0.05)
    # the state (pre-operational) with a toggling bit 7, starting at 0
    assert answers == [0x7F, 0xFF, 0x7F, 0xFF]
    node.nmt.state = "OPERATIONAL"
    time.sleep(0.05)
    m = sniffer.mark()
    sniffer.send(HB, rtr=True, dlc=1)
    f = sniffer.wait(lambda f: f.id == HB and not f.rtr, 1.0, m)
    assert f is not None and f.data[0] & 0x7F == 0x05
    # the master falls silent: after the life time, EMCY 0x8130
    m = sniffer.mark()
    quiet = time.monotonic()
    f = sniffer.wait_cob(EMCY, 3.0, m)
    assert f is not None, "no life guarding EMCY"
    assert f.data[:3] == bytes([0x30, 0x81, 0x11])
    assert time.monotonic() - quiet >= 0.2
    # guarding resumes: the error ends
    m = sniffer.mark()
    sniffer.send(HB, rtr=True, dlc=1)
    f = sniffer.wait_cob(EMCY, 2.0, m)
    assert f is not None and f.data == bytes(8)


def test_no_guarding_answer_while_heartbeat_is_produced(node, sniffer):
    node.sdo.download(0x1017, 0, u16(1000))
    time.sleep(0.05)
    m = sniffer.mark()
    sniffer.send(HB, rtr=True, dlc=1)
    # the next frame of the node is the periodic heartbeat, about a second later
    f = sniffer.wait(lambda f: f.id == HB and not f.rtr, 0.5, m)
    assert f is None
