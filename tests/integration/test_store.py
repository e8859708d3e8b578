"""Store and restore parameters (0x1010 / 0x1011, CiA 301 7.5.2.13-14)
with the daemon's parameter file (--storage), across process restarts.

PENDING: the core's 0x1010/0x1011 storage is being merged. tools/run-tests
leaves this file out (--ignore); remove it from PENDING there once merged.

Signatures (written as UNSIGNED32, i.e. the ASCII bytes on the wire):
"save" = 0x65766173, "load" = 0x64616F6C. Sub-index 1: all parameters,
2: communication, 3: application.
"""
from __future__ import annotations

import time

import canopen
import pytest

from conftest import BOOT_TIMEOUT, SDO_TIMEOUT, NODE_ID, u16, u32

SAVE = u32(0x65766173)
LOAD = u32(0x64616F6C)
HB = 0x700 + NODE_ID


@pytest.fixture
def storage(tmp_path):
    return tmp_path / "node5.params"


def boot(daemons, sniffer, network, eds_path, storage):
    m = sniffer.mark()
    d = daemons.start("--node-id", str(NODE_ID), "--storage", str(storage))
    assert sniffer.wait_cob(HB, BOOT_TIMEOUT, m, b"\x00") is not None, "no boot-up"
    if NODE_ID in network:
        del network[NODE_ID]
    n = network.add_node(NODE_ID, str(eds_path))
    n.sdo.RESPONSE_TIMEOUT = SDO_TIMEOUT
    n.daemon = d
    return n


def restart(node, daemons, sniffer, network, eds_path, storage):
    assert node.daemon.stop() == 0
    return boot(daemons, sniffer, network, eds_path, storage)


def test_store_capability_is_reported(daemons, sniffer, network, eds_path, storage):
    n = boot(daemons, sniffer, network, eds_path, storage)
    for sub in (1, 2, 3):
        assert int.from_bytes(n.sdo.upload(0x1010, sub), "little") & 1 == 1   # on command
        assert int.from_bytes(n.sdo.upload(0x1011, sub), "little") & 1 == 1


def test_store_restart_read_back(daemons, sniffer, network, eds_path, storage):
    n = boot(daemons, sniffer, network, eds_path, storage)
    n.sdo.download(0x2020, 0, u16(500))            # application
    n.sdo.download(0x2013, 0, b"stored text")
    n.sdo.download(0x1017, 0, u16(250))            # communication
    n.sdo.download(0x1010, 1, SAVE)
    assert storage.is_file()
    n = restart(n, daemons, sniffer, network, eds_path, storage)
    assert n.sdo.upload(0x2020, 0) == u16(500)
    assert n.sdo.upload(0x2013, 0) == b"stored text"
    assert n.sdo.upload(0x1017, 0) == u16(250)
    # the stored heartbeat time is in force from boot
    m = sniffer.mark()
    a = sniffer.wait_cob(HB, 1.0, m)
    b = sniffer.wait_cob(HB, 1.0, a.idx + 1)
    assert abs((b.t - a.t) - 0.25) < 0.0125


def test_wrong_signature_is_refused(daemons, sniffer, network, eds_path, storage):
    n = boot(daemons, sniffer, network, eds_path, storage)
    for index in (0x1010, 0x1011):
        with pytest.raises(canopen.SdoAbortedError) as e:
            n.sdo.download(index, 1, u32(0x12345678))
        assert e.value.code == 0x08000020


def test_store_communication_only(daemons, sniffer, network, eds_path, storage):
    n = boot(daemons, sniffer, network, eds_path, storage)
    n.sdo.download(0x2020, 0, u16(500))
    n.sdo.download(0x1017, 0, u16(250))
    n.sdo.download(0x1010, 2, SAVE)
    n = restart(n, daemons, sniffer, network, eds_path, storage)
    assert n.sdo.upload(0x1017, 0) == u16(250)
    assert n.sdo.upload(0x2020, 0) == u16(100)      # not stored: default


def test_store_application_only(daemons, sniffer, network, eds_path, storage):
    n = boot(daemons, sniffer, network, eds_path, storage)
    n.sdo.download(0x2020, 0, u16(500))
    n.sdo.download(0x1017, 0, u16(250))
    n.sdo.download(0x1010, 3, SAVE)
    n = restart(n, daemons, sniffer, network, eds_path, storage)
    assert n.sdo.upload(0x1017, 0) == u16(0)
    assert n.sdo.upload(0x2020, 0) == u16(500)


def test_reset_node_loads_stored_values(daemons, sniffer, network, eds_path, storage):
    n = boot(daemons, sniffer, network, eds_path, storage)
    n.sdo.download(0x2020, 0, u16(500))
    n.sdo.download(0x1010, 1, SAVE)
    n.sdo.download(0x2020, 0, u16(700))             # changed, not stored
    m = sniffer.mark()
    n.nmt.send_command(0x81)
    assert sniffer.wait_cob(HB, 2.0, m, b"\x00") is not None
    assert n.sdo.upload(0x2020, 0) == u16(500)


def test_restore_defaults(daemons, sniffer, network, eds_path, storage):
    n = boot(daemons, sniffer, network, eds_path, storage)
    n.sdo.download(0x2020, 0, u16(500))
    n.sdo.download(0x1017, 0, u16(250))
    n.sdo.download(0x1010, 1, SAVE)
    n.sdo.download(0x1011, 1, LOAD)
    # the values in use do not change until the next reset
    assert n.sdo.upload(0x2020, 0) == u16(500)
    m = sniffer.mark()
    n.nmt.send_command(0x81)                       # reset node
    assert sniffer.wait_cob(HB, 2.0, m, b"\x00") is not None
    assert n.sdo.upload(0x2020, 0) == u16(100)
    assert n.sdo.upload(0x1017, 0) == u16(0)
    # and after a restart of the process too
    n = restart(n, daemons, sniffer, network, eds_path, storage)
    assert n.sdo.upload(0x2020, 0) == u16(100)
    assert n.sdo.upload(0x1017, 0) == u16(0)


def test_restore_application_defaults_only(daemons, sniffer, network, eds_path, storage):
    n = boot(daemons, sniffer, network, eds_path, storage)
    n.sdo.download(0x2020, 0, u16(500))
    n.sdo.download(0x1017, 0, u16(250))
    n.sdo.download(0x1010, 1, SAVE)
    n.sdo.download(0x1011, 3, LOAD)
    n = restart(n, daemons, sniffer, network, eds_path, storage)
    assert n.sdo.upload(0x2020, 0) == u16(100)
    assert n.sdo.upload(0x1017, 0) == u16(250)


def test_no_storage_refuses_store(node):
    with pytest.raises(canopen.SdoAbortedError) as e:
        node.sdo.download(0x1010, 1, SAVE)
    assert e.value.code == 0x08000020


def test_parameter_file_survives_a_kill(daemons, sniffer, network, eds_path, storage):
    """The file is replaced atomically: a stored state stays readable even
    when the process is killed right after storing."""
    n = boot(daemons, sniffer, network, eds_path, storage)
    n.sdo.download(0x2020, 0, u16(321))
    n.sdo.download(0x1010, 1, SAVE)
    n.daemon.proc.kill()
    n.daemon.proc.wait()
    time.sleep(0.05)
    assert not storage.with_name(storage.name + ".tmp").exists()
    n = boot(daemons, sniffer, network, eds_path, storage)
    assert n.sdo.upload(0x2020, 0) == u16(321)
