/*
 * Transmit PDOs: sampling the mapped objects through the dictionary's read
 * path, the transmission types (synchronous cyclic/acyclic, RTR only,
 * event-driven with change detection, inhibit time and event timer), and the
 * SYNC start value and window.
 *
 * A TPDO never waits as a frame (co_priv.h, the TX path): when the HAL does not
 * take it, the TPDO stays due and is sampled again (event-driven) or retried
 * while the synchronous window is open (synchronous), so what goes out is
 * never older than necessary.
 */
#include "co_priv.h"

#define RETRY_US 1000UL /* TX path full: try again this much later */

/* Sample the mapped objects into @p out (8 bytes, zero-padded). */
CO_HOT void build(co_node_t *node, uint16_t i, uint8_t *out)
{
#if CO_FAST
    if ((co_pdo_st(node)[i].flags & CO_PDO_F_DIRECT) != 0U) {
        co_pdo_sample_direct(node, i, out);
        return;
    }
#endif
    co_pdo_sample(node, i, out);
}

/* Send @p data (8 bytes, zero beyond the mapping) now, or not at all. An
 * event-driven TPDO (254/255, @p event) restarts its inhibit time and event
 * timer. */
CO_HOT bool send(co_node_t *node, uint16_t i, const uint8_t *data, bool event)
{
    co_pdo_t *p = &co_pdo_st(node)[i];
    co_frame_t f;

    f.id = co_pdo_cob(node, i) & 0x7FFUL;
    f.dlc = p->len;
    (void)memcpy(f.data, data, 8U);
    if (!co_tx_now(node, &f)) {
        return false;
    }
    if (CO_TPDO_CHANGE) {
        /* what was sent, for change detection (from the frame: data may be
         * p->data) */
        (void)memcpy(p->data, f.data, 8U);
    }
    p->flags |= CO_PDO_F_SENT;
    if (event) {
        /* the event timer and the inhibit time start now (times of 0 end at
         * once: event_timers) */
        p->at = node->now;
        p->flags = (uint16_t)((p->flags & ~(uint32_t)CO_PDO_F_EVENT) | CO_PDO_F_INHIBIT |
                              CO_PDO_F_TIMER);
    }
    return true;
}

/* Synchronous send: sampled now (replacing data of an earlier SYNC still
 * waiting), sent now or, if the TX path is full, while the synchronous
 * window stays open. A build for speed samples straight
 * into the frame; a build for size sends through send(). */
static void send_sync(co_node_t *node, uint16_t i)
{
    co_pdo_t *p = &co_pdo_st(node)[i];
    bool sent;
#if CO_FAST
    co_frame_t f;

    build(node, i, f.data);
    f.id = co_pdo_cob(node, i) & 0x7FFUL;
    f.dlc = p->len;
    (void)memcpy(p->data, f.data, 8U);
    p->flags &= (uint16_t)~(CO_PDO_F_EVENT | CO_PDO_F_SYNC_PEND);
    sent = co_tx_now(node, &f);
    if (sent) {
        p->flags |= CO_PDO_F_SENT;
    }
#else
    build(node, i, p->data);
    p->flags &= (uint16_t)~(CO_PDO_F_EVENT | CO_PDO_F_SYNC_PEND);
    sent = send(node, i, p->data, false);
#endif
    if (!sent) {
        p->flags |= CO_PDO_F_SYNC_PEND;
        co_svc_touch(node, CO_ROW_PDO); /* retried while the window is open */
    }
}

/* Cyclic synchronous (1-240): due every n-th SYNC, the first time at the
 * SYNC whose counter equals the start value when the SYNC has a counter. */
static bool cyclic_due(co_node_t *node, uint16_t i, uint8_t type, uint8_t counter)
{
    co_pdo_t *p = &co_pdo_st(node)[i];
    const co_pdo_desc_t *d = &node->dev->pdo[i];
    uint8_t start = (d->start != 0U) ? *co_pdo_at(node, i, d->start) : 0U;

    if ((start != 0U) && ((p->flags & CO_PDO_F_STARTED) == 0U) &&
        (co_ram_u8(node, CO_RAM_1019) > 1U)) {
        /* the first transmission waits for the SYNC counter */
        if (counter != start) {
            return false;
        }
        p->flags |= CO_PDO_F_STARTED;
    } else {
        p->count++;
        if (p->count < type) {
            return false;
        }
    }
    p->count = 0U;
    return true;
}

#if CO_TPDO_CHANGE
/* The sampled data differ from the last sent (a loop: the C library's
 * memcmp costs more flash). */
static bool changed(const uint8_t *now, const uint8_t *sent)
{
    uint8_t d = 0U;

    for (uint8_t k = 0U; k < 8U; k++) {
        d |= (uint8_t)(now[k] ^ sent[k]);
    }
    return d != 0U;
}

/* Acyclic (0): due at the SYNC after a change of the data or a request. */
static bool acyclic_due(co_node_t *node, uint16_t i)
{
    const co_pdo_t *p = &co_pdo_st(node)[i];
    uint8_t now[8];

    build(node, i, now);
    return ((p->flags & (CO_PDO_F_EVENT | CO_PDO_F_SENT)) != CO_PDO_F_SENT) ||
           changed(now, p->data);
}
#else
/* Acyclic (0) without change detection: due at the SYNC after a request,
 * and at the first SYNC in Operational (nothing sent yet). */
static bool acyclic_due(co_node_t *node, uint16_t i)
{
    return (co_pdo_st(node)[i].flags & (CO_PDO_F_EVENT | CO_PDO_F_SENT)) != CO_PDO_F_SENT;
}
#endif

#if CO_PDO_RTR
/* Answer a remote request: type 252 with the data sampled at the last SYNC,
 * every other type with the data of now. */
static bool answer_rtr(co_node_t *node, uint16_t i)
{
    co_pdo_t *p = &co_pdo_st(node)[i];
    uint8_t type = co_pdo_type(node, i);
    uint8_t now[8];

    if ((type == 252U) && ((p->flags & CO_PDO_F_SAMPLED) != 0U)) {
        return send(node, i, p->data, false);
    }
    build(node, i, now);
    return send(node, i, now, type >= 254U);
}

/* A remote request on the COB-ID of TPDO i, which the node's dispatch found
 * valid and answering RTRs (co_pdo_rx_cob). */
void co_tpdo_rtr(co_node_t *node, uint16_t i)
{
    if ((node->nmt != (uint8_t)CO_NMT_OPERATIONAL) ||
        (co_pdo_st(node)[i].len == 0U)) {
        return;
    }
    /* answered at once; only when the TX path is full does co_tpdo_process retry */
    if (!answer_rtr(node, i)) {
        co_pdo_st(node)[i].flags |= CO_PDO_F_RTR;
    }
    co_svc_touch(node, CO_ROW_PDO); /* the retry, or the timers an answer restarts */
}
#endif

/* The event timer and the inhibit time of event-driven TPDO @p p (@p ev,
 * @p inh us, both running from p->at; an event timer of 0 is off, an
 * inhibit time of 0 ends at once), at now: its flags with them (the caller
 * stores them, after its own changes: one store). */
CO_INLINE uint32_t event_timers(const co_node_t *node, const co_pdo_t *p, uint32_t ev,
                                uint32_t inh)
{
    uint32_t f = p->flags;

    if (((f & CO_PDO_F_TIMER) != 0U) && (ev != 0U) && co_time_reached(node->now, p->at + ev)) {
        f |= CO_PDO_F_EVENT;
    }
    /* (the time since the transmission, not the end as a point in time: the
     * end of an inhibit time of 0 would otherwise look in the future again
     * 2^31 us later) */
    if (((f & CO_PDO_F_INHIBIT) != 0U) && ((node->now - p->at) >= inh)) {
        f &= ~(uint32_t)CO_PDO_F_INHIBIT;
    }
    return f;
}

/* The event timer (@p ev us) as a deadline while it runs. Once expired it
 * has set CO_PDO_F_EVENT, whose own deadline (inhibit time, TX retry)
 * counts: an expired timer is never a deadline (it would be one in the
 * past, and the caller's loop would spin until the TPDO can go). A running
 * inhibit time (@p inh us) is one too, also with no event waiting: it ends
 * when it ends, not when the next event looks at it (by then, 2^31 us
 * later, its end would look like a time ahead). */
CO_INLINE uint32_t timer_next(const co_node_t *node, const co_pdo_t *p, uint32_t ev,
                              uint32_t inh, uint32_t next_in)
{
    uint32_t next = next_in;
    uint32_t end = p->at + ev;

    if (((p->flags & CO_PDO_F_INHIBIT) != 0U) && (inh != 0U)) {
        next = co_deadline_min(node->now, next, p->at + inh);
    }
    if (((p->flags & CO_PDO_F_TIMER) != 0U) && (ev != 0U) && !co_time_reached(node->now, end)) {
        return co_deadline_min(node->now, next, end);
    }
    return next;
}

#if CO_TPDO_CHANGE
/* A due event-driven TPDO (CO_PDO_F_EVENT): sent with @p now unless the
 * inhibit time holds it back (its end is a deadline: timer_next); true when
 * the TX path did not take it. */
CO_INLINE bool event_due(co_node_t *node, uint16_t i, const uint8_t *now)
{
    const co_pdo_t *p = &co_pdo_st(node)[i];

    return ((p->flags & CO_PDO_F_INHIBIT) == 0U) && !send(node, i, now, true);
}

/* set.tpdo.change_mask: does the change from the data last sent to
 * @p now touch a bit of TPDO i's change mask (co_dev_t.tpdo_mask)? True
 * when no mask applies to its transmission type. */
static CO_NOINLINE bool masked_change(const co_node_t *node, uint16_t i, const uint8_t *now)
{
    const co_pdo_t *p = &co_pdo_st(node)[i];
    uint32_t type = (co_pdo_type(node, i) == 254U) ? CO_TPDO_MASK_254 : CO_TPDO_MASK_255;
    uint16_t off;
    uint32_t mask = 0U;

    if (((CO_SET(node, tpdo.change_mask) & type) == 0U) || (node->dev->tpdo_mask == NULL)) {
        return true;
    }
    off = node->dev->tpdo_mask[i - node->dev->n_rpdo];
    for (uint8_t b = 0U; b < 8U; b++) {
        if ((b & 3U) == 0U) {
            mask = co_ram_u32(node, (uint16_t)(off + b)); /* sub 1: bytes 0..3, sub 2: 4..7 */
        }
        uint8_t bits = (uint8_t)(mask >> (8U * (b & 3U)));
        if (((uint8_t)(now[b] ^ p->data[b]) & bits) != 0U) {
            return true;
        }
    }
    return false;
}

/* Event-driven (254/255), with change detection (@p detect): a change of
 * the data (with set.tpdo.change_mask, of the bits of its change mask;
 * looked at only when the data changed), a request, or the event timer, no
 * sooner than the inhibit time allows. Without (CO_TPDO_CHANGE_IGNORED): a
 * request or the event timer (which runs from the start of Operational,
 * when nothing has been sent), sampled when it goes out. Returns the next
 * deadline; @p held set when the TX path did not take it. */
CO_HOT uint32_t event_driven(co_node_t *node, uint16_t i, uint32_t next_in, bool detect,
                             bool *held)
{
    uint32_t next = next_in;
    co_pdo_t *p = &co_pdo_st(node)[i];
    uint32_t ev = co_pdo_event_us(node, i);
    uint32_t inh = co_pdo_inhibit_us(node, i);
    uint8_t now[8];

    p->flags = (uint16_t)event_timers(node, p, ev, inh);
    if (!detect && ((p->flags & CO_PDO_F_TIMER) == 0U) && (ev != 0U)) {
        /* (an inhibit time runs only after a transmission, which starts the
         * timer too) */
        p->at = node->now;
        p->flags |= CO_PDO_F_TIMER;
    }
    if ((detect || ((p->flags & CO_PDO_F_EVENT) != 0U)) &&
        ((p->flags & (CO_PDO_F_EVENT | CO_PDO_F_INHIBIT)) !=
         (CO_PDO_F_EVENT | CO_PDO_F_INHIBIT))) {
        /* sampled unless already due and waiting for the inhibit time anyway */
        build(node, i, now);
        if (detect &&
            (((p->flags & CO_PDO_F_SENT) == 0U) ||
             (changed(now, p->data) &&
              ((CO_SET(node, tpdo.change_mask) == 0U) || masked_change(node, i, now)) &&
              ((CO_CB(node, tpdo_event) == NULL) ||
               node->cb->tpdo_event(node->cb->ctx, node, (uint16_t)(i - node->dev->n_rpdo),
                                   p->data, now))))) {
            p->flags |= CO_PDO_F_EVENT;
        }
    }
    if (((p->flags & CO_PDO_F_EVENT) != 0U) && event_due(node, i, now)) {
        *held = true;
    }
    return timer_next(node, p, ev, inh, next);
}
#else
/* Event-driven (254/255) without change detection (CO_TPDO_CHANGE=0): once
 * on entering Operational (nothing sent yet), then on a request or at the
 * event timer, no sooner than the inhibit time allows; sampled when it goes
 * out (@p detect: unused). Returns the next deadline; @p held set when the
 * TX path did not take it. */
CO_HOT uint32_t event_driven(co_node_t *node, uint16_t i, uint32_t next, bool detect,
                             bool *held)
{
    co_pdo_t *p = &co_pdo_st(node)[i];
    uint32_t ev = co_pdo_event_us(node, i);
    uint32_t inh = co_pdo_inhibit_us(node, i);
    uint32_t f;
    uint8_t now[8];

    (void)detect;
    f = event_timers(node, p, ev, inh);
    if ((f & CO_PDO_F_SENT) == 0U) {
        f |= CO_PDO_F_EVENT;
    }
    p->flags = (uint16_t)f;
    if ((f & (CO_PDO_F_EVENT | CO_PDO_F_INHIBIT)) == CO_PDO_F_EVENT) {
        build(node, i, now);
        if (!send(node, i, now, true)) {
            *held = true;
        }
    }
    return timer_next(node, p, ev, inh, next);
}
#endif

/* At a SYNC: the synchronous TPDOs (RTR-only 253 and event-driven types
 * do not follow SYNC). */
CO_HOT void at_sync(co_node_t *node, uint16_t i, uint8_t type, uint8_t counter)
{
    co_pdo_t *p = &co_pdo_st(node)[i];

    if ((type > 240U) && (!CO_PDO_RTR || (type != 252U))) {
        return;
    }
    if (CO_PDO_RTR && (type == 252U)) {
        build(node, i, p->data); /* sampled now, sent on request */
        p->flags |= CO_PDO_F_SAMPLED;
    } else if ((type == 0U) ? acyclic_due(node, i) : cyclic_due(node, i, type, counter)) {
        send_sync(node, i);
    } else {
        /* not this SYNC: data still waiting is not sent in its window */
        p->flags &= (uint16_t)~CO_PDO_F_SYNC_PEND;
    }
}

/* At co_node_process: RTR answers and synchronous transmissions held back,
 * event-driven TPDOs with (@p detect) or without change detection
 * (CO_TPDO_CHANGE_IGNORED). Returns the next deadline. */
CO_HOT uint32_t at_process(co_node_t *node, uint16_t i, uint8_t type, uint32_t next_in, bool detect)
{
    uint32_t next = next_in;
    co_pdo_t *p = &co_pdo_st(node)[i];
    bool held = false; /* the TX path took not all: retried RETRY_US later */

#if CO_PDO_RTR
    if ((p->flags & CO_PDO_F_RTR) != 0U) {
        if (answer_rtr(node, i)) {
            p->flags &= (uint16_t)~CO_PDO_F_RTR;
        } else {
            held = true;
        }
    }
#endif
    if ((p->flags & CO_PDO_F_SYNC_PEND) != 0U) {
        /* CiA 301: synchronous PDOs outside the window are not sent */
        if (!co_sync_window(node) || send(node, i, p->data, false)) {
            p->flags &= (uint16_t)~CO_PDO_F_SYNC_PEND;
        } else {
            held = true;
        }
    } else if (type >= 254U) {
        /* (a synchronous TPDO's data waiting: not event-driven; a new type
         * restarts the TPDO, which drops it) */
#if CO_TPDO_CHANGE
        /* change detection compares the data at every co_node_process */
        node->pdo_poll = detect ? 1U : node->pdo_poll;
#endif
        next = event_driven(node, i, next, detect, &held);
    } else {
        /* synchronous (0..240), nothing waiting: the SYNC decides */
    }
    return held ? co_deadline_min(node->now, next, node->now + RETRY_US) : next;
}

/* The deadline of RPDO i (armed at a reception in Operational: every NMT
 * state change disarms it; an event timer of 0 is none). */
CO_HOT uint32_t rpdo_deadline(co_node_t *node, uint16_t i, uint32_t next)
{
    const co_pdo_t *p = &co_pdo_st(node)[i];
    uint32_t ev = ((p->flags & CO_PDO_F_TIMER) != 0U) ? co_pdo_event_us(node, i) : 0U;
    uint32_t end = p->at + ev;

    if (ev == 0U) {
        return next; /* not received yet, or no deadline monitoring */
    }
    if (co_time_reached(node->now, end)) {
        /* missed: monitoring stops until the next reception (the timer
         * flag cleared with the error state set), EMCY */
        co_rpdo_error(node, i, CO_PDO_F_TIMEOUT | CO_PDO_F_TIMER, CO_PDO_F_TIMEOUT);
        return next;
    }
    return co_deadline_min(node->now, next, end);
}

/* One pass over the usable TPDOs in Operational: at a SYNC (@p sync, the
 * SYNC's @p counter) or at co_node_process (the timers and events, and the
 * RPDOs' deadlines; returns the next deadline). */
CO_HOT uint32_t tpdo_pass(co_node_t *node, uint32_t next_in, bool sync, uint8_t counter)
{
    uint32_t next = next_in;
    uint32_t n = (uint32_t)node->dev->n_rpdo + node->dev->n_tpdo;
    bool detect = CO_SET(node, tpdo.change_detection) != CO_TPDO_CHANGE_IGNORED;

#if CO_TPDO_CHANGE
    if (!sync) {
        node->pdo_poll = 0U;
    }
#endif
    if (node->nmt != (uint8_t)CO_NMT_OPERATIONAL) {
        return next;
    }
    for (uint32_t k = sync ? node->dev->n_rpdo : 0U; k < n; k++) {
        uint16_t i = (uint16_t)k;
        uint8_t type = co_pdo_type(node, i);
        if (!sync && (k < node->dev->n_rpdo)) {
            next = rpdo_deadline(node, i, next);
            continue;
        }
        if (!co_pdo_usable(node, i)) {
            continue;
        }
        if (sync) {
            at_sync(node, i, type, counter);
        } else {
            next = at_process(node, i, type, next, detect);
        }
    }
    return next;
}

void co_tpdo_sync(co_node_t *node, uint8_t counter)
{
    (void)tpdo_pass(node, CO_NO_DEADLINE, true, counter);
}

uint32_t co_tpdo_process(co_node_t *node, uint32_t next)
{
    return tpdo_pass(node, next, false, 0U);
}

co_err_t co_tpdo_request(co_node_t *node, uint16_t n)
{
    uint16_t i = (uint16_t)(node->dev->n_rpdo + n);

    if (n >= node->dev->n_tpdo) { /* (no PDOs: no descriptors either) */
        return CO_ERR_NO_OBJECT;
    }
    if (!co_pdo_usable(node, i)) {
        return CO_ERR_STORE_STATE;
    }
    co_tpdo_raise(node, i);
    return CO_OK;
}
