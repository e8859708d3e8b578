"""The main job's master (tools/demo/master.py, issue 16): it runs to its end
on the bus with the conformance device (the PDO step at SYNC included, where
it once hung on a loaded machine), and a step that does not end is reported
as hung, with where it waits, instead of hanging the demo."""
from __future__ import annotations

import re
import subprocess
import sys
import threading
import types

import pytest

from conftest import DAEMON, IFACE, ROOT

MASTER = ROOT / "tools" / "demo" / "master.py"


def test_demo_runs_to_the_end(tmp_path):
    r = subprocess.run([sys.executable, str(MASTER), "--daemon", str(DAEMON), "--iface", IFACE,
                        "--devices", "generic-301", "--out", str(tmp_path)],
                       capture_output=True, text=True, timeout=300)
    out = r.stdout + r.stderr
    assert r.returncode == 0, out
    assert re.search(r"demo: \d+ steps ok, 0 failed", out), out
    # the PDO step: three SYNCs, each answered by TPDO1 with what RPDO1 wrote
    assert len(re.findall(r"TPDO1: 0x2102 = 0x12345678, 0x2101 = 0xBEEF", out)) == 3, out


@pytest.fixture
def master():
    sys.path.insert(0, str(MASTER.parent))
    try:
        import master as m
    finally:
        sys.path.pop(0)
    return m


def test_a_hung_step_is_reported_not_waited_for(master, capsys):
    demo = types.SimpleNamespace(results=[])
    never = threading.Event()

    def waits_forever():
        never.wait()

    def fails():
        raise TimeoutError("no TPDO1 after SYNC")

    master.Demo.step(demo, "fails", fails, timeout=5.0)      # reported, the demo goes on
    with pytest.raises(master.StepHung):
        master.Demo.step(demo, "hangs", waits_forever, timeout=0.3)
    never.set()
    out = capsys.readouterr().out
    assert demo.results == [("fails", False, "TimeoutError: no TPDO1 after SYNC"),
                            ("hangs", False, "hung: no end after 0.3 s")]
    assert "FAILED: no end after 0.3 s; the step waits in:" in out
    assert "in waits_forever" in out and "never.wait()" in out
