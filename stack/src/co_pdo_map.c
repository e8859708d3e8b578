/*
 * Mapped objects through the dictionary: one mapping entry (index:16 sub:8
 * bits:8) sampled into a TPDO's bits or written from an RPDO's bits by the
 * same path as SDO (hooks, limits, the core's rules), and the bit copies;
 * entries resolved when the mapping was enabled (co_pdo_config.c,
 * co_pdo_code) are copied directly between frame and RAM image.
 */
#include "co_priv.h"

/* Bit copies between little-endian bit strings: @p n bits of @p src to bit
 * @p dpos of @p dst, and @p n bits at bit @p spos of @p src into @p dst
 * (which starts zeroed). */
static void bits_put(uint8_t *dst, uint16_t dpos, const uint8_t *src, uint8_t n)
{
    for (uint8_t b = 0U; b < n; b++) {
        uint16_t at = (uint16_t)(dpos + b);
        uint8_t mask = (uint8_t)(1U << (at & 7U));
        if ((src[b >> 3U] & (1U << (b & 7U))) != 0U) {
            dst[at >> 3U] |= mask;
        } else {
            dst[at >> 3U] &= (uint8_t)~mask;
        }
    }
}

static void bits_get(uint8_t *dst, const uint8_t *src, uint16_t spos, uint8_t n)
{
    for (uint8_t b = 0U; b < n; b++) {
        uint16_t at = (uint16_t)(spos + b);
        if ((src[at >> 3U] & (1U << (at & 7U))) != 0U) {
            dst[b >> 3U] |= (uint8_t)(1U << (b & 7U));
        }
    }
}

/* Sample one mapped object through the dictionary's read path into @p out
 * at bit @p pos. An object that cannot be read (a hook's veto) is sent as
 * zeros. */
CO_NOINLINE static void sample(co_node_t *node, uint32_t v, uint16_t pos, uint8_t *out)
{
    uint8_t bits = (uint8_t)(v & 0xFFU);
    const co_od_entry_t *e;
    const co_od_sub_t *s;
    uint8_t tmp[8] = {0};
    co_od_chunk_t c = {tmp, 0U, 8U, 0U, 0U, false};

    if ((co_od_lookup(node, (uint16_t)(v >> 16U), (uint8_t)((v >> 8U) & 0xFFU), &e, &s) ==
         CO_OK) &&
        (co_od_read_part(node, e, s, &c) == CO_OK)) {
        if (((pos & 7U) == 0U) && ((bits & 7U) == 0U)) {
            (void)memcpy(&out[pos >> 3U], tmp, (size_t)bits >> 3U);
        } else {
            bits_put(out, pos, tmp, bits);
        }
    }
}

/* Part of an object, or not byte-aligned: the low @p bits of a value of
 * @p size bytes, extended by the sign for signed types. */
static void unpack(uint8_t *out, const uint8_t *data, uint16_t pos, uint8_t bits, bool sign,
                   uint8_t size)
{
    bits_get(out, data, pos, bits);
    if (sign && ((out[(bits - 1U) >> 3U] & (1U << ((bits - 1U) & 7U))) != 0U)) {
        for (uint8_t b = bits; b < (uint8_t)(size * 8U); b++) {
            out[b >> 3U] |= (uint8_t)(1U << (b & 7U));
        }
    }
}

/* Write one mapped object (entry @p v, at bit @p pos of @p data) through
 * the dictionary's write path. A value the object refuses (limits, a hook's
 * veto) is dropped. */
CO_NOINLINE static void store(co_node_t *node, uint32_t v, uint16_t pos, const uint8_t *data)
{
    uint16_t index = (uint16_t)(v >> 16U);
    uint8_t bits = (uint8_t)(v & 0xFFU);
    const co_od_entry_t *e;
    const co_od_sub_t *s;

    if ((index > 0x0007U) &&
        (co_od_lookup(node, index, (uint8_t)((v >> 8U) & 0xFFU), &e, &s) == CO_OK)) {
        uint8_t size = co_type_len(s->type);
        if (((pos & 7U) == 0U) && (bits == (uint8_t)(size * 8U))) {
            (void)co_od_write_value(node, e, s, &data[pos >> 3U], size);
        } else {
            uint8_t tmp[8] = {0};
            unpack(tmp, data, pos, bits, co_type_is_signed(s->type), size);
            (void)co_od_write_value(node, e, s, tmp, size);
        }
    }
}


void co_pdo_sample(co_node_t *node, uint16_t i, uint8_t *out)
{
    const co_pdo_desc_t *d = &node->dev->pdo[i];
    const co_pdo_t *p = &node->pdo.p[i];
    uint8_t count = co_ram_u8(node, d->count);
    uint16_t pos = 0U;
    uint16_t entry = d->map;

    for (uint8_t k = 0U; k < count; k++) {
        uint32_t v = co_ram_u32(node, entry);
        uint16_t code = co_pdo_code(p, k);
        if (code < CO_PDO_DUMMY) {
            uint8_t tmp[8];
            uint8_t n = (uint8_t)co_tpdo_code_len(code);
            (void)co_pdo_get_direct(node, code, tmp);
            (void)memcpy(&out[pos >> 3U], tmp, n);
        } else {
            sample(node, v, pos, out);
        }
        pos = (uint16_t)(pos + (v & 0xFFU));
        entry = (uint16_t)(entry + 4U);
    }
}

void co_pdo_store(co_node_t *node, uint16_t i, const uint8_t *data, uint8_t dlc)
{
    const co_pdo_desc_t *d = &node->dev->pdo[i];
    const co_pdo_t *p = &node->pdo.p[i];
    uint8_t count = co_ram_u8(node, d->count);
    uint16_t avail = (uint16_t)((dlc > 8U) ? 64U : (dlc * 8U));
    uint16_t pos = 0U;
    uint16_t entry = d->map;

    for (uint8_t k = 0U; k < count; k++) {
        uint32_t v = co_ram_u32(node, entry);
        uint16_t end = (uint16_t)(pos + (v & 0xFFU));
        uint16_t code = co_pdo_code(p, k);
        if (end > avail) {
            break;
        }
        if (code < CO_PDO_DUMMY) {
            co_pdo_put_direct(node, code, &data[pos >> 3U], (uint8_t)((v & 0xFFU) >> 3U));
        } else if (code == CO_PDO_DUMMY) {
            /* a gap */
        } else {
            store(node, v, pos, data);
        }
        pos = end;
        entry = (uint16_t)(entry + 4U);
    }
}
