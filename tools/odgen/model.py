"""Device description model: load a device .toml, check it, normalise it.

Everything the three back ends (C, EDS, markdown) need is computed here, and
every mistake in a description is reported as a DescError naming the object
(index/sub) and the problem. The file name is added by the caller.
"""
from __future__ import annotations

import re
import tomllib
from dataclasses import dataclass, field
from pathlib import Path


class DescError(Exception):
    """A mistake in a device description."""


# CiA 301 basic data types: name -> (type index, size in bytes (0: variable), kind)
TYPES = {
    "BOOLEAN": (0x01, 1, "bool"),
    "INTEGER8": (0x02, 1, "int"),
    "INTEGER16": (0x03, 2, "int"),
    "INTEGER24": (0x10, 3, "int"),
    "INTEGER32": (0x04, 4, "int"),
    "INTEGER40": (0x12, 5, "int"),
    "INTEGER48": (0x13, 6, "int"),
    "INTEGER56": (0x14, 7, "int"),
    "INTEGER64": (0x15, 8, "int"),
    "UNSIGNED8": (0x05, 1, "uint"),
    "UNSIGNED16": (0x06, 2, "uint"),
    "UNSIGNED24": (0x16, 3, "uint"),
    "UNSIGNED32": (0x07, 4, "uint"),
    "UNSIGNED40": (0x18, 5, "uint"),
    "UNSIGNED48": (0x19, 6, "uint"),
    "UNSIGNED56": (0x1A, 7, "uint"),
    "UNSIGNED64": (0x1B, 8, "uint"),
    "REAL32": (0x08, 4, "real"),
    "REAL64": (0x11, 8, "real"),
    "VISIBLE_STRING": (0x09, 0, "vstr"),
    "OCTET_STRING": (0x0A, 0, "ostr"),
    "UNICODE_STRING": (0x0B, 0, "ustr"),
    "TIME_OF_DAY": (0x0C, 6, "time"),
    "TIME_DIFFERENCE": (0x0D, 6, "time"),
    "DOMAIN": (0x0F, 0, "domain"),
}

OBJECT_CODES = {"VAR": 0x07, "ARRAY": 0x08, "RECORD": 0x09, "DOMAIN": 0x02}
ACCESS = ("ro", "wo", "rw", "rwr", "rww", "const")
STORAGE = ("comm", "app", "none")

# Flags as in stack/include/co/co_od.h
F_R, F_W, F_CONST, F_MAP_T, F_MAP_R = 0x0001, 0x0002, 0x0004, 0x0008, 0x0010
F_ROM, F_HOOKIO, F_NODEID, F_LIMIT = 0x0020, 0x0040, 0x0080, 0x0100
FLAG_NAMES = [
    (F_R, "CO_SUB_R"), (F_W, "CO_SUB_W"), (F_CONST, "CO_SUB_CONST"),
    (F_MAP_T, "CO_SUB_MAP_T"), (F_MAP_R, "CO_SUB_MAP_R"), (F_ROM, "CO_SUB_ROM"),
    (F_HOOKIO, "CO_SUB_HOOKIO"), (F_NODEID, "CO_SUB_NODEID"), (F_LIMIT, "CO_SUB_LIMIT"),
]

CORE_HEADER = Path(__file__).resolve().parents[2] / "stack" / "include" / "co" / "co_node.h"


def core_options(header: Path = CORE_HEADER) -> dict[str, int]:
    """The CO_OPT_* personality options the core defines (name without prefix -> bit)."""
    text = header.read_text(encoding="utf-8")
    return {m.group(1): int(m.group(2), 16)
            for m in re.finditer(r"#define\s+CO_OPT_(\w+)\s+0x([0-9A-Fa-f]+)U?", text)}


def where(index: int, sub: int | None = None) -> str:
    return f"object 0x{index:04X}" + ("" if sub is None else f" sub {sub}")


def snake(text: str) -> str:
    s = re.sub(r"[^0-9A-Za-z]+", "_", text).strip("_").lower()
    return s or "value"


@dataclass
class Sub:
    index: int
    sub: int
    name: str
    type: str
    access: str
    pdo: bool = False
    default: object = None        # int / float / str / bytes / None (see kind)
    nodeid: bool = False          # default is $NODEID + default
    low: int | None = None
    high: int | None = None
    unit: str = ""
    storage: str = "app"          # comm / app / none (RAM values only)
    rom: bool = False             # value lives in the const ROM image
    hookio: bool = False          # no stored value: the entry's hook does the I/O
    size: int = 0                 # bytes: type size, or capacity for strings/DOMAIN
    description: str = ""
    field: str = ""               # C field name in the RAM/ROM struct
    elem: int = -1                # element number within an array field, -1: scalar field
    limit_slot: int = -1          # index into the limits table, -1: none

    @property
    def code(self) -> int:
        return TYPES[self.type][0]

    @property
    def kind(self) -> str:
        return TYPES[self.type][2]

    @property
    def fixed(self) -> int:
        return TYPES[self.type][1]

    @property
    def flags(self) -> int:
        f = {"ro": F_R, "wo": F_W, "rw": F_R | F_W, "rwr": F_R | F_W,
             "rww": F_R | F_W, "const": F_R | F_CONST}[self.access]
        if self.pdo:
            if self.access in ("ro", "rwr"):
                f |= F_MAP_T
            elif self.access in ("wo", "rww"):
                f |= F_MAP_R
            else:
                f |= F_MAP_T | F_MAP_R
        if self.rom:
            f |= F_ROM
        if self.hookio:
            f |= F_HOOKIO
        if self.nodeid:
            f |= F_NODEID
        if self.limit_slot >= 0:
            f |= F_LIMIT
        return f

    @property
    def placement(self) -> str:
        """'rom', 'none' (hook I/O) or the RAM storage group."""
        if self.hookio:
            return "hook"
        if self.rom:
            return "rom"
        return self.storage


@dataclass
class Obj:
    index: int
    name: str
    code: str                     # VAR / ARRAY / RECORD / DOMAIN
    subs: list[Sub] = field(default_factory=list)
    hook: bool = False
    description: str = ""
    prefix: str = ""              # C name prefix
    origin: str = ""              # where it came from ([device] key or [[object]])
    hook_slot: int = -1


@dataclass
class Device:
    name: str
    base: str                     # file/CMake name, e.g. generic-301
    cname: str                    # C identifier base, e.g. generic_301
    source: str
    objects: list[Obj]
    info: dict
    eds: dict
    options: list[str]
    option_bits: int
    boot_emcy_data: list[int] | None
    limits: list[tuple[int, int]]
    n_hooks: int

    def find(self, index: int, sub: int) -> Sub | None:
        for o in self.objects:
            if o.index == index:
                for s in o.subs:
                    if s.sub == sub:
                        return s
        return None


# ---------------------------------------------------------------- helpers

def _int_range(s: Sub) -> tuple[int, int]:
    n = s.fixed * 8
    if s.kind == "int":
        return -(1 << (n - 1)), (1 << (n - 1)) - 1
    if s.kind == "bool":
        return 0, 1
    return 0, (1 << n) - 1


def _check_keys(tbl: dict, allowed: set[str], what: str) -> None:
    unknown = sorted(set(tbl) - allowed)
    if unknown:
        raise DescError(f"{what}: unknown key(s) {', '.join(unknown)}")


def _text(value, what: str, key: str, allow_empty: bool = False) -> str:
    if not isinstance(value, str):
        raise DescError(f"{what}: {key} must be a string")
    if not allow_empty and not value:
        raise DescError(f"{what}: {key} is empty")
    if any(ord(c) < 0x20 or ord(c) > 0x7E for c in value):
        raise DescError(f"{what}: {key} {value!r} must be printable ASCII (EDS files are ASCII)")
    if ";" in value:
        raise DescError(f"{what}: {key} {value!r} must not contain ';' (EDS comment character)")
    if value != value.strip():
        raise DescError(f"{what}: {key} {value!r} has leading/trailing blanks (EDS drops them)")
    return value


SUB_KEYS = {"sub", "name", "type", "access", "pdo_mapping", "default", "low_limit",
            "high_limit", "unit", "storage", "hookio", "rom", "size", "description"}
OBJ_KEYS = {"index", "name", "object", "hook", "cname", "description", "storage",
            "subs", "array", "element", "sub0", "names", "defaults"}
VAR_KEYS = SUB_KEYS - {"sub", "name"}


def default_storage(index: int) -> str:
    # error register and history are run-time state; 0x1010/0x1011 read the
    # core's storage capability (never stored)
    if index in (0x1001, 0x1003, 0x1010, 0x1011):
        return "none"
    if 0x1000 <= index <= 0x1FFF:
        return "comm"
    return "app"


def _parse_default(s: Sub, raw, what: str) -> None:
    """Normalise raw (from TOML) into s.default / s.nodeid."""
    kind = s.kind
    if raw is None:
        s.default = None
        return
    if kind in ("int", "uint", "bool"):
        if isinstance(raw, bool):
            raw = int(raw)
        if isinstance(raw, str):
            m = re.fullmatch(r"\s*\$NODEID\s*(?:\+\s*(0[xX][0-9A-Fa-f]+|[0-9]+))?\s*", raw)
            if not m:
                raise DescError(f"{what}: default {raw!r} is not a number or \"$NODEID+n\"")
            if s.fixed not in (1, 2, 4):
                raise DescError(f"{what}: $NODEID defaults need an 8/16/32-bit type, not {s.type}")
            s.nodeid = True
            raw = int(m.group(1), 0) if m.group(1) else 0
        if not isinstance(raw, int):
            raise DescError(f"{what}: default {raw!r} is not an integer ({s.type})")
        lo, hi = _int_range(s)
        top = raw + (127 if s.nodeid else 0)
        if raw < lo or top > hi:
            raise DescError(f"{what}: default {raw} does not fit {s.type} [{lo}, {hi}]")
        s.default = raw
    elif kind == "real":
        if isinstance(raw, bool) or not isinstance(raw, (int, float)):
            raise DescError(f"{what}: default {raw!r} is not a number ({s.type})")
        if raw != raw or raw in (float("inf"), float("-inf")):
            raise DescError(f"{what}: default must be finite")
        s.default = float(raw)
    elif kind == "time":
        if isinstance(raw, dict):
            _check_keys(raw, {"ms", "days"}, what + " default")
            ms, days = raw.get("ms", 0), raw.get("days", 0)
            if not (0 <= ms < (1 << 28)) or not (0 <= days < (1 << 16)):
                raise DescError(f"{what}: default ms must be 0..2^28-1 and days 0..65535")
            raw = ms | (days << 32)
        if isinstance(raw, bool) or not isinstance(raw, int) or not (0 <= raw < (1 << 48)):
            raise DescError(f"{what}: default {raw!r} is not a 48-bit value or {{ms, days}}")
        s.default = raw
    elif kind == "vstr":
        s.default = _text(raw, what, "default", allow_empty=True)
    elif kind == "ustr":
        s.default = _text(raw, what, "default", allow_empty=True)
    elif kind in ("ostr", "domain"):
        if isinstance(raw, list):
            if not all(isinstance(b, int) and not isinstance(b, bool) and 0 <= b <= 255 for b in raw):
                raise DescError(f"{what}: default bytes must be 0..255")
            s.default = bytes(raw)
        elif isinstance(raw, str):
            try:
                s.default = bytes.fromhex(raw)
            except ValueError:
                raise DescError(f"{what}: default {raw!r} is not hex bytes (\"01 02 AB\")") from None
        else:
            raise DescError(f"{what}: default must be hex bytes or a list of bytes")


def encoded_default(s: Sub) -> bytes:
    """The default as wire bytes (strings: without padding)."""
    if s.default is None:
        return b""
    if s.kind == "vstr":
        return s.default.encode("ascii")
    if s.kind == "ustr":
        return s.default.encode("utf-16-le")
    if s.kind in ("ostr", "domain"):
        return s.default
    raise AssertionError(s.kind)


def make_sub(index: int, tbl: dict, obj_storage: str | None, what: str,
             allowed: set[str] = SUB_KEYS) -> Sub:
    _check_keys(tbl, allowed, what)
    sub = tbl.get("sub", 0)
    if isinstance(sub, bool) or not isinstance(sub, int) or not 0 <= sub <= 254:
        raise DescError(f"{what}: sub-index {sub!r} must be 0..254")
    what = where(index, sub)
    name = _text(tbl.get("name", ""), what, "name")
    if len(name) > 241:
        raise DescError(f"{what}: name longer than 241 characters")
    tname = tbl.get("type")
    if tname is None:
        raise DescError(f"{what}: data type missing (type = \"UNSIGNED8\" ...)")
    if not isinstance(tname, str) or tname.upper() not in TYPES:
        raise DescError(f"{what}: unknown data type {tname!r}")
    tname = tname.upper()
    access = tbl.get("access", "rw")
    if access not in ACCESS:
        raise DescError(f"{what}: unknown access {access!r} (one of {', '.join(ACCESS)})")
    pdo = tbl.get("pdo_mapping", None)
    if pdo is not None and not isinstance(pdo, bool):
        raise DescError(f"{what}: pdo_mapping must be true or false")
    if access in ("rwr", "rww"):
        if pdo is False:
            raise DescError(f"{what}: access {access} means PDO-mappable; drop pdo_mapping = false")
        pdo = True
    pdo = bool(pdo)
    storage = tbl.get("storage", obj_storage or default_storage(index))
    if storage not in STORAGE:
        raise DescError(f"{what}: unknown storage {storage!r} (one of {', '.join(STORAGE)})")
    hookio = tbl.get("hookio", False)
    rom = tbl.get("rom", access == "const")
    if not isinstance(hookio, bool) or not isinstance(rom, bool):
        raise DescError(f"{what}: hookio and rom must be true or false")
    s = Sub(index=index, sub=sub, name=name, type=tname, access=access, pdo=pdo,
            storage=storage, rom=rom, hookio=hookio,
            unit=_text(tbl.get("unit", ""), what, "unit", allow_empty=True),
            description=_text(tbl.get("description", ""), what, "description", allow_empty=True))
    if rom and access not in ("ro", "const"):
        raise DescError(f"{what}: rom = true needs access ro or const, not {access}")
    if rom and hookio:
        raise DescError(f"{what}: a value is either in ROM or hook I/O, not both")
    if access == "const" and not rom:
        raise DescError(f"{what}: const values live in ROM (drop rom = false)")
    if pdo and s.fixed == 0:
        raise DescError(f"{what}: {tname} cannot be PDO-mapped (only fixed-size types)")
    _parse_default(s, tbl.get("default"), what)
    if s.nodeid and (rom or hookio):
        raise DescError(f"{what}: a $NODEID default needs a RAM value (not ROM/hook I/O)")
    if hookio and s.default is not None:
        raise DescError(f"{what}: a hook I/O value has no default")
    # size
    size = tbl.get("size")
    if s.fixed:
        if size is not None and size != s.fixed:
            raise DescError(f"{what}: size {size} differs from the size of {tname} ({s.fixed})")
        s.size = s.fixed
    else:
        enc = len(encoded_default(s))
        if size is None:
            size = enc
        if isinstance(size, bool) or not isinstance(size, int) or size < 0 or size > 0xFFFF:
            raise DescError(f"{what}: size {size!r} must be 0..65535 bytes")
        if size < enc:
            raise DescError(f"{what}: default is {enc} bytes, more than size {size}")
        if size == 0 and not hookio:
            raise DescError(f"{what}: {tname} needs a size (capacity in bytes) or hookio = true")
        if s.kind == "ustr" and size % 2:
            raise DescError(f"{what}: UNICODE_STRING size must be even (UTF-16)")
        s.size = size
    # limits
    lo, hi = tbl.get("low_limit"), tbl.get("high_limit")
    if lo is not None or hi is not None:
        if s.kind not in ("int", "uint"):
            raise DescError(f"{what}: limits are only supported on integer types, not {tname}"
                            + (" (the core does not check REAL limits; use a hook)"
                               if s.kind == "real" else ""))
        tlo, thi = _int_range(s)
        lo = tlo if lo is None else lo
        hi = thi if hi is None else hi
        for v in (lo, hi):
            if isinstance(v, bool) or not isinstance(v, int) or not tlo <= v <= thi:
                raise DescError(f"{what}: limit {v!r} does not fit {tname} [{tlo}, {thi}]")
        if lo > hi:
            raise DescError(f"{what}: low_limit {lo} is above high_limit {hi}")
        s.low, s.high = lo, hi
        if s.default is not None:
            first = s.default + (1 if s.nodeid else 0)
            last = s.default + (127 if s.nodeid else 0)
            if first < lo or last > hi:
                shown = f"$NODEID+{s.default}" if s.nodeid else str(s.default)
                raise DescError(f"{what}: default {shown} is out of limits [{lo}, {hi}]")
    return s


def _make_object(tbl: dict, what: str) -> Obj:
    index = tbl.get("index")
    if isinstance(index, bool) or not isinstance(index, int) or not 0x1000 <= index <= 0xFFFF:
        raise DescError(f"{what}: index {index!r} must be 0x1000..0xFFFF")
    what = where(index)
    _check_keys(tbl, OBJ_KEYS | VAR_KEYS, what)
    name = _text(tbl.get("name", ""), what, "name")
    has_subs = "subs" in tbl or "array" in tbl
    code = tbl.get("object", ("ARRAY" if "array" in tbl else "RECORD") if has_subs else
                   ("DOMAIN" if str(tbl.get("type", "")).upper() == "DOMAIN" else "VAR"))
    if code not in OBJECT_CODES:
        raise DescError(f"{what}: unknown object type {code!r} (VAR, ARRAY, RECORD, DOMAIN)")
    hook = tbl.get("hook", False)
    if not isinstance(hook, bool):
        raise DescError(f"{what}: hook must be true or false")
    prefix = tbl.get("cname", f"x{index:04X}")
    if not isinstance(prefix, str) or not re.fullmatch(r"[A-Za-z_][A-Za-z0-9_]*", prefix):
        raise DescError(f"{what}: cname {prefix!r} is not a C identifier")
    obj = Obj(index=index, name=name, code=code, hook=hook, prefix=prefix,
              description=_text(tbl.get("description", ""), what, "description", allow_empty=True),
              origin="[[object]]")
    storage = tbl.get("storage")
    if code in ("VAR", "DOMAIN"):
        if has_subs:
            raise DescError(f"{what}: a {code} has no subs/array (use ARRAY or RECORD)")
        var = {k: v for k, v in tbl.items() if k in VAR_KEYS}
        var["name"] = name
        if code == "DOMAIN":
            var.setdefault("type", "DOMAIN")
            if var["type"] != "DOMAIN":
                raise DescError(f"{what}: a DOMAIN object has data type DOMAIN")
        obj.subs.append(make_sub(index, var, storage, what))
        obj.hook = obj.hook or obj.subs[0].hookio
        return obj
    stray = sorted(set(tbl) & (VAR_KEYS - {"storage", "description"}))
    if stray:
        raise DescError(f"{what}: {', '.join(stray)} belong(s) to a sub-entry of a {code}")
    subs: list[Sub] = []
    if "array" in tbl:
        n = tbl["array"]
        if isinstance(n, bool) or not isinstance(n, int) or not 1 <= n <= 254:
            raise DescError(f"{what}: array = {n!r} must be 1..254 elements")
        elem = tbl.get("element")
        if not isinstance(elem, dict):
            raise DescError(f"{what}: array = {n} needs element = {{ name = ..., type = ... }}")
        names = tbl.get("names")
        defaults = tbl.get("defaults")
        if names is not None and (not isinstance(names, list) or len(names) != n):
            raise DescError(f"{what}: names must list {n} names")
        if defaults is not None and (not isinstance(defaults, list) or len(defaults) > n):
            raise DescError(f"{what}: defaults must list at most {n} values")
        for k in range(1, n + 1):
            e = dict(elem)
            if "sub" in e:
                raise DescError(f"{what}: element has no sub (the array numbers them 1..{n})")
            e["sub"] = k
            if names is not None:
                e["name"] = names[k - 1]
            else:
                e["name"] = f"{elem.get('name', '')} {k}".strip()
            if defaults is not None and k <= len(defaults):
                e["default"] = defaults[k - 1]
            subs.append(make_sub(index, e, storage, what))
        if "subs" in tbl:
            raise DescError(f"{what}: use either array = N or subs = [...], not both")
    elif "element" in tbl or "names" in tbl or "defaults" in tbl:
        raise DescError(f"{what}: element/names/defaults only go with array = N")
    else:
        lst = tbl.get("subs")
        if not isinstance(lst, list) or not lst or not all(isinstance(x, dict) for x in lst):
            raise DescError(f"{what}: subs must be a list of sub-entry tables")
        for x in lst:
            if "sub" not in x:
                raise DescError(f"{what}: a sub-entry without sub = <sub-index>")
            subs.append(make_sub(index, x, storage, what))
    sub0 = tbl.get("sub0")
    if sub0 is not None and any(s.sub == 0 for s in subs):
        raise DescError(f"{where(index, 0)}: given twice (sub0 and subs)")
    seen: set[int] = set()
    for s in subs:
        if s.sub in seen:
            raise DescError(f"{where(index, s.sub)}: duplicate sub-index")
        seen.add(s.sub)
    if not any(s.sub == 0 for s in subs):
        highest = max(s.sub for s in subs)
        s0 = {"name": "Number of entries" if code == "ARRAY" else "Highest sub-index supported",
              "type": "UNSIGNED8", "access": "const", "default": highest}
        if sub0 is not None:
            if not isinstance(sub0, dict):
                raise DescError(f"{where(index, 0)}: sub0 must be a table")
            s0.update(sub0)
        s0["sub"] = 0
        subs.insert(0, make_sub(index, s0, storage, what))
    subs.sort(key=lambda s: s.sub)
    s0 = subs[0]
    if s0.sub != 0 or s0.type != "UNSIGNED8":
        raise DescError(f"{where(index, 0)}: sub-index 0 of a {code} is UNSIGNED8")
    if code == "ARRAY":
        types = {s.type for s in subs[1:]}
        if len(types) > 1:
            raise DescError(f"{what}: the elements of an ARRAY share one data type "
                            f"(found {', '.join(sorted(types))})")
    obj.subs = subs
    obj.hook = obj.hook or any(s.hookio for s in subs)
    return obj


def _device_objects(dev: dict, what: str) -> list[Obj]:
    """Objects made from the [device] table: 0x1000, 0x1008, 0x1009, 0x100A, 0x1018."""
    out: list[Obj] = []

    def var(index, name, key, tname, access, value, size=None):
        t = {"name": name, "type": tname, "access": access, "default": value}
        if access == "ro":
            t["rom"] = True
        if size is not None:
            t["size"] = size
        o = Obj(index=index, name=name, code="VAR", prefix=f"x{index:04X}",
                origin=f"[device] {key}")
        o.subs.append(make_sub(index, t, None, f"{what} {key}"))
        out.append(o)

    if "device_type" in dev:
        var(0x1000, "Device type", "device_type", "UNSIGNED32", "ro", dev["device_type"])
    for index, key, name in ((0x1008, "device_name", "Manufacturer device name"),
                             (0x1009, "hw_version", "Manufacturer hardware version"),
                             (0x100A, "sw_version", "Manufacturer software version")):
        if key in dev:
            var(index, name, key, "VISIBLE_STRING", "const", dev[key])
    ids = ("vendor_id", "product_code", "revision", "serial")
    if any(k in dev for k in ids):
        if "vendor_id" not in dev:
            raise DescError(f"{what}: 0x1018 needs at least vendor_id")
        o = Obj(index=0x1018, name="Identity object", code="RECORD", prefix="x1018",
                origin="[device] vendor_id")
        subs = [{"sub": 0, "name": "Highest sub-index supported", "type": "UNSIGNED8",
                 "access": "const", "default": 4}]
        for k, (key, name) in enumerate(zip(ids, ("Vendor-ID", "Product code",
                                                   "Revision number", "Serial number")), 1):
            t = {"sub": k, "name": name, "type": "UNSIGNED32", "access": "ro"}
            if key in dev:
                t["default"] = dev[key]
                t["rom"] = True
            else:
                t["storage"] = "none"  # filled in by the application at run time
            subs.append(t)
        o.subs = [make_sub(0x1018, t, None, f"{what}") for t in subs]
        out.append(o)
    return out


DEVICE_KEYS = {"name", "vendor_name", "product_name", "order_code", "vendor_id", "product_code",
               "revision", "serial", "device_type", "device_name", "hw_version", "sw_version",
               "options", "boot_emcy_data", "baudrates", "description", "lss"}
EDS_KEYS = {"file_version", "file_revision", "date", "time", "author", "description"}
BAUDRATES = (10, 20, 50, 125, 250, 500, 800, 1000)


def _assign_fields(obj: Obj) -> None:
    """C field names; runs of equal consecutive elements 1..n become one C array."""
    subs = obj.subs
    if obj.code in ("VAR", "DOMAIN"):
        if subs[0].hookio:
            return
        subs[0].field = obj.prefix if obj.prefix != f"x{obj.index:04X}" else \
            f"{obj.prefix}_{snake(obj.name)}"
        return
    used: set[str] = set()

    def unique(base: str, s: Sub) -> str:
        name = base if base not in used else f"{base}_s{s.sub}"
        used.add(name)
        return name

    elems = [s for s in subs if s.sub > 0]
    stems = {re.sub(r"_?\d+$", "", snake(s.name)) for s in elems}
    groupable = (len(elems) >= 2 and
                 (obj.code == "ARRAY" or len(stems) == 1) and
                 [s.sub for s in elems] == list(range(1, len(elems) + 1)) and
                 len({(s.type, s.placement) for s in elems}) == 1 and
                 elems[0].fixed != 0 and elems[0].placement != "hook")
    for s in subs:
        if s.placement == "hook":
            continue
        if groupable and s.sub > 0:
            s.field = f"{obj.prefix}_{snake(obj.name)}"
            if s.sub == 1:
                s.field = unique(s.field, s)
            else:
                s.field = elems[0].field
            s.elem = s.sub - 1
        else:
            s.field = unique(f"{obj.prefix}_{snake(s.name)}", s)


def load(path: str | Path, base: str | None = None) -> Device:
    path = Path(path)
    try:
        data = tomllib.loads(path.read_text(encoding="utf-8"))
    except tomllib.TOMLDecodeError as e:
        raise DescError(f"TOML syntax: {e}") from None
    except OSError as e:
        raise DescError(f"cannot read: {e.strerror}") from None
    _check_keys(data, {"device", "eds", "object"}, "top level")
    dev = data.get("device")
    if not isinstance(dev, dict):
        raise DescError("[device] table missing")
    _check_keys(dev, DEVICE_KEYS, "[device]")
    name = _text(dev.get("name", ""), "[device]", "name")
    base = base or path.stem
    cname = re.sub(r"[^0-9A-Za-z_]", "_", base)
    if not re.fullmatch(r"[A-Za-z_][A-Za-z0-9_]*", cname):
        raise DescError(f"device base name {base!r} does not make a C identifier")

    known = core_options()
    opts = dev.get("options", [])
    if not isinstance(opts, list):
        raise DescError("[device] options must be a list of option names")
    bits = 0
    for o in opts:
        if o not in known:
            raise DescError(f"[device] options: unknown option {o!r} "
                            f"(known: {', '.join(sorted(known))})")
        bits |= known[o]
    bed = dev.get("boot_emcy_data")
    if bed is not None:
        if (not isinstance(bed, list) or len(bed) != 5 or
                not all(isinstance(b, int) and not isinstance(b, bool) and 0 <= b <= 255 for b in bed)):
            raise DescError("[device] boot_emcy_data must be 5 bytes")
        if "BOOT_EMCY" not in opts:
            raise DescError("[device] boot_emcy_data is only sent with option BOOT_EMCY")
    elif "BOOT_EMCY" in opts:
        raise DescError("[device] option BOOT_EMCY needs boot_emcy_data (5 bytes)")
    rates = dev.get("baudrates", list(BAUDRATES))
    if not isinstance(rates, list) or any(r not in BAUDRATES for r in rates):
        raise DescError(f"[device] baudrates must list kbit/s out of {BAUDRATES}")
    info = {
        "name": name,
        "vendor_name": _text(dev.get("vendor_name", "unknown"), "[device]", "vendor_name"),
        "product_name": _text(dev.get("product_name", name), "[device]", "product_name"),
        "order_code": _text(dev.get("order_code", ""), "[device]", "order_code", True),
        "description": _text(dev.get("description", ""), "[device]", "description", True),
        "baudrates": rates,
        "lss": bool(dev.get("lss", False)),
    }
    for k in ("vendor_id", "product_code", "revision"):
        v = dev.get(k, 0)
        if isinstance(v, bool) or not isinstance(v, int) or not 0 <= v <= 0xFFFFFFFF:
            raise DescError(f"[device] {k} must be an UNSIGNED32")
        info[k] = v
    eds = data.get("eds", {})
    if not isinstance(eds, dict):
        raise DescError("[eds] must be a table")
    _check_keys(eds, EDS_KEYS, "[eds]")
    date = eds.get("date", "2025-01-01")
    if not isinstance(date, str) or not re.fullmatch(r"\d{4}-\d{2}-\d{2}", date):
        raise DescError("[eds] date must be \"YYYY-MM-DD\"")
    time = eds.get("time", "12:00")
    if not isinstance(time, str) or not re.fullmatch(r"\d{2}:\d{2}", time):
        raise DescError("[eds] time must be \"hh:mm\" (24 h)")
    eds_info = {
        "file_version": eds.get("file_version", 1),
        "file_revision": eds.get("file_revision", 0),
        "date": date, "time": time,
        "author": _text(eds.get("author", "tools/odgen"), "[eds]", "author"),
        "description": _text(eds.get("description", info["description"] or name), "[eds]",
                             "description"),
    }
    for k in ("file_version", "file_revision"):
        v = eds_info[k]
        if isinstance(v, bool) or not isinstance(v, int) or not 0 <= v <= 255:
            raise DescError(f"[eds] {k} must be 0..255")

    objects = _device_objects(dev, "[device]")
    origins = {o.index: o.origin for o in objects}
    raw_objs = data.get("object", [])
    if not isinstance(raw_objs, list):
        raise DescError("object must be an array of tables ([[object]])")
    for k, tbl in enumerate(raw_objs):
        o = _make_object(tbl, f"[[object]] #{k + 1}")
        if o.index in origins:
            raise DescError(f"{where(o.index)}: duplicate index (already given by {origins[o.index]})")
        origins[o.index] = f"[[object]] #{k + 1}"
        objects.append(o)
    objects.sort(key=lambda o: o.index)
    if not objects:
        raise DescError("no objects")
    for mandatory in (0x1000, 0x1001, 0x1018):
        if mandatory not in origins:
            raise DescError(f"{where(mandatory)}: mandatory object missing (CiA 301)")

    # hooks, fields, limits
    slot = 0
    limits: list[tuple[int, int]] = []
    fields: dict[str, str] = {}
    for o in objects:
        if o.hook:
            o.hook_slot = slot
            slot += 1
        _assign_fields(o)
        for s in o.subs:
            if s.field and s.elem <= 0:
                other = fields.get(s.field)
                if other is not None:
                    raise DescError(f"{where(o.index, s.sub)}: C field name {s.field} "
                                    f"already used by {other} (set cname)")
                fields[s.field] = where(o.index, s.sub)
            if s.low is not None:
                pair = (s.low, s.high)
                if pair not in limits:
                    limits.append(pair)
                s.limit_slot = limits.index(pair)
    if slot > 255:
        raise DescError(f"{slot} hooked objects; at most 255")

    device = Device(name=name, base=base, cname=cname, source=str(path), objects=objects,
                    info=info, eds=eds_info, options=list(opts), option_bits=bits,
                    boot_emcy_data=bed, limits=limits, n_hooks=slot)
    _check_pdo_mappings(device)
    return device


def _check_pdo_mappings(dev: Device) -> None:
    """Default PDO mappings (0x1600-0x17FF RPDO, 0x1A00-0x1BFF TPDO)."""
    for o in dev.objects:
        if 0x1600 <= o.index <= 0x17FF:
            direction, need, pdo = "RPDO", F_MAP_R, "an RPDO"
        elif 0x1A00 <= o.index <= 0x1BFF:
            direction, need, pdo = "TPDO", F_MAP_T, "a TPDO"
        else:
            continue
        s0 = o.subs[0]
        count = s0.default or 0
        if count > len(o.subs) - 1:
            raise DescError(f"{where(o.index, 0)}: {count} mapped objects but only "
                            f"{len(o.subs) - 1} mapping entries")
        total = 0
        for s in o.subs[1:]:
            if s.type != "UNSIGNED32":
                raise DescError(f"{where(o.index, s.sub)}: a mapping entry is UNSIGNED32")
            v = s.default or 0
            if v == 0:
                if s.sub <= count:
                    raise DescError(f"{where(o.index, s.sub)}: empty mapping entry within "
                                    f"the {count} mapped objects")
                continue
            idx, sub, bits = v >> 16, (v >> 8) & 0xFF, v & 0xFF
            target = dev.find(idx, sub)
            what = f"{where(o.index, s.sub)}: default mapping 0x{v:08X} maps 0x{idx:04X} sub {sub}"
            if target is None:
                raise DescError(f"{what}, which does not exist")
            if not target.flags & need:
                raise DescError(f"{what}, which is not mappable into {pdo} "
                                f"(access {target.access}, pdo_mapping "
                                f"{'true' if target.pdo else 'false'})")
            if bits != target.fixed * 8:
                raise DescError(f"{what} with {bits} bits; {target.type} has {target.fixed * 8}")
            if s.sub <= count:
                total += bits
        if total > 64:
            raise DescError(f"{where(o.index)}: default {direction} mapping is {total} bits "
                            f"long, more than 64")
