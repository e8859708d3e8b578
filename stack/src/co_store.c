/*
 * Parameter storage: 0x1010 store parameters, 0x1011 restore default
 * parameters (CiA 301 7.5.2.13 / 7.5.2.14), on the HAL's non-volatile memory.
 *
 * Groups: sub1 all, sub2 communication (RAM image [0, comm_end)), sub3
 * application ([comm_end, app_end)). [app_end, ram_size) is never stored.
 *
 * NV layout: two banks of co_store_nv_size(dev) / 2 bytes, bank 0 at NV
 * address 0. A bank is a 16-byte header followed by a copy of the RAM image
 * [0, app_end) (native byte order, as the image holds it):
 *
 *   0  magic "coNV" (u32)      4  sequence number (u32)
 *   8  layout signature (u16) 10  app_end (u16)
 *  12  groups held (bit 0 communication, bit 1 application)
 *  13  format (1)             14  CRC-16 over bytes 0..13 and the data of
 *                                 the groups held (in address order)
 *
 * A bank is valid when magic, format, layout and CRC match; the valid bank
 * with the higher sequence number (wrap-safe) holds the stored set. Every
 * save or restore writes a complete new set into the other bank, data first
 * (ascending), header last, so until the header is complete the previous set
 * stays the newest valid one: a power cut at any byte leaves the old or the
 * new set, never a mix. Groups not saved are copied from the previous set; a
 * restore writes a set without the restored groups (persistent, effective at
 * the next reset that covers them).
 */
#include <string.h>

#include "co/co_endian.h"
#include "co_crc16.h"
#include "co_priv.h"

#define STORE_SIG_SAVE 0x65766173UL /* "save" */
#define STORE_SIG_LOAD 0x64616F6CUL /* "load" */
#define STORE_MAGIC    0x564E6F63UL /* "coNV" */
#define STORE_FORMAT   1U
#define STORE_HDR      16U
#define STORE_CHUNK    32U
#define GRP_COMM       0x01U
#define GRP_APP        0x02U
#define GRP_ALL        (GRP_COMM | GRP_APP)
#define NO_BANK        2U

typedef struct store_bank {
    uint32_t seq;
    uint8_t groups; /* groups the set holds (0 without a valid set) */
    uint8_t idx;    /* 0, 1 or NO_BANK */
} store_bank_t;

static bool has_nv(const co_node_t *node)
{
    return (node->hal.ops->nv_read != NULL) && (node->hal.ops->nv_write != NULL);
}

static uint32_t bank_size(const co_dev_t *dev)
{
    return ((uint32_t)STORE_HDR + dev->app_end + 3U) & ~(uint32_t)3U;
}

uint32_t co_store_nv_size(const co_dev_t *dev)
{
    return 2U * bank_size(dev);
}

static void group_span(const co_dev_t *dev, uint8_t grp, uint16_t *lo, uint16_t *hi)
{
    *lo = (grp == GRP_COMM) ? 0U : dev->comm_end;
    *hi = (grp == GRP_COMM) ? dev->comm_end : dev->app_end;
}

/* Identifies the RAM layout: sizes, the CPU's byte order (the image holds
 * native integers) and, for every stored value, where it is and what it is.
 * A set written with another layout is not loaded. */
static uint16_t layout_sig(const co_dev_t *dev)
{
    static const uint16_t order = 0x0102U;
    uint8_t b[8];
    uint16_t crc;

    co_put_u16(&b[0], dev->ram_size);
    co_put_u16(&b[2], dev->comm_end);
    co_put_u16(&b[4], dev->app_end);
    (void)memcpy(&b[6], &order, 2U);
    crc = co_crc16(0xFFFFU, b, 8U);
    for (uint16_t i = 0U; i < dev->od_count; i++) {
        const co_od_entry_t *e = &dev->od[i];
        for (uint8_t k = 0U; k < e->nsubs; k++) {
            const co_od_sub_t *s = &e->subs[k];
            if (((s->flags & (CO_SUB_ROM | CO_SUB_HOOKIO)) == 0U) && (s->off < dev->app_end)) {
                co_put_u16(&b[0], e->index);
                b[2] = s->sub;
                b[3] = s->type;
                co_put_u16(&b[4], s->off);
                co_put_u16(&b[6], s->size);
                crc = co_crc16(crc, b, 8U);
            }
        }
    }
    return crc;
}

/* Stream the data of @p grp in the bank at @p from through the CRC, and copy
 * it to the bank at @p to unless @p to is UINT32_MAX. False on an NV error. */
static bool stream(const co_node_t *node, uint32_t from, uint32_t to, uint8_t grp, uint16_t *crc)
{
    uint8_t buf[STORE_CHUNK];
    uint16_t lo;
    uint16_t hi;

    group_span(node->dev, grp, &lo, &hi);
    for (uint32_t a = lo; a < hi; a += STORE_CHUNK) {
        uint32_t n = ((hi - a) < STORE_CHUNK) ? (hi - a) : STORE_CHUNK;
        if (node->hal.ops->nv_read(node->hal.ctx, from + STORE_HDR + a, buf, n) != 0) {
            return false;
        }
        *crc = co_crc16(*crc, buf, n);
        if ((to != UINT32_MAX) &&
            (node->hal.ops->nv_write(node->hal.ctx, to + STORE_HDR + a, buf, n) != 0)) {
            return false;
        }
    }
    return true;
}

/* True when bank @p idx holds a valid set (then *b describes it); *io_err is
 * set when the NV could not be read. */
static bool bank_valid(const co_node_t *node, uint8_t idx, uint16_t sig, store_bank_t *b,
                       bool *io_err)
{
    uint8_t h[STORE_HDR];
    uint32_t base = idx * bank_size(node->dev);
    uint16_t crc;

    if (node->hal.ops->nv_read(node->hal.ctx, base, h, STORE_HDR) != 0) {
        *io_err = true;
        return false;
    }
    if ((co_get_u32(&h[0]) != STORE_MAGIC) || (co_get_u16(&h[8]) != sig) ||
        (co_get_u16(&h[10]) != node->dev->app_end) || ((h[12] & ~GRP_ALL) != 0U) ||
        (h[13] != STORE_FORMAT)) {
        return false;
    }
    crc = co_crc16(0xFFFFU, h, 14U);
    for (uint8_t grp = GRP_COMM; grp <= GRP_APP; grp = (uint8_t)(grp << 1U)) {
        if (((h[12] & grp) != 0U) && !stream(node, base, UINT32_MAX, grp, &crc)) {
            *io_err = true;
            return false;
        }
    }
    if (crc != co_get_u16(&h[14])) {
        return false;
    }
    b->seq = co_get_u32(&h[4]);
    b->groups = h[12];
    b->idx = idx;
    return true;
}

/* The bank holding the newest valid set (idx NO_BANK, groups 0: none). */
static store_bank_t newest(const co_node_t *node, uint16_t sig, bool *io_err)
{
    store_bank_t best = {0U, 0U, NO_BANK};
    store_bank_t b;

    for (uint8_t i = 0U; i < 2U; i++) {
        if (bank_valid(node, i, sig, &b, io_err) &&
            ((best.idx == NO_BANK) || ((int32_t)(b.seq - best.seq) > 0))) {
            best = b;
        }
    }
    return best;
}

/* Write a new set into the other bank: the groups @p from_ram from the RAM
 * image, the groups the newest set holds (less @p drop) copied from it. */
static co_err_t commit(co_node_t *node, uint8_t from_ram, uint8_t drop)
{
    const co_dev_t *dev = node->dev;
    uint16_t sig = layout_sig(dev);
    bool io_err = false;
    store_bank_t old = newest(node, sig, &io_err);
    uint8_t keep = (uint8_t)(old.groups & (uint8_t)~(from_ram | drop));
    uint32_t base = (old.idx == 0U) ? bank_size(dev) : 0U;
    uint8_t h[STORE_HDR];
    uint16_t crc;

    if (io_err) {
        return CO_ERR_HW; /* the previous set (and which bank is free) is unknown */
    }
    if ((from_ram == 0U) && ((old.groups & drop) == 0U)) {
        return CO_OK; /* restore: nothing of these groups is stored */
    }
    co_put_u32(&h[0], STORE_MAGIC);
    co_put_u32(&h[4], old.seq + 1U);
    co_put_u16(&h[8], sig);
    co_put_u16(&h[10], dev->app_end);
    h[12] = (uint8_t)(from_ram | keep);
    h[13] = STORE_FORMAT;
    crc = co_crc16(0xFFFFU, h, 14U);
    for (uint8_t grp = GRP_COMM; grp <= GRP_APP; grp = (uint8_t)(grp << 1U)) {
        uint16_t lo;
        uint16_t hi;
        group_span(dev, grp, &lo, &hi);
        if ((from_ram & grp) != 0U) {
            if ((hi > lo) && (node->hal.ops->nv_write(node->hal.ctx, base + STORE_HDR + lo,
                                                      &node->ram[lo], (uint32_t)hi - lo) != 0)) {
                return CO_ERR_HW;
            }
            crc = co_crc16(crc, &node->ram[lo], (uint32_t)hi - lo);
        } else if (((keep & grp) != 0U) &&
                   !stream(node, (uint32_t)old.idx * bank_size(dev), base, grp, &crc)) {
            return CO_ERR_HW;
        } else {
            /* group not in the new set */
        }
    }
    co_put_u16(&h[14], crc);
    return (node->hal.ops->nv_write(node->hal.ctx, base, h, STORE_HDR) != 0) ? CO_ERR_HW : CO_OK;
}

bool co_store_is_command(const co_od_entry_t *e, const co_od_sub_t *s)
{
    return ((e->index == 0x1010U) || (e->index == 0x1011U)) && (s->sub != 0U) &&
           (s->type == (uint8_t)CO_UNSIGNED32) &&
           ((s->flags & (CO_SUB_ROM | CO_SUB_HOOKIO)) == 0U);
}

co_err_t co_store_command(co_node_t *node, uint16_t index, uint8_t sub, const uint8_t *data)
{
    bool save = (index == 0x1010U);
    uint8_t grp = (sub == 1U) ? GRP_ALL : ((sub == 2U) ? GRP_COMM : ((sub == 3U) ? GRP_APP : 0U));

    if ((grp == 0U) || !has_nv(node) ||
        (co_get_u32(data) != (save ? STORE_SIG_SAVE : STORE_SIG_LOAD))) {
        return CO_ERR_STORE;
    }
    return save ? commit(node, grp, 0U) : commit(node, 0U, grp);
}

void co_store_reset(co_node_t *node, co_reset_t kind)
{
    const co_dev_t *dev = node->dev;
    uint8_t area = (kind == CO_RESET_NODE) ? GRP_ALL : GRP_COMM;
    uint32_t cap = has_nv(node) ? 1U : 0U; /* bit 0: on command */

    co_od_restore(node, 0U, (kind == CO_RESET_NODE) ? dev->ram_size : dev->comm_end);
    if (cap != 0U) {
        bool io_err = false; /* an unreadable bank counts as invalid */
        store_bank_t b = newest(node, layout_sig(dev), &io_err);
        for (uint8_t grp = GRP_COMM; grp <= GRP_APP; grp = (uint8_t)(grp << 1U)) {
            uint16_t lo;
            uint16_t hi;
            group_span(dev, grp, &lo, &hi);
            if (((area & b.groups & grp) != 0U) && (hi > lo) &&
                (node->hal.ops->nv_read(node->hal.ctx,
                                        ((uint32_t)b.idx * bank_size(dev)) + STORE_HDR + lo,
                                        &node->ram[lo], (uint32_t)hi - lo) != 0)) {
                co_od_restore(node, lo, hi);
            }
        }
    }
    /* What 0x1010 / 0x1011 read: the capability, whatever was written. */
    for (uint16_t index = 0x1010U; index <= 0x1011U; index++) {
        const co_od_entry_t *e = co_od_find(dev->od, dev->od_count, index);
        for (uint8_t k = 0U; (e != NULL) && (k < e->nsubs); k++) {
            if (co_store_is_command(e, &e->subs[k])) {
                uint32_t v = (e->subs[k].sub <= 3U) ? cap : 0U;
                (void)memcpy(&node->ram[e->subs[k].off], &v, 4U);
            }
        }
    }
}
