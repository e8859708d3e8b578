"""C back end: the const object dictionary of a device for the core (stack/).

One .h/.c pair per device. The header has the RAM image type (communication
values first, then stored application values, then values not stored; within
each region sorted by alignment so there is no padding inside a region; the
core's own objects at their places, co_node.h's CO_RAM_*: core_places), the
hook slot numbers, the node bundle type and the co_dev_t. The .c has the ROM
image, the default image, the limits table and the entry/sub tables, sorted
by index/sub-index. Offsets are left to the C compiler (offsetof).
"""
from __future__ import annotations

import copy
import dataclasses
import struct
from dataclasses import dataclass, field

import personality
from model import F_COB16, F_CONST, F_MAP_R, F_MAP_T, F_NODEID, F_R, F_ROM, F_W, FLAG_NAMES, DescError, \
    Device, Sub, encoded_default

REGIONS = (("comm", "communication parameters (stored)"),
           ("app", "application values (stored)"),
           ("none", "values not stored (restored to defaults at reset)"))


@dataclass
class Field:
    name: str
    ctype: str                    # element C type
    dims: list[int]               # array dimensions after the name
    align: int
    size: int
    region: str                   # comm / app / none / rom
    subs: list[Sub] = field(default_factory=list)
    what: str = ""                # (a field of no object: what it is)

    def decl(self) -> str:
        return f"{self.ctype} {self.name}" + "".join(f"[{d}]" for d in self.dims)


def scalar_ctype(s: Sub) -> tuple[str, list[int], int]:
    """(C type, dims, alignment) of one value of s."""
    k, n = s.kind, s.fixed
    if k == "real":
        return ("float" if n == 4 else "double"), [], n
    if k in ("int", "uint", "bool") and n in (1, 2, 4, 8):
        return f"{'int' if k == 'int' else 'uint'}{8 * n}_t", [], n
    if k in ("int", "uint", "time"):
        return "uint8_t", [n], 1
    if k == "vstr":
        return "char", [s.size], 1
    return "uint8_t", [s.size], 1


def build_fields(dev: Device) -> list[Field]:
    fields: dict[str, Field] = {}
    order: list[Field] = []
    for o in dev.objects:
        for s in o.subs:
            if not s.field:
                continue
            if s.field in fields:
                f = fields[s.field]
                f.subs.append(s)
                if f.dims:
                    f.dims[0] += 1
                # (else one value several sub-entries read: STORE_CONST)
                f.size += s.size
                continue
            ctype, dims, align = scalar_ctype(s)
            region = "rom" if s.rom else s.storage
            dims = ([1] if s.elem == 0 else []) + dims
            f = Field(name=s.field, ctype=ctype, dims=dims, align=align, size=s.size,
                      region=region, subs=[s])
            fields[s.field] = f
            order.append(f)
    return order


def layout_end(fields: list[Field]) -> int:
    """Where a struct of these fields in this order ends (natural alignment,
    before the padding at its end)."""
    off = 0
    for f in fields:
        off = (off + f.align - 1) // f.align * f.align + f.size
    return off


def layout(fields: list[Field]) -> int:
    """Size of a struct of these fields in this order with natural alignment."""
    off, top = 0, 1
    for f in fields:
        off = (off + f.align - 1) // f.align * f.align + f.size
        top = max(top, f.align)
    return (off + top - 1) // top * top


def sort_region(fields: list[Field], region: str) -> list[Field]:
    sel = [f for f in fields if f.region == region]
    return sorted(sel, key=lambda f: (-f.align, f.subs[0].index, f.subs[0].sub))


# ----------------------------------------------------------- C literals

def c_int(s: Sub, v: int) -> str:
    n, k = s.fixed, s.kind
    if k in ("uint", "bool"):
        if n == 1:
            return f"{v}U"
        if n == 2:
            return f"0x{v:04X}U"
        if n == 4:
            return f"0x{v:08X}UL"
        return f"UINT64_C(0x{v:016X})"
    if n == 8:
        return "(-INT64_C(9223372036854775807) - 1)" if v == -(1 << 63) else f"INT64_C({v})"
    if n == 4:
        return "(-2147483647L - 1L)" if v == -(1 << 31) else f"{v}L"
    return str(v)


def c_bytes(data: bytes) -> str:
    return "{" + ", ".join(f"0x{b:02X}U" for b in data) + "}"


def c_string(text: str, size: int) -> str:
    if len(text) >= size:
        return "{" + ", ".join(repr(c) if c not in "'\\" else f"'\\{c}'" for c in text) + "}"
    out = []
    for c in text:
        out.append("\\" + c if c in "\"\\" else c)
    return '"' + "".join(out).replace("??", "?\\?") + '"'


def wire(s: Sub, v: int) -> bytes:
    n = s.fixed
    return (v & ((1 << (8 * n)) - 1)).to_bytes(n, "little")


def c_value(s: Sub) -> str | None:
    """Initialiser of one value, None for all-zero/absent."""
    v = s.default
    if v is None:
        return None
    k = s.kind
    if k == "real":
        if s.fixed == 4:
            x = struct.unpack("<f", struct.pack("<f", v))[0]
            return None if x == 0.0 and str(x)[0] != "-" else f"{x.hex()}f /* {v!r} */"
        return None if v == 0.0 and str(v)[0] != "-" else f"{v.hex()} /* {v!r} */"
    if k in ("int", "uint", "bool", "time"):
        if v == 0:
            return None
        if s.fixed in (1, 2, 4, 8) and k != "time":
            return c_int(s, v)
        return c_bytes(wire(s, v))
    if k == "vstr":
        return c_string(v, s.size) if v else None
    data = encoded_default(s)
    return c_bytes(data) if data else None


def store_command(s: Sub) -> bool:
    """A sub-entry of 0x1010 / 0x1011 the core acts on (co_store_is_command):
    its value is what the store service writes at every reset (the
    capability), never the description's default, which needs no room in
    the default image."""
    return s.index in (0x1010, 0x1011) and s.sub != 0 and s.type == "UNSIGNED32" and \
        not s.rom and not s.hookio


# Without storage (a core built with CO_STORAGE=0) the commands of 0x1010 /
# 0x1011 read 0 whatever is written (the store service refuses them): they
# need no RAM, all read this one const 0, writable (CO_SUB_ROM | CO_SUB_W:
# the store service takes the writes, co_store_is_command).
STORE_CONST = "store_command_none"


def consts(dev: Device, storage: bool) -> Device:
    """@p dev as the C tables hold it: without storage its store commands
    (store_command) one const 0; const values of one type, size and value
    one field of the ROM image (the identity's zeros, equal sub-index
    counts: a const is only ever read)."""
    dev = copy.deepcopy(dev)
    seen: dict = {}
    for o in dev.objects:
        for s in o.subs:
            if not storage and store_command(s):
                s.rom, s.field, s.elem, s.default, s.nodeid = True, STORE_CONST, -1, 0, False
            if s.rom and s.field and s.elem < 0:
                s.field = seen.setdefault((s.type, s.size, repr(s.default)), s.field)
    return dev


# PDO mapping entries (co_od.h, CO_OD_MAP_ENTRY): in the RAM image 16 bits,
# a reference to a dummy type (1..7) or to a row of the device's
# mappable-object table (MAP_ROW0 + k) and the bits mapped - 1; the
# dictionary's users see the UNSIGNED32 index:16 sub:8 bits:8
MAP_REF_SHIFT, MAP_ROW0 = 6, 8
MAP_ROWS_MAX = (1 << (16 - MAP_REF_SHIFT)) - MAP_ROW0


class MapEntrySub(Sub):
    """A PDO mapping entry as the C tables hold it: a row of type UNSIGNED32
    and size 2 (its 16-bit form in the RAM image, co_od.c converts)."""

    @property
    def fixed(self) -> int:
        return 2


def mappable(dev: Device) -> list[Sub]:
    """The device's mappable-object table (co_dev_t.maps): every sub-entry of
    a fixed-size type that may be mapped into a PDO, sorted by index and
    sub-index."""
    subs = [s for o in dev.objects for s in o.subs
            if (s.flags & (F_MAP_T | F_MAP_R)) and s.fixed != 0]
    return sorted(subs, key=lambda s: (s.index, s.sub))


def map_entry_form(v: int, rows: dict, what: str) -> int:
    """The 16-bit form of mapping entry @p v (rows: (index, sub) -> row)."""
    if v == 0:
        return 0
    index, sub, bits = v >> 16, (v >> 8) & 0xFF, v & 0xFF
    if 1 <= index <= 7 and sub == 0:
        ref = index
    elif (index, sub) in rows:
        ref = MAP_ROW0 + rows[(index, sub)]
    else:
        raise DescError(f"{what}: default 0x{v:08X} maps 0x{index:04X}:{sub:02X}, "
                        "which is not a mappable object of the device")
    if not 1 <= bits <= 64:
        raise DescError(f"{what}: default 0x{v:08X} maps {bits} bits (1..64)")
    return (ref << MAP_REF_SHIFT) | (bits - 1)


def map_entries(pdos, table: list[Sub]) -> None:
    """The mapping entries (sub 1..) of the PDOs' mapping objects as the C
    tables hold them (MapEntrySub, their defaults in their 16-bit forms)."""
    if len(table) > MAP_ROWS_MAX:
        raise DescError(f"{len(table)} mappable objects; a PDO mapping entry's 16-bit form "
                        f"(co_od.h CO_OD_MAP_ROWS_MAX) names at most {MAP_ROWS_MAX}")
    rows = {(s.index, s.sub): k for k, s in enumerate(table)}
    for _comm, mapping in pdos[0] + pdos[1]:
        for k, s in enumerate(mapping.subs):
            if s.sub == 0 or isinstance(s, MapEntrySub):
                continue
            m = MapEntrySub(**{f.name: getattr(s, f.name) for f in dataclasses.fields(s)})
            m.size = 2
            if s.default is not None:
                m.default = map_entry_form(int(s.default), rows,
                                           f"object 0x{s.index:04X}:{s.sub:02X}")
            mapping.subs[k] = m


# COB-IDs the core checks (co_od.h, CO_SUB_COB16): in the RAM image 16 bits,
# bits 31 and 30 in bits 15 and 14, the CAN-ID in bits 10..0; the
# dictionary's users see the UNSIGNED32. Also the SDO server's (0x1200 sub 1
# and 2) where no SDO client or RPDO can write them (ro: no service checks
# them; co_od_write refuses an application's value without a 16-bit form)
COB16_OBJECTS = {0x1005: (0,), 0x1012: (0,), 0x1014: (0,)}
COB16_READ_ONLY = {0x1200: (1, 2)}


class Cob16Sub(Sub):
    """A COB-ID as the C tables hold it: a row of type UNSIGNED32, size 2 and
    CO_SUB_COB16 (its 16-bit form in the RAM image, co_od.c converts)."""

    @property
    def fixed(self) -> int:
        return 2

    @property
    def flags(self) -> int:
        return super().flags | F_COB16


def cob16_form(v: int, nodeid: bool, what: str) -> int:
    """The 16-bit form of COB-ID default @p v (+ a node-ID 1..127 with @p nodeid)."""
    if v & 0x3FFFF800 or (nodeid and (v & 0x7FF) + 127 > 0x7FF):
        raise DescError(f"{what}: default 0x{v:08X}{' + $NODEID' if nodeid else ''} is not "
                        "an 11-bit COB-ID (bits 29..11 are 0: the core stores it in 16 bits)")
    return (v & 0x7FF) | ((v >> 16) & 0xC000)


def cob_forms(dev: Device, pdos) -> None:
    """The COB-IDs the core reads (SYNC, TIME, EMCY, the PDOs it runs) and the
    SDO server's, RAM values, as the C tables hold them (Cob16Sub, their
    defaults in their 16-bit forms)."""
    pdo_comm = {comm.index for comm, _m in pdos[0] + pdos[1]}
    for o in dev.objects:
        want = (1,) if o.index in pdo_comm else COB16_OBJECTS.get(o.index, ())
        ro = COB16_READ_ONLY.get(o.index, ())
        for k, s in enumerate(o.subs):
            if (s.sub not in want and not (s.sub in ro and s.access == "ro")) or \
                    s.type != "UNSIGNED32" or s.rom or s.hookio or not s.field or \
                    isinstance(s, Cob16Sub):
                continue
            c = Cob16Sub(**{f.name: getattr(s, f.name) for f in dataclasses.fields(s)})
            c.size = 2
            if s.default is not None:
                c.default = cob16_form(int(s.default), s.nodeid,
                                       f"object 0x{s.index:04X}:{s.sub:02X}")
            o.subs[k] = c


def field_init(f: Field) -> str | None:
    if f.dims and f.subs[0].elem == 0:
        vals = [c_value(s) for s in f.subs]
        if all(v is None for v in vals):
            return None
        zero = "{0}" if scalar_ctype(f.subs[0])[1] else "0"
        return "{" + ", ".join(v if v is not None else zero for v in vals) + "}"
    return c_value(f.subs[0])


def flags_expr(flags: int) -> str:
    names = [n for bit, n in FLAG_NAMES if flags & bit]
    return "(uint16_t)(" + " | ".join(names) + ")" if names else "0U"


def limit_lit(v: int) -> str:
    if v > (1 << 63) - 1:
        v -= 1 << 64      # UNSIGNED64 above INT64_MAX: the core compares as uint64_t
    if v == -(1 << 63):
        return "(-INT64_C(9223372036854775807) - 1)"
    return f"INT64_C({v})"


def comment(text: str) -> str:
    return text.replace("*/", "* /")


# ------------------------------------------------------------ emitters

def generate(dev: Device, toml_name: str, warn=None, storage: bool = True) -> tuple[str, str]:
    """The C dictionary (.h, .c); @p storage: the core is built with
    CO_STORAGE (without it the store commands need no RAM)."""
    dev = consts(dev, storage)
    cn = dev.cname
    up = cn.upper()
    pdos_h = pdo_table(dev, warn)
    # (a device without PDOs needs no table: nothing refers to it)
    maps = mappable(dev) if pdos_h[0] or pdos_h[1] else []
    map_entries(pdos_h, maps)
    # (after the table: a mappable COB-ID's row has its UNSIGNED32's size)
    cob_forms(dev, pdos_h)
    fields = build_fields(dev)
    blocks = pdo_blocks(dev, fields, pdos_h)
    # the core's objects at their places (co_node.h, CO_RAM_*): the head of
    # the image, the start of the values not stored
    head, end, core_checks = core_places(dev, fields)
    core = {f.name for f in head + end}
    blocks = [[f for f in b if f.name not in core] for b in blocks]
    in_block = {f.name for b in blocks for f in b} | core
    # the padding inside the head and a PDO's block (a TPDO's byte after its
    # SYNC start value) holds communication values of one byte that no block
    # has
    fill = [f for f in sort_region(fields, "comm") if f.name not in in_block and f.size == 1]
    head = fill_holes(head, fill)
    blocks = [fill_holes(b, fill) for b in blocks]
    in_block |= {f.name for b in blocks + [head] for f in b}
    ram = head + [f for b in blocks for f in b] + \
        [f for r, _ in REGIONS[:2] for f in sort_region(fields, r) if f.name not in in_block]
    if any(f.subs and f.subs[0].index == 0x1003 and f.subs[0].sub >= 1 for f in end):
        # (0x1003 sub 1 at app_end + 4: app_end a multiple of 4)
        gap = -layout_end(ram) % 4
        if gap:
            ram.append(Field(name="core_align", ctype="uint8_t", dims=[gap], align=1, size=gap,
                             region=ram[-1].region))
        fill = [f for f in sort_region(fields, "none") if f.name not in in_block and f.size == 1]
        end = fill_holes(end, fill)
        in_block |= {f.name for f in end}
    ram += end + [f for f in sort_region(fields, "none") if f.name not in in_block]
    share, same = shared_tables(dev, ram)
    # the const values only the tables of sharing PDOs name are left out: a
    # shared table names the first PDO's
    rom_used = {s.field for o in dev.objects
                if share.get(o.index, (o.index,))[0] == o.index for s in table_subs(o) if s.rom}
    rom = [f for f in sort_region(fields, "rom") if f.name in rom_used]
    if not ram:
        ram = [Field(name="unused", ctype="uint8_t", dims=[], align=1, size=1, region="none")]
    # SDO downloads of strings and DOMAINs held in RAM arrive in parts: they
    # gather in this staging area (not stored) and replace the value only
    # when complete and accepted, so a rejected transfer leaves the old one
    stage = max([sub.size for o in dev.objects for sub in o.subs
                 if sub.field and sub.fixed == 0 and not sub.rom and not sub.hookio
                 and (sub.flags & F_W)], default=0)
    if stage:
        ram.append(Field(name="sdo_stage", ctype="uint8_t", dims=[stage], align=1, size=stage,
                         region="none"))
    ram_size = layout(ram)
    if ram_size > 0xFFFF:
        raise DescError(f"RAM image is {ram_size} bytes; the core addresses at most 65535 "
                        "(use hookio for large values)")
    if layout(rom) > 0xFFFF:
        raise DescError(f"ROM image is {layout(rom)} bytes; at most 65535")
    n_pdo_h = len(pdos_h[0]) + len(pdos_h[1])
    hooked = [o for o in dev.objects if o.hook]
    n_hooks = len(hooked)
    banner = (f"/* Generated by tools/odgen from {toml_name} ({dev.name}). Do not edit:\n"
              f" * change the description and rebuild. */\n")

    # ---------------- header
    h = [banner, f"#ifndef CODEV_{up}_H", f"#define CODEV_{up}_H", "",
         "#include <stdint.h>", "#include <string.h>", "", '#include "co/co_node.h"', "",
         f"/** RAM image of one {dev.name} node ({ram_size} bytes on a host with natural",
         " *  alignment): 16/32/64-bit values are native integers, other types wire bytes. */",
         f"typedef struct {cn}_ram {{"]
    for region, title in REGIONS:
        sel = [f for f in ram if f.region == region]
        if not sel:
            continue
        h.append(f"    /* {title} */")
        for f in sel:
            if f.name == "sdo_stage":
                h.append(f"    {f.decl()}; /* SDO download staging (not an object) */")
                continue
            if not f.subs:
                h.append(f"    {f.decl()}; /* {f.what} */")
                continue
            s0 = f.subs[0]
            if f.subs[0].elem == 0:
                where = f"0x{s0.index:04X}:{s0.sub:02X}..{f.subs[-1].sub:02X}"
                what = dev_obj_name(dev, s0.index)
            elif f.subs:
                where = f"0x{s0.index:04X}:{s0.sub:02X}"
                what = s0.name
            h.append(f"    {f.decl()}; /* {where} {comment(what)} */" if f.subs else
                     f"    {f.decl()};")
    # (not objects: the node's PDO states and hook table, co_dev_t.pdo_at,
    # hooks_at; the image ends where they start)
    tail = []
    if n_pdo_h:
        tail.append("pdo")
        h += ["    /* (not an object: the node's PDO states, co_dev_t.pdo_at) */",
              f"    co_pdo_t pdo[{n_pdo_h}U];"]
    if n_hooks:
        tail.append("hooks")
        h += ["    /* (not an object: the node's hook table, co_dev_t.hooks_at) */",
              f"    co_od_hook_t hooks[{n_hooks}U];"]
    h += [f"}} {cn}_ram_t;", "",
          f"/** The const description of the {dev.name} device type. */",
          f"extern const co_dev_t {cn}_dev;", "",
          f"/* Hook slots (co_od_bind_hook binds by index; these are the slot numbers). */"]
    for o in hooked:
        h.append(f"#define {up}_HOOK_{o.index:04X} {o.hook_slot}U /* {comment(o.name)} */")
    h += [f"#define {up}_N_HOOKS {n_hooks}U", "",
          f"/** A {dev.name} node with its storage: RAM image (with the PDO states and",
          " *  hook table). */",
          f"typedef struct {cn}_node {{",
          "    co_node_t node;",
          f"    {cn}_ram_t ram;",
          f"}} {cn}_node_t;", "",
          "/** Zero @p cfg and point it at the device and the RAM image (with the PDO",
          " *  states and hook table) of @p n; the caller sets hal, node_id and callbacks,",
          " *  then co_node_init()",
          " *  (inline: one caller, no call). */",
          f"static inline void {cn}_config({cn}_node_t *n, co_node_config_t *cfg)",
          "{",
          "    (void)memset(cfg, 0, sizeof *cfg);",
          f"    cfg->dev = &{cn}_dev;",
          f"    cfg->ram = &n->ram; /* (and its {n_pdo_h} PDO states, {n_hooks} hook slots) */",
          "}", "",
          f"#endif /* CODEV_{up}_H */", ""]

    # ---------------- source
    c = [banner, f'#include "{cn}.h"', "", "#include <stddef.h>", "#include <string.h>", "",
         "/* The RAM image offsets fit the core's 16-bit offsets. */",
         f"typedef char {cn}_ram_fits[(sizeof({cn}_ram_t) <= 0xFFFFU) ? 1 : -1];"]
    if any(s.kind == "real" for o in dev.objects for s in o.subs):
        c += ["/* REAL32/REAL64 values are IEEE 754 float/double. */",
              f"typedef char {cn}_real_sizes[((sizeof(float) == 4U) && (sizeof(double) == 8U)) ? 1 : -1];"]
    c.append("")
    # the rows of every table, one after the other (co_dev_t.rows), in the
    # ROM image after the const values (an implicit sub-index 0 reads the
    # last row's sub-index there: CO_OD_TAG_SUB0); an entry names its first
    # row (co_od_entry_t.rows)
    first_row: dict[int, int] = {}
    rl: list[str] = []
    n_rows = 0
    ram_off = offsets(ram)
    joins: list[str] = []   # (the places runs across fields rely on)
    # an object of one RAM value of its own (no hook, no table shared) whose
    # row is, but for its offset, a row already in the table uses that row:
    # its base is the distance between the two values (modulo 2^16, as the
    # core adds them); {row's (sub, type, flags, size, limit): (its number,
    # its offset)}, and {object: its base}
    one_rows: dict = {}
    var_base: dict[int, str] = {}
    for o in dev.objects:
        sh = share.get(o.index)
        if sh is not None and sh[0] != o.index:
            continue    # the table of the first PDO of its shape
        own = table_subs(o)
        key = None
        if len(own) == 1 and not o.hook and sh is None and not implicit0(o):
            s0 = own[0]
            if s0.field and not s0.rom and not s0.hookio:
                key = (s0.sub, s0.type, s0.flags, s0.size, s0.limit_slot)
        if key is not None and key in one_rows:
            first_row[o.index], at0 = one_rows[key]
            var_base[o.index] = f"(uint16_t)({off_expr(own[0])} - {at0})"
            rl.append(f"        /* 0x{o.index:04X} {comment(o.name)} ({o.code}): row "
                      f"{first_row[o.index]}, its RAM offset from its base */")
            continue
        first_row[o.index] = n_rows
        rl.append(f"        /* {n_rows}: 0x{o.index:04X} {comment(o.name)} ({o.code})" +
                  (f", its RAM offsets from F({sh[1]}): the table of every PDO of this shape"
                   if sh is not None and sh[1] is not None else
                   ": the table of every object of these const values" if sh is not None
                   else "") + (", sub-index 0 implicit" if implicit0(o) else "") + " */")
        for run in rows(table_subs(o), ram_off):
            s = run[0]
            n_rows += 1
            joins += run_joins(run)
            if s.hookio:
                off = "0U"
            else:
                m = "R" if s.rom else "F"
                off = f"{m}({s.field})" if s.elem <= 0 else \
                    f"(uint16_t)({m}({s.field}) + {s.elem * s.size}U)"
                if sh is not None and not s.rom:
                    off = f"(uint16_t)({off} - F({sh[1]}))"
                elif o.hook and not s.rom:
                    off = f"(uint16_t)({off} - {o.hook_slot}U)"   # (from its base, its slot)
            lim = f"{s.limit_slot}U" if s.limit_slot >= 0 else "0U"
            if len(run) == 1 and not o.hook and not s.rom and not s.hookio and s.field:
                one_rows.setdefault((s.sub, s.type, s.flags, s.size, s.limit_slot),
                                    (n_rows - 1, off))
            if len(run) == 1:
                rl.append(f"        CO_OD_SUB(0x{s.sub:02X}U, (uint8_t)CO_{s.type}, "
                          f"{flags_expr(s.flags)}, "
                          f"{s.size}U, {off}, {lim}), /* {comment(s.name)} */")
            else:
                rl.append(f"        CO_OD_RUN(0x{s.sub:02X}U, {len(run)}U, (uint8_t)CO_{s.type}, "
                          f"{flags_expr(s.flags)}, {s.size}U, {off}, {lim}), "
                          f"/* {comment(s.name)} .. {comment(run[-1].name)} */")
    if n_rows > 0xFFFF:
        raise DescError(f"{n_rows} rows of sub-entries: the core's tables hold at most 65535")
    if layout(rom) + 8 * n_rows > 0xFFFF:
        raise DescError(f"ROM image is {layout(rom) + 8 * n_rows} bytes with the rows; at most 65535")
    c += [f"#define F(field) ((uint16_t)offsetof({cn}_ram_t, field))", "",
          "/* The core's objects at their places (co_node.h, CO_RAM_*; co_node_init",
          " * refuses a device with them elsewhere). */",
          f"typedef char {cn}_core_at[(" + " &&\n    ".join(core_checks) + ") ? 1 : -1];", "",
          "/* Const values (CO_SUB_ROM), then the rows of the objects' tables. */",
          f"typedef struct {cn}_rom {{"]
    for f in rom:
        s0 = f.subs[0]
        c.append(f"    {f.decl()}; /* 0x{s0.index:04X}:{s0.sub:02X} {comment(s0.name)} */")
    c += [f"    co_od_sub_t rows[{n_rows}U]; /* co_dev_t.rows */",
          f"}} {cn}_rom_t;", "",
          f"#define R(field) ((uint16_t)offsetof({cn}_rom_t, field))", "",
          f"static const {cn}_rom_t rom = {{"]
    for f in rom:
        v = field_init(f)
        c.append(f"    .{f.name} = {v if v is not None else ('{0}' if f.dims else '0U')},")
    c += ["    .rows = {", *rl, "    },", "};", ""]
    if joins:
        c += ["/* the runs of values of fields of their own have them one after the other */",
              f"typedef char {cn}_run_joins[(" + " &&\n    ".join(joins) + ") ? 1 : -1];", ""]
    # sparse defaults (co_dev_t.defaults, co_od.h): runs of the values that
    # are not zero and of the $NODEID ones, in the order of their places in
    # the RAM image, as wire bytes; the core zeroes the rest. A $NODEID value
    # is a run of its own, marked for the core to add the node-ID (or, for a
    # PDO or EMCY COB-ID, the COB-ID base of LSS) to it: the core never walks
    # the dictionary to find them.
    runs = default_runs(ram)
    n_default_at = len(runs)
    if runs:
        c += ["/* Defaults of the RAM image (co_od.h, CO_OD_DEF_RUN): the values that are",
              " * not zero and the $NODEID ones (the core adds the node-ID to them), in",
              " * the order of their places, as wire bytes. */",
              "static const uint8_t defaults[] = {"]
        checks, end, n_bytes = [], "0U", 0
        for r in runs:
            head = f"CO_OD_DEF_RUN({r.n}U, {r.w}U)"
            if r.flags:
                head = f"(uint8_t)({head} | {' | '.join(r.flags)})"
            gap = f"(uint8_t)({r.at} - ({end}))" if r.at is not None else "255U"
            c.append(f"    {gap}, {head}, {', '.join(f'0x{x:02X}U' for x in r.data)},"
                     f" /* {comment(r.what)} */")
            if r.at is not None:
                checks.append(f"((int){r.at} <= 255)" if end == "0U" else
                              f"((int){r.at} - (int)({end}) >= 0) && "
                              f"((int){r.at} - (int)({end}) <= 255)")
                checks += [f"({x} == {y})" for x, y in r.joins]
                end = f"{r.at} + {len(r.data)}U"
            else:
                end = f"{end} + 256U"   # (a zero byte after a gap of 255)
            n_bytes += 2 + len(r.data)
        c += ["};", f"typedef char {cn}_default_runs[((sizeof defaults == {n_bytes}U) &&\n    " +
              " &&\n    ".join(checks) + ") ? 1 : -1];", ""]
    if dev.limits:
        c.append("static const co_od_limit_t limits[] = {")
        for lo, hi in dev.limits:
            c.append(f"    {{{limit_lit(lo)}, {limit_lit(hi)}}},")
        c += ["};", ""]
    if dev.boot_emcy_data is not None:
        c += [f"static const uint8_t boot_emcy[5] = {c_bytes(bytes(dev.boot_emcy_data))};", ""]
    c += [""]
    c += ["static const co_od_entry_t od[] = {"]
    for o in dev.objects:
        hook = f"{o.hook_slot + 1}U" if o.hook else "0U"
        sh = share.get(o.index)
        nrows = len(rows(table_subs(o), ram_off))
        at = first_row[(sh or (o.index,))[0]]
        if implicit0(o):
            base = f"{o.hook_slot}U" if o.hook else \
                (f"F({sh[1]})" if sh is not None and sh[1] is not None else "0U")
            c.append(f"    CO_OD_ENTRY_TAG(0x{o.index:04X}U, {nrows}U, {at}U, {base}, "
                     f"(uint8_t)(CO_OD_TAG(0x{o.index:04X}U, CO_OBJ_{o.code}, "
                     f"{'true' if o.hook else 'false'}) | CO_OD_TAG_SUB0)),")
        elif o.index in var_base:
            c.append(f"    CO_OD_ENTRY_AT(0x{o.index:04X}U, {nrows}U, "
                     f"(uint8_t)CO_OBJ_{o.code}, {at}U, {var_base[o.index]}),")
        elif sh is None or sh[1] is None:
            c.append(f"    CO_OD_ENTRY(0x{o.index:04X}U, {nrows}U, {hook}, "
                     f"(uint8_t)CO_OBJ_{o.code}, {at}U),")
        else:
            c.append(f"    CO_OD_ENTRY_AT(0x{o.index:04X}U, {nrows}U, "
                     f"(uint8_t)CO_OBJ_{o.code}, {at}U, F({sh[1]})),")
    c += ["};", ""]
    conds = []
    for o, lead in same:
        # every object that uses another's table has its values where it says
        for s, ls in zip(o.subs, lead.subs):
            # (one value or array of its own: the distances are its own)
            if s.field and not s.rom and not s.hookio and \
                    len({x.field for x in o.subs if x.field and not x.rom}) > 1:
                conds.append(f"({off_expr(s)} - F({share[o.index][1]}) == "
                             f"{off_expr(ls)} - F({share[lead.index][1]}))")
    if conds:
        c += ["/* the objects that share a table have the same layout */",
              f"typedef char {cn}_shapes[(" + " &&\n    ".join(conds) + ") ? 1 : -1];", ""]

    pdos = pdos_h
    n_pdo = len(pdos[0]) + len(pdos[1])
    if n_pdo:
        c += ["/* Where each PDO's parameters live (RPDOs, then TPDOs). */",
              "static const co_pdo_desc_t pdo[] = {"]
        at = offsets(ram)
        checks = []
        for comm, mapping in pdos[0] + pdos[1]:
            cs = {x.sub: x for x in comm.subs}
            ms = {x.sub: x for x in mapping.subs}
            n_map = len(mapping.subs) - 1

            def off(x):
                return at[x.field] + max(x.elem, 0) * x.size
            # where co_pdo_desc_t has the core look: the entries right before
            # their number, the transmission type right after it, the optional
            # parameters at most 255 bytes after the COB-ID (pdo_blocks lays
            # them out so)
            rel = {k: off(cs[k]) - off(cs[1]) for k in (6, 3, 5) if k in cs}
            if off(ms[1]) + 2 * n_map != off(ms[0]) or off(cs[2]) != off(ms[0]) + 1 or \
                    any(not 0 < r <= 255 for r in rel.values()):
                raise DescError(f"object 0x{comm.index:04X}: the parameters of a PDO must be "
                                "stored with the communication parameters, of no other object")
            checks += [f"({off_expr(ms[1])} + {2 * n_map}U == {off_expr(ms[0])})",
                       f"({off_expr(cs[2])} == {off_expr(ms[0])} + 1U)"] + \
                [f"({off_expr(cs[k])} == {off_expr(cs[1])} + {r}U)" for k, r in rel.items()]
            c.append(f"    {{{off_expr(cs[1])}, {off_expr(ms[0])}, {n_map}U, "
                     f"{rel.get(6, 0)}U, {rel.get(3, 0)}U, {rel.get(5, 0)}U}}, "
                     f"/* 0x{comm.index:04X} */")
        c += ["};", "",
              "/* each PDO's parameters where co_pdo_desc_t says */",
              f"typedef char {cn}_pdo_at[(" + " &&\n    ".join(checks) + ") ? 1 : -1];", ""]

    if maps:
        c += ["/* The mappable objects (co_od_map_t), which the PDO mapping entries in the",
              " * RAM image name by their row. */",
              "static const co_od_map_t maps[] = {"]
        for m in maps:
            info = [f"{m.fixed - 1}U"] + (["CO_OD_MAP_SIGNED"] if m.kind == "int" else [])
            if m.field and not m.rom and not m.hookio:
                off = off_expr(m)
                info.append(f"((({off} + 8U) > sizeof({cn}_ram_t)) ? CO_OD_MAP_AT_END : 0U)")
            else:
                off = "0U"
            c.append(f"    {{0x{m.index:04X}U, 0x{m.sub:02X}U, (uint8_t)({' | '.join(info)}), "
                     f"{off}}}, /* {comment(m.name)} */")
        c += ["};", ""]

    masks = mask_table(dev, len(pdos[1]))
    if masks:
        c += ["/* Change masks of the TPDOs (set.tpdo.change_mask): where sub 1 of each lives. */",
              "static const uint16_t tpdo_mask[] = {"]
        c += [f"    {off_expr(m)}, /* 0x{m.index:04X} */" for m in masks]
        c += ["};", ""]

    # the end of the RAM image (the hook table follows it)
    img_end = (f"(uint16_t)offsetof({cn}_ram_t, {tail[0]})" if tail else
               f"(uint16_t)sizeof({cn}_ram_t)")

    def first(region_names):
        for r in region_names:
            sel = [f for f in ram if f.region == r and f.name != "sdo_stage"]
            if sel:
                return f"F({sel[0].name})"
        return img_end

    c += [f"const co_dev_t {cn}_dev = {{",
          "    .od = od,",
          "    .rows = rom.rows,",
          "    .od_count = (uint16_t)(sizeof od / sizeof od[0]),",
          f"    .ram_size = {img_end},",
          f"    .comm_end = {first(('app', 'none'))},",
          f"    .app_end = {first(('none',))},",
          f"    .defaults = {'defaults' if runs else 'NULL'},",
          "    .rom = (const uint8_t *)&rom,",
          f"    .limits = {'limits' if dev.limits else 'NULL'},",
          f"    .n_hooks = {up}_N_HOOKS,",
          *([f"    .hooks_at = (uint16_t)offsetof({cn}_ram_t, hooks),"] if n_hooks else []),
          *([f"    .pdo_at = (uint16_t)offsetof({cn}_ram_t, pdo),"] if n_pdo_h else []),
          *personality.settings_guarded(dev.options),
          f"    .boot_emcy_data = {'boot_emcy' if dev.boot_emcy_data is not None else 'NULL'},",
          f"    .pdo = {'pdo' if n_pdo else 'NULL'},",
          f"    .maps = {'maps' if maps else 'NULL'},",
          f"    .n_maps = {len(maps)}U,",
          f"    .n_rpdo = {len(pdos[0])}U,",
          f"    .n_tpdo = {len(pdos[1])}U,",
          f"    .tpdo_mask = {'tpdo_mask' if masks else 'NULL'},",
          f"    .lss_bit_timings = 0x{dev.info['lss_bit_timings'] if dev.info['lss'] else 0:04X}U,",
          f"    .nodeid_index = 0x{(dev.nodeid_object or 0):04X}U,",
          f"    .stage = {'F(sdo_stage)' if stage else '0U'},",
          f"    .stage_size = {stage}U,",
          f"    .n_defaults = {n_default_at}U,",
          "};", ""]
    return "\n".join(h), "\n".join(c)


def owners_of(dev: Device) -> dict[str, set[int]]:
    """The objects whose sub-entries name each RAM/ROM field."""
    owners: dict[str, set[int]] = {}
    for o in dev.objects:
        for s in o.subs:
            if s.field:
                owners.setdefault(s.field, set()).add(o.index)
    return owners


def pdo_blocks(dev: Device, fields: list[Field], pdos) -> list[list[Field]]:
    """The RAM values of each PDO (both its objects) as one block at the start
    of the communication region, in an order that gives PDOs of the same
    shape the same layout and, without padding for CiA 301's parameters, the
    mapping parameters the same layout in RPDOs and TPDOs: the 4-byte values
    (COB-ID), the mapping entries, the number of entries, then the rest by
    growing alignment (transmission type, SYNC start value, inhibit time,
    event timer)."""
    by_name = {f.name: f for f in fields}
    owners = owners_of(dev)
    blocks = []
    for comm, mapping in pdos[0] + pdos[1]:
        objs = {comm.index, mapping.index}
        names: list[str] = []
        for o in (comm, mapping):
            for s in o.subs:
                if s.field and not s.rom and s.field not in names:
                    names.append(s.field)
        block = [by_name[n] for n in names]
        if not block or any(owners[n] - objs for n in names) or \
                any(f.region != "comm" for f in block):
            continue
        entries = [f for f in block if f.subs[0].index == mapping.index and f.subs[0].sub != 0]
        count = [f for f in block if f.subs[0].index == mapping.index and f.subs[0].sub == 0]
        # (the parameters the core reads first, in co_pdo_desc_t's order; any
        # other sub-entry after them)
        other = [f for f in block if f not in entries + count and
                 (f.subs[0].index != comm.index or f.subs[0].sub not in PDO_COMM_TYPES)]
        big = [f for f in block if f not in entries + count + other and
               (f.align >= 4 or (f.subs[0].index, f.subs[0].sub) == (comm.index, 1))]
        rest = [f for f in block if f not in entries + count + big + other]
        rest.sort(key=lambda f: (f.align, f.subs[0].index, f.subs[0].sub))
        other.sort(key=lambda f: (-f.align, f.subs[0].index, f.subs[0].sub))
        blocks.append(big + entries + count + rest + other)
    return blocks


# The core's objects at their places in the RAM image (co_node.h, CO_RAM_*):
# (index, sub, type, the place's name); the head of the image (stored with
# the communication parameters), then 0x1016 sub 1.. from CO_RAM_1016, and
# from app_end (the values not stored) 0x1001, 0x1003 sub 0, then 0x1003
# sub 1.. from app_end + 4.
CORE_HEAD = ((0x1007, "UNSIGNED32", "CO_RAM_1007"), (0x1005, "COB16", "CO_RAM_1005"),
             (0x1014, "COB16", "CO_RAM_1014"), (0x1015, "UNSIGNED16", "CO_RAM_1015"),
             (0x1017, "UNSIGNED16", "CO_RAM_1017"), (0x1019, "UNSIGNED8", "CO_RAM_1019"))
CORE_END = ((0x1001, "UNSIGNED8", "CO_RAM_END_1001"), (0x1003, "UNSIGNED8", "CO_RAM_END_1003"))
CORE_ARRAYS = {0x1016: ("comm", "CO_RAM_1016"), 0x1003: ("none", "CO_RAM_END_1003_1")}
CTYPES = {"UNSIGNED8": ("uint8_t", 1), "UNSIGNED16": ("uint16_t", 2),
          "UNSIGNED32": ("uint32_t", 4), "COB16": ("uint16_t", 2)}


def core_places(dev: Device, fields: list[Field]):
    """The fields of the core's objects in their places: (head, end, the
    source's checks of the places). An object the device lacks, or holds in
    ROM or behind a hook (the core does not use it), leaves a field of zeros
    of no object in its place; one of another type or storage is an error
    (the core would refuse the device)."""
    subs = {(s.index, s.sub): s for o in dev.objects for s in o.subs}
    by_name = {f.name: f for f in fields}

    def used(s) -> bool:
        return s is not None and bool(s.field) and not s.rom and not s.hookio

    def wrong(s, typ: str, region: str) -> None:
        if typ == "COB16":
            typ = "UNSIGNED32"   # (a COB-ID: cob_forms gave it its 16-bit form)
        if s.type != typ:
            raise DescError(f"object 0x{s.index:04X} sub {s.sub}: the core reads it as {typ}, "
                            f"not {s.type}")
        if s.storage != region:
            raise DescError(f"object 0x{s.index:04X} sub {s.sub}: the core has it "
                            + ("with the communication parameters" if region == "comm"
                               else "with the values not stored")
                            + f", not storage {s.storage!r}")

    def place(index: int, typ: str, region: str, where: str) -> tuple[Field, str]:
        s = subs.get((index, 0))
        if used(s):
            wrong(s, typ, region)
            f = by_name[s.field]
            if len(f.subs) != 1:
                raise DescError(f"object 0x{index:04X}: the core needs a value of its own")
            return f, where
        ctype, n = CTYPES[typ]
        return Field(name=f"core_x{index:04X}", ctype=ctype, dims=[], align=n, size=n,
                     region=region, what=f"no 0x{index:04X}: zeros in its place, {where}"), where

    def array(index: int) -> list[tuple[Field, str]]:
        region, where = CORE_ARRAYS[index]
        out: list[Field] = []
        for s in sorted((s for (i, _), s in subs.items() if i == index and s.sub >= 1),
                        key=lambda s: s.sub):
            if used(s):
                wrong(s, "UNSIGNED32", region)
                f = by_name[s.field]
                if f not in out:
                    out.append(f)
        # (the core reads sub 1.. one after the other: the source checks the
        # runs, run_joins, and co_node_init counts them)
        return [(f, where if k == 0 else "") for k, f in enumerate(out)]

    head = [place(i, t, "comm", w) for i, t, w in CORE_HEAD] + array(0x1016)
    end = [place(i, t, "none", w) for i, t, w in CORE_END] + array(0x1003)
    if len(end) > 2 and not used(subs.get((0x1003, 0))):
        raise DescError("object 0x1003: the core counts the errors in sub 0: give it a value "
                        "in RAM (sub0 with access rw)")
    checks = [f"(F({f.name}) == {w})" for f, w in head if w] + \
        [f"(F({f.name}) == F({end[0][0].name}) + {w})" for f, w in end[1:] if w]
    return [f for f, _ in head], [f for f, _ in end], checks


def fill_holes(block: list[Field], fill: list[Field]) -> list[Field]:
    """@p block (starting aligned) with the padding bytes before its values
    taken by one-byte fields of @p fill (removed from it)."""
    out, off = [], 0
    for f in block:
        while fill and off % f.align != 0:
            out.append(fill.pop(0))
            off += 1
        off = (off + f.align - 1) // f.align * f.align + f.size
        out.append(f)
    return out


def rows(subs, at: dict[str, int]) -> list[list]:
    """The rows of an object's table: runs of sub-entries of one row each
    (co_od_sub_t with CO_OD_RUN): consecutive sub-indices of one fixed-size
    type, access, size and limit whose values are consecutive elements of
    one array field of the RAM image, or RAM values of at most 4 bytes one
    right after the other in the layout @p at (offsets(): fields of their
    own; the source checks the places, run_joins), or one const value (one
    field of the ROM image), up to 64 of them (co_od.h, CO_SUB_RUN_SHIFT); any other sub-entry is a
    row of its own."""
    out: list[list] = []
    for s in subs:
        r = out[-1] if out else None
        p = r[-1] if r else None
        if p is not None and len(r) < 64 and s.sub == p.sub + 1 and s.type == p.type and \
                s.fixed != 0 and s.size == s.fixed and s.size == p.size and \
                s.flags == p.flags and s.limit_slot == p.limit_slot and s.rom == p.rom and \
                not s.hookio and not p.hookio and s.field and p.field and \
                ((not s.rom and s.field == p.field and p.elem >= 0 and s.elem == p.elem + 1) or
                 (not s.rom and s.field != p.field and s.size <= 4 and
                  ram_at(at, s) == ram_at(at, p) + p.size) or
                 (s.rom and s.field == p.field and s.elem == p.elem)):
            r.append(s)
        else:
            out.append([s])
    return out


def ram_at(at: dict[str, int], s) -> int:
    """Where RAM value @p s is in the layout @p at (offsets())."""
    return at[s.field] + max(s.elem, 0) * s.size


def run_joins(run) -> list[str]:
    """The checks of the source for a run of rows() (C conditions): each RAM
    value in a field after the previous one's is right after it."""
    return [f"({off_expr(s)} == {off_expr(p)} + {p.size}U)"
            for p, s in zip(run, run[1:]) if not s.rom and s.field != p.field]


def offsets(ram: list[Field]) -> dict[str, int]:
    """Where each field of the RAM image is with natural alignment (what a
    C compiler does for 1-, 2- and 4-byte values; the generated source checks
    every offset a shared table relies on)."""
    out, off = {}, 0
    for f in ram:
        off = (off + f.align - 1) // f.align * f.align
        out[f.name] = off
        off += f.size
    return out


def shared_tables(dev: Device, ram: list[Field]):
    """Objects of the same shape (the same sub-entries, types, access, const
    values, and the same distances between their RAM values) share the table
    of the first of them: its RAM offsets count from the object's first value
    (co_od_entry_t.base). Returns (share, same): share {object index: (index
    of the object whose table it uses, name of the object's first RAM
    value)} for every object of a shape that more than one has; same
    [(object, object whose table it uses)] for the compile-time checks."""
    owners = owners_of(dev)
    at = offsets(ram)
    by_name = {f.name: f for f in ram}
    share, same = {}, []
    first: dict = {}
    for o in dev.objects:
        names = {s.field for s in o.subs if s.field and not s.rom and not s.hookio}
        if o.hook:
            continue    # (a hooked object's base is its hook slot: rows of its own)
        if not names and not all(s.rom for s in o.subs):
            continue
        if any(owners[n] != {o.index} or n not in by_name for n in names):
            continue
        if len(names) > 1 and any(by_name[n].align > 4 for n in names):
            continue   # an 8-byte value's alignment differs between ABIs
        # (const values only: the table is the same for every such object,
        # base None: 0)
        base = min(names, key=lambda n: at[n]) if names else None

        def rel(s):
            return at[s.field] + max(s.elem, 0) * s.size - at[base]
        sig = (o.code, tuple((s.sub, s.type, s.flags, s.size, s.limit_slot, s.rom, s.hookio,
                              repr(s.default) if s.rom else
                              (None if s.hookio or not s.field else rel(s)))
                             for s in o.subs))
        if sig not in first:
            first[sig] = o
            continue
        lead = first[sig]
        lead_base = min((s.field for s in lead.subs if s.field and not s.rom and not s.hookio),
                        key=lambda n: at[n], default=None)
        share[lead.index] = (lead.index, lead_base)
        share[o.index] = (lead.index, base)
        same.append((o, lead))
    return share, same


def mask_table(dev: Device, n_tpdo: int) -> list:
    """Sub 1 of the change mask of each TPDO ([device] tpdo_mask + n), checked:
    two UNSIGNED32 RAM values back to back, no hook (the core reads them from
    the RAM image)."""
    if dev.tpdo_mask is None:
        return []
    out = []
    for n in range(n_tpdo):
        index = dev.tpdo_mask + n
        obj = next((o for o in dev.objects if o.index == index), None)
        what = f"object 0x{index:04X} ([device] tpdo_mask, TPDO{n + 1})"
        if obj is None:
            raise DescError(f"{what}: missing; each TPDO needs its change mask")
        s1, s2 = dev.find(index, 1), dev.find(index, 2)
        if s1 is None or s2 is None or s1.type != "UNSIGNED32" or s2.type != "UNSIGNED32":
            raise DescError(f"{what}: a change mask is sub 1 and 2, UNSIGNED32")
        if obj.hook or s1.rom or s1.hookio or s2.rom or s2.hookio:
            raise DescError(f"{what}: a change mask must be a RAM value without a hook "
                            "(the core reads it from the RAM image)")
        if not (s2.field == s1.field and s2.elem == s1.elem + 1 and s1.elem >= 0):
            raise DescError(f"{what}: sub 1 and 2 must be stored back to back (an array "
                            "of two UNSIGNED32)")
        out.append(s1)
    return out


def implicit0(o) -> bool:
    """Sub-index 0 of @p o is the highest of its sub-indices, a const
    UNSIGNED8 nothing else describes: no row, the core reads the last row's
    sub-index (CO_OD_TAG_SUB0)."""
    s0 = o.subs[0] if o.subs else None
    return s0 is not None and len(o.subs) > 1 and s0.sub == 0 and s0.rom and \
        s0.type == "UNSIGNED8" and s0.flags == (F_R | F_CONST | F_ROM) and \
        not s0.hookio and s0.limit_slot < 0 and s0.default == max(s.sub for s in o.subs)


def table_subs(o) -> list:
    """The sub-entries of @p o its table's rows describe."""
    return o.subs[1:] if implicit0(o) else o.subs


@dataclass
class DefRun:
    at: str | None                # offset of its first value (C); None: a zero byte after 255
    w: int                        # log2 of the size of its values
    data: bytes                   # wire bytes
    flags: list[str]
    what: str
    n: int = 1                    # number of values
    joins: list = field(default_factory=list)   # (C, C): offsets the merge relies on


def default_bytes(s: Sub) -> bytes:
    """The default of a RAM value as wire bytes (b"" for none)."""
    v = s.default
    if v is None:
        return b""
    if s.kind == "real":
        return struct.pack("<f" if s.fixed == 4 else "<d", v)
    if s.kind in ("int", "uint", "bool", "time"):
        return wire(s, v)
    return encoded_default(s)[:s.size]


def default_runs(ram: list[Field]) -> list[DefRun]:
    """The default runs of the RAM image @p ram (co_od.h, CO_OD_DEF_RUN): each
    value that is not zero and each $NODEID value (a run of its own), in the
    order of their places; values of one size next to each other in one
    region (at most one byte of zeros between values of one byte) make one
    run of at most 16 values; gaps above 255 bytes get a zero byte in between."""
    at = offsets(ram)
    vals = []   # (offset, region, w, bytes, nodeid flags or None, C offset, what)
    seen = set()
    for f in ram:
        if not f.subs or f.region == "rom" or all(store_command(s) for s in f.subs):
            continue
        for s in f.subs:
            if s.rom or s.hookio:
                continue
            off = at[f.name] + max(s.elem, 0) * s.size
            if off in seen:
                continue    # (one value several sub-entries read)
            seen.add(off)
            data = default_bytes(s)
            num = s.kind in ("int", "uint", "bool", "real") and s.fixed in (2, 4, 8)
            w = {2: 1, 4: 2, 8: 3}[s.fixed] if num else 0
            what = f"0x{s.index:04X}:{s.sub:02X} {s.name}"
            if (s.flags & F_NODEID) and s.fixed in (1, 2, 4):
                flags = ["CO_OD_DEF_NODEID"] + (["CO_OD_DEF_COB"] if is_pdo_emcy_cob(s) else [])
                vals.append((off, f.region, w, data.ljust(s.fixed, b"\0"), flags,
                             off_expr(s), what + " ($NODEID)"))
                continue
            if not any(data):
                continue
            if w == 0:
                data = data.rstrip(b"\0")
            vals.append((off, f.region, w, data, None, off_expr(s), what))
    vals.sort(key=lambda v: v[0])
    runs: list[DefRun] = []
    end = 0     # where the last run ends (the generator's layout; the source checks it)
    prev = None
    for off, region, w, data, flags, cexpr, what in vals:
        unit = 1 << w
        if prev is not None and flags is None and prev[4] is None and prev[1] == region and \
                prev[2] == w and off - end in ((0, 1) if w == 0 else (0,)) and \
                (len(runs[-1].data) + off - end + len(data)) >> w <= 16:
            r = runs[-1]
            r.data += bytes(off - end) + data
            r.n = len(r.data) >> w
            r.what += ", " + what
            r.joins.append((cexpr, f"{r.at} + {len(r.data) - len(data)}U"))
            end = off + len(data)
            prev = (off, region, w, data, flags)
            continue
        while off - end > 255:
            runs.append(DefRun(None, 0, b"\0", [], "(gap)"))
            end += 256
        for k in range(0, len(data), 16 * unit):
            part = data[k:k + 16 * unit]
            c_at = cexpr if k == 0 else f"(uint16_t)({cexpr} + {k}U)"
            runs.append(DefRun(c_at, w, part, flags or [], what, len(part) >> w))
        end = off + len(data)
        prev = (off, region, w, data, flags)
    return runs



def is_pdo_emcy_cob(s) -> bool:
    """The COB-ID of a PDO (communication parameter sub 1) or of the EMCY: its
    $NODEID default uses the node's COB-ID base (CO_LSS_COBS_KEEP)."""
    pdo = 0x1400 <= s.index <= 0x15FF or 0x1800 <= s.index <= 0x19FF
    return (pdo and s.sub == 1) or s.index == 0x1014


def off_expr(s) -> str:
    """Offset of a RAM value as a C expression (F() is defined in the source)."""
    return f"F({s.field})" if s.elem <= 0 else f"(uint16_t)(F({s.field}) + {s.elem * s.size}U)"


PDO_COMM_TYPES = {1: "UNSIGNED32", 2: "UNSIGNED8", 3: "UNSIGNED16", 5: "UNSIGNED16",
                  6: "UNSIGNED8"}


def pdo_table(dev: Device, warn=None):
    """([(comm, mapping)] of RPDOs, same of TPDOs): PDO n is 0x1400+n/0x1600+n
    (0x1800+n/0x1A00+n), numbered without gaps from 0. Objects in the PDO
    ranges that do not make such a PDO stay plain dictionary objects the core
    does not run; each reason goes to @p warn (a foreign EDS may have them)."""
    objs = {o.index: o for o in dev.objects}
    out = ([], [])
    note = warn if warn is not None else (lambda msg: None)
    for kind, (comm_base, map_base) in enumerate(((0x1400, 0x1600), (0x1800, 0x1A00))):
        for index in range(comm_base, comm_base + 0x200):
            comm, mapping = objs.get(index), objs.get(index - comm_base + map_base)
            if comm is None and mapping is None:
                rest = [i for i in objs if index < i < comm_base + 0x200 or
                        index - comm_base + map_base < i < map_base + 0x200]
                if rest:
                    note(f"object 0x{min(rest):04X}: not run as a PDO: PDOs must be numbered "
                         f"without gaps (0x{index:04X} is missing)")
                break
            problem = pdo_problem(comm, mapping, index, comm_base, map_base)
            if problem:
                note(f"{problem}; the core does not run this PDO or any after it")
                break
            out[kind].append((comm, mapping))
    return out


def pdo_problem(comm, mapping, index: int, comm_base: int, map_base: int) -> str | None:
    """Why a communication/mapping pair is not a PDO the core can run, or None."""
    what = f"object 0x{index:04X}"
    if comm is None or mapping is None:
        return (f"{what}: a PDO needs both its communication (0x{index:04X}) and "
                f"mapping (0x{index - comm_base + map_base:04X}) objects")
    cs = {x.sub: x for x in comm.subs}
    for sub, tname in PDO_COMM_TYPES.items():
        if sub in cs and cs[sub].type != tname:
            return f"{what} sub {sub}: must be {tname}"
    if 1 not in cs or 2 not in cs:
        return f"{what}: sub 1 (COB-ID) and sub 2 (transmission type) are required"
    ms = mapping.subs
    if (ms[0].sub != 0 or ms[0].type != "UNSIGNED8" or len(ms) < 2 or len(ms) > 9 or
            any(x.sub != k + 1 or x.type != "UNSIGNED32" for k, x in enumerate(ms[1:]))):
        return (f"object 0x{mapping.index:04X}: a PDO mapping is sub 0 UNSIGNED8 "
                "and 1..8 consecutive UNSIGNED32 entries")
    for x in [cs[k] for k in PDO_COMM_TYPES if k in cs] + ms:
        if x.rom or x.hookio:
            return (f"object 0x{x.index:04X} sub {x.sub}: PDO parameters must be "
                    "RAM values (not const, not hookio)")
    prev = None
    for x in ms[1:]:
        if prev is not None and not (x.field == prev.field and x.elem == prev.elem + 1):
            return f"object 0x{mapping.index:04X}: mapping entries must be stored back to back"
        prev = x
    return None


def dev_obj_name(dev: Device, index: int) -> str:
    for o in dev.objects:
        if o.index == index:
            return o.name
    return ""
