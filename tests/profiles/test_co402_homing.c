/*
 * CiA 402 homing mode on the simulated axis: every supported method from
 * several start positions really moves to its switch edge / index pulse,
 * sets homing attained (bit 12) with target reached (bit 10), and makes the
 * home position the home offset 0x607C. Errors, interruption and halt.
 *
 * The plant: index pulses at 100 + 4096 k, limit switches at -50000 and
 * +50000, and a home switch that is either part of the travel
 * [10000, 20000], open to the positive side [10000, ...) or open to the
 * negative side (..., -10000].
 */
#include <inttypes.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "t402.h"

static t402_t fx;
#define BUS (&fx.bus)
#define AX (&fx.ax)

enum { SW_PART, SW_POSITIVE, SW_NEGATIVE, SW_NO_HOME, SW_NONE };

static void plant(co402_sim_config_t *c, int kind, int32_t start)
{
    t402_sim_defaults(c);
    c->index_offset = 100;
    c->start_pos = start;
    c->switches = CO402_IN_NEG_LIMIT | CO402_IN_POS_LIMIT | CO402_IN_HOME;
    c->neg_limit = -50000;
    c->pos_limit = 50000;
    switch (kind) {
    case SW_PART:
        c->home_lo = 10000;
        c->home_hi = 20000;
        break;
    case SW_POSITIVE:
        c->home_lo = 10000;
        c->home_hi = INT32_MAX;
        break;
    case SW_NEGATIVE:
        c->home_lo = INT32_MIN;
        c->home_hi = -10000;
        break;
    case SW_NO_HOME:
        c->switches = CO402_IN_NEG_LIMIT | CO402_IN_POS_LIMIT;
        break;
    default:
        c->switches = 0U;
        break;
    }
}

/* Home with @p method from @p start; returns the statusword at the end. */
static uint16_t home(int8_t method, int kind, int32_t start, int32_t offset)
{
    co402_sim_config_t c;

    plant(&c, kind, start);
    t402_start(&fx, 1, 0, &c);
    t402_set(&fx, 0x6060, 0, 6, 1);
    t402_set(&fx, 0x6098, 0, method, 1);
    t402_set(&fx, 0x607C, 0, offset, 4);
    t402_enable(&fx);
    assert_int_equal(t402_sw(&fx), 0x0637); /* not started */
    t402_cw(&fx, 0x001F);
    if ((method != 35) && (method != 37)) {
        assert_int_equal(t402_sw(&fx), 0x0237); /* in progress */
    } else {
        assert_int_equal(t402_sw(&fx), 0x1237); /* found, done at the next tick */
    }
    t402_run_until(&fx, 0x0400, 0x0400, 30000000);
    return t402_sw(&fx);
}

/* The home position (raw plant coordinates) is the home offset now. */
static void expect_home(int8_t method, int kind, int32_t start, int32_t where)
{
    uint16_t sw = home(method, kind, start, 1000);

    if (sw != 0x1637) {
        print_error("method %d from %" PRId32 ": statusword 0x%04X\n", method, start, sw);
        fail();
    }
    if ((co402_position(AX) - co402_sim_position(&fx.sim)) != (1000 - where)) {
        print_error("method %d from %" PRId32 ": home at %" PRId32 ", expected %" PRId32 "\n",
                    method, start, co402_sim_position(&fx.sim) - (co402_position(AX) - 1000), where);
        fail();
    }
    assert_int_equal(t402_get(&fx, 0x6064, 0), co402_position(AX));
}

/* ---------------------------------------------------------------- SDO */

static void homing_by_sdo(void **state)
{
    co402_sim_config_t c;
    (void)state;
    plant(&c, SW_PART, 0);
    t402_start(&fx, 1, 0, &c);
    tb_xfer(BUS, "601 2F 60 60 00 06 00 00 00", "581 60 60 60 00 00 00 00 00");
    tb_xfer(BUS, "601 40 61 60 00 00 00 00 00", "581 4F 61 60 00 06 00 00 00");
    tb_xfer(BUS, "601 23 99 60 01 20 4E 00 00", "581 60 99 60 01 00 00 00 00"); /* 20000 */
    tb_xfer(BUS, "601 23 99 60 02 D0 07 00 00", "581 60 99 60 02 00 00 00 00"); /* 2000 */
    tb_xfer(BUS, "601 23 9A 60 00 40 0D 03 00", "581 60 9A 60 00 00 00 00 00"); /* 200000 */
    tb_xfer(BUS, "601 23 7C 60 00 A8 61 00 00", "581 60 7C 60 00 00 00 00 00"); /* 25000 */
    tb_xfer(BUS, "601 2F 98 60 00 18 00 00 00", "581 60 98 60 00 00 00 00 00"); /* 24 */
    t402_enable(&fx);
    tb_xfer(BUS, "601 2B 40 60 00 1F 00 00 00", "581 60 40 60 00 00 00 00 00");
    tb_xfer(BUS, "601 40 41 60 00 00 00 00 00", "581 4B 41 60 00 37 02 00 00");
    t402_run(&fx, 100000);
    tb_xfer(BUS, "601 40 41 60 00 00 00 00 00", "581 4B 41 60 00 37 02 00 00");
    t402_run_until(&fx, 0x0400, 0x0400, 5000000);
    tb_xfer(BUS, "601 40 41 60 00 00 00 00 00", "581 4B 41 60 00 37 16 00 00");
    /* method 24: the lower edge of the home switch (10000) is 25000 now */
    assert_int_equal(co402_position(AX) - co402_sim_position(&fx.sim), 25000 - 10000);
    /* clearing bit 4 keeps the result */
    tb_xfer(BUS, "601 2B 40 60 00 0F 00 00 00", "581 60 40 60 00 00 00 00 00");
    tb_xfer(BUS, "601 40 41 60 00 00 00 00 00", "581 4B 41 60 00 37 16 00 00");
}

static void current_position(void **state)
{
    (void)state;
    expect_home(35, SW_NONE, 1234, 1234);
    expect_home(37, SW_NONE, -777, -777);
    assert_int_equal(co402_sim_velocity(&fx.sim), 0); /* no motion at all */
}

/* ------------------------------------------------------ limit switches */

static void limit_switch_methods(void **state)
{
    (void)state;
    expect_home(1, SW_PART, 0, -49052);    /* index right of the negative limit */
    expect_home(1, SW_PART, -52000, -49052); /* starting on the switch */
    expect_home(17, SW_PART, 0, -50000);
    expect_home(2, SW_PART, 0, 49252);     /* index left of the positive limit */
    expect_home(18, SW_PART, 52000, 50000);
}

/* ------------------------------------------- home switch open on one side */

static void one_sided_home_switch(void **state)
{
    static const int32_t starts[] = {0, 30000};
    (void)state;
    for (unsigned i = 0; i < 2U; i++) {
        expect_home(3, SW_POSITIVE, starts[i], 8292);
        expect_home(4, SW_POSITIVE, starts[i], 12388);
        expect_home(19, SW_POSITIVE, starts[i], 10000);
        expect_home(20, SW_POSITIVE, starts[i], 10000);
        expect_home(5, SW_NEGATIVE, -starts[i], -8092);
        expect_home(6, SW_NEGATIVE, -starts[i], -12188);
        expect_home(21, SW_NEGATIVE, -starts[i], -10000);
        expect_home(22, SW_NEGATIVE, -starts[i], -10000);
    }
}

/* ------------------------------------- home switch on part of the travel */

static void home_switch_in_part_of_travel(void **state)
{
    /* from the left, on the switch, from the right (turning at a limit) */
    static const int32_t starts[] = {0, 15000, 30000};
    static const struct {
        int8_t method;
        int32_t home;
    } cases[] = {
        {7, 8292},    {8, 12388},   {9, 16484},   {10, 20580},  {11, 20580},
        {12, 16484},  {13, 12388},  {14, 8292},   {23, 10000},  {24, 10000},
        {25, 20000},  {26, 20000},  {27, 20000},  {28, 20000},  {29, 10000},
        {30, 10000},
    };
    (void)state;
    for (unsigned i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        for (unsigned k = 0; k < 3U; k++) {
            expect_home(cases[i].method, SW_PART, starts[k], cases[i].home);
        }
    }
    /* from left of the negative limit's reach too: 13 starts negative */
    expect_home(13, SW_PART, -40000, 12388);
}

/* ------------------------------------------------------ index pulse only */

static void index_pulse_methods(void **state)
{
    (void)state;
    expect_home(33, SW_NONE, 5000, 4196);
    expect_home(34, SW_NONE, 5000, 8292);
    expect_home(34, SW_NONE, 4196, 8292); /* next one, not the one it stands on */
}

/* ------------------------------------------------------ errors, interrupt */

static void homing_error(void **state)
{
    uint16_t sw;
    (void)state;
    /* method 4 without a home switch runs into the positive limit */
    sw = home(4, SW_NO_HOME, 0, 0);
    assert_int_equal(sw, 0x2637); /* homing error, at rest */
    t402_run(&fx, 100000);
    assert_int_equal(t402_sw(&fx), 0x2637);
    assert_true(co402_sim_position(&fx.sim) >= 50000);
    /* method 7 turns once at a limit switch; twice is an error */
    sw = home(7, SW_NO_HOME, 0, 0);
    assert_int_equal(sw, 0x2637);
    assert_true(co402_sim_position(&fx.sim) <= -50000);
    /* unknown method (the hook refuses it; a value from elsewhere is an error) */
    t402_set(&fx, 0x6098, 0, 37, 1);
    t402_cw(&fx, 0x000F);
    t402_cw(&fx, 0x001F);
    t402_run(&fx, 1000);
    assert_int_equal(t402_sw(&fx), 0x1637);
}

static void interrupt_and_restart(void **state)
{
    co402_sim_config_t c;
    (void)state;
    plant(&c, SW_PART, 0);
    t402_start(&fx, 1, 0, &c);
    t402_set(&fx, 0x6060, 0, 6, 1);
    t402_set(&fx, 0x6098, 0, 8, 1);
    t402_enable(&fx);
    t402_cw(&fx, 0x001F);
    t402_run(&fx, 200000);
    assert_true(co402_sim_velocity(&fx.sim) > 10000);
    t402_cw(&fx, 0x000F); /* falling edge of bit 4: interrupted */
    assert_int_equal(t402_sw(&fx), 0x0237);
    t402_run_until(&fx, 0x0400, 0x0400, 1000000);
    assert_int_equal(t402_sw(&fx), 0x0637); /* interrupted, at rest */
    t402_cw(&fx, 0x001F); /* a new start finishes */
    t402_run_until(&fx, 0x0400, 0x0400, 10000000);
    assert_int_equal(t402_sw(&fx), 0x1637);
    assert_int_equal(co402_position(AX) - co402_sim_position(&fx.sim), -12388);
    /* halt interrupts too */
    t402_cw(&fx, 0x000F);
    t402_set(&fx, 0x6098, 0, 2, 1);
    t402_cw(&fx, 0x001F);
    t402_run(&fx, 200000);
    t402_cw(&fx, 0x011F);
    t402_run_until(&fx, 0x0400, 0x0400, 1000000);
    assert_int_equal(t402_sw(&fx), 0x0637);
}

static void attained_cleared_with_bit4_option(void **state)
{
    co402_sim_config_t c;
    (void)state;
    plant(&c, SW_NONE, 0);
    t402_start(&fx, 1, CO402_OPT_HM_BIT4_CLEARS, &c);
    t402_set(&fx, 0x6060, 0, 6, 1);
    t402_set(&fx, 0x6098, 0, 37, 1);
    t402_enable(&fx);
    t402_cw(&fx, 0x001F);
    t402_run(&fx, 1000);
    assert_int_equal(t402_sw(&fx), 0x1637);
    t402_cw(&fx, 0x000F);
    assert_int_equal(t402_sw(&fx), 0x0637);
}

static void positions_after_homing(void **state)
{
    (void)state;
    expect_home(24, SW_PART, 0, 10000);
    /* a profile position move now goes to the new coordinates */
    t402_cw(&fx, 0x000F);
    t402_set(&fx, 0x6060, 0, 1, 1);
    t402_set(&fx, 0x607A, 0, 0, 4);
    t402_cw(&fx, 0x001F);
    t402_cw(&fx, 0x000F);
    t402_run_until(&fx, 0x0400, 0x0400, 5000000);
    t402_run(&fx, 100000);
    assert_int_equal(t402_get(&fx, 0x6064, 0), 0);
    assert_int_equal(co402_sim_position(&fx.sim), 9000); /* home 10000 was 1000 */
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(homing_by_sdo),
        cmocka_unit_test(current_position),
        cmocka_unit_test(limit_switch_methods),
        cmocka_unit_test(one_sided_home_switch),
        cmocka_unit_test(home_switch_in_part_of_travel),
        cmocka_unit_test(index_pulse_methods),
        cmocka_unit_test(homing_error),
        cmocka_unit_test(interrupt_and_restart),
        cmocka_unit_test(attained_cleared_with_bit4_option),
        cmocka_unit_test(positions_after_homing),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
