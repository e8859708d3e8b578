"""EDS -> description -> EDS round trips (test_import_*.py): run the importer
and the generator, and compare the two EDS files with python-canopen's
import_od (the second, independent reader; tools/odgen/eds_compare.py is the
first)."""
from __future__ import annotations

import logging
from pathlib import Path

import canopen
from canopen.objectdictionary import ODArray, ODRecord, ODVariable

from conftest import run_import, run_odgen
from cia306 import read_eds
from eds_compare import differences
from model import load

VAR_ATTRS = ("name", "data_type", "access_type", "pdo_mappable", "default", "relative", "min",
             "max", "value", "unit", "factor", "description", "storage_location")
INFO_ATTRS = ("vendor_name", "vendor_number", "product_name", "product_number",
              "revision_number", "order_code", "simple_boot_up_master", "simple_boot_up_slave",
              "granularity", "dynamic_channels_supported", "group_messaging", "nr_of_RXPDO",
              "nr_of_TXPDO", "LSS_supported")


def canopen_view(path: Path, node_id: int | None) -> dict:
    """What python-canopen reads from an EDS/DCF, as plain data."""
    logging.getLogger("canopen").setLevel(logging.ERROR)
    od = canopen.import_od(str(path), node_id)
    objs = {}
    for index in od:
        obj = od[index]
        if isinstance(obj, ODVariable):
            kind, members = "VAR", {0: obj}
        else:
            kind = "ARRAY" if isinstance(obj, ODArray) else "RECORD"
            assert isinstance(obj, (ODArray, ODRecord))
            members = {sub: obj[sub] for sub in obj.subindices}
        objs[index] = {"kind": kind, "name": obj.name,
                       "subs": {sub: {a: getattr(v, a) for a in VAR_ATTRS}
                                for sub, v in members.items()}}
    di = od.device_information
    info = {a: getattr(di, a) for a in INFO_ATTRS}
    info["allowed_baudrates"] = sorted(di.allowed_baudrates)
    return {"objects": objs, "info": info, "comments": od.comments,
            "node_id": od.node_id, "bitrate": od.bitrate}


def canopen_differences(src: Path, out: Path, node_id: int | None = 5) -> list[str]:
    """What python-canopen reads differently from out than from src (device
    information the source leaves out may be added)."""
    a, b = canopen_view(src, node_id), canopen_view(out, node_id)
    diffs = []
    for k, v in a["info"].items():
        if v not in (None, [], set()) and b["info"][k] != v:
            diffs.append(f"device_information.{k}: {v!r} -> {b['info'][k]!r}")
    for k in ("comments", "node_id", "bitrate"):
        if a[k] != b[k]:
            diffs.append(f"{k}: {a[k]!r} -> {b[k]!r}")
    oa, ob = a["objects"], b["objects"]
    for index in sorted(set(oa) | set(ob)):
        if index not in ob or index not in oa:
            diffs.append(f"0x{index:04X}: {'lost' if index not in ob else 'added'}")
            continue
        x, y = oa[index], ob[index]
        if (x["kind"], x["name"]) != (y["kind"], y["name"]):
            diffs.append(f"0x{index:04X}: {x['kind']} {x['name']!r} -> {y['kind']} {y['name']!r}")
        for sub in sorted(set(x["subs"]) | set(y["subs"])):
            if sub not in x["subs"] or sub not in y["subs"]:
                diffs.append(f"0x{index:04X} sub {sub}: "
                             f"{'lost' if sub not in y['subs'] else 'added'}")
                continue
            for attr, v in x["subs"][sub].items():
                w = y["subs"][sub][attr]
                if v != w and not (isinstance(v, float) and isinstance(w, float) and v != v
                                   and w != w):
                    diffs.append(f"0x{index:04X} sub {sub} {attr}: {v!r} -> {w!r}")
    return diffs


def round_trip(src: Path, work: Path, base: str, *import_args: str):
    """Import src into work/<base>.toml and generate from it into work/out/.
    Returns (import result, generated EDS path, loaded description)."""
    toml = work / f"{base}.toml"
    r = run_import(src, toml, *import_args)
    assert r.returncode == 0, r.stderr
    g = run_odgen(toml, work / "out")
    assert g.returncode == 0, g.stderr
    # only notes about PDO-range objects the core does not run as PDOs
    assert all(": warning: " in line and "PDO" in line
               for line in g.stderr.splitlines()), g.stderr
    return r, work / "out" / f"{base}.eds", load(toml)


def semantic_differences(src: Path, out: Path) -> list[str]:
    return differences(read_eds(src), read_eds(out))
