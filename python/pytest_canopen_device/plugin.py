"""pytest plugin: simulated CANopen devices as fixtures.

Options (or environment):
  --canopen-device PATH   the daemon ($CANOPEN_DEVICE, else canopen-device on PATH)
  --can-interface IF      the SocketCAN interface ($CANOPEN_IFACE, else vcan0)

Fixtures:
  simulated_device(device="generic-301", node_id=1, **kw) -> SimulatedDevice
      started and booted (its boot-up frame seen); every device a test
      started is stopped with SIGTERM at the end of the test, which fails if
      the daemon did not exit with status 0.
  can_interface, canopen_device_path
"""
from __future__ import annotations

import os

import pytest

from . import SimulatedDevice, find_daemon


def pytest_addoption(parser):
    g = parser.getgroup("canopen-device", "simulated CANopen devices")
    g.addoption("--canopen-device", default=None,
                help="canopen-device program (default: $CANOPEN_DEVICE, else PATH)")
    g.addoption("--can-interface", default=None,
                help="SocketCAN interface (default: $CANOPEN_IFACE, else vcan0)")


@pytest.fixture(scope="session")
def canopen_device_path(request):
    return find_daemon(request.config.getoption("--canopen-device"))


@pytest.fixture(scope="session")
def can_interface(request):
    return (request.config.getoption("--can-interface") or os.environ.get("CANOPEN_IFACE")
            or "vcan0")


@pytest.fixture
def simulated_device(canopen_device_path, can_interface, tmp_path):
    started: list[SimulatedDevice] = []

    def start(device="generic-301", node_id=1, timeout: float = 20.0, **kw) -> SimulatedDevice:
        kw.setdefault("interface", can_interface)
        kw.setdefault("daemon", canopen_device_path)
        kw.setdefault("workdir", tmp_path)
        dev = SimulatedDevice(device, node_id, **kw)
        started.append(dev)
        return dev.start(timeout)

    yield start
    problems = []
    for dev in started:
        try:
            dev.stop(check=dev.returncode is None or dev.returncode == 0)
        except Exception as e:   # report every device, then fail
            problems.append(str(e))
    if problems:
        pytest.fail("\n".join(problems), pytrace=False)
