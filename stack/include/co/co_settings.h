/**
 * @file co_settings.h
 * A device's personality: typed settings, one part per service, made by the
 * generator from the tables of the device's description ([nmt], [sdo],
 * [pdo], [tpdo], [emcy], [store], [device] lss; tools/odgen/personality.py).
 *
 * The zero of every field is the CiA 301 behaviour (CiA 305 for LSS), so a
 * zeroed co_settings_t is a strict CiA 301 device. Each other value is a
 * documented deviation of a real device (named after it). A build with
 * CO_PERSONALITY 0 (co_config.h) implements only the zeros: the code of the
 * deviations is left out and a device that needs one is refused.
 */
#ifndef CO_SETTINGS_H
#define CO_SETTINGS_H

#include <stdint.h>

/* ---- values of the fields that are not yes/no ---- */

/* co_nmt_settings_t.bootup */
#define CO_BOOTUP_FRAME 0U /**< the boot-up frame after initialisation */
#define CO_BOOTUP_NONE  1U /**< none (devices before DS301 4.0) */

/* co_sdo_settings_t.refused: the transfer kinds the server does not offer
 * (expedited is always offered); a set of these bits */
#define CO_SDO_XFER_SEG_UPLOAD   0x01U /**< segmented upload (only with the two below) */
#define CO_SDO_XFER_SEG_DOWNLOAD 0x02U /**< segmented download: refused at its initiate, 0x06010000 (SSD 630) */
#define CO_SDO_XFER_BLOCK        0x04U /**< block transfers: 0x05040001 */
/** expedited only: no segmented or block transfer (Kollmorgen S300/S700) */
#define CO_SDO_EXPEDITED_ONLY (CO_SDO_XFER_SEG_UPLOAD | CO_SDO_XFER_SEG_DOWNLOAD | CO_SDO_XFER_BLOCK)

/* co_sdo_settings_t.unknown_object / .read_only: the abort code */
#define CO_SDO_ABORT_CIA       0U /**< 0x06020000 no object / 0x06010002 read only */
#define CO_SDO_ABORT_NO_ACCESS 1U /**< 0x06010000 unsupported access (SSD 630) */

/* co_pdo_settings_t.parameter_writes */
#define CO_PDO_WRITES_CIA301 0U /**< CiA 301's rules (mapping while invalid, ...) */
#define CO_PDO_WRITES_PREOP  1U /**< 0x1400..0x1BFF only in Pre-operational, else
                                     0x08000022 (SSD 630) */
/* co_pdo_settings_t.granularity */
#define CO_PDO_MAP_BITS  0U /**< any bit length */
#define CO_PDO_MAP_BYTES 1U /**< whole bytes only, else 0x06040041 (Kollmorgen) */
/* co_pdo_settings_t.event_timer_unit */
#define CO_PDO_TIMER_MS    0U /**< 1 ms */
#define CO_PDO_TIMER_100US 1U /**< 100 us (Kollmorgen) */
/* co_pdo_settings_t.short_rpdo */
#define CO_RPDO_SHORT_EMCY   0U /**< an RPDO shorter than its mapping: EMCY 0x8210 */
#define CO_RPDO_SHORT_ACCEPT 1U /**< the entries it covers are written, no EMCY (AnaGate) */

/* co_tpdo_settings_t.change_detection */
#define CO_TPDO_CHANGE_SENDS   0U /**< a change of the mapped data sends a 254/255 TPDO */
#define CO_TPDO_CHANGE_IGNORED 1U /**< only a request, the event timer or an RTR; none on
                                       entering Operational (FAULHABER) */
/* co_tpdo_settings_t.change_mask: the transmission types whose change detection
 * the masks of co_dev_t.tpdo_mask filter; a set of these bits */
#define CO_TPDO_MASK_254 0x01U /**< (SSD 630) */
#define CO_TPDO_MASK_255 0x02U /**< (Kollmorgen) */

/* co_emcy_settings_t.reset */
#define CO_EMCY_RESET_ALL_CLEARED 0U /**< EMCY 0x0000 when no error is left */
#define CO_EMCY_RESET_EACH_CLEAR  1U /**< also when some remain (CiA 301 "may") */
/* co_emcy_settings_t.generic_bit */
#define CO_ERREG_GENERIC_ALWAYS       0U /**< every error sets 0x1001 bit 0 */
#define CO_ERREG_GENERIC_UNCLASSIFIED 1U /**< only an error that names no bit (Kollmorgen) */
/* co_emcy_settings_t.history */
#define CO_HISTORY_CODE_AND_INFO 0U /**< 0x1003: code and manufacturer bytes */
#define CO_HISTORY_CODE_ONLY     1U /**< the code only (Kollmorgen) */

/* co_store_settings_t.restore */
#define CO_RESTORE_DEFAULTS 0U /**< 0x1011 sub 1..3: the defaults at the next reset */
#define CO_RESTORE_SAVED    1U /**< also sub 4..6: the last saved set (FAULHABER) */

/* co_lss_settings_t.cob_ids: a node-ID change from one valid ID to another */
#define CO_LSS_COBS_FOLLOW 0U /**< the $NODEID COB-IDs follow the new node-ID */
#define CO_LSS_COBS_KEEP   1U /**< the PDO and EMCY COB-IDs stay; from 0xFF to valid the
                                   communication settings go back to their defaults
                                   and a stored communication set is dropped (FAULHABER) */
/* co_lss_settings_t.selective */
#define CO_LSS_MATCH_REVISION  0U /**< switch state selective compares all four parts */
#define CO_LSS_IGNORE_REVISION 1U /**< ... all but the revision number (FAULHABER) */
/* co_lss_settings_t.node_id */
#define CO_LSS_ID_CONFIGURED 0U /**< co_node_config_t.node_id, or the LSS-stored one */
#define CO_LSS_ID_ONLY       1U /**< only through LSS: the LSS-stored one or
                                     unconfigured (FAULHABER) */

/** NMT and error control ([nmt]). */
typedef struct co_nmt_settings {
    uint8_t bootup;                /**< CO_BOOTUP_* */
    uint8_t boot_emcy;             /**< 1: EMCY 0x0000 with co_dev_t.boot_emcy_data after
                                        the boot-up (SSD 630) */
    uint8_t guarding_with_hb;      /**< 1: guarding RTRs answered even while heartbeats
                                        are produced */
    uint8_t guarding_hb_exclusive; /**< 1: 0x100C/0x100D refused with 0x060A0023 while
                                        0x1017 is not 0 (Wandfluh DSV) */
} co_nmt_settings_t;

/** SDO server ([sdo]). */
typedef struct co_sdo_settings {
    uint8_t refused;        /**< CO_SDO_XFER_* not offered; 0: all */
    uint8_t unknown_object; /**< CO_SDO_ABORT_* for an index that does not exist */
    uint8_t read_only;      /**< CO_SDO_ABORT_* for a write to a read-only object */
} co_sdo_settings_t;

/** PDO communication and mapping parameters, RPDO reception ([pdo]). */
typedef struct co_pdo_settings {
    uint8_t parameter_writes;    /**< CO_PDO_WRITES_* */
    uint8_t mapping_while_valid; /**< 1: mapping writable while the PDO is valid, outside
                                      Operational (SSD 630, Kollmorgen) */
    uint8_t cob_id_while_valid;  /**< 1: the CAN-ID may change while valid (Kollmorgen) */
    uint8_t granularity;         /**< CO_PDO_MAP_* */
    uint8_t event_timer_unit;    /**< CO_PDO_TIMER_* */
    uint8_t short_rpdo;          /**< CO_RPDO_SHORT_* */
    uint8_t tpdo_after_rpdo;     /**< 1: RPDO n requests TPDO n when that has type 255
                                      (Wandfluh DSV) */
} co_pdo_settings_t;

/** Event-driven TPDOs ([tpdo]). */
typedef struct co_tpdo_settings {
    uint8_t change_detection; /**< CO_TPDO_CHANGE_* */
    uint8_t change_mask;      /**< CO_TPDO_MASK_* set; 0: none */
} co_tpdo_settings_t;

/** EMCY producer and error register ([emcy]). */
typedef struct co_emcy_settings {
    uint8_t reset;       /**< CO_EMCY_RESET_* */
    uint8_t state_pair;  /**< 1: after every error EMCY an EMCY 0x0000 with the register
                              (Kollmorgen) */
    uint8_t generic_bit; /**< CO_ERREG_GENERIC_* */
    uint8_t history;     /**< CO_HISTORY_* */
} co_emcy_settings_t;

/** Parameter storage ([store]). */
typedef struct co_store_settings {
    uint8_t restore; /**< CO_RESTORE_* */
} co_store_settings_t;

/** LSS slave, CiA 305 ([device] lss; build option CO_LSS). */
typedef struct co_lss_settings {
    uint8_t slave;     /**< 1: the device is an LSS slave */
    uint8_t cob_ids;   /**< CO_LSS_COBS_* */
    uint8_t selective; /**< CO_LSS_*_REVISION */
    uint8_t node_id;   /**< CO_LSS_ID_* */
} co_lss_settings_t;

/** The whole personality (co_dev_t.set). */
typedef struct co_settings {
    co_nmt_settings_t nmt;
    co_sdo_settings_t sdo;
    co_pdo_settings_t pdo;
    co_tpdo_settings_t tpdo;
    co_emcy_settings_t emcy;
    co_store_settings_t store;
    co_lss_settings_t lss;
} co_settings_t;

#endif /* CO_SETTINGS_H */
