"""A small CiA 306 (EDS/DCF) reader.

Two layers:

* read_ini(): the file as sections of key=value lines, with line numbers.
  Section and key names are case-insensitive (CiA 306); the spelling of the
  file is kept for writing them back. Blank lines and lines starting with ';'
  are skipped; so is an inline comment (';' after a blank). Anything else that
  is not "[section]" or "key=value" is an EdsError naming file and line.
* read_eds(): the meaning: FileInfo, DeviceInfo, DummyUsage, Comments,
  DeviceComissioning, the object lists, one EdsObject per object section with
  its sub-entries (CompactSubObj expanded, [xxxxName]/[xxxxValue]/
  [xxxxDenotation] applied), ObjectLinks, and every section and key the reader
  does not interpret (kept as text).

Values stay text here; value() turns a value of a given data type into a
comparable Python value (0x0A == 10 == 012 octal, two's complement for signed
types given in hex, "$NODEID+0x180" == "0x180+$NODEID").

The importer (eds_import.py) and the semantic comparison (eds_compare.py) both
use it. Standard library only.
"""
from __future__ import annotations

import re
import struct
from dataclasses import dataclass, field
from pathlib import Path


class EdsError(Exception):
    """A file that cannot be read as an EDS/DCF: "file:line: problem"."""


@dataclass
class Key:
    name: str           # as spelled in the file
    value: str
    line: int


@dataclass
class Section:
    name: str           # as spelled in the file
    line: int
    keys: dict[str, Key] = field(default_factory=dict)   # lower-case name -> Key

    def get(self, key: str, default: str | None = None) -> str | None:
        k = self.keys.get(key.lower())
        return default if k is None else k.value

    def has(self, key: str) -> bool:
        return key.lower() in self.keys

    def line_of(self, key: str) -> int:
        k = self.keys.get(key.lower())
        return self.line if k is None else k.line


def decode(data: bytes) -> str:
    """EDS files are ASCII; UTF-8 (UNICODE_STRING defaults) and, failing that,
    Latin-1 (old vendor files) are accepted."""
    if data.startswith(b"\xef\xbb\xbf"):
        data = data[3:]
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError:
        return data.decode("latin-1")


def read_ini(text: str, source: str = "<eds>") -> dict[str, Section]:
    sections: dict[str, Section] = {}
    cur: Section | None = None
    for no, raw in enumerate(text.splitlines(), 1):
        line = raw.strip()
        if not line or line.startswith(";") or line.startswith("#"):
            continue
        if line.startswith("["):
            m = re.fullmatch(r"\[([^\[\]]*)\]\s*(;.*)?", line)
            if not m or not m.group(1).strip():
                raise EdsError(f"{source}:{no}: malformed section header {line!r}")
            name = m.group(1).strip()
            if name.lower() in sections:
                first = sections[name.lower()]
                raise EdsError(f"{source}:{no}: section [{name}] given twice "
                               f"(first at line {first.line})")
            cur = Section(name=name, line=no)
            sections[name.lower()] = cur
            continue
        if "=" not in line:
            raise EdsError(f"{source}:{no}: expected 'key=value' or '[section]', got {line!r}")
        key, value = line.split("=", 1)
        key = key.strip()
        value = re.split(r"\s;", value, maxsplit=1)[0].strip()
        if cur is None:
            raise EdsError(f"{source}:{no}: key {key!r} before the first [section]")
        if not key:
            raise EdsError(f"{source}:{no}: empty key in [{cur.name}]")
        if key.lower() in cur.keys:
            raise EdsError(f"{source}:{no}: key {key} given twice in [{cur.name}] "
                           f"(first at line {cur.keys[key.lower()].line})")
        cur.keys[key.lower()] = Key(name=key, value=value, line=no)
    return sections


# --------------------------------------------------------------- values

# data type index -> (name, size in bytes (0: variable), kind)
DATA_TYPES = {
    0x01: ("BOOLEAN", 1, "bool"), 0x02: ("INTEGER8", 1, "int"), 0x03: ("INTEGER16", 2, "int"),
    0x04: ("INTEGER32", 4, "int"), 0x05: ("UNSIGNED8", 1, "uint"),
    0x06: ("UNSIGNED16", 2, "uint"), 0x07: ("UNSIGNED32", 4, "uint"),
    0x08: ("REAL32", 4, "real"), 0x09: ("VISIBLE_STRING", 0, "vstr"),
    0x0A: ("OCTET_STRING", 0, "ostr"), 0x0B: ("UNICODE_STRING", 0, "ustr"),
    0x0C: ("TIME_OF_DAY", 6, "uint"), 0x0D: ("TIME_DIFFERENCE", 6, "uint"),
    0x0F: ("DOMAIN", 0, "domain"), 0x10: ("INTEGER24", 3, "int"), 0x11: ("REAL64", 8, "real"),
    0x12: ("INTEGER40", 5, "int"), 0x13: ("INTEGER48", 6, "int"), 0x14: ("INTEGER56", 7, "int"),
    0x15: ("INTEGER64", 8, "int"), 0x16: ("UNSIGNED24", 3, "uint"),
    0x18: ("UNSIGNED40", 5, "uint"), 0x19: ("UNSIGNED48", 6, "uint"),
    0x1A: ("UNSIGNED56", 7, "uint"), 0x1B: ("UNSIGNED64", 8, "uint"),
}


def parse_int(text: str) -> int:
    """A CiA 306 integer: decimal, 0x hex, or octal with a leading 0 (as C's
    strtol with base 0), optionally signed."""
    t = text.strip().replace(" ", "")
    m = re.fullmatch(r"([+-]?)(0[xX][0-9A-Fa-f]+|0[0-7]*|[1-9][0-9]*)", t)
    if not m:
        raise ValueError(f"{text!r} is not an integer")
    sign, digits = m.groups()
    if digits[:2].lower() == "0x":
        v = int(digits, 16)
    elif digits.startswith("0") and len(digits) > 1:
        v = int(digits, 8)
    else:
        v = int(digits)
    return -v if sign == "-" else v


NODEID_RE = re.compile(r"\$NODEID", re.IGNORECASE)


def parse_nodeid(text: str) -> int | None:
    """The offset of "$NODEID+n" / "n+$NODEID" / "$NODEID", None if text has
    no $NODEID. ValueError for other uses of $NODEID."""
    t = text.strip().replace(" ", "")
    if not NODEID_RE.search(t):
        return None
    rest = NODEID_RE.sub("", t, count=1)
    if NODEID_RE.search(rest):
        raise ValueError(f"{text!r}: $NODEID twice")
    if rest == "":
        return 0
    if rest.startswith("+") and t.upper().startswith("$NODEID"):
        return parse_int(rest[1:])
    if rest.endswith("+") and t.upper().endswith("$NODEID"):
        return parse_int(rest[:-1])
    raise ValueError(f"{text!r} is not \"$NODEID+n\" or \"n+$NODEID\"")


@dataclass(frozen=True)
class NodeRel:
    """A value relative to the node-ID: $NODEID + offset."""
    offset: int

    def __str__(self) -> str:
        return f"$NODEID+0x{self.offset:X}"


def int_range(dtype: int) -> tuple[int, int]:
    _, size, kind = DATA_TYPES[dtype]
    n = 8 * size
    if kind == "int":
        return -(1 << (n - 1)), (1 << (n - 1)) - 1
    if kind == "bool":
        return 0, 1
    return 0, (1 << n) - 1


def value(text: str | None, dtype: int | None):
    """The value of text as data type dtype, as a comparable Python value:
    int, NodeRel, float, str (VISIBLE/UNICODE_STRING) or bytes (OCTET_STRING,
    DOMAIN); None for an absent or (non-string) empty value. ValueError if the
    text is not a value of that type. Unknown data types give the text."""
    if dtype not in DATA_TYPES:
        return None if text is None or text == "" else text
    _, size, kind = DATA_TYPES[dtype]
    if kind in ("vstr", "ustr"):
        return "" if text is None else text
    if text is None or text.strip() == "":
        return None
    t = text.strip()
    if kind in ("ostr", "domain"):
        h = t.replace(" ", "")
        if h[:2].lower() == "0x":
            h = h[2:]
        if len(h) % 2 or not re.fullmatch(r"[0-9A-Fa-f]*", h):
            raise ValueError(f"{text!r} is not hex bytes")
        return bytes.fromhex(h)
    if kind == "real":
        if re.fullmatch(r"0[xX][0-9A-Fa-f]+", t):   # the IEEE 754 bit pattern
            bits = int(t, 16)
            if size == 4:
                return struct.unpack("<f", (bits & 0xFFFFFFFF).to_bytes(4, "little"))[0]
            return struct.unpack("<d", (bits & (2**64 - 1)).to_bytes(8, "little"))[0]
        try:
            return float(t)
        except ValueError:
            raise ValueError(f"{text!r} is not a number") from None
    # integers, BOOLEAN, TIME_*
    lo, hi = int_range(dtype)
    off = parse_nodeid(t)
    if off is not None:
        return NodeRel(off)
    if kind == "bool" and t.lower() in ("true", "false"):
        return int(t.lower() == "true")
    v = parse_int(t)
    if kind == "int" and v > hi and t.lstrip("+").lower().startswith("0x") \
            and v < (1 << (8 * size)):
        v -= 1 << (8 * size)   # a signed value in two's complement
    if not lo <= v <= hi:
        raise ValueError(f"{text!r} does not fit {DATA_TYPES[dtype][0]} [{lo}, {hi}]")
    return v


# ------------------------------------------------------------ the model

SUB_ATTRS = ("parametername", "objecttype", "datatype", "accesstype", "defaultvalue",
             "pdomapping", "lowlimit", "highlimit", "objflags", "parametervalue",
             "denotation")
OBJ_ATTRS = ("parametername", "objecttype", "subnumber", "compactsubobj", "objflags")
FILEINFO = ("FileName", "FileVersion", "FileRevision", "EDSVersion", "Description",
            "CreationTime", "CreationDate", "CreatedBy", "ModificationTime",
            "ModificationDate", "ModifiedBy", "LastEDS")
DEVICEINFO = ("VendorName", "VendorNumber", "ProductName", "ProductNumber", "RevisionNumber",
              "OrderCode", "BaudRate_10", "BaudRate_20", "BaudRate_50", "BaudRate_125",
              "BaudRate_250", "BaudRate_500", "BaudRate_800", "BaudRate_1000",
              "SimpleBootUpMaster", "SimpleBootUpSlave", "Granularity",
              "DynamicChannelsSupported", "CompactPDO", "GroupMessaging", "NrOfRXPDO",
              "NrOfTXPDO", "LSS_Supported")
COMMISSIONING = ("NodeID", "NodeName", "Baudrate", "NetNumber", "NetworkName",
                 "CANopenManager", "LSS_SerialNumber")
LISTS = ("MandatoryObjects", "OptionalObjects", "ManufacturerObjects")
COMPACT_SUB0 = "NrOfObjects"
# keys of a CompactSubObj object section that every element shares
ELEMENT_KEYS = ("datatype", "accesstype", "defaultvalue", "pdomapping", "lowlimit", "highlimit",
                "parametervalue", "denotation")


@dataclass
class EdsSub:
    index: int
    sub: int
    section: str                      # section name ('' for compact elements)
    line: int
    name: str = ""
    object_type: int = 0x7
    data_type: int | None = None
    access: str | None = None         # as written (case kept)
    default: str | None = None        # text
    pdo: str | None = None
    low: str | None = None
    high: str | None = None
    obj_flags: str | None = None
    param_value: str | None = None
    denotation: str | None = None
    extra: dict[str, str] = field(default_factory=dict)   # other keys, as written


@dataclass
class EdsObject:
    index: int
    section: str
    line: int
    name: str = ""
    object_type: int = 0x7
    sub_number: int | None = None
    compact: int | None = None        # CompactSubObj
    obj_flags: str | None = None
    subs: dict[int, EdsSub] = field(default_factory=dict)
    links: list[int] | None = None    # [xxxxObjectLinks]
    extra: dict[str, str] = field(default_factory=dict)   # other keys of the object section
    # compact objects: the parts of the object section every element shares
    names: dict[int, str] | None = None
    values: dict[int, str] | None = None
    denotations: dict[int, str] | None = None
    own_sections: list[str] = field(default_factory=list)


@dataclass
class Eds:
    source: str
    sections: dict[str, Section]
    file_info: dict[str, str]                  # CiA 306 key spelling -> text
    device_info: dict[str, str]
    dummy_usage: dict[int, str] | None         # 1..7 -> text
    comments: list[str] | None
    commissioning: dict[str, str] | None
    lists: dict[str, list[int]]
    objects: dict[int, EdsObject]
    other: dict[str, Section]                  # sections not interpreted
    extra_keys: dict[str, dict[str, str]]      # interpreted section -> keys not interpreted
    warnings: list[str]


def _std_keys(sec: Section, names: tuple[str, ...]) -> tuple[dict[str, str], dict[str, str]]:
    by_lower = {n.lower(): n for n in names}
    std, extra = {}, {}
    for low, k in sec.keys.items():
        if low in by_lower:
            std[by_lower[low]] = k.value
        else:
            extra[k.name] = k.value
    return std, extra


def _sub_from(sec: Section, index: int, sub: int, src: str) -> EdsSub:
    s = EdsSub(index=index, sub=sub, section=sec.name, line=sec.line)
    for low, k in sec.keys.items():
        v = k.value
        where = f"{src}:{k.line}: [{sec.name}] {k.name}"
        if low == "parametername":
            s.name = v
        elif low == "objecttype":
            s.object_type = _int(v, where)
        elif low == "datatype":
            s.data_type = _int(v, where)
        elif low == "accesstype":
            s.access = v
        elif low == "defaultvalue":
            s.default = v
        elif low == "pdomapping":
            s.pdo = v
        elif low == "lowlimit":
            s.low = v
        elif low == "highlimit":
            s.high = v
        elif low == "objflags":
            s.obj_flags = v
        elif low == "parametervalue":
            s.param_value = v
        elif low == "denotation":
            s.denotation = v
        else:
            s.extra[k.name] = v
    return s


def _int(text: str, where: str) -> int:
    try:
        return parse_int(text)
    except ValueError:
        raise EdsError(f"{where}: {text!r} is not a number") from None


def _numbered(sec: Section, count_key: str, src: str) -> dict[int, str]:
    """[xxxxName]-style sections: count_key=N and 1..=value entries."""
    out: dict[int, str] = {}
    for low, k in sec.keys.items():
        if low == count_key.lower():
            continue
        if not re.fullmatch(r"\d+", k.name):
            raise EdsError(f"{src}:{k.line}: [{sec.name}] unexpected key {k.name!r}")
        out[int(k.name)] = k.value
    n = sec.get(count_key)
    if n is None:
        raise EdsError(f"{src}:{sec.line}: [{sec.name}] without {count_key}")
    count = _int(n, f"{src}:{sec.line_of(count_key)}: [{sec.name}] {count_key}")
    if count != len(out):
        raise EdsError(f"{src}:{sec.line_of(count_key)}: [{sec.name}] {count_key}={count} "
                       f"but {len(out)} entries")
    return out


def read_eds(path: str | Path, text: str | None = None) -> Eds:
    path = str(path)
    if text is None:
        try:
            text = decode(Path(path).read_bytes())
        except OSError as e:
            raise EdsError(f"{path}: cannot read: {e.strerror}") from None
    secs = read_ini(text, path)
    warnings: list[str] = []
    extra_keys: dict[str, dict[str, str]] = {}
    used: set[str] = set()

    def std(name: str, keys: tuple[str, ...]) -> dict[str, str] | None:
        sec = secs.get(name.lower())
        if sec is None:
            return None
        used.add(name.lower())
        d, extra = _std_keys(sec, keys)
        if extra:
            extra_keys[name] = extra
        return d

    file_info = std("FileInfo", FILEINFO)
    device_info = std("DeviceInfo", DEVICEINFO)
    if device_info is None:
        raise EdsError(f"{path}: no [DeviceInfo] section (CiA 306 requires it)")
    file_info = file_info if file_info is not None else {}
    dummy = None
    if "dummyusage" in secs:
        used.add("dummyusage")
        d, extra = _std_keys(secs["dummyusage"], tuple(f"Dummy{k:04d}" for k in range(1, 8)))
        if extra:
            extra_keys["DummyUsage"] = extra
        dummy = {int(k[-4:]): v for k, v in d.items()}
    comments = None
    if "comments" in secs:
        used.add("comments")
        sec = secs["comments"]
        lines = {}
        for low, k in sec.keys.items():
            m = re.fullmatch(r"line(\d+)", low)
            if m:
                lines[int(m.group(1))] = k.value
            elif low != "lines":
                extra_keys.setdefault("Comments", {})[k.name] = k.value
        n = _int(sec.get("Lines", "0"), f"{path}:{sec.line_of('Lines')}: [Comments] Lines")
        if sorted(lines) != list(range(1, n + 1)):
            raise EdsError(f"{path}:{sec.line_of('Lines')}: [Comments] Lines={n} but lines "
                           f"{sorted(lines)} given")
        comments = [lines[k] for k in range(1, n + 1)]
    commissioning = std("DeviceComissioning", COMMISSIONING)

    lists: dict[str, list[int]] = {}
    for name in LISTS:
        sec = secs.get(name.lower())
        if sec is None:
            continue
        used.add(name.lower())
        entries = []
        for low, k in sec.keys.items():
            if low == "supportedobjects":
                continue
            if not re.fullmatch(r"\d+", k.name):
                raise EdsError(f"{path}:{k.line}: [{sec.name}] unexpected key {k.name!r}")
            entries.append((int(k.name), _int(k.value, f"{path}:{k.line}: [{sec.name}] {k.name}")))
        entries.sort()
        lists[name] = [i for _, i in entries]
        n = sec.get("SupportedObjects")
        if n is None or _int(n, f"{path}:{sec.line}") != len(entries) or \
                [k for k, _ in entries] != list(range(1, len(entries) + 1)):
            warnings.append(f"{path}:{sec.line}: [{sec.name}] SupportedObjects={n} does not "
                            f"match its {len(entries)} entries (the object sections count)")

    objects: dict[int, EdsObject] = {}
    for low, sec in secs.items():
        if re.fullmatch(r"[0-9a-f]{4}", low):
            used.add(low)
            index = int(low, 16)
            o = EdsObject(index=index, section=sec.name, line=sec.line, own_sections=[sec.name])
            objects[index] = o
    # sub-entries and the other per-object sections
    for low, sec in secs.items():
        m = re.fullmatch(r"([0-9a-f]{4})(sub([0-9a-f]{1,2})|name|value|denotation|objectlinks)",
                         low)
        if not m:
            continue
        index = int(m.group(1), 16)
        o = objects.get(index)
        if o is None:
            raise EdsError(f"{path}:{sec.line}: [{sec.name}] belongs to object "
                           f"0x{index:04X}, which has no [{m.group(1).upper()}] section")
        used.add(low)
        o.own_sections.append(sec.name)
        what = m.group(2)
        if m.group(3) is not None:
            sub = int(m.group(3), 16)
            o.subs[sub] = _sub_from(sec, index, sub, path)
        elif what == "name":
            o.names = _numbered(sec, "NrOfEntries", path)
        elif what == "value":
            o.values = _numbered(sec, "NrOfEntries", path)
        elif what == "denotation":
            o.denotations = _numbered(sec, "NrOfEntries", path)
        else:
            o.links = list(_numbered(sec, "ObjectLinks", path).items())
            o.links = [_int(v, f"{path}:{sec.line}: [{sec.name}] {k}") for k, v in sorted(o.links)]

    for index, o in sorted(objects.items()):
        sec = secs[o.section.lower()]
        var = _sub_from(sec, index, 0, path)
        o.name = var.name
        o.object_type = var.object_type
        if not sec.has("ParameterName"):
            raise EdsError(f"{path}:{sec.line}: [{sec.name}] without ParameterName")
        if o.object_type in (0x7, 0x2):             # VAR, DOMAIN
            if o.subs:
                first = min(o.subs.values(), key=lambda s: s.line)
                raise EdsError(f"{path}:{first.line}: [{first.section}]: object 0x{index:04X} "
                               f"is a {'VAR' if o.object_type == 7 else 'DOMAIN'} and has no "
                               "sub-entries")
            if var.data_type is None and o.object_type == 0x2:
                var.data_type = 0x0F
            if var.data_type is None:
                raise EdsError(f"{path}:{sec.line}: [{sec.name}] without DataType")
            o.subs = {0: var}
            continue
        # ARRAY, RECORD (and DEFSTRUCT etc.: kept as they are)
        for k in list(sec.keys.values()):
            kl = k.name.lower()
            where = f"{path}:{k.line}: [{sec.name}] {k.name}"
            if kl == "subnumber":
                o.sub_number = _int(k.value, where)
            elif kl == "compactsubobj":
                o.compact = _int(k.value, where)
            elif kl == "objflags":
                o.obj_flags = k.value
            elif kl in ("parametername", "objecttype"):
                pass
            elif not (o.compact is not None or sec.has("CompactSubObj")) or kl not in ELEMENT_KEYS:
                o.extra[k.name] = k.value
        if o.compact:
            if o.subs:
                first = min(o.subs.values(), key=lambda s: s.line)
                raise EdsError(f"{path}:{first.line}: [{first.section}]: object 0x{index:04X} "
                               f"has CompactSubObj={o.compact}, so no sub-entry sections")
            if o.sub_number is not None:
                raise EdsError(f"{path}:{sec.line_of('SubNumber')}: [{sec.name}] has both "
                               "SubNumber and CompactSubObj")
            _expand_compact(o, var, sec, path)
        else:
            if o.names or o.values or o.denotations:
                warnings.append(f"{path}:{sec.line}: [{sec.name}] has Name/Value/Denotation "
                                "sections but no CompactSubObj")
            if o.sub_number is not None and o.sub_number != len(o.subs):
                warnings.append(f"{path}:{sec.line_of('SubNumber')}: [{sec.name}] "
                                f"SubNumber={o.sub_number} but {len(o.subs)} sub-entry "
                                "sections (the sections count)")
        o.subs = dict(sorted(o.subs.items()))

    listed = {i: n for n, lst in lists.items() for i in lst}
    for index in sorted(set(objects) - set(listed)):
        warnings.append(f"{path}:{objects[index].line}: object 0x{index:04X} is in no object list")
    for index in sorted(set(listed) - set(objects)):
        warnings.append(f"{path}: [{listed[index]}] lists 0x{index:04X}, which has no section")
    other = {sec.name: sec for low, sec in secs.items() if low not in used}
    return Eds(source=path, sections=secs, file_info=file_info, device_info=device_info,
               dummy_usage=dummy, comments=comments, commissioning=commissioning, lists=lists,
               objects=objects, other=other, extra_keys=extra_keys, warnings=warnings)


def _expand_compact(o: EdsObject, var: EdsSub, sec: Section, path: str) -> None:
    """CompactSubObj=N: sub 0 "NrOfObjects" (UNSIGNED8, ro, default N); subs
    1..N take DataType, AccessType, DefaultValue, PDOMapping and limits from
    the object section, the name "<ParameterName><k>" unless [xxxxName] gives
    one, the ParameterValue from [xxxxValue] and the Denotation from
    [xxxxDenotation]."""
    n = o.compact
    if not 1 <= n <= 254:
        raise EdsError(f"{path}:{sec.line_of('CompactSubObj')}: [{sec.name}] "
                       f"CompactSubObj={n} must be 1..254")
    if var.data_type is None:
        raise EdsError(f"{path}:{sec.line}: [{sec.name}] with CompactSubObj needs DataType")
    for what, d in (("Name", o.names), ("Value", o.values), ("Denotation", o.denotations)):
        bad = sorted(k for k in (d or {}) if not 1 <= k <= n)
        if bad:
            raise EdsError(f"{path}: [{o.section}{what}] names sub-index {bad[0]}, outside "
                           f"1..{n} (CompactSubObj)")
    o.subs = {0: EdsSub(index=o.index, sub=0, section="", line=sec.line, name=COMPACT_SUB0,
                        data_type=0x05, access="ro", default=str(n), pdo="0")}
    for k in range(1, n + 1):
        s = EdsSub(index=o.index, sub=k, section="", line=sec.line,
                   name=(o.names or {}).get(k, f"{var.name}{k}"), data_type=var.data_type,
                   access=var.access, default=var.default, pdo=var.pdo, low=var.low,
                   high=var.high, param_value=(o.values or {}).get(k, var.param_value),
                   denotation=(o.denotations or {}).get(k, var.denotation))
        o.subs[k] = s
