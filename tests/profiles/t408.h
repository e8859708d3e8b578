/*
 * Test fixture for the CiA 408 profile: one cia408 node (generated
 * dictionary) on the in-memory bus with its valve channel on the simulated
 * valve, time pushed in 1 ms steps.
 */
#ifndef T408_H
#define T408_H

#include <stdint.h>

#include "cia408.h"
#include "co/co408.h"
#include "co/co408_sim.h"
#include "co/co_profile.h"
#include "test_bus.h"

typedef struct t408 {
    tb_bus_t bus;
    cia408_node_t n;
    co_profile_host_t host;
    co_profile_t slots[2];
    co408_valve_t v;
    co408_sim_t sim;
} t408_t;

/** Start node @p id (modes 1 and 4 offered) and expect its boot-up. */
void t408_start(t408_t *f, uint8_t id);

/** Push time by @p us in 1 ms steps (node and profile processing). */
void t408_run(t408_t *f, uint32_t us);

/** SDO download of @p size bytes of @p value to index/sub, expecting the
 *  answer @p abort (0: the confirmation). */
void t408_sdo_write(t408_t *f, uint16_t index, uint8_t sub, int64_t value, uint8_t size,
                    uint32_t abort);

/** SDO upload, expecting @p size bytes of @p value. */
void t408_sdo_expect(t408_t *f, uint16_t index, uint8_t sub, int64_t value, uint8_t size);

/** The control word by SDO (confirmed). */
void t408_cw(t408_t *f, uint16_t cw);

/** The status word by SDO must be @p sw. */
void t408_expect_sw(t408_t *f, uint16_t sw);

/** A value through the dictionary path, sign-extended by its type. */
int64_t t408_get(t408_t *f, uint16_t index, uint8_t sub);

/** Signed range check. */
void t408_assert_range_at(int64_t v, int64_t lo, int64_t hi, const char *file, int line);
#define assert_between(v, lo, hi) t408_assert_range_at((int64_t)(v), (lo), (hi), __FILE__, __LINE__)

#endif
