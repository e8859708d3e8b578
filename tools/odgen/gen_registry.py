"""The device registry: every description in devices/ as a co_device_t.

    odgen.py registry --out DIR DEVICE.toml...

writes DIR/co_devices.h and DIR/co_devices.c: one `const co_device_t
co_device_<cname>` per description (name = the file's stem), found by name
with co_device_find(). What a device runs besides its dictionary comes from
its [profile] table:

    [profile]
    summary = "one line for --list-devices"   (default: [device] description)
    plugin = "c_symbol"      a co_device_plugin_t in a C file of devices/ (only
                             for behaviour no setting can describe: a vendor
                             plug-in, a power-on step)
    impl = "c_symbol"        or a whole co_device_impl_t in C (no parts below)

    [profile.cia402]         CiA 402 axes, generated (co/co402_device.h): axes,
    ...                      options, units, hm_methods, errors, sim
    [profile.cia401]         a CiA 401 module, generated (co/co401.h)

Its EDS is embedded as codev_eds_<cname> (cmake/embed_text.cmake).
"""
from __future__ import annotations

import re
from pathlib import Path

from model import DescError, load_raw


def _cname(name: str) -> str:
    return re.sub(r"[^0-9A-Za-z_]", "_", name)


def _c_string(s: str) -> str:
    return '"' + s.replace("\\", "\\\\").replace('"', '\\"') + '"'


def _int(tbl: dict, key: str, default: int, top: int, what: str) -> int:
    v = tbl.get(key, default)
    if isinstance(v, bool) or not isinstance(v, int) or not 0 <= v <= top:
        raise DescError(f"{what} {key} must be an integer 0..{top}")
    return v


# ---- [profile.cia401]: co401_config_t (profiles/cia401/include/co/co401.h)
CIA401_KEYS = {
    # key: (C field, default, top)
    "di": ("di", 0, 0xFFFF),               # digital input object (0: 0x6000/0x6100/0x6120)
    "do": ("dout", 0, 0xFFFF),             # digital output object (0: 0x6200/0x6300/0x6320)
    "first_sub": ("first_sub", 1, 1),      # sub-index of the first block (AnaGate: 0)
    "blocks_di": ("n_di", 0, 8),           # blocks of di (0: as many as the object has)
    "blocks_do": ("n_do", 0, 8),
    "filter_us": ("filter_us", 0, 0x7FFFFFFF),  # input filter time (0: 3 ms)
    "poll_us": ("poll_us", 0, 0x7FFFFFFF),      # inputs read at least this often (0: 10 ms)
}


def _cia401(cname: str, tbl: dict, what: str) -> tuple[str, str]:
    unknown = sorted(set(tbl) - set(CIA401_KEYS))
    if unknown:
        raise DescError(f"{what}: unknown key(s) {', '.join(unknown)}")
    fields = []
    for key, (field, default, top) in CIA401_KEYS.items():
        fields.append(f"    .{field} = 0x{_int(tbl, key, default, top, what):X}U,")
    for key in ("di", "do"):
        v = tbl.get(key, 0)
        if v and not 0x2000 <= v <= 0x9FFF:
            raise DescError(f"{what} {key} must be a manufacturer or profile object")
    cfg = f"static const co401_config_t cia401_{cname} = {{\n" + "\n".join(fields) + "\n};\n"
    return cfg, f"{{&co401_part, &cia401_{cname}, 1U}}"


# ---- [profile.cia402]: co402_params_t (profiles/cia402/include/co/co402_device.h)
CO402_H = Path(__file__).resolve().parents[2] / "profiles" / "cia402" / "include" / "co" / "co402.h"
CIA402_INTS = {
    # key: (C field, top)
    "modes": ("modes", 0xFFFFFFFF),
    "counts_per_rev": ("counts_per_rev", 0xFFFFFFFF),
    "vel_num": ("vel_num", 0xFFFFFFFF), "vel_den": ("vel_den", 0xFFFFFFFF),
    "acc_num": ("acc_num", 0xFFFFFFFF), "acc_den": ("acc_den", 0xFFFFFFFF),
    "full_speed": ("full_speed", 0xFFFFFFFF),
}
SIM_FIELDS = {  # co402_sim_config_t (co/co402_sim.h): C type of each field
    "step_us": "u32", "accel_rated": "u32", "torque_max": "u16", "speed_max": "u32",
    "kp": "u16", "kv": "u16", "ki": "u32", "friction": "u16", "counts_per_rev": "u32",
    "index_offset": "i32", "neg_limit": "i32", "pos_limit": "i32", "home_lo": "i32",
    "home_hi": "i32", "start_pos": "i32",
}
SWITCHES = {"NEG_LIMIT": "CO402_IN_NEG_LIMIT", "POS_LIMIT": "CO402_IN_POS_LIMIT",
            "HOME": "CO402_IN_HOME"}


def _co402_options() -> set[str]:
    return set(re.findall(r"#define CO402_OPT_(\w+)", CO402_H.read_text(encoding="utf-8")))


def _sint(v, lo: int, hi: int, what: str) -> int:
    if isinstance(v, bool) or not isinstance(v, int) or not lo <= v <= hi:
        raise DescError(f"{what} must be an integer {lo}..{hi}")
    return v


def _c_int(v: int, typ: str) -> str:
    if typ != "i32":
        return f"{v}U"
    return "INT32_MIN" if v == -0x80000000 else f"{v}"


def _cia402(cname: str, tbl: dict, what: str) -> tuple[str, str]:
    keys = {"axes", "options", "hm_methods", "errors", "sim"} | set(CIA402_INTS)
    unknown = sorted(set(tbl) - keys)
    if unknown:
        raise DescError(f"{what}: unknown key(s) {', '.join(unknown)}")
    axes = _sint(tbl.get("axes", 1), 1, 8, f"{what} axes")
    known = _co402_options()
    opts = tbl.get("options", [])
    if not isinstance(opts, list) or any(o not in known for o in opts):
        bad = [o for o in opts if o not in known] if isinstance(opts, list) else opts
        raise DescError(f"{what} options: unknown {bad} (known: {', '.join(sorted(known))})")
    out = []
    fields = [f"    .options = {' | '.join('CO402_OPT_' + o for o in opts) or '0U'},"]
    for key, (field, top) in CIA402_INTS.items():
        if key in tbl:
            fields.append(f"    .{field} = {_sint(tbl[key], 0, top, f'{what} {key}')}U,")
    hm = tbl.get("hm_methods")
    if hm is not None:
        rows = []
        for k, m in enumerate(hm):
            w = f"{what} hm_methods #{k + 1}"
            if not isinstance(m, dict) or set(m) - {"value", "runs_as", "fast_only"}:
                raise DescError(f"{w}: a table of value, runs_as, fast_only")
            v = _sint(m.get("value"), -128, 127, f"{w} value")
            r = _sint(m.get("runs_as", v), -128, 127, f"{w} runs_as")
            fl = "CO402_HM_FAST_ONLY" if m.get("fast_only", False) else "0U"
            rows.append(f"{{{v}, {r}, {fl}}}")
        out.append(f"static const co402_hm_method_t hm_{cname}[] = {{\n    " +
                   ",\n    ".join(rows) + ",\n};\n")
        fields.append(f"    .hm_methods = hm_{cname},\n    .n_hm_methods = {len(rows)}U,")
    errs = tbl.get("errors")
    if errs is not None:
        rows = []
        for k, e in enumerate(errs):
            w = f"{what} errors #{k + 1}"
            if not isinstance(e, dict) or set(e) - {"code", "reg", "mfr"}:
                raise DescError(f"{w}: a table of code, reg, mfr")
            code = _sint(e.get("code"), 0, 0xFFFF, f"{w} code")
            reg = _sint(e.get("reg", 0), 0, 0xFF, f"{w} reg")
            mfr = e.get("mfr", [0, 0, 0, 0, 0])
            if not isinstance(mfr, list) or len(mfr) != 5:
                raise DescError(f"{w} mfr must be 5 bytes")
            b = ", ".join(f"0x{_sint(x, 0, 255, f'{w} mfr'):02X}U" for x in mfr)
            rows.append(f"{{0x{code:04X}U, 0x{reg:02X}U, {{{b}}}}}")
        out.append(f"static const co402_error_t err_{cname}[] = {{\n    " +
                   ",\n    ".join(rows) + ",\n};\n")
        fields.append(f"    .errors = err_{cname},\n    .n_errors = {len(rows)}U,")
    sim = tbl.get("sim")
    if sim is not None:
        if not isinstance(sim, dict) or set(sim) - set(SIM_FIELDS) - {"switches"}:
            bad = sorted(set(sim) - set(SIM_FIELDS) - {"switches"}) if isinstance(sim, dict) else sim
            raise DescError(f"{what} sim: unknown key(s) {bad} (co402_sim_config_t fields)")
        lines = []
        for key, typ in SIM_FIELDS.items():
            if key in sim:
                lo, hi = {"u16": (0, 0xFFFF), "u32": (0, 0xFFFFFFFF),
                          "i32": (-0x80000000, 0x7FFFFFFF)}[typ]
                v = _sint(sim[key], lo, hi, f"{what} sim {key}")
                lines.append(f"    c->{key} = {_c_int(v, typ)};")
        if "switches" in sim:
            sw = sim["switches"]
            if not isinstance(sw, list) or any(x not in SWITCHES for x in sw):
                raise DescError(f"{what} sim switches: a list of {', '.join(SWITCHES)}")
            lines.append(f"    c->switches = {' | '.join(SWITCHES[x] for x in sw) or '0U'};")
        out.append(f"static void sim_{cname}(co402_sim_config_t *c)\n{{\n" + "\n".join(lines) +
                   "\n}\n")
        fields.append(f"    .sim_config = sim_{cname},")
    out.append(f"static const co402_params_t cia402_{cname} = {{\n" + "\n".join(fields) + "\n};\n")
    return "\n".join(out), f"{{&co402_part, &cia402_{cname}, {axes}U}}"


PROFILES = {"cia402": _cia402, "cia401": _cia401}
PROFILE_HEADERS = {"cia401": "co/co401_device.h",   # defines co401_part
                   "cia402": "co/co402_device.h"}   # defines co402_part


def generate(paths: list[str]) -> tuple[str, str]:
    devices = []
    plugins: dict[str, str | None] = {}
    for p in sorted(paths, key=lambda s: Path(s).stem):
        path = Path(p)
        try:
            data = load_raw(path)
            prof = data.get("profile", {})
            if not isinstance(prof, dict):
                raise DescError("[profile] must be a table")
            unknown = sorted(set(prof) - {"summary", "impl", "plugin"} - set(PROFILES))
            if unknown:
                raise DescError(f"[profile]: unknown key(s) {', '.join(unknown)}")
            dev = data.get("device", {})
            summary = prof.get("summary", dev.get("description", ""))
            if not isinstance(summary, str):
                raise DescError("[profile] summary must be a string")
            impl = prof.get("impl")
            if impl is not None and not re.fullmatch(r"[A-Za-z_][A-Za-z0-9_]*", str(impl)):
                raise DescError("[profile] impl must name a C symbol (co_device_impl_t)")
            plugin = prof.get("plugin")
            if plugin is not None and not re.fullmatch(r"[A-Za-z_][A-Za-z0-9_]*", str(plugin)):
                raise DescError("[profile] plugin must name a C symbol (co_device_plugin_t)")
            parts = [k for k in PROFILES if k in prof]
            if impl is not None and (parts or plugin is not None):
                raise DescError("[profile] impl: the C file's co_device_impl_t describes the "
                                "parts and the plug-in then (no [profile.<kind>], no plugin)")
        except DescError as e:
            raise DescError(f"{p}: {e}") from None
        devices.append((path.stem, _cname(path.stem), summary, impl, parts, prof))
        plugins[path.stem] = plugin

    h = ["/* Generated by tools/odgen (odgen.py registry) from the descriptions in devices/: do not edit. */",
         "#ifndef CO_DEVICES_H", "#define CO_DEVICES_H", "", "#include <stddef.h>", "",
         '#include "co/co_device.h"', ""]
    for name, cname, summary, _, _, _ in devices:
        h.append(f"extern const co_device_t co_device_{cname}; /* {name} */")
    h += ["", "/** The device named @p name (devices/<name>.toml), NULL if none. */",
          "const co_device_t *co_device_find(const char *name);", "",
          "/** The @p k-th device in name order (NULL after the last). */",
          "const co_device_t *co_device_at(size_t k);", "",
          "/** Number of devices. */", "size_t co_device_count(void);", "",
          "#endif /* CO_DEVICES_H */", ""]

    c = ["/* Generated by tools/odgen (odgen.py registry) from the descriptions in devices/: do not edit. */",
         '#include "co_devices.h"', "", "#include <string.h>", ""]
    headers = sorted({PROFILE_HEADERS[k] for d in devices for k in d[4]})
    c += [f'#include "{hd}"' for hd in headers]
    c += [f'#include "{cname}.h"' for _, cname, _, _, _, _ in devices]
    c.append("")
    for name, cname, summary, impl, parts, prof in devices:
        c.append(f"extern const unsigned char codev_eds_{cname}[];")
        if impl is not None:
            c.append(f"extern const co_device_impl_t {impl};")
        if plugins[name] is not None:
            c.append(f"extern const co_device_plugin_t {plugins[name]};")
    c.append("")
    for name, cname, summary, impl, parts, prof in devices:
        impl_ref = "NULL"
        if impl is not None:
            impl_ref = f"&{impl}"
        elif parts or plugins[name] is not None:
            items = []
            for k in parts:
                try:
                    cfg, item = PROFILES[k](cname, prof[k], f"[profile.{k}]")
                except DescError as e:
                    raise DescError(f"devices/{name}.toml: {e}") from None
                c.append(cfg)
                items.append(item)
            body = ""
            if items:
                c.append(f"static const co_device_part_t parts_{cname}[] = {{{', '.join(items)}}};")
                body += f"    .parts = parts_{cname},\n    .n_parts = {len(items)}U,\n"
            if plugins[name] is not None:
                body += f"    .plugin = &{plugins[name]},\n"
            c.append(f"static const co_device_impl_t impl_{cname} = {{\n{body}}};")
            impl_ref = f"&impl_{cname}"
        c.append(f"const co_device_t co_device_{cname} = {{\n"
                 f"    .name = {_c_string(name)},\n"
                 f"    .summary = {_c_string(summary)},\n"
                 f"    .dev = &{cname}_dev,\n"
                 f"    .eds = codev_eds_{cname},\n"
                 f"    .impl = {impl_ref},\n}};\n")
    c.append("static const co_device_t *const all[] = {")
    c += [f"    &co_device_{cname}," for _, cname, _, _, _, _ in devices]
    c += ["};", "",
          "size_t co_device_count(void)", "{",
          "    return sizeof all / sizeof all[0];", "}", "",
          "const co_device_t *co_device_at(size_t k)", "{",
          "    return (k < co_device_count()) ? all[k] : NULL;", "}", "",
          "const co_device_t *co_device_find(const char *name)", "{",
          "    for (size_t k = 0U; k < co_device_count(); k++) {",
          "        if (strcmp(all[k]->name, name) == 0) {",
          "            return all[k];", "        }", "    }",
          "    return NULL;", "}", ""]
    return "\n".join(h), "\n".join(c)


def main(argv: list[str]) -> int:
    import argparse
    import sys
    ap = argparse.ArgumentParser(prog="odgen.py registry")
    ap.add_argument("--out", required=True)
    ap.add_argument("toml", nargs="+")
    args = ap.parse_args(argv)
    try:
        h, c = generate(args.toml)
    except DescError as e:
        print(f"error: {e}", file=sys.stderr)
        return 1
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    for fname, text in (("co_devices.h", h), ("co_devices.c", c)):
        f = out / fname
        if not f.exists() or f.read_text(encoding="utf-8") != text:
            f.write_text(text, encoding="utf-8", newline="\n")
    return 0
