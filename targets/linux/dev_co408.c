/* The CiA 408 valves in the daemon (see dev_co408.h). */
#include "dev_co408.h"

#include "co_lx/clock.h"

int dco408_prepare(void *app, const device_entry_t *entry, co_node_config_t *cfg,
                   uint32_t now_us)
{
    dco408_app_t *a = (dco408_app_t *)app;
    const co408_device_t *device = (const co408_device_t *)entry->profile;

    if ((device == NULL) || (device->channels == 0U) ||
        (device->channels > CO408_UNIT_CHANNELS_MAX)) {
        return -1;
    }
    for (uint8_t n = 0U; n < device->channels; n++) {
        co408_sim_config_t sc;
        co408_device_sim_config(device, n, &sc);
        co408_sim_init(&a->sim[n], &sc, now_us);
        a->plants[n] = co408_sim_plant(&a->sim[n]);
    }
    /* the profile first, then the daemon's own callbacks (logging) */
    if (co408_unit_init(&a->unit, device, a->plants, &cfg->cb) != CO_OK) {
        return -1;
    }
    cfg->cb = co408_unit_callbacks(&a->unit);
    return 0;
}

int dco408_attach(void *app, co_node_t *node)
{
    dco408_app_t *a = (dco408_app_t *)app;

    return (co408_unit_attach(&a->unit, node, co_lx_now_us()) == CO_OK) ? 0 : -1;
}

uint32_t dco408_process(void *app, co_node_t *node, uint32_t now_us)
{
    dco408_app_t *a = (dco408_app_t *)app;

    (void)node;
    return co408_unit_process(&a->unit, now_us);
}
