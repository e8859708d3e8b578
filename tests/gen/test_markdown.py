"""(3) The markdown object table is generated: one row per sub-entry, every
object, in index order; also from the build (co_device)."""
from __future__ import annotations

import re

from conftest import build_dir
from model import load


def rows(md: str) -> list[list[str]]:
    out = []
    for line in md.splitlines():
        if line.startswith("| 0x") or line.startswith("|  |"):
            out.append([c.strip() for c in re.split(r"(?<!\\)\|", line)[1:-1]])
    return out


def test_markdown_table(device, generated):
    md = (generated / f"{device.stem}.md").read_text()
    dev = load(device)
    assert md.startswith(f"# {dev.name}: object dictionary")
    assert "| index | sub | name | object | type | access | PDO | default | limits | unit | storage |" in md
    table = rows(md)
    subs = [r for r in table if r[1] != ""]
    assert len(subs) == sum(len(o.subs) for o in dev.objects)
    indices = [int(r[0], 16) for r in table if r[0]]
    assert indices == [o.index for o in dev.objects]
    assert all(len(r) == 11 for r in table)


def test_markdown_in_build_tree(device):
    md = build_dir() / "codev" / device.stem / f"{device.stem}.md"
    assert md.exists(), f"{md} missing: co_device() did not generate it"
    assert md.read_text().startswith("# ")
