"""The plugin's own tests: the daemon of the build under test
($CODEV_BUILD_DIR, as in tests/integration) on the suite's interface
($CO_IFACE). pytester runs the README's example."""
from __future__ import annotations

import os
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
pytest_plugins = ["pytester"]

_build = Path(os.environ.get("CODEV_BUILD_DIR", ROOT / "build" / "host"))
os.environ.setdefault("CANOPEN_DEVICE", str((_build if _build.is_absolute() else ROOT / _build)
                                            / "bin" / "canopen-device"))
if "CO_IFACE" in os.environ:
    os.environ.setdefault("CANOPEN_IFACE", os.environ["CO_IFACE"])
