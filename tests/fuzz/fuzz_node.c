/*
 * libFuzzer target: the frame entry points of one node (co_node_rx,
 * co_node_process, and the device layer's co_device_process), driven by a sequence of
 * frames, time steps and TX-path states taken from the input. Built twice:
 * a generic-301 node (its plug-in devices/generic_301.c: DOMAIN and veto hooks)
 * and, with FUZZ_CIA402, a cia402 node with its CiA 402 profile on the
 * simulated plant. Beyond memory errors and undefined behaviour (ASan,
 * UBSan) every step checks the invariants below; a violation aborts with
 * its reason on stderr.
 *
 *  1. No frame with DLC > 8, no extended or remote frame from the node.
 *  2. No frame on a restricted or foreign COB-ID: only the node's SDO
 *     (0x580+id) and error-control (0x700+id) identifiers (for the node-ID
 *     it starts with and the one LSS gives it), an LSS slave's 0x7E4, the EMCY,
 *     SYNC, TIME and TPDO identifiers its dictionary has configured for
 *     sending at some time during the run.
 *  3. Const values (CO_SUB_CONST, ROM) never change; a download to a
 *     read-only or const object is never confirmed.
 *  4. co_node_process never returns a deadline at or before its now (one
 *     in the past or at now would make a caller's loop spin).
 *  5. An SDO initiate request (expedited/segmented/block up- or download)
 *     to an idle server of a node in Pre-operational or Operational, with
 *     the TX path free, gets exactly one answer (a save or restore on an
 *     asynchronous NV: once the set is durable, at the next round); no
 *     request gets more than
 *     one, except the sub-blocks of a block upload and answers to earlier
 *     requests that were held back (TX path full) and go out now; a client
 *     abort none.
 *
 * Input: records of one opcode byte and its operands (see step()).
 */
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "co/co_node.h"

#include "co/co_device.h"
#include "co_devices.h"

#ifdef FUZZ_CIA402
#include "cia402.h"
#define NODE_ID 2U
#define DEVICE co_device_cia402
#define DEV_CONFIG cia402_config
typedef cia402_node_t dev_node_t;
#else
#include "generic_301.h"
#define NODE_ID 5U
#define DEVICE co_device_generic_301
#define DEV_CONFIG generic_301_config
typedef generic_301_node_t dev_node_t;
#endif

#define NV_SIZE 32768U
/* co_node_t.tx_hold: the SDO server's answer waits for the TX path
 * (stack/src/co_priv.h, CO_TXH_SDO) */
#define FZ_TX_SDO 0x04U
#define SNAP_MAX 4096U

typedef struct fz {
    dev_node_t n;
    co_device_run_t run;        /* the device layer: profile parts on simulated plants, plug-in */
    uint64_t mem[(320U * 1024U) / 8U]; /* generic-301: two DOMAINs of 128 KiB */
    uint32_t now;
    unsigned refuse;            /* TX path full for this many sends */
    unsigned sent;              /* frames the node sent */
    unsigned sdo_answers;       /* frames on 0x580+id */
    uint8_t last_sdo[8];        /* the last of them */
    unsigned nv_busy;           /* asynchronous NV: busy answers still to give */
    bool store_wait;            /* an SDO download started a save: its answer is deferred */
    uint8_t allowed[256];       /* bit per COB-ID the node may send on */
    uint8_t nv[NV_SIZE];
    uint8_t snap[SNAP_MAX];     /* const values at the start */
    uint32_t snap_len;
    const co_frame_t *rx;       /* the frame being handled (for reports) */
    bool trace;                 /* FUZZ_TRACE set: every frame on stderr */
} fz_t;

static fz_t fz;

static void fail(const char *what)
{
    char txt[64] = "";
    if (fz.rx != NULL) {
        int n = snprintf(txt, sizeof txt, " (handling %03X", (unsigned)(fz.rx->id & 0x7FFU));
        for (uint8_t i = 0U; (i < fz.rx->dlc) && (i < 8U) && (n > 0) && ((size_t)n < sizeof txt); i++) {
            n += snprintf(&txt[n], sizeof txt - (size_t)n, " %02X", fz.rx->data[i]);
        }
        (void)snprintf(&txt[n], sizeof txt - (size_t)n, ")");
    }
    (void)fprintf(stderr, "fuzz invariant violated: %s%s\n", what, txt);
    abort();
}

static bool restricted(uint32_t id)
{
    return (id <= 0x07FU) || ((id >= 0x101U) && (id <= 0x180U)) ||
           ((id >= 0x581U) && (id <= 0x5FFU)) || ((id >= 0x601U) && (id <= 0x67FU)) ||
           ((id >= 0x6E0U) && (id <= 0x6FFU)) || (id >= 0x701U);
}

static void allow(uint32_t id)
{
    fz.allowed[(id & 0x7FFU) >> 3U] |= (uint8_t)(1U << (id & 7U));
}

static bool is_allowed(uint32_t id)
{
    return (fz.allowed[(id & 0x7FFU) >> 3U] & (uint8_t)(1U << (id & 7U))) != 0U;
}

/* A COB-ID the core reads, at @p p in the RAM image: its UNSIGNED32 from
 * its 16-bit form (co_od.h, CO_SUB_COB16) */
static uint32_t cob_at(const uint8_t *p)
{
    uint16_t v;
    (void)memcpy(&v, p, sizeof v);
    return co_od_cob_u32(v);
}

static uint32_t ram_cob(uint16_t off)
{
    return cob_at(&fz.n.node.ram[off]);
}

/* The identifiers the node's configuration lets it send on now (a frame
 * held back while the TX path was full may go out after a change: every
 * identifier allowed at some time stays allowed). */
static void update_allowed(void)
{
    const co_node_t *nd = &fz.n.node;
    const co_dev_t *dev = nd->dev;

    uint8_t id = co_node_id(nd);

    allow(0x580U + NODE_ID);
    allow(0x700U + NODE_ID);
    allow(0x080U + NODE_ID); /* EMCY default, while 0x1014 is absent */
    if ((id >= 1U) && (id <= 127U)) {
        /* LSS may give the node another node-ID (configure node-ID, then a
         * reset communication): its SDO, error-control and EMCY identifiers */
        allow(0x580U + id);
        allow(0x700U + id);
        allow(0x080U + id);
    }
    if (dev->set.lss.slave != 0U) {
        allow(0x7E4U); /* LSS slave -> master (CiA 305) */
    }
    /* 0x1014, 0x1005 at their places (co_node.h: CO_RAM_*; 0 without them) */
    if ((ram_cob(CO_RAM_1014) & 0x80000000UL) == 0U) {
        allow(ram_cob(CO_RAM_1014));
    }
    if ((ram_cob(CO_RAM_1005) & 0x40000000UL) != 0U) {
        allow(ram_cob(CO_RAM_1005));
    }
    if ((nd->time.cob != NULL) && ((cob_at(nd->time.cob) & 0x40000000UL) != 0U)) {
        allow(cob_at(nd->time.cob));
    }
    for (uint16_t i = dev->n_rpdo; i < (uint16_t)(dev->n_rpdo + dev->n_tpdo); i++) {
        uint32_t cob = ram_cob(dev->pdo[i].cob);
        if ((cob & 0x80000000UL) == 0U) {
            allow(cob);
        }
    }
}

static int hal_send(void *ctx, const co_frame_t *f)
{
    uint32_t id = f->id & 0x7FFU;

    (void)ctx;
    if (fz.refuse > 0U) {
        fz.refuse--;
        return 1;
    }
    if (f->dlc > 8U) {
        fail("frame with DLC > 8");
    }
    if ((f->id & ~0x7FFUL) != 0U) {
        fail("extended or remote frame sent");
    }
    if (!is_allowed(id)) {
        fail(restricted(id) ? "frame on a restricted COB-ID" : "frame on a foreign COB-ID");
    }
    fz.sent++;
    if (fz.trace) {
        (void)fprintf(stderr, "%10u  tx %03X", (unsigned)fz.now, (unsigned)id);
        for (uint8_t i = 0U; i < f->dlc; i++) {
            (void)fprintf(stderr, " %02X", f->data[i]);
        }
        (void)fprintf(stderr, "\n");
    }
    if (id == (0x580U + NODE_ID)) {
        fz.sdo_answers++;
        (void)memcpy(fz.last_sdo, f->data, 8U);
    }
    return 0;
}

static int nv_read(void *ctx, uint32_t addr, uint8_t *buf, uint32_t len)
{
    (void)ctx;
    if ((addr > NV_SIZE) || (len > (NV_SIZE - addr))) {
        return -1;
    }
    (void)memcpy(buf, &fz.nv[addr], len);
    return 0;
}

static int nv_write(void *ctx, uint32_t addr, const uint8_t *buf, uint32_t len)
{
    (void)ctx;
    if ((addr > NV_SIZE) || (len > (NV_SIZE - addr))) {
        return -1;
    }
    (void)memcpy(&fz.nv[addr], buf, len);
    return 0;
}

static int nv_write_async(void *ctx, uint32_t addr, const uint8_t *buf, uint32_t len)
{
    fz.nv_busy = 3U;
    return nv_write(ctx, addr, buf, len);
}

static int nv_erase(void *ctx, uint32_t addr, uint32_t len)
{
    (void)ctx;
    if (((addr % 64U) != 0U) || ((len % 64U) != 0U) || (addr > NV_SIZE) ||
        (len > (NV_SIZE - addr))) {
        fail("nv_erase outside whole erase units");
    }
    (void)memset(&fz.nv[addr], 0xFF, len);
    fz.nv_busy = 3U;
    return 0;
}

static int nv_poll(void *ctx)
{
    (void)ctx;
    if (fz.nv_busy > 0U) {
        fz.nv_busy--;
        return CO_NV_BUSY;
    }
    return 0;
}

static const co_hal_ops_t hal_ops = {.send = hal_send, .nv_read = nv_read, .nv_write = nv_write};
/* the same with asynchronous writes and an erase unit of 64 bytes (inputs
 * whose first byte is 0xA5): saves, restores and LSS stores in the
 * background, their answers deferred */
static const co_hal_ops_t hal_ops_async = {.send = hal_send,
                                           .nv_read = nv_read,
                                           .nv_write = nv_write_async,
                                           .nv_poll = nv_poll,
                                           .nv_erase = nv_erase,
                                           .nv_erase_unit = 64U};

/* ------------------------------------------------------------ const values */

static bool is_const(const co_od_sub_t *s)
{
    return (s->flags & (CO_SUB_CONST | CO_SUB_ROM)) != 0U;
}

static uint32_t const_values(uint8_t *out, uint32_t cap)
{
    const co_dev_t *dev = fz.n.node.dev;
    uint32_t at = 0U;

    for (uint16_t i = 0U; i < dev->od_count; i++) {
        const co_od_entry_t *e = &dev->od[i];
        for (uint32_t x = 0U; x < 256U; x++) {
            co_od_sub_t sd;
            const co_od_sub_t *s = co_od_find_sub(dev, e, (uint8_t)x, &sd);
            uint32_t len = 0U;
            if ((s == NULL) || !is_const(s) || ((s->flags & CO_SUB_HOOKIO) != 0U) || (s->size > 64U) ||
                ((at + s->size) > cap)) {
                continue;
            }
            if (co_od_read(&fz.n.node, e->index, s->sub, &out[at], s->size, &len) == CO_OK) {
                at += len;
            }
        }
    }
    return at;
}

static void check_const(void)
{
    uint8_t now[SNAP_MAX];
    uint32_t len = const_values(now, sizeof now);

    if ((len != fz.snap_len) || (memcmp(now, fz.snap, len) != 0)) {
        fail("a const value changed");
    }
}

/* Is (index, sub) read-only or const (not writable over SDO)? */
static bool not_writable(uint16_t index, uint8_t sub)
{
    const co_dev_t *dev = fz.n.node.dev;
    const co_od_entry_t *e = co_od_find(dev->od, dev->od_count, index);
    co_od_sub_t sub_buf;
    const co_od_sub_t *s = (e != NULL) ? co_od_find_sub(dev, e, sub, &sub_buf) : NULL;

    return (s != NULL) && (((s->flags & CO_SUB_W) == 0U) || ((s->flags & CO_SUB_CONST) != 0U));
}

/* ------------------------------------------------------------ steps */

static void process(void)
{
    uint32_t d;
    bool done_before = !co_store_busy(&fz.n.node);
    unsigned answers = fz.sdo_answers;

    update_allowed();
    d = co_node_process(&fz.n.node, fz.now);
    if (fz.store_wait) {
        /* a save's answer waits until the set is durable, then comes at the
         * next round (or never: the client aborted, a reset, Stopped) */
        if ((fz.sdo_answers != answers) || (fz.n.node.sdo.state == 0U)) {
            fz.store_wait = false;
        } else if (done_before && ((fz.n.node.tx_hold & FZ_TX_SDO) == 0U)) {
            fail("a save was durable but its SDO answer did not come");
        } else {
            /* still being written, or the answer is held back (TX path full) */
        }
    }
    if ((d != CO_NO_DEADLINE) && ((int32_t)(d - fz.now) <= 0)) {
        fail("co_node_process returned a deadline at or before its now");
    }
    (void)co_device_process(&fz.run, fz.now);
}

static void deliver(const co_frame_t *f)
{
    uint32_t id = f->id & 0x7FFU;
    bool sdo = (id == (0x600U + NODE_ID)) && ((f->id & (CO_FRAME_RTR | CO_FRAME_EFF)) == 0U);
    uint8_t st = fz.n.node.nmt;
    bool live = (st == (uint8_t)CO_NMT_PRE_OPERATIONAL) || (st == (uint8_t)CO_NMT_OPERATIONAL);
    bool idle = (fz.n.node.sdo.state == 0U) && (fz.n.node.tx_hold == 0U) && (fz.refuse == 0U);
    unsigned before = fz.sdo_answers;
    /* the answer to an earlier request, held back, may go out now */
    unsigned held_sdo = ((fz.n.node.tx_hold & FZ_TX_SDO) != 0U) ? 1U : 0U;
    uint8_t cs = f->data[0];
    uint8_t ccs = (uint8_t)(cs >> 5U);

    update_allowed();
    fz.rx = f;
    if (fz.trace) {
        (void)fprintf(stderr, "%10u  rx %03X%s%s", (unsigned)fz.now, (unsigned)id,
                      ((f->id & CO_FRAME_EFF) != 0U) ? " (29-bit)" : "",
                      ((f->id & CO_FRAME_RTR) != 0U) ? " R" : "");
        for (uint8_t i = 0U; i < f->dlc; i++) {
            (void)fprintf(stderr, " %02X", f->data[i]);
        }
        (void)fprintf(stderr, "   (nmt %02X sdo %u tx_hold %02X)\n", fz.n.node.nmt, fz.n.node.sdo.state,
                      fz.n.node.tx_hold);
    }
    co_node_rx(&fz.n.node, f, fz.now);
    if (fz.trace) {
        (void)fprintf(stderr, "            after: nmt %02X sdo %u tx_hold %02X refuse %u n_rx %u:", fz.n.node.nmt,
                      fz.n.node.sdo.state, fz.n.node.tx_hold, fz.refuse, fz.n.node.n_rx);
        for (uint8_t i = 0U; i < fz.n.node.n_rx; i++) {
            (void)fprintf(stderr, " %03X/%u", (unsigned)(fz.n.node.rx[i] & 0x7FFU), (unsigned)(fz.n.node.rx[i] >> 11U));
        }
        (void)fprintf(stderr, "\n");
    }
    if (sdo && live && (f->dlc == 8U)) {
        unsigned got = fz.sdo_answers - before;
        bool initiate = (ccs == 1U) || (ccs == 2U) || (ccs == 5U) || (ccs == 6U);
        bool sub_block = (cs == 0xA3U) || ((cs & 0xE3U) == 0xA2U);
        bool deferred = idle && (got == 0U) && (ccs == 1U) && co_store_busy(&fz.n.node) &&
                        (fz.n.node.sdo.state != 0U);
        if (deferred) {
            fz.store_wait = true; /* answered once durable (process) */
        }
        if (idle && initiate && (got != 1U) && !deferred) {
            fail("an SDO request to an idle server got no answer or more than one");
        }
        if ((ccs == 4U) && (got != 0U) && idle) {
            fail("a client abort was answered");
        }
        if (!sub_block && (got > (1U + held_sdo))) {
            fail("an SDO request got more than one answer");
        }
        if (idle && ((ccs == 1U) || (ccs == 6U)) && (got == 1U) &&
            not_writable((uint16_t)(f->data[1] | ((uint16_t)f->data[2] << 8U)), f->data[3]) &&
            (fz.last_sdo[0] != 0x80U)) {
            fail("a download to a read-only or const object was accepted");
        }
    }
    fz.rx = NULL;
}

/* Frames worth aiming at, by selector. */
static uint32_t pick_id(uint8_t sel, uint8_t raw)
{
    static const uint16_t base[] = {0x000U, 0x080U, 0x100U, 0x600U + NODE_ID, 0x700U + NODE_ID,
                                    0x200U + NODE_ID, 0x300U + NODE_ID, 0x400U + NODE_ID,
                                    0x500U + NODE_ID, 0x180U + NODE_ID, 0x280U + NODE_ID,
                                    0x77EU, 0x701U, 0x580U + NODE_ID, 0x081U, 0x7E5U};
    if (sel < 0xC0U) {
        return base[sel % (sizeof base / sizeof base[0])];
    }
    return ((uint32_t)(sel & 0x07U) << 8U) | raw;
}

static size_t step(const uint8_t *d, size_t n)
{
    uint8_t op;

    if (n == 0U) {
        return 0U;
    }
    op = d[0];
    switch (op & 0x07U) {
    case 0U:
    case 1U:
    case 2U: { /* a frame: selector, raw id, dlc/rtr, data */
        co_frame_t f;
        uint8_t len;
        if (n < 4U) {
            return n;
        }
        (void)memset(&f, 0, sizeof f);
        f.id = pick_id(d[1], d[2]);
        if ((d[3] & 0x80U) != 0U) {
            f.id |= CO_FRAME_RTR;
        }
        if ((d[3] & 0x40U) != 0U) {
            f.id |= CO_FRAME_EFF; /* ignored by the node */
        }
        f.dlc = (uint8_t)(d[3] & 0x0FU);
        if (f.dlc > 8U) {
            f.dlc = 8U;
        }
        len = ((f.id & CO_FRAME_RTR) != 0U) ? 0U : f.dlc;
        if ((size_t)4U + len > n) {
            len = (uint8_t)(n - 4U);
        }
        (void)memcpy(f.data, &d[4], len);
        deliver(&f);
        if ((op & 0x08U) != 0U) {
            process(); /* as a port does after each frame */
        }
        return 4U + (size_t)len;
    }
    case 3U: /* time passes: up to 65 ms in 1 us, or up to 6.5 s */
        if (n < 3U) {
            return n;
        }
        fz.now += (uint32_t)(d[1] | ((uint32_t)d[2] << 8U)) * (((op & 0x08U) != 0U) ? 100U : 1U);
        process();
        return 3U;
    case 4U: /* the caller's clock jumps: a stall (up to 71 minutes) */
        if (n < 3U) {
            return n;
        }
        fz.now += ((uint32_t)d[1] << 24U) | ((uint32_t)d[2] << 16U);
        process();
        return 3U;
    case 5U: /* the TX path refuses the next sends */
        if (n < 2U) {
            return n;
        }
        fz.refuse = d[1];
        return 2U;
    case 6U: /* a run of 1 ms process calls */
        if (n < 2U) {
            return n;
        }
        for (uint8_t k = 0U; k < (uint8_t)(d[1] & 0x3FU); k++) {
            fz.now += 1000U;
            process();
        }
        return 2U;
    default: /* process now */
        process();
        return 1U;
    }
}

static void start(bool async)
{
    co_node_config_t cfg;

    (void)memset(&fz, 0, sizeof fz);
    (void)memset(fz.nv, 0xFF, sizeof fz.nv);
    fz.now = 1000U;
    fz.trace = getenv("FUZZ_TRACE") != NULL;
    if ((co_device_mem_size(&DEVICE, true) > sizeof fz.mem) ||
        (co_device_init(&fz.run, &DEVICE, fz.mem, sizeof fz.mem, NULL, NULL, fz.now) != CO_OK)) {
        abort();
    }
    DEV_CONFIG(&fz.n, &cfg);
    cfg.cb = co_device_callbacks(&fz.run);
    cfg.hal.ops = async ? &hal_ops_async : &hal_ops;
    cfg.hal.ctx = &fz;
    cfg.node_id = NODE_ID;
    /* the boot-up: before co_node_init binds the objects */
    allow(0x700U + NODE_ID);
    allow(0x080U + NODE_ID);
    if (co_node_init(&fz.n.node, &cfg, fz.now) != CO_OK) {
        abort();
    }
    if (co_device_attach(&fz.run, &fz.n.node, fz.now) != CO_OK) {
        abort();
    }
    update_allowed();
    fz.snap_len = const_values(fz.snap, sizeof fz.snap);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    size_t at = 0U;
    unsigned k = 0U;

    start((size > 0U) && (data[0] == 0xA5U));
    while (at < size) {
        at += step(&data[at], size - at);
        if ((++k & 63U) == 0U) {
            check_const();
        }
    }
    check_const();
    return 0;
}
