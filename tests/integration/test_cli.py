"""The daemon's command line: usage errors, help/version/list, EDS export,
a missing or down interface, several nodes, SIGTERM/SIGINT."""
from __future__ import annotations

import signal
import subprocess
import time

import canopen
import pytest

from conftest import BOOT_TIMEOUT, SDO_TIMEOUT, DAEMON, IFACE, NODE_ID


def run(*args, timeout=10):
    return subprocess.run([str(DAEMON), *args], capture_output=True, text=True, timeout=timeout)


BAD = [
    (["--bogus"], "unknown option '--bogus'"),
    (["--node-id"], "--node-id needs a value"),
    (["--node-id", "0"], "--node-id must be 1..127"),
    (["--node-id", "128"], "--node-id must be 1..127"),
    (["--node-id", "12x"], "--node-id must be 1..127"),
    (["--device", "nosuch"], "unknown device 'nosuch'"),
    (["--log-level", "loud"], "--log-level must be"),
    (["--node", "5", "--node", "5"], "node-ID 5 given twice"),
    (["--node", "200"], "--node: node-ID must be 1..127"),
    (["--help=yes"], "--help takes no value"),
    (["stray"], "unexpected argument 'stray'"),
    (["--iface", "a-very-long-interface-name"], "--iface: bad interface name"),
    (["--storage", "/tmp/a", "--node", "7::/tmp/a"], "share the parameter file"),
    (["--device", "faulhaber-mc", "--node-id", "3"],
     "faulhaber-mc takes its node-ID only through LSS"),
    (["--node", "4:faulhaber-mc"], "faulhaber-mc takes its node-ID only through LSS"),
    (["--node", ":kollmorgen-s300-s700"], "--node: node-ID must be 1..127"),
    (["--serial", "0x100000000"], "--serial must be 0..0xFFFFFFFF"),
    (["--node", "5:generic-301::x"], "--node: serial number must be"),
]


@pytest.mark.parametrize("args,msg", BAD, ids=[" ".join(a) for a, _ in BAD])
def test_usage_error_exits_2_with_one_line(args, msg):
    r = run(*args)
    assert r.returncode == 2
    assert r.stdout == ""
    assert r.stderr.count("\n") == 1 and r.stderr.startswith("canopen-device: ")
    assert msg in r.stderr


def test_help_version_list():
    r = run("--help")
    assert r.returncode == 0 and "--export-eds PATH" in r.stdout and "--node-id N" in r.stdout
    r = run("--version")
    assert r.returncode == 0 and r.stdout.startswith("canopen-device 0.")
    r = run("--list-devices")
    assert r.returncode == 0 and r.stdout.split()[0] == "generic-301"
    lss = {ln.split()[0]: ln.split()[1] for ln in r.stdout.splitlines()}
    assert lss["generic-301"] == "LSS" and lss["cia402"] == "LSS"
    assert lss["faulhaber-mc"] == "LSS-only" and lss["ssd-630"] == "-"


def test_missing_interface_names_it_and_how_to_create_it():
    r = run("--iface", "vcan9")
    assert r.returncode == 1
    assert "vcan9" in r.stderr
    assert "ip link add dev vcan9 type vcan; ip link set up vcan9" in r.stderr


def test_interface_down():
    made = subprocess.run(["ip", "link", "add", "dev", "vcandown", "type", "vcan"],
                          capture_output=True)
    if made.returncode != 0:
        pytest.skip("cannot create a vcan interface here")
    try:
        r = run("--iface", "vcandown")
        assert r.returncode == 1
        assert "vcandown is down" in r.stderr and "ip link set up vcandown" in r.stderr
    finally:
        subprocess.run(["ip", "link", "del", "dev", "vcandown"], check=False)


def test_storage_in_a_missing_directory_exits_1():
    r = run("--storage", "/nonexistent-dir/params.bin")
    assert r.returncode == 1 and "/nonexistent-dir/params.bin" in r.stderr


def test_export_eds_loads_in_python_canopen(tmp_path):
    p = tmp_path / "g.eds"
    r = run("--export-eds", str(p))
    assert r.returncode == 0 and r.stdout == ""
    od = canopen.import_od(str(p), node_id=NODE_ID)
    assert od[0x1018][2].default == 0x301
    assert od[0x1008].default == "generic-301"
    assert od[0x1014].default == 0x80 + NODE_ID
    assert od[0x2300].data_type == 0x0F
    assert len(od) > 60
    # to stdout: the same text
    r2 = subprocess.run([str(DAEMON), "--export-eds", "-"], capture_output=True)
    assert r2.returncode == 0 and r2.stdout == p.read_bytes()
    # an unwritable place: exit 1
    r3 = run("--export-eds", "/nonexistent-dir/x.eds")
    assert r3.returncode == 1 and "/nonexistent-dir/x.eds" in r3.stderr


@pytest.mark.parametrize("sig", [signal.SIGTERM, signal.SIGINT], ids=["SIGTERM", "SIGINT"])
def test_signal_stops_cleanly_with_exit_0(daemons, sniffer, sig):
    m = sniffer.mark()
    d = daemons.start("--node-id", "12")
    assert sniffer.wait_cob(0x70C, BOOT_TIMEOUT, m, b"\x00") is not None
    t = time.monotonic()
    rc = d.stop(sig)
    assert rc == 0
    assert time.monotonic() - t < 2.0
    assert "stopped" in d.stderr()


def test_sigterm_while_busy(daemons, sniffer, network, eds_path):
    """SIGTERM in the middle of a transfer and with heartbeats running."""
    m = sniffer.mark()
    d = daemons.start("--node-id", "13")
    assert sniffer.wait_cob(0x70D, BOOT_TIMEOUT, m, b"\x00") is not None
    n = network.add_node(13, str(eds_path))
    n.sdo.RESPONSE_TIMEOUT = SDO_TIMEOUT
    n.sdo.download(0x1017, 0, (10).to_bytes(2, "little"))
    sniffer.send(0x60D, bytes([0x21, 0x00, 0x23, 0x00, 0x00, 0x10, 0, 0]))  # open a download
    assert sniffer.wait_cob(0x58D, 2.0, m) is not None
    assert d.stop() == 0


def test_log_levels(daemons, sniffer):
    m = sniffer.mark()
    quiet = daemons.start("--node-id", "14", "--log-level", "error")
    loud = daemons.start("--node-id", "15", "--log-level", "debug")
    for nid in (14, 15):
        assert sniffer.wait_cob(0x700 + nid, BOOT_TIMEOUT, m, b"\x00") is not None
    assert quiet.stop() == 0 and loud.stop() == 0
    assert quiet.stderr() == ""
    assert "info: node 15 (generic-301): up on " + IFACE in loud.stderr()
