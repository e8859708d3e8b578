"""Simulated CANopen devices for tests of CANopen masters.

`SimulatedDevice` runs one `canopen-device` process (any built-in device, or
any EDS/DCF file) on a SocketCAN interface, waits for its boot-up, talks to
its control interface and stops it cleanly. The pytest plugin
(`pytest_canopen_device.plugin`, registered by the package) makes it a
fixture: `simulated_device`.
"""
from __future__ import annotations

import os
import shutil
import signal
import socket
import subprocess
import tempfile
import time
from pathlib import Path

import can

__all__ = ["SimulatedDevice", "DeviceError", "find_daemon"]
__version__ = "0.1.0"


class DeviceError(RuntimeError):
    """The daemon did not start, did not boot or did not stop cleanly."""


def find_daemon(explicit: str | os.PathLike | None = None) -> Path:
    """The canopen-device program: `explicit`, else $CANOPEN_DEVICE, else PATH."""
    for cand in (explicit, os.environ.get("CANOPEN_DEVICE"), shutil.which("canopen-device")):
        if cand and Path(cand).is_file() and os.access(cand, os.X_OK):
            return Path(cand)
    raise DeviceError("canopen-device not found: pass --canopen-device PATH, set "
                      "CANOPEN_DEVICE or put it on PATH")


class SimulatedDevice:
    """One simulated node (one canopen-device process).

    device: a built-in device name (`canopen-device --list-devices`) or the
    path of an EDS/DCF file (the daemon builds its dictionary at start-up).
    """

    def __init__(self, device: str | os.PathLike = "generic-301", node_id: int = 1, *,
                 interface: str = "vcan0", daemon: str | os.PathLike | None = None,
                 storage: str | os.PathLike | None = None, control: bool = True,
                 extra_args: tuple[str, ...] = (), workdir: str | os.PathLike | None = None):
        self.device = str(device)
        self.node_id = int(node_id)
        self.interface = interface
        self.daemon = find_daemon(daemon)
        self.storage = storage
        self.extra_args = tuple(extra_args)
        self._own_dir = workdir is None
        self.workdir = Path(workdir) if workdir else Path(tempfile.mkdtemp(prefix="codev-"))
        self.log_path = self.workdir / f"node{self.node_id}.log"
        self.control_path = None
        self._sock_dir: Path | None = None
        if control and self.has_control(self.daemon):
            self.control_path = self.workdir / f"node{self.node_id}.sock"
            if len(os.fsencode(self.control_path)) > 100:
                # a Unix socket path has room for about 100 bytes (sun_path);
                # pytest's tmp_path can be longer: a short directory of its own
                self._sock_dir = Path(tempfile.mkdtemp(prefix="codev-"))
                self.control_path = self._sock_dir / f"node{self.node_id}.sock"
        self.proc: subprocess.Popen | None = None
        self.returncode: int | None = None
        self._log = None
        self._ctl: socket.socket | None = None
        self._ctl_buf = b""

    # ------------------------------------------------------------ helpers
    @staticmethod
    def has_control(daemon: Path) -> bool:
        """Whether this build of the daemon has the control interface (--control)."""
        out = subprocess.run([str(daemon), "--help"], capture_output=True, text=True).stdout
        return "--control" in out

    @property
    def is_eds(self) -> bool:
        return self.device.lower().endswith((".eds", ".dcf"))

    @property
    def eds(self) -> Path:
        """The device's EDS (for the master's object dictionary)."""
        if self.is_eds:
            return Path(self.device)
        path = self.workdir / f"{Path(self.device).name}.eds"
        if not path.exists():
            subprocess.run([str(self.daemon), "--device", self.device, "--export-eds",
                            str(path)], check=True, capture_output=True)
        return path

    def args(self) -> list[str]:
        a = [str(self.daemon), "--iface", self.interface, "--node-id", str(self.node_id),
             "--eds" if self.is_eds else "--device", self.device]
        if self.storage is not None:
            a += ["--storage", str(self.storage)]
        if self.control_path is not None:
            a += ["--control", str(self.control_path)]
        return a + list(self.extra_args)

    def stderr(self) -> str:
        return self.log_path.read_text() if self.log_path.exists() else ""

    # ------------------------------------------------------------ life cycle
    def start(self, timeout: float = 20.0) -> "SimulatedDevice":
        """Start the process and wait for the node's boot-up frame."""
        bus = can.Bus(interface="socketcan", channel=self.interface)
        try:
            self._log = open(self.log_path, "w")
            self.proc = subprocess.Popen(self.args(), stdout=subprocess.DEVNULL,
                                         stderr=self._log)
            end = time.monotonic() + timeout
            while time.monotonic() < end:
                m = bus.recv(0.1)
                if (m is not None and m.arbitration_id == 0x700 + self.node_id
                        and bytes(m.data) == b"\x00"):
                    return self
                if self.proc.poll() is not None:
                    raise DeviceError(f"{self.args()}: exit {self.proc.returncode}: "
                                      f"{self.stderr().strip()}")
            raise DeviceError(f"node {self.node_id}: no boot-up within {timeout} s\n"
                              f"{self.stderr()}")
        except BaseException:
            self.stop(check=False)
            raise
        finally:
            bus.shutdown()

    def wait_boot(self, timeout: float = 5.0) -> bool:
        """Wait for the next boot-up of the node (after an NMT reset)."""
        bus = can.Bus(interface="socketcan", channel=self.interface)
        try:
            end = time.monotonic() + timeout
            while time.monotonic() < end:
                m = bus.recv(0.1)
                if (m is not None and m.arbitration_id == 0x700 + self.node_id
                        and bytes(m.data) == b"\x00"):
                    return True
            return False
        finally:
            bus.shutdown()

    @property
    def running(self) -> bool:
        return self.proc is not None and self.proc.poll() is None

    def stop(self, timeout: float = 10.0, check: bool = True) -> int | None:
        """SIGTERM and wait; with check, a non-zero exit status raises."""
        if self._ctl is not None:
            self._ctl.close()
            self._ctl = None
        if self.proc is not None:
            if self.proc.poll() is None:
                self.proc.send_signal(signal.SIGTERM)
            try:
                self.returncode = self.proc.wait(timeout)
            except subprocess.TimeoutExpired:
                self.proc.kill()
                self.returncode = self.proc.wait()
                if check:
                    raise DeviceError(f"node {self.node_id}: did not stop on SIGTERM")
            self.proc = None
        if self._log is not None:
            self._log.close()
            self._log = None
        if self._sock_dir is not None:
            shutil.rmtree(self._sock_dir, ignore_errors=True)
            self._sock_dir = None
        if check and self.returncode not in (None, 0):
            raise DeviceError(f"node {self.node_id}: exit status {self.returncode}\n"
                              f"{self.stderr()}")
        return self.returncode

    def kill(self) -> None:
        """Drop off the bus at once (SIGKILL): the master sees the heartbeat stop."""
        if self.proc is not None and self.proc.poll() is None:
            self.proc.kill()
            self.returncode = self.proc.wait()

    def __enter__(self) -> "SimulatedDevice":
        return self.start()

    def __exit__(self, *exc) -> None:
        self.stop(check=exc[0] is None)

    # ------------------------------------------------------------ control interface
    def control(self, line: str, timeout: float = 5.0) -> str:
        """Send one command line to the daemon's control interface and return
        its answer line ('ok ...' or 'error ...')."""
        if self.control_path is None:
            raise DeviceError("this canopen-device has no control interface (--control)")
        if self._ctl is None:
            end = time.monotonic() + timeout
            while True:
                try:
                    s = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
                    s.connect(str(self.control_path))
                    break
                except OSError:
                    s.close()
                    if time.monotonic() > end:
                        raise
                    time.sleep(0.05)
            s.settimeout(timeout)
            self._ctl = s
        self._ctl.sendall(line.encode() + b"\n")
        while b"\n" not in self._ctl_buf:
            chunk = self._ctl.recv(4096)
            if not chunk:
                raise DeviceError("control interface closed the connection")
            self._ctl_buf += chunk
        answer, self._ctl_buf = self._ctl_buf.split(b"\n", 1)
        return answer.decode()

    def set(self, index: int, sub: int, value: int) -> None:
        """Set a value as the device's world would: an input or a fault of its
        simulated plant (a CiA 401 input `set(0x6000, 1, 0x55)`, a CiA 408
        solenoid cable break `set(0x2311, 0, 1)`), else an application write
        of the object."""
        answer = self.control(f"@{self.node_id} set 0x{index:04X} {sub} {value}")
        if answer != "ok":
            raise DeviceError(f"set 0x{index:04X} sub {sub} = {value}: {answer}")

    def get(self, index: int, sub: int) -> int:
        answer = self.control(f"@{self.node_id} get 0x{index:04X} {sub}")
        if not answer.startswith("ok "):
            raise DeviceError(f"get 0x{index:04X} sub {sub}: {answer}")
        return int(answer.split()[1], 0)

    def _ok(self, line: str) -> None:
        answer = self.control(f"@{self.node_id} {line}")
        if answer != "ok":
            raise DeviceError(f"{line}: {answer}")

    # ------------------------------------------------------------ fault injection
    def emcy(self, code: int, register: int = 0, data: bytes | None = None) -> None:
        """Raise error `code`: the device sends its EMCY (error register
        0x1001 = `register` bits + generic; `data`: the 5 manufacturer bytes)
        and keeps it active (0x1001, 0x1003) until clear_emcy(code)."""
        line = f"emcy 0x{code:04X}"
        if register or data is not None:
            line += f" 0x{register:02X}"
        if data is not None:
            if len(data) != 5:
                raise ValueError("EMCY manufacturer data: 5 bytes")
            line += "".join(f" 0x{b:02X}" for b in data)
        self._ok(line)

    def clear_emcy(self, code: int) -> None:
        """Clear error `code` (the EMCY 0x0000 follows when it was the last)."""
        self._ok(f"emcy clear 0x{code:04X}")

    def stop_heartbeat(self, settle: float = 0.1) -> None:
        """The node stops producing heartbeats but stays alive (SDO, PDO, EMCY
        go on; 0x1017 unchanged), so the master's heartbeat consumer times
        out. Returns `settle` seconds later, once a heartbeat that was already
        on its way has arrived."""
        self._ok("heartbeat stop")
        time.sleep(settle)

    def resume_heartbeat(self) -> None:
        """Heartbeats again: the first at once, then every 0x1017 ms."""
        self._ok("heartbeat resume")

    def off_bus(self, ms: int, wait: bool = False) -> None:
        """Drop off the bus for `ms` milliseconds as at bus-off: no frame in
        or out, then back by itself with EMCY 0x8140 ("recovered from
        bus-off") and its EMCY 0x0000 (docs/linux.md). With `wait`, returns
        once the time is over."""
        self._ok(f"offbus {int(ms)}")
        if wait:
            time.sleep(ms / 1000.0)

    def __repr__(self) -> str:
        return f"SimulatedDevice({self.device!r}, node_id={self.node_id}, {self.interface})"
