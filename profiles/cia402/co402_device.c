/*
 * CiA 402 as a part of a device (co/co402_device.h).
 */
#include "co/co402_device.h"

#include <stddef.h>
#include <string.h>

void co402_params_axis_config(const co402_params_t *params, uint8_t axis, co402_plant_t plant,
                              co402_config_t *cfg)
{
    (void)memset(cfg, 0, sizeof *cfg);
    cfg->axis = axis;
    cfg->options = params->options;
    cfg->plant = plant;
    cfg->modes = params->modes;
    cfg->counts_per_rev = params->counts_per_rev;
    cfg->hm_methods = params->hm_methods;
    cfg->n_hm_methods = params->n_hm_methods;
    cfg->errors = params->errors;
    cfg->n_errors = params->n_errors;
    cfg->vel_num = params->vel_num;
    cfg->vel_den = params->vel_den;
    cfg->acc_num = params->acc_num;
    cfg->acc_den = params->acc_den;
    cfg->full_speed = params->full_speed;
}

void co402_params_sim_config(const co402_params_t *params, co402_sim_config_t *c)
{
    co402_sim_defaults(c);
    if ((params != NULL) && (params->sim_config != NULL)) {
        params->sim_config(c);
    }
}

static co_err_t part_init(void *inst, const void *config, uint8_t n, const void *plant)
{
    co402_config_t cfg;

    if (n >= 8U) {
        return CO_ERR_VALUE;
    }
    co402_params_axis_config((const co402_params_t *)config, n, *(const co402_plant_t *)plant,
                             &cfg);
    co402_init((co402_axis_t *)inst, &cfg);
    return CO_OK;
}

static void part_sim_init(void *sim, const void *config, uint8_t n, uint32_t now_us, void *plant)
{
    co402_sim_config_t sc;

    (void)n;
    co402_params_sim_config((const co402_params_t *)config, &sc);
    co402_sim_init((co402_sim_t *)sim, &sc, now_us);
    *(co402_plant_t *)plant = co402_sim_plant((co402_sim_t *)sim);
}

const co_part_kind_t co402_part = {
    .name = "cia402",
    .ops = &co402_profile_ops,
    .inst_size = sizeof(co402_axis_t),
    .plant_size = sizeof(co402_plant_t),
    .sim_size = sizeof(co402_sim_t),
    .init = part_init,
    .sim_init = part_sim_init,
};

const co402_params_t *co402_device_params(const co_device_t *device)
{
    const co_device_impl_t *impl = device->impl;

    for (uint8_t p = 0U; (impl != NULL) && (p < impl->n_parts); p++) {
        if (impl->parts[p].kind == &co402_part) {
            return (const co402_params_t *)impl->parts[p].config;
        }
    }
    return NULL;
}

co402_axis_t *co402_device_axis(const co_device_run_t *run, uint8_t n)
{
    return (co402_axis_t *)co_device_instance(run, &co402_part, n);
}

uint8_t co402_device_axes(const co_device_t *device)
{
    const co_device_impl_t *impl = device->impl;
    uint8_t n = 0U;

    for (uint8_t p = 0U; (impl != NULL) && (p < impl->n_parts); p++) {
        if (impl->parts[p].kind == &co402_part) {
            n = (uint8_t)(n + impl->parts[p].count);
        }
    }
    return n;
}
