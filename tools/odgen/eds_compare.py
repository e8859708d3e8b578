"""Semantic comparison of two EDS/DCF files (CiA 306), attribute by attribute.

    eds_compare.py SOURCE.eds OTHER.eds      exit 0: OTHER loses nothing of SOURCE

Both files are read with cia306.read_eds and brought to a canonical form:
numbers by value (0x0A == 10 == 012), signed values given in two's
complement by value, "$NODEID+0x180" == "0x180+$NODEID", REAL by value,
OCTET_STRING/DOMAIN by bytes, AccessType in lower case, CompactSubObj
expanded into sub-entries, a limit equal to its type's bound == no limit,
absent PDOMapping/ObjFlags == 0, absent Denotation == empty, absent
DummyUsage entry == 0, dates and times by value (12:00AM == 00:00).

differences(source, other) lists what OTHER loses or changes: every object
and sub-entry with every attribute (ParameterName, ObjectType, DataType,
AccessType, DefaultValue, PDOMapping, LowLimit, HighLimit, ObjFlags,
ParameterValue, Denotation, ObjectLinks, and any other key), every FileInfo,
DeviceInfo and DeviceComissioning entry the source has, DummyUsage, the
Comments lines and every other section and key. Objects OTHER adds count too;
FileInfo/DeviceInfo entries it adds do not (they state defaults the source
left out). The object lists are derived data (they must match the object
sections, which read_eds checks) and SubNumber is the number of sub-entries.
"""
from __future__ import annotations

import re
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from cia306 import (DATA_TYPES, Eds, EdsError, EdsObject, EdsSub, int_range,  # noqa: E402
                    parse_int, read_eds, value)

NUMERIC_INFO = {"vendornumber", "productnumber", "revisionnumber", "granularity",
                "nrofrxpdo", "nroftxpdo", "simplebootupmaster", "simplebootupslave",
                "dynamicchannelssupported", "compactpdo", "groupmessaging", "lss_supported",
                "fileversion", "filerevision", "nodeid", "baudrate", "netnumber",
                "canopenmanager", "lss_serialnumber"}


def _num(text: str | None):
    if text is None:
        return None
    try:
        return parse_int(text)
    except ValueError:
        return ("text", text)


def _val(text: str | None, dtype: int | None):
    try:
        return value(text, dtype)
    except ValueError:
        return ("text", text.strip() if text else text)


def _limit(text: str | None, dtype: int | None, low: bool):
    v = _val(text, dtype)
    if isinstance(v, int) and dtype in DATA_TYPES:
        lo, hi = int_range(dtype)
        if v == (lo if low else hi):
            return None   # the type's bound: no limit
    return v


def _time(text: str):
    m = re.fullmatch(r"\s*(\d{1,2}):(\d{2})\s*([AaPp][Mm])?\s*", text)
    if not m:
        return ("text", text)
    h, mi, ap = int(m.group(1)), int(m.group(2)), (m.group(3) or "").upper()
    if ap:
        h = h % 12 + (12 if ap == "PM" else 0)
    return (h, mi)


def _date(text: str):
    m = re.fullmatch(r"\s*(\d{1,2})-(\d{1,2})-(\d{4})\s*", text)
    return (int(m.group(3)), int(m.group(1)), int(m.group(2))) if m else ("text", text)


def canon_info(d: dict[str, str] | None) -> dict:
    out = {}
    for k, v in (d or {}).items():
        low = k.lower()
        if low in NUMERIC_INFO or low.startswith("baudrate_"):
            out[low] = _num(v)
        elif low.endswith("time"):
            out[low] = _time(v)
        elif low.endswith("date"):
            out[low] = _date(v)
        else:
            out[low] = v
    return out


def canon_sub(s: EdsSub) -> dict:
    dt = s.data_type
    d = {
        "ParameterName": s.name,
        "ObjectType": s.object_type,
        "DataType": dt,
        "AccessType": s.access.lower() if s.access else None,
        "DefaultValue": _val(s.default, dt),
        "PDOMapping": _num(s.pdo) or 0,
        "LowLimit": _limit(s.low, dt, True),
        "HighLimit": _limit(s.high, dt, False),
        "ObjFlags": _num(s.obj_flags) or 0,
        "ParameterValue": _val(s.param_value, dt),
        "Denotation": s.denotation or None,
    }
    for k, v in s.extra.items():
        d["+" + k.lower()] = v
    return d


def canon_object(o: EdsObject) -> dict:
    d = {"ParameterName": o.name, "ObjectType": o.object_type,
         "ObjFlags": _num(o.obj_flags) or 0, "ObjectLinks": list(o.links or [])}
    for k, v in o.extra.items():
        d["+" + k.lower()] = v
    d["subs"] = {k: canon_sub(s) for k, s in o.subs.items()}
    return d


def _show(v) -> str:
    if isinstance(v, tuple) and len(v) == 2 and v[0] == "text":
        return repr(v[1])
    if isinstance(v, int) and not isinstance(v, bool):
        return f"{v} (0x{v:X})" if v >= 10 else str(v)
    return repr(v) if not hasattr(v, "offset") else str(v)


def _dict_diffs(where: str, a: dict, b: dict, losses_only: bool = False) -> list[str]:
    out = []
    for k in a:
        if k not in b:
            out.append(f"{where}: {k.lstrip('+')} {_show(a[k])} lost")
        elif a[k] != b[k]:
            out.append(f"{where}: {k.lstrip('+')} {_show(a[k])} -> {_show(b[k])}")
    if not losses_only:
        for k in b:
            if k not in a:
                out.append(f"{where}: {k.lstrip('+')} {_show(b[k])} added")
    return out


def object_differences(a: EdsObject, b: EdsObject) -> list[str]:
    ca, cb = canon_object(a), canon_object(b)
    sa, sb = ca.pop("subs"), cb.pop("subs")
    where = f"object 0x{a.index:04X}"
    out = _dict_diffs(where, ca, cb)
    for k in sorted(set(sa) | set(sb)):
        w = f"{where} sub {k}"
        if k not in sb:
            out.append(f"{w}: lost")
        elif k not in sa:
            out.append(f"{w}: added")
        else:
            out += _dict_diffs(w, sa[k], sb[k])
    return out


def _sections(e: Eds) -> dict[str, dict[str, str]]:
    """Sections the reader does not interpret, and the extra keys of those it does."""
    out = {name.lower(): {k.lower(): key.value for k, key in sec.keys.items()}
           for name, sec in e.other.items()}
    for name, keys in e.extra_keys.items():
        out.setdefault(name.lower(), {}).update({k.lower(): v for k, v in keys.items()})
    return out


def differences(src: Eds, out: Eds) -> list[str]:
    diffs: list[str] = []
    diffs += _dict_diffs("[FileInfo]", canon_info(src.file_info), canon_info(out.file_info),
                         losses_only=True)
    diffs += _dict_diffs("[DeviceInfo]", canon_info(src.device_info),
                         canon_info(out.device_info), losses_only=True)
    if src.commissioning is not None:
        diffs += _dict_diffs("[DeviceComissioning]", canon_info(src.commissioning),
                             canon_info(out.commissioning or {}), losses_only=True)
    da, db = src.dummy_usage or {}, out.dummy_usage or {}
    for k in range(1, 8):
        va, vb = _num(da.get(k, "0")), _num(db.get(k, "0"))
        if va != vb:
            diffs.append(f"[DummyUsage] Dummy{k:04d}: {_show(va)} -> {_show(vb)}")
    if (src.comments or []) != (out.comments or []):
        diffs.append(f"[Comments]: {src.comments!r} -> {out.comments!r}")
    sa, sb = _sections(src), _sections(out)
    for name, keys in sa.items():
        if name not in sb and name in out.sections:   # interpreted, without extra keys
            diffs += _dict_diffs(f"[{name}]", keys, {}, losses_only=True)
        elif name not in sb:
            diffs.append(f"[{name}]: section lost")
        else:
            diffs += _dict_diffs(f"[{name}]", keys, sb[name], losses_only=True)
    for index in sorted(set(src.objects) | set(out.objects)):
        if index not in out.objects:
            diffs.append(f"object 0x{index:04X}: lost")
        elif index not in src.objects:
            diffs.append(f"object 0x{index:04X}: added")
        else:
            diffs += object_differences(src.objects[index], out.objects[index])
    return diffs


def main(argv: list[str] | None = None) -> int:
    args = sys.argv[1:] if argv is None else argv
    if len(args) != 2:
        print(__doc__.split("\n\n")[1].strip(), file=sys.stderr)
        return 2
    try:
        a, b = read_eds(args[0]), read_eds(args[1])
    except EdsError as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    diffs = differences(a, b)
    for d in diffs:
        print(d)
    print(f"{len(a.objects)} objects, "
          f"{sum(len(o.subs) for o in a.objects.values())} sub-entries compared: "
          f"{len(diffs)} difference(s)", file=sys.stderr)
    return 1 if diffs else 0


if __name__ == "__main__":
    sys.exit(main())
