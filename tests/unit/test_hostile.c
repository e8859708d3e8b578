/*
 * A hostile bus and a careless configuration (issue 19), frame-exact:
 * time values beyond the 2^31 us timer horizon, a deadline never in the past,
 * restricted CAN-IDs, unconfirmed client aborts, and a stall of the caller's
 * clock longer than 2^31 us.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "co_priv.h"
#include "pdo_fx.h"
#include "test_bus.h"
#include "test_dev.h"

static tb_bus_t bus;
static td_node_t tn;
static pfx_t pfx;
#define BUS (&bus)
#define NODE (&tn.node)

static int setup(void **state)
{
    (void)state;
    memset(&tn, 0, sizeof tn);
    tb_init(&bus);
    td_start(&tn, &bus, 0, 5, NULL);
    tb_expect(BUS, "705 00");
    tb_expect_none(BUS);
    return 0;
}

/* Frames of one co_node_process call at @p now; the returned deadline. */
static uint32_t process_at(co_node_t *node, uint32_t now)
{
    uint32_t d = co_node_process(node, now);

    if (d != CO_NO_DEADLINE) {
        /* the rule: never a deadline before the time given */
        assert_true((int32_t)(d - now) >= 0);
    }
    return d;
}

/* Item 1: 0x1006 >= 2^31 us is refused over SDO, and a value that reaches
 * the RAM image anyway (a stored set, the application's pointer) is clamped
 * to the horizon: no SYNC at every co_node_process. */
static void sync_period_beyond_horizon(void **state)
{
    uint32_t *period = (uint32_t *)co_od_value_ptr(NODE, 0x1006, 0);
    uint32_t t0;

    (void)state;
    tb_xfer(BUS, "605 23 06 10 00 00 00 00 F0", "585 80 06 10 00 31 00 09 06");
    tb_xfer(BUS, "605 23 06 10 00 FF FF FF 7F", "585 60 06 10 00 00 00 00 00");
    tb_xfer(BUS, "605 23 06 10 00 00 00 00 80", "585 80 06 10 00 31 00 09 06");
    assert_int_equal(*period, 0x7FFFFFFFU);
    *period = 0xF0000000U; /* as a stored set or the application may leave it */
    tb_xfer(BUS, "605 23 05 10 00 80 00 00 40", "585 60 05 10 00 00 00 00 00");
    t0 = BUS->now;
    for (uint32_t k = 0; k < 1000U; k++) {
        uint32_t d = process_at(NODE, t0 + (k * 10U));
        assert_int_equal(d, t0 + 0x7FFFFFFFU);
    }
    tb_expect_none(BUS); /* not one SYNC in 10 ms */
    assert_int_equal(process_at(NODE, t0 + 0x7FFFFFFFU), t0 + 0x7FFFFFFFU + 0x7FFFFFFFU);
    tb_expect(BUS, "080");
    tb_expect_none(BUS);
}

/* Item 2: an event timer that expires while the inhibit time holds the
 * TPDO back is no deadline: co_node_process returns the inhibit end. */
static void tpdo_event_timer_while_inhibited(void **state)
{
    co_node_t *node = &pfx.n.node;
    uint32_t t0;
    uint32_t d;

    (void)state;
    pfx_start(&pfx, 5, NULL);
    tb_xfer(&pfx.bus, "605 23 00 18 01 85 01 00 80", "585 60 00 18 01 00 00 00 00");
    tb_xfer(&pfx.bus, "605 2B 00 18 03 64 00 00 00", "585 60 00 18 03 00 00 00 00");
    tb_xfer(&pfx.bus, "605 2B 00 18 05 01 00 00 00", "585 60 00 18 05 00 00 00 00");
    tb_xfer(&pfx.bus, "605 23 00 18 01 85 01 00 00", "585 60 00 18 01 00 00 00 00");
    tb_send(&pfx.bus, "000 01 05");
    t0 = pfx.bus.now;
    d = process_at(node, t0);
    tb_expect(&pfx.bus, "185 00 00"); /* event-driven: once on start */
    tb_expect_none(&pfx.bus);
    assert_int_equal(d, t0 + 1000U); /* the event timer (1 ms) */
    /* the timer expires; the inhibit time (10 ms) holds the TPDO back */
    for (uint32_t t = 1000U; t < 10000U; t += 500U) {
        d = process_at(node, t0 + t);
        assert_int_equal(d, t0 + 10000U);
    }
    tb_expect_none(&pfx.bus);
    d = process_at(node, t0 + 10000U);
    tb_expect(&pfx.bus, "185 00 00");
    tb_expect_none(&pfx.bus);
    assert_int_equal(d, t0 + 11000U);
}

/* Item 2 with the TX path full: the retry deadline, never the expired timer. */
static void tpdo_event_timer_tx_full(void **state)
{
    co_node_t *node = &pfx.n.node;
    uint32_t t0;

    (void)state;
    pfx_start(&pfx, 5, NULL);
    tb_xfer(&pfx.bus, "605 2B 00 18 05 01 00 00 00", "585 60 00 18 05 00 00 00 00");
    tb_send(&pfx.bus, "000 01 05");
    t0 = pfx.bus.now;
    (void)process_at(node, t0);
    tb_expect(&pfx.bus, "185 00 00");
    pfx.bus.refuse = 1000U;
    for (uint32_t t = 1000U; t < 5000U; t += 100U) {
        uint32_t d = process_at(node, t0 + t);
        assert_true((int32_t)(d - (t0 + t)) > 0);
    }
    pfx.bus.refuse = 0U;
    (void)process_at(node, t0 + 5000U);
    tb_expect(&pfx.bus, "185 00 00");
    tb_expect_none(&pfx.bus);
}

/* Item 3: EMCY, SYNC and TIME refuse restricted CAN-IDs (CiA 301 7.3.5)
 * like the PDOs do; NMT commands then never count as SYNC frames. */
static void restricted_cob_ids(void **state)
{
    (void)state;
    /* EMCY on 0x000 or on the node's own error-control COB-ID */
    tb_xfer(BUS, "605 23 14 10 00 00 00 00 00", "585 80 14 10 00 30 00 09 06");
    tb_xfer(BUS, "605 23 14 10 00 05 07 00 00", "585 80 14 10 00 30 00 09 06");
    tb_xfer(BUS, "605 23 14 10 00 05 06 00 00", "585 80 14 10 00 30 00 09 06");
    /* not valid: any CAN-ID may stand there; valid again: checked */
    tb_xfer(BUS, "605 23 14 10 00 00 00 00 80", "585 60 14 10 00 00 00 00 00");
    tb_xfer(BUS, "605 23 14 10 00 00 00 00 00", "585 80 14 10 00 30 00 09 06");
    tb_xfer(BUS, "605 23 14 10 00 85 00 00 00", "585 60 14 10 00 00 00 00 00");
    /* SYNC consumer on 0x000, 0x605, 0x77F */
    tb_xfer(BUS, "605 23 05 10 00 00 00 00 00", "585 80 05 10 00 30 00 09 06");
    tb_xfer(BUS, "605 23 05 10 00 05 06 00 00", "585 80 05 10 00 30 00 09 06");
    tb_xfer(BUS, "605 23 05 10 00 7F 07 00 00", "585 80 05 10 00 30 00 09 06");
    tb_xfer(BUS, "605 23 05 10 00 81 00 00 00", "585 60 05 10 00 00 00 00 00");
    /* TIME: unused it may be anything; consumed on the node's 0x605 no */
    tb_xfer(BUS, "605 23 12 10 00 05 06 00 00", "585 60 12 10 00 00 00 00 00");
    tb_xfer(BUS, "605 23 12 10 00 05 06 00 80", "585 80 12 10 00 30 00 09 06");
    tb_xfer(BUS, "605 23 12 10 00 05 06 00 40", "585 80 12 10 00 30 00 09 06");
    tb_xfer(BUS, "605 23 12 10 00 00 01 00 80", "585 60 12 10 00 00 00 00 00");
    /* the NMT start is no SYNC of the wrong length */
    tb_send(BUS, "000 01 05");
    tb_expect_none(BUS);
    assert_int_equal(co_node_nmt_state(NODE), CO_NMT_OPERATIONAL);
}

/* The restricted CAN-IDs are exactly CiA 301 7.3.5's list: every 11-bit
 * one through co_check_cob with a rule that always checks (the SYNC
 * consumer's). */
static void restricted_cob_ids_every_one(void **state)
{
    (void)state;
    for (uint32_t id = 0U; id <= 0x7FFU; id++) {
        bool listed = (id <= 0x07FU) || ((id >= 0x101U) && (id <= 0x180U)) ||
                      ((id >= 0x581U) && (id <= 0x5FFU)) || ((id >= 0x601U) && (id <= 0x67FU)) ||
                      ((id >= 0x6E0U) && (id <= 0x6FFU)) || (id >= 0x701U);
        assert_int_equal(co_check_cob(0U, id, CO_COB_WHEN_SET | CO_COB_ALWAYS),
                         listed ? CO_ERR_VALUE : CO_OK);
    }
}

/* Item 5: a client abort is unconfirmed, whatever its length. */
static void client_abort_is_never_answered(void **state)
{
    static const char *const aborts[] = {
        "605 80",
        "605 80 00",
        "605 80 00 10",
        "605 80 00 10 00",
        "605 80 00 10 00 00",
        "605 80 00 10 00 00 00",
        "605 80 00 10 00 00 00 04",
        "605 80 00 10 00 00 00 04 05",
        "605 9F 00 10 00 00 00 04 05", /* ccs 4 with other low bits */
    };
    (void)state;
    for (size_t k = 0; k < sizeof aborts / sizeof aborts[0]; k++) {
        tb_send(BUS, aborts[k]);
        tb_expect_none(BUS);
        /* ... also in the middle of a segmented download, which it ends */
        tb_xfer(BUS, "605 21 12 20 00 0A 00 00 00", "585 60 12 20 00 00 00 00 00");
        tb_send(BUS, aborts[k]);
        tb_expect_none(BUS);
        tb_xfer(BUS, "605 00 41 42 43 44 45 46 47", "585 80 00 00 00 01 00 04 05");
    }
    /* a block download's abort as well */
    tb_xfer(BUS, "605 C6 12 20 00 03 00 00 00", "585 A4 12 20 00 7F 00 00 00");
    tb_send(BUS, "605 80 12 20");
    tb_expect_none(BUS);
    tb_xfer(BUS, "605 40 17 10 00 00 00 00 00", "585 4B 17 10 00 00 00 00 00");
    /* an empty frame still gets its answer (no command byte to read) */
    tb_xfer(BUS, "605", "585 80 00 00 00 01 00 04 05");
}

/* Item 8: a stall of 40 minutes (more than 2^31 us): every timer is due at
 * once, not 31 minutes later. */
static void stall_beyond_horizon(void **state)
{
    const uint32_t stall = 40UL * 60UL * 1000000UL;
    uint32_t t0;
    uint32_t d;

    (void)state;
    tb_xfer(BUS, "605 2B 17 10 00 E8 03 00 00", "585 60 17 10 00 00 00 00 00");
    tb_xfer(BUS, "605 23 06 10 00 40 42 0F 00", "585 60 06 10 00 00 00 00 00");
    tb_xfer(BUS, "605 23 05 10 00 80 00 00 40", "585 60 05 10 00 00 00 00 00");
    t0 = BUS->now;
    tb_advance(BUS, 1000000U);
    tb_expect(BUS, "705 7F");
    tb_expect(BUS, "080");
    tb_expect_none(BUS);
    /* the process stops for 40 minutes */
    d = process_at(NODE, t0 + 1000000U + stall);
    tb_expect(BUS, "705 7F");
    tb_expect(BUS, "080");
    tb_expect_none(BUS);
    assert_int_equal(d, t0 + 2000000U + stall);
    /* the same when a frame is the first to bring the new time */
    BUS->now = t0 + 2000000U + stall + stall;
    tb_xfer(BUS, "605 40 17 10 00 00 00 00 00", "585 4B 17 10 00 E8 03 00 00");
    d = process_at(NODE, BUS->now);
    tb_expect(BUS, "705 7F");
    tb_expect(BUS, "080");
    tb_expect_none(BUS);
    assert_int_equal(d, BUS->now + 1000000U);
    /* a small step back (a receive time stamp older than the last
     * co_node_process) is no stall */
    d = co_node_process(NODE, BUS->now - 500U);
    tb_expect_none(BUS);
    assert_int_equal(d, BUS->now + 1000000U);
}

/* Item 8: an event timer and an RPDO deadline after a stall. */
static void stall_pdo_timers(void **state)
{
    co_node_t *node = &pfx.n.node;
    const uint32_t stall = 40UL * 60UL * 1000000UL;
    uint32_t t0;

    (void)state;
    pfx_start(&pfx, 5, NULL);
    tb_xfer(&pfx.bus, "605 2B 00 18 05 E8 03 00 00", "585 60 00 18 05 00 00 00 00");
    tb_send(&pfx.bus, "000 01 05");
    t0 = pfx.bus.now;
    assert_int_equal(process_at(node, t0), t0 + 1000000U);
    tb_expect(&pfx.bus, "185 00 00");
    tb_expect_none(&pfx.bus);
    assert_int_equal(process_at(node, t0 + 500000U + stall), t0 + 1500000U + stall);
    tb_expect(&pfx.bus, "185 00 00");
    tb_expect_none(&pfx.bus);
}

/* The value of 0x2012 (VISIBLE_STRING[32], "hello") as the dictionary holds it. */
static void expect_vstr(const char *text)
{
    char v[40] = {0};
    uint32_t len = 0;

    assert_int_equal(co_od_read(NODE, 0x2012, 0, v, sizeof v, &len), CO_OK);
    assert_int_equal(len, strlen(text));
    assert_memory_equal(v, text, len);
}

/* Item 4: a string download that is rejected, aborted or times out leaves
 * the old value; the new one appears only when the transfer is complete. */
static void rejected_download_leaves_old_value(void **state)
{
    (void)state;
    expect_vstr("hello");
    /* segmented, 14 bytes announced; the client aborts after 7 */
    tb_xfer(BUS, "605 21 12 20 00 0E 00 00 00", "585 60 12 20 00 00 00 00 00");
    tb_xfer(BUS, "605 00 59 59 59 59 59 59 59", "585 20 00 00 00 00 00 00 00");
    expect_vstr("hello"); /* the application never sees a half value */
    tb_send(BUS, "605 80 12 20 00 00 00 04 05");
    tb_expect_none(BUS);
    expect_vstr("hello");
    /* the same, ended by a length error (more than announced) */
    tb_xfer(BUS, "605 21 12 20 00 0A 00 00 00", "585 60 12 20 00 00 00 00 00");
    tb_xfer(BUS, "605 00 59 59 59 59 59 59 59", "585 20 00 00 00 00 00 00 00");
    tb_xfer(BUS, "605 11 59 59 59 59 59 59 59", "585 80 12 20 00 12 00 07 06");
    expect_vstr("hello");
    /* ... by a timeout */
    tb_xfer(BUS, "605 21 12 20 00 0E 00 00 00", "585 60 12 20 00 00 00 00 00");
    tb_xfer(BUS, "605 00 59 59 59 59 59 59 59", "585 20 00 00 00 00 00 00 00");
    tb_advance(BUS, 1000000U);
    tb_expect(BUS, "585 80 12 20 00 00 00 04 05");
    tb_expect_none(BUS);
    expect_vstr("hello");
    /* ... by a block download whose CRC is wrong */
    tb_xfer(BUS, "605 C6 12 20 00 0E 00 00 00", "585 A4 12 20 00 7F 00 00 00");
    tb_send(BUS, "605 01 59 59 59 59 59 59 59");
    tb_expect_none(BUS);
    tb_xfer(BUS, "605 82 20 43 69 41 20 33 30", "585 A2 02 7F 00 00 00 00 00");
    expect_vstr("hello");
    tb_xfer(BUS, "605 C1 00 00 00 00 00 00 00", "585 80 12 20 00 04 00 04 05");
    expect_vstr("hello");
    /* a complete transfer replaces it */
    tb_xfer(BUS, "605 21 12 20 00 0E 00 00 00", "585 60 12 20 00 00 00 00 00");
    tb_xfer(BUS, "605 00 59 59 59 59 59 59 59", "585 20 00 00 00 00 00 00 00");
    tb_xfer(BUS, "605 11 20 43 69 41 20 33 30", "585 30 00 00 00 00 00 00 00");
    expect_vstr("YYYYYYY CiA 30");
    /* the next one shorter: the rest is cleared, no old bytes show */
    tb_xfer(BUS, "605 21 12 20 00 08 00 00 00", "585 60 12 20 00 00 00 00 00");
    tb_xfer(BUS, "605 00 61 62 63 64 65 66 67", "585 20 00 00 00 00 00 00 00");
    tb_xfer(BUS, "605 1D 68 00 00 00 00 00 00", "585 30 00 00 00 00 00 00 00");
    expect_vstr("abcdefgh");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(sync_period_beyond_horizon, setup),
        cmocka_unit_test(tpdo_event_timer_while_inhibited),
        cmocka_unit_test(tpdo_event_timer_tx_full),
        cmocka_unit_test_setup(restricted_cob_ids, setup),
        cmocka_unit_test(restricted_cob_ids_every_one),
        cmocka_unit_test_setup(client_abort_is_never_answered, setup),
        cmocka_unit_test_setup(stall_beyond_horizon, setup),
        cmocka_unit_test(stall_pdo_timers),
        cmocka_unit_test_setup(rejected_download_leaves_old_value, setup),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
