"""EDS back end: a CiA 306 (EDS version 4.0) electronic data sheet.

Everything CiA 306 defines that a description states is written: FileInfo,
DeviceInfo, DummyUsage, Comments, DeviceComissioning (DCF), the object lists,
and per object ParameterName, ObjectType, DataType, AccessType, DefaultValue,
PDOMapping, LowLimit/HighLimit, SubNumber or CompactSubObj (with
[xxxxName]/[xxxxValue]/[xxxxDenotation]), ObjFlags, ParameterValue,
Denotation and [xxxxObjectLinks]; then further keys and sections verbatim
(eds_keys, [eds.sections.*], eds_only objects).
"""
from __future__ import annotations

from model import DCF_KEYS, EDS_DEVICE_INFO, Device, Obj, RawObj, Sub

OBJTYPE = {"VAR": 0x7, "ARRAY": 0x8, "RECORD": 0x9, "DOMAIN": 0x2}
STANDARD_SECTIONS = ("FileInfo", "DeviceInfo", "DeviceComissioning", "DummyUsage", "Comments")


def eds_number(s: Sub, v: int) -> str:
    if s.kind == "int":
        return str(v)
    if s.kind == "bool" or s.fixed == 1:
        return str(v)
    return f"0x{v:0{2 * s.fixed}X}"


def eds_value(s: Sub, v, nodeid: bool, pad: bool = True) -> str | None:
    """A value of s as EDS text (None: nothing to write)."""
    if v is None:
        return None
    k = s.kind
    if nodeid:
        return f"$NODEID+0x{v:X}"   # also for +0: python-canopen needs the "+n"
    if k in ("int", "uint", "bool"):
        return eds_number(s, v)
    if k == "time":
        return f"0x{v:012X}"
    if k == "real":
        return repr(v)
    if k in ("vstr", "ustr"):
        return v if v else None
    # OCTET_STRING / stored DOMAIN: 2 hex digits per byte. The device holds
    # (and uploads) its whole capacity, so the default is padded with zeros.
    if pad:
        return v.ljust(s.size, b"\0").hex().upper() if v else None
    return v.hex().upper() if v else None


def eds_default(s: Sub) -> str | None:
    return eds_value(s, s.default, s.nodeid)


def eds_limit(s: Sub, v: int | None, nodeid: bool) -> str | None:
    if v is None:
        return None
    return f"$NODEID+0x{v:X}" if nodeid else eds_number(s, v)


def value_lines(s: Sub) -> list[str]:
    """DataType .. HighLimit of one sub-entry (or of the elements of a compact object)."""
    out = [f"DataType=0x{s.code:04X}", f"AccessType={s.access}"]
    d = eds_default(s)
    if d is not None:
        out.append(f"DefaultValue={d}")
    out.append(f"PDOMapping={1 if s.pdo else 0}")
    lo, hi = eds_limit(s, s.eds_low, s.low_nodeid), eds_limit(s, s.eds_high, s.high_nodeid)
    if lo is not None:
        out.append(f"LowLimit={lo}")
    if hi is not None:
        out.append(f"HighLimit={hi}")
    return out


def extra_lines(obj_flags: int | None, keys: dict[str, str]) -> list[str]:
    out = [] if obj_flags is None else [f"ObjFlags=0x{obj_flags:X}"]
    return out + [f"{k}={v}" for k, v in keys.items()]


def sub_lines(s: Sub, objtype: int = OBJTYPE["VAR"]) -> list[str]:
    out = [f"ParameterName={s.name}", f"ObjectType=0x{objtype:X}"] + value_lines(s)
    pv = eds_value(s, s.parameter_value, s.pv_nodeid, pad=False)
    if pv is not None:
        out.append(f"ParameterValue={pv}")
    if s.denotation:
        out.append(f"Denotation={s.denotation}")
    return out + extra_lines(s.obj_flags, s.eds_keys)


def numbered(head: str, count_key: str, entries: list[tuple[int, str]]) -> list[str]:
    return [head, f"{count_key}={len(entries)}"] + [f"{k}={v}" for k, v in entries] + [""]


def compact_sections(o: Obj) -> list[str]:
    elems = o.subs[1:]
    e1 = elems[0]
    out = [f"[{o.index:04X}]", f"ParameterName={o.name}", f"ObjectType=0x{OBJTYPE[o.code]:X}"]
    out += value_lines(e1)
    out += [f"CompactSubObj={len(elems)}"] + extra_lines(o.obj_flags, o.eds_keys) + [""]
    if any(s.name != f"{o.name}{s.sub}" for s in elems):
        out += numbered(f"[{o.index:04X}Name]", "NrOfEntries", [(s.sub, s.name) for s in elems])
    values = [(s.sub, eds_value(s, s.parameter_value, s.pv_nodeid, pad=False)) for s in elems]
    values = [(k, v) for k, v in values if v is not None]
    if values:
        out += numbered(f"[{o.index:04X}Value]", "NrOfEntries", values)
    dens = [(s.sub, s.denotation) for s in elems if s.denotation]
    if dens:
        out += numbered(f"[{o.index:04X}Denotation]", "NrOfEntries", dens)
    return out


def obj_sections(o: Obj) -> list[str]:
    head = f"[{o.index:04X}]"
    if o.code in ("VAR", "DOMAIN"):
        out = [head] + sub_lines(o.subs[0], OBJTYPE[o.code]) + [""]
    elif o.compact:
        out = compact_sections(o)
    else:
        out = [head, f"ParameterName={o.name}", f"ObjectType=0x{OBJTYPE[o.code]:X}",
               f"SubNumber=0x{len(o.subs):X}"] + extra_lines(o.obj_flags, o.eds_keys) + [""]
        for s in o.subs:
            out += [f"[{o.index:04X}sub{s.sub:X}]"] + sub_lines(s) + [""]
    if o.links is not None:
        out += numbered(f"[{o.index:04X}ObjectLinks]", "ObjectLinks",
                        [(k, f"0x{i:04X}") for k, i in enumerate(o.links, 1)])
    return out


def raw_sections(o: RawObj) -> list[str]:
    out = []
    for name, keys in o.sections:
        out += [f"[{name}]"] + [f"{k}={v}" for k, v in keys.items()] + [""]
    return out


def object_list(title: str, objs: list) -> list[str]:
    out = [f"[{title}]", f"SupportedObjects={len(objs)}"]
    out += [f"{k}=0x{o.index:04X}" for k, o in enumerate(objs, 1)]
    out.append("")
    for o in objs:
        out += raw_sections(o) if isinstance(o, RawObj) else obj_sections(o)
    return out


def section(name: str, lines: list[tuple[str, str]], extra: dict[str, str] | None) -> list[str]:
    """[name] with lines; extra keys replace lines of the same key or follow them."""
    extra = dict(extra or {})
    low = {k.lower(): k for k in extra}
    out = [f"[{name}]"]
    for k, v in lines:
        if k.lower() in low:
            v = extra.pop(low[k.lower()])
        out.append(f"{k}={v}")
    out += [f"{k}={v}" for k, v in extra.items()]
    return out + [""]


def t12(hhmm: str) -> str:
    hh, mm = (int(x) for x in hhmm.split(":"))
    return f"{(hh % 12) or 12:02d}:{mm:02d}{'AM' if hh < 12 else 'PM'}"


def mdy(date: str) -> str:
    y, m, d = date.split("-")
    return f"{m}-{d}-{y}"


def generate(dev: Device, toml_name: str, file_name: str) -> str:
    info, eds = dev.info, dev.eds
    extra = eds["sections"]
    n_rpdo = sum(1 for o in dev.objects if 0x1400 <= o.index <= 0x15FF)
    n_tpdo = sum(1 for o in dev.objects if 0x1800 <= o.index <= 0x19FF)
    out = []
    if eds["comments"] is not None:
        out += [f"; Generated by tools/odgen from {toml_name}. Do not edit: change the "
                "description and rebuild.", ""]
    out += section("FileInfo", [
        ("FileName", eds["file_name"] or file_name),
        ("FileVersion", str(eds["file_version"])),
        ("FileRevision", str(eds["file_revision"])),
        ("EDSVersion", eds["eds_version"]),
        ("Description", eds["description"]),
        ("CreationTime", t12(eds["time"])),
        ("CreationDate", mdy(eds["date"])),
        ("CreatedBy", eds["author"]),
        ("ModificationTime", t12(eds["modified_time"])),
        ("ModificationDate", mdy(eds["modified_date"])),
        ("ModifiedBy", eds["modified_by"])], extra.get("FileInfo"))

    derived = {"simple_boot_up_master": False, "simple_boot_up_slave": True,
               "granularity": 8 if n_rpdo or n_tpdo else 0, "dynamic_channels_supported": False,
               "compact_pdo": False, "group_messaging": False,
               "nr_of_rxpdo": n_rpdo, "nr_of_txpdo": n_tpdo}
    flags = []
    for k, key in EDS_DEVICE_INFO.items():
        v = eds[k] if eds[k] is not None else derived[k]
        flags.append((key, str(int(v))))
    out += section("DeviceInfo", [
        ("VendorName", info["vendor_name"]),
        ("VendorNumber", f"0x{info['vendor_number']:08X}"),
        ("ProductName", info["product_name"]),
        ("ProductNumber", f"0x{info['product_number']:08X}"),
        ("RevisionNumber", f"0x{info['revision_number']:08X}"),
        ("OrderCode", info["order_code"])]
        + [(f"BaudRate_{r}", "1" if r in info["baudrates"] else "0")
           for r in (10, 20, 50, 125, 250, 500, 800, 1000)]
        + flags + [("LSS_Supported", "1" if info["lss"] else "0")], extra.get("DeviceInfo"))
    if dev.dcf is not None or "DeviceComissioning" in extra:
        lines = []
        for k, key in DCF_KEYS.items():
            if dev.dcf and k in dev.dcf:
                v = dev.dcf[k]
                lines.append((key, str(int(v)) if isinstance(v, (bool, int)) else v))
        out += section("DeviceComissioning", lines, extra.get("DeviceComissioning"))
    out += section("DummyUsage", [(f"Dummy000{k}", "1" if k in eds["dummy_usage"] else "0")
                                  for k in range(1, 8)], extra.get("DummyUsage"))
    comments = eds["comments"]
    if comments is None:
        comments = [f"Generated by tools/odgen from {toml_name}.",
                    "Do not edit: change the description and rebuild."]
    out += section("Comments", [("Lines", str(len(comments)))]
                   + [(f"Line{k}", c) for k, c in enumerate(comments, 1)], extra.get("Comments"))
    for name, keys in extra.items():
        if name not in STANDARD_SECTIONS:
            out += section(name, [], keys)

    objs: list = sorted([*dev.objects, *dev.eds_only], key=lambda o: o.index)
    mandatory = [o for o in objs if o.index in (0x1000, 0x1001, 0x1018)]
    manufacturer = [o for o in objs if 0x2000 <= o.index <= 0x5FFF]
    optional = [o for o in objs if o not in mandatory and o not in manufacturer]
    out += object_list("MandatoryObjects", mandatory)
    out += object_list("OptionalObjects", optional)
    out += object_list("ManufacturerObjects", manufacturer)
    return "\n".join(out)
