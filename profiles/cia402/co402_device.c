/*
 * Running a CiA 402 device from its descriptor: node, axes on simulated
 * plants, device plug-in.
 */
#include "co/co402_device.h"

#include <string.h>

co_err_t co402_device_start(co402_device_run_t *r, const co402_device_t *d, void *node_mem,
                            void *ctx, co_hal_t hal, uint8_t node_id,
                            const co_node_callbacks_t *app, uint32_t now_us)
{
    co_node_config_t cfg;
    co_err_t err;

    if ((d->n_axes > CO402_DEVICE_AXES_MAX) || (node_mem == NULL) || (d->config == NULL) ||
        ((d->ctx_size != 0U) && (ctx == NULL))) {
        return CO_ERR_VALUE;
    }
    (void)memset(r, 0, sizeof *r);
    r->desc = d;
    r->ctx = ctx;
    if (ctx != NULL) {
        (void)memset(ctx, 0, d->ctx_size);
    }
    co_profile_host_init(&r->host, r->slots, (uint8_t)(CO402_DEVICE_AXES_MAX + 1U), app);
    for (uint8_t i = 0U; i < d->n_axes; i++) {
        co402_sim_config_t sc;
        co402_config_t ac = d->axis;
        if (d->sim != NULL) {
            d->sim(i, &sc);
        } else {
            co402_sim_defaults(&sc);
        }
        co402_sim_init(&r->sim[i], &sc, now_us);
        ac.axis = i;
        ac.plant = co402_sim_plant(&r->sim[i]);
        co402_init(&r->axis[i], &ac);
        err = co_profile_add(&r->host, &co402_profile_ops, &r->axis[i]);
        if (err != CO_OK) {
            return err;
        }
    }
    if (d->ops != NULL) {
        err = co_profile_add(&r->host, d->ops, r);
        if (err != CO_OK) {
            return err;
        }
    }
    d->config(node_mem, &cfg);
    cfg.hal = hal;
    cfg.node_id = node_id;
    cfg.cb = co_profile_host_callbacks(&r->host);
    r->node = (co_node_t *)node_mem; /* the generated node struct starts with its co_node_t */
    err = co_node_init(r->node, &cfg, now_us);
    if (err != CO_OK) {
        return err;
    }
    return co_profile_host_attach(&r->host, r->node, now_us);
}

uint32_t co402_device_process(co402_device_run_t *r, uint32_t now_us)
{
    /* the plug-ins first: what their tick changed goes out in this call */
    uint32_t b = co_profile_host_process(&r->host, now_us);
    uint32_t a = co_node_process(r->node, now_us);

    if (a == CO_NO_DEADLINE) {
        return b;
    }
    if (b == CO_NO_DEADLINE) {
        return a;
    }
    return (((b - a) & 0x80000000UL) != 0U) ? b : a; /* b before a (wrap-safe) */
}
