#!/usr/bin/env python3
"""The main job's master: brings up simulated devices on a virtual CAN bus
and drives them with python-canopen, printing a readable transcript.

    tools/run-demo            (builds, then runs this through tools/vcan-run)
    master.py [--daemon PATH] [--iface vcan0]

Steps: boot-ups, identity over SDO, NMT states, heartbeats watched, a PDO
mapped and exchanged at SYNC, a parameter stored and read back after the
device process restarts, and a CiA 402 drive (simulated motor) enabled,
moved in profile position with its statusword, position and velocity
sampled by TPDOs at SYNC and plotted to PNG and SVG (tools/plot-trace), then
homed; next to it a CiA 401 I/O module (loopback simulation): outputs set by
RPDO come back as inputs by TPDO, an input set through the daemon's control
interface sends its TPDO, a masked input change sends none. A step that fails is reported as FAILED with its
reason and the demo goes on; the exit status is 1 when any step failed. A
step that does not end within STEP_TIMEOUT is reported as hung, with the
stack it waits in, and the demo stops there (every wait of a step has its
own time limit as well).
"""
from __future__ import annotations

import argparse
import json
import signal
import socket
import subprocess
import sys
import tempfile
import threading
import time
import traceback
from pathlib import Path

import can
import canopen
import canopen.lss

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(Path(__file__).resolve().parent))
from cia402_master import Drive, Sample, state_of, write_csv  # noqa: E402
from cia408_master import (ValveSample, rpdo, setup_closed_loop, valve_state,  # noqa: E402
                           wait_sw, write_valve_csv)

GENERIC_ID = 5
# Every step ends within this time or is reported as hung, with where it
# waits, and the demo stops there (exit status 1). Generous: the VM without
# KVM on a loaded machine; a step takes a few seconds, a plot (matplotlib)
# minutes in the VM (tools/run-demo plots on the host: --plot-later).
STEP_TIMEOUT = 300.0
PLOT_TIMEOUT = 240.0
SEND_TIMEOUT = 1.0     # a frame the socket does not take within this fails the step
DEFAULT_DEVICES = ("generic-301", "cia402", "cia408", "cia401")
T0 = time.monotonic()


def say(text: str = "") -> None:
    print(f"[{time.monotonic() - T0:7.3f}] {text}" if text else "", flush=True)


def hexs(b: bytes) -> str:
    return b.hex(" ").upper()


class Watch:
    """A raw socket that records frames; the transcript shows those asked for.
    If its socket fails, every later wait says so (instead of timing out as
    if the devices were silent)."""

    def __init__(self, iface: str):
        self.bus = can.Bus(interface="socketcan", channel=iface)
        self.frames: list[can.Message] = []
        self.lock = threading.Condition()
        self.alive = True
        self.error: Exception | None = None
        self.t = threading.Thread(target=self.run, name="watch", daemon=True)
        self.t.start()

    def run(self):
        while self.alive:
            try:
                m = self.bus.recv(0.05)
            except Exception as e:   # the socket failed: tell the waiters
                with self.lock:
                    self.error = e
                    self.lock.notify_all()
                return
            if m is not None and not m.is_error_frame:
                with self.lock:
                    self.frames.append(m)
                    self.lock.notify_all()

    def mark(self) -> int:
        with self.lock:
            return len(self.frames)

    def wait(self, pred, timeout: float, mark: int):
        end = time.monotonic() + timeout
        i = mark
        with self.lock:
            while True:
                while i < len(self.frames):
                    if pred(self.frames[i]):
                        return self.frames[i], i
                    i += 1
                if self.error is not None:
                    raise RuntimeError(f"the bus watch failed: {self.error}")
                left = end - time.monotonic()
                if left <= 0:
                    return None, i
                self.lock.wait(left)

    def since(self, mark: int, cob: int | None = None):
        with self.lock:
            return [m for m in self.frames[mark:] if cob is None or m.arbitration_id == cob]

    def send(self, cob: int, data: bytes = b""):
        self.bus.send(can.Message(arbitration_id=cob, data=data, is_extended_id=False),
                      timeout=SEND_TIMEOUT)

    def close(self):
        self.alive = False
        self.t.join(2.0)
        self.bus.shutdown()


class StepHung(Exception):
    """A step did not end within its time (Demo.step)."""


STATES = {0x00: "boot-up", 0x04: "stopped", 0x05: "operational", 0x7F: "pre-operational"}


class Demo:
    def __init__(self, daemon: Path, iface: str, out: Path, devices: list[str] | None,
                 plot_later: Path | None = None):
        self.daemon = daemon
        self.plot_later = plot_later
        self.out = out
        self.wanted = devices
        self.iface = iface
        self.tmp = Path(tempfile.mkdtemp(prefix="canopen-demo-"))
        self.procs: dict[int, subprocess.Popen] = {}
        self.results: list[tuple[str, bool, str]] = []
        self.watch = Watch(iface)
        self.net = canopen.Network()
        self.net.connect(interface="socketcan", channel=iface)
        self.eds: dict[str, Path] = {}
        self.nodes: dict[int, canopen.RemoteNode] = {}
        self.device_of: dict[int, str] = {}
        self.lss_only: set[str] = set()

    # ------------------------------------------------------------ helpers
    def step(self, title: str, fn, timeout: float = STEP_TIMEOUT) -> None:
        """Run one step in a thread of its own: a step that fails is reported
        and the demo goes on; one that does not end within `timeout` is
        reported as hung with the stack it waits in (StepHung)."""
        print(f"\n== {title} ==", flush=True)
        box: dict = {}

        def work():
            try:
                box["note"] = fn() or ""
            except BaseException as e:   # handed to the main thread
                box["error"] = e

        worker = threading.Thread(target=work, name=title, daemon=True)
        worker.start()
        worker.join(timeout)
        if worker.is_alive():
            frame = sys._current_frames().get(worker.ident)
            where = "".join(traceback.format_stack(frame)) if frame else "?\n"
            say(f"FAILED: no end after {timeout:g} s; the step waits in:")
            print(where, end="", flush=True)
            self.results.append((title, False, f"hung: no end after {timeout:g} s"))
            raise StepHung(title)
        if "error" not in box:
            self.results.append((title, True, box["note"]))
            return
        e = box["error"]
        if not isinstance(e, Exception):   # KeyboardInterrupt, SystemExit
            raise e
        # a failed step is reported, the demo goes on
        reason = f"{type(e).__name__}: {e}" if str(e) else type(e).__name__
        if isinstance(e, canopen.SdoAbortedError):
            reason = f"SDO abort 0x{e.code:08X} ({e})"
        say(f"FAILED: {reason}")
        if not isinstance(e, (canopen.SdoAbortedError, canopen.SdoCommunicationError,
                              AssertionError, TimeoutError)):
            traceback.print_exception(type(e), e, e.__traceback__, limit=3, file=sys.stdout)
        self.results.append((title, False, reason))

    def plot(self, csv_path: Path, png: Path, more: list[str]) -> None:
        """Plot a trace with tools/plot-trace, or with --plot-later leave the
        command to the caller (run-demo plots on the host: matplotlib takes
        minutes to start in a VM without KVM)."""
        argv = [str(ROOT / "tools" / "plot-trace"), str(csv_path), "-o", str(png), *more]
        rel = (lambda p: p.relative_to(ROOT) if p.is_relative_to(ROOT) else p)
        if self.plot_later is not None:
            with open(self.plot_later, "a") as f:
                f.write(json.dumps(argv) + "\n")
            say(f"trace {rel(csv_path)}, plot {rel(png)} (drawn on the host after the run)")
            return
        subprocess.run([sys.executable, *argv], check=True, timeout=PLOT_TIMEOUT)
        say(f"trace {rel(csv_path)}, plot {rel(png)}")

    def start_device(self, node_id: int, device: str, storage: bool = False) -> None:
        lss = device in self.lss_only       # its node-ID only through LSS (FAULHABER)
        args = [str(self.daemon), "--iface", self.iface, "--device", device,
                "--log-level", "error"]
        args += ["--serial", str(0x100 + node_id)] if lss else ["--node-id", str(node_id)]
        args += ["--control", str(self.tmp / f"node{node_id}.sock")]
        if storage:
            args += ["--storage", str(self.tmp / f"node{node_id}.params")]
        m = self.watch.mark()
        say("start  " + " ".join(a if a != str(self.daemon) else "canopen-device" for a in args))
        self.procs[node_id] = subprocess.Popen(args)
        if lss:
            m = self.lss_assign(node_id, device, 0x100 + node_id)
        f, _ = self.watch.wait(lambda f: f.arbitration_id == 0x700 + node_id, 5.0, m)
        if f is None or bytes(f.data) != b"\x00":
            raise TimeoutError(f"no boot-up from node {node_id}")
        say(f"<- {f.arbitration_id:03X} {hexs(f.data)}   boot-up of node {node_id} ({device})")
        if node_id in self.net:
            del self.net[node_id]
        node = self.net.add_node(node_id, str(self.eds[device]))
        node.sdo.RESPONSE_TIMEOUT = 2.0
        self.nodes[node_id] = node
        self.device_of[node_id] = device

    def lss_assign(self, node_id: int, device: str, serial: int) -> int:
        """LSS as the drive's quick start: select it by its LSS address (the
        revision is not compared), configure the node-ID, back to waiting.
        Returns the watch mark before the switch (the boot-up follows it)."""
        od = canopen.import_od(str(self.eds[device]))
        vendor, product = od[0x1018][1].default, od[0x1018][2].default
        end = time.monotonic() + 5.0
        while True:
            try:
                if self.net.lss.send_switch_state_selective(vendor, product, 0, serial):
                    break
            except canopen.lss.LssError:
                pass
            if time.monotonic() > end:
                raise TimeoutError(f"no LSS answer from {device} (serial {serial:#x})")
        self.net.lss.configure_node_id(node_id)
        say(f"-> 7E5 LSS selective {vendor:#x}/{product:#x}/-/{serial:#x}, "
            f"configure node-ID {node_id}, switch to waiting")
        m = self.watch.mark()
        self.net.lss.send_switch_state_global(self.net.lss.WAITING_STATE)
        return m

    def stop_device(self, node_id: int) -> int:
        p = self.procs.pop(node_id)
        p.send_signal(signal.SIGTERM)
        rc = p.wait(10)
        say(f"SIGTERM node {node_id}: exit {rc}")
        return rc

    def nmt(self, node_id: int, state: str) -> None:
        m = self.watch.mark()
        self.nodes[node_id].nmt.state = state
        f, _ = self.watch.wait(lambda f: f.arbitration_id == 0, 1.0, m)
        say(f"-> 000 {hexs(f.data)}   NMT {state.lower()} node {node_id}")

    def heartbeat_state(self, node_id: int, timeout: float = 2.0) -> int:
        f, _ = self.watch.wait(lambda f: f.arbitration_id == 0x700 + node_id, timeout,
                               self.watch.mark())
        if f is None:
            raise TimeoutError(f"no heartbeat from node {node_id}")
        return f.data[0]

    # ------------------------------------------------------------ steps
    def boot(self):
        for name in self.devices:
            p = self.tmp / f"{name}.eds"
            subprocess.run([str(self.daemon), "--device", name, "--export-eds", str(p)],
                           check=True, timeout=30)
            self.eds[name] = p
        say(f"EDS exported: {', '.join(sorted(self.eds))}")
        self.start_device(GENERIC_ID, "generic-301", storage=True)
        for k, name in enumerate(n for n in self.devices if n != "generic-301"):
            self.start_device(GENERIC_ID + 1 + k, name)
        return f"{len(self.nodes)} node(s) up"

    def identity(self):
        for nid, node in self.nodes.items():
            say(f"node {nid} ({self.device_of[nid]}):")
            sdo = node.sdo
            rows = [
                ("0x1000 device type", f"0x{int.from_bytes(sdo.upload(0x1000, 0), 'little'):08X}"),
            ]
            for index, what in ((0x1008, "device name"), (0x1009, "hardware version"),
                                (0x100A, "software version")):
                try:
                    rows.append((f"0x{index:04X} {what}", sdo.upload(index, 0).decode("ascii")))
                except canopen.SdoAbortedError as e:   # optional (CiA 301)
                    rows.append((f"0x{index:04X} {what}", f"- (abort 0x{e.code:08X})"))
            for sub, what in ((1, "vendor-ID"), (2, "product code"), (3, "revision"),
                              (4, "serial number")):
                v = int.from_bytes(sdo.upload(0x1018, sub), "little")
                rows.append((f"0x1018:{sub} {what}", f"0x{v:08X}"))
            for k, v in rows:
                say(f"   {k:<26} {v}")

    def nmt_and_heartbeats(self):
        nid = GENERIC_ID
        node = self.nodes[nid]
        node.sdo.download(0x1017, 0, (200).to_bytes(2, "little"))
        say("0x1017 producer heartbeat time := 200 ms")
        m = self.watch.mark()
        time.sleep(1.05)
        beats = self.watch.since(m, 0x700 + nid)
        prev = None
        for b in beats:
            gap = f"  (+{(b.timestamp - prev) * 1000:.1f} ms)" if prev is not None else ""
            prev = b.timestamp
            say(f"<- {b.arbitration_id:03X} {hexs(b.data)}   heartbeat: "
                f"{STATES.get(b.data[0], '?')}{gap}")
        if len(beats) < 3:
            raise AssertionError(f"only {len(beats)} heartbeats in 1 s")
        iv = [(b.timestamp - a.timestamp) * 1000 for a, b in zip(beats, beats[1:])]
        say(f"heartbeat period measured: {sum(iv) / len(iv):.1f} ms (set 200 ms)")
        for state, code in (("OPERATIONAL", 0x05), ("STOPPED", 0x04),
                            ("PRE-OPERATIONAL", 0x7F), ("OPERATIONAL", 0x05)):
            self.nmt(nid, state)
            got = self.heartbeat_state(nid)
            say(f"   heartbeat says: {STATES.get(got, hex(got))}")
            if got != code:
                raise AssertionError(f"expected {STATES[code]}, heartbeat says 0x{got:02X}")

    def pdo_at_sync(self):
        nid = GENERIC_ID
        node = self.nodes[nid]
        node.tpdo.read()
        node.rpdo.read()
        tp, rp = node.tpdo[1], node.rpdo[1]
        tp.clear()
        tp.add_variable(0x2102)            # Process data U32
        tp.add_variable(0x2101)            # Process data U16
        tp.trans_type = 1                  # every SYNC
        tp.enabled = True
        node.tpdo.save()
        say(f"TPDO1 0x{tp.cob_id:03X} mapped: 0x2102 (U32), 0x2101 (U16), every SYNC")
        say(f"RPDO1 0x{rp.cob_id:03X} mapped: "
            + ", ".join(f"0x{v.index:04X} ({v.length} bit)" for v in rp.map))
        self.nmt(nid, "OPERATIONAL")
        rp[0x2102].raw = 0x12345678
        rp[0x2101].raw = 0xBEEF
        rp[0x2100].raw = 0x42
        rp.transmit()
        say(f"-> {rp.cob_id:03X} {hexs(bytes(rp.data))}   RPDO1 from the master")
        time.sleep(0.05)
        got = None
        for k in range(3):
            m = self.watch.mark()
            self.watch.send(0x080)
            say("-> 080      SYNC")
            f, _ = self.watch.wait(lambda f: f.arbitration_id == tp.cob_id, 1.0, m)
            if f is None:
                raise TimeoutError("no TPDO1 after SYNC")
            got = bytes(f.data)
            u32v = int.from_bytes(got[:4], "little")
            u16v = int.from_bytes(got[4:6], "little")
            say(f"<- {f.arbitration_id:03X} {hexs(got)}   TPDO1: 0x2102 = 0x{u32v:08X}, "
                f"0x2101 = 0x{u16v:04X}")
            time.sleep(0.05)
        if got != bytes.fromhex("78563412EFBE"):
            raise AssertionError("TPDO1 does not carry what RPDO1 wrote")
        return "RPDO values came back in the TPDO at SYNC"

    def store_and_restart(self):
        nid = GENERIC_ID
        node = self.nodes[nid]
        node.sdo.download(0x2020, 0, (777).to_bytes(2, "little"))
        say("0x2020 Limited UNSIGNED16 := 777")
        node.sdo.download(0x1010, 1, b"save")
        say("0x1010:1 store all parameters := 'save'")
        self.stop_device(nid)
        self.start_device(nid, "generic-301", storage=True)
        v = int.from_bytes(self.nodes[nid].sdo.upload(0x2020, 0), "little")
        say(f"0x2020 after restart: {v}")
        if v != 777:
            raise AssertionError(f"read back {v}, stored 777")
        self.nodes[nid].sdo.download(0x1011, 1, b"load")
        say("0x1011:1 restore default parameters := 'load' (defaults from the next reset)")

    def emergency(self):
        nid = GENERIC_ID
        node = self.nodes[nid]
        node.sdo.download(0x1016, 1, ((0x7E << 16) | 300).to_bytes(4, "little"))
        say("0x1016:1 := node 0x7E, 300 ms (the master plays node 0x7E)")
        m = self.watch.mark()
        self.watch.send(0x77E, b"\x05")
        say("-> 77E 05   one heartbeat of node 0x7E, then silence")
        f, _ = self.watch.wait(lambda f: f.arbitration_id == 0x80 + nid, 2.0, m)
        if f is None:
            raise TimeoutError("no EMCY")
        code = int.from_bytes(f.data[:2], "little")
        say(f"<- {f.arbitration_id:03X} {hexs(f.data)}   EMCY 0x{code:04X} "
            f"(heartbeat consumer), error register 0x{f.data[2]:02X}")
        m = self.watch.mark()
        self.watch.send(0x77E, b"\x05")
        f, _ = self.watch.wait(lambda f: f.arbitration_id == 0x80 + nid, 2.0, m)
        if f is None:
            raise TimeoutError("no EMCY reset")
        say(f"<- {f.arbitration_id:03X} {hexs(f.data)}   EMCY 0x0000: error reset")
        node.sdo.download(0x1016, 1, bytes(4))

    def control(self, node_id: int, line: str) -> str:
        """One command of the daemon's control interface (docs/linux.md)."""
        with socket.socket(socket.AF_UNIX, socket.SOCK_STREAM) as s:
            s.settimeout(2.0)
            s.connect(str(self.tmp / f"node{node_id}.sock"))
            s.sendall((line + "\n").encode())
            reply = s.makefile("r").readline().strip()
        say(f"control: {line}  ->  {reply}")
        return reply

    def io_module(self):
        nid = next(n for n, d in self.device_of.items() if d == "cia401")
        node = self.nodes[nid]
        tpdo1 = 0x180 + nid

        def tpdo(m, what, data=None, timeout=2.0):
            f, _ = self.watch.wait(lambda f: f.arbitration_id == tpdo1 and
                                   (data is None or bytes(f.data) == data), timeout, m)
            if f is None:
                raise TimeoutError(f"no TPDO1 ({what})")
            say(f"<- {f.arbitration_id:03X} {hexs(f.data)}   TPDO1 inputs 1..16: {what}")

        m = self.watch.mark()
        self.nmt(nid, "OPERATIONAL")
        tpdo(m, "first transmission in Operational")
        m = self.watch.mark()
        self.net.send_message(0x200 + nid, bytes([0x0F, 0xF0]))
        say(f"-> {0x200 + nid:03X} 0F F0   RPDO1 outputs 1..16")
        tpdo(m, "the outputs looped back", bytes([0x0F, 0xF0]))
        m = self.watch.mark()
        if self.control(nid, "set 0x6000 1 0x8F") != "ok":
            raise AssertionError("control interface refused the input")
        tpdo(m, "input 8 set from outside", bytes([0x8F, 0xF0]))
        node.sdo[0x6006][2].raw = 0x0F
        say("SDO 0x6006:2 = 0x0F   interrupt mask: only inputs 9..12 send")
        m = self.watch.mark()
        self.net.send_message(0x200 + nid, bytes([0x8F, 0x00]))
        say(f"-> {0x200 + nid:03X} 8F 00   RPDO1: outputs 13..16 off")
        time.sleep(0.3)
        if any(f.arbitration_id == tpdo1 for f in self.watch.since(m)):
            raise AssertionError("a masked input change sent TPDO1")
        say(f"   no TPDO1 within 0.3 s; {self.control(nid, 'get 0x6000 2')} (the input did change)")
        return "outputs by RPDO, inputs by TPDO, control interface, interrupt mask"

    def drive_id(self) -> int:
        return next(n for n, d in self.device_of.items() if d == "cia402")

    def drive_move(self):
        nid = self.drive_id()
        node = self.nodes[nid]
        node.tpdo.read()
        for k, objs in ((1, (0x6041, 0x6064)), (2, (0x606C, 0x6062))):
            tp = node.tpdo[k]
            tp.clear()
            for o in objs:
                tp.add_variable(o)
            tp.trans_type = 1
            tp.enabled = True
        node.tpdo.save()
        t1, t2 = node.tpdo[1].cob_id, node.tpdo[2].cob_id
        say(f"node {nid}: TPDO1 0x{t1:03X} := statusword 0x6041 + position actual 0x6064, "
            f"TPDO2 0x{t2:03X} := velocity actual 0x606C + position demand 0x6062, every SYNC")
        self.nmt(nid, "OPERATIONAL")
        drive = Drive(node, 0, lambda text: say("   " + text))
        drive.enable()
        target, velocity, acc = 43008, 20480, 40960   # 10.5 rev at 5 rev/s, 4096 increments/rev
        drive.set_mode(1)
        m = self.watch.mark()
        self.net.sync.start(0.02)
        say("SYNC every 20 ms from the master")
        try:
            time.sleep(0.2)
            drive.pp_move(target, velocity, acc)
            time.sleep(0.3)
        finally:
            self.net.sync.stop()
        frames = self.watch.since(m)
        samples = []
        t0 = frames[0].timestamp if frames else 0.0
        last2 = None
        for f in frames:
            if f.arbitration_id == t2:
                last2 = bytes(f.data)
            elif f.arbitration_id == t1 and last2 is not None:
                d1 = bytes(f.data)
                sw = int.from_bytes(d1[0:2], "little")
                pos = int.from_bytes(d1[2:6], "little", signed=True)
                vel = int.from_bytes(last2[0:4], "little", signed=True)
                dem = int.from_bytes(last2[4:8], "little", signed=True)
                if not samples or samples[-1].statusword != sw:
                    say(f"<- {t1:03X} {hexs(d1)}   (SYNC at +{f.timestamp - t0:5.2f} s) "
                        f"statusword 0x{sw:04X} "
                        f"({'target reached' if sw & 0x0400 else 'moving'}"
                        f"{', set-point acknowledged' if sw & 0x1000 else ''}), position {pos}")
                samples.append(Sample(f.timestamp - t0, pos, dem, vel, sw))
        say(f"{len(samples)} samples of the move from TPDO1/TPDO2 at SYNC")
        if len(samples) < 50:
            raise AssertionError(f"only {len(samples)} PDO samples")
        end = samples[-1]
        if abs(end.position - target) > 2 or not end.statusword & 0x0400:
            raise AssertionError(f"move ended at {end.position}, statusword "
                                 f"0x{end.statusword:04X}")
        self.out.mkdir(parents=True, exist_ok=True)
        csv_path, png = self.out / "cia402-move.csv", self.out / "cia402-move.png"
        write_csv(csv_path, samples)
        self.plot(csv_path, png, ["-o", str(png.with_suffix(".svg")), "--title",
                                  f"cia402 node {nid}: profile position 0 to {target}"])
        return f"target {target} reached ({state_of(end.statusword)}), plot {png.name}"

    def valve_id(self) -> int:
        return next(n for n, d in self.device_of.items() if d == "cia408")

    def valve_step(self):
        """vprc closed loop: set-point steps by RPDO2, the pressure by TPDO2."""
        nid = self.valve_id()
        node = self.nodes[nid]
        setup_closed_loop(node)
        t2 = node.tpdo[2].cob_id
        say(f"node {nid}: control mode 4 (vprc closed loop), TPDO2 0x{t2:03X} := status word "
            f"0x6041 + actual value 0x6381 + control deviation 0x63D0 (type 255, 5 ms inhibit)")
        self.nmt(nid, "OPERATIONAL")
        steps = [(0.0, 0), (0.1, 8192), (0.6, 4096), (1.0, -4096), (1.4, 0)]
        m = self.watch.mark()
        t0 = time.monotonic()
        for at, sp in steps:
            time.sleep(max(0.0, t0 + at - time.monotonic()))
            cob, data = rpdo(nid, 0x0007, sp)
            self.net.send_message(cob, data)
            say(f"-> {cob:03X} {hexs(data)}   RPDO2: control word D, H, M; set-point {sp} "
                f"({sp * 100 / 16384:+.0f} %)")
        time.sleep(0.4)
        # the set-point in force at each TPDO2: the last RPDO2 seen before it
        # on the bus (one clock for both: the frames' receive times)
        samples = []
        tf = None
        sp = 0
        for f in self.watch.since(m):
            d = bytes(f.data)
            if f.arbitration_id == 0x300 + nid and len(d) >= 4:
                sp = int.from_bytes(d[2:4], "little", signed=True)
                tf = f.timestamp if tf is None else tf
                last = samples[-1] if samples else ValveSample(0.0, 0, 0, 0, 0x000F)
                samples.append(ValveSample(f.timestamp - tf, last.actual, sp, last.deviation,
                                           last.statusword))
            elif f.arbitration_id == t2 and len(d) >= 6 and tf is not None:
                sw = int.from_bytes(d[0:2], "little")
                act = int.from_bytes(d[2:4], "little", signed=True)
                dev = int.from_bytes(d[4:6], "little", signed=True)
                samples.append(ValveSample(f.timestamp - tf, act, sp, dev, sw))
        if len(samples) < 20:
            raise AssertionError(f"only {len(samples)} samples")
        first = next((s for s in samples if s.setpoint == 8192 and s.statusword & 0x1000), None)
        if first is None:
            raise AssertionError("the pressure never reached the 50 % set-point's target window")
        say(f"{len(samples)} samples from TPDO2; target window (bit 12) reached "
            f"{(first.t - 0.1) * 1000:.0f} ms after the 50 % step, actual {first.actual}")
        self.out.mkdir(parents=True, exist_ok=True)
        csv_path, png = self.out / "cia408-step.csv", self.out / "cia408-step.png"
        write_valve_csv(csv_path, samples)
        self.plot(csv_path, png, ["--title",
                                  f"cia408 node {nid}: vprc set-point steps (position = actual "
                                  f"value, demand = set-point, velocity = control deviation)"])
        # NMT stop forces the fault reaction; the EMCY 0x8100 when it may go out
        m = self.watch.mark()
        self.nmt(nid, "STOPPED")
        time.sleep(0.1)
        self.nmt(nid, "PRE-OPERATIONAL")
        f, _ = self.watch.wait(lambda f: f.arbitration_id == 0x80 + nid, 1.0, m)
        if f is None:
            raise TimeoutError("no EMCY 0x8100 after the stop")
        say(f"<- {f.arbitration_id:03X} {hexs(f.data)}   EMCY 0x8100: NMT stop forced the "
            f"fault reaction")
        sw = wait_sw(node, lambda s: s & 0xF in (0x1, 0x3), 1.0)
        say(f"status word 0x{sw:04X}: {valve_state(sw)}")
        node.sdo.download(0x6040, 0, (0x0003).to_bytes(2, "little"))
        node.sdo.download(0x6040, 0, (0x000B).to_bytes(2, "little"))
        sw = wait_sw(node, lambda s: s & 0xF == 0xB, 1.0)
        say(f"fault reset (control word bit 3 rising): status word 0x{sw:04X}, {valve_state(sw)}")
        if sw & 0xF != 0xB:
            raise AssertionError(f"fault reset: status word 0x{sw:04X}")
        return f"plot {png.name}; NMT stop -> EMCY 0x8100, {valve_state(sw)} after the reset"

    def drive_homing(self):
        nid = self.drive_id()
        drive = Drive(self.nodes[nid], 0, lambda text: say("   " + text))
        before = drive.read(0x6064, signed=True)
        sw, pos = drive.homing(34, (8192, 2048))   # next index pulse, positive direction
        say(f"position {before} before homing, {pos} after: the next index pulse (every 4096 "
            f"increments) became the home offset 0")
        if not sw & 0x1000 or abs(pos) > 100 or abs(before - pos) < 1000:
            raise AssertionError(f"homing: statusword 0x{sw:04X}, position {pos}")
        return "homing attained on the index pulse"

    def shutdown(self):
        m = self.watch.mark()
        self.net.send_message(0x000, bytes([0x02, 0]))
        say("-> 000 02 00   NMT stop, all nodes")
        time.sleep(0.3)
        for f in self.watch.since(m):
            if f.arbitration_id >= 0x701:
                say(f"<- {f.arbitration_id:03X} {hexs(f.data)}   heartbeat: "
                    f"{STATES.get(f.data[0], '?')}")
                break
        for nid in list(self.procs):
            if self.stop_device(nid) != 0:
                raise AssertionError(f"node {nid} did not stop cleanly")

    # ------------------------------------------------------------ main
    def run(self) -> int:
        listing = subprocess.run([str(self.daemon), "--list-devices"], check=True,
                                 capture_output=True, text=True).stdout
        known = [ln.split()[0] for ln in listing.splitlines() if ln.strip()]
        self.lss_only = {ln.split()[0] for ln in listing.splitlines()
                         if ln.strip() and ln.split()[1] == "LSS-only"}
        wanted = known if self.wanted == ["all"] else (self.wanted or list(DEFAULT_DEVICES))
        unknown = [d for d in wanted if d not in known]
        if unknown:
            print(f"demo: unknown device(s) {', '.join(unknown)}; the daemon has "
                  f"{', '.join(known)}", flush=True)
            return 2
        self.devices = ["generic-301"] + [d for d in wanted if d != "generic-301"]
        print(f"canopen demo: python-canopen {canopen.__version__} master on {self.iface}; "
              f"devices: {', '.join(self.devices)}", flush=True)
        try:
            self.steps()
        except StepHung as e:
            print(f"\ndemo: stopped after the step that hung ({e})", flush=True)
        return self.summary()

    def steps(self) -> None:
        self.step("boot-up", self.boot)
        if not self.nodes:
            return
        self.step("identity over SDO", self.identity)
        self.step("NMT and heartbeats", self.nmt_and_heartbeats)
        self.step("PDO mapped and exchanged at SYNC", self.pdo_at_sync)
        self.step("emergency: heartbeat consumer timeout", self.emergency)
        self.step("parameter stored, process restarted, read back", self.store_and_restart)
        if "cia402" in self.devices:
            self.step("CiA 402 drive: enable, profile-position move, plot", self.drive_move)
            self.step("CiA 402 drive: homing", self.drive_homing)
        if "cia408" in self.devices:
            self.step("CiA 408 valve: set-point steps by RPDO, closed loop, plot; NMT stop",
                      self.valve_step)
        if "cia401" in self.devices:
            self.step("CiA 401 I/O module: outputs, inputs, control interface", self.io_module)
        self.step("stop", self.shutdown)

    def summary(self) -> int:
        print("\n== summary ==", flush=True)
        for title, ok, note in self.results:
            print(f"  {'ok    ' if ok else 'FAILED'}  {title}" + (f": {note}" if note else ""))
        failed = sum(1 for _, ok, _ in self.results if not ok)
        print(f"demo: {len(self.results) - failed} steps ok, {failed} failed", flush=True)
        return 1 if failed else 0

    def close(self):
        for p in self.procs.values():
            p.send_signal(signal.SIGTERM)
            try:
                p.wait(5)
            except subprocess.TimeoutExpired:
                p.kill()
        self.net.disconnect()
        self.watch.close()


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--daemon", default=str(ROOT / "build" / "host" / "bin" / "canopen-device"))
    ap.add_argument("--iface", default="vcan0")
    ap.add_argument("--out", default=str(ROOT / "build" / "demo"),
                    help="where the move trace (CSV) and its plot (PNG, SVG) go")
    ap.add_argument("--devices", nargs="+", metavar="NAME",
                    help="devices to bring up (default: generic-301 cia402 cia401; 'all': every "
                         "device of canopen-device --list-devices)")
    ap.add_argument("--plot-later", metavar="FILE",
                    help="write the plot-trace commands to FILE (one JSON list a line) "
                         "instead of running them (tools/run-demo plots on the host)")
    a = ap.parse_args()
    demo = Demo(Path(a.daemon), a.iface, Path(a.out), a.devices,
                Path(a.plot_later) if a.plot_later else None)
    try:
        return demo.run()
    finally:
        demo.close()


if __name__ == "__main__":
    sys.exit(main())
