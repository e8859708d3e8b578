"""A device's personality as typed settings per service ([sdo], [pdo],
[tpdo], [emcy], [nmt], [store]): the same co_dev_t options as the option
list they replace, contradictions and impossible combinations refused."""
from __future__ import annotations

import pytest

from conftest import ROOT
from model import DescError, core_options, loads

BASE = ROOT / "devices" / "x.toml"  # include paths are relative to devices/
OPT = core_options()


def bits(*names: str) -> int:
    out = 0
    for n in names:
        out |= OPT[n]
    return out


def dev(text: str):
    return loads('include = "generic-301.toml"\n' + text, BASE)


@pytest.mark.parametrize("typed, legacy", [
    ('[sdo]\ntransfers = ["expedited"]', ["SDO_EXPEDITED_ONLY"]),
    ('[sdo]\ntransfers = ["expedited", "segmented-upload", "segmented-download"]',
     ["SDO_NO_BLOCK"]),
    ('[sdo]\ntransfers = ["expedited", "segmented-upload"]',
     ["SDO_NO_BLOCK", "SDO_NO_SEG_DOWNLOAD"]),
    ('[sdo]\ntransfers = ["expedited", "segmented-upload", "block"]', ["SDO_NO_SEG_DOWNLOAD"]),
    ('[sdo]\nunknown_object = "no-access"\nread_only = "no-access"',
     ["UNKNOWN_INDEX_NO_ACCESS", "READ_ONLY_NO_ACCESS"]),
    ('[pdo]\nparameter_writes = "pre-operational"\nmapping_while_valid = true\n'
     'cob_id_while_valid = true\nmapping_granularity = "byte"\nevent_timer_unit = "100us"\n'
     'short_rpdo = "accept"',
     ["PDO_CONFIG_PREOP_ONLY", "PDO_MAP_WHILE_VALID", "PDO_COBID_WHILE_VALID", "PDO_MAP_BYTES",
      "EVENT_TIMER_100US", "RPDO_SHORT_OK"]),
    ('[tpdo]\nchange_detection = false', ["TPDO_NO_CHANGE_DETECT"]),
    ('[emcy]\nreset = "each-clear"\nstate_pair = true\ngeneric_bit = "unclassified-only"\n'
     'history = "code-only"',
     ["EMCY_RESET_PARTIAL", "EMCY_STATE_PAIR", "ERREG_NO_GENERIC", "HISTORY_CODE_ONLY"]),
    ('[nmt]\nbootup = false\nguarding_with_heartbeat = true',
     ["NO_BOOTUP", "GUARD_WITH_HEARTBEAT"]),
    ('[store]\nrestore_saved = true', ["RESTORE_SAVED"]),
    ('[sdo]\ntransfers = ["expedited", "segmented-upload", "segmented-download", "block"]\n'
     '[pdo]\nparameter_writes = "cia301"\n[emcy]\nreset = "all-cleared"', []),
])
def test_typed_is_the_option_list(typed: str, legacy: list[str]) -> None:
    a = dev(typed)
    b = dev("[device]\noptions = [" + ", ".join(f'"{o}"' for o in legacy) + "]")
    # (| LSS: the base, generic-301, is an LSS slave, [device] lss)
    assert a.option_bits == b.option_bits == bits(*legacy) | OPT["LSS"]


def test_boot_emcy_and_change_mask() -> None:
    # the change mask needs its objects: a device that has them (its own
    # settings replaced by these)
    d = loads('include = "ssd-630.toml"\n[emcy]\nboot = [1, 2, 3, 4, 5]\n'
              '[tpdo]\nchange_mask = { object = 0x2014, types = [254, 255] }\n', BASE)
    assert d.boot_emcy_data == [1, 2, 3, 4, 5]
    assert d.tpdo_mask == 0x2014
    assert d.option_bits & bits("BOOT_EMCY", "TPDO_MASK_254", "TPDO_MASK_255") == \
        bits("BOOT_EMCY", "TPDO_MASK_254", "TPDO_MASK_255")


@pytest.mark.parametrize("text, needle", [
    ('[sdo]\ntransfers = ["segmented-upload"]', "not a set it can offer"),
    ('[sdo]\ntransfers = ["expedited", "segmented-download"]', "not a set it can offer"),
    ('[sdo]\ntransfers = ["expedited", "fast"]', "must list transfer kinds"),
    ('[sdo]\nread_only = "maybe"', "must be one of"),
    ('[nmt]\nbootup = "yes"', "must be one of"),
    ('[pdo]\nwhen = 1', "unknown key"),
    ('[device]\noptions = ["SDO_NO_BLOCK"]\n[sdo]\ntransfers = '
     '["expedited", "segmented-upload", "segmented-download", "block"]', "contradicts"),
    ('[device]\noptions = ["EMCY_RESET_PARTIAL"]\n[emcy]\nreset = "all-cleared"', "contradicts"),
    ('[emcy]\nboot = [1, 2]', "5 bytes"),
    ('[tpdo]\nchange_mask = { object = 0x2014, types = [1] }', "254 and/or 255"),
])
def test_refused(text: str, needle: str) -> None:
    with pytest.raises(DescError) as e:
        dev(text)
    assert needle in str(e.value)
