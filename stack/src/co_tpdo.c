/*
 * Transmit PDOs: sampling the mapped objects through the dictionary's read
 * path, the transmission types (synchronous cyclic/acyclic, RTR only,
 * event-driven with change detection, inhibit time and event timer), and the
 * SYNC start value and window.
 *
 * A TPDO never waits in the core's TX hold-back queue: when the HAL does not
 * take it, the TPDO stays due and is sampled again (event-driven) or retried
 * while the synchronous window is open (synchronous), so what goes out is
 * never older than necessary.
 */
#include "co_priv.h"

#define RETRY_US 1000UL /* TX path full: try again this much later */

/* Sample the mapped objects into @p out (8 bytes, zero-padded). */
static void build(co_node_t *node, uint16_t i, uint8_t *out)
{
    const co_pdo_desc_t *d = &node->dev->pdo[i];
    uint8_t count = co_ram_u8(node, d->count);
    uint16_t pos = 0U;

    (void)memset(out, 0, 8U);
    for (uint8_t k = 0U; k < count; k++) {
        uint32_t v = co_ram_u32(node, (uint16_t)(d->map + (4U * k)));
        uint8_t bits = (uint8_t)(v & 0xFFU);
        const co_od_entry_t *e;
        const co_od_sub_t *s;
        uint8_t tmp[8] = {0};
        uint32_t len = 0U;
        uint32_t total;
        bool last;

        if ((co_od_lookup(node, (uint16_t)(v >> 16U), (uint8_t)((v >> 8U) & 0xFFU), &e, &s) ==
             CO_OK) &&
            (co_od_read_part(node, e, s, 0U, tmp, 8U, &len, &total, &last) == CO_OK)) {
            if (((pos & 7U) == 0U) && ((bits & 7U) == 0U)) {
                (void)memcpy(&out[pos >> 3U], tmp, (size_t)bits >> 3U);
            } else {
                co_bits_put(out, pos, tmp, bits);
            }
        }
        /* an object that cannot be read (a hook's veto) is sent as zeros */
        pos = (uint16_t)(pos + bits);
    }
}

static bool send(co_node_t *node, uint16_t i, const uint8_t *data)
{
    co_pdo_t *p = &node->pdo[i];

    if (!co_tx_try(node, co_pdo_cob(node, i) & 0x7FFUL, data, p->len)) {
        return false;
    }
    if (data != p->data) {
        (void)memcpy(p->data, data, 8U);
    }
    p->flags |= CO_PDO_F_SENT;
    return true;
}

/* Event-driven send with inhibit time and event timer restart. */
static bool send_event(co_node_t *node, uint16_t i, const uint8_t *data)
{
    co_pdo_t *p = &node->pdo[i];
    uint16_t off = node->dev->pdo[i].inhibit;
    uint32_t inhibit = (off == CO_PDO_NONE) ? 0U : ((uint32_t)co_ram_u16(node, off) * 100UL);
    uint32_t ev = co_pdo_event_us(node, i);

    if (!send(node, i, data)) {
        return false;
    }
    p->flags &= (uint16_t)~(CO_PDO_F_EVENT | CO_PDO_F_INHIBIT | CO_PDO_F_TIMER);
    if (inhibit != 0U) {
        p->inhibit = node->now + inhibit;
        p->flags |= CO_PDO_F_INHIBIT;
    }
    if (ev != 0U) {
        p->timer = node->now + ev;
        p->flags |= CO_PDO_F_TIMER;
    }
    return true;
}

/* Synchronous send: sampled now, sent now or, if the TX path is full, while
 * the synchronous window stays open. */
static void send_sync(co_node_t *node, uint16_t i)
{
    co_pdo_t *p = &node->pdo[i];

    build(node, i, p->data);
    p->flags &= (uint16_t)~CO_PDO_F_EVENT;
    if (!send(node, i, p->data)) {
        p->flags |= CO_PDO_F_SYNC_PEND;
    }
}

void co_tpdo_sync(co_node_t *node, uint8_t counter)
{
    uint16_t n = (uint16_t)(node->dev->n_rpdo + node->dev->n_tpdo);

    if (node->nmt != (uint8_t)CO_NMT_OPERATIONAL) {
        return;
    }
    for (uint16_t i = node->dev->n_rpdo; i < n; i++) {
        co_pdo_t *p = &node->pdo[i];
        uint8_t type;
        if (!co_pdo_usable(node, i)) {
            continue;
        }
        type = co_pdo_type(node, i);
        p->flags &= (uint16_t)~CO_PDO_F_SYNC_PEND; /* a new SYNC replaces it */
        if (type == 252U) {
            build(node, i, p->data); /* sampled now, sent on request */
            p->flags |= CO_PDO_F_SAMPLED;
        } else if (type == 0U) {
            /* acyclic: at the SYNC after a change or a request */
            uint8_t now[8];
            build(node, i, now);
            if (((p->flags & (CO_PDO_F_EVENT | CO_PDO_F_SENT)) != CO_PDO_F_SENT) ||
                (memcmp(now, p->data, 8U) != 0)) {
                send_sync(node, i);
            }
        } else if (type <= 240U) {
            const co_pdo_desc_t *d = &node->dev->pdo[i];
            uint8_t start = (d->start != CO_PDO_NONE) ? co_ram_u8(node, d->start) : 0U;
            bool counted = (node->sync_overflow != NULL) && (*node->sync_overflow > 1U);
            if (counted && (start != 0U) && ((p->flags & CO_PDO_F_STARTED) == 0U)) {
                /* the first transmission waits for the SYNC counter */
                if (counter == start) {
                    p->flags |= CO_PDO_F_STARTED;
                    p->count = 0U;
                    send_sync(node, i);
                }
            } else {
                p->count++;
                if (p->count >= type) {
                    p->count = 0U;
                    send_sync(node, i);
                }
            }
        } else {
            /* RTR-only 253 and event-driven types do not follow SYNC */
        }
    }
}

void co_tpdo_rtr(co_node_t *node, uint16_t i)
{
    co_pdo_t *p = &node->pdo[i];

    if ((node->nmt != (uint8_t)CO_NMT_OPERATIONAL) || !co_pdo_usable(node, i)) {
        return;
    }
    p->flags |= CO_PDO_F_RTR;
    (void)co_tpdo_process(node, CO_NO_DEADLINE);
}

/* Answer a remote request: type 252 with the data sampled at the last SYNC,
 * every other type with the data of now. */
static bool answer_rtr(co_node_t *node, uint16_t i)
{
    co_pdo_t *p = &node->pdo[i];
    uint8_t now[8];

    if ((co_pdo_type(node, i) == 252U) && ((p->flags & CO_PDO_F_SAMPLED) != 0U)) {
        return send(node, i, p->data);
    }
    build(node, i, now);
    if (co_pdo_type(node, i) >= 254U) {
        return send_event(node, i, now);
    }
    return send(node, i, now);
}

/* Event-driven (254/255): change of the data, a request, or the event timer,
 * no sooner than the inhibit time allows. Returns the next deadline. */
static uint32_t event_driven(co_node_t *node, uint16_t i, uint32_t next)
{
    co_pdo_t *p = &node->pdo[i];
    uint8_t now[8];

    if (((p->flags & CO_PDO_F_TIMER) != 0U) && co_time_reached(node->now, p->timer)) {
        p->flags |= CO_PDO_F_EVENT;
    }
    if (((p->flags & CO_PDO_F_INHIBIT) != 0U) && co_time_reached(node->now, p->inhibit)) {
        p->flags &= (uint16_t)~CO_PDO_F_INHIBIT;
    }
    build(node, i, now);
    if (((p->flags & CO_PDO_F_SENT) == 0U) || (memcmp(now, p->data, 8U) != 0)) {
        p->flags |= CO_PDO_F_EVENT;
    }
    if ((p->flags & CO_PDO_F_EVENT) != 0U) {
        if ((p->flags & CO_PDO_F_INHIBIT) != 0U) {
            next = co_deadline_min(node->now, next, p->inhibit);
        } else if (!send_event(node, i, now)) {
            next = co_deadline_min(node->now, next, node->now + RETRY_US);
        } else {
            /* sent */
        }
    }
    if ((p->flags & CO_PDO_F_TIMER) != 0U) {
        next = co_deadline_min(node->now, next, p->timer);
    }
    return next;
}

uint32_t co_tpdo_process(co_node_t *node, uint32_t next)
{
    uint16_t n = (uint16_t)(node->dev->n_rpdo + node->dev->n_tpdo);

    if (node->nmt != (uint8_t)CO_NMT_OPERATIONAL) {
        return next;
    }
    for (uint16_t i = node->dev->n_rpdo; i < n; i++) {
        co_pdo_t *p = &node->pdo[i];
        uint8_t type;
        if (!co_pdo_usable(node, i)) {
            continue;
        }
        type = co_pdo_type(node, i);
        if ((p->flags & CO_PDO_F_RTR) != 0U) {
            if (answer_rtr(node, i)) {
                p->flags &= (uint16_t)~CO_PDO_F_RTR;
            } else {
                next = co_deadline_min(node->now, next, node->now + RETRY_US);
            }
        }
        if ((p->flags & CO_PDO_F_SYNC_PEND) != 0U) {
            /* CiA 301: synchronous PDOs outside the window are not sent */
            if (!co_sync_window_open(node) || send(node, i, p->data)) {
                p->flags &= (uint16_t)~CO_PDO_F_SYNC_PEND;
            } else {
                next = co_deadline_min(node->now, next, node->now + RETRY_US);
            }
        }
        if (type >= 254U) {
            next = event_driven(node, i, next);
        }
    }
    return next;
}
