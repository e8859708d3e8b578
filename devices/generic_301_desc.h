/*
 * generic-301's device plug-in (generic_301_impl, devices/generic_301.c):
 *   0x2300 "Large data": a DOMAIN of up to G301_DOMAIN_CAP bytes held in
 *          memory. A download is staged and becomes the value only when it
 *          completes (an aborted transfer leaves the old value); longer
 *          values are refused with 0x06070012. Empty after start and after
 *          reset node.
 *   0x2200 "Hooked UNSIGNED32": the write hook refuses 0xDEADBEEF with
 *          0x06090030 (an application veto as the master sees it).
 *   0x2024 "Uptime": seconds since start or the last reset node.
 * 0x1010/0x1011 keep their slots for the core's storage.
 */
#ifndef GENERIC_301_DESC_H
#define GENERIC_301_DESC_H

#include <stdbool.h>
#include <stdint.h>

#include "co/co_node.h"

#define G301_DOMAIN_CAP (128U * 1024U)
#define G301_VETO_VALUE 0xDEADBEEFUL

typedef struct g301_app {
    uint8_t domain[G301_DOMAIN_CAP];
    uint8_t stage[G301_DOMAIN_CAP];
    uint32_t domain_len;
    uint32_t stage_len;
    uint32_t t0;          /**< time uptime counts from */
    uint32_t next_tick;   /**< next uptime update */
    bool restart;         /**< take t0 at the next process */
} g301_app_t;

/* the plug-in state (co_device_impl_t.state_size) is a g301_app_t */

#endif /* GENERIC_301_DESC_H */
