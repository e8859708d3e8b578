/*
 * PDO types. A device's PDOs are described by a const table the generator
 * makes (where each PDO's parameters live in the node's RAM image); the
 * runtime state is a caller-allocated array of n_rpdo + n_tpdo elements
 * (the generated <device>_node_t holds it). Included by co_node.h.
 */
#ifndef CO_PDO_H
#define CO_PDO_H

#include <stdint.h>

#include "co/co_config.h"

#define CO_PDO_NONE 0xFFFFU /**< co_pdo_desc_t: this sub-entry does not exist */

/** Where the parameters of one PDO live: offsets into the RAM image of the
 *  native values of the communication record (0x1400+n / 0x1800+n) and the
 *  mapping record (0x1600+n / 0x1A00+n). RPDOs first, then TPDOs. */
typedef struct co_pdo_desc {
    uint16_t cob;     /**< sub1 COB-ID, UNSIGNED32 */
    uint16_t type;    /**< sub2 transmission type, UNSIGNED8 */
    uint16_t inhibit; /**< sub3 inhibit time, UNSIGNED16 (CO_PDO_NONE: absent) */
    uint16_t event;   /**< sub5 event timer, UNSIGNED16 (CO_PDO_NONE: absent) */
    uint16_t start;   /**< sub6 SYNC start value, UNSIGNED8 (CO_PDO_NONE: absent) */
    uint16_t count;   /**< mapping sub0, UNSIGNED8 */
    uint16_t map;     /**< mapping sub1; sub2.. follow as consecutive UNSIGNED32 */
    uint8_t map_max;  /**< mapping entries the record has (1..8) */
} co_pdo_desc_t;

/** Runtime state of one PDO (private to the core). */
typedef struct co_pdo {
    uint32_t at;      /**< when its times started (us): TPDO the last event-driven
                           transmission (event timer and inhibit time run from it),
                           RPDO the last reception (deadline monitoring) */
    uint16_t flags;
    uint8_t count;    /**< TPDO: SYNCs counted; RPDO: length of the buffered frame */
    uint8_t len;      /**< bytes the mapping covers */
    uint8_t data[8];  /**< TPDO: last sent / sampled; RPDO: buffered until SYNC */
#if CO_PDO_FAST_MAX > 0
    uint16_t plain[CO_PDO_FAST_MAX]; /**< RAM offsets of the mapped values when every
                           entry is a plain value (copied directly, whole, byte-aligned) */
#endif
} co_pdo_t;

#endif /* CO_PDO_H */
