"""A device's personality as typed settings, one table per service of the
core, instead of a list of option bits:

    [nmt]   bootup = true                       guarding_with_heartbeat = false
    [sdo]   transfers = ["expedited", "segmented-upload", "segmented-download", "block"]
            unknown_object = "no-object" | "no-access"
            read_only = "read-only" | "no-access"
    [pdo]   parameter_writes = "cia301" | "pre-operational"
            mapping_while_valid = false         cob_id_while_valid = false
            mapping_granularity = "bit" | "byte"
            event_timer_unit = "ms" | "100us"   short_rpdo = "emcy" | "accept"
    [tpdo]  change_detection = true
            change_mask = { object = 0x2014, types = [255] }
    [emcy]  reset = "all-cleared" | "each-clear"  state_pair = false
            generic_bit = "always" | "unclassified-only"
            history = "code-and-info" | "code-only"
            boot = [b0, b1, b2, b3, b4]         (EMCY 0x0000 after boot-up, these bytes 3..7)
    [store] restore_saved = false

Every key is optional (the default is CiA 301). The generator turns them
into the core's typed settings (co_dev_t.set, stack/include/co/co_settings.h:
one part per service, every field's zero the CiA behaviour), boot_emcy_data
and tpdo_mask. The older `[device] options = [...]` list names the same
deviations (SETTINGS below) and may be used alongside, but not against, a
setting given here.
"""
from __future__ import annotations

from model import DescError

# every deviation by name: (its bit in Device.option_bits, the field of
# co_settings_t it sets, the value; fields that are sets OR their values)
SETTINGS = {
    "UNKNOWN_INDEX_NO_ACCESS": (0x0001, "sdo.unknown_object", "CO_SDO_ABORT_NO_ACCESS"),
    "READ_ONLY_NO_ACCESS": (0x0002, "sdo.read_only", "CO_SDO_ABORT_NO_ACCESS"),
    "NO_BOOTUP": (0x0004, "nmt.bootup", "CO_BOOTUP_NONE"),
    "BOOT_EMCY": (0x0008, "nmt.boot_emcy", "1U"),
    "EMCY_STATE_PAIR": (0x0010, "emcy.state_pair", "1U"),
    "EMCY_RESET_PARTIAL": (0x0020, "emcy.reset", "CO_EMCY_RESET_EACH_CLEAR"),
    "SDO_EXPEDITED_ONLY": (0x0040, "sdo.refused", "CO_SDO_EXPEDITED_ONLY"),
    "SDO_NO_BLOCK": (0x0080, "sdo.refused", "CO_SDO_XFER_BLOCK"),
    "GUARD_WITH_HEARTBEAT": (0x0100, "nmt.guarding_with_hb", "1U"),
    "PDO_MAP_WHILE_VALID": (0x0200, "pdo.mapping_while_valid", "1U"),
    "RPDO_SHORT_OK": (0x0400, "pdo.short_rpdo", "CO_RPDO_SHORT_ACCEPT"),
    "EVENT_TIMER_100US": (0x0800, "pdo.event_timer_unit", "CO_PDO_TIMER_100US"),
    "LSS": (0x1000, "lss.slave", "1U"),
    "LSS_KEEP_COBS": (0x2000, "lss.cob_ids", "CO_LSS_COBS_KEEP"),
    "LSS_NO_REVISION": (0x4000, "lss.selective", "CO_LSS_IGNORE_REVISION"),
    "LSS_ONLY": (0x8000, "lss.node_id", "CO_LSS_ID_ONLY"),
    "PDO_COBID_WHILE_VALID": (0x00010000, "pdo.cob_id_while_valid", "1U"),
    "PDO_CONFIG_PREOP_ONLY": (0x00020000, "pdo.parameter_writes", "CO_PDO_WRITES_PREOP"),
    "PDO_MAP_BYTES": (0x00040000, "pdo.granularity", "CO_PDO_MAP_BYTES"),
    "TPDO_NO_CHANGE_DETECT": (0x00080000, "tpdo.change_detection", "CO_TPDO_CHANGE_IGNORED"),
    "TPDO_MASK_254": (0x00100000, "tpdo.change_mask", "CO_TPDO_MASK_254"),
    "TPDO_MASK_255": (0x00200000, "tpdo.change_mask", "CO_TPDO_MASK_255"),
    "ERREG_NO_GENERIC": (0x01000000, "emcy.generic_bit", "CO_ERREG_GENERIC_UNCLASSIFIED"),
    "HISTORY_CODE_ONLY": (0x02000000, "emcy.history", "CO_HISTORY_CODE_ONLY"),
    "SDO_NO_SEG_DOWNLOAD": (0x04000000, "sdo.refused", "CO_SDO_XFER_SEG_DOWNLOAD"),
    "RESTORE_SAVED": (0x08000000, "store.restore", "CO_RESTORE_SAVED"),
    "TPDO_AFTER_RPDO": (0x10000000, "pdo.tpdo_after_rpdo", "1U"),
    "GUARD_HB_EXCLUSIVE": (0x20000000, "nmt.guarding_hb_exclusive", "1U"),
}


def settings_c(options: list[str]) -> list[str]:
    """The designated initialisers of co_dev_t.set for these deviations
    (field -> value; a set's values ORed), in the order of SETTINGS."""
    fields: dict[str, list[str]] = {}
    for name, (_, field, value) in SETTINGS.items():
        if name in options:
            fields.setdefault(field, []).append(value)
    return [f"    .set.{f} = {v[0] if len(v) == 1 else '(uint8_t)(' + ' | '.join(v) + ')'},"
            for f, v in fields.items()]


def settings_guarded(options: list[str]) -> list[str]:
    """settings_c() for a core of any build: co_dev_t has the field set only
    with CO_PERSONALITY or CO_LSS; a core with neither refuses a device that
    needs a deviation or LSS at compile time (#error), except "no block SDO"
    where the core has none (CO_SDO_BLOCK=0), which such a core does anyway
    (what build.py says with --build)."""
    lines = settings_c(options)
    if not lines:
        return []
    named = [n for n in SETTINGS if n in options]
    need = "#error \"this device's personality (" + ", ".join(named) + \
        ") needs CO_PERSONALITY=1 (or CO_LSS=1 for LSS)\""
    rest = [n for n in named if n != "SDO_NO_BLOCK"]
    return ["#if CO_PERSONALITY || CO_LSS", *lines,
            *(["#else", need] if rest else ["#elif CO_SDO_BLOCK", need]), "#endif"]


TRANSFERS = ("expedited", "segmented-upload", "segmented-download", "block")
# the SDO transfer sets the server offers -> options
TRANSFER_SETS = {
    frozenset(TRANSFERS): set(),
    frozenset(TRANSFERS) - {"block"}: {"SDO_NO_BLOCK"},
    frozenset(TRANSFERS) - {"segmented-download"}: {"SDO_NO_SEG_DOWNLOAD"},
    frozenset(TRANSFERS) - {"segmented-download", "block"}: {"SDO_NO_SEG_DOWNLOAD",
                                                              "SDO_NO_BLOCK"},
    frozenset({"expedited"}): {"SDO_EXPEDITED_ONLY"},
}

# (table, key): (choices: value -> option or None, the options the key governs)
CHOICES = {
    ("nmt", "bootup"): ({True: None, False: "NO_BOOTUP"}, {"NO_BOOTUP"}),
    ("nmt", "guarding_with_heartbeat"): ({False: None, True: "GUARD_WITH_HEARTBEAT"},
                                         {"GUARD_WITH_HEARTBEAT"}),
    ("sdo", "unknown_object"): ({"no-object": None, "no-access": "UNKNOWN_INDEX_NO_ACCESS"},
                                {"UNKNOWN_INDEX_NO_ACCESS"}),
    ("sdo", "read_only"): ({"read-only": None, "no-access": "READ_ONLY_NO_ACCESS"},
                           {"READ_ONLY_NO_ACCESS"}),
    ("pdo", "parameter_writes"): ({"cia301": None, "pre-operational": "PDO_CONFIG_PREOP_ONLY"},
                                  {"PDO_CONFIG_PREOP_ONLY"}),
    ("pdo", "mapping_while_valid"): ({False: None, True: "PDO_MAP_WHILE_VALID"},
                                     {"PDO_MAP_WHILE_VALID"}),
    ("pdo", "cob_id_while_valid"): ({False: None, True: "PDO_COBID_WHILE_VALID"},
                                    {"PDO_COBID_WHILE_VALID"}),
    ("pdo", "mapping_granularity"): ({"bit": None, "byte": "PDO_MAP_BYTES"}, {"PDO_MAP_BYTES"}),
    ("pdo", "event_timer_unit"): ({"ms": None, "100us": "EVENT_TIMER_100US"},
                                  {"EVENT_TIMER_100US"}),
    ("pdo", "short_rpdo"): ({"emcy": None, "accept": "RPDO_SHORT_OK"}, {"RPDO_SHORT_OK"}),
    ("tpdo", "change_detection"): ({True: None, False: "TPDO_NO_CHANGE_DETECT"},
                                   {"TPDO_NO_CHANGE_DETECT"}),
    ("emcy", "reset"): ({"all-cleared": None, "each-clear": "EMCY_RESET_PARTIAL"},
                        {"EMCY_RESET_PARTIAL"}),
    ("emcy", "state_pair"): ({False: None, True: "EMCY_STATE_PAIR"}, {"EMCY_STATE_PAIR"}),
    ("emcy", "generic_bit"): ({"always": None, "unclassified-only": "ERREG_NO_GENERIC"},
                              {"ERREG_NO_GENERIC"}),
    ("emcy", "history"): ({"code-and-info": None, "code-only": "HISTORY_CODE_ONLY"},
                          {"HISTORY_CODE_ONLY"}),
    ("store", "restore_saved"): ({False: None, True: "RESTORE_SAVED"}, {"RESTORE_SAVED"}),
}
SPECIAL = {("sdo", "transfers"), ("tpdo", "change_mask"), ("emcy", "boot")}
TABLES = sorted({t for t, _ in CHOICES} | {t for t, _ in SPECIAL})


def _show(v) -> str:
    return "true" if v is True else "false" if v is False else repr(v)


def apply(data: dict, opts: list[str], boot: list[int] | None, mask: int | None):
    """The options, boot EMCY bytes and change-mask object the typed tables
    of @p data say, merged with the [device] ones. Returns (opts, boot, mask)."""
    out = list(opts)

    def add(o: str, what: str) -> None:
        if o not in out:
            out.append(o)

    def govern(governed: set[str], wanted: set[str], what: str) -> None:
        legacy = {o for o in opts if o in governed}
        if legacy - wanted:
            raise DescError(f"{what} contradicts [device] options "
                            + ", ".join(sorted(legacy - wanted)))
        for o in sorted(wanted):
            add(o, what)

    for table in TABLES:
        tbl = data.get(table)
        if tbl is None:
            continue
        if not isinstance(tbl, dict):
            raise DescError(f"[{table}] must be a table")
        keys = {k for t, k in CHOICES if t == table} | {k for t, k in SPECIAL if t == table}
        unknown = sorted(set(tbl) - keys)
        if unknown:
            raise DescError(f"[{table}]: unknown key(s) {', '.join(unknown)} "
                            f"(known: {', '.join(sorted(keys))})")
        for key, value in tbl.items():
            what = f"[{table}] {key}"
            if (table, key) in CHOICES:
                choices, governed = CHOICES[(table, key)]
                hit = [c for c in choices if c == value and type(c) is type(value)]
                if not hit:
                    raise DescError(f"{what} must be one of "
                                    + ", ".join(_show(c) for c in choices))
                o = choices[hit[0]]
                govern(governed, {o} if o else set(), what)
            elif (table, key) == ("sdo", "transfers"):
                if (not isinstance(value, list) or
                        any(not isinstance(t, str) or t not in TRANSFERS for t in value)):
                    raise DescError(f"{what} must list transfer kinds out of "
                                    + ", ".join(TRANSFERS))
                kinds = frozenset(value)
                if kinds not in TRANSFER_SETS:
                    raise DescError(f"{what}: the server offers expedited transfers always and "
                                    "segmented upload whenever it offers more; "
                                    f"{sorted(kinds)} is not a set it can offer")
                govern({"SDO_NO_BLOCK", "SDO_NO_SEG_DOWNLOAD", "SDO_EXPEDITED_ONLY"},
                       TRANSFER_SETS[kinds], what)
            elif (table, key) == ("emcy", "boot"):
                if (not isinstance(value, list) or len(value) != 5 or
                        not all(isinstance(b, int) and not isinstance(b, bool) and 0 <= b <= 255
                                for b in value)):
                    raise DescError(f"{what} must be 5 bytes (EMCY bytes 3..7)")
                if boot is not None and list(boot) != list(value):
                    raise DescError(f"{what} contradicts [device] boot_emcy_data")
                boot = list(value)
                add("BOOT_EMCY", what)
            else:  # ("tpdo", "change_mask")
                if not isinstance(value, dict) or set(value) - {"object", "types"} or \
                        "object" not in value:
                    raise DescError(f"{what} must be {{ object = 0xIIII, types = [254, 255] }}")
                obj = value["object"]
                types = value.get("types", [254, 255])
                if isinstance(obj, bool) or not isinstance(obj, int):
                    raise DescError(f"{what}: object must be an index")
                if (not isinstance(types, list) or not types or
                        any(t not in (254, 255) or isinstance(t, bool) for t in types)):
                    raise DescError(f"{what}: types must list 254 and/or 255")
                if mask is not None and mask != obj:
                    raise DescError(f"{what} contradicts [device] tpdo_mask")
                mask = obj
                govern({"TPDO_MASK_254", "TPDO_MASK_255"},
                       {f"TPDO_MASK_{t}" for t in types}, what)
    return out, boot, mask
