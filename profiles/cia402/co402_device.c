/*
 * CiA 402 devices: a device's axes on the plug-in host (co/co402_device.h).
 */
#include "co/co402_device.h"

#include <stddef.h>
#include <string.h>

void co402_device_axis_config(const co402_device_t *device, uint8_t axis, co402_plant_t plant,
                              co402_config_t *cfg)
{
    (void)memset(cfg, 0, sizeof *cfg);
    cfg->axis = axis;
    cfg->options = device->options;
    cfg->plant = plant;
    cfg->modes = device->modes;
    cfg->counts_per_rev = device->counts_per_rev;
    cfg->hm_methods = device->hm_methods;
    cfg->n_hm_methods = device->n_hm_methods;
    cfg->errors = device->errors;
    cfg->n_errors = device->n_errors;
    cfg->vel_num = device->vel_num;
    cfg->vel_den = device->vel_den;
    cfg->acc_num = device->acc_num;
    cfg->acc_den = device->acc_den;
    cfg->full_speed = device->full_speed;
}

void co402_device_sim_config(const co402_device_t *device, co402_sim_config_t *c)
{
    co402_sim_defaults(c);
    if (device->sim_config != NULL) {
        device->sim_config(c);
    }
}

co_err_t co402_drive_init(co402_drive_t *drv, const co402_device_t *device,
                          const co402_plant_t *plants, const co_node_callbacks_t *app)
{
    (void)memset(drv, 0, sizeof *drv);
    if ((device->axes == 0U) || (device->axes > CO402_DRIVE_AXES_MAX) || (plants == NULL)) {
        return CO_ERR_VALUE;
    }
    drv->device = device;
    co_profile_host_init(&drv->host, drv->slots, (uint8_t)(CO402_DRIVE_AXES_MAX + 1U), app);
    for (uint8_t n = 0U; n < device->axes; n++) {
        co402_config_t cfg;
        co_err_t err;
        co402_device_axis_config(device, n, plants[n], &cfg);
        co402_init(&drv->axis[n], &cfg);
        err = co_profile_add(&drv->host, &co402_profile_ops, &drv->axis[n]);
        if (err != CO_OK) {
            return err;
        }
    }
    if (device->plugin != NULL) {
        return co_profile_add(&drv->host, device->plugin, drv);
    }
    return CO_OK;
}

void co402_drive_set_state(co402_drive_t *drv, void *state)
{
    drv->state = state;
    if ((state != NULL) && (drv->device != NULL)) {
        (void)memset(state, 0, drv->device->state_size);
    }
}

co_node_callbacks_t co402_drive_callbacks(co402_drive_t *drv)
{
    return co_profile_host_callbacks(&drv->host);
}

co_err_t co402_drive_attach(co402_drive_t *drv, co_node_t *node, uint32_t now_us)
{
    co_err_t err;

    if ((drv->device == NULL) || ((drv->device->state_size != 0U) && (drv->state == NULL))) {
        return CO_ERR_VALUE;
    }
    drv->node = node;
    err = co_profile_host_attach(&drv->host, node, now_us);

    if ((err == CO_OK) && (drv->device->powered_on != NULL)) {
        drv->device->powered_on(node, now_us);
    }
    return err;
}

uint32_t co402_drive_process(co402_drive_t *drv, uint32_t now_us)
{
    return co_profile_host_process(&drv->host, now_us);
}

co402_axis_t *co402_drive_axis(co402_drive_t *drv, uint8_t n)
{
    return ((drv->device != NULL) && (n < drv->device->axes)) ? &drv->axis[n] : NULL;
}

co_node_t *co402_drive_node(const co402_drive_t *drv)
{
    return drv->node;
}

void *co402_drive_state(const co402_drive_t *drv)
{
    return drv->state;
}
