/*
 * The CiA 402 drives in the daemon: one adapter for every device of
 * devices/co402_devices.h. Each axis runs on a simulated plant (co402_sim.h)
 * that the daemon's loop advances in real (monotonic) time: the profile asks
 * for its control tick as the node's next deadline, so the loop wakes up for
 * it and the motor really moves between two SDO requests of a master.
 *
 * device_entry_t.profile is the co402_device_t; prepare puts the profile's
 * callbacks in front of the daemon's, attach starts the axes (Switch on
 * disabled) and the device's power-on step.
 */
#ifndef DEV_CO402_H
#define DEV_CO402_H

#include <stdint.h>

#include "co/co402_device.h"
#include "co/co402_sim.h"
#include "device_registry.h"

typedef struct dco402_app {
    co402_drive_t drv;
    co402_sim_t sim[CO402_DRIVE_AXES_MAX];
    co402_plant_t plants[CO402_DRIVE_AXES_MAX];
    void *state; /* the device plug-in's state (state_size bytes) */
} dco402_app_t;

int dco402_prepare(void *app, const device_entry_t *entry, co_node_config_t *cfg,
                   uint32_t now_us);
int dco402_attach(void *app, co_node_t *node);
uint32_t dco402_process(void *app, co_node_t *node, uint32_t now_us);
void dco402_detach(void *app, co_node_t *node);

#endif /* DEV_CO402_H */
