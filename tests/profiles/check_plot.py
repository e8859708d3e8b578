"""Run co402_trace, check the trace, render it with tools/plot-trace and
check the PNG (a CTest test; arguments: plot tool, output prefix, then the
command that runs the trace program: the program itself, or, when the tests
are cross-built, the emulator that runs it (CMAKE_CROSSCOMPILING_EMULATOR)
followed by the program).

The trace must show the move: the position rises to the first set-point's
way, turns, ends at 4000 with statusword bit 10 (target reached) and the
set-point acknowledge (bit 12) seen on the way. The PNG must be a valid
960x720 RGB image with the position, velocity and statusword colours in it.
"""
from __future__ import annotations

import csv
import struct
import subprocess
import sys
import zlib


def check_trace(path: str) -> None:
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    assert rows, "empty trace"
    pos = [int(r["position"]) for r in rows]
    vel = [int(r["velocity"]) for r in rows]
    sw = [int(r["statusword"]) for r in rows]
    t = [int(r["t_ms"]) for r in rows]
    assert t == list(range(t[0], t[0] + len(t))), "one row per millisecond"
    assert pos[0] == 0 and pos[-1] == 4000, (pos[0], pos[-1])
    assert 14000 < max(pos) < 16500, max(pos)
    assert 9900 <= max(vel) <= 10100 and -10100 <= min(vel) <= -9900, (max(vel), min(vel))
    assert any(s & 0x1000 for s in sw), "set-point acknowledge seen"
    assert sw[-1] & 0x0400 and (sw[-1] & 0x006F) == 0x0027, hex(sw[-1])


def check_png(path: str) -> None:
    data = open(path, "rb").read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", "PNG signature"
    pos, chunks = 8, {}
    while pos < len(data):
        n, tag = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        crc, = struct.unpack(">I", data[pos + 8 + n:pos + 12 + n])
        assert zlib.crc32(tag + body) == crc, f"CRC of {tag!r}"
        chunks.setdefault(tag, b"")
        chunks[tag] += body
        pos += 12 + n
    w, h, depth, ctype = struct.unpack(">IIBB", chunks[b"IHDR"][:10])
    assert (w, h, depth, ctype) == (960, 720, 8, 2), (w, h, depth, ctype)
    raw = zlib.decompress(chunks[b"IDAT"])
    assert len(raw) == h * (1 + 3 * w)
    colours = set()
    for y in range(h):
        row = raw[y * (1 + 3 * w):(y + 1) * (1 + 3 * w)]
        assert row[0] == 0
        colours.update(bytes(row[1 + 3 * x:4 + 3 * x]) for x in range(0, w, 1))
    for c in ((31, 97, 196), (230, 120, 20), (25, 150, 70), (120, 60, 170)):
        assert bytes(c) in colours, f"colour {c} drawn"


def main() -> int:
    plot, prefix = sys.argv[1:3]
    trace_cmd = sys.argv[3:]
    assert trace_cmd, "usage: check_plot.py PLOT PREFIX [EMULATOR...] TRACE"
    subprocess.run([*trace_cmd, prefix + ".csv"], check=True)
    check_trace(prefix + ".csv")
    subprocess.run([sys.executable, plot, prefix + ".csv", "-o", prefix + ".png",
                    "--title", "cia402 profile position"], check=True)
    check_png(prefix + ".png")
    print(f"{prefix}.png: ok")
    return 0


if __name__ == "__main__":
    sys.exit(main())
