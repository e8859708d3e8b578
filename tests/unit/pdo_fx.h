/*
 * Fixture of the PDO tests: one pdo-test node (tests/unit/devices/pdo-test.toml)
 * on the in-memory bus, with a device copy whose settings a test may set, and
 * hooks on 0x2020 that count, veto and refresh.
 */
#ifndef PDO_FX_H
#define PDO_FX_H

#include <stdint.h>

#include "pdo_test.h"
#include "test_bus.h"

typedef struct pfx {
    tb_bus_t bus;
    pdo_test_node_t n;
    co_dev_t dev;           /* pdo_test_dev with the test's settings */
    unsigned hook_reads;
    unsigned hook_writes;
    uint32_t hook_value;    /* what the read hook puts into 0x2020 */
    uint32_t hook_written;  /* last value the write hook saw */
    co_err_t hook_veto;     /* the write hook's answer */
} pfx_t;

/** Start node @p id with the personality @p set (NULL: CiA 301) on a fresh bus; the boot-up is consumed. */
void pfx_start(pfx_t *f, uint8_t id, const co_settings_t *set);

/** Set a value as the application does (co_od_write with as_app). */
void pfx_set(pfx_t *f, uint16_t index, uint8_t sub, uint32_t value, uint32_t len);

/** Read a value through the dictionary (co_od_read). */
uint32_t pfx_get(pfx_t *f, uint16_t index, uint8_t sub);

#endif
