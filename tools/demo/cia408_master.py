"""The CiA 408 valve as the demo master drives it (tools/demo/master.py):
device mode and control mode by SDO, the device state machine and the
set-point by RPDO, the actual value, control deviation and status word
from a TPDO, written as a trace for tools/plot-trace."""
from __future__ import annotations

import time
from dataclasses import dataclass

import canopen

# Device states by the status word's bits 3..0 (R M H D), CiA 408.
STATES = {0x0: "NOT_READY", 0x8: "INIT", 0x9: "DISABLED", 0xB: "HOLD",
          0xF: "DEVICE_MODE_ACTIVE", 0x7: "FAULT_REACTION", 0x3: "FAULT_HOLD", 0x1: "FAULT"}


def valve_state(sw: int) -> str:
    return STATES.get(sw & 0xF, f"0x{sw & 0xF:X}")


@dataclass
class ValveSample:
    t: float          # s after the first set-point
    actual: int       # 6381h, internal resolution (16384 = 100 %)
    setpoint: int     # the set-point sent last (6380h)
    deviation: int    # 63D0h
    statusword: int


def write_valve_csv(path, samples: list[ValveSample]) -> None:
    """The columns tools/plot-trace draws: position = actual value,
    position_demand = set-point, velocity = control deviation. The TPDO
    goes out only when its data change, so each value holds until the next
    sample: a row with the old values just before every new one."""
    with open(path, "w") as f:
        f.write("t_ms,position,position_demand,velocity,statusword\n")
        prev = None
        for s in samples:
            if prev is not None and s.t > prev.t:
                f.write(f"{s.t * 1000 - 0.1:.1f},{prev.actual},{prev.setpoint},"
                        f"{prev.deviation},{prev.statusword}\n")
            f.write(f"{s.t * 1000:.1f},{s.actual},{s.setpoint},{s.deviation},{s.statusword}\n")
            prev = s


def setup_closed_loop(node: canopen.RemoteNode) -> None:
    """vprc closed loop (6043h = 4) with the following-error window (bit 11)
    and the target window (bit 12) on; TPDO2 := status word, actual value,
    control deviation; RPDO2 = control word + vprc set-point (the default)."""
    sdo = node.sdo
    sdo.download(0x6042, 0, bytes([1]))          # set-point via fieldbus
    sdo.download(0x6043, 0, bytes([4]))          # vprc closed loop
    sdo.download(0x63D1, 0, bytes([2]))          # following-error monitoring
    sdo.download(0x63D3, 1, (1638).to_bytes(2, "little"))   # 10 %
    sdo.download(0x2402, 0, bytes([2]))          # target window
    sdo.download(0x2404, 0, (164).to_bytes(4, "little"))    # 1 %
    sdo.download(0x2403, 0, (10).to_bytes(2, "little"))     # 10 ms
    node.tpdo.read()
    tp = node.tpdo[2]
    tp.clear()
    for o in (0x6041, (0x6381, 1), (0x63D0, 1)):
        if isinstance(o, tuple):
            tp.add_variable(o[0], o[1])
        else:
            tp.add_variable(o)
    tp.trans_type = 255
    tp.inhibit_time = 50                         # 5 ms
    tp.enabled = True
    node.tpdo.save()


def rpdo(node_id: int, cw: int, sp: int) -> tuple[int, bytes]:
    return 0x300 + node_id, cw.to_bytes(2, "little") + sp.to_bytes(2, "little", signed=True)


def wait_sw(node: canopen.RemoteNode, pred, timeout: float) -> int:
    end = time.monotonic() + timeout
    while True:
        sw = int.from_bytes(node.sdo.upload(0x6041, 0), "little")
        if pred(sw) or time.monotonic() > end:
            return sw
        time.sleep(0.01)
