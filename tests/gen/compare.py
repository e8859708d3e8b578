"""Compare a generated EDS with the dictionary od_dump printed from the
compiled C tables (used by test_eds_matches_c.py and test_c_edge.py)."""
from __future__ import annotations

import configparser
import copy
import json
import struct
import subprocess

import canopen
from canopen.objectdictionary import ODArray, ODRecord

NODE_ID = 5
R, W, CONST, MAP_T, MAP_R, ROM, HOOKIO, NODEID, LIMIT = (
    0x1, 0x2, 0x4, 0x8, 0x10, 0x20, 0x40, 0x80, 0x100)
COB16 = 0x0200   # a COB-ID in its 16-bit form (co_od.h CO_SUB_COB16)
NO_DATA = 0x08000024
NO_ACCESS = 0x06010000

SIGNED = {0x02: 1, 0x03: 2, 0x10: 3, 0x04: 4, 0x12: 5, 0x13: 6, 0x14: 7, 0x15: 8}
UNSIGNED = {0x01: 1, 0x05: 1, 0x06: 2, 0x16: 3, 0x07: 4, 0x18: 5, 0x19: 6, 0x1A: 7, 0x1B: 8,
            0x0C: 6, 0x0D: 6}


def access_of(flags: int) -> str:
    """The CiA 306 access type the core's flags stand for (co_od.h)."""
    if flags & CONST:
        return "const"
    if flags & R and flags & W:
        mt, mr = bool(flags & MAP_T), bool(flags & MAP_R)
        return "rwr" if mt and not mr else "rww" if mr and not mt else "rw"
    return "ro" if flags & R else "wo"


def decode(dtype: int, data: bytes):
    if dtype in SIGNED:
        return int.from_bytes(data, "little", signed=True)
    if dtype in UNSIGNED:
        return int.from_bytes(data, "little")
    if dtype == 0x08:
        return struct.unpack("<f", data)[0]
    if dtype == 0x11:
        return struct.unpack("<d", data)[0]
    if dtype == 0x09:
        return data.decode("ascii")
    if dtype == 0x0B:
        return data.decode("utf-16-le")
    return bytes(data)


def expected(var, size: int):
    """The EDS default as the device must hold it, or the empty value."""
    d = var.default
    t = var.data_type
    if t == 0x08 and d is not None:
        return struct.unpack("<f", struct.pack("<f", d))[0]   # REAL32 precision
    if d is None:
        # no DefaultValue: zero; an OCTET_STRING/DOMAIN holds its whole capacity
        return {0x08: 0.0, 0x11: 0.0, 0x09: "", 0x0B: "", 0x0A: bytes(size),
                0x0F: bytes(size)}.get(t, 0)
    return d


def eds_vars(od):
    out = {}
    for obj in od.values():
        if isinstance(obj, (ODArray, ODRecord)):
            for var in obj.values():
                out[(obj.index, var.subindex)] = var
        else:
            out[(obj.index, 0)] = obj
    return out


def expand_compact(evars: dict, raw: configparser.RawConfigParser) -> None:
    """python-canopen reads a CompactSubObj=N object without [xxxxName] as
    sub-indices 0 and 1 only, and gives sub-index 0 neither the access (ro)
    nor the value (N) CiA 306 implies: complete it (elements 2..N are
    sub-index 1 again)."""
    for sec in raw.sections():
        if len(sec) != 4 or "CompactSubObj" not in raw[sec]:
            continue
        index, n = int(sec, 16), int(raw[sec]["CompactSubObj"], 0)
        if (index, 1) not in evars:
            continue
        s0 = copy.copy(evars[(index, 0)])
        s0.access_type, s0.default = "ro", n
        evars[(index, 0)] = s0
        for k in range(2, n + 1):
            evars.setdefault((index, k), evars[(index, 1)])


def run_dump(exe, node_id: int = NODE_ID) -> dict:
    return json.loads(subprocess.run([str(exe), str(node_id)], check=True, capture_output=True,
                                     text=True).stdout)


def type_range(dtype: int) -> tuple[int, int]:
    if dtype in SIGNED:
        n = 8 * SIGNED[dtype]
        return -(1 << (n - 1)), (1 << (n - 1)) - 1
    return 0, (1 << (8 * UNSIGNED[dtype])) - 1


def eds_limit(text: str | None, dtype: int, low: bool) -> int:
    """An EDS limit as the C dictionary checks it: absent = the type's bound,
    "$NODEID+n" = the range over all node-IDs (n+1 .. n+127), hex two's
    complement for signed types."""
    if text is None:
        return type_range(dtype)[0 if low else 1]
    if "$NODEID" in text:
        off = int(text.replace(" ", "").replace("$NODEID", "").strip("+"), 0)
        return off + (1 if low else 127)
    v = int(text, 0)
    if dtype in SIGNED and v > type_range(dtype)[1]:
        v -= 1 << (8 * SIGNED[dtype])
    return v


def compare(eds_path, dump, node_id: int = NODE_ID, eds_only=()) -> int:
    """Assert that the EDS at eds_path describes the dumped dictionary; returns
    the number of values compared. eds_only: indices only the EDS has (objects
    an import kept verbatim; not in the C dictionary)."""
    od = canopen.import_od(str(eds_path), node_id=node_id)
    raw = configparser.RawConfigParser(inline_comment_prefixes=(";",))
    raw.optionxform = str
    raw.read(eds_path, encoding="utf-8")   # ASCII, but an imported UNICODE_STRING default
    evars = {k: v for k, v in eds_vars(od).items() if k[0] >= 0x1000 and k[0] not in eds_only}
    expand_compact(evars, raw)

    # same objects, sorted, same object types (python-canopen lists the
    # DummyUsage entries as objects 0x0001..0x0007)
    c_indices = [e["index"] for e in dump["entries"]]
    assert c_indices == sorted(c_indices), "entries not sorted by index"
    assert not set(c_indices) & set(eds_only)
    assert c_indices == sorted(i for i in od.keys() if i >= 0x1000 and i not in eds_only)
    for e in dump["entries"]:
        assert int(raw[f"{e['index']:04X}"]["ObjectType"], 0) == e["code"], hex(e["index"])
        subs = [s["sub"] for s in e["subs"]]
        assert subs == sorted(subs), f"{e['index']:04X}: subs not sorted"
    c_subs = {(e["index"], s["sub"]) for e in dump["entries"] for s in e["subs"]}
    assert c_subs == set(evars)

    checked = 0
    for e in dump["entries"]:
        for s in e["subs"]:
            key = (e["index"], s["sub"])
            where = f"0x{key[0]:04X} sub {key[1]}"
            var = evars[key]
            flags = s["flags"]
            assert var.data_type == s["type"], where
            assert var.access_type == access_of(flags), where
            assert var.pdo_mappable == bool(flags & (MAP_T | MAP_R)), where
            assert var.relative == bool(flags & NODEID), where
            # limits (raw EDS text: python-canopen cannot parse 24/40/48/56-bit signed ones)
            name = (f"{key[0]:04X}" if isinstance(od[key[0]], canopen.objectdictionary.ODVariable)
                    else f"{key[0]:04X}sub{key[1]:X}")
            if raw.has_section(name):
                sec = raw[name]
            else:   # CompactSubObj: the elements' keys are on the object, sub 0 has none
                sec = raw[f"{key[0]:04X}"] if key[1] else {}
            if flags & LIMIT:
                lo, hi = s["limit"]
                if s["type"] in UNSIGNED:
                    lo, hi = lo & (2**64 - 1), hi & (2**64 - 1)
                assert "LowLimit" in sec or "HighLimit" in sec, where
                assert (eds_limit(sec.get("LowLimit"), s["type"], True),
                        eds_limit(sec.get("HighLimit"), s["type"], False)) == (lo, hi), where
            else:
                assert "LowLimit" not in sec and "HighLimit" not in sec, where
            # value
            if flags & HOOKIO:
                # only a hook provides it; none is bound in od_dump
                assert s["abort"] == NO_ACCESS and var.default is None, where
                continue
            if s["type"] == 0x0B:
                # UNICODE_STRING: compare the stored UTF-16 text (co_od_read is
                # checked by test_unicode_string_reads_whole_text below)
                data = bytes.fromhex(s["ram"] if s["ram"] is not None else s["value"])  # RAM/ROM
                ends = [k for k in range(0, len(data), 2) if data[k:k + 2] == b"\0\0"]
                data = data[:ends[0]] if ends else data
            elif s["abort"] == NO_DATA:
                # 0x1003 entries beyond the error count: compare what is stored
                assert key[0] == 0x1003 and key[1] > 0, where
                data = bytes.fromhex(s["ram"])
            else:
                assert s["abort"] == 0, f"{where}: abort 0x{s['abort']:08X}"
                data = bytes.fromhex(s["value"])
            fixed = {**SIGNED, **UNSIGNED, 0x08: 4, 0x11: 8}.get(s["type"])
            if fixed:
                # (a PDO mapping entry's row, a COB-ID's with CO_SUB_COB16: its
                # 16-bit form in the RAM image, co_od.h; the dictionary reads its
                # UNSIGNED32)
                mapping = (0x1600 <= key[0] <= 0x17FF or 0x1A00 <= key[0] <= 0x1BFF) and \
                    key[1] > 0 and s["type"] == 0x07 and not flags & COB16
                cob16 = bool(flags & COB16) and s["type"] == 0x07
                assert len(data) == fixed, where
                assert s["size"] == (2 if (mapping or cob16) and s["size"] == 2 else fixed), where
            assert decode(s["type"], data) == expected(var, s["size"]), where
            checked += 1
    assert checked > 0
    return checked
