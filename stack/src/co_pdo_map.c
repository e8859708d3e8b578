/*
 * Mapped objects through the dictionary: one mapping entry (index:16 sub:8
 * bits:8) sampled into a TPDO's bits or written from an RPDO's bits by the
 * same path as SDO (hooks, limits, the core's rules), with a bit copy. The
 * PDOs whose entries are all resolved when the mapping was enabled
 * (co_pdo_config.c, CO_PDO_F_DIRECT) never come here (co_pdo_sample_direct,
 * co_pdo_store_direct); the others take every entry this way.
 */
#include "co_priv.h"

/* @p n bits at bit @p spos of @p src to bit @p dpos of @p dst (little-endian
 * bit strings); whole bytes at byte boundaries at once. */
static void bits_copy(uint8_t *dst, uint16_t dpos, const uint8_t *src, uint16_t spos, uint8_t n)
{
    if (((dpos | spos | n) & 7U) == 0U) {
        co_copy(&dst[dpos >> 3U], &src[spos >> 3U], (size_t)n >> 3U);
        return;
    }
    for (uint8_t b = 0U; b < n; b++) {
        uint16_t s = (uint16_t)(spos + b);
        uint16_t d = (uint16_t)(dpos + b);
        uint8_t mask = (uint8_t)(1U << (d & 7U));
        if ((src[s >> 3U] & (1U << (s & 7U))) != 0U) {
            dst[d >> 3U] |= mask;
        } else {
            dst[d >> 3U] &= (uint8_t)~mask;
        }
    }
}

/* One entry @p v at bit @p pos through the dictionary: sampled into @p tx
 * (an object that cannot be read, a hook's veto, is sent as zeros), or,
 * with @p tx NULL, written from @p rx (a value the object refuses, limits
 * or a hook's veto, is dropped; a dummy entry is a gap). */
static void entry_io(co_node_t *node, uint32_t v, uint16_t pos, const uint8_t *rx,
                                 uint8_t *tx)
{
    uint16_t index = (uint16_t)(v >> 16U);
    uint8_t bits = (uint8_t)(v & 0xFFU);
    const co_od_entry_t *e;
    const co_od_sub_t *s;
    uint8_t tmp[8] = {0};

    if ((index > 0x0007U) &&
        (co_od_lookup(node, index, (uint8_t)((v >> 8U) & 0xFFU), &e, &s) == CO_OK)) {
        if (tx == NULL) {
            /* the low bits, extended to the value's size by the sign for
             * signed types */
            uint8_t size = co_type_len(s->type);
            bits_copy(tmp, 0U, rx, pos, bits);
            if (co_type_is_signed(s->type) &&
                ((tmp[(bits - 1U) >> 3U] & (1U << ((bits - 1U) & 7U))) != 0U)) {
                for (uint8_t b = bits; b < (uint8_t)(size * 8U); b++) {
                    tmp[b >> 3U] |= (uint8_t)(1U << (b & 7U));
                }
            }
            (void)co_od_write_value(node, e, s, tmp, size);
            return;
        }
        co_od_chunk_t c = {tmp, 0U, 8U, 0U, 0U, false};
        if (co_od_read_part(node, e, s, &c) != CO_OK) {
            (void)memset(tmp, 0, sizeof tmp);
        }
    }
    if (tx != NULL) {
        bits_copy(tx, pos, tmp, 0U, bits);
    }
}

/* The entries of PDO i through the dictionary (a PDO with an entry the
 * engine cannot copy directly; the others have CO_PDO_F_DIRECT). A TPDO
 * (@p tx) samples into @p tx (zeroed by the caller); an RPDO writes from
 * @p rx the entries its @p dlc bytes cover. */
static void pdo_io(co_node_t *node, uint16_t i, const uint8_t *rx, uint8_t dlc, uint8_t *tx)
{
    const co_pdo_desc_t *d = &node->dev->pdo[i];
    uint8_t count = co_ram_u8(node, d->count);
    uint16_t avail = (uint16_t)(((tx != NULL) || (dlc > 8U)) ? 64U : (dlc * 8U));
    uint16_t pos = 0U;

    for (uint8_t k = 0U; k < count; k++) {
        uint32_t v = co_ram_u32(node, (uint16_t)(d->map + (4U * k)));
        uint16_t end = (uint16_t)(pos + (v & 0xFFU));
        if (end > avail) {
            break;
        }
        entry_io(node, v, pos, rx, tx);
        pos = end;
    }
}

void co_pdo_sample(co_node_t *node, uint16_t i, uint8_t *out)
{
    pdo_io(node, i, NULL, 0U, out);
}

void co_pdo_store(co_node_t *node, uint16_t i, const uint8_t *data, uint8_t dlc)
{
    pdo_io(node, i, data, dlc, NULL);
}
