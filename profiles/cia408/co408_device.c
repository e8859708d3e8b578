/*
 * CiA 408 devices: a valve's channels on the plug-in host (co/co408_device.h).
 */
#include "co/co408_device.h"

#include <stddef.h>
#include <string.h>

void co408_device_sim_config(const co408_device_t *device, uint8_t ch, co408_sim_config_t *c)
{
    co408_sim_defaults(c);
    if (device->sim_config != NULL) {
        device->sim_config(ch, c);
    }
}

co_err_t co408_unit_init(co408_unit_t *u, const co408_device_t *device,
                         const co408_plant_t *plants, const co_node_callbacks_t *app)
{
    (void)memset(u, 0, sizeof *u);
    if ((device->channels == 0U) || (device->channels > CO408_UNIT_CHANNELS_MAX) ||
        (plants == NULL)) {
        return CO_ERR_VALUE;
    }
    u->device = device;
    co_profile_host_init(&u->host, u->slots, (uint8_t)CO408_UNIT_CHANNELS_MAX, app);
    for (uint8_t n = 0U; n < device->channels; n++) {
        co408_config_t cfg;
        co_err_t err;
        (void)memset(&cfg, 0, sizeof cfg);
        cfg.channel = n;
        cfg.plant = plants[n];
        cfg.modes = device->modes[n];
        cfg.n_modes = device->n_modes[n];
        cfg.bad_value = device->bad_value;
        co408_init(&u->valve[n], &cfg);
        err = co_profile_add(&u->host, &co408_profile_ops, &u->valve[n]);
        if (err != CO_OK) {
            return err;
        }
    }
    return CO_OK;
}

co_node_callbacks_t co408_unit_callbacks(co408_unit_t *u)
{
    return co_profile_host_callbacks(&u->host);
}

co_err_t co408_unit_attach(co408_unit_t *u, co_node_t *node, uint32_t now_us)
{
    return (u->device == NULL) ? CO_ERR_VALUE : co_profile_host_attach(&u->host, node, now_us);
}

uint32_t co408_unit_process(co408_unit_t *u, uint32_t now_us)
{
    return co_profile_host_process(&u->host, now_us);
}

co408_valve_t *co408_unit_valve(co408_unit_t *u, uint8_t n)
{
    return ((u->device != NULL) && (n < u->device->channels)) ? &u->valve[n] : NULL;
}

/* ---- CiA 408 as a part of a device (co/co_device.h): one valve per channel,
 * configured by the co408_device_t, on its simulated valve. */

static co_err_t part_init(void *inst, const void *config, uint8_t n, const void *plant)
{
    const co408_device_t *device = (const co408_device_t *)config;
    co408_config_t cfg;

    if (n >= CO408_UNIT_CHANNELS_MAX) {
        return CO_ERR_VALUE;
    }
    (void)memset(&cfg, 0, sizeof cfg);
    cfg.channel = n;
    cfg.plant = *(const co408_plant_t *)plant;
    cfg.modes = device->modes[n];
    cfg.n_modes = device->n_modes[n];
    cfg.bad_value = device->bad_value;
    co408_init((co408_valve_t *)inst, &cfg);
    return CO_OK;
}

static void part_sim_init(void *sim, const void *config, uint8_t n, uint32_t now_us, void *plant)
{
    co408_sim_config_t sc;

    co408_device_sim_config((const co408_device_t *)config, n, &sc);
    co408_sim_init((co408_sim_t *)sim, &sc, now_us);
    *(co408_plant_t *)plant = co408_sim_plant((co408_sim_t *)sim);
}

const co_part_kind_t co408_part = {
    .name = "cia408",
    .ops = &co408_profile_ops,
    .inst_size = sizeof(co408_valve_t),
    .plant_size = sizeof(co408_plant_t),
    .sim_size = sizeof(co408_sim_t),
    .init = part_init,
    .sim_init = part_sim_init,
};
