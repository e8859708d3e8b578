"""Boot-up and the NMT state machine (CiA 301 7.3.2) over vcan."""
from __future__ import annotations

import canopen
import pytest

from conftest import BOOT_TIMEOUT, SDO_TIMEOUT, NODE_ID, u16

HB = 0x700 + NODE_ID
NMT_START, NMT_STOP, NMT_PREOP, NMT_RESET_NODE, NMT_RESET_COMM = 0x01, 0x02, 0x80, 0x81, 0x82


def test_boot_up_frame_is_the_first_frame(daemons, sniffer):
    m = sniffer.mark()
    daemons.start("--node-id", "0x22")
    f = sniffer.wait(lambda f: f.id & 0x7F == 0x22, 5.0, m)
    assert f is not None, "no frame from node 0x22"
    assert (f.id, f.data, f.rtr) == (0x722, b"\x00", False)
    # pre-operational, heartbeat producer off: nothing else follows
    assert sniffer.wait(lambda f: f.id & 0x7F == 0x22 and f.id != 0x722, 0.5, m) is None


def command(node, sniffer, state: str, code: int):
    """Send an NMT command; the heartbeats must report the new state (a
    heartbeat already on its way may still show the old one) and keep it."""
    m = sniffer.mark()
    node.nmt.state = state
    f = sniffer.wait(lambda f: f.id == HB and f.data[0] == code, 1.0, m)
    assert f is not None, f"heartbeat never says 0x{code:02X}"
    for _ in range(2):
        f = sniffer.wait_cob(HB, 1.0, f.idx + 1)
        assert f is not None and f.data[0] == code


def hb_state(sniffer, timeout=2.0):
    """The state of the next heartbeat after now."""
    f = sniffer.wait_cob(HB, timeout, sniffer.mark())
    assert f is not None, "no heartbeat"
    return f.data[0]


def test_nmt_state_cycle(node, sniffer):
    node.sdo.download(0x1017, 0, u16(50))            # heartbeat every 50 ms
    assert hb_state(sniffer) == 0x7F                  # pre-operational
    m = sniffer.mark()
    command(node, sniffer, "OPERATIONAL", 0x05)
    assert sniffer.wait_cob(0x000, 1.0, m, bytes([NMT_START, NODE_ID])) is not None
    command(node, sniffer, "STOPPED", 0x04)
    # no SDO in Stopped: the request is not answered
    node.sdo.RESPONSE_TIMEOUT = 0.5
    m = sniffer.mark()
    with pytest.raises(canopen.SdoCommunicationError):
        node.sdo.upload(0x1000, 0)
    assert sniffer.since(m, 0x580 + NODE_ID) == []
    node.sdo.RESPONSE_TIMEOUT = SDO_TIMEOUT
    command(node, sniffer, "PRE-OPERATIONAL", 0x7F)
    assert node.sdo.upload(0x1000, 0) == bytes(4)
    command(node, sniffer, "OPERATIONAL", 0x05)


def test_reset_communication_restores_communication_objects(node, sniffer):
    node.sdo.download(0x1017, 0, u16(100))
    node.sdo.download(0x2020, 0, u16(500))           # an application parameter
    command(node, sniffer, "OPERATIONAL", 0x05)
    m = sniffer.mark()
    node.nmt.send_command(NMT_RESET_COMM)
    boot = sniffer.wait_cob(HB, 2.0, m, b"\x00")
    assert boot is not None, "no boot-up after reset communication"
    # communication area back to defaults: no heartbeat after the boot-up
    assert sniffer.wait(lambda f: f.id == HB, 0.4, boot.idx + 1) is None
    assert node.sdo.upload(0x1017, 0) == u16(0)
    # the application area is kept
    assert node.sdo.upload(0x2020, 0) == u16(500)


def test_reset_node_restores_everything(node, sniffer):
    node.sdo.download(0x2020, 0, u16(500))
    node.sdo.download(0x1017, 0, u16(100))
    data = bytes(range(200))
    node.sdo.download(0x2300, 0, data)               # application DOMAIN
    m = sniffer.mark()
    node.nmt.send_command(NMT_RESET_NODE)
    assert sniffer.wait_cob(HB, 2.0, m, b"\x00") is not None, "no boot-up after reset node"
    assert node.sdo.upload(0x2020, 0) == u16(100)
    assert node.sdo.upload(0x1017, 0) == u16(0)
    assert node.sdo.upload(0x2300, 0) == b""          # the application was reset too
    # and it is a working node again
    node.sdo.download(0x1017, 0, u16(50))
    command(node, sniffer, "OPERATIONAL", 0x05)


def test_broadcast_reaches_every_node(daemons, sniffer, network, eds_path):
    m = sniffer.mark()
    daemons.start("--node", "6", "--node", "7:generic-301")
    for nid in (6, 7):
        assert sniffer.wait_cob(0x700 + nid, BOOT_TIMEOUT, m, b"\x00") is not None
    nodes = [network.add_node(nid, str(eds_path)) for nid in (6, 7)]
    for n in nodes:
        n.sdo.RESPONSE_TIMEOUT = SDO_TIMEOUT
        n.sdo.download(0x1017, 0, u16(50))
    for cs, state in ((NMT_START, 0x05), (NMT_STOP, 0x04), (NMT_PREOP, 0x7F)):
        network.send_message(0x000, bytes([cs, 0]))
        m = sniffer.mark()
        for nid in (6, 7):
            f = sniffer.wait(lambda f, nid=nid: f.id == 0x700 + nid and f.data[0] == state,
                             2.0, m)
            assert f is not None, f"node {nid} not in state 0x{state:02X}"
    m = sniffer.mark()
    network.send_message(0x000, bytes([NMT_RESET_NODE, 0]))
    for nid in (6, 7):
        assert sniffer.wait_cob(0x700 + nid, 2.0, m, b"\x00") is not None
    # a command for one node leaves the other alone
    for n in nodes:
        n.sdo.download(0x1017, 0, u16(50))
    network.send_message(0x000, bytes([NMT_START, 7]))
    m = sniffer.mark()
    assert sniffer.wait(lambda f: f.id == 0x707 and f.data == b"\x05", 2.0, m) is not None
    assert sniffer.wait(lambda f: f.id == 0x706, 2.0, m).data == b"\x7f"


def test_nodes_in_one_process_see_each_other(daemons, sniffer, network, eds_path):
    """Node 9 consumes node 8's heartbeat (both in one process, separate
    sockets): when node 8 stops producing, node 9 raises EMCY 0x8130."""
    m = sniffer.mark()
    daemons.start("--node", "8", "--node", "9")
    for nid in (8, 9):
        assert sniffer.wait_cob(0x700 + nid, BOOT_TIMEOUT, m, b"\x00") is not None
    n8, n9 = (network.add_node(nid, str(eds_path)) for nid in (8, 9))
    n8.sdo.download(0x1017, 0, u16(50))
    n9.sdo.download(0x1016, 1, (8 << 16 | 200).to_bytes(4, "little"))
    m = sniffer.mark()
    assert sniffer.wait_cob(0x708, 1.0, m) is not None
    n8.sdo.download(0x1017, 0, u16(0))
    f = sniffer.wait_cob(0x89, 2.0, m)
    assert f is not None and f.data[:3] == bytes([0x30, 0x81, 0x11])
