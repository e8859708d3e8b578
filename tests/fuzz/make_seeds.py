#!/usr/bin/env python3
"""Write the seed corpus of the fuzz targets (tests/fuzz/corpus/<target>/)
from readable scenarios, in the input format of fuzz_node.c:

  "605 40 00 10 00 00 00 00 00"  a frame, then co_node_process (op 0x08)
  "R 705"                         a remote frame, then co_node_process
  "T 1000"                        time passes by 1000 us (at most 65535)
  "L 50"                          50 rounds of 1 ms (at most 63)
  "S 2400"                        the clock jumps by 2400 s (a stall)
  "X 5"                           the TX path refuses the next 5 frames

Run it after changing a scenario; the files are committed.
"""
from __future__ import annotations

import hashlib
import struct
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent


def encode(lines: list[str]) -> bytes:
    out = bytearray()
    for line in lines:
        w = line.split()
        if w[0] == "T":
            out += bytes([0x03]) + struct.pack("<H", int(w[1]))
        elif w[0] == "L":
            out += bytes([0x06, int(w[1]) & 0x3F])
        elif w[0] == "S":
            us = int(w[1]) * 1_000_000 & 0xFFFF0000
            out += bytes([0x04, us >> 24, (us >> 16) & 0xFF])
        elif w[0] == "X":
            out += bytes([0x05, int(w[1])])
        elif w[0] == "R":
            cob = int(w[1], 16)
            dlc = int(w[2]) if len(w) > 2 else 0
            out += bytes([0x08, 0xC0 | (cob >> 8), cob & 0xFF, 0x80 | dlc])
        else:
            cob = int(w[0], 16)
            data = bytes(int(x, 16) for x in w[1:])
            out += bytes([0x08, 0xC0 | (cob >> 8), cob & 0xFF, len(data)]) + data
    return bytes(out)


def sdo_w(node: int, index: int, sub: int, value: int, size: int) -> str:
    cmd = {1: 0x2F, 2: 0x2B, 4: 0x23}[size]
    b = value.to_bytes(4, "little")
    return f"{0x600 + node:03X} {cmd:02X} {index & 0xFF:02X} {index >> 8:02X} {sub:02X} " + \
        " ".join(f"{x:02X}" for x in b)


def sdo_r(node: int, index: int, sub: int) -> str:
    return f"{0x600 + node:03X} 40 {index & 0xFF:02X} {index >> 8:02X} {sub:02X} 00 00 00 00"


def generic(n: int = 5) -> dict[str, list[str]]:
    s = {}
    s["nmt_sync_pdo"] = [f"000 01 {n:02X}", "080", f"{0x200 + n:03X} 11 22 33 44 55 66 77",
                         "080", "T 5000", f"R {0x180 + n:03X}", "000 80 00", "000 02 00",
                         f"000 81 {n:02X}", "L 10"]
    s["sdo_expedited"] = [sdo_r(n, 0x1000, 0), sdo_r(n, 0x1018, 1), sdo_r(n, 0x1018, 9),
                          sdo_w(n, 0x2102, 0, 0x12345678, 4), sdo_r(n, 0x2102, 0),
                          sdo_w(n, 0x1000, 0, 1, 4), sdo_w(n, 0x2200, 0, 0xDEADBEEF, 4),
                          sdo_r(n, 0x5FFF, 0), f"{0x600 + n:03X} 80 00 10 00 00 00 04 05",
                          f"{0x600 + n:03X} E0 00 10 00", f"{0x600 + n:03X}"]
    s["sdo_segmented"] = [f"{0x600 + n:03X} 21 00 23 00 0E 00 00 00",
                          f"{0x600 + n:03X} 00 59 59 59 59 59 59 59",
                          f"{0x600 + n:03X} 11 20 43 69 41 20 33 30",
                          f"{0x600 + n:03X} 40 00 23 00 00 00 00 00",
                          f"{0x600 + n:03X} 60 00 00 00 00 00 00 00",
                          f"{0x600 + n:03X} 70 00 00 00 00 00 00 00",
                          f"{0x600 + n:03X} 40 08 10 00 00 00 00 00",
                          f"{0x600 + n:03X} 60 00 00 00 00 00 00 00",
                          f"{0x600 + n:03X} 21 00 23 00 0E 00 00 00",
                          f"{0x600 + n:03X} 00 59 59 59 59 59 59 59", "T 60000", "L 60"]
    s["sdo_block"] = [f"{0x600 + n:03X} C6 00 23 00 0E 00 00 00",
                      f"{0x600 + n:03X} 01 59 59 59 59 59 59 59",
                      f"{0x600 + n:03X} 82 20 43 69 41 20 33 30",
                      f"{0x600 + n:03X} C1 00 00 00 00 00 00 00",
                      f"{0x600 + n:03X} A4 00 23 00 7F 00 00 00",
                      f"{0x600 + n:03X} A3 00 00 00 00 00 00 00",
                      f"{0x600 + n:03X} A2 02 7F 00 00 00 00 00",
                      f"{0x600 + n:03X} A1 00 00 00 00 00 00 00",
                      f"{0x600 + n:03X} A4 08 10 00 02 00 00 00", "X 3",
                      f"{0x600 + n:03X} A3 00 00 00 00 00 00 00", "L 5",
                      f"{0x600 + n:03X} A2 01 02 00 00 00 00 00"]
    s["storage"] = [sdo_w(n, 0x1017, 0, 100, 2), sdo_w(n, 0x2102, 0, 0xCAFE, 4),
                    sdo_w(n, 0x1010, 1, 0x65766173, 4), f"000 81 {n:02X}", "L 20",
                    sdo_w(n, 0x1010, 3, 0x65766173, 4), sdo_w(n, 0x1011, 1, 0x64616F6C, 4),
                    f"000 82 {n:02X}", sdo_w(n, 0x1010, 2, 0x12345678, 4), "L 63"]
    s["heartbeat"] = [sdo_w(n, 0x1017, 0, 10, 2), sdo_w(n, 0x1016, 1, (0x7E << 16) | 50, 4),
                      "77E 05", "L 30", "77E 05", "L 63", "77E 7F", "S 2400", "L 20",
                      sdo_w(n, 0x1016, 1, (n << 16) | 50, 4), sdo_w(n, 0x1017, 0, 0, 2)]
    s["guarding"] = [sdo_w(n, 0x100C, 0, 20, 2), sdo_w(n, 0x100D, 0, 3, 1),
                     f"R {0x700 + n:03X} 1", "L 10", f"R {0x700 + n:03X} 1", "L 63", "L 63",
                     f"R {0x700 + n:03X} 1"]
    s["sync_producer"] = [sdo_w(n, 0x1006, 0, 10000, 4), sdo_w(n, 0x1019, 0, 0, 1),
                          sdo_w(n, 0x1005, 0, 0x40000080, 4), f"000 01 {n:02X}", "L 40",
                          sdo_w(n, 0x1006, 0, 0xF0000000, 4), "L 10", "X 10", "L 20",
                          sdo_w(n, 0x1005, 0, 0x00000080, 4), "080 01"]
    s["pdo_remap"] = [sdo_w(n, 0x1800, 1, 0x80000180 + n, 4), sdo_w(n, 0x1A00, 0, 0, 1),
                      sdo_w(n, 0x1A00, 1, 0x21020020, 4), sdo_w(n, 0x1A00, 0, 1, 1),
                      sdo_w(n, 0x1800, 2, 254, 1), sdo_w(n, 0x1800, 3, 100, 2),
                      sdo_w(n, 0x1800, 5, 1, 2), sdo_w(n, 0x1800, 1, 0x180 + n, 4),
                      f"000 01 {n:02X}", "L 30", sdo_w(n, 0x2102, 0, 7, 4), "L 30",
                      sdo_w(n, 0x1400, 1, 0x80000200 + n, 4), sdo_w(n, 0x1400, 2, 1, 1),
                      sdo_w(n, 0x1400, 5, 20, 2), sdo_w(n, 0x1400, 1, 0x200 + n, 4),
                      f"{0x200 + n:03X} 01 02 03 04 05 06 07", "080", "L 40",
                      f"{0x200 + n:03X} 01 02", "080"]
    s["emcy_time"] = [sdo_w(n, 0x1015, 0, 100, 2), sdo_w(n, 0x1014, 0, 0x80000080 + n, 4),
                      sdo_w(n, 0x1014, 0, 0x00000000, 4), sdo_w(n, 0x1014, 0, 0x080 + n, 4),
                      "080 05", "080", "100 00 00 00 00 00 00", sdo_w(n, 0x1012, 0, 0x40000100, 4),
                      "L 10"]
    return s


def cia402(n: int = 2) -> dict[str, list[str]]:
    s = {}
    enable = [sdo_w(n, 0x6040, 0, 0x06, 2), "L 5", sdo_w(n, 0x6040, 0, 0x07, 2), "L 5",
              sdo_w(n, 0x6040, 0, 0x0F, 2), "L 20"]
    s["pp_move"] = [sdo_w(n, 0x6060, 0, 1, 1)] + enable + [
        sdo_w(n, 0x607A, 0, 20000, 4), sdo_w(n, 0x6081, 0, 10000, 4),
        sdo_w(n, 0x6040, 0, 0x1F, 2), "L 10", sdo_w(n, 0x6040, 0, 0x0F, 2), "L 63", "L 63",
        sdo_r(n, 0x6041, 0), sdo_r(n, 0x6064, 0)]
    s["pv"] = [sdo_w(n, 0x6060, 0, 3, 1)] + enable + [
        sdo_w(n, 0x60FF, 0, 5000, 4), "L 63", sdo_w(n, 0x6094, 1, 0x09090909, 4),
        sdo_w(n, 0x60FF, 0, 0x7FFFFFFF, 4), "L 63", sdo_w(n, 0x6040, 0, 0x02, 2), "L 40"]
    s["csp_rpdo"] = [sdo_w(n, 0x1400, 1, 0x80000200 + n, 4), sdo_w(n, 0x1600, 0, 0, 1),
                     sdo_w(n, 0x1600, 1, 0x60400010, 4), sdo_w(n, 0x1600, 2, 0x607A0020, 4),
                     sdo_w(n, 0x1600, 0, 2, 1), sdo_w(n, 0x1400, 1, 0x200 + n, 4),
                     sdo_w(n, 0x6060, 0, 8, 1)] + enable + [
        f"000 01 {n:02X}", f"{0x200 + n:03X} 0F 00 10 A3 E0 12", "080", "L 20", "080", "L 20",
        f"{0x200 + n:03X} 0F 00 00 00 00 80", "080", "L 63", "080"]
    s["homing"] = [sdo_w(n, 0x6060, 0, 6, 1), sdo_w(n, 0x6098, 0, 35, 1)] + enable + [
        sdo_w(n, 0x6040, 0, 0x1F, 2), "L 63", "L 63", sdo_r(n, 0x6041, 0),
        sdo_w(n, 0x6098, 0, 1, 1), sdo_w(n, 0x6040, 0, 0x0F, 2), sdo_w(n, 0x6040, 0, 0x1F, 2),
        "L 63"]
    s["fault_quickstop"] = enable + [sdo_w(n, 0x6040, 0, 0x0B, 2), "L 30",
                                     sdo_w(n, 0x6040, 0, 0x80, 2), "L 5",
                                     sdo_w(n, 0x6040, 0, 0x00, 2), sdo_w(n, 0x605A, 0, 7, 2),
                                     "S 2400", "L 10", f"000 81 {n:02X}", "L 10"]
    s["factors"] = [sdo_w(n, 0x6093, 1, 7, 4), sdo_w(n, 0x6093, 2, 3, 4),
                    sdo_w(n, 0x6094, 1, 0xFFFFFFFF, 4), sdo_w(n, 0x6094, 2, 1, 4),
                    sdo_w(n, 0x6060, 0, 2, 1)] + enable + [
        sdo_w(n, 0x6042, 0, 0x7FFF, 2), "L 63", sdo_r(n, 0x6044, 0), sdo_r(n, 0x606C, 0)]
    return s


def main() -> int:
    for target, scen in (("generic301", generic()), ("cia402", cia402())):
        d = HERE / "corpus" / target
        d.mkdir(parents=True, exist_ok=True)
        for old in d.glob("seed-*"):
            old.unlink()
        for name, lines in scen.items():
            (d / f"seed-{name}").write_bytes(encode(lines))
        # an input whose first byte is 0xA5 runs on the asynchronous NV
        # with an erase unit (and starts with "refuse 0 frames")
        store = scen.get("storage", scen.get("pp_move"))
        (d / "seed-async-nv").write_bytes(bytes([0xA5, 0x00]) + encode(store))
        print(f"{d.relative_to(HERE.parents[1])}: {len(scen) + 1} seeds")
    return 0


if __name__ == "__main__":
    sys.exit(main())
