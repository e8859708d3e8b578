/*
 * Test fixture for the CiA 402 profile: one cia402 node (generated
 * dictionary) on the in-memory bus with its axis on the simulated plant,
 * and time pushed in control ticks.
 */
#ifndef T402_H
#define T402_H

#include <stdint.h>

#include "cia402.h"
#include "co/co402.h"
#include "co/co402_sim.h"
#include "co/co_profile.h"
#include "test_bus.h"

typedef struct t402 {
    tb_bus_t bus;
    cia402_node_t n;
    co_profile_host_t host;
    co_profile_t slots[2];
    co402_axis_t ax;
    co402_sim_t sim;
    co402_sim_config_t simcfg;
    unsigned syncs;
} t402_t;

/** Signed range check (cmocka's assert_in_range is unsigned). */
void t402_assert_range_at(int64_t v, int64_t lo, int64_t hi, const char *file, int line);
#define assert_between(v, lo, hi) t402_assert_range_at((int64_t)(v), (lo), (hi), __FILE__, __LINE__)

/** Simulation parameters the tests start from (co402_sim_defaults). */
void t402_sim_defaults(co402_sim_config_t *c);

/** Start node @p id with the axis options @p options on the plant @p sim
 *  (NULL: t402_sim_defaults). Expects the boot-up frame. */
void t402_start(t402_t *f, uint8_t id, uint32_t options, const co402_sim_config_t *sim);

/** Push time by @p us in 1 ms steps (node and profile processing). */
void t402_run(t402_t *f, uint32_t us);

/** Run until (statusword & mask) == value, at most @p max_us; returns the
 *  time it took (fails the test on time-out). */
uint32_t t402_run_until(t402_t *f, uint16_t mask, uint16_t value, uint32_t max_us);

/** Write through the dictionary path as the application (hooks run). */
void t402_set(t402_t *f, uint16_t index, uint8_t sub, int64_t value, uint8_t size);

/** Read a value through the dictionary path. */
int64_t t402_get(t402_t *f, uint16_t index, uint8_t sub);

/** Write the controlword through the dictionary path. */
void t402_cw(t402_t *f, uint16_t cw);

/** The statusword as stored in the dictionary. */
uint16_t t402_sw(t402_t *f);

/** Shutdown, switch on, enable operation (by SDO, checking each answer). */
void t402_enable(t402_t *f);

#endif
