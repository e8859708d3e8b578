/*
 * Error control: heartbeat producer (0x1017), heartbeat consumer (0x1016),
 * node guarding and life guarding (0x100C, 0x100D).
 */
#include "co_priv.h"

enum { HBC_UNUSED = 0, HBC_WAITING, HBC_ACTIVE, HBC_LOST };
enum { GUARD_OFF = 0, GUARD_ARMED, GUARD_LOST };

static uint32_t ms_to_us(uint32_t ms)
{
    return co_dict_us(ms, 1000UL);
}

static void event(co_node_t *node, co_hb_event_t ev, uint8_t id, uint8_t state)
{
    if (node->cb.hb_event != NULL) {
        node->cb.hb_event(node->cb.ctx, node, ev, id, (co_nmt_state_t)state);
    }
}

/* EMCY 0x8130 is active while any monitored producer or the guarding master
 * is lost, and cleared when the last one comes back. */
static void update_error(co_node_t *node)
{
    bool lost = (node->guard_state == (uint8_t)GUARD_LOST);

    for (uint8_t k = 0U; (k < node->n_hb_cons) && !lost; k++) {
        lost = (node->hbc[k].state == (uint8_t)HBC_LOST);
    }
    if (lost) {
        co_emcy_raise(node, CO_EMCY_HB_GUARD, CO_ERREG_COMM, NULL);
    } else if (co_emcy_is_active(node, CO_EMCY_HB_GUARD)) {
        co_emcy_clear(node, CO_EMCY_HB_GUARD);
    } else {
        /* nothing to change */
    }
}

static bool heartbeat_producing(const co_node_t *node)
{
    return (node->hb_prod != NULL) && (*node->hb_prod != 0U);
}

/* CiA 301: with a non-zero heartbeat producer time the node uses the
 * heartbeat protocol, not node guarding (unless the device's option says it
 * answers both). */
static bool guarding_answered(const co_node_t *node)
{
    return !heartbeat_producing(node) ||
           co_opt(node, CO_OPT_GUARD_WITH_HEARTBEAT);
}

/* Life time in ms: guard time 0x100C x life time factor 0x100D (0: off). */
static uint32_t life_ms(const co_node_t *node)
{
    uint32_t life = 0U;

    if ((node->guard_time != NULL) && (node->life_factor != NULL)) {
        life = (uint32_t)*node->guard_time * *node->life_factor;
    }
    return life;
}

/* Life guarding ends when it is switched off (life time 0) or when the node
 * stops answering guarding requests (heartbeat producer time set). CiA 301
 * is silent about a life-guarding error that is pending at that moment; we
 * end it like a recovery: nobody monitors the master any more, and an error
 * that nothing can ever clear would stay in 0x1001 for good. */
static void guard_check(co_node_t *node)
{
    if ((node->guard_state != (uint8_t)GUARD_OFF) &&
        ((life_ms(node) == 0U) || !guarding_answered(node))) {
        bool was_lost = (node->guard_state == (uint8_t)GUARD_LOST);
        node->guard_state = (uint8_t)GUARD_OFF;
        if (was_lost) {
            update_error(node);
            event(node, CO_GUARD_RECOVERED, 0U, node->nmt);
        }
    }
}

void co_hb_producer_changed(co_node_t *node)
{
    if (heartbeat_producing(node)) {
        node->hb_deadline = node->now + ms_to_us(*node->hb_prod);
    }
    guard_check(node);
}

/* Entries in state HBC_UNUSED are (re)configured from 0x1016: a used one
 * waits for its producer's first heartbeat. The others keep monitoring. */
static void consumers_restart(co_node_t *node)
{
    for (uint8_t k = 0U; k < node->n_hb_cons; k++) {
        uint32_t v = node->hb_cons[k];
        bool used = ((v & 0xFFFFU) != 0U) && (((v >> 16U) & 0xFFU) != 0U);
        if (node->hbc[k].state == (uint8_t)HBC_UNUSED) {
            node->hbc[k].state = used ? (uint8_t)HBC_WAITING : (uint8_t)HBC_UNUSED;
            node->hbc[k].nmt = (uint8_t)CO_NMT_INITIALISING;
        }
    }
    co_rx_rebuild(node);
}

/* After a write of 0x1016 sub k, co_comm_written has set hbc[k-1].state to
 * HBC_UNUSED: only that entry starts over. CiA 301 does not say what a write
 * does to the other entries; restarting them would pause their monitoring
 * and end a pending timeout of a producer that is still silent. */
void co_hb_consumers_changed(co_node_t *node)
{
    consumers_restart(node);
    update_error(node);
}

/* Reset communication: everything starts over. The EMCY 0x8130 that a lost
 * producer or master may have left active is not touched here: this runs
 * before the boot-up frame, which must be the first frame after the reset;
 * co_nmt_boot ends that error once the node is in Pre-operational. */
void co_hb_reset(co_node_t *node)
{
    node->guard_toggle = 0U;
    node->guard_state = (uint8_t)GUARD_OFF;
    /* The boot-up frame counts as the first heartbeat. */
    if (heartbeat_producing(node)) {
        node->hb_deadline = node->now + ms_to_us(*node->hb_prod);
    }
    for (uint8_t k = 0U; k < node->n_hb_cons; k++) {
        node->hbc[k].state = (uint8_t)HBC_UNUSED;
    }
    consumers_restart(node);
}

void co_hb_rx(co_node_t *node, uint8_t slot, const co_frame_t *f)
{
    co_hb_consumer_t *c = &node->hbc[slot];
    uint8_t st;
    uint8_t id;
    uint8_t prev;

    if (co_frame_is_rtr(f) || (f->dlc < 1U) || (slot >= node->n_hb_cons) ||
        (c->state == (uint8_t)HBC_UNUSED)) {
        return;
    }
    st = (uint8_t)(f->data[0] & 0x7FU);
    id = (uint8_t)((node->hb_cons[slot] >> 16U) & 0x7FU);
    prev = c->state;
    c->deadline = node->now + ms_to_us(node->hb_cons[slot] & 0xFFFFU);
    c->state = (uint8_t)HBC_ACTIVE;
    if (prev == (uint8_t)HBC_WAITING) {
        event(node, CO_HB_STARTED, id, st);
    } else if (prev == (uint8_t)HBC_LOST) {
        update_error(node);
        event(node, CO_HB_RECOVERED, id, st);
    } else {
        /* still alive */
    }
    if (c->nmt != st) {
        c->nmt = st;
        if (prev != (uint8_t)HBC_WAITING) {
            event(node, CO_HB_STATE, id, st);
        }
    }
}

void co_guard_rx(co_node_t *node, const co_frame_t *f)
{
    uint8_t reply;
    uint32_t life;

    if (!co_frame_is_rtr(f)) {
        return; /* a data frame on our error-control COB-ID is not for us */
    }
    if (!guarding_answered(node)) {
        return;
    }
    reply = (uint8_t)(node->guard_toggle | node->nmt);
    node->guard_toggle ^= 0x80U;
    co_tx(node, 0x700UL + node->node_id, &reply, 1U);

    life = life_ms(node);
    if (life != 0U) {
        bool was_lost = (node->guard_state == (uint8_t)GUARD_LOST);
        node->guard_state = (uint8_t)GUARD_ARMED;
        node->guard_deadline = node->now + ms_to_us(life);
        if (was_lost) {
            update_error(node);
            event(node, CO_GUARD_RECOVERED, 0U, node->nmt);
        }
    }
}

uint32_t co_hb_process(co_node_t *node, uint32_t next)
{
    uint32_t now = node->now;

    if (heartbeat_producing(node)) {
        if (co_time_reached(now, node->hb_deadline)) {
            uint8_t st = node->nmt;
            uint32_t period = ms_to_us(*node->hb_prod);
            co_tx(node, 0x700UL + node->node_id, &st, 1U);
            node->hb_deadline += period;
            if (co_time_reached(now, node->hb_deadline)) {
                node->hb_deadline = now + period; /* fell behind: no burst */
            }
        }
        next = co_deadline_min(now, next, node->hb_deadline);
    }
    for (uint8_t k = 0U; k < node->n_hb_cons; k++) {
        co_hb_consumer_t *c = &node->hbc[k];
        if (c->state == (uint8_t)HBC_ACTIVE) {
            if (co_time_reached(now, c->deadline)) {
                c->state = (uint8_t)HBC_LOST;
                update_error(node);
                event(node, CO_HB_TIMEOUT, (uint8_t)((node->hb_cons[k] >> 16U) & 0x7FU), c->nmt);
                co_nmt_error(node, CO_ERRBEH_COMM); /* 0x1029: a communication error */
            } else {
                next = co_deadline_min(now, next, c->deadline);
            }
        }
    }
    /* 0x100C/0x100D written since the last call (co_comm_written keeps a
     * lost state so that the next request can end it) */
    guard_check(node);
    if (node->guard_state == (uint8_t)GUARD_ARMED) {
        if (co_time_reached(now, node->guard_deadline)) {
            node->guard_state = (uint8_t)GUARD_LOST;
            update_error(node);
            event(node, CO_GUARD_LOST, 0U, node->nmt);
            co_nmt_error(node, CO_ERRBEH_COMM); /* 0x1029: a communication error */
        } else {
            next = co_deadline_min(now, next, node->guard_deadline);
        }
    }
    return next;
}
