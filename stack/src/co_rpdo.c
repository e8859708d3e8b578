/*
 * Receive PDOs: length checks, synchronous buffering, deadline monitoring,
 * and writing the mapped objects through the dictionary's write path.
 */
#include "co_priv.h"

static bool any_rpdo(const co_node_t *node, uint16_t flag)
{
    for (uint16_t i = 0U; i < node->dev->n_rpdo; i++) {
        if ((node->pdo[i].flags & flag) != 0U) {
            return true;
        }
    }
    return false;
}

/* Set or clear an RPDO error state; the EMCY goes with the first PDO in the
 * state and ends with the last one leaving it. */
static void rpdo_error(co_node_t *node, uint16_t i, uint16_t flag, uint16_t code, bool on)
{
    co_pdo_t *p = &node->pdo[i];

    if (on == ((p->flags & flag) != 0U)) {
        return;
    }
    if (on) {
        p->flags |= flag;
        co_emcy_raise(node, code, CO_ERREG_COMM, NULL);
    } else {
        p->flags &= (uint16_t)~flag;
        if (!any_rpdo(node, flag)) {
            co_emcy_clear(node, code);
        }
    }
}

/* Part of an object, or not byte-aligned: the low @p bits of a value of
 * @p size bytes, extended by the sign for signed types. */
static void unpack(uint8_t *out, const uint8_t *data, uint16_t pos, uint8_t bits, bool sign,
                   uint8_t size)
{
    co_bits_get(out, data, pos, bits);
    if (sign && ((out[(bits - 1U) >> 3U] & (1U << ((bits - 1U) & 7U))) != 0U)) {
        for (uint8_t b = bits; b < (uint8_t)(size * 8U); b++) {
            out[b >> 3U] |= (uint8_t)(1U << (b & 7U));
        }
    }
}

/* Write the mapped objects from @p data (@p dlc bytes): entries the frame
 * does not cover completely are skipped (only with CO_OPT_RPDO_SHORT_OK can
 * that happen). A value an object refuses (limits, a hook's veto) is
 * dropped; the other entries still take effect. */
static void apply(co_node_t *node, uint16_t i, const uint8_t *data, uint8_t dlc)
{
    const co_pdo_desc_t *d = &node->dev->pdo[i];
    uint8_t count = co_ram_u8(node, d->count);
    uint16_t avail = (uint16_t)((dlc > 8U) ? 64U : (dlc * 8U));
    uint16_t pos = 0U;

    for (uint8_t k = 0U; k < count; k++) {
        uint32_t v = co_ram_u32(node, (uint16_t)(d->map + (4U * k)));
        uint16_t index = (uint16_t)(v >> 16U);
        uint8_t bits = (uint8_t)(v & 0xFFU);
        const co_od_entry_t *e;
        const co_od_sub_t *s;

        if ((uint16_t)(pos + bits) > avail) {
            break;
        }
        if ((index > 0x0007U) &&
            (co_od_lookup(node, index, (uint8_t)((v >> 8U) & 0xFFU), &e, &s) == CO_OK)) {
            uint8_t size = co_type_size(s->type);
            if (((pos & 7U) == 0U) && (bits == (uint8_t)(size * 8U))) {
                (void)co_od_write_value(node, e, s, &data[pos >> 3U], size);
            } else {
                uint8_t tmp[8] = {0};
                unpack(tmp, data, pos, bits, co_type_is_signed(s->type), size);
                (void)co_od_write_value(node, e, s, tmp, size);
            }
        }
        pos = (uint16_t)(pos + bits);
    }
}

void co_rpdo_rx(co_node_t *node, uint16_t i, const co_frame_t *f)
{
    co_pdo_t *p = &node->pdo[i];
    uint32_t ev;

    if ((node->nmt != (uint8_t)CO_NMT_OPERATIONAL) || co_frame_is_rtr(f) ||
        !co_pdo_usable(node, i)) {
        return;
    }
    if (f->dlc < p->len) {
        if ((node->dev->options & CO_OPT_RPDO_SHORT_OK) == 0U) {
            rpdo_error(node, i, CO_PDO_F_SHORT, CO_EMCY_PDO_SHORT, true);
            return; /* CiA 301: not processed */
        }
    } else {
        rpdo_error(node, i, CO_PDO_F_SHORT, CO_EMCY_PDO_SHORT, false);
    }
    /* longer than mapped: processed (the first bytes), and reported */
    rpdo_error(node, i, CO_PDO_F_LONG, CO_EMCY_PDO_LONG, f->dlc > p->len);
    ev = co_pdo_event_us(node, i);
    if (ev != 0U) {
        p->timer = node->now + ev;
        p->flags |= CO_PDO_F_TIMER;
    }
    rpdo_error(node, i, CO_PDO_F_TIMEOUT, CO_EMCY_RPDO_TIMEOUT, false);
    if (co_pdo_type(node, i) <= 240U) {
        /* synchronous: takes effect at the next SYNC, if it came in time */
        if (co_sync_window_open(node)) {
            (void)memcpy(p->data, f->data, 8U);
            p->dlc = f->dlc;
            p->flags |= CO_PDO_F_RXBUF;
        }
        return;
    }
    apply(node, i, f->data, f->dlc);
}

void co_rpdo_sync(co_node_t *node)
{
    if (node->nmt != (uint8_t)CO_NMT_OPERATIONAL) {
        return;
    }
    for (uint16_t i = 0U; i < node->dev->n_rpdo; i++) {
        co_pdo_t *p = &node->pdo[i];
        if ((p->flags & CO_PDO_F_RXBUF) != 0U) {
            p->flags &= (uint16_t)~CO_PDO_F_RXBUF;
            apply(node, i, p->data, p->dlc);
        }
    }
}

uint32_t co_rpdo_process(co_node_t *node, uint32_t next)
{
    for (uint16_t i = 0U; i < node->dev->n_rpdo; i++) {
        co_pdo_t *p = &node->pdo[i];
        if ((p->flags & CO_PDO_F_TIMER) == 0U) {
            continue;
        }
        if (co_time_reached(node->now, p->timer)) {
            p->flags &= (uint16_t)~CO_PDO_F_TIMER;
            rpdo_error(node, i, CO_PDO_F_TIMEOUT, CO_EMCY_RPDO_TIMEOUT, true);
        } else {
            next = co_deadline_min(node->now, next, p->timer);
        }
    }
    return next;
}
