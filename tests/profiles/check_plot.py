"""Run co402_trace, check the trace, render it with tools/plot-trace and
check the PNG (a CTest test; arguments: plot tool, output prefix, then the
command that runs the trace program: the program itself, or, when the tests
are cross-built, the emulator that runs it (CMAKE_CROSSCOMPILING_EMULATOR)
followed by the program).

The trace must show the move: the position rises to the first set-point's
way, turns, ends at 4000 with statusword bit 10 (target reached) and the
set-point acknowledge (bit 12) seen on the way. The PNG must be written by
matplotlib with the position, demand, velocity and statusword colours in it;
the SVG must carry the title, the axis labels with their units and the legend
as text.
"""
from __future__ import annotations

import csv
import struct
import subprocess
import sys
import zlib

# the series colours tools/plot-trace draws with
POS, DEMAND, VEL, BIT = (0x1f, 0x61, 0xc4), (0xe6, 0x78, 0x14), (0x19, 0x96, 0x46), (0x78, 0x3c, 0xaa)


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


def png_chunks(data: bytes) -> dict[bytes, bytes]:
    assert data[:8] == b"\x89PNG\r\n\x1a\n", "PNG signature"
    pos, chunks = 8, {}
    while pos < len(data):
        n, tag = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        crc, = struct.unpack(">I", data[pos + 8 + n:pos + 12 + n])
        assert zlib.crc32(tag + body) == crc, f"CRC of {tag!r}"
        chunks[tag] = chunks.get(tag, b"") + body
        pos += 12 + n
    return chunks


def near(pixels, rgb: tuple[int, int, int], tol: int = 6) -> int:
    """Number of pixels within tol (per channel) of the colour."""
    import numpy as np
    d = np.abs(pixels[:, :, :3].astype(int) - np.array(rgb)).max(axis=2)
    return int((d <= tol).sum())


def check_png(path: str) -> None:
    import matplotlib.image
    chunks = png_chunks(open(path, "rb").read())
    assert b"Software" in chunks.get(b"tEXt", b"") and b"matplotlib" in chunks[b"tEXt"], \
        "written by matplotlib"
    w, h = struct.unpack(">II", chunks[b"IHDR"][:8])
    assert w >= 1000 and h >= 800, (w, h)
    img = (matplotlib.image.imread(path) * 255).round().astype("uint8")
    assert img.shape[:2] == (h, w), img.shape
    # every series drawn: position, demand, velocity lines, statusword bars
    for name, c, least in (("position", POS, 300), ("demand", DEMAND, 100),
                           ("velocity", VEL, 1000), ("statusword bits", BIT, 20000)):
        assert near(img, c) >= least, f"{name} colour {c}: {near(img, c)} pixels"
    # mostly white background: the plot is not one block of colour
    assert near(img, (255, 255, 255), 0) > w * h // 2


def check_svg(path: str, title: str) -> None:
    import xml.etree.ElementTree as ET
    root = ET.parse(path).getroot()
    texts = {"".join(e.itertext()).strip() for e in root.iter("{http://www.w3.org/2000/svg}text")}
    for want in (title, "position [inc]", "velocity [inc/s]", "time [s]",
                 "statusword (0x6041) bit", "10 target reached", "position actual (0x6064)",
                 "position demand (0x6062)", "velocity actual (0x606C)"):
        assert want in texts, f"SVG text {want!r} missing (have {sorted(texts)[:40]})"
    paths = list(root.iter("{http://www.w3.org/2000/svg}path"))
    assert len(paths) > 20, len(paths)


def main() -> int:
    plot, prefix = sys.argv[1:3]
    trace_cmd = sys.argv[3:]
    assert trace_cmd, "usage: check_plot.py PLOT PREFIX [EMULATOR...] TRACE"
    subprocess.run([*trace_cmd, prefix + ".csv"], check=True)
    check_trace(prefix + ".csv")
    title = "cia402 profile position"
    subprocess.run([sys.executable, plot, prefix + ".csv", "-o", prefix + ".png",
                    "-o", prefix + ".svg", "--title", title], check=True)
    check_png(prefix + ".png")
    check_svg(prefix + ".svg", title)
    bad = subprocess.run([sys.executable, plot, prefix + ".csv", "-o", prefix + ".gif"],
                         capture_output=True, text=True)
    assert bad.returncode == 2 and ".png or .svg" in bad.stderr, (bad.returncode, bad.stderr)
    print(f"{prefix}.png, {prefix}.svg: ok")
    return 0


if __name__ == "__main__":
    sys.exit(main())
