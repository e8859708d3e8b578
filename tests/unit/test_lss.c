/*
 * LSS slave (CiA 305): every request frame-exact with its answers and error
 * answers, the state rules (waiting vs configuration), unconfigured nodes,
 * the node-ID change and the COB-IDs that follow it (CiA default and the
 * FAULHABER options), the stored configuration, and fastscan against several
 * unconfigured nodes on one in-memory bus. Device: tests/unit/devices/
 * lss-test.toml (vendor 0xA5, product 0x305, revision 0x00020001, serial
 * set per node).
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
#include "lss_test.h"
#include "test_bus.h"
#include "test_frames.h"

#define UNCONF CO_NODE_ID_UNCONFIGURED
#define N_NODES TB_NODES_MAX

typedef struct fx {
    tb_bus_t bus;
    lss_test_node_t n[N_NODES];
    co_dev_t dev;
    uint32_t serial[N_NODES];
    int resets[N_NODES];
    co_node_callbacks_t cb[N_NODES];
} fx_t;

static fx_t fx;

/* The application keeps the serial number (a RAM value a node reset clears). */
static void set_serial(co_node_t *node, uint32_t serial)
{
    uint8_t b[4];

    co_put_u32(b, serial); /* co_od_write takes wire bytes (little-endian) */
    assert_int_equal(co_od_write(node, 0x1018U, 4U, b, 4U, true), CO_OK);
}

static void on_reset(void *ctx, co_node_t *node, co_reset_t kind)
{
    uint8_t idx = (uint8_t)(uintptr_t)ctx;
    fx.resets[idx]++;
    if (kind == CO_RESET_NODE) {
        set_serial(node, fx.serial[idx]);
    }
}

/* lss-test's device, with the LSS settings of @p lss when not NULL (an LSS
 * slave either way) */
static void setup_bus(const co_settings_t *lss)
{
    memset(&fx, 0, sizeof fx);
    tb_init(&fx.bus);
    fx.dev = lss_test_dev;
    if (lss != NULL) {
        fx.dev.set.lss = lss->lss;
        fx.dev.set.lss.slave = 1U;
    }
}

/* (Re)start node @p idx with node-ID @p id (UNCONF: unconfigured) on its NV. */
static co_result_t start_ops(uint8_t idx, uint8_t id, uint32_t serial, const co_hal_ops_t *ops)
{
    co_node_config_t cfg;
    co_result_t e;

    lss_test_config(&fx.n[idx], &cfg);
    cfg.dev = &fx.dev;
    cfg.hal = tb_hal(&fx.bus, idx);
    cfg.hal.ops = ops;
    cfg.node_id = id;
    (void)memset(&fx.cb[idx], 0, sizeof fx.cb[idx]);
    fx.cb[idx].ctx = (void *)(uintptr_t)idx;
    fx.cb[idx].nmt_reset = on_reset;
    cfg.cb = &fx.cb[idx];
    fx.serial[idx] = serial;
    e = co_node_init(&fx.n[idx].node, &cfg, fx.bus.now);
    if (e == CO_RESULT_OK) {
        set_serial(&fx.n[idx].node, serial);
        tb_attach(&fx.bus, idx, &fx.n[idx].node);
    }
    return e;
}

static void start(uint8_t idx, uint8_t id, uint32_t serial)
{
    assert_int_equal(start_ops(idx, id, serial, &tb_hal_ops), CO_RESULT_OK);
}

/* @p cob + @p bytes, padded with zeros to 8 bytes (LSS frames are 8 long). */
static void pad(char *out, size_t cap, const char *cob, const char *bytes)
{
    size_t n = 0U;
    bool in_word = false;

    for (const char *p = bytes; *p != '\0'; p++) {
        if ((*p != ' ') && !in_word) {
            n++;
        }
        in_word = (*p != ' ');
    }
    snprintf(out, cap, "%s %s", cob, bytes);
    for (; n < 8U; n++) {
        strncat(out, " 00", cap - strlen(out) - 1U);
    }
}

static void req(const char *bytes)
{
    char f[64];
    pad(f, sizeof f, "7E5", bytes);
    tb_send(&fx.bus, f);
}

#define ans(bytes)                                                                               \
    do {                                                                                         \
        char f_[64];                                                                             \
        pad(f_, sizeof f_, "7E4", (bytes));                                                      \
        tb_expect(&fx.bus, f_);                                                                  \
    } while (0)

/* a request with exactly one answer / with none */
#define xfer(rq, an)                                                                             \
    do {                                                                                         \
        req(rq);                                                                                 \
        ans(an);                                                                                 \
        tb_expect_none(&fx.bus);                                                                 \
    } while (0)
#define silent(rq)                                                                               \
    do {                                                                                         \
        req(rq);                                                                                 \
        tb_expect_none(&fx.bus);                                                                 \
    } while (0)

static uint32_t u32_of(uint8_t idx, uint16_t index, uint8_t sub)
{
    uint8_t b[4] = {0};
    uint32_t len = 0U;
    assert_int_equal(co_od_read(&fx.n[idx].node, index, sub, b, 4U, &len), CO_OK);
    return co_get_u32(b);
}

/* ------------------------------------------------------------------ tests */

/* Node-ID 0xFF: no boot-up, nothing but LSS, not even with a heartbeat time
 * or an EMCY; NMT, SDO and guarding for any ID are not served. */
static void test_unconfigured_silent(void **state)
{
    (void)state;
    setup_bus(NULL);
    start(0, UNCONF, 1U);
    tb_expect_none(&fx.bus);
    assert_int_equal(co_node_id(&fx.n[0].node), UNCONF);
    assert_int_equal(co_node_nmt_state(&fx.n[0].node), CO_NMT_INITIALISING);
    fx.n[0].ram.x1017_producer_heartbeat_time = 10U;
    co_emcy_raise(&fx.n[0].node, 0x5000U, 0U, NULL);
    tb_send(&fx.bus, "000 01 00");
    tb_send(&fx.bus, "000 82 00");
    tb_send(&fx.bus, "67F 40 00 10 00 00 00 00 00");
    tb_send(&fx.bus, "6FF 40 00 10 00 00 00 00 00");
    tb_send(&fx.bus, "77F R");
    tb_advance(&fx.bus, 100000U);
    tb_expect_none(&fx.bus);
    assert_int_equal(co_node_nmt_state(&fx.n[0].node), CO_NMT_INITIALISING);
    /* it is there for LSS */
    xfer("4C", "50");
}

/* A node without the LSS option cannot start unconfigured. */
static void test_unconfigured_needs_lss(void **state)
{
    (void)state;
    setup_bus(NULL);
    fx.dev.set.lss.slave = 0U;
    assert_int_equal(start_ops(0, UNCONF, 1U, &tb_hal_ops), CO_RESULT_BAD_NODE_ID);
    assert_int_equal(start_ops(0, 0U, 1U, &tb_hal_ops), CO_RESULT_BAD_NODE_ID);
    assert_int_equal(start_ops(0, 128U, 1U, &tb_hal_ops), CO_RESULT_BAD_NODE_ID);
    /* and without LSS nothing answers on 0x7E5 */
    start(0, 5U, 1U);
    tb_expect(&fx.bus, "705 00");
    silent("04 01");
    silent("5E");
    silent("4C");
}

/* Quick start (FAULHABER §2.1/§2.2): one unconfigured node, switch global to
 * configuration, node-ID and bit timing, store, back to waiting: the node
 * initialises at once and sends its boot-up at the new ID. */
static void test_global_configure_store(void **state)
{
    (void)state;
    setup_bus(NULL);
    start(0, UNCONF, 7U);
    silent("04 01");
    xfer("5E", "5E FF");
    xfer("11 05", "11 00");
    xfer("5E", "5E FF"); /* still the active one until waiting */
    xfer("13 00 03", "13 00");
    xfer("17", "17 00");
    tb_expect_none(&fx.bus);
    req("04 00");
    tb_expect(&fx.bus, "705 00");
    tb_expect_none(&fx.bus);
    assert_int_equal(co_node_id(&fx.n[0].node), 5U);
    assert_int_equal(co_node_nmt_state(&fx.n[0].node), CO_NMT_PRE_OPERATIONAL);
    /* the COB-IDs of the pre-defined connection set for node 5 */
    assert_int_equal(u32_of(0, 0x1014U, 0U), 0x85U);
    assert_int_equal(u32_of(0, 0x1400U, 1U), 0x205U);
    assert_int_equal(u32_of(0, 0x1800U, 1U), 0x185U);
    assert_int_equal(u32_of(0, 0x1018U, 4U), 7U); /* the application's serial */
    tb_xfer(&fx.bus, "605 40 18 10 01 00 00 00 00", "585 43 18 10 01 A5 00 00 00");
    /* the next power-on: the stored node-ID and bit timing, whatever the config says */
    fx.bus.bit_timing_calls = 0U;
    start(0, UNCONF, 7U);
    tb_expect(&fx.bus, "705 00");
    assert_int_equal(fx.bus.bit_timing_calls, 1U);
    assert_int_equal(fx.bus.bit_timing[0], 3U);
    assert_int_equal(co_node_bit_timing(&fx.n[0].node), 3U); /* the stored one */
    start(0, 9U, 7U);
    tb_expect(&fx.bus, "705 00");
    tb_expect_none(&fx.bus);
}

/* FAULHABER: the node-ID comes only through LSS; the configured one is
 * not used, the LSS-stored one is. */
static void test_lss_only(void **state)
{
    (void)state;
    setup_bus(&(co_settings_t){.lss.node_id = CO_LSS_ID_ONLY});
    start(0, 5U, 1U);
    tb_expect_none(&fx.bus);
    assert_int_equal(co_node_id(&fx.n[0].node), UNCONF);
    silent("04 01");
    xfer("11 06", "11 00");
    xfer("17", "17 00");
    req("04 00");
    tb_expect(&fx.bus, "706 00");
    start(0, 5U, 1U);
    tb_expect(&fx.bus, "706 00");
    tb_expect_none(&fx.bus);
}

/* Configure node-ID: 1..127 and 0xFF accepted, the rest answered with
 * error code 1 (node-ID out of range), the pending ID unchanged. */
static void test_configure_node_id_range(void **state)
{
    (void)state;
    setup_bus(NULL);
    start(0, 3U, 1U);
    tb_flush(&fx.bus);
    silent("04 01");
    xfer("11 00", "11 01");
    xfer("11 80", "11 01");
    xfer("11 FE", "11 01");
    xfer("11 01", "11 00");
    xfer("11 7F", "11 00");
    xfer("11 FF", "11 00");
    xfer("11 81", "11 01");
    assert_int_equal(fx.n[0].node.pending_id, UNCONF);
    /* a configured node keeps its ID until a reset communication */
    xfer("5E", "5E 03");
    xfer("11 0C", "11 00");
    silent("04 00");
    assert_int_equal(co_node_id(&fx.n[0].node), 3U);
    tb_xfer(&fx.bus, "603 40 00 10 00 00 00 00 00", "583 43 00 10 00 00 00 00 00");
    tb_send(&fx.bus, "000 82 03");
    tb_expect(&fx.bus, "70C 00");
    tb_expect_none(&fx.bus);
    assert_int_equal(co_node_id(&fx.n[0].node), 12U);
    tb_send(&fx.bus, "603 40 00 10 00 00 00 00 00");
    tb_expect_none(&fx.bus);
    tb_xfer(&fx.bus, "60C 40 00 10 00 00 00 00 00", "58C 43 00 10 00 00 00 00 00");
}

/* Which request is served in which state. */
static void test_state_rules(void **state)
{
    (void)state;
    setup_bus(NULL);
    start(0, UNCONF, 0x11U);
    /* waiting: configuration requests and inquiries get nothing */
    silent("11 05");
    silent("13 00 02");
    silent("15 0A 00");
    silent("17");
    silent("5A");
    silent("5B");
    silent("5C");
    silent("5D");
    silent("5E");
    assert_int_equal(fx.n[0].node.pending_id, UNCONF);
    /* waiting: identify and fastscan are served */
    xfer("4C", "50");
    xfer("51 00 00 00 00 80 00 00", "4F");
    /* configuration: fastscan and switch selective are not */
    silent("04 01");
    silent("51 00 00 00 00 80 00 00");
    silent("40 A5 00 00 00");
    silent("41 05 03 00 00");
    silent("42 01 00 02 00");
    silent("43 11 00 00 00");
    xfer("4C", "50");
    xfer("5A", "5A A5 00 00 00");
    /* a reserved switch mode changes nothing */
    silent("04 02");
    xfer("5B", "5B 05 03 00 00");
    silent("04 00");
    silent("5B");
    /* malformed: not 8 bytes, a remote frame, an unknown specifier */
    silent("04 01");
    tb_send(&fx.bus, "7E5 5E 00 00 00 00 00 00");
    tb_send(&fx.bus, "7E5 R8");
    tb_send(&fx.bus, "7E5 5E");
    tb_expect_none(&fx.bus);
    silent("20");
    silent("FF");
    xfer("5E", "5E FF");
}

/* Inquire identity and node-ID (configuration state). */
static void test_inquire(void **state)
{
    (void)state;
    setup_bus(NULL);
    start(0, 0x22U, 0x8899AABBU);
    tb_flush(&fx.bus);
    silent("04 01");
    xfer("5A", "5A A5 00 00 00");
    xfer("5B", "5B 05 03 00 00");
    xfer("5C", "5C 01 00 02 00");
    xfer("5D", "5D BB AA 99 88");
    xfer("5E", "5E 22");
}

/* Switch state selective: the four parts in order, the answer 0x44, then
 * configuration; any mismatch or a part out of order starts over. */
static void test_switch_selective(void **state)
{
    (void)state;
    setup_bus(NULL);
    start(0, 0x10U, 0x1234U);
    start(1, 0x11U, 0x1235U);
    tb_flush(&fx.bus);
    silent("40 A5 00 00 00");
    silent("41 05 03 00 00");
    silent("42 01 00 02 00");
    req("43 35 12 00 00");
    ans("44");
    tb_expect_none(&fx.bus);
    assert_int_equal(fx.bus.from[fx.bus.n_log - 1U], 1U);
    xfer("5E", "5E 11"); /* only node 0x11 is in configuration */
    silent("04 00");
    /* wrong vendor, wrong revision, order broken, restart in the middle */
    silent("40 A6 00 00 00");
    silent("41 05 03 00 00");
    silent("42 01 00 02 00");
    silent("43 34 12 00 00");
    silent("40 A5 00 00 00");
    silent("41 05 03 00 00");
    silent("42 00 00 00 00");
    silent("43 34 12 00 00");
    silent("41 05 03 00 00");
    silent("42 01 00 02 00");
    silent("43 34 12 00 00");
    silent("40 A5 00 00 00");
    silent("41 05 03 00 00");
    silent("40 A5 00 00 00");
    silent("41 05 03 00 00");
    silent("42 01 00 02 00");
    req("43 34 12 00 00");
    ans("44");
    tb_expect_none(&fx.bus);
    xfer("5E", "5E 10");
}

/* FAULHABER: the revision number is not compared (the master may send 0). */
static void test_switch_selective_no_revision(void **state)
{
    (void)state;
    setup_bus(&(co_settings_t){.lss.selective = CO_LSS_IGNORE_REVISION});
    start(0, 0x10U, 0x1234U);
    tb_flush(&fx.bus);
    silent("40 A5 00 00 00");
    silent("41 05 03 00 00");
    silent("42 00 00 00 00");
    xfer("43 34 12 00 00", "44");
    xfer("5E", "5E 10");
    silent("04 00");
    /* the other parts still count */
    silent("40 A5 00 00 00");
    silent("41 06 03 00 00");
    silent("42 00 00 00 00");
    silent("43 34 12 00 00");
}

/* Identify remote slave: vendor, product, revision and serial ranges
 * (bounds included), in both states; 0x4F from every node inside. */
static void test_identify_remote(void **state)
{
    (void)state;
    setup_bus(NULL);
    start(0, 0x10U, 100U);
    start(1, 0x11U, 200U);
    tb_flush(&fx.bus);
    silent("46 A5 00 00 00");
    silent("47 05 03 00 00");
    silent("48 01 00 02 00");
    silent("49 01 00 02 00");
    silent("4A 64 00 00 00");
    req("4B C7 00 00 00"); /* 100..199: node 0 */
    ans("4F");
    tb_expect_none(&fx.bus);
    assert_int_equal(fx.bus.from[fx.bus.n_log - 1U], 0U);
    /* both; node 1 in configuration */
    silent("40 A5 00 00 00");
    silent("41 05 03 00 00");
    silent("42 01 00 02 00");
    xfer("43 C8 00 00 00", "44");
    silent("46 A5 00 00 00");
    silent("47 05 03 00 00");
    silent("48 00 00 00 00");
    silent("49 FF FF FF FF");
    silent("4A 00 00 00 00");
    req("4B C8 00 00 00");
    ans("4F");
    ans("4F");
    tb_expect_none(&fx.bus);
    /* revision outside, serial outside, wrong product, order broken */
    silent("46 A5 00 00 00");
    silent("47 05 03 00 00");
    silent("48 02 00 02 00");
    silent("49 FF FF FF FF");
    silent("4A 00 00 00 00");
    silent("4B C8 00 00 00");
    silent("46 A5 00 00 00");
    silent("47 05 03 00 00");
    silent("48 00 00 00 00");
    silent("49 FF FF FF FF");
    silent("4A 65 00 00 00");
    silent("4B C7 00 00 00");
    silent("46 A5 00 00 00");
    silent("47 04 03 00 00");
    silent("48 00 00 00 00");
    silent("49 FF FF FF FF");
    silent("4A 00 00 00 00");
    silent("4B C8 00 00 00");
    silent("46 A5 00 00 00");
    silent("48 00 00 00 00");
    silent("49 FF FF FF FF");
    silent("4A 00 00 00 00");
    silent("4B C8 00 00 00");
}

/* Identify non-configured remote slave: only nodes whose active and
 * pending node-IDs are 0xFF answer, in either state. */
static void test_identify_non_configured(void **state)
{
    (void)state;
    setup_bus(NULL);
    start(0, UNCONF, 1U);
    start(1, 0x20U, 2U);
    tb_flush(&fx.bus);
    req("4C");
    ans("50");
    tb_expect_none(&fx.bus);
    assert_int_equal(fx.bus.from[fx.bus.n_log - 1U], 0U);
    silent("04 01");
    xfer("4C", "50");
    /* a pending node-ID: no longer answers */
    req("11 30");
    ans("11 00");
    ans("11 00");
    silent("4C");
}

/* Configure bit timing: table 0 with the device's rates; error 1 for
 * another table, a reserved index and a rate the device lacks. Activate
 * bit timing switches after the switch delay, not before. */
static void test_bit_timing(void **state)
{
    (void)state;
    setup_bus(NULL);
    start(0, 0x10U, 1U);
    tb_flush(&fx.bus);
    silent("04 01");
    xfer("13 00 01", "13 01"); /* 800 kbit/s: not in lss-test's baudrates */
    xfer("13 00 05", "13 01"); /* reserved */
    xfer("13 00 09", "13 01"); /* automatic detection: not offered */
    xfer("13 00 0A", "13 01");
    xfer("13 01 00", "13 01"); /* table 1: none */
    xfer("13 FF 02", "13 01");
    xfer("13 00 00", "13 00");
    xfer("13 00 08", "13 00");
    xfer("13 00 02", "13 00");
    assert_int_equal(fx.bus.bit_timing_calls, 0U);
    assert_int_equal(co_node_bit_timing(&fx.n[0].node), 0xFFU); /* configured, not active */
    silent("15 64 00"); /* 100 ms */
    tb_advance(&fx.bus, 99000U);
    assert_int_equal(fx.bus.bit_timing_calls, 0U);
    tb_advance(&fx.bus, 1000U);
    assert_int_equal(fx.bus.bit_timing_calls, 1U);
    assert_int_equal(fx.bus.bit_timing[0], 2U);
    assert_int_equal(co_node_bit_timing(&fx.n[0].node), 2U);
    tb_advance(&fx.bus, 500000U);
    assert_int_equal(fx.bus.bit_timing_calls, 1U);
    /* not in waiting */
    silent("04 00");
    silent("15 00 00");
    tb_advance(&fx.bus, 1000U);
    assert_int_equal(fx.bus.bit_timing_calls, 1U);
    /* without a configured bit timing there is nothing to activate */
    setup_bus(NULL);
    start(0, 0x10U, 1U);
    tb_flush(&fx.bus);
    silent("04 01");
    silent("15 00 00");
    tb_advance(&fx.bus, 1000U);
    assert_int_equal(fx.bus.bit_timing_calls, 0U);
}

/* Store configuration: 0 done, 1 not supported (no NV), 2 media error;
 * a failed store keeps the previous configuration. */
static void test_store_errors(void **state)
{
    (void)state;
    setup_bus(NULL);
    assert_int_equal(start_ops(0, 0x10U, 1U, &tb_hal_ops_no_nv), CO_RESULT_OK);
    tb_flush(&fx.bus);
    silent("04 01");
    xfer("17", "17 01");

    setup_bus(NULL);
    start(0, 0x10U, 1U);
    tb_flush(&fx.bus);
    silent("04 01");
    xfer("11 20", "11 00");
    xfer("17", "17 00");
    xfer("11 21", "11 00");
    fx.bus.nv_fail_write = true;
    xfer("17", "17 02");
    fx.bus.nv_fail_write = false;
    start(0, 0x10U, 1U);
    tb_expect(&fx.bus, "720 00");
    /* a power cut in the middle of a store keeps the previous one */
    silent("04 01");
    xfer("11 22", "11 00");
    tb_nv_cut(&fx.bus, 9U, true);
    xfer("17", "17 02");
    tb_nv_power_on(&fx.bus);
    start(0, 0x10U, 1U);
    tb_expect(&fx.bus, "720 00");
    silent("04 01");
    xfer("11 23", "11 00");
    xfer("17", "17 00");
    start(0, 0x10U, 1U);
    tb_expect(&fx.bus, "723 00");
    tb_expect_none(&fx.bus);
}

/* Store configuration on flash written in the background (tb_hal_ops_async:
 * erase units of TB_NV_ERASE_UNIT bytes, every erase and write busy for 40
 * polls): each record has an erase unit of its own behind the parameter
 * banks, erased before it is written; the answer comes when the record is
 * durable and the node serves the bus meanwhile. */
static void test_store_async_flash(void **state)
{
    uint32_t unit_base;
    unsigned polls;

    (void)state;
    setup_bus(0U);
    fx.bus.nv_busy_each = 40U;
    assert_int_equal(start_ops(0, 0x10U, 1U, &tb_hal_ops_async), CO_RESULT_OK);
    tb_flush(&fx.bus);
    unit_base = co_store_nv_size_unit(&fx.dev, TB_NV_ERASE_UNIT) - 2U * TB_NV_ERASE_UNIT;
    silent("04 01");
    xfer("11 20", "11 00");
    silent("17"); /* erasing: no answer yet */
    assert_int_equal(fx.bus.nv_erases, 1U);
    assert_int_equal(fx.bus.nv_erase_addr, unit_base); /* no record yet: record 0 */
    assert_int_equal(fx.bus.nv_erase_len, TB_NV_ERASE_UNIT);
    xfer("5E", "5E 10"); /* served meanwhile */
    xfer("17", "17 02"); /* a second store while one is written: refused */
    polls = fx.bus.nv_polls;
    tb_advance(&fx.bus, 30000U);
    tb_expect_none(&fx.bus);
    tb_advance(&fx.bus, 60000U);
    ans("17 00");
    tb_expect_none(&fx.bus);
    assert_in_range(fx.bus.nv_polls - polls, 80U, 84U); /* erase, then the record */
    assert_int_equal(fx.bus.nv_unerased, 0U);
    /* the next one goes to the other record's unit */
    xfer("11 21", "11 00");
    silent("17");
    assert_int_equal(fx.bus.nv_erase_addr, unit_base + TB_NV_ERASE_UNIT);
    tb_advance(&fx.bus, 100000U);
    ans("17 00");
    assert_int_equal(fx.bus.nv_unerased, 0U);
    /* a failure the HAL reports: media error */
    xfer("11 22", "11 00");
    fx.bus.nv_fail_poll = true;
    silent("17");
    tb_advance(&fx.bus, 100000U);
    ans("17 02");
    fx.bus.nv_fail_poll = false;
    tb_expect_none(&fx.bus);
    assert_int_equal(start_ops(0, 0x10U, 1U, &tb_hal_ops_async), CO_RESULT_OK);
    tb_expect(&fx.bus, "721 00");
    tb_expect_none(&fx.bus);
}

/* CiA default: at reset communication the new node-ID's COB-IDs. */
static void test_change_cia_cobs_follow(void **state)
{
    (void)state;
    setup_bus(NULL);
    start(0, 5U, 1U);
    tb_flush(&fx.bus);
    silent("04 01");
    xfer("11 07", "11 00");
    silent("04 00");
    tb_send(&fx.bus, "000 82 05");
    tb_expect(&fx.bus, "707 00");
    tb_expect_none(&fx.bus);
    assert_int_equal(u32_of(0, 0x1014U, 0U), 0x87U);
    assert_int_equal(u32_of(0, 0x1400U, 1U), 0x207U);
    assert_int_equal(u32_of(0, 0x1800U, 1U), 0x187U);
    /* the NMT of the old ID no longer reaches it, the new one does */
    tb_send(&fx.bus, "000 01 05");
    assert_int_equal(co_node_nmt_state(&fx.n[0].node), CO_NMT_PRE_OPERATIONAL);
    tb_send(&fx.bus, "000 01 07");
    assert_int_equal(co_node_nmt_state(&fx.n[0].node), CO_NMT_OPERATIONAL);
    tb_send(&fx.bus, "080");
    tb_expect(&fx.bus, "187 00 00");
    tb_expect_none(&fx.bus);
}

/* FAULHABER: valid -> valid keeps the PDO and EMCY COB-IDs (SDO, NMT and
 * heartbeat follow the new ID); 0xFF first, then valid: the pre-defined
 * connection set of the new ID, and the stored communication settings are
 * gone. */
static void test_change_keep_cobs(void **state)
{
    (void)state;
    setup_bus(&(co_settings_t){.lss.cob_ids = CO_LSS_COBS_KEEP});
    start(0, 5U, 1U);
    tb_flush(&fx.bus);
    /* a stored communication setting: heartbeat 1000 ms */
    tb_xfer(&fx.bus, "605 2B 17 10 00 E8 03 00 00", "585 60 17 10 00 00 00 00 00");
    tb_xfer(&fx.bus, "605 23 10 10 02 73 61 76 65", "585 60 10 10 02 00 00 00 00");
    silent("04 01");
    xfer("11 07", "11 00");
    silent("04 00");
    tb_send(&fx.bus, "000 82 00");
    tb_expect(&fx.bus, "707 00");
    tb_expect_none(&fx.bus);
    assert_int_equal(u32_of(0, 0x1014U, 0U), 0x85U);
    assert_int_equal(u32_of(0, 0x1400U, 1U), 0x205U);
    assert_int_equal(u32_of(0, 0x1800U, 1U), 0x185U);
    assert_int_equal(fx.n[0].ram.x1017_producer_heartbeat_time, 1000U);
    tb_xfer(&fx.bus, "607 40 14 10 00 00 00 00 00", "587 43 14 10 00 85 00 00 00");
    tb_send(&fx.bus, "000 01 07");
    tb_send(&fx.bus, "080");
    tb_expect(&fx.bus, "185 00 00");
    tb_expect_none(&fx.bus);
    /* stored and restarted: the same rule after power-on */
    silent("04 01");
    xfer("17", "17 00");
    silent("04 00");
    start(0, UNCONF, 1U);
    tb_expect(&fx.bus, "707 00");
    tb_expect_none(&fx.bus);
    assert_int_equal(u32_of(0, 0x1800U, 1U), 0x185U);
    assert_int_equal(u32_of(0, 0x1014U, 0U), 0x85U);
    /* to 0xFF: at the reset the node goes silent (LSS only) */
    silent("04 01");
    xfer("11 FF", "11 00");
    silent("04 00");
    tb_send(&fx.bus, "000 82 07");
    tb_expect_none(&fx.bus);
    assert_int_equal(co_node_id(&fx.n[0].node), UNCONF);
    xfer("4C", "50");
    tb_advance(&fx.bus, 2000000U);
    tb_expect_none(&fx.bus); /* not even the heartbeat */
    /* and to 9: the defaults of node 9, the stored communication set dropped */
    silent("04 01");
    xfer("11 09", "11 00");
    req("04 00");
    tb_expect(&fx.bus, "709 00");
    tb_expect_none(&fx.bus);
    assert_int_equal(u32_of(0, 0x1014U, 0U), 0x89U);
    assert_int_equal(u32_of(0, 0x1400U, 1U), 0x209U);
    assert_int_equal(u32_of(0, 0x1800U, 1U), 0x189U);
    assert_int_equal(fx.n[0].ram.x1017_producer_heartbeat_time, 0U);
    tb_send(&fx.bus, "000 81 09");
    tb_expect(&fx.bus, "709 00");
    assert_int_equal(fx.n[0].ram.x1017_producer_heartbeat_time, 0U);
}

/* CiA default from 0xFF: the stored communication set loads again. */
static void test_unconfigured_cia_keeps_stored(void **state)
{
    (void)state;
    setup_bus(NULL);
    start(0, 5U, 1U);
    tb_flush(&fx.bus);
    tb_xfer(&fx.bus, "605 2B 17 10 00 E8 03 00 00", "585 60 17 10 00 00 00 00 00");
    tb_xfer(&fx.bus, "605 23 10 10 02 73 61 76 65", "585 60 10 10 02 00 00 00 00");
    assert_int_equal(co_node_set_id(&fx.n[0].node, UNCONF, fx.bus.now), CO_OK);
    tb_send(&fx.bus, "000 82 05");
    tb_expect_none(&fx.bus);
    assert_int_equal(co_node_set_id(&fx.n[0].node, 9U, fx.bus.now), CO_OK);
    tb_expect(&fx.bus, "709 00");
    assert_int_equal(fx.n[0].ram.x1017_producer_heartbeat_time, 1000U);
    /* stored values load as stored (CiA 301), the PDO's COB-ID too */
    assert_int_equal(u32_of(0, 0x1800U, 1U), 0x185U);
    /* without a stored set the $NODEID defaults follow */
    tb_xfer(&fx.bus, "609 23 11 10 02 6C 6F 61 64", "589 60 11 10 02 00 00 00 00");
    tb_send(&fx.bus, "000 82 09");
    tb_expect(&fx.bus, "709 00");
    assert_int_equal(u32_of(0, 0x1800U, 1U), 0x189U);
    assert_int_equal(u32_of(0, 0x1014U, 0U), 0x89U);
}

/* co_node_set_id: the run-time node-ID change without LSS. */
static void test_set_id_api(void **state)
{
    (void)state;
    setup_bus(NULL);
    fx.dev.set.lss.slave = 0U;
    start(0, 5U, 1U);
    tb_flush(&fx.bus);
    assert_int_equal(co_node_set_id(&fx.n[0].node, 0U, fx.bus.now), CO_ERR_VALUE);
    assert_int_equal(co_node_set_id(&fx.n[0].node, 128U, fx.bus.now), CO_ERR_VALUE);
    assert_int_equal(co_node_set_id(&fx.n[0].node, UNCONF, fx.bus.now), CO_ERR_VALUE);
    assert_int_equal(co_node_set_id(&fx.n[0].node, 100U, fx.bus.now), CO_OK);
    tb_expect_none(&fx.bus);
    assert_int_equal(co_node_id(&fx.n[0].node), 5U);
    co_node_nmt_command(&fx.n[0].node, 0x81U, fx.bus.now);
    tb_expect(&fx.bus, "764 00");
    assert_int_equal(co_node_id(&fx.n[0].node), 100U);
    assert_int_equal(u32_of(0, 0x1800U, 1U), 0x1E4U);
}

/* ---------------------------------------------------------------- fastscan */

/* One fastscan request; true when any node answered 0x4F. */
static bool fs(uint32_t id, uint8_t bit, uint8_t sub, uint8_t next)
{
    char f[64];
    const co_frame_t *a;
    bool any = false;

    snprintf(f, sizeof f, "7E5 51 %02X %02X %02X %02X %02X %02X %02X", (unsigned)(id & 0xFFU),
             (unsigned)((id >> 8) & 0xFFU), (unsigned)((id >> 16) & 0xFFU),
             (unsigned)(id >> 24), bit, sub, next);
    tb_send(&fx.bus, f);
    while ((a = tb_next(&fx.bus)) != NULL) {
        TF_ASSERT_FRAME(a, "7E4 4F 00 00 00 00 00 00 00");
        any = true;
    }
    return any;
}

/* The master's side of CiA 305 fastscan (as python-canopen does it): the
 * smallest LSS address of the unconfigured nodes, which then is in
 * configuration. False when no node takes part. */
static bool fastscan(uint32_t out[4])
{
    if (!fs(0U, 0x80U, 0U, 0U)) {
        return false;
    }
    for (uint8_t sub = 0U; sub < 4U; sub++) {
        uint32_t v = 0U;
        for (int bit = 31; bit >= 0; bit--) {
            if (!fs(v, (uint8_t)bit, sub, sub)) {
                v |= (uint32_t)1U << (uint32_t)bit;
            }
        }
        if (!fs(v, 0U, sub, (uint8_t)((sub + 1U) & 3U))) {
            return false;
        }
        out[sub] = v;
    }
    return true;
}

/* Three unconfigured nodes and a configured one: fastscan finds the
 * unconfigured ones by serial number, each gets a node-ID and boots; the
 * configured one never answers. */
static void test_fastscan_several(void **state)
{
    static const uint32_t serials[3] = {0x00C0FFEEU, 0x00000042U, 0x00C0FFEFU};
    static const uint8_t order[3] = {1U, 0U, 2U}; /* ascending serial */
    uint32_t addr[4];
    char boot[16];

    (void)state;
    setup_bus(NULL);
    for (uint8_t i = 0U; i < 3U; i++) {
        start(i, UNCONF, serials[i]);
    }
    start(3, 0x40U, 0x00000001U);
    tb_flush(&fx.bus);
    for (uint8_t k = 0U; k < 3U; k++) {
        uint8_t idx = order[k];
        assert_true(fastscan(addr));
        assert_int_equal(addr[0], 0xA5U);
        assert_int_equal(addr[1], 0x305U);
        assert_int_equal(addr[2], 0x00020001U);
        assert_int_equal(addr[3], serials[idx]);
        /* exactly that node is in configuration */
        req("5D");
        {
            const co_frame_t *a = tb_next(&fx.bus);
            assert_non_null(a);
            assert_int_equal(fx.bus.from[fx.bus.read_pos - 1U], idx);
            assert_int_equal(co_get_u32(&a->data[1]), serials[idx]);
        }
        tb_expect_none(&fx.bus);
        snprintf(boot, sizeof boot, "11 %02X", 0x10U + k);
        xfer(boot, "11 00");
        xfer("17", "17 00");
        req("04 00");
        snprintf(boot, sizeof boot, "%03X 00", 0x710U + k);
        tb_expect(&fx.bus, boot);
        tb_expect_none(&fx.bus);
        assert_int_equal(co_node_id(&fx.n[idx].node), 0x10U + k);
    }
    assert_false(fastscan(addr));
    /* after a restart they come up configured */
    for (uint8_t i = 0U; i < 3U; i++) {
        start(i, UNCONF, serials[i]);
    }
    tb_expect(&fx.bus, "711 00");
    tb_expect(&fx.bus, "710 00");
    tb_expect(&fx.bus, "712 00");
    tb_expect_none(&fx.bus);
}

/* The LSS-number steps: a master that knows vendor and product confirms
 * them whole (bit 0) and goes on with the next part; a request for another
 * part than the slave's position, or a number that differs in a checked
 * bit, gets no answer; the last part (next < sub) completes the scan. */
static void test_fastscan_steps(void **state)
{
    (void)state;
    setup_bus(NULL);
    start(0, UNCONF, 0x00000100U);
    start(1, UNCONF, 0x00000200U);
    tb_flush(&fx.bus);
    req("51 00 00 00 00 80 00 00"); /* both answer */
    ans("4F");
    ans("4F");
    silent("51 05 03 00 00 00 01 02");        /* product, but the slaves are at vendor */
    silent("51 A4 00 00 00 00 00 01");        /* vendor with bit 0 wrong */
    silent("51 A5 00 00 00 21 00 01");        /* bit 33: not a bit */
    req("51 A5 00 00 00 00 00 01");           /* vendor confirmed, next: product */
    ans("4F");
    ans("4F");
    req("51 05 03 00 00 00 01 03");           /* product confirmed, next: serial */
    ans("4F");
    ans("4F");
    silent("51 01 00 02 00 00 02 03");        /* revision: not where they are */
    silent("51 00 03 00 00 00 03 00");        /* serial 0x300: neither */
    xfer("51 00 01 00 00 00 03 00", "4F");    /* serial 0x100 whole, next 0 < 3: done */
    assert_int_equal(fx.bus.from[fx.bus.n_log - 1U], 0U);
    xfer("5D", "5D 00 01 00 00");
    silent("04 00");
    silent("5E"); /* back in waiting (still without an ID): no inquiry */
}

/* Revision after serial (next < sub ends the scan): node 0 is configured,
 * node 1 waits at serial, node 0's scan position after completion is 2. */
static void test_fastscan_complete(void **state)
{
    (void)state;
    setup_bus(NULL);
    start(0, UNCONF, 0x00000100U);
    start(1, UNCONF, 0x00000200U);
    tb_flush(&fx.bus);
    req("51 00 00 00 00 80 00 00");
    ans("4F");
    ans("4F");
    req("51 A5 00 00 00 00 00 03"); /* vendor, then serial */
    ans("4F");
    ans("4F");
    req("51 00 00 00 00 0A 03 03"); /* serial bits 10..31 zero: both */
    ans("4F");
    ans("4F");
    tb_expect_none(&fx.bus);
    xfer("51 00 00 00 00 09 03 03", "4F"); /* bits 9..31 zero: not 0x200 */
    assert_int_equal(fx.bus.from[fx.bus.n_log - 1U], 0U);
    xfer("51 00 01 00 00 00 03 02", "4F"); /* serial 0x100 whole, next 2 < 3: done */
    xfer("5D", "5D 00 01 00 00");
    silent("51 01 00 02 00 00 02 00");     /* node 0 in configuration, node 1 at serial */
    silent("04 00");
    /* node 0 back in waiting without an ID, at revision (2) */
    xfer("51 01 00 02 00 00 02 00", "4F");
    assert_int_equal(fx.bus.from[fx.bus.n_log - 1U], 0U);
    xfer("51 00 02 00 00 00 03 00", "4F");
    assert_int_equal(fx.bus.from[fx.bus.n_log - 1U], 1U);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_unconfigured_silent),
        cmocka_unit_test(test_unconfigured_needs_lss),
        cmocka_unit_test(test_global_configure_store),
        cmocka_unit_test(test_lss_only),
        cmocka_unit_test(test_configure_node_id_range),
        cmocka_unit_test(test_state_rules),
        cmocka_unit_test(test_inquire),
        cmocka_unit_test(test_switch_selective),
        cmocka_unit_test(test_switch_selective_no_revision),
        cmocka_unit_test(test_identify_remote),
        cmocka_unit_test(test_identify_non_configured),
        cmocka_unit_test(test_bit_timing),
        cmocka_unit_test(test_store_errors),
        cmocka_unit_test(test_store_async_flash),
        cmocka_unit_test(test_change_cia_cobs_follow),
        cmocka_unit_test(test_change_keep_cobs),
        cmocka_unit_test(test_unconfigured_cia_keeps_stored),
        cmocka_unit_test(test_set_id_api),
        cmocka_unit_test(test_fastscan_several),
        cmocka_unit_test(test_fastscan_steps),
        cmocka_unit_test(test_fastscan_complete),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
