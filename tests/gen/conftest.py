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


def run_odgen(toml: Path, out: Path, *extra: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, str(ODGEN), "--out", str(out), *extra, str(toml)],
                          capture_output=True, text=True, check=False)


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
