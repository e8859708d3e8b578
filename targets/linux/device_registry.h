/*
 * The devices the daemon can be: one entry per device type.
 *
 * An entry names the generated dictionary (co_dev_t), the sizes of the
 * per-node RAM image and hook table the daemon allocates, the device's EDS
 * (embedded at build time from the generator's output), and the
 * application part: per-node state of app_size bytes (zeroed) and optional
 * callbacks. A profile (CiA 402 drive, 401 I/O, ...) plugs in here:
 *
 *   prepare  before co_node_init: may put the profile's callbacks in front
 *            of the daemon's (cfg->cb); the profile's device description is
 *            entry->profile. Non-zero stops the daemon (exit 1).
 *   attach   after co_node_init (boot-up sent, Pre-operational): bind hooks,
 *            set up the state; non-zero stops the daemon (exit 1).
 *   process  every loop round and at the deadline it returned last: run the
 *            state machine / plant; returns its next deadline (absolute us,
 *            CO_NO_DEADLINE for none).
 *   sync     a SYNC was received or produced.
 *   nmt      the NMT state changed.
 *   reset    an NMT reset is executed (the core has restored its objects).
 *   detach   at stop: release what attach took.
 */
#ifndef DEVICE_REGISTRY_H
#define DEVICE_REGISTRY_H

#include <stddef.h>
#include <stdint.h>

#include "co/co_node.h"

typedef struct device_entry {
    const char *name;
    const char *summary;
    const co_dev_t *dev;
    size_t ram_size;          /**< bytes of the RAM image (== dev->ram_size) */
    uint8_t n_hooks;          /**< hook slots (== dev->n_hooks) */
    const unsigned char *eds; /**< EDS text (CiA 306, ASCII), NUL-terminated */
    size_t app_size;          /**< bytes of per-node application state */
    const void *profile;      /**< the profile's description of the device (or NULL) */
    int (*prepare)(void *app, const struct device_entry *entry, co_node_config_t *cfg,
                   uint32_t now_us);
    int (*attach)(void *app, co_node_t *node);
    uint32_t (*process)(void *app, co_node_t *node, uint32_t now_us);
    void (*sync)(void *app, co_node_t *node, uint8_t counter);
    void (*nmt)(void *app, co_node_t *node, co_nmt_state_t state);
    void (*reset)(void *app, co_node_t *node, co_reset_t kind);
    void (*detach)(void *app, co_node_t *node);
} device_entry_t;

/** Number of devices in the registry. */
size_t device_count(void);

/** The @p i-th device (registry order). */
const device_entry_t *device_at(size_t i);

/** The device called @p name, or NULL. */
const device_entry_t *device_find(const char *name);

#endif /* DEVICE_REGISTRY_H */
