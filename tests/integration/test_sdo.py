"""SDO server seen by python-canopen over vcan: expedited, segmented and
block transfers in both directions (the 100 kB DOMAIN included) and the
abort codes the master receives (CiA 301 7.2.4)."""
from __future__ import annotations

import os
import time

import canopen
import pytest

from conftest import NODE_ID, u16, u32

RX, TX = 0x600 + NODE_ID, 0x580 + NODE_ID


def server_frames(sniffer, mark):
    return [f for f in sniffer.since(mark, TX)]


def test_expedited_both_directions(node, sniffer):
    m = sniffer.quiet_mark()
    assert node.sdo.upload(0x1000, 0) == bytes(4)                        # device type
    assert node.sdo.upload(0x1018, 2) == u32(0x301)                      # product code
    assert node.sdo.upload(0x2002, 0) == (-1616).to_bytes(2, "little", signed=True)
    assert node.sdo.upload(0x2003, 0) == (-242424).to_bytes(3, "little", signed=True)
    for index, data in ((0x2100, b"\x5a"), (0x2101, u16(0xBEEF)), (0x2102, u32(0x12345678)),
                        (0x200B, b"\x01\x02\x03")):
        node.sdo.download(index, 0, data)
        assert node.sdo.upload(index, 0) == data
    # every answer was expedited (upload 0x4x with e=1, download 0x60)
    cmds = {f.data[0] for f in server_frames(sniffer, m)}
    assert cmds <= {0x43, 0x47, 0x4B, 0x4F, 0x60}


def test_segmented_both_directions(node, sniffer):
    m = sniffer.quiet_mark()
    assert node.sdo.upload(0x1008, 0) == b"generic-301"
    assert server_frames(sniffer, m)[0].data[0] == 0x41          # segmented, size indicated
    text = b"written in seven-byte segments!"
    m = sniffer.quiet_mark()
    node.sdo.download(0x2013, 0, text, force_segment=True)
    assert [f.data[0] & 0xE0 for f in server_frames(sniffer, m)][:2] == [0x60, 0x20]
    assert node.sdo.upload(0x2013, 0) == text
    # 64-bit values go segmented too when the master insists
    v = (0x0123456789ABCDEF).to_bytes(8, "little")
    node.sdo.download(0x2103, 0, v, force_segment=True)
    assert node.sdo.upload(0x2103, 0) == v


def test_segmented_domain_both_directions(node):
    data = os.urandom(3000)
    node.sdo.download(0x2300, 0, data, force_segment=True)
    assert node.sdo.upload(0x2300, 0) == data


def test_block_both_directions(node, sniffer):
    text = b"block transfer of a string"
    m = sniffer.quiet_mark()
    with node.sdo.open(0x2013, 0, "wb", block_transfer=True, size=len(text)) as f:
        f.write(text)
    assert server_frames(sniffer, m)[0].data[0] & 0xE0 == 0xA0     # block download
    m = sniffer.quiet_mark()
    with node.sdo.open(0x2013, 0, "rb", block_transfer=True) as f:
        assert f.read() == text
    assert server_frames(sniffer, m)[0].data[0] & 0xE0 == 0xC0     # block upload


def test_domain_100k_block_both_directions(node):
    data = os.urandom(100 * 1024)
    t = time.monotonic()
    with node.sdo.open(0x2300, 0, "wb", block_transfer=True, size=len(data)) as f:
        f.write(data)
    with node.sdo.open(0x2300, 0, "rb", block_transfer=True) as f:
        back = f.read()
    assert back == data, "100 kB DOMAIN differs after the round trip"
    assert time.monotonic() - t < 120


def test_domain_longer_than_capacity_is_refused(node):
    node.sdo.download(0x2300, 0, b"kept")
    f = node.sdo.open(0x2300, 0, "wb", size=140000)    # segmented, size indicated
    with pytest.raises(canopen.SdoAbortedError) as e:
        f.write(bytes(140000))
    assert e.value.code == 0x06070012                   # data type length too high
    with pytest.raises(canopen.SdoAbortedError):
        f.close()   # the master's closing segment: no transfer is open any more
    assert node.sdo.upload(0x2300, 0) == b"kept"                 # the old value stays


ABORTS = [
    ("upload", 0x5000, 0, None, 0x06020000),            # object does not exist
    ("upload", 0x1018, 9, None, 0x06090011),            # sub-index does not exist
    ("upload", 0x2022, 0, None, 0x06010001),            # write-only
    ("download", 0x1000, 0, u32(1), 0x06010002),        # read-only
    ("download", 0x2023, 0, u32(1), 0x06010002),        # const
    ("download", 0x2020, 0, u16(5), 0x06090032),        # below the low limit
    ("download", 0x2020, 0, u16(2000), 0x06090031),     # above the high limit
    ("download", 0x2100, 0, u16(1), 0x06070010),        # length does not match
    ("download", 0x2200, 0, u32(0xDEADBEEF), 0x06090030),  # the application vetoes
    ("download", 0x1014, 0, u32(0x20000085), 0x06090030),  # 29-bit EMCY COB-ID
]


@pytest.mark.parametrize("kind,index,sub,data,code", ABORTS,
                         ids=[f"{a[0]}-{a[1]:04X}sub{a[2]}-{a[4]:08X}" for a in ABORTS])
def test_abort_codes_seen_by_the_master(node, kind, index, sub, data, code):
    with pytest.raises(canopen.SdoAbortedError) as e:
        if kind == "upload":
            node.sdo.upload(index, sub)
        else:
            node.sdo.download(index, sub, data)
    assert e.value.code == code


def test_abort_frames_on_the_wire(node, sniffer):
    # unknown command specifier
    m = sniffer.mark()
    sniffer.send(RX, bytes([0xE0, 0x00, 0x10, 0x00, 0, 0, 0, 0]))
    f = sniffer.wait_cob(TX, 2.0, m)
    assert f.data[0] == 0x80 and f.data[4:] == u32(0x05040001)
    # a segmented download left open: the server gives up after 1 s
    m = sniffer.mark()
    sniffer.send(RX, bytes([0x21, 0x13, 0x20, 0x00, 0x20, 0, 0, 0]))
    f = sniffer.wait_cob(TX, 2.0, m)
    assert f.data == bytes([0x60, 0x13, 0x20, 0x00, 0, 0, 0, 0])
    t0 = f.t
    f = sniffer.wait_cob(TX, 3.0, f.idx + 1)
    assert f is not None and f.data == bytes([0x80, 0x13, 0x20, 0x00]) + u32(0x05040000)
    assert 0.9 <= f.t - t0 <= 1.5
