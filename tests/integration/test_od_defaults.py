"""Every readable object of generic-301, read over SDO on vcan by
python-canopen, holds the default the exported EDS gives for it (issue 5:
the running device agrees with its own EDS)."""
from __future__ import annotations

import sys
import time
from pathlib import Path

import canopen

from conftest import NODE_ID

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "gen"))
from compare import decode, eds_vars, expected  # noqa: E402  (tests/gen/compare.py)

NO_DATA = 0x08000024
LIVE = {(0x2024, 0)}     # "Uptime": seconds since start, checked separately
EMPTY = {(0x2300, 0)}    # the DOMAIN: empty until written
# 0x1010/0x1011 capabilities: the EDS says 1 (saves on command); this daemon
# runs without --storage, so the HAL has no NV and they read 0 (docs/core.md,
# Storage); test_store.py checks the 1 with a parameter file.
NO_NV = {(i, s) for i in (0x1010, 0x1011) for s in (1, 2, 3)}


def readable(var) -> bool:
    return var.access_type in ("ro", "rw", "rwr", "rww", "const")


def test_every_readable_object_holds_its_eds_default(node, eds_path):
    started = time.monotonic()
    od = canopen.import_od(str(eds_path), node_id=NODE_ID)
    checked = 0
    for (index, sub), var in sorted(eds_vars(od).items()):
        where = f"0x{index:04X} sub {sub} ({var.name})"
        if not readable(var):
            continue
        try:
            data = node.sdo.upload(index, sub)
        except canopen.SdoAbortedError as e:
            # the error history has no entries yet
            assert index == 0x1003 and sub > 0 and e.code == NO_DATA, f"{where}: {e}"
            checked += 1
            continue
        if (index, sub) in LIVE:
            assert 0 <= int.from_bytes(data, "little") <= time.monotonic() - started + 2, where
        elif (index, sub) in EMPTY:
            assert data == b"", where
        elif (index, sub) in NO_NV:
            assert int.from_bytes(data, "little") == 0, where
        else:
            value = decode(var.data_type, data)
            if var.data_type == 0x0B:           # UNICODE_STRING: up to the terminator
                raw = data
                ends = [k for k in range(0, len(raw), 2) if raw[k:k + 2] == b"\0\0"]
                value = decode(0x0B, raw[:ends[0]] if ends else raw)
            want = expected(var, len(data))
            assert value == want, f"{where}: device {value!r}, EDS {want!r}"
        checked += 1
    assert checked > 150, checked
