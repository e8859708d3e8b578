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

/** Where the parameters of one PDO live in the RAM image (native values):
 *  the number of its mapping entries (mapping record sub0, UNSIGNED8) with
 *  the entries (sub1..map_max, 16 bits each: co_od.h CO_OD_MAP_ENTRY, the
 *  dictionary shows them as UNSIGNED32) right before it and the
 *  transmission type (communication record sub2, UNSIGNED8) right after it;
 *  the COB-ID (sub1, UNSIGNED32 in its 16-bit form: co_od.h CO_SUB_COB16), and the optional parameters by their
 *  distance after the COB-ID. RPDOs first, then TPDOs. */
typedef struct co_pdo_desc {
    uint16_t cob;     /**< sub1 COB-ID */
    uint16_t count;   /**< mapping sub0 */
    uint8_t map_max;  /**< mapping entries the record has (1..8) */
    uint8_t start;    /**< sub6 SYNC start value, UNSIGNED8: from cob (0: none) */
    uint8_t inhibit;  /**< sub3 inhibit time, UNSIGNED16: from cob (0: none) */
    uint8_t event;    /**< sub5 event timer, UNSIGNED16: from cob (0: none) */
} co_pdo_desc_t;

/** Runtime state of one PDO (private to the core). */
typedef struct co_pdo {
    uint32_t at;      /**< when its times started (us): TPDO the last event-driven
                           transmission (event timer and inhibit time run from it),
                           RPDO the last reception (deadline monitoring) */
    uint16_t flags;
    uint8_t count;    /**< TPDO: SYNCs counted; RPDO: length of the buffered frame */
    uint8_t len;      /**< bytes the mapping covers; 0: disabled or invalid */
    uint8_t data[8];  /**< TPDO: sampled (synchronous: sent until the window closes;
                           type 252: for the answers), with change detection the
                           last sent; RPDO: buffered until SYNC */
} co_pdo_t;

#endif /* CO_PDO_H */
