"""CiA 402 master steps over SDO with python-canopen: enable a drive, run a
profile-position move, run a homing. Used by the main job (master.py) and by
the integration tests (tests/integration/test_drives.py).

Every step waits for the statusword the standard prescribes and raises
DriveError naming the statusword seen when it does not come. A move can be
sampled (time, position, demand, velocity, statusword) for tools/plot-trace.
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field

import canopen

AXIS_OFFSET = 0x800

# controlword commands (CiA 402, device control)
SHUTDOWN = 0x0006
SWITCH_ON = 0x0007
ENABLE_OPERATION = 0x000F
FAULT_RESET = 0x0080
NEW_SET_POINT = 0x0010       # bit 4: pp new set-point / hm start
CHANGE_IMMEDIATELY = 0x0020  # bit 5
RELATIVE = 0x0040            # bit 6

# statusword bits
SW_TARGET_REACHED = 1 << 10
SW_BIT12 = 1 << 12           # pp: set-point acknowledge; hm: homing attained
SW_BIT13 = 1 << 13           # pp: following error; hm: homing error
SW_FAULT = 1 << 3

MODE_PP = 1
MODE_HM = 6


class DriveError(AssertionError):
    pass


# (mask, value, state) of the statusword, CiA 402 table "state coding"
STATES = ((0x4F, 0x00, "Not ready to switch on"), (0x4F, 0x40, "Switch on disabled"),
          (0x6F, 0x21, "Ready to switch on"), (0x6F, 0x23, "Switched on"),
          (0x6F, 0x27, "Operation enabled"), (0x6F, 0x07, "Quick stop active"),
          (0x4F, 0x0F, "Fault reaction active"), (0x4F, 0x08, "Fault"))


def state_of(sw: int) -> str:
    """The CiA 402 state a statusword shows."""
    return next((name for mask, value, name in STATES if sw & mask == value), "?")


@dataclass
class Sample:
    t: float
    position: int
    demand: int
    velocity: int
    statusword: int


@dataclass
class Drive:
    """Axis `axis` of a python-canopen RemoteNode."""
    node: canopen.RemoteNode
    axis: int = 0
    log: callable = field(default=lambda text: None)

    def ix(self, index: int) -> int:
        return index + AXIS_OFFSET * self.axis

    def read(self, index: int, sub: int = 0, signed: bool = False) -> int:
        data = self.node.sdo.upload(self.ix(index), sub)
        return int.from_bytes(data, "little", signed=signed)

    def write(self, index: int, value: int, size: int, sub: int = 0) -> None:
        self.node.sdo.download(self.ix(index), sub,
                               value.to_bytes(size, "little", signed=value < 0))

    def statusword(self) -> int:
        return self.read(0x6041)

    def control(self, cw: int) -> None:
        self.write(0x6040, cw, 2)

    def wait_sw(self, what: str, pred, timeout: float = 3.0, period: float = 0.01,
                sample: list[Sample] | None = None, t0: float = 0.0) -> int:
        end = time.monotonic() + timeout
        while True:
            sw = self.statusword()
            if sample is not None:
                sample.append(self.sample(t0, sw))
            if pred(sw):
                return sw
            if time.monotonic() > end:
                raise DriveError(f"axis {self.axis}: {what} not seen within {timeout} s "
                                 f"(statusword 0x{sw:04X}, {state_of(sw)})")
            time.sleep(period)

    def sample(self, t0: float, sw: int) -> Sample:
        return Sample(time.monotonic() - t0, self.read(0x6064, signed=True),
                      self.read(0x6062, signed=True), self.read(0x606C, signed=True), sw)

    def command(self, cw: int, mask: int, want: int, name: str) -> int:
        self.control(cw)
        sw = self.wait_sw(name, lambda s: s & mask == want)
        self.log(f"controlword 0x{cw:04X} -> statusword 0x{sw:04X} ({state_of(sw)})")
        return sw

    def enable(self) -> int:
        """Fault reset if needed, then shutdown, switch on, enable operation."""
        sw = self.statusword()
        self.log(f"statusword 0x{sw:04X} ({state_of(sw)})")
        if sw & SW_FAULT:
            self.control(0x0000)
            self.command(FAULT_RESET, 0x4F, 0x40, "Switch on disabled after fault reset")
        self.command(SHUTDOWN, 0x6F, 0x21, "Ready to switch on")
        self.command(SWITCH_ON, 0x6F, 0x23, "Switched on")
        return self.command(ENABLE_OPERATION, 0x6F, 0x27, "Operation enabled")

    def set_mode(self, mode: int) -> None:
        """0x6060 = mode, until 0x6061 shows it. A drive that changes modes only
        at rest (0x08000022 while it still settles) is asked again."""
        end = time.monotonic() + 2.0
        while True:
            try:
                self.write(0x6060, mode, 1)
                break
            except canopen.SdoAbortedError as e:
                if e.code != 0x08000022 or time.monotonic() > end:
                    raise
                time.sleep(0.02)
        while self.read(0x6061, signed=True) != mode:
            if time.monotonic() > end:
                raise DriveError(f"axis {self.axis}: 0x6061 did not follow 0x6060 = {mode}")
            time.sleep(0.01)
        self.log(f"mode of operation {mode} (0x6061 = {mode})")

    def pp_move(self, target: int, velocity: int, acceleration: int,
                timeout: float = 10.0, sample: list[Sample] | None = None) -> int:
        """Absolute profile-position move; returns the final position."""
        self.set_mode(MODE_PP)
        self.write(0x6081, velocity, 4)
        self.write(0x6083, acceleration, 4)
        self.write(0x6084, acceleration, 4)
        self.write(0x607A, target, 4)
        self.control(ENABLE_OPERATION)         # bit 4 low: the next write is its rising edge
        t0 = time.monotonic()
        if sample is not None:
            sample.append(self.sample(t0, self.statusword()))
        self.control(ENABLE_OPERATION | NEW_SET_POINT)
        sw = self.wait_sw("set-point acknowledge (bit 12)", lambda s: s & SW_BIT12, 2.0,
                          sample=sample, t0=t0)
        self.log(f"new set-point {target} (controlword 0x001F) -> acknowledged, "
                 f"statusword 0x{sw:04X}")
        self.control(ENABLE_OPERATION)
        sw = self.wait_sw("target reached (bit 10)",
                          lambda s: (s & SW_TARGET_REACHED) and not (s & SW_BIT12),
                          timeout, period=0.02, sample=sample, t0=t0)
        if sample is not None:
            for _ in range(10):         # the settled end of the move
                time.sleep(0.02)
                sample.append(self.sample(t0, self.statusword()))
        pos = self.read(0x6064, signed=True)
        self.log(f"target reached after {time.monotonic() - t0:.2f} s: statusword 0x{sw:04X}, "
                 f"position actual 0x6064 = {pos}")
        return pos

    def homing(self, method: int, speeds: tuple[int, int] | None = None,
               timeout: float = 15.0) -> tuple[int, int]:
        """Homing with `method` (0x6098); returns the statusword that showed
        homing attained and the position then. Bit 4 stays set (some drives
        drop homing attained when it is cleared)."""
        self.set_mode(MODE_HM)
        self.write(0x6098, method, 1)
        if speeds is not None:
            self.write(0x6099, speeds[0], 4, sub=1)
            self.write(0x6099, speeds[1], 4, sub=2)
        self.control(ENABLE_OPERATION)
        t0 = time.monotonic()
        self.control(ENABLE_OPERATION | NEW_SET_POINT)
        sw = self.wait_sw("homing attained (bits 10 and 12)",
                          lambda s: (s & (SW_TARGET_REACHED | SW_BIT12)) ==
                          (SW_TARGET_REACHED | SW_BIT12) or (s & SW_BIT13),
                          timeout, period=0.02)
        if sw & SW_BIT13:
            raise DriveError(f"axis {self.axis}: homing error, statusword 0x{sw:04X}")
        pos = self.read(0x6064, signed=True)
        self.log(f"homing method {method}: attained after {time.monotonic() - t0:.2f} s, "
                 f"statusword 0x{sw:04X}, position actual {pos}")
        return sw, pos


def write_csv(path, samples: list[Sample]) -> None:
    with open(path, "w") as f:
        f.write("t_ms,position,position_demand,velocity,statusword\n")
        for s in samples:
            f.write(f"{s.t * 1000:.1f},{s.position},{s.demand},{s.velocity},{s.statusword}\n")
