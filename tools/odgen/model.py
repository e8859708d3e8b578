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
F_COB16 = 0x0200    # (the C tables only: a COB-ID in its 16-bit form, gen_c.Cob16Sub)
FLAG_NAMES = [
    (F_R, "CO_SUB_R"), (F_W, "CO_SUB_W"), (F_CONST, "CO_SUB_CONST"),
    (F_MAP_T, "CO_SUB_MAP_T"), (F_MAP_R, "CO_SUB_MAP_R"), (F_ROM, "CO_SUB_ROM"),
    (F_HOOKIO, "CO_SUB_HOOKIO"), (F_NODEID, "CO_SUB_NODEID"), (F_LIMIT, "CO_SUB_LIMIT"),
    (F_COB16, "CO_SUB_COB16"),
]

def core_options() -> dict[str, int]:
    """The personality deviations the core implements, by name -> their bit in
    Device.option_bits (the C side is typed: co_settings.h, personality.SETTINGS)."""
    from personality import SETTINGS
    return {name: bit for name, (bit, _, _) in SETTINGS.items()}


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
    parameter_value: object = None  # DCF ParameterValue (same kinds as default); EDS only
    pv_nodeid: bool = False       # parameter_value is $NODEID + parameter_value
    denotation: str = ""          # DCF Denotation; EDS only
    obj_flags: int | None = None  # CiA 306 ObjFlags of this section
    eds_keys: dict = field(default_factory=dict)   # further EDS keys, written verbatim
    eds_low: int | None = None    # the limits as the EDS states them (None: not given)
    eds_high: int | None = None
    low_nodeid: bool = False      # eds_low is $NODEID + eds_low
    high_nodeid: bool = False
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
    compact: bool = False         # EDS: CompactSubObj form
    links: list[int] | None = None  # EDS: [xxxxObjectLinks]
    obj_flags: int | None = None  # EDS: ObjFlags of the ARRAY/RECORD section
    eds_keys: dict = field(default_factory=dict)   # further keys of that section


@dataclass
class RawObj:
    """An object only the EDS has: its sections verbatim (imported objects the
    C dictionary cannot hold; eds_only says why)."""
    index: int
    name: str
    reason: str
    sections: list[tuple[str, dict[str, str]]]


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
    eds_only: list[RawObj] = field(default_factory=list)
    dcf: dict | None = None       # [DeviceComissioning] of a DCF
    tpdo_mask: int | None = None  # index of TPDO1's change mask (options TPDO_MASK_254/255)
    nodeid_object: int | None = None  # node-ID object taken at Reset Communication

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
    if not value.isprintable():
        raise DescError(f"{what}: {key} {value!r} must be printable text on one line")
    if re.search(r"\s;", value):
        raise DescError(f"{what}: {key} {value!r}: ';' after a blank starts an EDS comment")
    if value != value.strip():
        raise DescError(f"{what}: {key} {value!r} has leading/trailing blanks (EDS drops them)")
    return value


SUB_KEYS = {"sub", "name", "type", "access", "pdo_mapping", "default", "low_limit",
            "high_limit", "unit", "storage", "hookio", "rom", "size", "description",
            "parameter_value", "denotation", "obj_flags", "eds_keys"}
OBJ_KEYS = {"index", "name", "object", "hook", "cname", "description", "storage",
            "subs", "array", "element", "sub0", "names", "defaults", "compact", "links",
            "obj_flags", "eds_keys"}
# keys of an ARRAY/RECORD that describe the object section itself
OBJ_SECTION_KEYS = {"storage", "description", "obj_flags", "eds_keys"}
RAW_KEYS = {"index", "eds_only", "sections"}
VAR_KEYS = SUB_KEYS - {"sub", "name"}


def default_storage(index: int) -> str:
    # error register and history are run-time state; 0x1010/0x1011 read the
    # core's storage capability (never stored)
    if index in (0x1001, 0x1003, 0x1010, 0x1011):
        return "none"
    if 0x1000 <= index <= 0x1FFF:
        return "comm"
    return "app"


NODEID_RE = re.compile(r"\s*(?:\$NODEID\s*(?:\+\s*(0[xX][0-9A-Fa-f]+|[0-9]+))?|"
                       r"(0[xX][0-9A-Fa-f]+|[0-9]+)\s*\+\s*\$NODEID)\s*")


def _parse_value(s: Sub, raw, what: str, key: str = "default") -> tuple[object, bool]:
    """A value (default or parameter_value) of s from TOML: (value, relative to
    the node-ID)."""
    kind = s.kind
    if raw is None:
        return None, False
    nodeid = False
    if kind in ("int", "uint", "bool"):
        if isinstance(raw, bool):
            raw = int(raw)
        if isinstance(raw, str):
            m = NODEID_RE.fullmatch(raw)
            if not m:
                raise DescError(f"{what}: {key} {raw!r} is not a number or \"$NODEID+n\"")
            if s.fixed not in (1, 2, 4):
                raise DescError(f"{what}: $NODEID {key}s need an 8/16/32-bit type, not {s.type}")
            nodeid = True
            off = m.group(1) or m.group(2)
            raw = int(off, 0) if off else 0
        if not isinstance(raw, int):
            raise DescError(f"{what}: {key} {raw!r} is not an integer ({s.type})")
        lo, hi = _int_range(s)
        top = raw + (127 if nodeid else 0)
        if raw < lo or top > hi:
            raise DescError(f"{what}: {key} {raw} does not fit {s.type} [{lo}, {hi}]")
        return raw, nodeid
    if kind == "real":
        if isinstance(raw, bool) or not isinstance(raw, (int, float)):
            raise DescError(f"{what}: {key} {raw!r} is not a number ({s.type})")
        if raw != raw or raw in (float("inf"), float("-inf")):
            raise DescError(f"{what}: {key} must be finite")
        return float(raw), False
    if kind == "time":
        if isinstance(raw, dict):
            _check_keys(raw, {"ms", "days"}, f"{what} {key}")
            ms, days = raw.get("ms", 0), raw.get("days", 0)
            if not (0 <= ms < (1 << 28)) or not (0 <= days < (1 << 16)):
                raise DescError(f"{what}: {key} ms must be 0..2^28-1 and days 0..65535")
            raw = ms | (days << 32)
        if isinstance(raw, bool) or not isinstance(raw, int) or not (0 <= raw < (1 << 48)):
            raise DescError(f"{what}: {key} {raw!r} is not a 48-bit value or {{ms, days}}")
        return raw, False
    if kind == "vstr":
        text = _text(raw, what, key, allow_empty=True)
        if not text.isascii():
            raise DescError(f"{what}: {key} {text!r}: a VISIBLE_STRING is ASCII "
                            "(use UNICODE_STRING)")
        return text, False
    if kind == "ustr":
        return _text(raw, what, key, allow_empty=True), False
    # OCTET_STRING, DOMAIN
    if isinstance(raw, list):
        if not all(isinstance(b, int) and not isinstance(b, bool) and 0 <= b <= 255 for b in raw):
            raise DescError(f"{what}: {key} bytes must be 0..255")
        return bytes(raw), False
    if isinstance(raw, str):
        try:
            return bytes.fromhex(raw), False
        except ValueError:
            raise DescError(f"{what}: {key} {raw!r} is not hex bytes (\"01 02 AB\")") from None
    raise DescError(f"{what}: {key} must be hex bytes or a list of bytes")


def _parse_default(s: Sub, raw, what: str) -> None:
    """Normalise raw (from TOML) into s.default / s.nodeid."""
    s.default, s.nodeid = _parse_value(s, raw, what)


def _parse_limit(s: Sub, raw, what: str, key: str) -> tuple[int | None, bool]:
    """A limit: an integer or "$NODEID+n" (offset, relative)."""
    if raw is None:
        return None, False
    if isinstance(raw, str):
        m = NODEID_RE.fullmatch(raw)
        if not m:
            raise DescError(f"{what}: {key} {raw!r} is not an integer or \"$NODEID+n\"")
        off = m.group(1) or m.group(2)
        return (int(off, 0) if off else 0), True
    if isinstance(raw, bool) or not isinstance(raw, int):
        raise DescError(f"{what}: limit {raw!r} is not an integer")
    return raw, False


# EDS keys a description states with its own keys (eds_keys may not repeat them)
EDS_STANDARD_KEYS = {"parametername", "objecttype", "datatype", "accesstype", "defaultvalue",
                     "pdomapping", "lowlimit", "highlimit", "objflags", "parametervalue",
                     "denotation", "subnumber", "compactsubobj"}


# keys odgen writes into an ARRAY/RECORD section (and, with CompactSubObj, the element keys)
OBJ_SECTION_STANDARD = {"parametername", "objecttype", "subnumber", "compactsubobj", "objflags"}
ELEMENT_STANDARD = {"datatype", "accesstype", "defaultvalue", "pdomapping", "lowlimit",
                    "highlimit", "parametervalue", "denotation"}


def _obj_flags(raw, what: str) -> int | None:
    if raw is None:
        return None
    if isinstance(raw, bool) or not isinstance(raw, int) or not 0 <= raw <= 0xFFFFFFFF:
        raise DescError(f"{what}: obj_flags must be an UNSIGNED32 (bit 0: refuse write on "
                        "download, bit 1: refuse read on scan)")
    return raw


def is_ini_name(name: str) -> bool:
    """A section or key name an EDS can hold."""
    return (bool(name) and name.isprintable() and name == name.strip()
            and not name.startswith((";", "#", "[")) and "]" not in name)


def eds_keys(raw, what: str, standard: set[str] = EDS_STANDARD_KEYS,
             table: str = "eds_keys") -> dict[str, str]:
    """Extra EDS keys, written verbatim: { Key = "text" }."""
    if not isinstance(raw, dict):
        raise DescError(f"{what}: {table} must be a table of Key = \"text\"")
    for k, v in raw.items():
        if not is_ini_name(k) or "=" in k:
            raise DescError(f"{what}: {table} key {k!r} is not an EDS key name")
        if k.lower() in standard:
            raise DescError(f"{what}: {table} key {k} is a CiA 306 key the description "
                            "states itself")
        if not isinstance(v, str):
            raise DescError(f"{what}: {table} {k} must be text")
        _text(v, what, f"{table} {k}", allow_empty=True)
    return dict(raw)


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
    s.parameter_value, s.pv_nodeid = _parse_value(s, tbl.get("parameter_value"), what,
                                                  "parameter_value")
    s.denotation = _text(tbl.get("denotation", ""), what, "denotation", allow_empty=True)
    s.obj_flags = _obj_flags(tbl.get("obj_flags"), what)
    s.eds_keys = eds_keys(tbl.get("eds_keys", {}), what)
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
    # limits (integers, or "$NODEID+n": the C dictionary checks the range over
    # all node-IDs 1..127, the EDS states them as written)
    lo, lo_rel = _parse_limit(s, tbl.get("low_limit"), what, "low_limit")
    hi, hi_rel = _parse_limit(s, tbl.get("high_limit"), what, "high_limit")
    if lo is not None or hi is not None:
        if s.kind not in ("int", "uint"):
            raise DescError(f"{what}: limits are only supported on integer types, not {tname}"
                            + (" (the core does not check REAL limits; use a hook)"
                               if s.kind == "real" else ""))
        tlo, thi = _int_range(s)
        for v, rel in ((lo, lo_rel), (hi, hi_rel)):
            if v is not None and not (tlo <= v and v + (127 if rel else 0) <= thi):
                shown = f"$NODEID+{v}" if rel else str(v)
                raise DescError(f"{what}: limit {shown} does not fit {tname} [{tlo}, {thi}]")
        if (lo_rel or hi_rel) and s.fixed not in (1, 2, 4):
            raise DescError(f"{what}: $NODEID limits need an 8/16/32-bit type, not {tname}")
        s.eds_low, s.low_nodeid, s.eds_high, s.high_nodeid = lo, lo_rel, hi, hi_rel

        def at(v, rel, n, dflt):
            return dflt if v is None else v + (n if rel else 0)

        def shown(v, rel, dflt):
            return str(dflt) if v is None else (f"$NODEID+{v}" if rel else str(v))

        lo_s, hi_s = shown(lo, lo_rel, tlo), shown(hi, hi_rel, thi)
        for n in (1, 127):   # everything is linear in the node-ID
            if at(lo, lo_rel, n, tlo) > at(hi, hi_rel, n, thi):
                raise DescError(f"{what}: low_limit {lo_s} is above high_limit {hi_s}"
                                + (f" for node-ID {n}" if lo_rel or hi_rel else ""))
        s.low = tlo if lo is None else lo + (1 if lo_rel else 0)
        s.high = thi if hi is None else hi + (127 if hi_rel else 0)
        if s.default is not None:
            for n in (1, 127):
                d = s.default + (n if s.nodeid else 0)
                if not at(lo, lo_rel, n, tlo) <= d <= at(hi, hi_rel, n, thi):
                    d_s = f"$NODEID+{s.default}" if s.nodeid else str(s.default)
                    raise DescError(f"{what}: default {d_s} is out of limits [{lo_s}, {hi_s}]")
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
    links = tbl.get("links")
    if links is not None:
        if not isinstance(links, list) or not all(
                isinstance(x, int) and not isinstance(x, bool) and 0 <= x <= 0xFFFF for x in links):
            raise DescError(f"{what}: links must be a list of indices (ObjectLinks)")
        obj.links = list(links)
    compact = tbl.get("compact", False)
    if not isinstance(compact, bool):
        raise DescError(f"{what}: compact must be true or false")
    storage = tbl.get("storage")
    if code in ("VAR", "DOMAIN"):
        if has_subs:
            raise DescError(f"{what}: a {code} has no subs/array (use ARRAY or RECORD)")
        if compact:
            raise DescError(f"{what}: compact (CompactSubObj) is for an ARRAY or RECORD")
        var = {k: v for k, v in tbl.items() if k in VAR_KEYS}
        var["name"] = name
        if code == "DOMAIN":
            var.setdefault("type", "DOMAIN")
            if var["type"] != "DOMAIN":
                raise DescError(f"{what}: a DOMAIN object has data type DOMAIN")
        obj.subs.append(make_sub(index, var, storage, what))
        obj.hook = obj.hook or obj.subs[0].hookio
        return obj
    stray = sorted(set(tbl) & (VAR_KEYS - OBJ_SECTION_KEYS))
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
            elif compact:   # CiA 306: CompactSubObj names the elements <name><k>
                e["name"] = f"{name}{k}"
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
        if compact:   # CiA 306: the sub-index 0 CompactSubObj implies
            s0 = {"name": COMPACT_SUB0, "type": "UNSIGNED8", "access": "ro", "default": highest,
                  "rom": True}
        if sub0 is not None:
            if not isinstance(sub0, dict):
                raise DescError(f"{where(index, 0)}: sub0 must be a table")
            s0.update(sub0)
        s0["sub"] = 0
        subs.insert(0, make_sub(index, s0, storage, what))
    subs.sort(key=lambda s: s.sub)
    s0 = subs[0]
    # 0x1004 "Number of PDOs supported" (CiA 301 up to 4.0, withdrawn since)
    # defined its sub-index 0 as UNSIGNED32 (RPDOs in bits 0..15, TPDOs in 16..31)
    wide = index == 0x1004 and code == "RECORD" and s0.type == "UNSIGNED32"
    if s0.sub != 0 or (s0.type != "UNSIGNED8" and not wide):
        raise DescError(f"{where(index, 0)}: sub-index 0 of a {code} is UNSIGNED8")
    if code == "ARRAY":
        types = {s.type for s in subs[1:]}
        if len(types) > 1:
            raise DescError(f"{what}: the elements of an ARRAY share one data type "
                            f"(found {', '.join(sorted(types))})")
    obj.subs = subs
    obj.hook = obj.hook or any(s.hookio for s in subs)
    obj.obj_flags = _obj_flags(tbl.get("obj_flags"), what)
    obj.eds_keys = eds_keys(tbl.get("eds_keys", {}), what,
                            OBJ_SECTION_STANDARD | (ELEMENT_STANDARD if compact else set()))
    if compact:
        _check_compact(obj)
    obj.compact = compact
    return obj


COMPACT_SUB0 = "NrOfObjects"


def _check_compact(obj: Obj) -> None:
    """CompactSubObj=N can state an ARRAY/RECORD whose sub-index 0 is the
    implied one and whose elements 1..N share everything but name,
    parameter_value and denotation."""
    what = f"{where(obj.index)}: compact = true"
    s0, elems = obj.subs[0], obj.subs[1:]
    if [s.sub for s in elems] != list(range(1, len(elems) + 1)) or not elems:
        raise DescError(f"{what} needs the sub-indices 1..N without gaps")
    if (s0.name, s0.type, s0.access, s0.default, s0.pdo, s0.eds_low, s0.eds_high, s0.obj_flags,
            s0.eds_keys, s0.parameter_value, s0.denotation) != \
            (COMPACT_SUB0, "UNSIGNED8", "ro", len(elems), False, None, None, None, {}, None, ""):
        raise DescError(f"{what}: sub-index 0 must be the implied one ({COMPACT_SUB0}, "
                        f"UNSIGNED8, ro, default {len(elems)}, not mappable, nothing else)")

    def shared(s: Sub):
        return (s.type, s.access, s.pdo, s.default, s.nodeid, s.eds_low, s.low_nodeid,
                s.eds_high, s.high_nodeid)
    for s in elems:
        if shared(s) != shared(elems[0]):
            raise DescError(f"{where(obj.index, s.sub)}: compact = true, but this element's "
                            "type, access, PDO mapping, default or limits differ from "
                            "sub-index 1's")
        if s.obj_flags is not None or s.eds_keys:
            raise DescError(f"{where(obj.index, s.sub)}: compact = true: obj_flags and "
                            "eds_keys go on the object, not on an element")


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
    layout = dev.get("identity_layout", "cia")
    if layout not in ("cia", "vendor-at-sub0"):
        raise DescError(f"{what}: identity_layout {layout!r} must be \"cia\" or "
                        "\"vendor-at-sub0\"")
    if layout == "vendor-at-sub0":
        # A device that documents 0x1018 with the vendor-ID in sub-index 0, the
        # product code in 1 and the revision in 2 (AnaGate Motion)
        if "vendor_id" not in dev or "serial" in dev:
            raise DescError(f"{what}: identity_layout vendor-at-sub0 needs vendor_id and has "
                            "no serial")
        o = Obj(index=0x1018, name="Identity object", code="RECORD", prefix="x1018",
                origin="[device] vendor_id")
        o.subs = [make_sub(0x1018, {"sub": k, "name": name, "type": "UNSIGNED32",
                                    "access": "ro", "rom": True, "default": dev.get(key, 0)},
                           None, what)
                  for k, (key, name) in enumerate((("vendor_id", "Vendor-ID"),
                                                   ("product_code", "Product code"),
                                                   ("revision", "Revision number")))]
        out.append(o)
        return out
    if any(k in dev for k in ids):
        if "vendor_id" not in dev:
            raise DescError(f"{what}: 0x1018 needs at least vendor_id")
        o = Obj(index=0x1018, name="Identity object", code="RECORD", prefix="x1018",
                origin="[device] vendor_id")
        # sub 0 is 4 (CiA 301) unless the device documents another number
        # (Wandfluh DSV: 1, with sub 1..4 present all the same)
        sub0 = _uint(dev.get("identity_sub0", 4), "[device] identity_sub0", 4)
        if sub0 < 1:
            raise DescError(f"{what}: identity_sub0 must be 1..4")
        subs = [{"sub": 0, "name": "Highest sub-index supported", "type": "UNSIGNED8",
                 "access": "const", "default": sub0}]
        for k, (key, name) in enumerate(zip(ids, ("Vendor-ID", "Product code",
                                                   "Revision number", "Serial number")), 1):
            t = {"sub": k, "name": name, "type": "UNSIGNED32", "access": "ro"}
            if key in dev and not (key == "serial" and dev.get("lss") is True):
                t["default"] = dev[key]
                t["rom"] = True
            else:
                # filled in by the application at run time; an LSS slave's serial
                # number is the instance's (distinct LSS addresses), its default
                # the description's
                t["storage"] = "none"
                if key in dev:
                    t["default"] = dev[key]
            subs.append(t)
        o.subs = [make_sub(0x1018, t, None, f"{what}") for t in subs]
        out.append(o)
    return out


DEVICE_KEYS = {"name", "vendor_name", "product_name", "order_code", "vendor_id", "product_code",
               "revision", "serial", "device_type", "device_name", "hw_version", "sw_version",
               "options", "boot_emcy_data", "baudrates", "description", "lss",
               "vendor_number", "product_number", "revision_number", "mandatory_objects",
               "identity_layout", "tpdo_mask", "nodeid_object", "identity_sub0"}
EDS_KEYS = {"file_version", "file_revision", "date", "time", "author", "description",
            "file_name", "eds_version", "modified_date", "modified_time", "modified_by",
            "comments", "dummy_usage", "sections", "simple_boot_up_master",
            "simple_boot_up_slave", "granularity", "dynamic_channels_supported", "compact_pdo",
            "group_messaging", "nr_of_rxpdo", "nr_of_txpdo"}
BAUDRATES = (10, 20, 50, 125, 250, 500, 800, 1000)
# kbit/s -> index of the CiA 305 bit-timing table (LSS configure bit timing)
LSS_BIT_TIMING = {1000: 0, 800: 1, 500: 2, 250: 3, 125: 4, 50: 6, 20: 7, 10: 8}


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
        text = path.read_text(encoding="utf-8")
    except OSError as e:
        raise DescError(f"cannot read: {e.strerror}") from None
    return loads(text, path, base)


def _uint(v, what: str, top: int = 0xFFFFFFFF) -> int:
    if isinstance(v, bool) or not isinstance(v, int) or not 0 <= v <= top:
        raise DescError(f"{what} must be an integer 0..{top}")
    return v


def _flag(v, what: str) -> bool:
    if not isinstance(v, bool):
        raise DescError(f"{what} must be true or false")
    return v


def _raw_object(tbl: dict, what: str) -> RawObj:
    index = tbl.get("index")
    if isinstance(index, bool) or not isinstance(index, int) or not 0 <= index <= 0xFFFF:
        raise DescError(f"{what}: index {index!r} must be 0x0000..0xFFFF")
    what = where(index)
    _check_keys(tbl, RAW_KEYS, what + " (eds_only)")
    reason = _text(tbl.get("eds_only"), what, "eds_only")
    secs = tbl.get("sections")
    head = f"{index:04X}"
    if not isinstance(secs, dict) or not secs or next(iter(secs)).upper() != head:
        raise DescError(f"{what}: eds_only needs sections, the first one \"{head}\"")
    out = []
    for name, keys in secs.items():
        if not re.fullmatch(head + r"(sub[0-9A-Fa-f]{1,2}|Name|Value|Denotation|ObjectLinks)?",
                            name, re.IGNORECASE):
            raise DescError(f"{what}: section {name!r} does not belong to object {head}")
        out.append((name, eds_keys(keys, f"{what} [{name}]", set(), "section")))
    pname = {k.lower(): v for k, v in out[0][1].items()}.get("parametername")
    if not pname:
        raise DescError(f"{what}: section {head} without ParameterName")
    return RawObj(index=index, name=pname, reason=reason, sections=out)


DCF_KEYS = {"node_id": "NodeID", "node_name": "NodeName", "baudrate": "Baudrate",
            "net_number": "NetNumber", "network_name": "NetworkName",
            "canopen_manager": "CANopenManager", "lss_serial_number": "LSS_SerialNumber"}
EDS_DEVICE_INFO = {   # [eds] key -> DeviceInfo key; None: the generator works it out
    "simple_boot_up_master": "SimpleBootUpMaster", "simple_boot_up_slave": "SimpleBootUpSlave",
    "granularity": "Granularity", "dynamic_channels_supported": "DynamicChannelsSupported",
    "compact_pdo": "CompactPDO", "group_messaging": "GroupMessaging",
    "nr_of_rxpdo": "NrOfRXPDO", "nr_of_txpdo": "NrOfTXPDO"}
DERIVED_SECTIONS = ("mandatoryobjects", "optionalobjects", "manufacturerobjects")


def _eds_table(eds: dict, info: dict, name: str) -> dict:
    _check_keys(eds, EDS_KEYS, "[eds]")
    date = eds.get("date", "2025-01-01")
    if not isinstance(date, str) or not re.fullmatch(r"\d{4}-\d{2}-\d{2}", date):
        raise DescError("[eds] date must be \"YYYY-MM-DD\"")
    time = eds.get("time", "12:00")
    if not isinstance(time, str) or not re.fullmatch(r"\d{2}:\d{2}", time):
        raise DescError("[eds] time must be \"hh:mm\" (24 h)")
    mdate = eds.get("modified_date", date)
    if not isinstance(mdate, str) or not re.fullmatch(r"\d{4}-\d{2}-\d{2}", mdate):
        raise DescError("[eds] modified_date must be \"YYYY-MM-DD\"")
    mtime = eds.get("modified_time", time)
    if not isinstance(mtime, str) or not re.fullmatch(r"\d{2}:\d{2}", mtime):
        raise DescError("[eds] modified_time must be \"hh:mm\" (24 h)")
    author = _text(eds.get("author", "tools/odgen"), "[eds]", "author", True)
    out = {
        "file_name": None if "file_name" not in eds else
        _text(eds["file_name"], "[eds]", "file_name"),
        "file_version": _uint(eds.get("file_version", 1), "[eds] file_version", 255),
        "file_revision": _uint(eds.get("file_revision", 0), "[eds] file_revision", 255),
        "eds_version": _text(eds.get("eds_version", "4.0"), "[eds]", "eds_version"),
        "date": date, "time": time, "author": author,
        "modified_date": mdate, "modified_time": mtime,
        "modified_by": _text(eds.get("modified_by", author), "[eds]", "modified_by", True),
        "description": _text(eds.get("description", info["description"] or name), "[eds]",
                             "description", True),
        "comments": None,
        "dummy_usage": [],
        "sections": {},
    }
    if "comments" in eds:
        c = eds["comments"]
        if not isinstance(c, list):
            raise DescError("[eds] comments must be a list of lines")
        out["comments"] = [_text(x, "[eds]", "comments line", True) for x in c]
    d = eds.get("dummy_usage", [])
    if not isinstance(d, list) or any(isinstance(x, bool) or x not in range(1, 8) for x in d):
        raise DescError("[eds] dummy_usage must list data type indices 1..7 "
                        "(the dummy objects PDO mappings may use)")
    out["dummy_usage"] = sorted(set(d))
    for k in EDS_DEVICE_INFO:
        v = eds.get(k)
        if k.startswith("nr_of") or k == "granularity":
            out[k] = None if v is None else _uint(v, f"[eds] {k}", 0xFFFF)
        else:
            out[k] = None if v is None else _flag(v, f"[eds] {k}")
    secs = eds.get("sections", {})
    if not isinstance(secs, dict):
        raise DescError("[eds] sections must be tables: [eds.sections.Name]")
    for sname, keys in secs.items():
        if not is_ini_name(sname) or re.match(r"[0-9A-Fa-f]{4}", sname) \
                or sname.lower() in DERIVED_SECTIONS:
            raise DescError(f"[eds.sections] {sname!r}: not a section the description may "
                            "add (object sections belong to [[object]], object lists are "
                            "generated)")
        out["sections"][sname] = eds_keys(keys, f"[eds.sections.{sname}]", set(), "section")
    return out


def _dcf_table(dcf) -> dict | None:
    if dcf is None:
        return None
    if not isinstance(dcf, dict):
        raise DescError("[dcf] must be a table")
    _check_keys(dcf, set(DCF_KEYS), "[dcf]")
    out = {}
    for k, v in dcf.items():
        if k in ("node_name", "network_name"):
            out[k] = _text(v, "[dcf]", k, True)
        elif k == "canopen_manager":
            out[k] = _flag(v, "[dcf] canopen_manager")
        elif k == "node_id":
            out[k] = _uint(v, "[dcf] node_id", 127)
        else:
            out[k] = _uint(v, f"[dcf] {k}")
    return out


def _include(data: dict, path: Path, _seen: list | None = None) -> dict:
    """include = "other.toml": the other description (relative to this one) is
    the base; this one's [device], [eds], [dcf] and personality ([sdo] ...)
    keys replace the base's, its
    objects replace the base's objects of the same index or are added. The
    base may include another description in turn."""
    _seen = _seen or [path.resolve()]
    inc = data["include"]
    if not isinstance(inc, str) or not inc:
        raise DescError("include must name a description file (\"other.toml\")")
    ipath = path.parent / inc
    try:
        base = tomllib.loads(ipath.read_text(encoding="utf-8"))
    except OSError as e:
        raise DescError(f"include {inc!r}: cannot read: {e.strerror}") from None
    except tomllib.TOMLDecodeError as e:
        raise DescError(f"include {inc!r}: TOML syntax: {e}") from None
    if "include" in base:   # the base includes another in turn
        if len(stack := [*_seen, ipath.resolve()]) > 8 or ipath.resolve() in _seen:
            raise DescError(f"include {inc!r}: includes itself (or more than 8 deep)")
        base = _include(base, ipath, stack)
    import personality  # noqa: PLC0415

    _check_keys(base, {"device", "eds", "dcf", "object", "profile", *personality.TABLES},
                f"include {inc!r}: top level")
    out: dict = {}
    for key in ("device", "eds", "dcf", "profile", *personality.TABLES):
        a, b = base.get(key), data.get(key)
        if a is None or b is None:
            if a is not None or b is not None:
                out[key] = a if b is None else b
            continue
        if not isinstance(a, dict) or not isinstance(b, dict):
            raise DescError(f"[{key}] must be a table")
        out[key] = {**a, **b}
        if key == "profile":   # one level deeper: [profile.cia402] keys
            for k in set(a) & set(b):
                if isinstance(a[k], dict) and isinstance(b[k], dict):
                    out[key][k] = {**a[k], **b[k]}
    objs = base.get("object", [])
    mine = data.get("object", [])
    if not isinstance(objs, list) or not isinstance(mine, list):
        raise DescError("object must be an array of tables ([[object]])")
    merged = list(objs)
    for tbl in mine:
        idx = tbl.get("index") if isinstance(tbl, dict) else None
        at = [k for k, o in enumerate(merged) if isinstance(o, dict) and o.get("index") == idx]
        if idx is not None and at:
            merged[at[0]] = tbl   # replaces the base's object
        else:
            merged.append(tbl)
    out["object"] = merged
    return out


def load_raw(path: str | Path) -> dict:
    """The description's tables with its include resolved (for the device
    registry: tools/odgen/gen_registry.py reads [profile])."""
    path = Path(path)
    try:
        data = tomllib.loads(path.read_text(encoding="utf-8"))
    except OSError as e:
        raise DescError(f"cannot read: {e.strerror}") from None
    except tomllib.TOMLDecodeError as e:
        raise DescError(f"TOML syntax: {e}") from None
    if "include" in data:
        data = _include(data, path)
    return data


def loads(text: str, path: str | Path = "<description>", base: str | None = None) -> Device:
    """Load a description from its text (path: for messages and the default base)."""
    import personality  # noqa: PLC0415 (it imports this module's DescError)

    path = Path(path)
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as e:
        raise DescError(f"TOML syntax: {e}") from None
    _check_keys(data, {"include", "device", "eds", "dcf", "object", "profile", *personality.TABLES},
                "top level")
    if "include" in data:
        data = _include(data, path)
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
    for o in opts:
        if o not in known:
            raise DescError(f"[device] options: unknown option {o!r} "
                            f"(known: {', '.join(sorted(known))})")
    # the typed settings per service ([sdo], [pdo], [tpdo], [emcy], ...)
    opts, bed, mask = personality.apply(data, opts, dev.get("boot_emcy_data"),
                                        dev.get("tpdo_mask"))
    bits = 0
    for o in opts:
        bits |= known[o]
    if bed is not None:
        if (not isinstance(bed, list) or len(bed) != 5 or
                not all(isinstance(b, int) and not isinstance(b, bool) and 0 <= b <= 255 for b in bed)):
            raise DescError("[device] boot_emcy_data must be 5 bytes")
        if "BOOT_EMCY" not in opts:
            raise DescError("[device] boot_emcy_data is only sent with option BOOT_EMCY")
    elif "BOOT_EMCY" in opts:
        raise DescError("[device] option BOOT_EMCY needs boot_emcy_data (5 bytes)")
    if mask is not None:
        mask = _uint(mask, "[device] tpdo_mask", 0xFFFF)
        if not 0x2000 <= mask <= 0x5FFF:
            raise DescError("[device] tpdo_mask must be a manufacturer object (0x2000..0x5FFF)")
    nodeid = dev.get("nodeid_object")
    if nodeid is not None:
        nodeid = _uint(nodeid, "[device] nodeid_object", 0xFFFF)
        if not 0x2000 <= nodeid <= 0x5FFF:
            raise DescError("[device] nodeid_object must be a manufacturer object (0x2000..0x5FFF)")
    mask_opts = [o for o in opts if o in ("TPDO_MASK_254", "TPDO_MASK_255")]
    if mask_opts and mask is None:
        raise DescError(f"[device] option {mask_opts[0]} needs tpdo_mask (the index of "
                        "TPDO1's change mask)")
    if mask is not None and not mask_opts:
        raise DescError("[device] tpdo_mask is only used with option TPDO_MASK_254 or "
                        "TPDO_MASK_255")
    rates = dev.get("baudrates", list(BAUDRATES))
    if not isinstance(rates, list) or any(r not in BAUDRATES for r in rates):
        raise DescError(f"[device] baudrates must list kbit/s out of {BAUDRATES}")
    info = {
        "name": name,
        "vendor_name": _text(dev.get("vendor_name", "unknown"), "[device]", "vendor_name", True),
        "product_name": _text(dev.get("product_name", name), "[device]", "product_name", True),
        "order_code": _text(dev.get("order_code", ""), "[device]", "order_code", True),
        "description": _text(dev.get("description", ""), "[device]", "description", True),
        "baudrates": rates,
        "lss": _flag(dev.get("lss", False), "[device] lss"),
    }
    # [device] lss = true: the device is an LSS slave (core option LSS; EDS LSS_Supported)
    if info["lss"] and "LSS" not in opts:
        opts = list(opts) + ["LSS"]
        bits |= known["LSS"]
    if not info["lss"] and any(o.startswith("LSS") for o in opts):
        raise DescError("[device] the LSS options need lss = true")
    info["lss_bit_timings"] = sum(1 << LSS_BIT_TIMING[r] for r in rates)
    for k in ("vendor_id", "product_code", "revision"):
        info[k] = _uint(dev.get(k, 0), f"[device] {k}")
    # DeviceInfo numbers: the identity unless the EDS states other ones
    for k, ident in (("vendor_number", "vendor_id"), ("product_number", "product_code"),
                     ("revision_number", "revision")):
        info[k] = _uint(dev.get(k, info[ident]), f"[device] {k}")
    mandatory = _flag(dev.get("mandatory_objects", True), "[device] mandatory_objects")
    eds = data.get("eds", {})
    if not isinstance(eds, dict):
        raise DescError("[eds] must be a table")
    eds_info = _eds_table(eds, info, name)
    if "PDO_MAP_BYTES" in opts and eds_info.get("granularity") not in (None, 8):
        raise DescError("[eds] granularity: option PDO_MAP_BYTES maps whole bytes only "
                        "(granularity 8)")
    dcf = _dcf_table(data.get("dcf"))

    objects = _device_objects(dev, "[device]")
    origins = {o.index: o.origin for o in objects}
    raw_objs = data.get("object", [])
    if not isinstance(raw_objs, list):
        raise DescError("object must be an array of tables ([[object]])")
    eds_only: list[RawObj] = []
    for k, tbl in enumerate(raw_objs):
        if not isinstance(tbl, dict):
            raise DescError(f"[[object]] #{k + 1} must be a table")
        if "eds_only" in tbl:
            o = _raw_object(tbl, f"[[object]] #{k + 1}")
            eds_only.append(o)
        else:
            o = _make_object(tbl, f"[[object]] #{k + 1}")
            objects.append(o)
        if o.index in origins:
            raise DescError(f"{where(o.index)}: duplicate index (already given by {origins[o.index]})")
        origins[o.index] = f"[[object]] #{k + 1}"
    objects.sort(key=lambda o: o.index)
    eds_only.sort(key=lambda o: o.index)
    if not objects:
        raise DescError("no objects")
    present = {o.index for o in objects}
    for m in (0x1000, 0x1001, 0x1018):
        if mandatory and m not in present:
            raise DescError(f"{where(m)}: mandatory object missing (CiA 301)"
                            + (" (it is eds_only)" if m in origins else ""))

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
                    boot_emcy_data=bed, limits=limits, n_hooks=slot, eds_only=eds_only,
                    dcf=dcf, tpdo_mask=mask, nodeid_object=nodeid)
    _check_pdo_mappings(device)
    if nodeid is not None:
        s = device.find(nodeid, 0)
        if s is None or s.type != "UNSIGNED8" or s.hookio or s.rom:
            raise DescError(f"[device] nodeid_object 0x{nodeid:04X}: needs an UNSIGNED8 RAM value "
                            "at sub-index 0")
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
            if 1 <= idx <= 7 and sub == 0:   # a dummy entry: a gap of that data type
                if idx not in dev.eds["dummy_usage"]:
                    raise DescError(f"{what}, a dummy entry [eds] dummy_usage does not allow")
                dsize = {1: (1, 8), 2: (8,), 3: (16,), 4: (32,), 5: (8,), 6: (16,), 7: (32,)}[idx]
                if bits not in dsize:
                    raise DescError(f"{what} with {bits} bits; the dummy has {dsize[-1]}")
                if bits % 8 and "PDO_MAP_BYTES" in dev.options:
                    raise DescError(f"{what} with {bits} bits; option PDO_MAP_BYTES maps "
                                    "whole bytes only")
                if s.sub <= count:
                    total += bits
                continue
            if target is None and any(r.index == idx for r in dev.eds_only):
                raise DescError(f"{what}, which is eds_only (not in the C dictionary)")
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
