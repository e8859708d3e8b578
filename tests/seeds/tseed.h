/*
 * Test fixture for the seed devices: nodes of a CiA 402 device (generated
 * dictionary + co_device_t, co_devices.h) on the in-memory bus, each axis on its own
 * simulated plant, time pushed in 1 ms steps.
 */
#ifndef TSEED_H
#define TSEED_H

#include <stdint.h>

#include "co/co402.h"
#include "co/co402_device.h"
#include "co/co_device.h"
#include "co/co402_sim.h"
#include "test_bus.h"

#define TSEED_NODES 2U

typedef struct tseed_node {
    co_device_run_t run;
    uint64_t mem[2048];      /* the device's instance and plug-in state */
    co402_sim_t sim;
    co402_sim_config_t simcfg;
    co_node_t *node;
} tseed_node_t;

typedef struct tseed {
    tb_bus_t bus;
    tseed_node_t n[TSEED_NODES];
    unsigned count;
} tseed_t;

/** Signed range check (cmocka's assert_in_range is unsigned). */
void tseed_assert_range_at(int64_t v, int64_t lo, int64_t hi, const char *file, int line);
#define assert_between(v, lo, hi) tseed_assert_range_at((int64_t)(v), (lo), (hi), __FILE__, __LINE__)

/** An empty bus (time 1000 us). */
void tseed_init(tseed_t *f);

/** Power on node @p k (slot on the bus) of @p dev with node-ID @p id: @p cfg
 *  comes from the device's <cname>_config() and points at @p node's storage;
 *  @p sim: the plant (NULL: the device's simulated motor). The boot frames
 *  are left on the bus for the test to expect. */
void tseed_start(tseed_t *f, unsigned k, const co_device_t *dev, co_node_config_t *cfg,
                 co_node_t *node, uint8_t id, const co402_sim_config_t *sim);

/** Push time by @p us in 1 ms steps (every node and its axes). */
void tseed_run(tseed_t *f, uint32_t us);

/** Run until (statusword of node @p k & mask) == value, at most @p max_us;
 *  returns the time it took (fails the test on time-out). */
uint32_t tseed_run_until(tseed_t *f, unsigned k, uint16_t mask, uint16_t value, uint32_t max_us);

/** Read a value of node @p k through the dictionary path (sign-extended). */
int64_t tseed_get(tseed_t *f, unsigned k, uint16_t index, uint8_t sub);

/** Write a value of node @p k through the dictionary path as the application. */
void tseed_set(tseed_t *f, unsigned k, uint16_t index, uint8_t sub, int64_t value, uint8_t size);

/** The statusword of node @p k. */
uint16_t tseed_sw(tseed_t *f, unsigned k);

/** The axis of node @p k. */
co402_axis_t *tseed_axis(tseed_t *f, unsigned k);

/** tb_expect with printf formatting. */
void tseed_expectf_at(tb_bus_t *bus, const char *file, int line, const char *fmt, ...);
#define tseed_expectf(bus, ...) tseed_expectf_at((bus), __FILE__, __LINE__, __VA_ARGS__)

/** tb_send with printf formatting. */
void tseed_sendf(tb_bus_t *bus, const char *fmt, ...);

/** The next frame on the bus, which must have COB-ID @p id and @p dlc bytes. */
const co_frame_t *tseed_frame_at(tb_bus_t *bus, uint16_t id, uint8_t dlc, const char *file,
                                 int line);
#define tseed_frame(bus, id, dlc) tseed_frame_at((bus), (id), (dlc), __FILE__, __LINE__)

/** Little-endian 32-bit value of @p f at byte @p at (sign-extended). */
int32_t tseed_i32(const co_frame_t *f, unsigned at);
int16_t tseed_i16(const co_frame_t *f, unsigned at);

#endif
