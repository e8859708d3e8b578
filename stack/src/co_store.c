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
 *  12  groups held (bit 0 communication, bit 1 application); bits 2, 3:
 *      of those, the groups restored to defaults whose data is kept for a
 *      restore of the saved set (CO_RESTORE_SAVED)
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
 * the next reset that covers them). With CO_RESTORE_SAVED a restore
 * keeps the group's data, marked restored (the defaults load), and 0x1011
 * sub 4..6 ("restore the saved set": all, communication, application) take
 * the mark away again, so that the last saved values load at the next reset.
 *
 * Flash (co_hal_ops_t.nv_erase, nv_erase_unit): each bank starts on an erase
 * unit and spans whole units; a command erases the bank it writes first.
 * An asynchronous HAL (nv_poll): the erase, then the writes of the set, run
 * in the background while the node serves the bus (co_store_process polls
 * every millisecond); the set is taken from the RAM image in one go once
 * the erase is done, and the SDO answer comes when the HAL says the set is
 * durable. A newest set that fails its CRC (damaged after it was written,
 * or a save cut short in its header) is reported after the boot-up (EMCY
 * 0x5530, 0x1001, 0x1003) until a save writes a whole one.
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
#define GRP_RESTORED   2U           /* header byte 12: restored groups << GRP_RESTORED */
#define NO_BANK        2U
#define AT_RAM         0xFFFFFFFFUL /* stream(): the RAM image instead of a bank */
#define AT_NONE        0xFFFFFFFEUL /* stream(): nowhere (CRC only) */

typedef struct store_bank {
    uint32_t seq;
    uint8_t groups; /* groups the set holds (0 without a valid set) */
    uint8_t restored; /* of those, the groups restored to defaults (data kept) */
    uint8_t idx;    /* 0, 1 or NO_BANK */
} store_bank_t;

#if CO_STORAGE
/* Header byte 12: groups held, and the restored ones among them. */
static bool groups_valid(uint8_t b)
{
    uint8_t held = (uint8_t)(b & GRP_ALL);
    uint8_t restored = (uint8_t)((uint8_t)(b >> GRP_RESTORED) & GRP_ALL);

    return ((b & (uint8_t)~(GRP_ALL | (GRP_ALL << GRP_RESTORED))) == 0U) &&
           ((restored & (uint8_t)~held) == 0U);
}

static bool has_nv(const co_node_t *node)
{
    return (node->hal.ops->nv_read != NULL) && (node->hal.ops->nv_write != NULL);
}
#endif

/* Bytes of one bank: header and data, in whole erase units (at least 4). */
static uint32_t bank_bytes(const co_dev_t *dev, uint32_t erase_unit)
{
    uint32_t u = (erase_unit > 4U) ? erase_unit : 4U;

    return ((uint32_t)STORE_HDR + dev->app_end + u - 1U) & ~(u - 1U);
}

/* The LSS records' spacing: each in an erase unit of its own. */
static uint32_t lss_stride(uint32_t erase_unit)
{
    return (erase_unit > CO_LSS_REC) ? erase_unit : CO_LSS_REC;
}

static uint32_t bank_size(const co_node_t *node)
{
    return bank_bytes(node->dev, node->hal.ops->nv_erase_unit);
}

uint32_t co_store_nv_size_unit(const co_dev_t *dev, uint32_t erase_unit)
{
    uint32_t size = 2U * bank_bytes(dev, erase_unit);

#if CO_LSS
    if (dev->set.lss.slave != 0U) {
        size += 2U * lss_stride(erase_unit); /* the LSS records (co_lss.c) */
    }
#endif
    return size;
}

uint32_t co_store_nv_size(const co_dev_t *dev)
{
    return co_store_nv_size_unit(dev, 0U);
}

uint32_t co_store_lss_addr(const co_node_t *node, uint8_t rec)
{
    return (2U * bank_size(node)) + ((uint32_t)rec * lss_stride(node->hal.ops->nv_erase_unit));
}

uint32_t co_store_lss_unit(const co_node_t *node)
{
    return lss_stride(node->hal.ops->nv_erase_unit);
}

#if CO_STORAGE
typedef struct {
    const co_dev_t *dev;
    uint16_t crc;
} sig_walk_t;

/* (co_od_each_sub) a stored value: where it is and what it is, into the
 * layout signature */
static void sig_add(void *ctx, const co_od_entry_t *e, const co_od_sub_t *s)
{
    sig_walk_t *w = (sig_walk_t *)ctx;
    uint8_t b[8];

    if (((s->flags & (CO_SUB_ROM | CO_SUB_HOOKIO)) == 0U) && (co_od_off(e, s) < w->dev->app_end)) {
        co_put_u16(&b[0], e->index);
        b[2] = s->sub;
        /* (a COB-ID's 16-bit form: a value of another size) */
        b[3] = s->type;
        co_put_u16(&b[4], co_od_off(e, s));
        co_put_u16(&b[6], s->size);
        w->crc = co_crc16(w->crc, b, 8U);
    }
}

/* Identifies the RAM layout: sizes, the CPU's byte order (the image holds
 * native integers) and, for every stored value, where it is and what it is
 * (and the mappable objects, which the stored PDO mapping entries name).
 * A set written with another layout is not loaded. */
static uint16_t layout_sig(const co_dev_t *dev)
{
    static const uint16_t order = 0x0102U;
    uint8_t b[8];
    uint16_t crc;
    sig_walk_t w;

    co_put_u16(&b[0], dev->ram_size);
    co_put_u16(&b[2], dev->comm_end);
    co_put_u16(&b[4], dev->app_end);
    (void)memcpy(&b[6], (const uint8_t *)&order, 2U);
    w.dev = dev;
    w.crc = co_crc16(0xFFFFU, b, 8U);
    co_od_each_sub(dev, sig_add, &w); /* every stored value */
    crc = w.crc;
    /* the mapping entries' 16-bit forms name rows of the mappable-object table */
    for (uint32_t k = 0U; k < dev->n_maps; k++) {
        co_put_u16(&b[0], dev->maps[k].index);
        b[2] = dev->maps[k].sub;
        crc = co_crc16(crc, b, 3U);
    }
    return crc;
}

/* Move the bytes of @p grp (groups are contiguous: comm, then app) from
 * @p src to @p dst (bank base addresses, AT_RAM, or AT_NONE for @p dst) and
 * run them through *crc. False on an NV error. */
static bool stream(co_node_t *node, uint32_t src, uint32_t dst, uint8_t grp, uint16_t *crc)
{
    const co_hal_ops_t *ops = node->hal.ops;
    uint32_t a = ((grp & GRP_COMM) != 0U) ? 0U : node->dev->comm_end;
    uint32_t hi = ((grp & GRP_APP) != 0U) ? node->dev->app_end : node->dev->comm_end;
    uint8_t buf[STORE_CHUNK];

    (void)memset(buf, 0, sizeof buf); /* (nv_read fills it before use) */
    for (; a < hi; a += STORE_CHUNK) {
        uint32_t n = (((hi - a) < STORE_CHUNK) ? (hi - a) : STORE_CHUNK);
        uint8_t *p = ((src == AT_RAM) || (dst == AT_RAM)) ? &node->ram[a] : buf;
        bool ok = true;
        if (src != AT_RAM) {
            ok = (ops->nv_read(node->hal.ctx, src + STORE_HDR + a, p, n) == 0);
        }
        if (ok && (dst != AT_RAM) && (dst != AT_NONE)) {
            ok = (ops->nv_write(node->hal.ctx, dst + STORE_HDR + a, p, n) == 0);
        }
        if (!ok) {
            return false;
        }
        *crc = co_crc16(*crc, p, n);
    }
    return true;
}

/* The bank holding the newest valid set (idx NO_BANK, groups 0: none); a
 * bank is valid when magic, format, layout and CRC match. *io_err is set
 * when the NV could not be read, *damaged when a bank of this layout newer
 * than the one chosen fails its CRC (a set damaged after it was written, or
 * a save cut short while it wrote its header). */
static store_bank_t newest(co_node_t *node, uint16_t sig, bool *io_err, bool *damaged)
{
    store_bank_t best = {0U, 0U, 0U, NO_BANK};
    bool bad = false;
    uint32_t bad_seq = 0U;

    for (uint8_t i = 0U; i < 2U; i++) {
        uint32_t base = i * bank_size(node);
        uint8_t h[STORE_HDR];
        bool ok = (node->hal.ops->nv_read(node->hal.ctx, base, h, STORE_HDR) == 0);
        if (ok && (co_get_u32(&h[0]) == STORE_MAGIC) && (co_get_u16(&h[8]) == sig) &&
            groups_valid(h[12]) && (h[13] == STORE_FORMAT)) {
            uint16_t crc = co_crc16(0xFFFFU, h, 14U);
            ok = stream(node, base, AT_NONE, (uint8_t)(h[12] & GRP_ALL), &crc);
            if (ok && (crc != co_get_u16(&h[14]))) {
                bad = true;
                bad_seq = co_get_u32(&h[4]);
            } else if (ok && ((best.idx == NO_BANK) ||
                              ((int32_t)(co_get_u32(&h[4]) - best.seq) > 0))) {
                best.seq = co_get_u32(&h[4]);
                best.groups = (uint8_t)(h[12] & GRP_ALL);
                best.restored = (uint8_t)((uint8_t)(h[12] >> GRP_RESTORED) & GRP_ALL);
                best.idx = i;
            } else {
                /* an older valid set */
            }
        }
        *io_err = *io_err || !ok;
    }
    *damaged = bad && ((best.idx == NO_BANK) || ((int32_t)(bad_seq - best.seq) > 0));
    return best;
}

/* What a command does to the stored set (commit): co_store_t's from_ram,
 * drop, mark, unmark. */

/* What a command writes: the newest set, the new set's groups and marks,
 * and the bank it goes to (the other one). */
typedef struct store_plan {
    store_bank_t old;
    uint32_t base;
    uint16_t sig;
    uint8_t held;
    uint8_t restored;
    bool noop;        /* nothing changes: nothing is written */
} store_plan_t;

static co_err_t plan(co_node_t *node, store_plan_t *p)
{
    const co_store_t *c = &node->store;
    bool io_err = false;
    bool damaged = false;

    p->sig = layout_sig(node->dev);
    p->old = newest(node, p->sig, &io_err, &damaged);
    p->held = (uint8_t)((p->old.groups & (uint8_t)~c->drop) | c->from_ram);
    p->restored = (uint8_t)((p->old.restored | c->mark) &
                            (uint8_t)~(c->unmark | c->from_ram) & p->held);
    p->base = (p->old.idx == 0U) ? bank_size(node) : 0U;
    /* restore: nothing of these groups is stored (or it is done) */
    p->noop = (c->from_ram == 0U) && (p->held == p->old.groups) &&
              (p->restored == p->old.restored);
    /* the previous set (and which bank is free) is unknown */
    return io_err ? CO_ERR_HW : CO_OK;
}

/* Write a new set into the other bank: the groups of from_ram from the RAM
 * image, the other groups the newest set holds (less drop) copied from it,
 * with their restored marks changed as mark / unmark say; data in address
 * order, the header last. Nothing is written when nothing changes. */
static co_err_t commit(co_node_t *node)
{
    const co_dev_t *dev = node->dev;
    store_plan_t p;
    uint8_t h[STORE_HDR];
    uint16_t crc;
    co_err_t err = plan(node, &p);

    if ((err != CO_OK) || p.noop) {
        return err;
    }
    co_put_u32(&h[0], STORE_MAGIC);
    co_put_u32(&h[4], p.old.seq + 1U);
    co_put_u16(&h[8], p.sig);
    co_put_u16(&h[10], dev->app_end);
    h[12] = (uint8_t)(p.held | (uint8_t)(p.restored << GRP_RESTORED));
    h[13] = STORE_FORMAT;
    crc = co_crc16(0xFFFFU, h, 14U);
    for (uint8_t grp = GRP_COMM; grp <= GRP_APP; grp = (uint8_t)(grp << 1U)) {
        uint32_t src = ((node->store.from_ram & grp) != 0U)
                           ? AT_RAM
                           : ((uint32_t)p.old.idx * bank_size(node));
        if (((p.held & grp) != 0U) && !stream(node, src, p.base, grp, &crc)) {
            return CO_ERR_HW;
        }
    }
    co_put_u16(&h[14], crc);
    return (node->hal.ops->nv_write(node->hal.ctx, p.base, h, STORE_HDR) != 0) ? CO_ERR_HW
                                                                                : CO_OK;
}

enum { STEP_IDLE = 0, STEP_ERASE, STEP_WRITE, STEP_DONE };

/* A command's end: a set written whole ends the report of a damaged one
 * (the EMCY service clears it, co_store_damaged). */
static co_err_t store_finish(co_node_t *node, co_err_t err)
{
    node->store.result = err;
    node->store.step = (uint8_t)STEP_DONE;
    if (err == CO_OK) {
        node->store.damaged = 0U;
    }
    /* the SDO server waiting for the end of an asynchronous command answers
     * in this round (its row comes before this one: co_node_process runs
     * a row touched during the pass once more), not at its next poll */
    co_svc_touch(node, CO_ROW_SDO);
    return err;
}

bool co_store_damaged(const co_node_t *node)
{
    return node->store.damaged != 0U;
}

bool co_store_busy(const co_node_t *node)
{
    return (node->store.step == (uint8_t)STEP_ERASE) || (node->store.step == (uint8_t)STEP_WRITE);
}

co_err_t co_store_result(const co_node_t *node)
{
    return node->store.result;
}

/* Start the command node->store describes: erase the bank it writes (with
 * nv_erase), write the set, and with an asynchronous HAL (nv_poll) leave
 * the rest to store_process. */
static co_err_t start_command(co_node_t *node)
{
    const co_hal_ops_t *ops = node->hal.ops;
    bool async = (ops->nv_poll != NULL);
    co_err_t err;

    if (ops->nv_erase != NULL) {
        store_plan_t p;
        err = plan(node, &p);
        if ((err != CO_OK) || p.noop) {
            return store_finish(node, err);
        }
        if (ops->nv_erase(node->hal.ctx, p.base, bank_size(node)) != 0) {
            return store_finish(node, CO_ERR_HW);
        }
        if (async) {
            node->store.step = (uint8_t)STEP_ERASE; /* written when the erase is done */
            return CO_OK;
        }
    }
    err = commit(node);
    if ((err != CO_OK) || !async) {
        return store_finish(node, err);
    }
    node->store.step = (uint8_t)STEP_WRITE;
    return CO_OK;
}

/* An asynchronous HAL at work: poll it every millisecond (the bus is served
 * meanwhile); once the erase is done the set is written, once the set is
 * durable the command ends (the SDO server answers at its next round,
 * within 1 ms). */
static uint32_t store_process(co_node_t *node, uint32_t next)
{
    uint32_t at = next;
    int r;

    if (!co_store_busy(node)) {
        return at;
    }
    r = node->hal.ops->nv_poll(node->hal.ctx);
    if (r == CO_NV_BUSY) {
        return co_deadline_min(node->now, at, node->now + 1000U);
    }
    if (r != 0) {
        (void)store_finish(node, CO_ERR_HW);
    } else if (node->store.step == (uint8_t)STEP_ERASE) {
        co_err_t err = commit(node); /* the RAM image as it is now */
        if (err != CO_OK) {
            (void)store_finish(node, err);
        } else {
            node->store.step = (uint8_t)STEP_WRITE;
            return co_deadline_min(node->now, at, node->now + 1000U);
        }
    } else {
        (void)store_finish(node, CO_OK);
    }
    return at;
}

#else /* !CO_STORAGE */

/* Without CO_STORAGE the node behaves as with a HAL without NV: no set is
 * ever read or written, and none of that code is built. */
bool co_store_busy(const co_node_t *node)
{
    (void)node;
    return false;
}
#endif

/* A sub-entry of 0x1010 / 0x1011 the core acts on: sub >= 1, UNSIGNED32,
 * with a stored value (command_sub), that is not a read-only const
 * (command_of: its value in RAM, or a writable const); its writes never
 * store, co_store_obj takes them. */
CO_INLINE bool command_sub(const co_od_sub_t *s)
{
    return (s->sub != 0U) && (s->type == (uint8_t)CO_UNSIGNED32) &&
           ((s->flags & CO_SUB_HOOKIO) == 0U);
}

CO_INLINE bool command_of(const co_od_sub_t *s)
{
    return command_sub(s) && ((s->flags & (CO_SUB_ROM | CO_SUB_W)) != CO_SUB_ROM);
}

bool co_store_is_command(const co_od_entry_t *e, const co_od_sub_t *s)
{
    return ((e->index == 0x1010U) || (e->index == 0x1011U)) && command_of(s);
}

#if CO_STORAGE
/* The highest sub-index of 0x1010 / 0x1011 the core acts on. */
static uint8_t last_sub(const co_node_t *node, uint16_t index)
{
    return ((index == 0x1011U) && (CO_SET(node, store.restore) == CO_RESTORE_SAVED)) ? 6U : 3U;
}

static co_err_t command(co_node_t *node, uint16_t index, uint8_t sub, const uint8_t *data)
{
    static const uint8_t groups_of_sub[7] = {0U, GRP_ALL, GRP_COMM, GRP_APP,
                                             GRP_ALL, GRP_COMM, GRP_APP};
    bool save = (index == 0x1010U);
    uint8_t grp = (sub <= last_sub(node, index)) ? groups_of_sub[sub] : 0U;
    co_store_t *c = &node->store;

    if ((grp == 0U) || !has_nv(node) ||
        (co_get_u32(data) != (save ? STORE_SIG_SAVE : STORE_SIG_LOAD))) {
        return CO_ERR_STORE;
    }
    if (co_store_busy(node)) {
        return CO_ERR_STORE_STATE; /* the previous command is still being written */
    }
    c->from_ram = 0U;
    c->drop = 0U;
    c->mark = 0U;
    c->unmark = 0U;
    if (save) {
        c->from_ram = grp;
    } else if (sub >= 4U) {
        c->unmark = grp; /* the saved set loads again */
    } else if (CO_SET(node, store.restore) == CO_RESTORE_SAVED) {
        c->mark = grp; /* defaults, the saved data kept for sub 4..6 */
    } else {
        c->drop = grp;
    }
    return start_command(node);
}

void co_store_forget_comm(co_node_t *node)
{
    /* (while a command is being written the stored set is not dropped) */
    if (has_nv(node) && !co_store_busy(node)) {
        node->store.from_ram = 0U;
        node->store.drop = GRP_COMM;
        node->store.mark = 0U;
        node->store.unmark = 0U;
        (void)start_command(node);
    }
}

#else
void co_store_forget_comm(co_node_t *node)
{
    (void)node; /* no set to drop */
}
#endif

#if CO_STORAGE
/* A reset of a kind: the node restored its area to defaults (co_node.c);
 * the stored groups of that area over them. */
static void store_reset(co_node_t *node, uint8_t kind)
{
    const co_dev_t *dev = node->dev;
    bool all = (kind == (uint8_t)CO_RESET_NODE);
    uint16_t end = all ? dev->ram_size : dev->comm_end;
    uint32_t cap = has_nv(node) ? 1U : 0U; /* bit 0: on command */

    if ((kind != (uint8_t)CO_RESET_NODE) && (kind != (uint8_t)CO_RESET_COMMUNICATION)) {
        return; /* values are loaded by the resets of a kind only */
    }
    node->store.damaged = 0U;
    if (cap != 0U) {
        bool io_err = false; /* an unreadable bank counts as invalid */
        bool damaged = false;
        store_bank_t b = newest(node, layout_sig(dev), &io_err, &damaged);
        uint8_t grp = (uint8_t)(b.groups & (uint8_t)~b.restored & (all ? GRP_ALL : GRP_COMM));
        uint16_t crc = 0U;
        if ((grp != 0U) && !stream(node, (uint32_t)b.idx * bank_size(node), AT_RAM, grp, &crc)) {
            co_od_restore(node, end);
        }
        /* reported after the boot-up by the EMCY service (co_store_damaged):
         * EMCY 0x5530, 0x1001, 0x1003 */
        node->store.damaged = damaged ? 1U : 0U;
    }
    /* What 0x1010 / 0x1011 read: the capability, whatever was written.
     * (Without CO_STORAGE they read 0: a const 0, odgen's choice for such a
     * build, or a value in RAM the engine never writes (co_store_obj) and
     * co_od_restore zeroed.) */
    for (uint16_t index = 0x1010U; index <= 0x1011U; index++) {
        const co_od_entry_t *e = co_od_find(dev->od, dev->od_count, index);
        for (uint32_t k = 1U; (e != NULL) && (k <= 0xFEU); k++) {
            co_od_sub_t sd;
            const co_od_sub_t *s = co_od_find_sub(dev, e, (uint8_t)k, &sd);
            if ((s != NULL) && co_store_is_command(e, s) && ((s->flags & CO_SUB_ROM) == 0U)) {
                uint32_t v = (s->sub <= last_sub(node, index)) ? cap : 0U;
                (void)memcpy(&node->ram[co_od_off(e, s)], (const uint8_t *)&v, 4U);
            }
        }
    }
}
#endif

/* ------------------------------------------------------------ service */

/* A checked write to 0x1010 / 0x1011 (the hook of those only:
 * co_svc_hooks): a sub-entry the core acts on (command_sub) saves or
 * restores, its value is never stored; any other is stored as usual. */
#if CO_STORAGE
co_err_t co_store_obj(co_node_t *node, uint8_t op, const co_od_entry_t *e,
                      const co_od_sub_t *s, const uint8_t *data, uint32_t len)
{
    (void)op;
    if (!command_of(s)) {
        co_od_commit(node, e, s, data, len);
        return CO_OK;
    }
    return command(node, e->index, s->sub, data);
}
#else
/* Without storage the hook is a check (CO_SVC_CHECK, before the
 * application's hook): a command is refused, there is no non-volatile
 * memory; any other value the engine stores. (command_sub: a read-only
 * const, which only an RPDO could write, keeps its value either way.) */
co_err_t co_store_obj(co_node_t *node, uint8_t op, const co_od_entry_t *e,
                      const co_od_sub_t *s, const uint8_t *data, uint32_t len)
{
    (void)node;
    (void)op;
    (void)e;
    (void)data;
    (void)len;
    return command_sub(s) ? CO_ERR_STORE : CO_OK;
}
#endif

#if CO_STORAGE
const co_service_t co_svc_store = {
    store_reset, NULL, store_process,
};
#endif
/* (without storage the service has nothing to do: no row in co_services[]) */
