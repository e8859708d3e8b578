"""EDS/DCF import: a CiA 306 file -> a device description (.toml) for odgen.

    odgen.py import VENDOR.eds [-o DEVICE.toml] [--use-values]

The description states everything the file states, so that odgen writes an
EDS back that loses nothing (eds_compare.py checks this for every import
before the description is written):

* FileInfo, DeviceInfo, DummyUsage, Comments -> [device] and [eds] keys;
  DeviceComissioning (DCF) -> [dcf]; keys and sections odgen has no key for
  -> [eds.sections.*] (written back verbatim).
* every object -> [[object]] with name, type, access, PDO mapping, default
  ($NODEID expressions kept), limits, ObjFlags, ObjectLinks, CompactSubObj
  (compact = true), DCF ParameterValue and Denotation, and other keys as
  eds_keys.
* an object the C dictionary cannot hold (unknown data type, REAL limits, a
  PDO-mapped string, a default that is not a value of its type, ...) or that
  odgen could not write back unchanged is kept verbatim as eds_only, with
  the reason. The importer prints each one.

Where the EDS does not say something a description needs, the importer takes
the generator's default and says so in a comment: storage group (comm for
0x1000-0x1FFF, app otherwise), ROM for const values, the capacity of strings
(their default, at least 32 bytes if writable), hook I/O for a DOMAIN without
a default.

--use-values: a DCF's ParameterValue becomes the default (a $NODEID default
stays relative when the value is the default for the DCF's node-ID) and
[DeviceComissioning] is dropped: the description of a device configured like
that node.
"""
from __future__ import annotations

import argparse
import copy
import dataclasses
import re
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

import gen_c  # noqa: E402
import gen_eds  # noqa: E402
from cia306 import (DATA_TYPES, NodeRel, Eds, EdsError, EdsObject,  # noqa: E402
                    EdsSub, parse_int, read_eds, value)
from eds_compare import differences  # noqa: E402
from model import ACCESS, BAUDRATES, EDS_DEVICE_INFO, DescError, _make_object, loads  # noqa: E402

STRING_CAPACITY = 32     # bytes the importer gives a writable string beyond its default
OBJECT_TYPES = {0x0: "NULL", 0x2: "DOMAIN", 0x5: "DEFTYPE", 0x6: "DEFSTRUCT", 0x7: "VAR",
                0x8: "ARRAY", 0x9: "RECORD"}


class Unsupported(Exception):
    """An object the description cannot state: it becomes eds_only."""


# ------------------------------------------------------------ TOML text

def key(k: str) -> str:
    return k if re.fullmatch(r"[A-Za-z0-9_-]+", k) else string(k)


def string(s: str) -> str:
    out = []
    for c in s:
        if c in '"\\':
            out.append("\\" + c)
        elif ord(c) < 0x20 or ord(c) == 0x7F:
            out.append(f"\\u{ord(c):04X}")
        else:
            out.append(c)
    return '"' + "".join(out) + '"'


class Hex(int):
    """An integer written in hex."""


def toml(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, Hex):
        return f"0x{int(v):X}" if v >= 0 else str(int(v))
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        return repr(v)
    if isinstance(v, str):
        return string(v)
    if isinstance(v, list):
        return "[" + ", ".join(toml(x) for x in v) + "]"
    if isinstance(v, dict):
        return "{ " + ", ".join(f"{key(k)} = {toml(x)}" for k, x in v.items()) + " }"
    raise TypeError(type(v))


# ---------------------------------------------------------- conversions

def _int(text: str | None, what: str, lo: int = 0, hi: int = 0xFFFFFFFF) -> int | None:
    if text is None:
        return None
    try:
        v = parse_int(text)
    except ValueError:
        raise Unsupported(f"{what} {text!r} is not a number") from None
    if not lo <= v <= hi:
        raise Unsupported(f"{what} {text!r} is out of range {lo}..{hi}")
    return v


def _value(text: str | None, dtype: int, what: str):
    """EDS text -> TOML value of the description (None: absent)."""
    try:
        v = value(text, dtype)
    except ValueError as e:
        raise Unsupported(f"{what}: {e}") from None
    if v is None:
        return None
    if isinstance(v, NodeRel):
        return f"$NODEID+0x{v.offset:X}"
    if isinstance(v, bytes):
        return " ".join(f"{b:02X}" for b in v)
    if isinstance(v, int) and DATA_TYPES[dtype][2] == "uint" and DATA_TYPES[dtype][1] > 1:
        return Hex(v)
    return v


def _encoded_len(v, kind: str) -> int:
    if v is None:
        return 0
    if kind == "ustr":
        return len(v.encode("utf-16-le"))
    if kind in ("ostr", "domain"):
        return len(v.replace(" ", "")) // 2
    return len(v.encode("utf-8"))


def configured_sub(s: EdsSub, node_id: int | None) -> EdsSub:
    """--use-values: the ParameterValue becomes the DefaultValue; a $NODEID
    default stays when the value is that default for the DCF's node-ID."""
    if s.param_value is None:
        return s
    keep = False
    try:
        d, v = value(s.default, s.data_type), value(s.param_value, s.data_type)
        keep = v == d or (isinstance(d, NodeRel) and node_id is not None
                          and v == d.offset + node_id)
    except (ValueError, KeyError):
        pass
    return dataclasses.replace(s, default=s.default if keep else s.param_value,
                               param_value=None)


def configured(eds: Eds, node_id: int | None) -> Eds:
    """The EDS as --use-values describes it: values as defaults, no DeviceComissioning."""
    e = copy.deepcopy(eds)
    for o in e.objects.values():
        o.subs = {k: configured_sub(s, node_id) for k, s in o.subs.items()}
    e.commissioning = None
    e.extra_keys.pop("DeviceComissioning", None)
    return e


def convert_sub(s: EdsSub, index: int, notes: list[str], use_values: bool,
                node_id: int | None, var: bool = False) -> dict:
    where = f"sub {s.sub}: "
    if s.object_type != 0x7 and not var:
        raise Unsupported(f"{where}ObjectType 0x{s.object_type:X} in a sub-entry (odgen "
                          "writes sub-entries as VAR)")
    dt = s.data_type
    if dt is None:
        raise Unsupported(f"{where}no DataType")
    if dt not in DATA_TYPES:
        raise Unsupported(f"{where}data type 0x{dt:04X} is not a CiA 301 basic type")
    tname, fixed, kind = DATA_TYPES[dt]
    if s.access is None:
        raise Unsupported(f"{where}no AccessType")
    access = s.access.lower()
    if access not in ACCESS:
        raise Unsupported(f"{where}AccessType {s.access!r} is not one of CiA 306's")
    t: dict = {"name": s.name, "type": tname}
    if access != "rw":
        t["access"] = access
    pdo = _int(s.pdo, f"{where}PDOMapping", 0, 1)
    if pdo:
        t["pdo_mapping"] = True
    elif pdo == 0 and access in ("rwr", "rww"):
        t["pdo_mapping"] = False     # the model refuses it: the object becomes eds_only
    if use_values:
        s = configured_sub(s, node_id)
    dflt = _value(s.default, dt, f"{where}DefaultValue")
    pv = _value(s.param_value, dt, f"{where}ParameterValue")
    if kind in ("vstr", "ustr") and dflt == "":
        dflt = None
    if dflt is not None:
        t["default"] = dflt
    for k, text in (("low_limit", s.low), ("high_limit", s.high)):
        if text is None:
            continue
        v = _value(text, dt, f"{where}{'LowLimit' if k == 'low_limit' else 'HighLimit'}")
        if v is not None:
            t[k] = v
    flags = _int(s.obj_flags, f"{where}ObjFlags")
    if flags is not None:
        t["obj_flags"] = Hex(flags)
    if pv is not None and not (kind in ("vstr", "ustr") and pv == ""):
        t["parameter_value"] = pv
    if s.denotation:
        t["denotation"] = s.denotation
    if s.extra:
        t["eds_keys"] = dict(s.extra)
    # what the EDS does not say
    if not fixed:
        n = _encoded_len(dflt, kind)
        writable = access in ("rw", "wo", "rwr", "rww")
        if kind == "domain" and dflt is None:
            t["hookio"] = True
            notes.append(f"{where}DOMAIN without a default: hook I/O "
                         "(the application's hook provides the data)")
        elif kind in ("vstr", "ustr") and (writable or n == 0):
            size = max(n, STRING_CAPACITY)
            t["size"] = size
            notes.append(f"{where}{tname} capacity {size} bytes "
                         "(importer's choice; the EDS does not say)")
        elif kind in ("ostr", "domain") and n == 0:
            t["size"] = STRING_CAPACITY
            notes.append(f"{where}{tname} capacity {STRING_CAPACITY} bytes "
                         "(importer's choice; the EDS does not say)")
    return t


def convert_object(o: EdsObject, use_values: bool, node_id: int | None) -> tuple[dict, list[str]]:
    notes: list[str] = []
    if o.index < 0x1000:
        raise Unsupported("index below 0x1000 (data type definitions are not in the C "
                          "dictionary)")
    code = OBJECT_TYPES.get(o.object_type)
    if code not in ("VAR", "DOMAIN", "ARRAY", "RECORD"):
        raise Unsupported(f"ObjectType 0x{o.object_type:X} ({code or 'unknown'})")
    t: dict = {"index": Hex(o.index), "name": o.name}
    if code in ("VAR", "DOMAIN"):
        var = convert_sub(o.subs[0], o.index, notes, use_values, node_id, var=True)
        del var["name"]
        is_domain_type = var["type"] == "DOMAIN"
        if code == "VAR" and is_domain_type:
            t["object"] = "VAR"
        elif code == "DOMAIN" and not is_domain_type:
            raise Unsupported(f"a DOMAIN object (ObjectType 0x2) of data type {var['type']}")
        t.update(var)
        return t, notes
    t["object"] = code
    if not o.subs:
        raise Unsupported(f"an {code} without sub-entries")
    flags = _int(o.obj_flags, "ObjFlags")
    if flags is not None:
        t["obj_flags"] = Hex(flags)
    if o.extra:
        t["eds_keys"] = dict(o.extra)
    if o.links is not None:
        t["links"] = [Hex(i) for i in o.links]
    subs = {k: convert_sub(s, o.index, notes, use_values, node_id) for k, s in o.subs.items()}
    if o.compact:
        n = o.compact
        t["compact"] = True
        elems = [subs[k] for k in range(1, n + 1)]
        shared = [{k: v for k, v in e.items() if k not in ("name", "parameter_value",
                                                              "denotation")} for e in elems]
        if any(x != shared[0] for x in shared):   # --use-values gave elements own defaults
            notes.append(f"CompactSubObj={n} written out: the elements' defaults differ now")
            del t["compact"]
            t["subs"] = [{"sub": k, **v} for k, v in subs.items()]
            return t, notes
        per_element = any("parameter_value" in e or "denotation" in e for e in elems)
        if not per_element:
            element = {k: v for k, v in elems[0].items() if k != "name"}
            t["array"] = n
            t["element"] = element
            if any(e["name"] != f"{o.name}{k}" for k, e in enumerate(elems, 1)):
                t["names"] = [e["name"] for e in elems]
            return t, notes
        t["subs"] = [{"sub": k, **subs[k]} for k in range(1, n + 1)]
        return t, notes
    t["subs"] = [{"sub": k, **v} for k, v in subs.items()]
    return t, notes


def raw_object(o: EdsObject, eds: Eds, reason: str) -> dict:
    secs = {}
    for name in o.own_sections:
        sec = eds.sections[name.lower()]
        secs[name] = {k.name: k.value for k in sec.keys.values()}
    return {"index": Hex(o.index), "eds_only": reason, "sections": secs}


def _reason(msg: str, index: int) -> str:
    return re.sub(rf"^object 0x{index:04X}:? ?", "", msg)


# ------------------------------------------------------------ the file

def _date(text: str | None) -> str | None:
    m = re.fullmatch(r"(\d{1,2})-(\d{1,2})-(\d{4})", (text or "").strip())
    return f"{m.group(3)}-{int(m.group(1)):02d}-{int(m.group(2)):02d}" if m else None


def _time(text: str | None) -> str | None:
    m = re.fullmatch(r"(\d{1,2}):(\d{2})\s*([AaPp][Mm])?", (text or "").strip())
    if not m:
        return None
    h, mi, ap = int(m.group(1)), int(m.group(2)), (m.group(3) or "").upper()
    if ap:
        h = h % 12 + (12 if ap == "PM" else 0)
    return f"{h:02d}:{mi:02d}" if h < 24 and mi < 60 else None


class Importer:
    def __init__(self, eds: Eds, base: str, use_values: bool):
        self.eds, self.base, self.use_values = eds, base, use_values
        self.device: dict = {}
        self.eds_tbl: dict = {}
        self.sections: dict[str, dict[str, str]] = {}
        self.dcf: dict | None = None
        self.head_notes: list[str] = []
        self.objects: dict[int, tuple[dict, list[str]]] = {}
        self.eds_only: dict[int, str] = {}
        self.node_id: int | None = None
        self.mandatory = True

    def raw(self, sec: str, k: str, v: str) -> None:
        self.sections.setdefault(sec, {})[k] = v

    def head(self) -> None:
        e = self.eds
        fi, di = e.file_info, e.device_info
        dev = {"name": self.base}
        for k, ek in (("vendor_name", "VendorName"), ("product_name", "ProductName"),
                      ("order_code", "OrderCode")):
            if ek in di:
                dev[k] = di[ek]
        for k, ek in (("vendor_number", "VendorNumber"), ("product_number", "ProductNumber"),
                      ("revision_number", "RevisionNumber")):
            if ek in di:
                try:
                    v = parse_int(di[ek])
                    if not 0 <= v <= 0xFFFFFFFF:
                        raise ValueError
                    dev[k] = Hex(v)
                except ValueError:
                    self.raw("DeviceInfo", ek, di[ek])
        rates = []
        for r in BAUDRATES:
            k = f"BaudRate_{r}"
            if k in di:
                if di[k].strip() in ("0", "1"):
                    if di[k].strip() == "1":
                        rates.append(r)
                else:
                    self.raw("DeviceInfo", k, di[k])
        dev["baudrates"] = rates
        if "LSS_Supported" in di:
            if di["LSS_Supported"].strip() in ("0", "1"):
                dev["lss"] = di["LSS_Supported"].strip() == "1"
            else:
                self.raw("DeviceInfo", "LSS_Supported", di["LSS_Supported"])
        self.device = dev
        # DeviceInfo flags: stated when they differ from what odgen works out
        n_rpdo = sum(1 for i in e.objects if 0x1400 <= i <= 0x15FF)
        n_tpdo = sum(1 for i in e.objects if 0x1800 <= i <= 0x19FF)
        derived = {"simple_boot_up_master": 0, "simple_boot_up_slave": 1,
                   "granularity": 8 if n_rpdo or n_tpdo else 0, "dynamic_channels_supported": 0,
                   "compact_pdo": 0, "group_messaging": 0, "nr_of_rxpdo": n_rpdo,
                   "nr_of_txpdo": n_tpdo}
        t = self.eds_tbl
        for k, ek in EDS_DEVICE_INFO.items():
            if ek not in di:
                continue
            try:
                v = parse_int(di[ek])
            except ValueError:
                self.raw("DeviceInfo", ek, di[ek])
                continue
            flag = not (k.startswith("nr_of") or k == "granularity")
            if flag and v not in (0, 1) or not 0 <= v <= 0xFFFF:
                self.raw("DeviceInfo", ek, di[ek])
            elif v != derived[k]:
                t[k] = bool(v) if flag else v
        # FileInfo
        if "FileName" in fi and fi["FileName"] != f"{self.base}.eds":
            if fi["FileName"]:
                t["file_name"] = fi["FileName"]
            else:
                self.raw("FileInfo", "FileName", "")
        for k, ek in (("file_version", "FileVersion"), ("file_revision", "FileRevision")):
            if ek in fi:
                try:
                    v = parse_int(fi[ek])
                    if not 0 <= v <= 255:
                        raise ValueError
                    t[k] = v
                except ValueError:
                    self.raw("FileInfo", ek, fi[ek])
        if fi.get("EDSVersion", "4.0") != "4.0":
            if fi["EDSVersion"]:
                t["eds_version"] = fi["EDSVersion"]
            else:
                self.raw("FileInfo", "EDSVersion", "")
        if "Description" in fi:
            t["description"] = fi["Description"]
        for k, ek, conv in (("date", "CreationDate", _date), ("time", "CreationTime", _time),
                            ("modified_date", "ModificationDate", _date),
                            ("modified_time", "ModificationTime", _time)):
            if ek in fi:
                v = conv(fi[ek])
                if v is None:
                    self.raw("FileInfo", ek, fi[ek])
                else:
                    t[k] = v
        if "CreatedBy" in fi:
            t["author"] = fi["CreatedBy"]
        if "ModifiedBy" in fi:
            t["modified_by"] = fi["ModifiedBy"]
        elif "CreatedBy" in fi:
            pass   # odgen writes ModifiedBy = author: an addition, not a loss
        if "LastEDS" in fi:
            self.raw("FileInfo", "LastEDS", fi["LastEDS"])
        # no [Comments] is no comment lines (odgen's own two lines would be an addition)
        t["comments"] = list(e.comments or [])
        if e.dummy_usage:
            used = []
            for k, v in sorted(e.dummy_usage.items()):
                if v.strip() == "1":
                    used.append(k)
                elif v.strip() != "0":
                    self.raw("DummyUsage", f"Dummy{k:04d}", v)
            t["dummy_usage"] = used
        # DeviceComissioning
        if e.commissioning is not None:
            c = e.commissioning
            nid = c.get("NodeID")
            if nid is not None:
                try:
                    self.node_id = parse_int(nid)
                except ValueError:
                    pass
            if self.use_values:
                self.head_notes.append("--use-values: ParameterValues are the defaults; "
                                       "[DeviceComissioning] dropped")
            else:
                dcf = {}
                for k, ek in (("node_id", "NodeID"), ("node_name", "NodeName"),
                              ("baudrate", "Baudrate"), ("net_number", "NetNumber"),
                              ("network_name", "NetworkName"),
                              ("canopen_manager", "CANopenManager"),
                              ("lss_serial_number", "LSS_SerialNumber")):
                    if ek not in c:
                        continue
                    if k in ("node_name", "network_name"):
                        dcf[k] = c[ek]
                        continue
                    try:
                        v = parse_int(c[ek])
                        top = {"node_id": 127, "canopen_manager": 1}.get(k, 0xFFFFFFFF)
                        if not 0 <= v <= top:
                            raise ValueError
                        dcf[k] = bool(v) if k == "canopen_manager" else v
                    except ValueError:
                        self.raw("DeviceComissioning", ek, c[ek])
                self.dcf = dcf
                if not dcf:
                    self.sections.setdefault("DeviceComissioning", {})
        for name, keys in e.extra_keys.items():
            for k, v in keys.items():
                self.raw(name, k, v)
        for name, sec in e.other.items():
            self.sections[name] = {k.name: k.value for k in sec.keys.values()}

    def convert(self) -> None:
        for index, o in sorted(self.eds.objects.items()):
            try:
                tbl, notes = convert_object(o, self.use_values, self.node_id)
                _make_object(tbl, f"object 0x{index:04X}")
            except Unsupported as e:
                self.eds_only[index] = str(e)
                continue
            except DescError as e:
                self.eds_only[index] = _reason(str(e), index)
                continue
            self.objects[index] = (tbl, notes)

    def demote(self, index: int, reason: str) -> None:
        self.objects.pop(index, None)
        self.eds_only[index] = reason

    # ---------------------------------------------------------- writing

    def text(self) -> str:
        e = self.eds
        out = [f"# {self.base}: imported from {Path(e.source).name} by tools/odgen "
               f"(odgen.py import).",
               "# Review it like any description; the C dictionary, the EDS and the table",
               "# are generated from it. The importer took the generator's defaults where",
               "# the EDS does not say (storage: comm for 0x1000-0x1FFF, app otherwise;",
               "# const values in ROM; ro values in RAM; see the notes at the objects).",
               "# The C dictionary uses the defaults; parameter_value and denotation (DCF)",
               "# are written to the EDS only."]
        for n in self.head_notes:
            out.append(f"# {n}")
        for w in e.warnings:
            m = re.match(r".*?:(\d+): (.*)", w)
            out.append(f"# source line {m.group(1)}: {m.group(2)}" if m else
                       f"# source: {w.split(': ', 1)[-1]}")
        if self.eds_only:
            out.append(f"# {len(self.eds_only)} object(s) are eds_only: in the EDS, not in the "
                       "C dictionary (reasons at the objects).")
        out += ["", "[device]"]
        dev = dict(self.device)
        if not self.mandatory:
            out.append("# the source lacks some of 0x1000, 0x1001, 0x1018 (CiA 301 mandatory)")
            dev["mandatory_objects"] = False
        out += [f"{key(k)} = {toml(v)}" for k, v in dev.items()]
        out += ["", "[eds]"]
        out += [f"{key(k)} = {toml(v)}" for k, v in self.eds_tbl.items()]
        for name, keys in self.sections.items():
            out += ["", f"[eds.sections.{key(name)}]"]
            out += [f"{key(k)} = {toml(v)}" for k, v in keys.items()]
        if self.dcf is not None:
            out += ["", "[dcf]"] + [f"{key(k)} = {toml(v)}" for k, v in self.dcf.items()]
        for index in sorted(set(self.objects) | set(self.eds_only)):
            out.append("")
            if index in self.eds_only:
                t = raw_object(e.objects[index], e, self.eds_only[index])
                out += ["[[object]]", f"index = {toml(t['index'])}",
                        f"eds_only = {toml(t['eds_only'])}"]
                for name, keys in t["sections"].items():
                    out.append(f"[object.sections.{key(name)}]")
                    out += [f"{key(k)} = {toml(v)}" for k, v in keys.items()]
                continue
            tbl, notes = self.objects[index]
            out += [f"# {n}" for n in notes]
            out.append("[[object]]")
            for k, v in tbl.items():
                if k == "subs":
                    out.append("subs = [")
                    out += [f"  {toml(s)}," for s in v]
                    out.append("]")
                else:
                    out.append(f"{key(k)} = {toml(v)}")
        out.append("")
        return "\n".join(out)


def import_eds(path: str | Path, base: str | None = None, use_values: bool = False,
               warn=None) -> tuple[str, list[str]]:
    """The description text for the EDS/DCF at path, and the warnings (source
    problems, eds_only objects). EdsError for an unreadable file, DescError
    if the result does not load (a bug)."""
    eds = read_eds(path)
    base = base or re.sub(r"[^0-9A-Za-z_-]", "_", Path(path).stem)
    imp = Importer(eds, base, use_values)
    imp.head()
    imp.convert()
    for _ in range(len(eds.objects) + 3):
        text = imp.text()
        try:
            dev = loads(text, f"{base}.toml", base)
            gen_c.generate(dev, f"{base}.toml")
        except DescError as e:
            msg = str(e)
            m = re.match(r"object 0x([0-9A-F]{4})", msg)
            if m and int(m.group(1), 16) in imp.objects:
                index = int(m.group(1), 16)
                imp.demote(index, _reason(msg, index))
                continue
            if "mandatory object missing" in msg and imp.mandatory:
                imp.mandatory = False
                continue
            raise DescError(f"the imported description does not load: {msg}") from None
        # the self-check: odgen's EDS must state what the source states
        out = read_eds(f"{base}.eds", gen_eds.generate(dev, f"{base}.toml", f"{base}.eds"))
        diffs = differences(configured(eds, imp.node_id) if use_values else eds, out)
        by_obj: dict[int, str] = {}
        other = []
        for d in diffs:
            m = re.match(r"object 0x([0-9A-F]{4})", d)
            if m and int(m.group(1), 16) in imp.objects:
                by_obj.setdefault(int(m.group(1), 16), d)
            else:
                other.append(d)
        if other:
            raise DescError("the imported description would change the EDS: "
                            + "; ".join(other[:5]))
        if not by_obj:
            break
        for index, d in by_obj.items():
            imp.demote(index, "odgen would write it differently: " + _reason(d, index))
    else:
        raise DescError("the import does not settle (a bug)")
    warnings = list(eds.warnings)
    for index, why in sorted(imp.eds_only.items()):
        warnings.append(f"{path}:{eds.objects[index].line}: object 0x{index:04X} kept as "
                        f"eds_only (not in the C dictionary): {why}")
    return text, warnings


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="odgen.py import",
                                 description="EDS/DCF -> device description (.toml)")
    ap.add_argument("eds", help="CiA 306 EDS or DCF")
    ap.add_argument("-o", "--output", help="description to write (default: <eds stem>.toml "
                    "in the current directory)")
    ap.add_argument("--use-values", action="store_true",
                    help="DCF: ParameterValues become the defaults")
    args = ap.parse_args(argv)
    out = Path(args.output) if args.output else Path(Path(args.eds).stem + ".toml")
    base = re.sub(r"[^0-9A-Za-z_-]", "_", out.stem)
    try:
        text, warnings = import_eds(args.eds, base, args.use_values)
    except EdsError as e:
        print(f"error: {e}", file=sys.stderr)
        return 1
    except DescError as e:
        print(f"{args.eds}: error: {e}", file=sys.stderr)
        return 1
    for w in warnings:
        print(f"warning: {w}", file=sys.stderr)
    out.write_text(text, encoding="utf-8", newline="\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
