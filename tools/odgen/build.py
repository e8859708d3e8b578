"""The core's build-time options (stack/include/co/co_config.h) and the
services a device description needs: a description that needs a service or
option the build leaves out is refused at generation time, with the option
that would have to be on (the core refuses the same device at co_node_init;
this says it before anything is compiled).

The defaults come from co_config.h itself (every `#define CO_X value` inside
its `#ifndef CO_X`); a build's overrides are the NAME=VALUE definitions of
its core library (cmake: co_core(<lib> NAME=VALUE ...), passed on by
co_device as --build NAME=VALUE).
"""
from __future__ import annotations

import re
from pathlib import Path

from model import Device, DescError

# in the source tree (tools/odgen -> stack/include) or installed
# (share/canopen-stack/odgen -> include/canopen-stack)
_HERE = Path(__file__).resolve()
CONFIG_HEADER = next((p for p in (
    _HERE.parents[2] / "stack" / "include" / "co" / "co_config.h",
    _HERE.parents[3] / "include" / "canopen-stack" / "co" / "co_config.h") if p.exists()),
    _HERE.parents[2] / "stack" / "include" / "co" / "co_config.h")


def _value(text: str) -> int | None:
    t = text.strip().rstrip("uUlL")
    try:
        return int(t, 0)
    except ValueError:
        return None  # an expression (e.g. CO_RX_SLOTS_MAX): not a switch


def defaults(header: Path = CONFIG_HEADER) -> dict[str, int]:
    text = header.read_text(encoding="utf-8")
    out = {}
    for m in re.finditer(r"#ifndef\s+(CO_\w+)\s*\n(?:\s*/\*.*?\*/\s*\n)?\s*#define\s+\1\s+([^\n]+)",
                         text, re.S):
        v = _value(m.group(2))
        if v is not None:
            out[m.group(1)] = v
    return out


def parse(defs: list[str]) -> dict[str, int]:
    """NAME=VALUE definitions of a core build (others, e.g. without a value, are ignored)."""
    out = {}
    for d in defs:
        for item in re.split(r"[;,]", d):
            name, sep, val = item.partition("=")
            if name == "CO_CONFIG_HEADER":
                continue  # the header's options come with --build-header
            if sep and name.startswith("CO_"):
                v = _value(val)
                if v is None:
                    raise DescError(f"build option {item!r}: not a number")
                out[name] = v
    return out


def header_options(path: Path) -> dict[str, int]:
    """The `#define CO_X VALUE` lines of a configuration header (CO_CONFIG_HEADER)."""
    out = {}
    for m in re.finditer(r"^\s*#\s*define\s+(CO_\w+)\s+([^\n]+)", path.read_text(encoding="utf-8"),
                         re.M):
        v = _value(re.sub(r"/\*.*?\*/|//.*", "", m.group(2)))
        if v is not None:
            out[m.group(1)] = v
    return out


# (option, what a device needs it for, test on the device)
def _has(dev: Device, *indexes: int) -> list[int]:
    return [o.index for o in dev.objects if o.index in indexes]


def check(dev: Device, build: dict[str, int]) -> None:
    """Raise DescError naming every service or option @p dev needs that
    the build (co_config.h defaults overridden by @p build) leaves out."""
    cfg = defaults()
    cfg.update(build)
    missing = []

    def need(option: str, what: str) -> None:
        missing.append(f"{what} needs {option}=1 (this build: {option}={cfg.get(option)})")

    if not cfg.get("CO_TIME", 1) and _has(dev, 0x1012):
        need("CO_TIME", "TIME (object 0x1012)")
    if not cfg.get("CO_SYNC_PRODUCER", 1) and _has(dev, 0x1006):
        need("CO_SYNC_PRODUCER", "the SYNC producer (object 0x1006)")
    if not cfg.get("CO_ERROR_BEHAVIOUR", 1) and _has(dev, 0x1029):
        need("CO_ERROR_BEHAVIOUR", "error behaviour (object 0x1029)")
    found = _has(dev, 0x100C, 0x100D)
    if not cfg.get("CO_NODE_GUARDING", 1) and found:
        need("CO_NODE_GUARDING", "node guarding (object " +
             ", ".join(f"0x{i:04X}" for i in found) + ")")
    if not cfg.get("CO_LIMITS", 1) and dev.limits:
        need("CO_LIMITS", "value limits")
    if not cfg.get("CO_SDO_BLOCK", 1) and offers_block(dev):
        missing.append("block SDO (offered unless [sdo] transfers leaves out \"block\") needs "
                       "CO_SDO_BLOCK=1 (this build: CO_SDO_BLOCK=0)")
    if not cfg.get("CO_PERSONALITY", 1):
        # a core without block SDO answers block requests as SDO_NO_BLOCK
        # says (0x05040001): that setting is no deviation for it
        devs = [o for o in dev.options if o != "LSS" and
                not (o == "SDO_NO_BLOCK" and not cfg.get("CO_SDO_BLOCK", 1))]
        if dev.nodeid_object:
            devs.append(f"nodeid_object 0x{dev.nodeid_object:04X}")
        if devs:
            missing.append("the personality " + ", ".join(devs) + " needs CO_PERSONALITY=1 "
                           "(this build: CO_PERSONALITY=0, CiA 301 behaviour only)")
    if not cfg.get("CO_PDO_RTR", 1):
        rtr = [f"0x{o.index:04X}" for o in dev.objects if 0x1800 <= o.index <= 0x19FF
               for s in o.subs if s.sub == 2 and s.default in (252, 253)]
        if rtr:
            need("CO_PDO_RTR", "TPDO transmission type 252/253 (" + ", ".join(rtr) + ")")
    if not cfg.get("CO_PDO_BITWISE", 1):
        bits = sorted({f"0x{o.index:04X}" for o in dev.objects
                       if (0x1600 <= o.index <= 0x17FF) or (0x1A00 <= o.index <= 0x1BFF)
                       for s in o.subs if s.sub >= 1 and isinstance(s.default, int)
                       and (s.default & 7) != 0})
        if bits:
            need("CO_PDO_BITWISE", "a mapping length not a multiple of 8 (" + ", ".join(bits) + ")")
    if not cfg.get("CO_TPDO_CHANGE", 1):
        # settings of the change detection a core without it does not have
        # (with CO_PERSONALITY=0 the options are refused as deviations too)
        change = [o for o in dev.options
                  if o in ("TPDO_NO_CHANGE_DETECT", "TPDO_MASK_254", "TPDO_MASK_255")]
        if dev.tpdo_mask is not None:
            change.append(f"tpdo_mask 0x{dev.tpdo_mask:04X}")
        if change:
            need("CO_TPDO_CHANGE", "TPDO change detection settings (" + ", ".join(change) + ")")
    if not cfg.get("CO_LSS", 1) and "LSS" in dev.options:
        need("CO_LSS", "LSS ([device] lss)")
    if missing:
        raise DescError("the core this device is built with leaves out what it needs: "
                        + "; ".join(missing))


def offers_block(dev: Device) -> bool:
    return not ({"SDO_NO_BLOCK", "SDO_EXPEDITED_ONLY"} & set(dev.options))
