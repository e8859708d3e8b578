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

const co_node_callbacks_t *co408_unit_callbacks(co408_unit_t *u)
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

/* Control interface (co_device_set, docs/profiles.md): the faults of a
 * channel's simulated valve by their EMCY code as the index, the channel's
 * inputs at CO408_SIM_INPUTS + channel; sub-index: the channel's number
 * (faults: 0 or 1 channel 1, 2 channel 2) or the input. */
static co_err_t sim_fault(co408_sim_t *s, uint16_t index, int64_t value)
{
    uint32_t clear;
    uint32_t set;

    switch (index) {
    case CO408_ERR_SOLENOID1:
        clear = CO408_SIM_SOL_A_OPEN | CO408_SIM_SOL_A_SHORT;
        set = (value == 1) ? CO408_SIM_SOL_A_OPEN : CO408_SIM_SOL_A_SHORT;
        break;
    case CO408_ERR_SOLENOID2:
        clear = CO408_SIM_SOL_B_OPEN | CO408_SIM_SOL_B_SHORT;
        set = (value == 1) ? CO408_SIM_SOL_B_OPEN : CO408_SIM_SOL_B_SHORT;
        break;
    case CO408_ERR_SUPPLY:
        clear = CO408_SIM_UNDERVOLT;
        set = clear;
        break;
    default: /* CO408_ERR_SP_CABLE */
        clear = CO408_SIM_SP_CABLE;
        set = clear;
        break;
    }
    if ((value < 0) || (value > ((clear == set) ? 1 : 2))) {
        return CO_ERR_VALUE;
    }
    co408_sim_inject(s, (s->faults & ~clear) | ((value != 0) ? set : 0U));
    return CO_OK;
}

static co_err_t part_sim_set(void *inst, void *sim, uint16_t index, uint8_t sub, int64_t value)
{
    co408_sim_t *s = (co408_sim_t *)sim;
    uint8_t ch = ((const co408_valve_t *)inst)->cfg.channel;

    if (s == NULL) {
        return CO_ERR_NO_OBJECT;
    }
    if ((index == CO408_ERR_SOLENOID1) || (index == CO408_ERR_SOLENOID2) ||
        (index == CO408_ERR_SUPPLY) || (index == CO408_ERR_SP_CABLE)) {
        uint8_t want = (sub == 0U) ? 0U : (uint8_t)(sub - 1U);
        return (want == ch) ? sim_fault(s, index, value) : CO_ERR_NO_OBJECT;
    }
    if (index != (uint16_t)(CO408_SIM_INPUTS + ch)) {
        return CO_ERR_NO_OBJECT;
    }
    switch (sub) {
    case CO408_SIM_IN_ENABLE:
        if ((value < 0) || (value > 1)) {
            return CO_ERR_VALUE;
        }
        co408_sim_set_input(s, CO408_IN_ENABLE, value != 0);
        return CO_OK;
    case CO408_SIM_IN_LOCAL_SP:
        if ((value < -(int64_t)CO408_FULL) || (value > (int64_t)CO408_FULL)) {
            return CO_ERR_VALUE;
        }
        co408_sim_set_local_sp(s, (int32_t)value);
        return CO_OK;
    default:
        return CO_ERR_NO_SUB;
    }
}

const co_part_kind_t co408_part = {
    .name = "cia408",
    .ops = &co408_profile_ops,
    .inst_size = sizeof(co408_valve_t),
    .plant_size = sizeof(co408_plant_t),
    .sim_size = sizeof(co408_sim_t),
    .init = part_init,
    .sim_init = part_sim_init,
    .sim_set = part_sim_set,
};
