/*
 * The plug-in host: fans the node's callbacks out to the instances and
 * collects their deadlines.
 */
#include "co/co_profile.h"

#include <stdbool.h>
#include <stddef.h>
#include <string.h>

/* The time of the event being dispatched. The node's callbacks carry no
 * time; the core stamps every received frame and process call into
 * its time (co_node_now) before it dispatches, so that is the time of the SYNC or NMT
 * command at hand. (Only read, never written.) */
static uint32_t event_time(const co_node_t *node)
{
    return co_node_now(node);
}

void co_profile_host_init(co_profile_host_t *h, co_profile_t *slots, uint8_t cap,
                          const co_node_callbacks_t *app)
{
    (void)memset(h, 0, sizeof *h);
    h->slots = slots;
    h->cap = cap;
    if (app != NULL) {
        h->app = *app;
    }
}

co_err_t co_profile_add(co_profile_host_t *h, const co_profile_ops_t *ops, void *inst)
{
    if ((ops == NULL) || (ops->attach == NULL)) {
        return CO_ERR_VALUE;
    }
    if (h->n >= h->cap) {
        return CO_ERR_NO_MEMORY;
    }
    h->slots[h->n].ops = ops;
    h->slots[h->n].inst = inst;
    h->n++;
    return CO_OK;
}

static void cb_nmt_state(void *ctx, co_node_t *node, co_nmt_state_t state)
{
    co_profile_host_t *h = (co_profile_host_t *)ctx;

    if (h->node == node) {
        for (uint8_t i = 0U; i < h->n; i++) {
            if (h->slots[i].ops->nmt_state != NULL) {
                h->slots[i].ops->nmt_state(h->slots[i].inst, state, event_time(node));
            }
        }
    }
    if (h->app.nmt_state != NULL) {
        h->app.nmt_state(h->app.ctx, node, state);
    }
}

static void cb_nmt_reset(void *ctx, co_node_t *node, co_reset_t kind)
{
    co_profile_host_t *h = (co_profile_host_t *)ctx;

    if (h->node == node) {
        for (uint8_t i = 0U; i < h->n; i++) {
            if (h->slots[i].ops->reset != NULL) {
                h->slots[i].ops->reset(h->slots[i].inst, kind, event_time(node));
            }
        }
    }
    if (h->app.nmt_reset != NULL) {
        h->app.nmt_reset(h->app.ctx, node, kind);
    }
}

static void cb_hb_event(void *ctx, co_node_t *node, co_hb_event_t ev, uint8_t id,
                        co_nmt_state_t state)
{
    co_profile_host_t *h = (co_profile_host_t *)ctx;

    if (h->node == node) {
        for (uint8_t i = 0U; i < h->n; i++) {
            if (h->slots[i].ops->error_control != NULL) {
                h->slots[i].ops->error_control(h->slots[i].inst, ev, id, event_time(node));
            }
        }
    }
    if (h->app.hb_event != NULL) {
        h->app.hb_event(h->app.ctx, node, ev, id, state);
    }
}

static void cb_sync(void *ctx, co_node_t *node, uint8_t counter)
{
    co_profile_host_t *h = (co_profile_host_t *)ctx;

    if (h->node == node) {
        for (uint8_t i = 0U; i < h->n; i++) {
            if (h->slots[i].ops->sync != NULL) {
                h->slots[i].ops->sync(h->slots[i].inst, counter, event_time(node));
            }
        }
    }
    if (h->app.sync != NULL) {
        h->app.sync(h->app.ctx, node, counter);
    }
}

static void cb_emcy_mfr(void *ctx, co_node_t *node, uint16_t code, uint8_t mfr[5])
{
    co_profile_host_t *h = (co_profile_host_t *)ctx;

    if (h->node == node) {
        for (uint8_t i = 0U; i < h->n; i++) {
            if (h->slots[i].ops->emcy_mfr != NULL) {
                h->slots[i].ops->emcy_mfr(h->slots[i].inst, code, mfr);
            }
        }
    }
    if (h->app.emcy_mfr != NULL) {
        h->app.emcy_mfr(h->app.ctx, node, code, mfr);
    }
}

static void cb_rpdo(void *ctx, co_node_t *node, uint16_t n)
{
    co_profile_host_t *h = (co_profile_host_t *)ctx;

    if (h->node == node) {
        for (uint8_t i = 0U; i < h->n; i++) {
            if (h->slots[i].ops->rpdo != NULL) {
                h->slots[i].ops->rpdo(h->slots[i].inst, n, event_time(node));
            }
        }
    }
    if (h->app.rpdo != NULL) {
        h->app.rpdo(h->app.ctx, node, n);
    }
}

static bool cb_tpdo_event(void *ctx, co_node_t *node, uint16_t n, const uint8_t last[8],
                          const uint8_t now[8])
{
    co_profile_host_t *h = (co_profile_host_t *)ctx;
    uint8_t changed[8];
    uint8_t any = 0U;

    for (uint8_t b = 0U; b < 8U; b++) {
        changed[b] = (uint8_t)(last[b] ^ now[b]);
    }
    if (h->node == node) {
        for (uint8_t i = 0U; i < h->n; i++) {
            if (h->slots[i].ops->tpdo_event != NULL) {
                h->slots[i].ops->tpdo_event(h->slots[i].inst, n, last, now, changed);
            }
        }
    }
    for (uint8_t b = 0U; b < 8U; b++) {
        any |= changed[b];
    }
    if ((any != 0U) && (h->app.tpdo_event != NULL)) {
        return h->app.tpdo_event(h->app.ctx, node, n, last, now);
    }
    return any != 0U;
}

static void cb_nmt_command(void *ctx, co_node_t *node, uint8_t cs)
{
    co_profile_host_t *h = (co_profile_host_t *)ctx;

    if (h->node == node) {
        for (uint8_t i = 0U; i < h->n; i++) {
            if (h->slots[i].ops->nmt_command != NULL) {
                h->slots[i].ops->nmt_command(h->slots[i].inst, cs, event_time(node));
            }
        }
    }
    if (h->app.nmt_command != NULL) {
        h->app.nmt_command(h->app.ctx, node, cs);
    }
}

static void cb_error_class(void *ctx, co_node_t *node, uint8_t sub)
{
    co_profile_host_t *h = (co_profile_host_t *)ctx;

    if (h->node == node) {
        for (uint8_t i = 0U; i < h->n; i++) {
            if (h->slots[i].ops->error_class != NULL) {
                h->slots[i].ops->error_class(h->slots[i].inst, sub, event_time(node));
            }
        }
    }
    if (h->app.error_class != NULL) {
        h->app.error_class(h->app.ctx, node, sub);
    }
}

static void cb_time(void *ctx, co_node_t *node, uint32_t ms, uint16_t days)
{
    const co_profile_host_t *h = (const co_profile_host_t *)ctx;

    if (h->app.time != NULL) {
        h->app.time(h->app.ctx, node, ms, days);
    }
}

const co_node_callbacks_t *co_profile_host_callbacks(co_profile_host_t *h)
{
    co_node_callbacks_t *cb = &h->node_cb;

    (void)memset(cb, 0, sizeof *cb);
    cb->ctx = h;
    cb->nmt_state = cb_nmt_state;
    cb->nmt_reset = cb_nmt_reset;
    cb->hb_event = cb_hb_event;
    cb->sync = cb_sync;
    cb->time = cb_time;
    cb->emcy_mfr = cb_emcy_mfr;
    cb->rpdo = cb_rpdo;
    cb->tpdo_event = cb_tpdo_event;
    cb->nmt_command = cb_nmt_command;
    cb->error_class = cb_error_class;
    return cb;
}

co_err_t co_profile_host_attach(co_profile_host_t *h, co_node_t *node, uint32_t now_us)
{
    for (uint8_t i = 0U; i < h->n; i++) {
        co_err_t err = h->slots[i].ops->attach(h->slots[i].inst, node, now_us);
        if (err != CO_OK) {
            return err;
        }
    }
    h->node = node;
    return CO_OK;
}

uint32_t co_profile_host_process(co_profile_host_t *h, uint32_t now_us)
{
    uint32_t next = CO_NO_DEADLINE;

    if (h->node == NULL) {
        return next;
    }
    for (uint8_t i = 0U; i < h->n; i++) {
        if (h->slots[i].ops->process != NULL) {
            uint32_t d = h->slots[i].ops->process(h->slots[i].inst, now_us);
            if ((d != CO_NO_DEADLINE) &&
                ((next == CO_NO_DEADLINE) || ((int32_t)(d - now_us) < (int32_t)(next - now_us)))) {
                next = d;
            }
        }
    }
    return next;
}
