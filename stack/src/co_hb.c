/*
 * Error control: heartbeat producer (0x1017), heartbeat consumer (0x1016),
 * node guarding and life guarding (0x100C, 0x100D).
 */
#include "co/co_endian.h"
#include "co_priv.h"

/* A consumer entry's state, without a byte of its own: hbc_nmt holds
 * HBC_WAITING (bit 7, no NMT state has it) until the first heartbeat (also
 * in an entry not used), then the state the producer reported last;
 * hbc_left is HBC_LOST (no count of units reaches it: hbc_advance) while
 * the producer is lost, else the units to the deadline (0: it has come). */
#define HBC_WAITING 0x80U
#define HBC_LOST    0xFFFFU
enum { GUARD_OFF = 0, GUARD_ARMED, GUARD_LOST };

static uint32_t ms_to_us(uint32_t ms)
{
    return co_dict_us(ms, 1000UL);
}

static void event(co_node_t *node, co_hb_event_t ev, uint8_t id, uint8_t state)
{
    if (CO_CB(node, hb_event) != NULL) {
        node->cb->hb_event(node->cb->ctx, node, ev, id, (co_nmt_state_t)state);
    }
}

/* 0x1016 sub @p k + 1 (co_node.h, CO_RAM_1016; k < n_hb_cons) */
static uint32_t hb_cons(const co_node_t *node, uint32_t k)
{
    return co_ram_u32(node, (uint16_t)(CO_RAM_1016 + (4U * k)));
}

/* An entry in use: a consumer time and a producer (CiA 301: 0 in either
 * switches it off) */
static bool hbc_used(uint32_t v)
{
    return ((v & 0xFFFFU) != 0U) && (((v >> 16U) & 0xFFU) != 0U);
}

/* 0x1017 (0 without the object) */
static uint16_t hb_prod(const co_node_t *node)
{
    return co_ram_u16(node, CO_RAM_1017);
}

/* An event of consumer entry @p k: its producer, the state it reported last. */
static void hb_event(co_node_t *node, co_hb_event_t ev, uint32_t k)
{
    event(node, ev, (uint8_t)((hb_cons(node, k) >> 16U) & 0x7FU),
          node->errctl.hbc_nmt[k]);
}

/* EMCY 0x8130 is active while any monitored producer or the guarding master
 * is lost, and cleared when the last one comes back. */
static void update_error(co_node_t *node)
{
#if CO_NODE_GUARDING
    bool lost = node->errctl.guard_state == (uint8_t)GUARD_LOST;
#else
    bool lost = false;
#endif

    for (uint32_t k = node->n_hb_cons; k > 0U; k--) {
        if (node->errctl.hbc_left[k - 1U] == HBC_LOST) {
            lost = true;
        }
    }
    if (lost) {
        co_emcy_raise(node, CO_EMCY_HB_GUARD, CO_ERREG_COMM, NULL); /* (once) */
    } else {
        co_emcy_clear(node, CO_EMCY_HB_GUARD); /* (nothing when it is not active) */
    }
}

static bool heartbeat_producing(const co_node_t *node)
{
    return hb_prod(node) != 0U;
}

#if CO_NODE_GUARDING
/* CiA 301: with a non-zero heartbeat producer time the node uses the
 * heartbeat protocol, not node guarding (unless the device's option says it
 * answers both). */
static bool guarding_answered(const co_node_t *node)
{
    return !heartbeat_producing(node) ||
           (CO_SET(node, nmt.guarding_with_hb) != 0U);
}

/* Life time in ms: guard time 0x100C x life time factor 0x100D (0: off). */
static uint32_t life_ms(const co_node_t *node)
{
    uint32_t life = 0U;

    if ((node->errctl.guard_time != NULL) && (node->errctl.life_factor != NULL)) {
        life = (uint32_t)*node->errctl.guard_time * *node->errctl.life_factor;
    }
    return life;
}
#endif

/* Life guarding ends when it is switched off (life time 0) or when the node
 * stops answering guarding requests (heartbeat producer time set). CiA 301
 * is silent about a life-guarding error that is pending at that moment; we
 * end it like a recovery: nobody monitors the master any more, and an error
 * that nothing can ever clear would stay in 0x1001 for good. */
static void guard_check(co_node_t *node)
{
#if CO_NODE_GUARDING
    if ((node->errctl.guard_state != (uint8_t)GUARD_OFF) &&
        ((life_ms(node) == 0U) || !guarding_answered(node))) {
        bool was_lost = (node->errctl.guard_state == (uint8_t)GUARD_LOST);
        node->errctl.guard_state = (uint8_t)GUARD_OFF;
        if (was_lost) {
            update_error(node);
            event(node, CO_GUARD_RECOVERED, 0U, node->nmt);
        }
    }
#else
    (void)node; /* never armed without guarding */
#endif
}

/* Entry @p k starts over from its 0x1016 value: a used one (hbc_used)
 * waits for its producer's first heartbeat, with no deadline until then. */
static void consumer_start(co_node_t *node, uint32_t k)
{
    node->errctl.hbc_left[k] = 0U; /* (no deadline: hbc_advance) */
    node->errctl.hbc_nmt[k] = (uint8_t)HBC_WAITING;
    co_rx_invalidate(node);
}

/* Reset communication: everything starts over. The EMCY 0x8130 that a lost
 * producer or master may have left active is not touched here: this runs
 * before the boot-up frame, which must be the first frame after the reset;
 * co_nmt_boot ends that error once the node is in Pre-operational. */
static void hb_reset(co_node_t *node)
{
#if CO_NODE_GUARDING
    node->errctl.guard_toggle = 0U;
    node->errctl.guard_state = (uint8_t)GUARD_OFF; /* (never armed without guarding) */
#endif
    /* The boot-up frame counts as the first heartbeat. */
    node->errctl.hb_last = node->now;
    for (uint32_t k = node->n_hb_cons; k > 0U; k--) {
        consumer_start(node, k - 1U);
    }
}

/* The consumers' deadlines in 16 bits: units of 1024 us (HBC_SHIFT) after
 * a time base (co_errctl_t.hbc_base), rounded up. A consumer time of at
 * most 65,535 ms is at most 64,001 units. Rounded up, a timeout is never
 * detected before the consumer time has passed, and at most 1023 us after
 * it (when co_node_process is called at the deadline it returned): CiA 301
 * gives the consumer time in ms and a master sets it well above its
 * producer time (CAN arbitration and the port's tick, typically 1 ms, add
 * jitter of the same order), so a detection within the next millisecond is
 * what a consumer of ms resolution does anyway. RAM -16 B for 8 consumers
 * (the base +4). */
#define HBC_SHIFT 10U
#define HBC_UNIT  (1UL << HBC_SHIFT)

/* Move the time base to node->now, less than a unit before it: the
 * deadlines' units shrink by the whole units passed (0: the deadline has
 * come; an entry not active has 0). A time before the base (a receive time
 * stamp taken before the last run: co_priv.h, CO_STEP_BACK_MAX) moves
 * nothing. With no deadline ahead the base is simply now (none to keep),
 * so the base is never older than the last heartbeat or run of the service
 * while a deadline is ahead: the service runs by the earliest (at most
 * 65.5 s ahead), and a call 67 s (2^16 units) or more after the base, of
 * a port that called it late, finds every deadline come. */
static void hbc_advance(co_node_t *node)
{
    co_errctl_t *c = &node->errctl;
    uint32_t d = node->now - c->hbc_base;
    uint32_t units = 0U;
    uint32_t any = 0U;

    if (d <= (0xFFFFFFFFUL - CO_STEP_BACK_MAX)) {
        units = d >> HBC_SHIFT; /* (else a time stamp before the base) */
    }
    c->hbc_base += units << HBC_SHIFT;
    for (uint32_t k = node->n_hb_cons; k > 0U; k--) {
        uint32_t left = c->hbc_left[k - 1U];
        if (left != HBC_LOST) {
            if (left > units) {
                left -= units;
            } else {
                left = 0U;
            }
            c->hbc_left[k - 1U] = (uint16_t)left;
            any |= left;
        }
    }
    if (any == 0U) {
        c->hbc_base = node->now;
    }
}

/* A heartbeat (a data frame of at least one byte) of the producer whom
 * entry @p slot monitors. */
static void hb_rx(co_node_t *node, uint32_t slot, const co_frame_t *f)
{
    co_errctl_t *c = &node->errctl;
    uint8_t st = (uint8_t)(f->data[0] & 0x7FU);
    bool waiting = c->hbc_nmt[slot] == (uint8_t)HBC_WAITING;
    bool lost = c->hbc_left[slot] == HBC_LOST;
    bool changed = c->hbc_nmt[slot] != st;
    uint32_t since;
    int32_t end;

    /* the deadline: the consumer time after now, now less than a unit
     * after the base (or before it: a time stamp before the last run) */
    hbc_advance(node);
    since = node->now - c->hbc_base;
    end = (int32_t)since +
          (int32_t)ms_to_us(hb_cons(node, slot) & 0xFFFFU);
    c->hbc_left[slot] =
        (uint16_t)((end > 0) ? (((uint32_t)end + (HBC_UNIT - 1U)) >> HBC_SHIFT) : 0U);
    c->hbc_nmt[slot] = st;
    if (lost) {
        update_error(node);
    }
    if (waiting || lost) {
        /* the first heartbeat, or one after a timeout */
        hb_event(node, waiting ? CO_HB_STARTED : CO_HB_RECOVERED, slot);
    }
    if (changed && !waiting) {
        hb_event(node, CO_HB_STATE, slot);
    }
}

#if CO_NODE_GUARDING
static void guard_rx(co_node_t *node, const co_frame_t *f)
{
    uint32_t life;

    if (!co_frame_is_rtr(f)) {
        return; /* a data frame on our error-control COB-ID is not for us */
    }
    if (!guarding_answered(node)) {
        return;
    }
    /* the reply: toggle bit and NMT state, made as it goes (the toggle
     * changes then; a request while a reply still waits gets that one) */
    co_tx_hold(node, CO_TXH_GUARD, NULL);

    life = life_ms(node);
    if (life != 0U) {
        bool was_lost = (node->errctl.guard_state == (uint8_t)GUARD_LOST);
        node->errctl.guard_state = (uint8_t)GUARD_ARMED;
        node->errctl.guard_deadline = node->now + ms_to_us(life);
        if (was_lost) {
            update_error(node);
            event(node, CO_GUARD_RECOVERED, 0U, node->nmt);
        }
    }
}

#endif

static uint32_t errctl_process(co_node_t *node, uint32_t next)
{
    uint32_t now = node->now;

    if (heartbeat_producing(node)) {
        /* A change of the NMT state sends no heartbeat of its own: CiA 301
         * defines the heartbeat as cyclic (the next one carries the new
         * state); only the boot-up marks a transition. */
        uint32_t period = ms_to_us(hb_prod(node));
        uint32_t due = node->errctl.hb_last + period;
        if (co_time_reached(now, due)) {
            if ((node->bits & CO_NODE_HB_MUTED) == 0U) {
                /* its state when it goes (one that waits still: the next
                 * one replaces it, the cycle keeps its times) */
                co_tx_hold(node, CO_TXH_HB, NULL);
            }
            /* fell behind (or a shorter period): no burst */
            due = co_time_reached(now, due + period) ? now : due;
            node->errctl.hb_last = due;
            due += period;
        }
        next = co_deadline_min(now, next, due);
    }
    hbc_advance(node);
    for (uint32_t k = 0U; k < node->n_hb_cons; k++) {
        co_errctl_t *c = &node->errctl;
        uint32_t left = c->hbc_left[k];
        if ((c->hbc_nmt[k] == (uint8_t)HBC_WAITING) || (left == HBC_LOST)) {
            /* not monitored (yet), or lost */
        } else if (left == 0U) {
            c->hbc_left[k] = (uint16_t)HBC_LOST;
            update_error(node);
            hb_event(node, CO_HB_TIMEOUT, k);
            co_nmt_error(node, CO_ERRBEH_COMM); /* 0x1029: a communication error */
        } else {
            next = co_deadline_min(now, next, c->hbc_base + (left << HBC_SHIFT));
        }
    }
    /* 0x100C/0x100D written since the last call (errctl_written keeps a
     * lost state so that the next request can end it) */
    guard_check(node);
#if CO_NODE_GUARDING
    if (node->errctl.guard_state == (uint8_t)GUARD_ARMED) {
        if (co_time_reached(now, node->errctl.guard_deadline)) {
            node->errctl.guard_state = (uint8_t)GUARD_LOST;
            update_error(node);
            event(node, CO_GUARD_LOST, 0U, node->nmt);
            co_nmt_error(node, CO_ERRBEH_COMM); /* 0x1029: a communication error */
        } else {
            next = co_deadline_min(now, next, node->errctl.guard_deadline);
        }
    }
#endif
    return next;
}

void co_node_hb_mute(co_node_t *node, bool muted, uint32_t now_us)
{
    bool was = (node->bits & CO_NODE_HB_MUTED) != 0U;

    node->bits = (uint8_t)((node->bits & (uint8_t)~CO_NODE_HB_MUTED) |
                           (muted ? CO_NODE_HB_MUTED : 0U));
    if (muted) {
        node->tx_hold &= (uint8_t)~CO_TXH_HB; /* one that waits too */
    }
    if (was && !muted && heartbeat_producing(node)) {
        /* the first heartbeat at once */
        node->errctl.hb_last = now_us - ms_to_us(hb_prod(node));
    }
    co_svc_touch(node, CO_ROW_ERRCTL);
}

/* ------------------------------------------------------------ service */

/* (its objects: 0x1016, 0x1017 at their places in the RAM image, co_node.h's
 * CO_RAM_*; the number of consumers and guarding's objects: co_binds[],
 * co_services.c) */

static void errctl_rx_slots(co_node_t *node)
{
#if CO_NODE_GUARDING
    co_rx_add(node, (uint16_t)(0x700U + node->node_id), CO_ROW_ERRCTL);
#endif
    for (uint32_t k = node->n_hb_cons; k > 0U; k--) {
        uint8_t id = (uint8_t)((hb_cons(node, k - 1U) >> 16U) & 0x7FU);
        if (hbc_used(hb_cons(node, k - 1U)) && (id != node->node_id)) {
            co_rx_add(node, (uint16_t)(0x700U + id), CO_ROW_ERRCTL);
        }
    }
}

static void errctl_event(co_node_t *node, uint8_t ev)
{
    if (ev == CO_SVC_START) {
        hb_reset(node);
    } else if (ev == CO_SVC_SLOTS) {
        errctl_rx_slots(node);
    } else {
        /* nothing to do */
    }
}

/* A frame on 0x700 + a node-ID the node has a slot for: its own (the
 * guarding RTR), or a producer's that entries in use monitor (not its own:
 * errctl_rx_slots); one entry per producer (hb_consumer_check). */
static void errctl_rx(co_node_t *node, uint16_t arg, const co_frame_t *f)
{
    uint8_t id = (uint8_t)(f->id & 0x7FU);

    (void)arg;
#if CO_NODE_GUARDING
    if (id == node->node_id) {
        guard_rx(node, f);
        return;
    }
#endif
    if (co_frame_is_rtr(f) || (f->dlc < 1U)) {
        return; /* no heartbeat */
    }
    for (uint32_t k = 0U; k < node->n_hb_cons; k++) {
        uint32_t v = hb_cons(node, k);
        if (hbc_used(v) && (((v >> 16U) & 0x7FU) == id)) {
            hb_rx(node, k, f);
            return;
        }
    }
}

/* 0x1016: one producer may be monitored by one entry only. */
static co_err_t hb_consumer_check(const co_node_t *node, uint8_t sub, uint32_t v)
{
    uint8_t id = (uint8_t)((v >> 16U) & 0xFFU);

    if ((v & 0xFF000000UL) != 0U) {
        return CO_ERR_VALUE;
    }
    if (((v & 0xFFFFU) == 0U) || (id == 0U)) {
        return CO_OK; /* entry not used */
    }
    if (id > 127U) {
        return CO_ERR_VALUE;
    }
    for (uint32_t k = node->n_hb_cons; k > 0U; k--) { /* (k: the sub-index) */
        uint32_t o = hb_cons(node, k - 1U);
        if ((k != sub) && (((o >> 16U) & 0xFFU) == id) && ((o & 0xFFFFU) != 0U)) {
            return CO_ERR_PARAM_INCOMPAT;
        }
    }
    return CO_OK;
}

co_err_t co_errctl_obj(co_node_t *node, uint8_t op, const co_od_entry_t *e,
                       const co_od_sub_t *s, const uint8_t *data, uint32_t len)
{
    uint8_t sub = s->sub;
    /* (the hook of 0x1016 only, without guarding) */
    bool consumer = ((CO_NODE_GUARDING == 0) || (e->index == 0x1016U)) && (sub > 0U) &&
                    (sub <= node->n_hb_cons);

    (void)len;

    if (op == (uint8_t)CO_SVC_CHECK) {
        if ((e->index < 0x1016U) && (CO_SET(node, nmt.guarding_hb_exclusive) != 0U) &&
            heartbeat_producing(node)) {
            return CO_ERR_RESOURCE; /* guarding refused while the heartbeat runs */
        }
        /* (an entry the service monitors is an UNSIGNED32: 4 bytes) */
        return consumer ? hb_consumer_check(node, sub, co_get_u32(data)) : CO_OK;
    }
    if (consumer) {
        /* only this entry starts over: CiA 301 does not say what a write
         * does to the other entries; restarting them would pause their
         * monitoring and end a pending timeout of a producer that is still
         * silent */
        consumer_start(node, sub - 1U);
        update_error(node);
#if CO_NODE_GUARDING
    } else if (e->index != 0x1016U) {
        /* 0x100C / 0x100D: life guarding is re-armed with the new life time
         * by the next guarding request. A lost state is kept: that request
         * must still end the error (errctl_process ends it if life guarding
         * is now off). */
        if (node->errctl.guard_state == (uint8_t)GUARD_ARMED) {
            node->errctl.guard_state = (uint8_t)GUARD_OFF;
        }
        co_svc_touch(node, CO_ROW_ERRCTL);
#endif
    } else {
        /* 0x1016 sub 0 */
    }
    return CO_OK;
}

/* 0x1017 (CiA 301: the producer's cycle time), checked: the value it
 * replaces says whether the producer runs. Switched on, the cycle starts at
 * the write; written while the producer runs, the cycle goes on: the next
 * heartbeat is due one (new) period after the last one, at once if that
 * has passed. A write does not restart the cycle, or a master writing
 * 0x1017 faster than its period would silence the node. (A write the
 * application's hook then refuses leaves a producer that was off with a
 * cycle start it does not use.) With guarding, once written: life guarding
 * may end (the heartbeat replaces it). */
co_err_t co_hb_prod_obj(co_node_t *node, uint8_t op, const co_od_entry_t *e,
                        const co_od_sub_t *s, const uint8_t *data, uint32_t len)
{
    (void)e;
    (void)s;
    (void)len;
    if (op != (uint8_t)CO_SVC_CHECK) {
        guard_check(node); /* (written: only with guarding, co_svc_hooks) */
    } else if (len == 2U) { /* (an UNSIGNED16 at its place; not one behind a hook) */
        uint16_t ms = co_get_u16(data);
        if (hb_prod(node) == 0U) {
            node->errctl.hb_last = node->now;
        }
        if (ms != 0U) {
            /* the next heartbeat: errctl_process needs to run no sooner */
            co_svc_due(node, node->errctl.hb_last + ms_to_us(ms));
        }
    } else {
        /* not a value the service reads (behind a hook) */
    }
    return CO_OK;
}

const co_service_t co_svc_errctl = {
    errctl_event, errctl_rx, errctl_process,
};
