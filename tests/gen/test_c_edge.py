"""Edge cases of the C back end: a device with extreme values, odd strings,
grouped byte-array elements, gaps, options and no serial number compiles with
the project's warnings (-Werror), links with the core and matches its EDS."""
from __future__ import annotations

import shutil
import textwrap

import pytest

from compare import compare, run_dump
from conftest import compile_dump, run_odgen

EDGE = r'''
[device]
name = "edge"
vendor_id = 0xFFFFFFFF
product_code = 1
device_type = 0x000F0191
device_name = "e"
options = ["SDO_NO_BLOCK", "BOOT_EMCY", "EMCY_RESET_PARTIAL"]
boot_emcy_data = [0x56, 0x31, 0x2E, 0x30, 0x00]

[[object]]
index = 0x1001
name = "Error register"
type = "UNSIGNED8"
access = "ro"

[[object]]
index = 0x1016
name = "Consumer heartbeat time"
array = 2
element = { name = "Consumer", type = "UNSIGNED32" }
defaults = [0x00050064]

[[object]]
index = 0x2000
name = "I64 extremes"
type = "INTEGER64"
default = -9223372036854775808
low_limit = -9223372036854775808
high_limit = 9223372036854775807

[[object]]
index = 0x2001
name = "U64 extremes"
type = "UNSIGNED64"
default = 18446744073709551615
low_limit = 1
high_limit = 18446744073709551615

[[object]]
index = 0x2002
name = "I32 min"
type = "INTEGER32"
default = -2147483648
low_limit = -2147483648
high_limit = 0

[[object]]
index = 0x2003
name = "Negative zero"
type = "REAL32"
default = -0.0

[[object]]
index = 0x2004
name = "Full string"
type = "VISIBLE_STRING"
default = 'a"b\c'

[[object]]
index = 0x2005
name = "Trigraph string"
type = "VISIBLE_STRING"
size = 8
default = "??=x"

[[object]]
index = 0x2006
name = "Hook-only U32"
type = "UNSIGNED32"
hookio = true

[[object]]
index = 0x2007
name = "I24 array"
array = 3
element = { name = "I24", type = "INTEGER24", pdo_mapping = true, low_limit = -10, high_limit = 10 }
defaults = [-1, 0, 5]

[[object]]
index = 0x2008
name = "Gaps"
subs = [
  { sub = 1, name = "first", type = "UNSIGNED16", default = "$NODEID" },
  { sub = 3, name = "third", type = "UNSIGNED8", default = "$NODEID+0x40", storage = "comm" },
  { sub = 7, name = "seventh", type = "UNSIGNED32", access = "wo", pdo_mapping = true },
]

[[object]]
index = 0x2009
name = "Stored domain"
object = "DOMAIN"
size = 4
default = "01 02"

[[object]]
index = 0x200A
name = "Octets without default"
type = "OCTET_STRING"
size = 3

[[object]]
index = 0x200B
name = "Output"
type = "UNSIGNED16"
access = "rww"

[[object]]
index = 0x200C
name = "Time difference"
type = "TIME_DIFFERENCE"
default = 0xFFFF0FFFFFFF

[[object]]
index = 0x6000
name = "Profile value"
type = "INTEGER8"
access = "ro"
default = -128
'''

@pytest.mark.skipif(shutil.which("cc") is None, reason="no C compiler")
def test_edge_device(tmp_path):
    src = tmp_path / "edge.toml"
    src.write_text(textwrap.dedent(EDGE))
    r = run_odgen(src, tmp_path)
    assert r.returncode == 0, r.stderr
    exe = compile_dump(tmp_path, "edge")
    dump = run_dump(exe, 127)
    # options SDO_NO_BLOCK, BOOT_EMCY, EMCY_RESET_PARTIAL as typed settings
    assert dump["set"]["sdo"] == {"refused": 0x04, "unknown_object": 0, "read_only": 0}
    assert dump["set"]["nmt"]["boot_emcy"] == 1 and dump["set"]["nmt"]["bootup"] == 0
    assert dump["set"]["emcy"]["reset"] == 1 and dump["set"]["emcy"]["history"] == 0
    assert dump["n_hooks"] == 1
    # 0x1018 sub 4 without [device] serial: a RAM value the application fills in
    s1018 = next(e for e in dump["entries"] if e["index"] == 0x1018)["subs"]
    assert s1018[4]["ram"] is not None and not s1018[4]["flags"] & 0x20
    assert compare(tmp_path / "edge.eds", dump, node_id=127) > 20
    header = (tmp_path / "edge.h").read_text()
    assert "uint8_t x2007_i24_array[3][3];" in header
    assert "#define EDGE_HOOK_2006 0U" in header


# the device and its 0x1001, which the descriptions below begin with
HEAD = r'''
[device]
name = "{name}"
vendor_id = 1
product_code = 1
device_type = 0x000F0191

[[object]]
index = 0x1001
name = "Error register"
type = "UNSIGNED8"
access = "ro"
'''

STORE = HEAD.format(name="store") + r'''
[[object]]
index = 0x1010
name = "Store parameters"
array = 3
element = { name = "Save", type = "UNSIGNED32", access = "rw" }
defaults = [1, 1, 1]

[[object]]
index = 0x1017
name = "Producer heartbeat time"
type = "UNSIGNED16"
access = "rw"
default = 1000
'''


def test_store_commands_have_no_default(tmp_path):
    """0x1010 / 0x1011 sub 1.. read what the store service writes at every
    reset (the capability), never their description's default: the default
    image leaves them out (they restore to 0 before the service writes them)."""
    src = tmp_path / "store.toml"
    src.write_text(textwrap.dedent(STORE))
    r = run_odgen(src, tmp_path)
    assert r.returncode == 0, r.stderr
    c = (tmp_path / "store.c").read_text()
    defaults = c[c.index("static const uint8_t defaults[]"):]
    defaults = defaults[:defaults.index("};")]
    assert "x1017_producer_heartbeat_time" in defaults
    assert "x1010" not in defaults


ROWS = HEAD.format(name="rows") + r'''
[[object]]
index = 0x1003
name = "Pre-defined error field"
array = 4
sub0 = { name = "Number of errors", access = "rw", default = 0 }
element = { name = "Standard error field", type = "UNSIGNED32", access = "ro" }

[[object]]
index = 0x1019
name = "Synchronous counter overflow value"
type = "UNSIGNED8"
access = "rw"
default = 7

[[object]]
index = 0x1200
name = "SDO server parameter"
subs = [
  { sub = 1, name = "COB-ID client to server", type = "UNSIGNED32", access = "ro", default = "$NODEID+0x600" },
  { sub = 2, name = "COB-ID server to client", type = "UNSIGNED32", access = "ro", default = "$NODEID+0x580" },
]
'''


@pytest.mark.skipif(shutil.which("cc") is None, reason="no C compiler")
def test_rows_shared_and_joined(tmp_path):
    """Rows the generator saves: 0x1200's two COB-IDs, fields of their own one
    right after the other, are one run (their places checked by the source);
    0x1019, one value whose row is 0x1003's sub 0 but for its offset, uses
    that row with its own base. Both still read their own values."""
    src = tmp_path / "rows.toml"
    src.write_text(textwrap.dedent(ROWS))
    r = run_odgen(src, tmp_path)
    assert r.returncode == 0, r.stderr
    c = (tmp_path / "rows.c").read_text()
    assert "CO_OD_RUN(0x01U, 2U, (uint8_t)CO_UNSIGNED32" in c
    assert "rows_run_joins" in c
    od = c[c.index("static const co_od_entry_t od[]"):]
    e1003 = next(x for x in od.splitlines() if "0x1003U" in x)
    e1019 = next(x for x in od.splitlines() if "0x1019U" in x)
    assert "CO_OD_ENTRY_AT(0x1019U" in e1019 and "F(x1003_number_of_errors)" in e1019
    row = int(e1003.split(",")[-2].strip(" U)"))  # 0x1003's first row: its sub 0
    assert f" {row}U, (uint16_t)(F(x1019" in e1019
    exe = compile_dump(tmp_path, "rows")
    dump = run_dump(exe, 5)
    subs = {(e["index"], s["sub"]): s for e in dump["entries"] for s in e["subs"]}
    assert subs[(0x1019, 0)]["value"] == "07" and subs[(0x1019, 0)]["flags"] & 0x02
    assert subs[(0x1003, 0)]["value"] == "00"
    assert subs[(0x1200, 1)]["value"] == "05060000" and subs[(0x1200, 2)]["value"] == "85050000"
    assert compare(tmp_path / "rows.eds", dump, node_id=5) > 5
