/*
 * SDO server: block download and block upload (CiA 301 v4.2, 7.2.4.3.9 to
 * 7.2.4.3.16) with and without CRC (CRC-16 CCITT, polynomial 0x1021, initial
 * value 0) and size indication, a 100 kB round trip through a hook-backed
 * DOMAIN driven by a small in-memory block client, CRC, sequence and block
 * size errors, retransmission, protocol switch, timeouts, a full TX path and
 * the personality options that disable block transfers.
 *
 * Frame notation as in test_sdo.c: "601 ..." is the client's request,
 * "581 ..." the answer of node 1.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "co/co_endian.h"
#include "test_bus.h"
#include "test_dev.h"
#include "test_frames.h"

#define DOM_CAP 102400U /* the DOMAIN 0x2200 holds up to 100 kB */

/* The storage behind the hook of the DOMAIN 0x2200. */
typedef struct dom {
    uint8_t data[DOM_CAP];
    uint32_t len;        /**< valid bytes */
    bool tell_total;     /**< the read hook reports io->total */
    uint32_t fake_total; /**< reported instead of len when not 0 (a wrong hook) */
    uint32_t next_wr;    /**< the offset the next write must have */
    uint32_t writes;     /**< write hook calls */
    uint32_t last_writes; /**< ... of which with io->last */
    uint32_t reads;      /**< read hook calls */
    uint32_t max_read;   /**< a read produces at most this many bytes (0: no limit) */
} dom_t;

typedef struct fx {
    tb_bus_t bus;
    td_node_t n;
    td_node_t n2;
    dom_t dom;
} fx_t;

static fx_t fx;

static co_err_t dom_read(void *ctx, co_od_io_t *io)
{
    dom_t *d = (dom_t *)ctx;
    uint32_t n = 0U;

    d->reads++;
    if (io->offset < d->len) {
        n = d->len - io->offset;
        if (n > io->len) {
            n = io->len;
        }
        if ((d->max_read != 0U) && (n > d->max_read)) {
            n = d->max_read;
        }
        (void)memcpy(io->buf, &d->data[io->offset], n);
    }
    io->len = n;
    io->total = d->tell_total ? ((d->fake_total != 0U) ? d->fake_total : d->len) : 0U;
    io->last = (io->offset + n) >= d->len;
    return CO_OK;
}

static co_err_t dom_write(void *ctx, co_od_io_t *io)
{
    dom_t *d = (dom_t *)ctx;

    d->writes++;
    /* the server writes the value in order, without gaps or repeats */
    assert_int_equal(io->offset, d->next_wr);
    if ((io->total > DOM_CAP) || (io->offset > DOM_CAP) || (io->len > (DOM_CAP - io->offset))) {
        return CO_ERR_TYPE_TOO_LONG;
    }
    if (io->len > 0U) {
        (void)memcpy(&d->data[io->offset], io->buf, io->len);
    }
    d->next_wr = io->offset + io->len;
    if (io->last) {
        d->len = io->offset + io->len;
        d->next_wr = 0U;
        d->last_writes++;
    }
    return CO_OK;
}

static int setup(void **state)
{
    co_od_hook_t hook;

    memset(&fx, 0, sizeof fx);
    tb_init(&fx.bus);
    td_start(&fx.n, &fx.bus, 0, 1, NULL);
    tb_flush(&fx.bus);
    fx.dom.tell_total = true;
    hook.read = dom_read;
    hook.write = dom_write;
    hook.ctx = &fx.dom;
    assert_int_equal(co_od_bind_hook(&fx.n.node, 0x2200U, &hook), CO_RESULT_OK);
    *state = &fx;
    return 0;
}

#define FX ((fx_t *)*state)
#define BUS (&FX->bus)
#define RAMV (FX->n.ram)
#define DOM (FX->dom)

/* ---------------------------------------------------------- helpers */

/* CRC-16 CCITT, polynomial 0x1021, initial value 0, bit by bit: the
 * reference the server's CRC (a byte at a time, by shifts) is checked against. */
static uint16_t ref_crc(const uint8_t *p, uint32_t n)
{
    uint16_t crc = 0U;

    for (uint32_t i = 0U; i < n; i++) {
        crc = (uint16_t)(crc ^ (uint16_t)((uint16_t)p[i] << 8U));
        for (unsigned b = 0U; b < 8U; b++) {
            if ((crc & 0x8000U) != 0U) {
                crc = (uint16_t)((uint16_t)(crc << 1U) ^ 0x1021U);
            } else {
                crc = (uint16_t)(crc << 1U);
            }
        }
    }
    return crc;
}

/* The DOMAIN's value: @p n bytes counting up from @p first. */
static void dom_count(dom_t *d, uint32_t n, uint8_t first)
{
    for (uint32_t i = 0U; i < n; i++) {
        d->data[i] = (uint8_t)(first + i);
    }
    d->len = n;
}

/* xorshift32: reproducible pseudo-random test data */
static void fill_random(uint8_t *p, uint32_t n, uint32_t seed)
{
    uint32_t x = seed;

    for (uint32_t i = 0U; i < n; i++) {
        x ^= x << 13U;
        x ^= x >> 17U;
        x ^= x << 5U;
        p[i] = (uint8_t)(x >> 24U);
    }
}

/* The client sends the 8 bytes @p d to node 1. */
static void send_bytes(tb_bus_t *bus, const uint8_t *d)
{
    co_frame_t f;

    co_frame_set(&f, 0x601U, d, 8U);
    tb_send_frame(bus, &f);
}

static void fmt_bytes(char *txt, size_t cap, const uint8_t *d)
{
    (void)snprintf(txt, cap, "581 %02X %02X %02X %02X %02X %02X %02X %02X", (unsigned)d[0],
                   (unsigned)d[1], (unsigned)d[2], (unsigned)d[3], (unsigned)d[4],
                   (unsigned)d[5], (unsigned)d[6], (unsigned)d[7]);
}

/* The next frame node 1 sent must be exactly 581 d[0..7]. */
static void expect_bytes_at(tb_bus_t *bus, const uint8_t *d, const char *file, int line)
{
    char txt[48];

    fmt_bytes(txt, sizeof txt, d);
    tb_expect_at(bus, txt, file, line);
}
#define EXPECT_BYTES(bus, d) expect_bytes_at((bus), (d), __FILE__, __LINE__)

/* Forget the frames logged so far (all of which must have been checked), so
 * that long transfers do not overflow the bus log. */
static void bus_rewind(tb_bus_t *bus)
{
    assert_int_equal(bus->read_pos, bus->n_log);
    bus->n_log = 0U;
    bus->read_pos = 0U;
    bus->deliver_pos = 0U;
}

static void init8(uint8_t *d, uint8_t cmd, uint16_t index, uint8_t sub, uint32_t data)
{
    d[0] = cmd;
    co_put_u16(&d[1], index);
    d[3] = sub;
    co_put_u32(&d[4], data);
}

/* ---------------------------------------------------------- the block client */

typedef struct dl_cfg {
    bool crc;      /**< client supports CRC */
    bool size;     /**< size indicated */
    uint32_t drop; /**< segment number (1-based, over the whole value) that is lost
                        the first time it is sent; 0: none. Not the last segment of
                        a sub-block (the server could not notice the loss then). */
} dl_cfg_t;

/* Block-download @p len bytes of @p data to index:sub, checking every answer
 * of the server exactly (blksize 127, acknowledges, end response). */
static void client_block_download(tb_bus_t *bus, uint16_t index, uint8_t sub,
                                  const uint8_t *data, uint32_t len, const dl_cfg_t *cfg)
{
    uint8_t d[8];
    uint8_t r[8];
    uint32_t pos = 0U; /* bytes the server has acknowledged */
    uint32_t last_n = 0U;
    bool dropped = false;
    bool done = false;

    init8(d, (uint8_t)(0xC0U | (cfg->crc ? 0x04U : 0U) | (cfg->size ? 0x02U : 0U)), index, sub,
          cfg->size ? len : 0U);
    send_bytes(bus, d);
    init8(r, 0xA4U, index, sub, 127U);
    EXPECT_BYTES(bus, r);
    tb_expect_none(bus);

    while (!done) {
        uint32_t p = pos;
        uint8_t seq = 0U;
        uint8_t good = 0U; /* what the server must acknowledge */
        bool gap = false;
        bool last = false;

        while ((seq < 127U) && !last) {
            uint32_t n = ((len - p) > 7U) ? 7U : (len - p);
            uint32_t segno = (p / 7U) + 1U;
            last = (p + n) >= len;
            seq++;
            (void)memset(d, 0, sizeof d);
            d[0] = (uint8_t)(seq | (last ? 0x80U : 0U));
            if (n > 0U) {
                (void)memcpy(&d[1], &data[p], n);
            }
            p += n;
            last_n = n;
            if (!dropped && (segno == cfg->drop)) {
                dropped = true;
                gap = true;
                continue; /* lost on the bus */
            }
            send_bytes(bus, d);
            if (!gap) {
                good = seq;
            }
            if (!last && (seq < 127U)) {
                tb_expect_none(bus); /* no answer inside a sub-block */
            }
        }
        (void)memset(r, 0, sizeof r);
        r[0] = 0xA2U;
        r[1] = good;
        r[2] = 127U;
        EXPECT_BYTES(bus, r);
        tb_expect_none(bus);
        pos += (uint32_t)good * 7U;
        done = last && (good == seq);
        bus_rewind(bus);
    }
    {
        uint16_t crc = cfg->crc ? ref_crc(data, len) : 0U;
        (void)memset(d, 0, sizeof d);
        d[0] = (uint8_t)(0xC1U | ((7U - last_n) << 2U));
        co_put_u16(&d[1], crc);
        send_bytes(bus, d);
        (void)memset(r, 0, sizeof r);
        r[0] = 0xA1U;
        EXPECT_BYTES(bus, r);
        tb_expect_none(bus);
    }
}

typedef struct ul_cfg {
    bool crc;              /**< client supports CRC */
    uint8_t blksize;       /**< segments per sub-block the client asks for */
    uint32_t short_block;  /**< in this sub-block (1-based) the client acknowledges
                                only short_ack segments; 0: never */
    uint8_t short_ack;
} ul_cfg_t;

/* Block-upload index:sub into @p out (@p cap bytes, plus 7 of slack); the
 * initiate response must announce @p size (size_known) or no size. Checks the
 * server's sequence numbers and the end frame (n and CRC) exactly. Returns
 * the number of bytes received. */
static uint32_t client_block_upload(tb_bus_t *bus, uint16_t index, uint8_t sub, uint8_t *out,
                                    uint32_t cap, bool size_known, uint32_t size,
                                    const ul_cfg_t *cfg)
{
    uint8_t d[8];
    uint8_t r[8];
    uint32_t pos = 0U; /* bytes acknowledged */
    uint32_t block = 0U;
    uint32_t total;
    bool done = false;

    init8(d, (uint8_t)(0xA0U | (cfg->crc ? 0x04U : 0U)), index, sub, cfg->blksize);
    send_bytes(bus, d);
    init8(r, (uint8_t)(0xC4U | (size_known ? 0x02U : 0U)), index, sub, size_known ? size : 0U);
    EXPECT_BYTES(bus, r);
    tb_expect_none(bus);
    bus_rewind(bus);

    init8(d, 0xA3U, 0U, 0U, 0U);
    send_bytes(bus, d);
    while (!done) {
        uint8_t seq = 0U;
        uint8_t ack;
        bool last = false;

        block++;
        while ((seq < cfg->blksize) && !last) {
            const co_frame_t *f = tb_next(bus);
            uint32_t at = pos + ((uint32_t)seq * 7U);
            assert_non_null(f);
            assert_int_equal(co_frame_cob(f), 0x581U);
            assert_int_equal(f->dlc, 8U);
            assert_int_equal(f->data[0] & 0x7FU, seq + 1U);
            assert_true(at <= cap);
            (void)memcpy(&out[at], &f->data[1], 7U);
            last = (f->data[0] & 0x80U) != 0U;
            seq++;
        }
        tb_expect_none(bus); /* the sub-block is complete: the server waits */
        bus_rewind(bus);
        ack = seq;
        if (block == cfg->short_block) {
            ack = cfg->short_ack;
            last = false;
        }
        (void)memset(d, 0, sizeof d);
        d[0] = 0xA2U;
        d[1] = ack;
        d[2] = cfg->blksize;
        send_bytes(bus, d);
        pos += (uint32_t)ack * 7U;
        done = last;
    }
    {
        const co_frame_t *f = tb_next(bus);
        uint32_t n;
        assert_non_null(f);
        n = ((uint32_t)f->data[0] >> 2U) & 7U;
        assert_true(pos >= n);
        total = pos - n;
        (void)memset(r, 0, sizeof r);
        r[0] = (uint8_t)(0xC1U | (n << 2U));
        co_put_u16(&r[1], cfg->crc ? ref_crc(out, total) : 0U);
        {
            char txt[48];
            fmt_bytes(txt, sizeof txt, r);
            TF_ASSERT_FRAME(f, txt);
        }
        tb_expect_none(bus);
    }
    init8(d, 0xA1U, 0U, 0U, 0U);
    send_bytes(bus, d);
    tb_expect_none(bus);
    bus_rewind(bus);
    if (size_known) {
        assert_int_equal(total, size);
    }
    return total;
}

/* ---------------------------------------------------------- 1: small values */

static void reference_crc_check_value(void **state)
{
    (void)state;
    /* the CRC-16/XMODEM check value */
    assert_int_equal(ref_crc((const uint8_t *)"123456789", 9U), 0x31C3U);
    assert_int_equal(ref_crc(NULL, 0U), 0U);
}

static void block_download_crc_check_value(void **state)
{
    /* "123456789" into the string: the end request carries the check value 0x31C3 */
    tb_xfer(BUS, "601 C6 12 20 00 09 00 00 00", "581 A4 12 20 00 7F 00 00 00");
    tb_send(BUS, "601 01 31 32 33 34 35 36 37");
    tb_expect_none(BUS);
    tb_xfer(BUS, "601 82 38 39 00 00 00 00 00", "581 A2 02 7F 00 00 00 00 00");
    tb_xfer(BUS, "601 D5 C3 31 00 00 00 00 00", "581 A1 00 00 00 00 00 00 00");
    assert_string_equal(RAMV.vstr, "123456789");
}

static void block_download_u32(void **state)
{
    /* CRC, size indicated */
    tb_xfer(BUS, "601 C6 04 20 00 04 00 00 00", "581 A4 04 20 00 7F 00 00 00");
    tb_xfer(BUS, "601 81 78 56 34 12 00 00 00", "581 A2 01 7F 00 00 00 00 00");
    assert_int_equal(RAMV.u32, 0xDEADBEEFUL); /* nothing committed before the end */
    tb_xfer(BUS, "601 CD FA D0 00 00 00 00 00", "581 A1 00 00 00 00 00 00 00");
    assert_int_equal(RAMV.u32, 0x12345678UL);
    /* no CRC, no size: the CRC field of the end request is not looked at */
    tb_xfer(BUS, "601 C0 04 20 00 00 00 00 00", "581 A4 04 20 00 7F 00 00 00");
    tb_xfer(BUS, "601 81 BE BA FE CA 00 00 00", "581 A2 01 7F 00 00 00 00 00");
    tb_xfer(BUS, "601 CD 55 AA 00 00 00 00 00", "581 A1 00 00 00 00 00 00 00");
    assert_int_equal(RAMV.u32, 0xCAFEBABEUL);
    /* CRC without size */
    tb_xfer(BUS, "601 C4 04 20 00 00 00 00 00", "581 A4 04 20 00 7F 00 00 00");
    tb_xfer(BUS, "601 81 44 33 22 11 00 00 00", "581 A2 01 7F 00 00 00 00 00");
    tb_xfer(BUS, "601 CD 0C 5A 00 00 00 00 00", "581 A1 00 00 00 00 00 00 00");
    assert_int_equal(RAMV.u32, 0x11223344UL);
    /* size without CRC */
    tb_xfer(BUS, "601 C2 04 20 00 04 00 00 00", "581 A4 04 20 00 7F 00 00 00");
    tb_xfer(BUS, "601 81 78 56 34 12 00 00 00", "581 A2 01 7F 00 00 00 00 00");
    tb_xfer(BUS, "601 CD 00 00 00 00 00 00 00", "581 A1 00 00 00 00 00 00 00");
    assert_int_equal(RAMV.u32, 0x12345678UL);
    /* the server is idle again */
    tb_xfer(BUS, "601 40 04 20 00 00 00 00 00", "581 43 04 20 00 78 56 34 12");
}

static void block_download_u64_two_segments(void **state)
{
    tb_xfer(BUS, "601 C6 06 20 00 08 00 00 00", "581 A4 06 20 00 7F 00 00 00");
    tb_send(BUS, "601 01 01 02 03 04 05 06 07");
    tb_expect_none(BUS);
    tb_xfer(BUS, "601 82 08 00 00 00 00 00 00", "581 A2 02 7F 00 00 00 00 00");
    assert_true(RAMV.u64 == 0U);
    tb_xfer(BUS, "601 D9 AC 76 00 00 00 00 00", "581 A1 00 00 00 00 00 00 00");
    assert_true(RAMV.u64 == 0x0807060504030201ULL);
}

/* A block download of the u64 0x2006 (initiate @p init) of two segments:
 * 7 bytes, then @p last_seg; the end request @p end gets @p answer and
 * the value stays 0. */
static void u64_block_refused(void **state, const char *init, const char *last_seg,
                              const char *end, const char *answer)
{
    tb_xfer(BUS, init, "581 A4 06 20 00 7F 00 00 00");
    tb_send(BUS, "601 01 01 02 03 04 05 06 07");
    tb_expect_none(BUS);
    tb_xfer(BUS, last_seg, "581 A2 02 7F 00 00 00 00 00");
    tb_xfer(BUS, end, answer);
    assert_true(RAMV.u64 == 0U);
}

static void block_download_u64_last_segment_too_long(void **state)
{
    /* the last segment is held in the server's 8-byte value buffer after the
     * 7 bytes gathered: an end request claiming 2 bytes of it (9 in all) is
     * refused for its length (before any CRC, which would cover a byte the
     * value has no room for), and the value stays */
    u64_block_refused(state, "601 C6 06 20 00 08 00 00 00", "601 82 08 09 00 00 00 00 00",
                      "601 D5 00 00 00 00 00 00 00", "581 80 06 20 00 12 00 07 06");
    /* without an indicated size: too long for the type */
    u64_block_refused(state, "601 C4 06 20 00 00 00 00 00", "601 82 08 09 00 00 00 00 00",
                      "601 D5 00 00 00 00 00 00 00", "581 80 06 20 00 10 00 07 06");
    /* the 1-byte end of the same transfer with a wrong CRC: refused for the CRC */
    u64_block_refused(state, "601 C6 06 20 00 08 00 00 00", "601 82 08 00 00 00 00 00 00",
                      "601 D9 AD 76 00 00 00 00 00", "581 80 06 20 00 04 00 04 05");
}

static void block_download_string(void **state)
{
    /* 32 bytes (the whole capacity), CRC, size indicated: 5 segments, 4 bytes in the last */
    tb_xfer(BUS, "601 C6 12 20 00 20 00 00 00", "581 A4 12 20 00 7F 00 00 00");
    tb_send(BUS, "601 01 43 41 4E 6F 70 65 6E");
    tb_send(BUS, "601 02 20 62 6C 6F 63 6B 20");
    tb_send(BUS, "601 03 74 72 61 6E 73 66 65");
    tb_send(BUS, "601 04 72 2C 20 33 32 20 62");
    tb_expect_none(BUS);
    tb_xfer(BUS, "601 85 79 74 65 73 00 00 00", "581 A2 05 7F 00 00 00 00 00");
    tb_xfer(BUS, "601 CD E1 4A 00 00 00 00 00", "581 A1 00 00 00 00 00 00 00");
    assert_memory_equal(RAMV.vstr, "CANopen block transfer, 32 bytes", 32U);
    /* 10 bytes, no size, no CRC: the rest of the string is cleared */
    tb_xfer(BUS, "601 C0 12 20 00 00 00 00 00", "581 A4 12 20 00 7F 00 00 00");
    tb_send(BUS, "601 01 43 41 4E 6F 70 65 6E");
    tb_expect_none(BUS);
    tb_xfer(BUS, "601 82 20 34 32 00 00 00 00", "581 A2 02 7F 00 00 00 00 00");
    tb_xfer(BUS, "601 D1 00 00 00 00 00 00 00", "581 A1 00 00 00 00 00 00 00");
    assert_string_equal(RAMV.vstr, "CANopen 42");
    {
        static const uint8_t zeros[22] = {0};
        assert_memory_equal(&RAMV.vstr[10], zeros, sizeof zeros);
    }
    /* an announced size beyond the capacity is refused at once */
    tb_xfer(BUS, "601 C6 12 20 00 21 00 00 00", "581 80 12 20 00 12 00 07 06");
}

static void block_download_size_mismatch(void **state)
{
    /* announced 4 bytes, the end request says 5 */
    tb_xfer(BUS, "601 C2 04 20 00 04 00 00 00", "581 A4 04 20 00 7F 00 00 00");
    tb_xfer(BUS, "601 81 78 56 34 12 99 00 00", "581 A2 01 7F 00 00 00 00 00");
    tb_xfer(BUS, "601 C9 00 00 00 00 00 00 00", "581 80 04 20 00 12 00 07 06");
    /* announced 10 bytes for the string, 7 arrive */
    tb_xfer(BUS, "601 C2 12 20 00 0A 00 00 00", "581 A4 12 20 00 7F 00 00 00");
    tb_xfer(BUS, "601 81 43 41 4E 6F 70 65 6E", "581 A2 01 7F 00 00 00 00 00");
    tb_xfer(BUS, "601 C1 00 00 00 00 00 00 00", "581 80 12 20 00 13 00 07 06");
    /* announced 8 bytes, a second full segment follows the first */
    tb_xfer(BUS, "601 C2 06 20 00 08 00 00 00", "581 A4 06 20 00 7F 00 00 00");
    tb_send(BUS, "601 01 01 02 03 04 05 06 07");
    tb_expect_none(BUS);
    tb_xfer(BUS, "601 02 01 02 03 04 05 06 07", "581 80 06 20 00 12 00 07 06");
    /* a segment that is not the last one overruns the announced 4 bytes */
    tb_xfer(BUS, "601 C6 04 20 00 04 00 00 00", "581 A4 04 20 00 7F 00 00 00");
    tb_xfer(BUS, "601 01 78 56 34 12 00 00 00", "581 80 04 20 00 12 00 07 06");
    assert_int_equal(RAMV.u32, 0xDEADBEEFUL);
    assert_true(RAMV.u64 == 0U);
}

static void block_upload_u32(void **state)
{
    RAMV.u32 = 0x12345678UL;
    /* CRC; size indicated by the server */
    tb_xfer(BUS, "601 A4 04 20 00 7F 00 00 00", "581 C6 04 20 00 04 00 00 00");
    tb_xfer(BUS, "601 A3 00 00 00 00 00 00 00", "581 81 78 56 34 12 00 00 00");
    tb_xfer(BUS, "601 A2 01 7F 00 00 00 00 00", "581 CD FA D0 00 00 00 00 00");
    tb_send(BUS, "601 A1 00 00 00 00 00 00 00");
    tb_expect_none(BUS);
    /* without CRC the CRC field is 0 */
    tb_xfer(BUS, "601 A0 04 20 00 10 00 00 00", "581 C6 04 20 00 04 00 00 00");
    tb_xfer(BUS, "601 A3 00 00 00 00 00 00 00", "581 81 78 56 34 12 00 00 00");
    tb_xfer(BUS, "601 A2 01 10 00 00 00 00 00", "581 CD 00 00 00 00 00 00 00");
    tb_send(BUS, "601 A1 00 00 00 00 00 00 00");
    tb_expect_none(BUS);
    /* the server is idle again */
    tb_xfer(BUS, "601 40 04 20 00 00 00 00 00", "581 43 04 20 00 78 56 34 12");
}

static void block_upload_string(void **state)
{
    memcpy(RAMV.vstr, "CANopen block transfer, 32 bytes", 32U);
    tb_xfer(BUS, "601 A4 12 20 00 7F 00 00 00", "581 C6 12 20 00 20 00 00 00");
    tb_send(BUS, "601 A3 00 00 00 00 00 00 00");
    tb_expect(BUS, "581 01 43 41 4E 6F 70 65 6E");
    tb_expect(BUS, "581 02 20 62 6C 6F 63 6B 20");
    tb_expect(BUS, "581 03 74 72 61 6E 73 66 65");
    tb_expect(BUS, "581 04 72 2C 20 33 32 20 62");
    tb_expect(BUS, "581 85 79 74 65 73 00 00 00");
    tb_expect_none(BUS);
    tb_xfer(BUS, "601 A2 05 7F 00 00 00 00 00", "581 CD E1 4A 00 00 00 00 00");
    tb_send(BUS, "601 A1 00 00 00 00 00 00 00");
    tb_expect_none(BUS);
    /* the default "hello": 5 bytes up to the NUL */
    memcpy(RAMV.vstr, "hello\0\0\0", 8U);
    tb_xfer(BUS, "601 A4 12 20 00 7F 00 00 00", "581 C6 12 20 00 05 00 00 00");
    tb_xfer(BUS, "601 A3 00 00 00 00 00 00 00", "581 81 68 65 6C 6C 6F 00 00");
    tb_xfer(BUS, "601 A2 01 7F 00 00 00 00 00", "581 C9 62 C3 00 00 00 00 00");
    tb_send(BUS, "601 A1 00 00 00 00 00 00 00");
    tb_expect_none(BUS);
    /* an empty string: one empty last segment, n = 7, CRC of nothing */
    memset(RAMV.vstr, 0, sizeof RAMV.vstr);
    tb_xfer(BUS, "601 A4 12 20 00 7F 00 00 00", "581 C6 12 20 00 00 00 00 00");
    tb_xfer(BUS, "601 A3 00 00 00 00 00 00 00", "581 81 00 00 00 00 00 00 00");
    tb_xfer(BUS, "601 A2 01 7F 00 00 00 00 00", "581 DD 00 00 00 00 00 00 00");
    tb_send(BUS, "601 A1 00 00 00 00 00 00 00");
    tb_expect_none(BUS);
}

static void block_upload_domain_with_and_without_size(void **state)
{
    dom_count(&DOM, 10U, 0xA0U);
    /* the hook tells the total: size indicated */
    tb_xfer(BUS, "601 A4 00 22 00 7F 00 00 00", "581 C6 00 22 00 0A 00 00 00");
    tb_send(BUS, "601 A3 00 00 00 00 00 00 00");
    tb_expect(BUS, "581 01 A0 A1 A2 A3 A4 A5 A6");
    tb_expect(BUS, "581 82 A7 A8 A9 00 00 00 00");
    tb_expect_none(BUS);
    tb_xfer(BUS, "601 A2 02 7F 00 00 00 00 00", "581 D1 DB 91 00 00 00 00 00");
    tb_send(BUS, "601 A1 00 00 00 00 00 00 00");
    tb_expect_none(BUS);
    /* the hook does not know the total: no size, the end comes from io->last */
    DOM.tell_total = false;
    tb_xfer(BUS, "601 A4 00 22 00 7F 00 00 00", "581 C4 00 22 00 00 00 00 00");
    tb_send(BUS, "601 A3 00 00 00 00 00 00 00");
    tb_expect(BUS, "581 01 A0 A1 A2 A3 A4 A5 A6");
    tb_expect(BUS, "581 82 A7 A8 A9 00 00 00 00");
    tb_expect_none(BUS);
    tb_xfer(BUS, "601 A2 02 7F 00 00 00 00 00", "581 D1 DB 91 00 00 00 00 00");
    tb_send(BUS, "601 A1 00 00 00 00 00 00 00");
    tb_expect_none(BUS);
}

static void upload_sends_no_more_than_announced(void **state)
{
    dom_count(&DOM, 20U, 0x30U);
    /* the hook announces 10 bytes but has 20: the server sends the 10 */
    DOM.fake_total = 10U;
    tb_xfer(BUS, "601 A4 00 22 00 7F 00 00 00", "581 C6 00 22 00 0A 00 00 00");
    tb_send(BUS, "601 A3 00 00 00 00 00 00 00");
    tb_expect(BUS, "581 01 30 31 32 33 34 35 36");
    tb_expect(BUS, "581 82 37 38 39 00 00 00 00");
    tb_expect_none(BUS);
    tb_xfer(BUS, "601 A2 02 7F 00 00 00 00 00", "581 D1 58 9C 00 00 00 00 00");
    tb_send(BUS, "601 A1 00 00 00 00 00 00 00");
    tb_expect_none(BUS);
    /* ... also within the first, staged chunk */
    DOM.fake_total = 3U;
    tb_xfer(BUS, "601 A4 00 22 00 7F 00 00 00", "581 C6 00 22 00 03 00 00 00");
    tb_xfer(BUS, "601 A3 00 00 00 00 00 00 00", "581 81 30 31 32 00 00 00 00");
    tb_xfer(BUS, "601 A2 01 7F 00 00 00 00 00", "581 D1 10 E5 00 00 00 00 00");
    tb_send(BUS, "601 A1 00 00 00 00 00 00 00");
    tb_expect_none(BUS);
}

/* ---------------------------------------------------------- 2: 100 kB */

static void domain_100k_round_trip(void **state)
{
    static uint8_t src[DOM_CAP];
    static uint8_t back[DOM_CAP + 7U];
    const dl_cfg_t dl = {true, true, 0U};
    const ul_cfg_t ul = {true, 100U, 0U, 0U};
    uint32_t n;

    fill_random(src, DOM_CAP, 0x2545F491UL);
    client_block_download(BUS, 0x2200U, 0U, src, DOM_CAP, &dl);
    assert_int_equal(DOM.len, DOM_CAP);
    assert_memory_equal(DOM.data, src, DOM_CAP);
    /* one write per segment (14629), the last one flagged */
    assert_int_equal(DOM.writes, (DOM_CAP + 6U) / 7U);
    assert_int_equal(DOM.last_writes, 1U);

    memset(back, 0, sizeof back);
    n = client_block_upload(BUS, 0x2200U, 0U, back, DOM_CAP, true, DOM_CAP, &ul);
    assert_int_equal(n, DOM_CAP);
    assert_memory_equal(back, src, DOM_CAP);
    assert_int_equal(ref_crc(back, n), ref_crc(src, DOM_CAP));
}

static void domain_round_trip_variants(void **state)
{
    static uint8_t src[3000];
    static uint8_t back[3000 + 7];
    uint32_t n;

    fill_random(src, sizeof src, 0x9E3779B9UL);
    /* without CRC and size; a lost segment in the middle of a full sub-block
     * is acknowledged at its end (ackseq 49 at seqno 127) */
    {
        const dl_cfg_t dl = {false, false, 50U};
        client_block_download(BUS, 0x2200U, 0U, src, (uint32_t)sizeof src, &dl);
    }
    assert_int_equal(DOM.len, sizeof src);
    assert_memory_equal(DOM.data, src, sizeof src);
    /* a lost segment in the second sub-block */
    {
        const dl_cfg_t dl = {true, true, 200U};
        fill_random(src, sizeof src, 7U);
        client_block_download(BUS, 0x2200U, 0U, src, (uint32_t)sizeof src, &dl);
    }
    assert_memory_equal(DOM.data, src, sizeof src);
    /* size unknown to the hook; the client acknowledges only part of the
     * second sub-block, then all of it in the first sub-block */
    DOM.tell_total = false;
    {
        const ul_cfg_t ul = {true, 127U, 2U, 60U};
        memset(back, 0, sizeof back);
        n = client_block_upload(BUS, 0x2200U, 0U, back, (uint32_t)sizeof src, false, 0U, &ul);
        assert_int_equal(n, sizeof src);
        assert_memory_equal(back, src, sizeof src);
    }
    {
        const ul_cfg_t ul = {false, 1U, 1U, 0U};
        memset(back, 0, sizeof back);
        n = client_block_upload(BUS, 0x2200U, 0U, back, (uint32_t)sizeof src, false, 0U, &ul);
        assert_int_equal(n, sizeof src);
        assert_memory_equal(back, src, sizeof src);
    }
    /* a length that is a multiple of 7 and of a whole sub-block (n = 0) */
    {
        const dl_cfg_t dl = {true, true, 0U};
        const ul_cfg_t ul = {true, 127U, 0U, 0U};
        DOM.tell_total = true;
        client_block_download(BUS, 0x2200U, 0U, src, 127U * 7U, &dl);
        assert_int_equal(DOM.len, 127U * 7U);
        n = client_block_upload(BUS, 0x2200U, 0U, back, (uint32_t)sizeof src, true, 127U * 7U, &ul);
        assert_int_equal(n, 127U * 7U);
        assert_memory_equal(back, src, 127U * 7U);
    }
    /* an empty DOMAIN */
    {
        const dl_cfg_t dl = {true, true, 0U};
        const ul_cfg_t ul = {true, 127U, 0U, 0U};
        client_block_download(BUS, 0x2200U, 0U, src, 0U, &dl);
        assert_int_equal(DOM.len, 0U);
        n = client_block_upload(BUS, 0x2200U, 0U, back, (uint32_t)sizeof src, true, 0U, &ul);
        assert_int_equal(n, 0U);
    }
}

/* ---------------------------------------------------------- 3: CRC error */

static void crc_error_aborts_and_commits_nothing(void **state)
{
    tb_xfer(BUS, "601 C6 04 20 00 04 00 00 00", "581 A4 04 20 00 7F 00 00 00");
    tb_xfer(BUS, "601 81 78 56 34 12 00 00 00", "581 A2 01 7F 00 00 00 00 00");
    tb_xfer(BUS, "601 CD FA D1 00 00 00 00 00", "581 80 04 20 00 04 00 04 05");
    assert_int_equal(RAMV.u32, 0xDEADBEEFUL);
    /* two segments, gathered and not committed */
    tb_xfer(BUS, "601 C4 06 20 00 00 00 00 00", "581 A4 06 20 00 7F 00 00 00");
    tb_send(BUS, "601 01 01 02 03 04 05 06 07");
    tb_xfer(BUS, "601 82 08 00 00 00 00 00 00", "581 A2 02 7F 00 00 00 00 00");
    tb_xfer(BUS, "601 D9 76 AC 00 00 00 00 00", "581 80 06 20 00 04 00 04 05");
    assert_true(RAMV.u64 == 0U);
    /* the server is idle again; the right CRC is accepted */
    tb_xfer(BUS, "601 40 04 20 00 00 00 00 00", "581 43 04 20 00 EF BE AD DE");
    tb_xfer(BUS, "601 C6 04 20 00 04 00 00 00", "581 A4 04 20 00 7F 00 00 00");
    tb_xfer(BUS, "601 81 78 56 34 12 00 00 00", "581 A2 01 7F 00 00 00 00 00");
    tb_xfer(BUS, "601 CD FA D0 00 00 00 00 00", "581 A1 00 00 00 00 00 00 00");
    assert_int_equal(RAMV.u32, 0x12345678UL);
    /* 5 bytes for the announced 4: the CRC is checked first (a wrong one
     * is the CRC error), a right one over the 5 bytes meets the size check */
    tb_xfer(BUS, "601 C6 04 20 00 04 00 00 00", "581 A4 04 20 00 7F 00 00 00");
    tb_xfer(BUS, "601 81 78 56 34 12 99 00 00", "581 A2 01 7F 00 00 00 00 00");
    tb_xfer(BUS, "601 C9 FA D0 00 00 00 00 00", "581 80 04 20 00 04 00 04 05");
    tb_xfer(BUS, "601 C6 04 20 00 04 00 00 00", "581 A4 04 20 00 7F 00 00 00");
    tb_xfer(BUS, "601 81 78 56 34 12 99 00 00", "581 A2 01 7F 00 00 00 00 00");
    tb_xfer(BUS, "601 C9 ED 23 00 00 00 00 00", "581 80 04 20 00 12 00 07 06");
    assert_int_equal(RAMV.u32, 0x12345678UL);
}

/* ---------------------------------------------------------- 4: sequence errors */

static void download_lost_segment_is_repeated(void **state)
{
    tb_xfer(BUS, "601 C6 12 20 00 20 00 00 00", "581 A4 12 20 00 7F 00 00 00");
    tb_send(BUS, "601 01 43 41 4E 6F 70 65 6E");
    tb_send(BUS, "601 02 20 62 6C 6F 63 6B 20");
    /* 03 is lost */
    tb_send(BUS, "601 04 72 2C 20 33 32 20 62");
    tb_expect_none(BUS);
    tb_xfer(BUS, "601 85 79 74 65 73 00 00 00", "581 A2 02 7F 00 00 00 00 00");
    /* the client repeats from the third segment, numbered from 1 */
    tb_send(BUS, "601 01 74 72 61 6E 73 66 65");
    tb_send(BUS, "601 02 72 2C 20 33 32 20 62");
    tb_expect_none(BUS);
    tb_xfer(BUS, "601 83 79 74 65 73 00 00 00", "581 A2 03 7F 00 00 00 00 00");
    tb_xfer(BUS, "601 CD E1 4A 00 00 00 00 00", "581 A1 00 00 00 00 00 00 00");
    assert_memory_equal(RAMV.vstr, "CANopen block transfer, 32 bytes", 32U);

    /* the first segment lost: acknowledge 0, everything again */
    tb_xfer(BUS, "601 C6 04 20 00 04 00 00 00", "581 A4 04 20 00 7F 00 00 00");
    tb_xfer(BUS, "601 82 00 00 00 00 00 00 00", "581 A2 00 7F 00 00 00 00 00");
    tb_xfer(BUS, "601 81 78 56 34 12 00 00 00", "581 A2 01 7F 00 00 00 00 00");
    tb_xfer(BUS, "601 CD FA D0 00 00 00 00 00", "581 A1 00 00 00 00 00 00 00");
    assert_int_equal(RAMV.u32, 0x12345678UL);
}

static void download_seqno_zero_aborts(void **state)
{
    tb_xfer(BUS, "601 C6 12 20 00 20 00 00 00", "581 A4 12 20 00 7F 00 00 00");
    tb_xfer(BUS, "601 00 43 41 4E 6F 70 65 6E", "581 80 12 20 00 03 00 04 05");
    /* also after good segments */
    tb_xfer(BUS, "601 C6 12 20 00 20 00 00 00", "581 A4 12 20 00 7F 00 00 00");
    tb_send(BUS, "601 01 43 41 4E 6F 70 65 6E");
    tb_xfer(BUS, "601 00 20 62 6C 6F 63 6B 20", "581 80 12 20 00 03 00 04 05");
    assert_int_equal(RAMV.u32, 0xDEADBEEFUL);
    /* the server is idle again */
    tb_xfer(BUS, "601 40 04 20 00 00 00 00 00", "581 43 04 20 00 EF BE AD DE");
}

/* ---------------------------------------------------------- 5: upload acks */

static void upload_start_string(void **state)
{
    memcpy(RAMV.vstr, "CANopen block transfer, 32 bytes", 32U);
    tb_xfer(BUS, "601 A4 12 20 00 7F 00 00 00", "581 C6 12 20 00 20 00 00 00");
    tb_send(BUS, "601 A3 00 00 00 00 00 00 00");
    tb_expect(BUS, "581 01 43 41 4E 6F 70 65 6E");
    tb_expect(BUS, "581 02 20 62 6C 6F 63 6B 20");
    tb_expect(BUS, "581 03 74 72 61 6E 73 66 65");
    tb_expect(BUS, "581 04 72 2C 20 33 32 20 62");
    tb_expect(BUS, "581 85 79 74 65 73 00 00 00");
    tb_expect_none(BUS);
}

static void upload_partial_ack_retransmits(void **state)
{
    upload_start_string(state);
    /* two segments arrived: the server repeats from the third, numbered from 1 */
    tb_send(BUS, "601 A2 02 7F 00 00 00 00 00");
    tb_expect(BUS, "581 01 74 72 61 6E 73 66 65");
    tb_expect(BUS, "581 02 72 2C 20 33 32 20 62");
    tb_expect(BUS, "581 83 79 74 65 73 00 00 00");
    tb_expect_none(BUS);
    tb_xfer(BUS, "601 A2 03 7F 00 00 00 00 00", "581 CD E1 4A 00 00 00 00 00");
    tb_send(BUS, "601 A1 00 00 00 00 00 00 00");
    tb_expect_none(BUS);

    /* none arrived: everything again (the first segment too) */
    upload_start_string(state);
    tb_send(BUS, "601 A2 00 7F 00 00 00 00 00");
    tb_expect(BUS, "581 01 43 41 4E 6F 70 65 6E");
    tb_expect(BUS, "581 02 20 62 6C 6F 63 6B 20");
    tb_expect(BUS, "581 03 74 72 61 6E 73 66 65");
    tb_expect(BUS, "581 04 72 2C 20 33 32 20 62");
    tb_expect(BUS, "581 85 79 74 65 73 00 00 00");
    tb_expect_none(BUS);
    tb_xfer(BUS, "601 A2 05 7F 00 00 00 00 00", "581 CD E1 4A 00 00 00 00 00");
    tb_send(BUS, "601 A1 00 00 00 00 00 00 00");
    tb_expect_none(BUS);

    /* a 2-byte string: the last segment is shorter than the staged first one */
    memcpy(RAMV.vstr, "Hi\0", 3U);
    tb_xfer(BUS, "601 A0 12 20 00 7F 00 00 00", "581 C6 12 20 00 02 00 00 00");
    tb_xfer(BUS, "601 A3 00 00 00 00 00 00 00", "581 81 48 69 00 00 00 00 00");
    tb_xfer(BUS, "601 A2 00 7F 00 00 00 00 00", "581 81 48 69 00 00 00 00 00");
    tb_xfer(BUS, "601 A2 01 7F 00 00 00 00 00", "581 D5 00 00 00 00 00 00 00");
    tb_send(BUS, "601 A1 00 00 00 00 00 00 00");
    tb_expect_none(BUS);

    /* 10 bytes in two segments, the first acknowledged again and again */
    memcpy(RAMV.vstr, "CANopen 42\0", 11U);
    tb_xfer(BUS, "601 A4 12 20 00 7F 00 00 00", "581 C6 12 20 00 0A 00 00 00");
    tb_send(BUS, "601 A3 00 00 00 00 00 00 00");
    tb_expect(BUS, "581 01 43 41 4E 6F 70 65 6E");
    tb_expect(BUS, "581 82 20 34 32 00 00 00 00");
    tb_expect_none(BUS);
    tb_send(BUS, "601 A2 00 7F 00 00 00 00 00");
    tb_expect(BUS, "581 01 43 41 4E 6F 70 65 6E");
    tb_expect(BUS, "581 82 20 34 32 00 00 00 00");
    tb_expect_none(BUS);
    tb_xfer(BUS, "601 A2 01 7F 00 00 00 00 00", "581 81 20 34 32 00 00 00 00");
    tb_xfer(BUS, "601 A2 01 7F 00 00 00 00 00", "581 D1 04 FB 00 00 00 00 00");
    tb_send(BUS, "601 A1 00 00 00 00 00 00 00");
    tb_expect_none(BUS);
}

static void upload_block_size_changes_in_ack(void **state)
{
    memcpy(RAMV.vstr, "CANopen block transfer, 32 bytes", 32U);
    tb_xfer(BUS, "601 A4 12 20 00 02 00 00 00", "581 C6 12 20 00 20 00 00 00");
    tb_send(BUS, "601 A3 00 00 00 00 00 00 00");
    tb_expect(BUS, "581 01 43 41 4E 6F 70 65 6E");
    tb_expect(BUS, "581 02 20 62 6C 6F 63 6B 20");
    tb_expect_none(BUS);
    /* one of two arrived; go on with sub-blocks of 3 */
    tb_send(BUS, "601 A2 01 03 00 00 00 00 00");
    tb_expect(BUS, "581 01 20 62 6C 6F 63 6B 20");
    tb_expect(BUS, "581 02 74 72 61 6E 73 66 65");
    tb_expect(BUS, "581 03 72 2C 20 33 32 20 62");
    tb_expect_none(BUS);
    tb_xfer(BUS, "601 A2 03 7F 00 00 00 00 00", "581 81 79 74 65 73 00 00 00");
    tb_xfer(BUS, "601 A2 01 7F 00 00 00 00 00", "581 CD E1 4A 00 00 00 00 00");
    tb_send(BUS, "601 A1 00 00 00 00 00 00 00");
    tb_expect_none(BUS);
}

static void upload_sequence_and_block_size_errors(void **state)
{
    /* ackseq beyond what was sent */
    upload_start_string(state);
    tb_xfer(BUS, "601 A2 06 7F 00 00 00 00 00", "581 80 12 20 00 03 00 04 05");
    memcpy(RAMV.vstr, "CANopen block transfer, 32 bytes", 32U);
    tb_xfer(BUS, "601 A4 12 20 00 02 00 00 00", "581 C6 12 20 00 20 00 00 00");
    tb_send(BUS, "601 A3 00 00 00 00 00 00 00");
    tb_expect(BUS, "581 01 43 41 4E 6F 70 65 6E");
    tb_expect(BUS, "581 02 20 62 6C 6F 63 6B 20");
    tb_xfer(BUS, "601 A2 03 02 00 00 00 00 00", "581 80 12 20 00 03 00 04 05");
    /* invalid block size in the initiate */
    tb_xfer(BUS, "601 A4 12 20 00 00 00 00 00", "581 80 12 20 00 02 00 04 05");
    tb_xfer(BUS, "601 A4 12 20 00 80 00 00 00", "581 80 12 20 00 02 00 04 05");
    tb_xfer(BUS, "601 A0 04 20 00 FF 00 00 00", "581 80 04 20 00 02 00 04 05");
    /* invalid block size in an acknowledge */
    upload_start_string(state);
    tb_xfer(BUS, "601 A2 02 00 00 00 00 00 00", "581 80 12 20 00 02 00 04 05");
    upload_start_string(state);
    tb_xfer(BUS, "601 A2 02 80 00 00 00 00 00", "581 80 12 20 00 02 00 04 05");
    /* the server is idle again */
    tb_xfer(BUS, "601 40 04 20 00 00 00 00 00", "581 43 04 20 00 EF BE AD DE");
}

/* ---------------------------------------------------------- 6: protocol switch */

static void upload_protocol_switch(void **state)
{
    RAMV.u32 = 0x12345678UL;
    /* pst >= size: expedited */
    tb_xfer(BUS, "601 A4 04 20 00 7F 04 00 00", "581 43 04 20 00 78 56 34 12");
    tb_xfer(BUS, "601 A4 04 20 00 7F 7F 00 00", "581 43 04 20 00 78 56 34 12");
    /* pst < size, or 0: block */
    tb_xfer(BUS, "601 A4 04 20 00 7F 03 00 00", "581 C6 04 20 00 04 00 00 00");
    tb_send(BUS, "601 80 04 20 00 00 00 04 05");
    tb_expect_none(BUS);
    tb_xfer(BUS, "601 A4 04 20 00 7F 00 00 00", "581 C6 04 20 00 04 00 00 00");
    tb_send(BUS, "601 80 04 20 00 00 00 04 05");
    tb_expect_none(BUS);
    /* "hello": segmented */
    tb_xfer(BUS, "601 A4 12 20 00 7F 05 00 00", "581 41 12 20 00 05 00 00 00");
    tb_xfer(BUS, "601 60 00 00 00 00 00 00 00", "581 05 68 65 6C 6C 6F 00 00");
    tb_xfer(BUS, "601 A4 12 20 00 7F 04 00 00", "581 C6 12 20 00 05 00 00 00");
    tb_send(BUS, "601 80 12 20 00 00 00 04 05");
    tb_expect_none(BUS);
    /* a DOMAIN of 10 bytes: segmented when its size is known, block otherwise */
    memset(DOM.data, 0x5A, 10U);
    DOM.len = 10U;
    tb_xfer(BUS, "601 A4 00 22 00 7F 0A 00 00", "581 41 00 22 00 0A 00 00 00");
    tb_xfer(BUS, "601 60 00 00 00 00 00 00 00", "581 00 5A 5A 5A 5A 5A 5A 5A");
    tb_xfer(BUS, "601 70 00 00 00 00 00 00 00", "581 19 5A 5A 5A 00 00 00 00");
    DOM.tell_total = false;
    tb_xfer(BUS, "601 A4 00 22 00 7F 0A 00 00", "581 C4 00 22 00 00 00 00 00");
    tb_send(BUS, "601 80 00 22 00 00 00 04 05");
    tb_expect_none(BUS);
}

/* ---------------------------------------------------------- 7: timeouts */

static void expect_timeout(void **state, const char *abort_frame)
{
    tb_advance(BUS, 999999U);
    tb_expect_none(BUS);
    tb_advance(BUS, 1U);
    tb_expect(BUS, abort_frame);
    tb_expect_none(BUS);
    /* idle again */
    tb_xfer(BUS, "601 40 00 10 00 00 00 00 00", "581 43 00 10 00 92 01 02 00");
}

static void block_timeouts(void **state)
{
    /* download: inside a sub-block; every segment restarts the timer */
    tb_xfer(BUS, "601 C6 12 20 00 20 00 00 00", "581 A4 12 20 00 7F 00 00 00");
    tb_advance(BUS, 600000U);
    tb_send(BUS, "601 01 43 41 4E 6F 70 65 6E");
    tb_advance(BUS, 600000U);
    tb_send(BUS, "601 02 20 62 6C 6F 63 6B 20");
    tb_expect_none(BUS);
    expect_timeout(state, "581 80 12 20 00 00 00 04 05");
    /* download: waiting for the end request */
    tb_xfer(BUS, "601 C6 04 20 00 04 00 00 00", "581 A4 04 20 00 7F 00 00 00");
    tb_xfer(BUS, "601 81 78 56 34 12 00 00 00", "581 A2 01 7F 00 00 00 00 00");
    expect_timeout(state, "581 80 04 20 00 00 00 04 05");
    assert_int_equal(RAMV.u32, 0xDEADBEEFUL);
    /* upload: waiting for the start command */
    tb_xfer(BUS, "601 A4 04 20 00 7F 00 00 00", "581 C6 04 20 00 04 00 00 00");
    expect_timeout(state, "581 80 04 20 00 00 00 04 05");
    /* upload: waiting for the acknowledge */
    tb_xfer(BUS, "601 A4 04 20 00 7F 00 00 00", "581 C6 04 20 00 04 00 00 00");
    tb_xfer(BUS, "601 A3 00 00 00 00 00 00 00", "581 81 EF BE AD DE 00 00 00");
    expect_timeout(state, "581 80 04 20 00 00 00 04 05");
    /* upload: waiting for the client's end response */
    tb_xfer(BUS, "601 A4 04 20 00 7F 00 00 00", "581 C6 04 20 00 04 00 00 00");
    tb_xfer(BUS, "601 A3 00 00 00 00 00 00 00", "581 81 EF BE AD DE 00 00 00");
    tb_xfer(BUS, "601 A2 01 7F 00 00 00 00 00", "581 CD 6B F4 00 00 00 00 00");
    expect_timeout(state, "581 80 04 20 00 00 00 04 05");
}

/* ---------------------------------------------------------- 8: TX path full */

static void upload_tx_full_loses_nothing(void **state)
{
    memcpy(RAMV.vstr, "CANopen block transfer, 32 bytes", 32U);
    tb_xfer(BUS, "601 A4 12 20 00 7F 00 00 00", "581 C6 12 20 00 20 00 00 00");
    BUS->refuse = 3U;
    tb_send(BUS, "601 A3 00 00 00 00 00 00 00");
    tb_expect_none(BUS);
    tb_advance(BUS, 1000U);
    tb_expect_none(BUS);
    tb_advance(BUS, 1000U);
    assert_int_equal(BUS->refused, 3U);
    tb_expect(BUS, "581 01 43 41 4E 6F 70 65 6E");
    tb_expect(BUS, "581 02 20 62 6C 6F 63 6B 20");
    tb_expect(BUS, "581 03 74 72 61 6E 73 66 65");
    tb_expect(BUS, "581 04 72 2C 20 33 32 20 62");
    tb_expect(BUS, "581 85 79 74 65 73 00 00 00");
    tb_expect_none(BUS);
    tb_xfer(BUS, "601 A2 05 7F 00 00 00 00 00", "581 CD E1 4A 00 00 00 00 00");
    tb_send(BUS, "601 A1 00 00 00 00 00 00 00");
    tb_expect_none(BUS);
}

static void upload_tx_full_mid_sub_block(void **state)
{
    uint8_t r[8];

    dom_count(&DOM, 100U, 0x00U); /* 15 segments, 2 bytes in the last */
    tb_xfer(BUS, "601 A4 00 22 00 7F 00 00 00", "581 C6 00 22 00 64 00 00 00");
    /* the TX path fills up after the fifth segment */
    BUS->refuse_after = 5U;
    BUS->refuse = 4U;
    tb_send(BUS, "601 A3 00 00 00 00 00 00 00");
    for (uint32_t k = 0U; k < 5U; k++) {
        (void)memset(r, 0, sizeof r);
        r[0] = (uint8_t)(k + 1U);
        (void)memcpy(&r[1], &DOM.data[k * 7U], 7U);
        EXPECT_BYTES(BUS, r);
    }
    tb_expect_none(BUS);
    tb_advance(BUS, 10000U);
    assert_int_equal(BUS->refused, 4U);
    for (uint32_t k = 5U; k < 15U; k++) {
        uint32_t n = (k == 14U) ? 2U : 7U;
        (void)memset(r, 0, sizeof r);
        r[0] = (uint8_t)((k + 1U) | ((k == 14U) ? 0x80U : 0U));
        (void)memcpy(&r[1], &DOM.data[k * 7U], n);
        EXPECT_BYTES(BUS, r);
    }
    tb_expect_none(BUS);
    (void)memset(r, 0, sizeof r);
    r[0] = (uint8_t)(0xC1U | (5U << 2U));
    co_put_u16(&r[1], ref_crc(DOM.data, 100U));
    tb_send(BUS, "601 A2 0F 7F 00 00 00 00 00");
    EXPECT_BYTES(BUS, r);
    tb_expect_none(BUS);
    tb_send(BUS, "601 A1 00 00 00 00 00 00 00");
    tb_expect_none(BUS);
}

/* The server reads the value a chunk of segments at a time: the hook runs
 * once per chunk, whatever the block size, a retransmission starts a chunk
 * where it resumes, and a hook that produces less than asked goes on where
 * it stopped. */
static void upload_reads_chunks(void **state)
{
    static const uint8_t sizes[] = {1U, 2U, 7U, 8U, 9U, 127U};
    static uint8_t src[1000];
    static uint8_t back[1000 + 7];
    uint32_t n;

    fill_random(src, sizeof src, 0xC0FFEEU);
    (void)memcpy(DOM.data, src, sizeof src);
    DOM.len = 100U; /* 15 segments: the first read at the initiate (7
                       bytes), then 7..62 and 63..99 */
    {
        const ul_cfg_t ul = {true, 127U, 0U, 0U};
        n = client_block_upload(BUS, 0x2200U, 0U, back, 100U, true, 100U, &ul);
        assert_int_equal(n, 100U);
        assert_memory_equal(back, src, 100U);
        assert_int_equal(DOM.reads, 3U);
    }
    /* 1000 bytes, block sizes from 1 to 127, half of the first block
     * acknowledged (none of it with 1): frames and the CRC of the end frame
     * exact (client_block_upload) */
    DOM.len = sizeof src;
    for (uint32_t k = 0U; k < sizeof sizes; k++) {
        const ul_cfg_t ul = {true, sizes[k], 1U, (uint8_t)(sizes[k] / 2U)};
        (void)memset(back, 0, sizeof back);
        n = client_block_upload(BUS, 0x2200U, 0U, back, sizeof src, true, sizeof src, &ul);
        assert_int_equal(n, sizeof src);
        assert_memory_equal(back, src, sizeof src);
    }
    /* a hook that produces at most 10 bytes a read: the same frames */
    DOM.max_read = 10U;
    {
        const ul_cfg_t ul = {true, 127U, 1U, 100U};
        (void)memset(back, 0, sizeof back);
        n = client_block_upload(BUS, 0x2200U, 0U, back, sizeof src, true, sizeof src, &ul);
        assert_int_equal(n, sizeof src);
        assert_memory_equal(back, src, sizeof src);
    }
    /* ... at most 5 bytes: a segment would be short before the end */
    DOM.max_read = 5U;
    tb_xfer(BUS, "601 A4 00 22 00 7F 00 00 00", "581 C6 00 22 00 E8 03 00 00");
    tb_xfer(BUS, "601 A3 00 00 00 00 00 00 00", "581 80 00 22 00 00 00 00 08");
    /* ... and in the middle of the value */
    DOM.max_read = 0U;
    tb_xfer(BUS, "601 A4 00 22 00 7F 00 00 00", "581 C6 00 22 00 E8 03 00 00");
    DOM.max_read = 3U;
    tb_send(BUS, "601 A3 00 00 00 00 00 00 00");
    {
        uint8_t r[8] = {0x01U};
        (void)memcpy(&r[1], src, 7U);
        EXPECT_BYTES(BUS, r);
    }
    tb_expect(BUS, "581 80 00 22 00 00 00 00 08");
    tb_expect_none(BUS);
}

/* A segmented upload of a value a hook produces a few bytes at a time:
 * each segment carries what one read gave, the first the chunk staged at
 * the initiate (its length kept beside it in the staging buffer). */
static void segmented_upload_short_chunks(void **state)
{
    dom_count(&DOM, 10U, 0x30U);
    DOM.max_read = 3U;
    tb_xfer(BUS, "601 40 00 22 00 00 00 00 00", "581 41 00 22 00 0A 00 00 00");
    tb_xfer(BUS, "601 60 00 00 00 00 00 00 00", "581 08 30 31 32 00 00 00 00");
    tb_xfer(BUS, "601 70 00 00 00 00 00 00 00", "581 18 33 34 35 00 00 00 00");
    tb_xfer(BUS, "601 60 00 00 00 00 00 00 00", "581 08 36 37 38 00 00 00 00");
    tb_xfer(BUS, "601 70 00 00 00 00 00 00 00", "581 1D 39 00 00 00 00 00 00");
    tb_expect_none(BUS);
    assert_int_equal(DOM.reads, 4U); /* the first segment read no more */
}

/* ---------------------------------------------------------- 9: options */

static void options_disable_block_transfers(void **state)
{
    co_dev_t dev = td_dev;

    dev.set = (co_settings_t){.sdo.refused = CO_SDO_XFER_BLOCK};
    td_start(&FX->n2, BUS, 1, 2, &dev);
    tb_expect(BUS, "702 00");
    tb_xfer(BUS, "602 C6 04 20 00 04 00 00 00", "582 80 04 20 00 01 00 04 05");
    tb_xfer(BUS, "602 C0 12 20 00 00 00 00 00", "582 80 12 20 00 01 00 04 05");
    tb_xfer(BUS, "602 A4 04 20 00 7F 00 00 00", "582 80 04 20 00 01 00 04 05");
    tb_xfer(BUS, "602 A0 12 20 00 7F 05 00 00", "582 80 12 20 00 01 00 04 05");
    /* expedited and segmented transfers still work */
    tb_xfer(BUS, "602 40 04 20 00 00 00 00 00", "582 43 04 20 00 EF BE AD DE");
    tb_xfer(BUS, "602 40 12 20 00 00 00 00 00", "582 41 12 20 00 05 00 00 00");
    tb_xfer(BUS, "602 60 00 00 00 00 00 00 00", "582 05 68 65 6C 6C 6F 00 00");
    /* node 1 of the plain device has them */
    tb_xfer(BUS, "601 A4 04 20 00 7F 00 00 00", "581 C6 04 20 00 04 00 00 00");
    tb_send(BUS, "601 80 04 20 00 00 00 04 05");
    tb_expect_none(BUS);

    /* expedited only implies no block transfers either */
    dev.set = (co_settings_t){.sdo.refused = CO_SDO_EXPEDITED_ONLY};
    td_start(&FX->n2, BUS, 1, 3, &dev);
    tb_expect(BUS, "703 00");
    tb_xfer(BUS, "603 C6 04 20 00 04 00 00 00", "583 80 04 20 00 01 00 04 05");
    tb_xfer(BUS, "603 A4 04 20 00 7F 00 00 00", "583 80 04 20 00 01 00 04 05");
    BUS->nodes[1] = NULL;
}

/* ---------------------------------------------------------- other commands */

static void client_abort_and_wrong_commands(void **state)
{
    /* a client abort ends a block download silently */
    tb_xfer(BUS, "601 C6 12 20 00 20 00 00 00", "581 A4 12 20 00 7F 00 00 00");
    tb_send(BUS, "601 01 43 41 4E 6F 70 65 6E");
    tb_send(BUS, "601 80 12 20 00 00 00 04 05");
    tb_expect_none(BUS);
    tb_xfer(BUS, "601 40 04 20 00 00 00 00 00", "581 43 04 20 00 EF BE AD DE");
    /* ... and a block upload */
    upload_start_string(state);
    tb_send(BUS, "601 80 12 20 00 00 00 04 05");
    tb_expect_none(BUS);
    tb_xfer(BUS, "601 40 04 20 00 00 00 00 00", "581 43 04 20 00 EF BE AD DE");
    /* an end request without a transfer */
    tb_xfer(BUS, "601 C1 00 00 00 00 00 00 00", "581 80 00 00 00 01 00 04 05");
    /* a wrong command where the end request is due */
    tb_xfer(BUS, "601 C6 04 20 00 04 00 00 00", "581 A4 04 20 00 7F 00 00 00");
    tb_xfer(BUS, "601 81 78 56 34 12 00 00 00", "581 A2 01 7F 00 00 00 00 00");
    tb_xfer(BUS, "601 40 04 20 00 00 00 00 00", "581 80 04 20 00 01 00 04 05");
    /* a wrong command where the start command is due */
    tb_xfer(BUS, "601 A4 04 20 00 7F 00 00 00", "581 C6 04 20 00 04 00 00 00");
    tb_xfer(BUS, "601 A2 00 7F 00 00 00 00 00", "581 80 04 20 00 01 00 04 05");
    /* block transfers of objects that cannot be accessed */
    tb_xfer(BUS, "601 C6 00 10 00 04 00 00 00", "581 80 00 10 00 02 00 01 06");
    tb_xfer(BUS, "601 A4 22 20 00 7F 00 00 00", "581 80 22 20 00 01 00 01 06");
    tb_xfer(BUS, "601 A4 34 12 00 7F 00 00 00", "581 80 34 12 00 00 00 02 06");
    tb_xfer(BUS, "601 C6 04 20 00 05 00 00 00", "581 80 04 20 00 10 00 07 06");
    assert_int_equal(RAMV.u32, 0xDEADBEEFUL);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(reference_crc_check_value),
        cmocka_unit_test_setup(block_download_crc_check_value, setup),
        cmocka_unit_test_setup(block_download_u32, setup),
        cmocka_unit_test_setup(block_download_u64_two_segments, setup),
        cmocka_unit_test_setup(block_download_u64_last_segment_too_long, setup),
        cmocka_unit_test_setup(block_download_string, setup),
        cmocka_unit_test_setup(block_download_size_mismatch, setup),
        cmocka_unit_test_setup(block_upload_u32, setup),
        cmocka_unit_test_setup(block_upload_string, setup),
        cmocka_unit_test_setup(block_upload_domain_with_and_without_size, setup),
        cmocka_unit_test_setup(upload_sends_no_more_than_announced, setup),
        cmocka_unit_test_setup(domain_100k_round_trip, setup),
        cmocka_unit_test_setup(domain_round_trip_variants, setup),
        cmocka_unit_test_setup(crc_error_aborts_and_commits_nothing, setup),
        cmocka_unit_test_setup(download_lost_segment_is_repeated, setup),
        cmocka_unit_test_setup(download_seqno_zero_aborts, setup),
        cmocka_unit_test_setup(upload_partial_ack_retransmits, setup),
        cmocka_unit_test_setup(upload_block_size_changes_in_ack, setup),
        cmocka_unit_test_setup(upload_sequence_and_block_size_errors, setup),
        cmocka_unit_test_setup(upload_protocol_switch, setup),
        cmocka_unit_test_setup(block_timeouts, setup),
        cmocka_unit_test_setup(upload_tx_full_loses_nothing, setup),
        cmocka_unit_test_setup(upload_tx_full_mid_sub_block, setup),
        cmocka_unit_test_setup(upload_reads_chunks, setup),
        cmocka_unit_test_setup(segmented_upload_short_chunks, setup),
        cmocka_unit_test_setup(options_disable_block_transfers, setup),
        cmocka_unit_test_setup(client_abort_and_wrong_commands, setup),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
