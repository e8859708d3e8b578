"""The fixtures of pytest_canopen_device against the real daemon on vcan:
boot-up seen before the test body runs, a built-in device and an EDS file,
a bad EDS reported with the daemon's line, a device dropped off the bus,
the control interface, a clean stop (exit 0), and the README's example."""
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


def test_readme_example_passes(pytester):
    code = re.search(r"```python\n(.*?)```", README.read_text(), re.S).group(1)
    pytester.makepyfile(test_readme=code)
    r = pytester.runpytest_subprocess("-q")   # the plugin comes from its entry point
    r.assert_outcomes(passed=1)
