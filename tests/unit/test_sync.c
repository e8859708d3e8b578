/*
 * SYNC consumer/producer (0x1005, 0x1006, 0x1007, 0x1019) and TIME (0x1012),
 * with exact frames and pushed time.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "test_bus.h"
#include "test_dev.h"

typedef struct fx {
    tb_bus_t bus;
    td_node_t n;
    unsigned syncs;
    uint8_t last_counter;
    unsigned times;
    uint32_t ms;
    uint16_t days;
} fx_t;

static fx_t fx;

static void on_sync(void *ctx, co_node_t *node, uint8_t counter)
{
    fx_t *f = (fx_t *)ctx;
    (void)node;
    f->syncs++;
    f->last_counter = counter;
}

static void on_time(void *ctx, co_node_t *node, uint32_t ms, uint16_t days)
{
    fx_t *f = (fx_t *)ctx;
    (void)node;
    f->times++;
    f->ms = ms;
    f->days = days;
}

static int setup(void **state)
{
    co_node_callbacks_t cb;
    memset(&fx, 0, sizeof fx);
    tb_init(&fx.bus);
    memset(&cb, 0, sizeof cb);
    cb.ctx = &fx;
    cb.sync = on_sync;
    cb.time = on_time;
    td_start_cb(&fx.n, &fx.bus, 0, 1, NULL, &cb);
    tb_expect(&fx.bus, "701 00");
    *state = &fx;
    return 0;
}

#define BUS (&fx.bus)

static void consumer_without_counter(void **state)
{
    (void)state;
    tb_send(BUS, "080");
    assert_int_equal(fx.syncs, 1);
    assert_int_equal(fx.last_counter, 0);
    /* a SYNC with a counter byte while 0x1019 is 0: EMCY 0x8240, not used */
    tb_send(BUS, "080 05");
    tb_expect(BUS, "081 40 82 11 00 00 00 00 00");
    assert_int_equal(fx.syncs, 1);
    /* the right length again clears it */
    tb_send(BUS, "080");
    tb_expect(BUS, "081 00 00 00 00 00 00 00 00");
    assert_int_equal(fx.syncs, 2);
    tb_send(BUS, "080 R");
    assert_int_equal(fx.syncs, 2);
    tb_expect_none(BUS);
}

static void consumer_only_in_pre_operational_and_operational(void **state)
{
    (void)state;
    tb_send(BUS, "000 02 01");
    tb_send(BUS, "080");
    assert_int_equal(fx.syncs, 0);
    tb_send(BUS, "000 01 01");
    tb_send(BUS, "080");
    assert_int_equal(fx.syncs, 1);
}

static void consumer_with_counter(void **state)
{
    (void)state;
    tb_xfer(BUS, "601 2F 19 10 00 05 00 00 00", "581 60 19 10 00 00 00 00 00");
    tb_send(BUS, "080 03");
    assert_int_equal(fx.syncs, 1);
    assert_int_equal(fx.last_counter, 3);
    tb_send(BUS, "080");
    tb_expect(BUS, "081 40 82 11 00 00 00 00 00");
    assert_int_equal(fx.syncs, 1);
}

static void counter_overflow_value_rules(void **state)
{
    (void)state;
    tb_xfer(BUS, "601 2F 19 10 00 01 00 00 00", "581 80 19 10 00 30 00 09 06");
    tb_xfer(BUS, "601 2F 19 10 00 F1 00 00 00", "581 80 19 10 00 30 00 09 06");
    tb_xfer(BUS, "601 2F 19 10 00 F0 00 00 00", "581 60 19 10 00 00 00 00 00");
    /* not while a communication cycle period is set */
    tb_xfer(BUS, "601 23 06 10 00 10 27 00 00", "581 60 06 10 00 00 00 00 00");
    tb_xfer(BUS, "601 2F 19 10 00 02 00 00 00", "581 80 19 10 00 22 00 00 08");
}

static void producer_period_and_counter(void **state)
{
    (void)state;
    /* counter 1..3, period 10 ms, then become producer */
    tb_xfer(BUS, "601 2F 19 10 00 03 00 00 00", "581 60 19 10 00 00 00 00 00");
    tb_xfer(BUS, "601 23 06 10 00 10 27 00 00", "581 60 06 10 00 00 00 00 00");
    tb_xfer(BUS, "601 23 05 10 00 80 00 00 40", "581 60 05 10 00 00 00 00 00");
    tb_advance(BUS, 9999);
    tb_expect_none(BUS);
    tb_advance(BUS, 1);
    tb_expect(BUS, "080 01");
    tb_advance(BUS, 10000);
    tb_expect(BUS, "080 02");
    tb_advance(BUS, 10000);
    tb_expect(BUS, "080 03");
    tb_advance(BUS, 10000);
    tb_expect(BUS, "080 01");
    tb_expect_none(BUS);
    assert_int_equal(fx.syncs, 4); /* the producer uses its own SYNC too */
    /* no SYNC in Stopped */
    tb_send(BUS, "000 02 01");
    tb_advance(BUS, 30000);
    tb_expect_none(BUS);
    /* the CAN-ID may not change while producing */
    tb_send(BUS, "000 80 01");
    tb_flush(BUS);
    tb_xfer(BUS, "601 23 05 10 00 81 00 00 40", "581 80 05 10 00 30 00 09 06");
    /* stop producing, then change it */
    tb_xfer(BUS, "601 23 05 10 00 80 00 00 00", "581 60 05 10 00 00 00 00 00");
    tb_xfer(BUS, "601 23 05 10 00 81 00 00 00", "581 60 05 10 00 00 00 00 00");
    tb_advance(BUS, 30000);
    tb_expect_none(BUS);
    tb_send(BUS, "080 01"); /* no longer the SYNC COB-ID */
    tb_send(BUS, "081 02");
    assert_int_equal(fx.syncs, 5);
    assert_int_equal(fx.last_counter, 2);
    tb_expect_none(BUS);
}

static void bad_sync_cob_ids(void **state)
{
    (void)state;
    tb_xfer(BUS, "601 23 05 10 00 80 00 00 20", "581 80 05 10 00 30 00 09 06"); /* 29-bit */
    tb_xfer(BUS, "601 23 05 10 00 80 08 00 00", "581 80 05 10 00 30 00 09 06"); /* bit 11 */
}

/* 0x1005 in its 16-bit form (co_od.h, CO_SUB_COB16): bits 31 and 30 and the
 * CAN-ID read back as written; a value with any of bits 29..11 is refused
 * and leaves the old one. */
static void sync_cob_id_in_16_bits(void **state)
{
    (void)state;
    tb_xfer(BUS, "601 40 05 10 00 00 00 00 00", "581 43 05 10 00 80 00 00 00");
    assert_int_equal(fx.n.ram.sync_cob, 0x0080U);
    tb_xfer(BUS, "601 23 05 10 00 81 00 00 C0", "581 60 05 10 00 00 00 00 00");
    assert_int_equal(fx.n.ram.sync_cob, 0xC081U);
    tb_xfer(BUS, "601 40 05 10 00 00 00 00 00", "581 43 05 10 00 81 00 00 C0");
    static const char *const bad[] = {"601 23 05 10 00 81 08 00 C0",  /* bit 11 */
                                      "601 23 05 10 00 81 00 01 C0",  /* bit 16 */
                                      "601 23 05 10 00 81 00 00 E0"}; /* bit 29 */
    for (size_t k = 0U; k < sizeof bad / sizeof bad[0]; k++) {
        tb_xfer(BUS, bad[k], "581 80 05 10 00 30 00 09 06");
        assert_int_equal(fx.n.ram.sync_cob, 0xC081U);
    }
    tb_xfer(BUS, "601 40 05 10 00 00 00 00 00", "581 43 05 10 00 81 00 00 C0");
    /* a segmented download of the UNSIGNED32, one segment (the CAN-ID in
     * use stays) */
    tb_xfer(BUS, "601 21 05 10 00 04 00 00 00", "581 60 05 10 00 00 00 00 00");
    tb_xfer(BUS, "601 07 81 00 00 40 00 00 00", "581 20 00 00 00 00 00 00 00");
    assert_int_equal(fx.n.ram.sync_cob, 0x4081U);
    tb_xfer(BUS, "601 40 05 10 00 00 00 00 00", "581 43 05 10 00 81 00 00 40");
    tb_xfer(BUS, "601 23 05 10 00 80 00 00 00", "581 60 05 10 00 00 00 00 00");
    assert_int_equal(fx.n.ram.sync_cob, 0x0080U);
}

static void window(void **state)
{
    (void)state;
    assert_true(co_sync_window_open(&fx.n.node)); /* 0x1007 = 0: always */
    tb_xfer(BUS, "601 23 07 10 00 E8 03 00 00", "581 60 07 10 00 00 00 00 00"); /* 1 ms */
    tb_send(BUS, "080");
    tb_advance(BUS, 1000);
    assert_true(co_sync_window_open(&fx.n.node));
    tb_advance(BUS, 1);
    assert_false(co_sync_window_open(&fx.n.node));
    tb_send(BUS, "080");
    assert_true(co_sync_window_open(&fx.n.node));
}

static void time_consumer_and_producer(void **state)
{
    (void)state;
    /* 12:00:00.000 = 43200000 ms, day 15000 */
    tb_send(BUS, "100 00 2E 93 02 98 3A");
    assert_int_equal(fx.times, 1);
    assert_int_equal(fx.ms, 43200000UL);
    assert_int_equal(fx.days, 15000);
    tb_send(BUS, "100 00 2E 93 02 98"); /* too short */
    assert_int_equal(fx.times, 1);
    assert_int_equal(co_time_send(&fx.n.node, 1, 2), CO_ERR_NO_ACCESS);
    /* consumer off: not received; producer on */
    tb_xfer(BUS, "601 23 12 10 00 00 01 00 40", "581 60 12 10 00 00 00 00 00");
    /* (in its 16-bit form, co_od.h CO_SUB_COB16) */
    assert_int_equal(fx.n.ram.time_cob, 0x4100U);
    tb_xfer(BUS, "601 40 12 10 00 00 00 00 00", "581 43 12 10 00 00 01 00 40");
    tb_send(BUS, "100 00 2E 93 02 98 3A");
    assert_int_equal(fx.times, 1);
    assert_int_equal(co_time_send(&fx.n.node, 43200000UL, 15000), CO_OK);
    tb_expect(BUS, "100 00 2E 93 02 98 3A");
    /* CAN-ID fixed while in use */
    tb_xfer(BUS, "601 23 12 10 00 01 01 00 40", "581 80 12 10 00 30 00 09 06");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(consumer_without_counter, setup),
        cmocka_unit_test_setup(sync_cob_id_in_16_bits, setup),
        cmocka_unit_test_setup(consumer_only_in_pre_operational_and_operational, setup),
        cmocka_unit_test_setup(consumer_with_counter, setup),
        cmocka_unit_test_setup(counter_overflow_value_rules, setup),
        cmocka_unit_test_setup(producer_period_and_counter, setup),
        cmocka_unit_test_setup(bad_sync_cob_ids, setup),
        cmocka_unit_test_setup(window, setup),
        cmocka_unit_test_setup(time_consumer_and_producer, setup),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
