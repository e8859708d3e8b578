/* generic-301's device plug-in (see generic_301_desc.h). */
#include "generic_301_desc.h"

#include <string.h>

#include "co/co_device.h"
#include "co/co_endian.h"

static co_err_t domain_read(void *ctx, co_od_io_t *io)
{
    const g301_app_t *a = (const g301_app_t *)ctx;
    uint32_t n = 0U;

    if (io->offset < a->domain_len) {
        n = a->domain_len - io->offset;
        if (n > io->len) {
            n = io->len;
        }
        (void)memcpy(io->buf, &a->domain[io->offset], n);
    }
    io->len = n;
    io->total = a->domain_len;
    io->last = (io->offset + n) >= a->domain_len;
    return CO_OK;
}

static co_err_t domain_write(void *ctx, co_od_io_t *io)
{
    g301_app_t *a = (g301_app_t *)ctx;

    if (io->offset == 0U) {
        a->stage_len = 0U; /* a new transfer */
    }
    if ((io->total > G301_DOMAIN_CAP) || (io->offset > G301_DOMAIN_CAP) ||
        (io->len > (G301_DOMAIN_CAP - io->offset))) {
        return CO_ERR_TYPE_TOO_LONG;
    }
    if (io->offset != a->stage_len) {
        return CO_ERR_GENERAL; /* the server writes in order; anything else is a bug */
    }
    if (io->len > 0U) {
        (void)memcpy(&a->stage[io->offset], io->buf, io->len);
    }
    a->stage_len = io->offset + io->len;
    if (io->last) {
        (void)memcpy(a->domain, a->stage, a->stage_len);
        a->domain_len = a->stage_len;
        a->stage_len = 0U;
    }
    return CO_OK;
}

static co_err_t hooked_write(void *ctx, co_od_io_t *io)
{
    (void)ctx;
    if ((io->len == 4U) && (co_get_u32(io->buf) == G301_VETO_VALUE)) {
        return CO_ERR_VALUE;
    }
    return CO_OK;
}

static co_err_t g301_attach(void *inst, co_node_t *node, uint32_t now_us)
{
    g301_app_t *a = (g301_app_t *)co_device_state((const co_device_run_t *)inst);
    co_od_hook_t dom = {domain_read, domain_write, a};
    co_od_hook_t veto = {NULL, hooked_write, a};

    a->domain_len = 0U;
    a->stage_len = 0U;
    a->restart = true;
    (void)now_us;
    if (co_od_bind_hook(node, 0x2300U, &dom) != CO_RESULT_OK) {
        return CO_ERR_OD_MISSING;
    }
    return (co_od_bind_hook(node, 0x2200U, &veto) == CO_RESULT_OK) ? CO_OK : CO_ERR_OD_MISSING;
}

static uint32_t g301_process(void *inst, uint32_t now_us)
{
    const co_device_run_t *run = (const co_device_run_t *)inst;
    g301_app_t *a = (g301_app_t *)co_device_state(run);
    co_node_t *node = co_device_node(run);
    uint32_t *uptime = (uint32_t *)co_od_value_ptr(node, 0x2024U, 0U);

    if (a->restart) {
        a->restart = false;
        a->t0 = now_us;
        a->next_tick = now_us + 1000000UL;
    }
    if ((int32_t)(now_us - a->next_tick) >= 0) {
        a->next_tick += 1000000UL;
        if (uptime != NULL) {
            *uptime = (now_us - a->t0) / 1000000UL;
        }
    }
    return a->next_tick;
}

static void g301_reset(void *inst, co_reset_t kind, uint32_t now_us)
{
    g301_app_t *a = (g301_app_t *)co_device_state((const co_device_run_t *)inst);

    (void)now_us;
    if (kind == CO_RESET_NODE) {
        a->domain_len = 0U;
        a->stage_len = 0U;
        a->restart = true;
    }
}

static const co_profile_ops_t g301_ops = {
    .name = "generic-301",
    .attach = g301_attach,
    .process = g301_process,
    .reset = g301_reset,
};

const co_device_plugin_t generic_301_plugin = {
    .ops = &g301_ops,
    .state_size = sizeof(g301_app_t),
};
