#!/usr/bin/env python3
"""Object-dictionary generator: one description file per device, three products.

    odgen.py [--base NAME] [--out DIR] [--c] [--eds] [--md] DEVICE.toml
    odgen.py import VENDOR.eds [-o DEVICE.toml] [--use-values]   (eds_import.py)
    odgen.py compare SOURCE.eds OTHER.eds                          (eds_compare.py)
    odgen.py registry --out DIR DEVICE.toml...   co_devices.c/.h   (gen_registry.py)

From devices/NAME.toml it writes into DIR (default: current directory)
  NAME_C.h / NAME_C.c   the const object dictionary for the core (NAME_C is
                        NAME with non-identifier characters replaced by '_')
  NAME.eds              the CiA 306 electronic data sheet
  NAME.md               the object table
(all three unless some of --c/--eds/--md are given). Any mistake in the
description stops with "FILE: object 0xIIII sub S: problem" and exit code 1.
Python 3.11+ standard library only (tomllib).
"""
from __future__ import annotations

import argparse
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

import build  # noqa: E402
import gen_c  # noqa: E402
import gen_eds  # noqa: E402
import gen_md  # noqa: E402
from model import DescError, load  # noqa: E402


def main(argv: list[str] | None = None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    if argv and argv[0] == "import":
        import eds_import
        return eds_import.main(argv[1:])
    if argv and argv[0] == "registry":
        import gen_registry
        return gen_registry.main(argv[1:])
    if argv and argv[0] == "compare":
        import eds_compare
        return eds_compare.main(argv[1:])
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("toml", help="device description (.toml)")
    ap.add_argument("--base", help="output base name (default: the file's stem)")
    ap.add_argument("--out", default=".", help="output directory")
    ap.add_argument("--c", action="store_true", help="write the C dictionary")
    ap.add_argument("--eds", action="store_true", help="write the EDS")
    ap.add_argument("--md", action="store_true", help="write the markdown table")
    ap.add_argument("--build", action="append", default=[], metavar="NAME=VALUE",
                    help="a build-time option of the core the device is built with "
                         "(co_config.h; ',' or ';'-separated lists too): a device that needs "
                         "a service or option the build leaves out is refused")
    ap.add_argument("--build-header", default="", metavar="PATH",
                    help="the core's configuration header (CO_CONFIG_HEADER): its "
                         "#define CO_X VALUE lines are build options as well")
    args = ap.parse_args(argv)
    every = not (args.c or args.eds or args.md)
    src = args.toml
    try:
        dev = load(src, args.base)
        opts = build.parse(args.build)
        if args.build_header:
            opts.update(build.header_options(Path(args.build_header)))
        build.check(dev, opts)
        name = Path(src).name
        out = Path(args.out)
        products = {}
        if every or args.c:
            cfg = build.defaults()
            cfg.update(opts)
            h, c = gen_c.generate(
                dev, name, lambda msg: print(f"{src}: warning: {msg}", file=sys.stderr),
                storage=cfg.get("CO_STORAGE", 1) != 0)
            products[f"{dev.cname}.h"] = h
            products[f"{dev.cname}.c"] = c
        if every or args.eds:
            products[f"{dev.base}.eds"] = gen_eds.generate(dev, name, f"{dev.base}.eds")
        if every or args.md:
            products[f"{dev.base}.md"] = gen_md.generate(dev, name)
    except DescError as e:
        print(f"{src}: error: {e}", file=sys.stderr)
        return 1
    out.mkdir(parents=True, exist_ok=True)
    for fname, text in products.items():
        (out / fname).write_text(text, encoding="utf-8", newline="\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
