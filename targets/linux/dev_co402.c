/* The CiA 402 drives in the daemon (see dev_co402.h). */
#include "dev_co402.h"

#include <stdlib.h>

#include "co_lx/clock.h"

int dco402_prepare(void *app, const device_entry_t *entry, co_node_config_t *cfg,
                   uint32_t now_us)
{
    dco402_app_t *a = (dco402_app_t *)app;
    const co402_device_t *device = (const co402_device_t *)entry->profile;
    co402_sim_config_t sc;

    if ((device == NULL) || (device->axes == 0U) || (device->axes > CO402_DRIVE_AXES_MAX)) {
        return -1;
    }
    co402_device_sim_config(device, &sc);
    for (uint8_t n = 0U; n < device->axes; n++) {
        co402_sim_init(&a->sim[n], &sc, now_us);
        a->plants[n] = co402_sim_plant(&a->sim[n]);
    }
    /* the profile first, then the daemon's own callbacks (logging) */
    if (co402_drive_init(&a->drv, device, a->plants, &cfg->cb) != CO_OK) {
        return -1;
    }
    if (device->state_size != 0U) {
        a->state = calloc(1U, device->state_size);
        if (a->state == NULL) {
            return -1;
        }
        co402_drive_set_state(&a->drv, a->state);
    }
    cfg->cb = co402_drive_callbacks(&a->drv);
    return 0;
}

int dco402_attach(void *app, co_node_t *node)
{
    dco402_app_t *a = (dco402_app_t *)app;

    return (co402_drive_attach(&a->drv, node, co_lx_now_us()) == CO_OK) ? 0 : -1;
}

uint32_t dco402_process(void *app, co_node_t *node, uint32_t now_us)
{
    dco402_app_t *a = (dco402_app_t *)app;

    (void)node;
    return co402_drive_process(&a->drv, now_us);
}

void dco402_detach(void *app, co_node_t *node)
{
    dco402_app_t *a = (dco402_app_t *)app;

    (void)node;
    free(a->state);
    a->state = NULL;
}
