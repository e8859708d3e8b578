/*
 * Mapped objects: each mapping entry (its 16-bit form, co_od.h) sampled into
 * a TPDO's bits or written from an RPDO's bits, directly from its row of
 * the mappable-object table when the mapping was found copyable as it was
 * enabled (co_pdo_config.c, CO_PDO_F_DIRECT), else by the same path as SDO
 * (hooks, limits, the core's rules) with a bit copy. A build for speed
 * (CO_FAST) copies the CO_PDO_F_DIRECT PDOs inline instead
 * (co_pdo_sample_direct, co_pdo_store_direct); a build for size comes here
 * for every PDO.
 */
#include "co_priv.h"

#if !CO_FAST
uint32_t co_pdo_time_us(const co_node_t *node, uint16_t i, bool inhibit)
{
    const co_pdo_desc_t *d = &node->dev->pdo[i];
    uint8_t rel = inhibit ? d->inhibit : d->event;
    uint32_t unit = (inhibit || (CO_SET(node, pdo.event_timer_unit) == CO_PDO_TIMER_100US))
                        ? 100UL
                        : 1000UL;

    return (rel == 0U) ? 0U : co_dict_us(co_pdo_u16(node, i, rel), unit);
}
#endif

/* @p n bits at bit @p spos of @p src to bit @p dpos of @p dst (little-endian
 * bit strings); whole bytes at byte boundaries at once (without
 * CO_PDO_BITWISE every mapping is in whole bytes: only that). */
static void bits_copy(uint8_t *dst, uint16_t dpos, const uint8_t *src, uint16_t spos, uint8_t n)
{
    if (!CO_PDO_BITWISE || (((dpos | spos | n) & 7U) == 0U)) {
        co_copy(&dst[dpos >> 3U], &src[spos >> 3U], (size_t)n >> 3U);
        return;
    }
    for (uint32_t b = 0U; b < n; b++) {
        uint32_t s = spos + b;
        uint32_t d = dpos + b;
        uint32_t bit = ((uint32_t)src[s >> 3U] >> (s & 7U)) & 1U;
        dst[d >> 3U] = (uint8_t)((dst[d >> 3U] & ~(1U << (d & 7U))) | (bit << (d & 7U)));
    }
}

/* One entry (16-bit form @p ref) at bit @p pos of @p buf: sampled into it
 * (@p tx; an object that cannot be read, a hook's veto, is sent as zeros),
 * or written from it (a value the object refuses, limits or a hook's veto,
 * is dropped; a dummy entry is a gap). An entry of a CO_PDO_F_DIRECT PDO
 * (@p direct) is copied between its RAM value and the bits directly, any
 * other goes through the dictionary. */
static void entry_io(co_node_t *node, uint32_t ref, bool direct, uint16_t pos, uint8_t *buf,
                     bool tx)
{
    uint8_t bits = (uint8_t)co_pdo_ref_bits(ref);
    const co_od_map_t *m;
    const co_od_entry_t *e = NULL; /* (an entry through the dictionary: its descriptor in s) */
    co_od_sub_t s;
    uint8_t *ram = node->ram;
    uint8_t size;
    bool sign;
    uint8_t tmp[8] = {0};

    if (co_pdo_ref_dummy(ref)) {
        return; /* a dummy entry (an RPDO's gap) */
    }
    m = co_pdo_row(node->dev, ref);
    if (!direct) {
        if (co_od_lookup(node, m->index, m->sub, &e, &s) != CO_OK) {
            return; /* an object that is not there (a TPDO's zeros: buf is zero) */
        }
        size = co_type_len(s.type);
        sign = co_type_is_signed(s.type);
    } else {
        ram = &ram[m->off];
        size = (uint8_t)((m->info & CO_OD_MAP_SIZE) + 1U);
        sign = (m->info & CO_OD_MAP_SIGNED) != 0U;
    }
    if (tx) {
        const uint8_t *src = tmp;
        if (e != NULL) {
            co_od_chunk_t c = {NULL, NULL, NULL, NULL, 0U, tmp, 8U, 0U, false};
            if (co_od_read_part(node, e, &s, &c) != CO_OK) {
                (void)memset(tmp, 0, sizeof tmp);
            }
        } else if (CO_NATIVE_LE) {
            src = ram; /* the low bytes (on a big-endian CPU the entry maps the whole value) */
        } else {
            co_to_wire(tmp, ram, size);
        }
        bits_copy(buf, pos, src, 0U, bits);
        return;
    }
    /* the low bits, extended to the value's size by the sign for signed types */
    if (sign) {
        uint16_t top = (uint16_t)(pos + bits - 1U);
        if ((buf[top >> 3U] & (1U << (top & 7U))) != 0U) {
            (void)memset(tmp, 0xFF, sizeof tmp);
        }
    }
    bits_copy(tmp, 0U, buf, pos, bits);
    if (e != NULL) {
        (void)co_od_write_value(node, e, &s, tmp, size);
    } else if (CO_NATIVE_LE) {
        co_copy(ram, tmp, size);
    } else {
        co_from_wire(ram, tmp, size);
    }
}

/* The entries of PDO i: sampled into @p buf (8 bytes, zero past the
 * mapping) with @p dlc CO_PDO_SAMPLE, else written from @p buf, the entries
 * its @p dlc bytes (0..8) cover. */
void co_pdo_io(co_node_t *node, uint16_t i, uint8_t *buf, uint8_t dlc)
{
    const uint8_t *map = co_pdo_map(node, &node->dev->pdo[i]);
    uint32_t count = co_pdo_count(node, i);
    bool direct = (co_pdo_st(node)[i].flags & CO_PDO_F_DIRECT) != 0U;
    bool tx = dlc == CO_PDO_SAMPLE;
    uint32_t avail = tx ? 64U : (dlc * 8U);
    uint32_t pos = 0U;

    if (tx) {
        (void)memset(buf, 0, 8U);
    }
    for (uint32_t k = 0U; k < count; k++) {
        uint32_t ref = co_pdo_ref(map, k);
        uint32_t end = pos + co_pdo_ref_bits(ref);
        if (end > avail) {
            break;
        }
        entry_io(node, ref, direct, (uint16_t)pos, buf, tx);
        pos = end;
    }
}
