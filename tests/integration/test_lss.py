"""LSS (CiA 305) with python-canopen's LssMaster over vcan: fastscan finds
unconfigured devices, gives them node-IDs that they store and boot with
again after a process restart; inquiry of a selected node's identity; the
FAULHABER drive commissioned the way its manual's quick start does (digest
seed-001 §1.5, §2.1/§2.2), with the manual's COB-ID rules afterwards."""
from __future__ import annotations

import time

import canopen
import canopen.lss
import pytest

from conftest import BOOT_TIMEOUT, SDO_TIMEOUT, lss_select

LSS = canopen.lss.LssMaster
NMT_RESET_COMM = 0x82


def wait_listening(daemon, timeout: float = BOOT_TIMEOUT) -> None:
    """An unconfigured node sends nothing: its log says when it listens."""
    end = time.monotonic() + timeout
    while "waiting for LSS" not in daemon.stderr():
        assert daemon.proc.poll() is None, daemon.stderr()
        assert time.monotonic() < end, f"{daemon.args}: not up\n{daemon.stderr()}"
        time.sleep(0.05)


def boot(sniffer, node_id: int, mark: int, timeout: float = BOOT_TIMEOUT):
    f = sniffer.wait_cob(0x700 + node_id, timeout, mark, b"\x00")
    assert f is not None, f"no boot-up of node {node_id}"
    return f


def sdo_u32(network, node_id: int, index: int, sub: int) -> int:
    node = network.add_node(node_id) if node_id not in network else network[node_id]
    node.sdo.RESPONSE_TIMEOUT = SDO_TIMEOUT
    return int.from_bytes(node.sdo.upload(index, sub), "little")


@pytest.fixture
def lss(network):
    m = network.lss
    m.RESPONSE_TIMEOUT = 1.0   # a bit answered by nobody costs this much in fastscan
    return m


def test_fastscan_two_unconfigured_store_and_restart(lss, network, daemons, sniffer,
                                                      tmp_path):
    args = [["--device", "generic-301", "--serial", "0x101",
             "--storage", str(tmp_path / "a.params")],
            ["--device", "generic-301", "--serial", "0x102",
             "--storage", str(tmp_path / "b.params")]]
    procs = [daemons.start(*a) for a in args]
    for p in procs:
        wait_listening(p)
    m0 = sniffer.mark()
    found = []
    for node_id in (10, 11):
        ok, address = lss.fast_scan()
        assert ok, "fastscan found no unconfigured node"
        assert address[:3] == [0x0, 0x301, 0x00010000]
        found.append(address[3])
        assert lss.inquire_node_id() == 0xFF
        lss.configure_node_id(node_id)
        lss.store_configuration()
        m = sniffer.mark()
        lss.send_switch_state_global(LSS.WAITING_STATE)
        boot(sniffer, node_id, m)
    assert found == [0x101, 0x102]          # the smaller LSS address first
    assert lss.fast_scan() == (False, None)  # nobody unconfigured left
    assert not [f for f in sniffer.since(m0) if 0x700 < f.id < 0x780 and f.id not in (0x70A, 0x70B)]
    assert sdo_u32(network, 10, 0x1018, 4) == 0x101
    assert sdo_u32(network, 11, 0x1018, 4) == 0x102
    # a restart of the processes: the stored node-IDs
    for p in procs:
        assert p.stop() == 0
    m = sniffer.mark()
    procs = [daemons.start(*a) for a in args]
    boot(sniffer, 10, m)
    boot(sniffer, 11, m)
    assert sdo_u32(network, 10, 0x1018, 4) == 0x101
    assert sdo_u32(network, 11, 0x1018, 4) == 0x102
    assert "waiting for LSS" not in procs[0].stderr()


def test_inquire_identity_of_a_selected_node(lss, network, daemons, sniffer):
    m = sniffer.mark()
    daemons.start("--node-id", "12", "--serial", "0x4242")
    daemons.start("--node-id", "13", "--serial", "0x4343")
    boot(sniffer, 12, m)
    boot(sniffer, 13, m)
    assert lss.send_switch_state_selective(0x0, 0x301, 0x00010000, 0x4343)
    assert lss.inquire_lss_address(canopen.lss.CS_INQUIRE_VENDOR_ID) == 0x0
    assert lss.inquire_lss_address(canopen.lss.CS_INQUIRE_PRODUCT_CODE) == 0x301
    assert lss.inquire_lss_address(canopen.lss.CS_INQUIRE_REVISION_NUMBER) == 0x00010000
    assert lss.inquire_lss_address(canopen.lss.CS_INQUIRE_SERIAL_NUMBER) == 0x4343
    assert lss.inquire_node_id() == 13
    lss.send_switch_state_global(LSS.WAITING_STATE)
    # a wrong serial selects nobody
    with pytest.raises(canopen.lss.LssError):
        lss.send_switch_state_selective(0x0, 0x301, 0x00010000, 0x4444)
    # in waiting, inquiries go unanswered
    with pytest.raises(canopen.lss.LssError):
        lss.inquire_node_id()


def test_faulhaber_quick_start_and_cob_id_rules(lss, network, daemons, sniffer, tmp_path):
    vendor, product, serial = 0x147, 0xC4E, 0xF00
    args = ["--device", "faulhaber-mc", "--serial", str(serial),
            "--storage", str(tmp_path / "mc.params")]
    d = daemons.start(*args)
    wait_listening(d)
    # factory state: unconfigured, silent; found by "identify non-configured"
    m = sniffer.mark()
    lss.send_identify_non_configured_remote_slave()
    assert sniffer.wait(lambda f: f.id == 0x7E4 and f.data[0] == 0x50, 3.0, m) is not None
    # the master's own queue gets that answer too, from its listener thread: take
    # it out, or it may land there after the next command cleared the queue and
    # be taken as that command's answer ("Response message is not for the request")
    assert lss.responses.get(True, 3.0)[0] == 0x50
    assert not [f for f in sniffer.since(m) if 0x700 < f.id < 0x780]
    # quick start: the one drive on the bus; switch global, node-ID, bit rate, store
    lss.send_switch_state_global(LSS.CONFIGURATION_STATE)
    assert lss.inquire_node_id() == 0xFF
    with pytest.raises(canopen.lss.LssError, match="LSS Error: 1"):
        lss.configure_node_id(0)             # node-ID out of range
    with pytest.raises(canopen.lss.LssError, match="LSS Error: 1"):
        lss.configure_bit_timing(5)          # 100 kbit/s: not in the drive's table
    lss.configure_node_id(3)
    lss.configure_bit_timing(3)              # 250 kbit/s
    lss.store_configuration()
    m = sniffer.mark()
    lss.send_switch_state_global(LSS.WAITING_STATE)
    boot(sniffer, 3, m)                      # answers at its new ID straight away
    assert sdo_u32(network, 3, 0x2400, 0) == 0xFF  # stored, not in force: still auto-baud
    assert sdo_u32(network, 3, 0x1014, 0) == 0x83
    assert sdo_u32(network, 3, 0x1800, 1) == 0x183
    assert sdo_u32(network, 3, 0x1400, 1) == 0x203
    # valid -> valid: selected with revision 0 (the drive ignores it); the PDO and
    # EMCY COB-IDs stay, SDO and NMT follow the new ID at reset communication
    assert lss.send_switch_state_selective(vendor, product, 0, serial)
    lss.configure_node_id(4)
    lss.store_configuration()
    lss.send_switch_state_global(LSS.WAITING_STATE)
    m = sniffer.mark()
    network.send_message(0, bytes([NMT_RESET_COMM, 3]))
    boot(sniffer, 4, m)
    assert sdo_u32(network, 4, 0x1014, 0) == 0x83
    assert sdo_u32(network, 4, 0x1800, 1) == 0x183
    assert sdo_u32(network, 4, 0x1200, 1) == 0x604
    # the same after a power cycle (process restart), with the stored bit rate
    assert d.stop() == 0
    m = sniffer.mark()
    d = daemons.start(*args)
    boot(sniffer, 4, m)
    assert sdo_u32(network, 4, 0x1800, 1) == 0x183
    assert "LSS bit timing 3 (250 kbit/s)" in d.stderr()
    assert sdo_u32(network, 4, 0x2400, 0) == 3   # "Baudrate set": the index in force
    # to 0xFF first: silent at the reset; then 5: the pre-defined connection set of 5
    lss_select(network, vendor, product, 0, serial)
    lss.configure_node_id(0xFF)
    lss.send_switch_state_global(LSS.WAITING_STATE)
    m = sniffer.mark()
    network.send_message(0, bytes([NMT_RESET_COMM, 4]))
    time.sleep(1.0)
    assert not [f for f in sniffer.since(m) if 0x700 < f.id < 0x780]
    lss.send_switch_state_global(LSS.CONFIGURATION_STATE)
    assert lss.inquire_node_id() == 0xFF
    lss.configure_node_id(5)
    m = sniffer.mark()
    lss.send_switch_state_global(LSS.WAITING_STATE)
    boot(sniffer, 5, m)
    assert sdo_u32(network, 5, 0x1014, 0) == 0x85
    assert sdo_u32(network, 5, 0x1800, 1) == 0x185
    assert sdo_u32(network, 5, 0x1400, 1) == 0x205
