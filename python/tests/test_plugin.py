"""The fixtures of pytest_canopen_device against the real daemon on vcan:
boot-up seen before the test body runs, a built-in device and an EDS file,
a bad EDS reported with the daemon's line, a device dropped off the bus,
the control interface and its fault injection (EMCY raised and cleared,
heartbeats stopped and resumed, off the bus for a while, a simulated input
set), a clean stop (exit 0), and the README's example."""
from __future__ import annotations

import re
import subprocess
import time
from pathlib import Path

import can
import canopen
import pytest

from pytest_canopen_device import DeviceError, SimulatedDevice

README = Path(__file__).resolve().parents[1] / "README.md"


@pytest.fixture
def network(can_interface):
    net = canopen.Network()
    net.connect(interface="socketcan", channel=can_interface)
    yield net
    net.disconnect()


def test_builtin_device_is_booted_and_answers(simulated_device, network):
    dev = simulated_device("generic-301", node_id=5)
    assert dev.running
    node = network.add_node(5, str(dev.eds))
    assert node.sdo.upload(0x1000, 0) == (0).to_bytes(4, "little")
    assert node.sdo.upload(0x1018, 2) == (0x301).to_bytes(4, "little")


def test_eds_file_device(simulated_device, network, canopen_device_path, tmp_path):
    eds = tmp_path / "drive.eds"
    subprocess.run([str(canopen_device_path), "--device", "cia402", "--export-eds", str(eds)],
                   check=True)
    eds.write_text(eds.read_text().replace("DefaultValue=0x00020192", "DefaultValue=0x00020193"))
    dev = simulated_device(str(eds), node_id=6)
    assert dev.eds == eds
    node = network.add_node(6, str(eds))
    assert node.sdo.upload(0x1000, 0) == (0x00020193).to_bytes(4, "little")


def test_stop_is_clean_and_reported(canopen_device_path, can_interface, tmp_path):
    dev = SimulatedDevice("generic-301", 7, interface=can_interface,
                          daemon=canopen_device_path, workdir=tmp_path).start()
    assert dev.stop() == 0
    assert not dev.running


def test_bad_eds_is_a_clear_error(canopen_device_path, can_interface, tmp_path):
    bad = tmp_path / "bad.eds"
    bad.write_text("[1000]\nDataType=0x0007\nAccessType=xx\n")
    dev = SimulatedDevice(str(bad), 8, interface=can_interface, daemon=canopen_device_path,
                          workdir=tmp_path)
    with pytest.raises(DeviceError, match=re.escape("bad.eds:3: [1000] AccessType: unknown "
                                                    "access type 'xx'")):
        dev.start()
    assert dev.returncode == 2


def test_kill_drops_the_device_off_the_bus(simulated_device, network, can_interface):
    dev = simulated_device("generic-301", node_id=9)
    network.add_node(9, str(dev.eds)).sdo.download(0x1017, 0, (20).to_bytes(2, "little"))
    bus = can.Bus(interface="socketcan", channel=can_interface)
    try:
        assert any(m is not None and m.arbitration_id == 0x709
                   for m in (bus.recv(0.5) for _ in range(10))), "heartbeats"
        dev.kill()
        while bus.recv(0.0) is not None:   # what was on the way before the kill
            pass
        end = time.monotonic() + 0.3
        while time.monotonic() < end:
            m = bus.recv(0.05)
            assert m is None or m.arbitration_id != 0x709, "a heartbeat after the kill"
    finally:
        bus.shutdown()


def test_control_interface(simulated_device, canopen_device_path, network):
    if not SimulatedDevice.has_control(canopen_device_path):
        pytest.skip("this canopen-device has no --control")
    dev = simulated_device("generic-301", node_id=10)
    node = network.add_node(10, str(dev.eds))
    dev.set(0x1017, 0, 150)                          # planted by the device's world
    assert node.sdo.upload(0x1017, 0) == (150).to_bytes(2, "little")
    node.sdo.download(0x1017, 0, (250).to_bytes(2, "little"))
    assert dev.get(0x1017, 0) == 250
    assert dev.control("help").startswith("ok")


def frames(bus, seconds: float) -> list[tuple[int, bytes]]:
    out, end = [], time.monotonic() + seconds
    while time.monotonic() < end:
        m = bus.recv(0.02)
        if m is not None and not m.is_error_frame:
            out.append((m.arbitration_id, bytes(m.data)))
    return out


def test_fault_injection_emcy_and_heartbeat(simulated_device, network, can_interface):
    dev = simulated_device("generic-301", node_id=11)
    node = network.add_node(11, str(dev.eds))
    node.sdo.download(0x1017, 0, (50).to_bytes(2, "little"))
    bus = can.Bus(interface="socketcan", channel=can_interface)
    try:
        dev.emcy(0x4210, register=0x08, data=b"\x01\x02\x03\x04\x05")
        assert (0x8B, bytes([0x10, 0x42, 0x09, 1, 2, 3, 4, 5])) in frames(bus, 0.3)
        assert node.sdo.upload(0x1001, 0) == b"\x09"
        dev.clear_emcy(0x4210)
        assert (0x8B, bytes(8)) in frames(bus, 0.3)
        with pytest.raises(DeviceError, match="not active"):
            dev.clear_emcy(0x4210)
        dev.stop_heartbeat()
        with pytest.raises(canopen.nmt.NmtError):        # the master's wait times out
            node.nmt.wait_for_heartbeat(0.3)
        assert node.sdo.upload(0x1017, 0) == (50).to_bytes(2, "little")   # still alive
        dev.resume_heartbeat()
        assert node.nmt.wait_for_heartbeat(1.0) == "PRE-OPERATIONAL"
    finally:
        bus.shutdown()


def test_fault_injection_off_bus_and_inputs(simulated_device, network, can_interface):
    dev = simulated_device("cia401", node_id=12)
    node = network.add_node(12, str(dev.eds))
    bus = can.Bus(interface="socketcan", channel=can_interface)
    try:
        dev.set(0x6000, 1, 0x5A)                         # a simulated input
        assert node.sdo.upload(0x6000, 1) == b"\x5A"
        while bus.recv(0.0) is not None:                 # what came before
            pass
        dev.off_bus(400)
        got = frames(bus, 0.2)
        assert not [f for f in got if f[0] & 0x7F == 12], got       # silent
        got = frames(bus, 1.0)
        emcys = [d for cob, d in got if cob == 0x8C]
        assert emcys[:2] == [bytes([0x40, 0x81, 0x11, 0, 0, 0, 0, 0]), bytes(8)], got
        assert node.sdo.upload(0x1018, 1) is not None    # answered again
    finally:
        bus.shutdown()


def test_readme_example_passes(pytester):
    code = re.search(r"```python\n(.*?)```", README.read_text(), re.S).group(1)
    pytester.makepyfile(test_readme=code)
    r = pytester.runpytest_subprocess("-q")   # the plugin comes from its entry point
    r.assert_outcomes(passed=1)
