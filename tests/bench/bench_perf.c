/*
 * Instructions per frame on the workloads of ../shared/perf-reference.md
 * (W1..W6, the idle tick), as a port calls the stack. tools/bench-instructions
 * runs one workload per process under callgrind (--instr-atstart=no): only
 * the measured loop between CALLGRIND_START_INSTRUMENTATION and
 * CALLGRIND_STOP_INSTRUMENTATION is counted.
 *
 *   bench_perf_<dev> WORKLOAD MODE
 *     WORKLOAD  w1 w2 w2b w3 w4 w5 idle w6
 *     MODE      port: the frame, then co_node_process (the port's 1 ms tick)
 *               rx:   co_node_rx only (receive only)
 *
 * The node: node-ID 5, heartbeat producer 1000 ms, 8 unused consumer
 * entries, RPDO1 0x205 type 254, TPDO1..4 0x185..0x485 type 1 with 1/2/3/4
 * mapped objects, configured through the dictionary per CiA 301 (COB-ID
 * invalid, mapping count 0, entries, count, COB-ID valid) before NMT start;
 * 1 ms of time per frame, 10,000 frames. Built per device (BENCH_CN): on
 * seg-ex the PDOs map objects of CANopenNode's example dictionary
 * ("dictionary" mappings), on seg-app / cono-app the application's objects
 * 0x2000..0x2003 ("app" mappings); W6 reads the 100,000-byte DOMAIN 0x2100
 * of cono-app by block upload. Every run is verified afterwards (answers,
 * dictionary values, every TPDO's payload, frames sent); a failed check
 * prints "FAIL ..." and exits 1.
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <valgrind/callgrind.h>

#include "co/co_endian.h"
#include "co/co_node.h"

#define XCAT(a, b) a##b
#define CAT(a, b)  XCAT(a, b)
#define STR(a)     #a
#define XSTR(a)    STR(a)
#include XSTR(BENCH_CN.h)

#define NODE_T   CAT(BENCH_CN, _node_t)
#define CONFIG   CAT(BENCH_CN, _config)
#define NODE_ID  5U
#define FRAMES   10000U
#define TICK_US  1000U
#define DOM_SIZE 100000U

static NODE_T slave;
static co_node_t *node = &slave.node;
static uint32_t now = 1000000U;
static int failed;

/* The TX path: every frame taken and counted; the last frame of each
 * function code (COB-ID >> 7: TPDO1..4 3, 5, 7, 9, SDO 11, heartbeat 14)
 * kept for the checks; block upload segments copied into the received
 * DOMAIN image (blk: where the current block's first segment goes). */
static struct {
    co_frame_t last[16];
    uint32_t n;
    uint32_t hb;
    uint8_t *blk;
} tx;

static int bench_send(void *ctx, const co_frame_t *f)
{
    uint32_t fc = (f->id >> 7U) & 0x0FU;

    (void)ctx;
    tx.last[fc] = *f;
    tx.n++;
    if (fc == 14U) {
        tx.hb++;
    } else if ((fc == 11U) && (tx.blk != NULL) && ((f->data[0] & 0x7FU) != 0U)) {
        (void)memcpy(&tx.blk[((f->data[0] & 0x7FU) - 1U) * 7U], &f->data[1], 7U);
    } else {
        /* kept in last[] */
    }
    return 0;
}

static const co_hal_ops_t ops = {.send = bench_send};

static void check(int ok, const char *what)
{
    if (!ok) {
        printf("FAIL %s\n", what);
        failed = 1;
    }
}

/* The last frame sent with function code @p fc. */
static const co_frame_t *sent(uint32_t fc)
{
    return &tx.last[fc];
}

static int frame_is(const co_frame_t *f, uint16_t id, uint8_t dlc, const uint8_t *data)
{
    return (f->id == id) && (f->dlc == dlc) && (memcmp(f->data, data, dlc) == 0);
}

static co_frame_t frame(uint16_t id, uint8_t dlc, const uint8_t *data)
{
    co_frame_t f;

    (void)memset(&f, 0, sizeof f);
    f.id = id;
    f.dlc = dlc;
    if (dlc > 0U) {
        (void)memcpy(f.data, data, dlc);
    }
    return f;
}

static void wr(uint16_t index, uint8_t sub, uint32_t v, uint32_t len)
{
    uint8_t b[4];
    char what[48];

    co_put_u32(b, v);
    (void)snprintf(what, sizeof what, "configure 0x%04X:%u", index, sub);
    check(co_od_write(node, index, sub, b, len, false) == CO_OK, what);
}

static uint32_t rd(uint16_t index, uint8_t sub)
{
    uint8_t b[4] = {0};
    uint32_t len = 0U;

    check(co_od_read(node, index, sub, b, sizeof b, &len) == CO_OK, "read back");
    return co_get_u32(b);
}

/* A PDO per CiA 301: invalid, mapping count 0, entries, count, valid. */
static void map_pdo(uint16_t comm, uint32_t cob, uint8_t type, const uint32_t *map, uint8_t n)
{
    uint16_t mapi = (uint16_t)(comm + 0x200U);

    wr(comm, 1U, cob | 0x80000000UL, 4U);
    wr(comm, 2U, type, 1U);
    wr(mapi, 0U, 0U, 1U);
    for (uint8_t k = 0U; k < n; k++) {
        wr(mapi, (uint8_t)(k + 1U), map[k], 4U);
    }
    wr(mapi, 0U, n, 1U);
    wr(comm, 1U, cob, 4U);
}

/* The mappings: RPDO1, then TPDO1..4 taking the first 1, 2, 3, 4 entries. */
#ifdef BENCH_APP
static const uint32_t rpdo_map[4] = {0x20000008UL, 0x20010008UL, 0x20020010UL, 0x20030020UL};
static const uint32_t tpdo_map[4] = {0x20030020UL, 0x20020010UL, 0x20000008UL, 0x20010008UL};
#else
/* CANopenNode's example: 0x1280:01 (32 bit), 0x1280:02 (16 of 32 bits), two
 * dummy UNSIGNED8; the TPDOs map communication objects, two of them in part. */
static const uint32_t rpdo_map[4] = {0x12800120UL, 0x12800210UL, 0x00050008UL, 0x00050008UL};
static const uint32_t tpdo_map[4] = {0x12800120UL, 0x12800210UL, 0x10010008UL, 0x12000108UL};
#endif
static const uint8_t tpdo_len[4] = {4U, 6U, 7U, 8U};

/* W6: the DOMAIN 0x2100, served by the application's read hook. */
#ifdef BENCH_HOOK
static uint8_t domain[DOM_SIZE];
static uint8_t got[DOM_SIZE + 7U];

static co_err_t domain_read(void *ctx, co_od_io_t *io)
{
    uint32_t n = DOM_SIZE - io->offset;

    (void)ctx;
    if (io->offset >= DOM_SIZE) {
        n = 0U;
    } else if (n > io->len) {
        n = io->len;
    } else {
        /* the rest */
    }
    (void)memcpy(io->buf, &domain[io->offset], n);
    io->len = n;
    io->total = DOM_SIZE;
    io->last = (io->offset + n) >= DOM_SIZE;
    return CO_OK;
}
#endif

static void setup(void)
{
    co_node_config_t cfg;
    static const uint8_t start[2] = {0x01, NODE_ID};
    co_frame_t f;

    CONFIG(&slave, &cfg);
    cfg.hal.ops = &ops;
    cfg.node_id = NODE_ID;
    if (co_node_init(node, &cfg, now) != CO_RESULT_OK) {
        printf("FAIL co_node_init\n");
        exit(1);
    }
#ifdef BENCH_HOOK
    {
        static const co_od_hook_t hook = {domain_read, NULL, NULL};
        for (uint32_t k = 0U; k < DOM_SIZE; k++) {
            domain[k] = (uint8_t)((k * 7U) ^ (k >> 8U));
        }
        check(co_od_bind_hook(node, 0x2100U, &hook) == CO_RESULT_OK, "bind 0x2100");
    }
#endif
    wr(0x1017U, 0U, 1000U, 2U);
    map_pdo(0x1400U, 0x200U + NODE_ID, 254U, rpdo_map, 4U);
    for (uint16_t k = 0U; k < 4U; k++) {
        map_pdo((uint16_t)(0x1800U + k), 0x40000000UL + 0x180U + (0x100U * k) + NODE_ID, 1U,
                tpdo_map, (uint8_t)(k + 1U));
    }
    f = frame(0x000U, 2U, start);
    co_node_rx(node, &f, now);
    (void)co_node_process(node, now);
    check(co_node_nmt_state(node) == CO_NMT_OPERATIONAL, "NMT start");
    (void)memset(&tx, 0, sizeof tx);
}

/* The measured loop: the frame @p f, each with a data byte @p vary set to
 * the frame's number (0xFF: none), then the port's 1 ms tick. */
static void run_frames(co_frame_t *f, int port, uint8_t vary, uint32_t *poke)
{
    CALLGRIND_START_INSTRUMENTATION;
    for (uint32_t i = 1U; i <= FRAMES; i++) {
        if (vary < 8U) {
            f->data[vary] = (uint8_t)i;
        }
        if (poke != NULL) {
            *poke = i;
        }
        co_node_rx(node, f, now);
        if (port) {
            (void)co_node_process(node, now);
        }
        now += TICK_US;
    }
    CALLGRIND_STOP_INSTRUMENTATION;
}

/* Heartbeats of a port loop of FRAMES ms at 1000 ms; none without the tick. */
static void check_hb(int port)
{
    check(port ? ((tx.hb >= (FRAMES / 1000U) - 1U) && (tx.hb <= (FRAMES / 1000U) + 1U))
               : (tx.hb == 0U),
          "heartbeats sent");
}

static void w_sdo(int port, const uint8_t *req, const uint8_t *ans)
{
    co_frame_t f = frame(0x600U + NODE_ID, 8U, req);

    run_frames(&f, port, 0xFFU, NULL);
    check(tx.n - tx.hb == FRAMES, "one SDO answer per request");
    check(frame_is(sent(11U), 0x580U + NODE_ID, 8U, ans), "SDO answer");
}

static void w1(int port)
{
    static const uint8_t req[8] = {0x40, 0x00, 0x10, 0x00, 0, 0, 0, 0};
    static const uint8_t ans[8] = {0x43, 0x00, 0x10, 0x00, 0x91, 0x01, 0x0F, 0x00};

    w_sdo(port, req, ans);
    check_hb(port);
}

static void w2(int port)
{
    static const uint8_t req[8] = {0x2B, 0x17, 0x10, 0x00, 0xE8, 0x03, 0, 0};
    static const uint8_t ans[8] = {0x60, 0x17, 0x10, 0x00, 0, 0, 0, 0};

    w_sdo(port, req, ans);
    check(rd(0x1017U, 0U) == 1000U, "0x1017 value");
    check_hb(port); /* the writes do not restart the heartbeat's cycle */
}

static void w2b(int port)
{
    static const uint8_t req[8] = {0x2B, 0x15, 0x10, 0x00, 0x64, 0x00, 0, 0};
    static const uint8_t ans[8] = {0x60, 0x15, 0x10, 0x00, 0, 0, 0, 0};

    w_sdo(port, req, ans);
    check(rd(0x1015U, 0U) == 100U, "0x1015 value");
    check_hb(port);
}

static void w3(int port)
{
    static const uint8_t d[8] = {0x00, 0x12, 0x34, 0x56, 0xAB, 0xCD, 0xEE, 0xFF};
    co_frame_t f = frame(0x200U + NODE_ID, 8U, d);
    uint8_t last = (uint8_t)FRAMES;

    run_frames(&f, port, 0U, NULL);
    check(tx.n == tx.hb, "no frame but heartbeats");
    check_hb(port);
#ifdef BENCH_APP
    check(rd(0x2000U, 0U) == last, "0x2000 value");
    check(rd(0x2001U, 0U) == 0x12U, "0x2001 value");
    check(rd(0x2002U, 0U) == 0x5634U, "0x2002 value");
    check(rd(0x2003U, 0U) == 0xFFEECDABUL, "0x2003 value");
#else
    check(rd(0x1280U, 1U) == (0x56341200UL | last), "0x1280:1 value");
    check(rd(0x1280U, 2U) == 0xCDABU, "0x1280:2 value (16 of 32 bits)");
#endif
}

static void w4(int port)
{
    co_frame_t f = frame(0x080U, 0U, NULL);
    uint32_t *poke = (uint32_t *)co_od_value_ptr(node, (uint16_t)(tpdo_map[0] >> 16U),
                                                 (uint8_t)(tpdo_map[0] >> 8U));
    uint8_t all[8];

    check(poke != NULL, "value of the first mapped object");
    if (poke == NULL) {
        return;
    }
#ifdef BENCH_APP
    *(uint16_t *)co_od_value_ptr(node, 0x2002U, 0U) = 0xBEEFU;
    *(uint8_t *)co_od_value_ptr(node, 0x2000U, 0U) = 0x11U;
    *(uint8_t *)co_od_value_ptr(node, 0x2001U, 0U) = 0x22U;
    co_put_u32(&all[0], FRAMES);
    co_put_u16(&all[4], 0xBEEFU);
    all[6] = 0x11U;
    all[7] = 0x22U;
#else
    wr(0x1280U, 2U, 0x12345678UL, 4U);
    co_put_u32(&all[0], FRAMES);
    co_put_u16(&all[4], 0x5678U);
    all[6] = 0x00U;       /* 0x1001: no error */
    all[7] = NODE_ID;     /* 0x1200:01 = 0x600 + node-ID, low 8 bits */
#endif
    run_frames(&f, port, 0xFFU, poke);
    check(tx.n - tx.hb == 4U * FRAMES, "4 TPDOs per SYNC");
    check_hb(port);
    for (uint32_t k = 0U; k < 4U; k++) {
        check(frame_is(sent(3U + (2U * k)), (uint16_t)(0x180U + (0x100U * k) + NODE_ID), tpdo_len[k], all),
              "TPDO payload");
    }
}

static void w5(int port)
{
    static const uint8_t d[8] = {1, 2, 3, 4, 5, 6, 7, 8};
    co_frame_t f = frame(0x3FFU, 8U, d);

    run_frames(&f, port, 0xFFU, NULL);
    check(tx.n == tx.hb, "no frame but heartbeats");
    check_hb(port);
}

static void idle(void)
{
    CALLGRIND_START_INSTRUMENTATION;
    for (uint32_t i = 0U; i < FRAMES; i++) {
        (void)co_node_process(node, now);
        now += TICK_US;
    }
    CALLGRIND_STOP_INSTRUMENTATION;
    check(tx.n == tx.hb, "no frame but heartbeats");
    check_hb(1);
}

#ifdef BENCH_HOOK
/* W6: block upload of 0x2100 (CRC, 127 segments per block); a client
 * frame, then (port) the tick, each 1 ms apart. */
static void client(const uint8_t *d, int port)
{
    co_frame_t f = frame(0x600U + NODE_ID, 8U, d);

    co_node_rx(node, &f, now);
    if (port) {
        (void)co_node_process(node, now);
    }
    now += TICK_US;
}

static uint16_t crc16(const uint8_t *p, uint32_t n)
{
    uint16_t crc = 0U;

    for (uint32_t i = 0U; i < n; i++) {
        crc = (uint16_t)(crc ^ (uint16_t)(p[i] << 8U));
        for (int b = 0; b < 8; b++) {
            crc = (uint16_t)(((crc & 0x8000U) != 0U) ? (uint16_t)((uint16_t)(crc << 1U) ^ 0x1021U) : (uint16_t)(crc << 1U));
        }
    }
    return crc;
}

static void w6(int port)
{
    static const uint8_t init[8] = {0xA4, 0x00, 0x21, 0x00, 127, 0, 0, 0};
    static const uint8_t go[8] = {0xA3, 0, 0, 0, 0, 0, 0, 0};
    static const uint8_t end[8] = {0xA1, 0, 0, 0, 0, 0, 0, 0};
    uint8_t ack[8] = {0xA2, 0, 127, 0, 0, 0, 0, 0};
    const co_frame_t *l;
    uint32_t segs = 0U;
    uint32_t blocks = 0U;
    uint8_t crc_hi;
    uint8_t crc_lo;
    uint8_t unused;

    CALLGRIND_START_INSTRUMENTATION;
    client(init, port);
    tx.blk = got;
    client(go, port);
    while (blocks < ((DOM_SIZE / 7U) + 1U)) {
        l = sent(11U); /* the last segment of a block (or an abort) */
        segs += l->data[0] & 0x7FU;
        blocks++;
        ack[1] = (uint8_t)(l->data[0] & 0x7FU);
        tx.blk = ((l->data[0] & 0x80U) != 0U) ? NULL : &got[segs * 7U];
        client(ack, port);
        if (tx.blk == NULL) {
            break; /* the last block: the end came */
        }
    }
    l = sent(11U);
    crc_lo = l->data[1];
    crc_hi = l->data[2];
    unused = (uint8_t)((l->data[0] >> 2U) & 7U);
    client(end, port);
    CALLGRIND_STOP_INSTRUMENTATION;
    check((l->data[0] & 0xE3U) == 0xC1U, "block upload end");
    check((segs * 7U) - unused == DOM_SIZE, "block upload size");
    check(memcmp(got, domain, DOM_SIZE) == 0, "block upload data");
    check((uint16_t)((crc_hi << 8U) | crc_lo) == crc16(domain, DOM_SIZE), "block upload CRC");
    check(blocks == (DOM_SIZE + (127U * 7U) - 1U) / (127U * 7U), "blocks");
}
#endif

int main(int argc, char **argv)
{
    int port;
    const char *w;

    if ((argc != 3) || ((strcmp(argv[2], "port") != 0) && (strcmp(argv[2], "rx") != 0))) {
        fprintf(stderr, "usage: %s w1|w2|w2b|w3|w4|w5|idle|w6 port|rx\n", argv[0]);
        return 2;
    }
    w = argv[1];
    port = strcmp(argv[2], "port") == 0;
    setup();
    if (strcmp(w, "w1") == 0) {
        w1(port);
    } else if (strcmp(w, "w2") == 0) {
        w2(port);
    } else if (strcmp(w, "w2b") == 0) {
        w2b(port);
    } else if (strcmp(w, "w3") == 0) {
        w3(port);
    } else if (strcmp(w, "w4") == 0) {
        w4(port);
    } else if (strcmp(w, "w5") == 0) {
        w5(port);
    } else if (strcmp(w, "idle") == 0) {
        idle();
#ifdef BENCH_HOOK
    } else if (strcmp(w, "w6") == 0) {
        w6(port);
#endif
    } else {
        fprintf(stderr, "%s: unknown workload %s\n", argv[0], w);
        return 2;
    }
    printf("%s %s: frames sent %u, heartbeats %u%s\n", w, argv[2], (unsigned)tx.n,
           (unsigned)tx.hb, failed ? "" : ", verified");
    return failed;
}
