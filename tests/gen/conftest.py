"""Shared helpers for the generator tests (tests/gen).

The comparison tests use a built tree: $CODEV_BUILD_DIR (tools/run-tests sets
it), else build/host. Everything else runs the generator itself.
"""
from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
ODGEN = ROOT / "tools" / "odgen" / "odgen.py"
DEVICES = sorted((ROOT / "devices").glob("*.toml"))

sys.path.insert(0, str(ODGEN.parent))


def build_dir() -> Path:
    d = Path(os.environ.get("CODEV_BUILD_DIR", ROOT / "build" / "host"))
    return d if d.is_absolute() else ROOT / d


FOREIGN = ROOT / ".cache" / "foreign"
WARN = ["-std=c99", "-Wall", "-Wextra", "-Wpedantic", "-Wconversion", "-Wshadow", "-Werror"]


def run_odgen(toml: Path, out: Path, *extra: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, str(ODGEN), "--out", str(out), *extra, str(toml)],
                          capture_output=True, text=True, check=False)


def run_import(eds: Path, toml: Path, *extra: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, str(ODGEN), "import", str(eds), "-o", str(toml),
                           *extra], capture_output=True, text=True, check=False)


def foreign(name: str) -> Path:
    """A foreign EDS file fetched by tools/setup (tests/gen/foreign/README.md)."""
    p = FOREIGN / name
    if not p.exists():
        pytest.fail(f"{p} missing: run tools/setup (it fetches the foreign EDS files)")
    return p


def compile_dump(src_dir: Path, cname: str) -> Path:
    """Compile the generated <cname>.c in src_dir with od_dump.c and the core
    library of the built tree (warnings as errors); the od_dump executable."""
    lib = build_dir() / "stack" / "libcostack.a"
    if not lib.exists():
        pytest.fail(f"{lib} missing: build the tree first or set CODEV_BUILD_DIR")
    exe = src_dir / f"od_dump_{cname}"
    cc = subprocess.run(["cc", *WARN, f"-DCODEV_NAME={cname}", f"-I{src_dir}",
                         f"-I{ROOT / 'stack' / 'include'}", str(src_dir / f"{cname}.c"),
                         str(ROOT / "tests" / "gen" / "od_dump.c"), str(lib), "-o", str(exe)],
                        capture_output=True, text=True)
    assert cc.returncode == 0, cc.stderr
    assert cc.stderr == ""
    return exe


@pytest.fixture(params=DEVICES, ids=[p.stem for p in DEVICES])
def device(request) -> Path:
    return request.param


@pytest.fixture
def generated(device, tmp_path) -> Path:
    """Run the generator on a device description into a fresh directory."""
    r = run_odgen(device, tmp_path)
    assert r.returncode == 0, r.stderr
    assert r.stderr == ""
    return tmp_path
