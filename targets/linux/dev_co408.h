/*
 * The CiA 408 valves in the daemon: one adapter for every device of
 * devices/co408_devices.h. Each channel runs on a simulated valve
 * (co408_sim.h) that the daemon's loop advances in monotonic time (the
 * profile asks for its 1 ms control tick as the node's next deadline).
 * device_entry_t.profile is the co408_device_t.
 */
#ifndef DEV_CO408_H
#define DEV_CO408_H

#include <stdint.h>

#include "co/co408_device.h"
#include "co/co408_sim.h"
#include "device_registry.h"

typedef struct dco408_app {
    co408_unit_t unit;
    co408_sim_t sim[CO408_UNIT_CHANNELS_MAX];
    co408_plant_t plants[CO408_UNIT_CHANNELS_MAX];
} dco408_app_t;

int dco408_prepare(void *app, const device_entry_t *entry, co_node_config_t *cfg,
                   uint32_t now_us);
int dco408_attach(void *app, co_node_t *node);
uint32_t dco408_process(void *app, co_node_t *node, uint32_t now_us);

#endif /* DEV_CO408_H */
