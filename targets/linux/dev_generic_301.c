/* The application part of generic-301 (see dev_generic_301.h). */
#include "dev_generic_301.h"

#include <string.h>

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

int g301_attach(void *app, co_node_t *node)
{
    g301_app_t *a = (g301_app_t *)app;
    co_od_hook_t dom = {domain_read, domain_write, a};
    co_od_hook_t veto = {NULL, hooked_write, a};

    a->domain_len = 0U;
    a->stage_len = 0U;
    a->restart = true;
    if ((co_od_bind_hook(node, 0x2300U, &dom) != CO_RESULT_OK) ||
        (co_od_bind_hook(node, 0x2200U, &veto) != CO_RESULT_OK)) {
        return -1;
    }
    return 0;
}

uint32_t g301_process(void *app, co_node_t *node, uint32_t now_us)
{
    g301_app_t *a = (g301_app_t *)app;
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

void g301_reset(void *app, co_node_t *node, co_reset_t kind)
{
    g301_app_t *a = (g301_app_t *)app;

    (void)node;
    if (kind == CO_RESET_NODE) {
        a->domain_len = 0U;
        a->stage_len = 0U;
        a->restart = true;
    }
}
