/*
 * Test fixture for the FAULHABER and AnaGate seed tests: one node of a device
 * (co_devices.h: generated dictionary + co_device_t, its CiA 402 axes each on
 * a simulated plant of the fixture, other parts on the device's own
 * simulation, its device plug-in) on the in-memory bus,
 * time pushed in 1 ms steps (the device's axes and plug-in run before the
 * node), SDO and frame helpers in the manuals' notation.
 */
#ifndef SEEDRUN_H
#define SEEDRUN_H

#include <stdbool.h>
#include <stdint.h>

#include "co/co402_device.h"
#include "co/co_device.h"
#include "co/co402_sim.h"
#include "test_bus.h"

#define SR_AXES_MAX 4U
#define SR_MEM (64U * 1024U) /* instances, plants and plug-in state */

typedef struct seedrun {
    tb_bus_t bus;
    co_device_run_t run;
    co402_sim_t sim[SR_AXES_MAX];
    uint64_t mem[SR_MEM / 8U];
    co_node_t *node;
    uint8_t id;
} seedrun_t;

/** Start @p d as node @p id: @p cfg comes from the device's <cname>_config()
 *  and points at @p node's storage; @p sim: the plant of every CiA 402 axis
 *  (NULL: the device's simulated motor). Expects the boot-up frame. */
void sr_start(seedrun_t *s, const co_device_t *d, co_node_config_t *cfg, co_node_t *node,
              const co402_sim_config_t *sim, uint8_t id);

/** Process node and plug-ins at the present time (frames a write caused). */
void sr_poll(seedrun_t *s);

/** Push time by @p ms in 1 ms steps. */
void sr_run(seedrun_t *s, uint32_t ms);

/** Push time in 1 ms steps until a node sent a frame (at most @p max_ms);
 *  returns the ms it took. Fails the test on time-out. */
uint32_t sr_run_until_frame(seedrun_t *s, uint32_t max_ms);

/** SDO write (expedited, 1/2/4 bytes) expecting the confirmation and nothing else. */
void sr_sdo_write(seedrun_t *s, uint16_t index, uint8_t sub, uint32_t value, uint8_t size);

/** SDO read through the bus (expedited upload); the value. */
uint32_t sr_sdo_read(seedrun_t *s, uint16_t index, uint8_t sub);

/** SDO request @p req ("2B 40 60 00 06 00 00 00": the 8 data bytes) on
 *  0x600+id, expecting @p resp on 0x580+id and nothing else. */
void sr_sdo(seedrun_t *s, const char *req, const char *resp);

/** The next frame must be @p text; formats the COB-ID with the node-ID
 *  added when @p text starts with "+" ("+180 21 00" is 0x182 for node 2). */
void sr_expect_at(seedrun_t *s, const char *text, const char *file, int line);
#define sr_expect(s, text) sr_expect_at((s), (text), __FILE__, __LINE__)

/** Read a value through the dictionary (as the application). */
int64_t sr_get(seedrun_t *s, uint16_t index, uint8_t sub);

/** Write a value through the dictionary as the application (hooks run). */
void sr_set(seedrun_t *s, uint16_t index, uint8_t sub, int64_t value, uint8_t size);

/** Signed range check. */
void sr_assert_range_at(int64_t v, int64_t lo, int64_t hi, const char *file, int line);
#define sr_between(v, lo, hi) sr_assert_range_at((int64_t)(v), (lo), (hi), __FILE__, __LINE__)

#endif
