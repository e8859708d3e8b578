"""Integration tests: canopen-device on a virtual CAN bus, python-canopen as
the master.

Run through tools/vcan-run (tools/run-tests does), which provides vcan0
natively or in a VM:

    tools/vcan-run -- .venv/bin/python -m pytest tests/integration

The daemon is $CODEV_BUILD_DIR/bin/canopen-device (default build/host).
Every test starts its own daemon(s) and stops them with SIGTERM, checking
the exit status 0. `sniffer` is a second raw socket on the bus that records
every frame with the kernel's timestamp, for exact frames and timing.
"""
from __future__ import annotations

import itertools
import os
import signal
import socket
import subprocess
import threading
import time
from dataclasses import dataclass
from pathlib import Path

import can
import canopen
import canopen.lss
import pytest

ROOT = Path(__file__).resolve().parents[2]
IFACE = os.environ.get("CO_IFACE", "vcan0")


def build_dir() -> Path:
    d = Path(os.environ.get("CODEV_BUILD_DIR", ROOT / "build" / "host"))
    return d if d.is_absolute() else ROOT / d


DAEMON = build_dir() / "bin" / "canopen-device"

# Generous: the suite runs the ASan build of the daemon, often in a VM
# without KVM on a loaded machine. Timing itself is checked by tests of
# their own (heartbeat period), not by these limits.
BOOT_TIMEOUT = 20.0   # process start to boot-up frame
SDO_TIMEOUT = 5.0     # python-canopen's wait for one SDO response


def pytest_sessionstart(session):
    if not DAEMON.is_file():
        pytest.exit(f"{DAEMON} is not built (cmake --build build/host)", returncode=2)
    try:
        s = socket.socket(socket.AF_CAN, socket.SOCK_RAW, socket.CAN_RAW)
        s.bind((IFACE,))
        s.close()
    except OSError as e:
        pytest.exit(f"no CAN interface {IFACE} ({e}): run the suite through tools/vcan-run",
                    returncode=2)


# ------------------------------------------------------------------ frames

@dataclass
class Frame:
    t: float          # kernel receive time, s
    id: int
    data: bytes
    rtr: bool = False
    idx: int = -1     # position in Sniffer.frames

    def __str__(self) -> str:
        return f"{self.id:03X} " + ("R" if self.rtr else self.data.hex(" ").upper())


class Sniffer:
    """Records every frame on the bus from a socket of its own."""

    def __init__(self):
        self.bus = can.Bus(interface="socketcan", channel=IFACE)
        self.frames: list[Frame] = []
        self.cond = threading.Condition()
        self.running = True
        self.thread = threading.Thread(target=self._run, daemon=True)
        self.thread.start()

    def _run(self):
        while self.running:
            try:
                m = self.bus.recv(0.05)
            except can.CanOperationError:
                time.sleep(0.01)   # the interface is down for a while (test_robustness)
                continue
            if m is None or m.is_error_frame:
                continue
            with self.cond:
                self.frames.append(Frame(m.timestamp, m.arbitration_id, bytes(m.data),
                                         m.is_remote_frame, len(self.frames)))
                self.cond.notify_all()

    def mark(self) -> int:
        with self.cond:
            return len(self.frames)

    def quiet_mark(self, quiet: float = 0.1, limit: float = 2.0) -> int:
        """A mark taken once the bus has been quiet for `quiet` seconds (the
        sniffer has caught up with everything sent before)."""
        end = time.monotonic() + limit
        n = self.mark()
        while time.monotonic() < end:
            time.sleep(quiet)
            k = self.mark()
            if k == n:
                break
            n = k
        return n

    def since(self, mark: int = 0, cob: int | None = None) -> list[Frame]:
        with self.cond:
            fr = self.frames[mark:]
        return [f for f in fr if cob is None or f.id == cob]

    def wait(self, pred, timeout: float = 3.0, mark: int = 0) -> Frame | None:
        """The first frame from index `mark` on for which pred(frame) holds."""
        end = time.monotonic() + timeout
        i = mark
        with self.cond:
            while True:
                while i < len(self.frames):
                    if pred(self.frames[i]):
                        return self.frames[i]
                    i += 1
                left = end - time.monotonic()
                if left <= 0:
                    return None
                self.cond.wait(left)

    def wait_cob(self, cob: int, timeout: float = 3.0, mark: int = 0, data: bytes | None = None):
        return self.wait(lambda f: f.id == cob and (data is None or f.data == data), timeout, mark)

    def send(self, cob: int, data: bytes = b"", rtr: bool = False, dlc: int | None = None):
        self.bus.send(can.Message(arbitration_id=cob, data=data, is_extended_id=False,
                                  is_remote_frame=rtr, dlc=dlc if dlc is not None else len(data)))

    def close(self):
        self.running = False
        self.thread.join()
        self.bus.shutdown()


@pytest.fixture
def sniffer():
    s = Sniffer()
    yield s
    s.close()


# ------------------------------------------------------------------ daemon

class Daemon:
    def __init__(self, args: list[str], log: Path, stdout=subprocess.DEVNULL):
        self.args = [str(DAEMON), "--iface", IFACE, *args]
        self.log = log
        self._err = open(log, "w")
        self.proc = subprocess.Popen(self.args, stdout=stdout, stderr=self._err)

    def stop(self, sig=signal.SIGTERM, timeout: float = 10.0) -> int:
        if self.proc.poll() is None:
            self.proc.send_signal(sig)
        try:
            rc = self.proc.wait(timeout)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            rc = self.proc.wait()
        self._err.close()
        return rc

    def stderr(self) -> str:
        return self.log.read_text()


@pytest.fixture
def daemons(tmp_path):
    """Start daemons: daemons.start('--node-id', '5', ...). Stopped with
    SIGTERM at the end of the test, which must give exit status 0."""
    started: list[Daemon] = []

    class Starter:
        def start(self, *args: str, stdout=subprocess.DEVNULL) -> Daemon:
            d = Daemon(list(args), tmp_path / f"daemon{len(started)}.log", stdout)
            started.append(d)
            return d

    yield Starter()
    for d in started:
        if d.proc.poll() is None:
            rc = d.stop()
            assert rc == 0, f"{d.args}: exit {rc}\n{d.stderr()}"


@pytest.fixture(scope="session")
def eds_path(tmp_path_factory) -> Path:
    p = tmp_path_factory.mktemp("eds") / "generic-301.eds"
    subprocess.run([str(DAEMON), "--device", "generic-301", "--export-eds", str(p)], check=True)
    return p


@pytest.fixture
def network():
    net = canopen.Network()
    net.connect(interface="socketcan", channel=IFACE)
    yield net
    net.disconnect()


NODE_ID = 5

# Axes the CiA 402 devices run (their co_device_impl_t in devices/*.c; 1 when
# not listed).
# A dictionary may hold more: anagate-motion-bt2 is the 4-axis module with 2
# motors fitted.
AXES = {"anagate-motion": 4, "anagate-motion-bt2": 2, "anagate-motion-bl": 2,
        "anagate-motion-400vac": 2}


def lss_modes() -> dict[str, str]:
    """Device name -> "LSS", "LSS-only" or "-" (canopen-device --list-devices)."""
    out = subprocess.run([str(DAEMON), "--list-devices"], check=True, capture_output=True,
                         text=True).stdout
    return {ln.split()[0]: ln.split()[1] for ln in out.splitlines() if ln.strip()}


_serials = itertools.count(0x5E000)


def lss_select(network, vendor: int, product: int, revision: int, serial: int,
               timeout: float = BOOT_TIMEOUT) -> None:
    """Switch state selective to the node with that LSS address, retrying
    until its process listens (an unconfigured node sends no boot-up)."""
    end = time.monotonic() + timeout
    while True:
        try:
            if network.lss.send_switch_state_selective(vendor, product, revision, serial):
                return
        except canopen.lss.LssError:
            pass
        assert time.monotonic() < end, f"no LSS answer from serial {serial:#x}"


def start_device(device: str, node_id: int, network, daemons, sniffer, tmp_path,
                 *extra: str):
    """Export `device`'s EDS, start it as `node_id` (with the daemon options
    `extra`) and wait for its boot-up; its python-canopen RemoteNode. A
    device whose node-ID comes only through LSS (faulhaber-mc) starts
    unconfigured with a serial number of its own and gets `node_id` the way
    its manual's quick start gives it: LSS selective, configure node-ID,
    back to waiting."""
    eds = tmp_path / f"{device}.eds"
    subprocess.run([str(DAEMON), "--device", device, "--export-eds", str(eds)], check=True)
    od = canopen.import_od(str(eds), node_id=node_id)
    node = network.add_node(node_id, od)
    node.sdo.RESPONSE_TIMEOUT = SDO_TIMEOUT
    m = sniffer.mark()
    if lss_modes()[device] == "LSS-only":
        serial = next(_serials)
        daemons.start("--device", device, "--serial", str(serial), *extra)
        lss_select(network, od[0x1018][1].default, od[0x1018][2].default, 0, serial)
        network.lss.configure_node_id(node_id)
        m = sniffer.mark()
        network.lss.send_switch_state_global(network.lss.WAITING_STATE)
    else:
        daemons.start("--node-id", str(node_id), "--device", device, *extra)
    assert sniffer.wait_cob(0x700 + node_id, BOOT_TIMEOUT, m, b"\x00") is not None, "no boot-up"
    return node


@pytest.fixture
def node(network, eds_path, daemons, sniffer):
    """generic-301 as node 5 (booted: its boot-up was seen), as a
    python-canopen RemoteNode."""
    n = network.add_node(NODE_ID, str(eds_path))
    n.sdo.RESPONSE_TIMEOUT = SDO_TIMEOUT
    m = sniffer.mark()
    n.daemon = daemons.start("--node-id", str(NODE_ID))
    assert sniffer.wait_cob(0x700 + NODE_ID, BOOT_TIMEOUT, m, b"\x00") is not None, "no boot-up"
    return n


def u32(v: int) -> bytes:
    return v.to_bytes(4, "little")


def u16(v: int) -> bytes:
    return v.to_bytes(2, "little")
