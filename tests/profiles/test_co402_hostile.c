/*
 * The CiA 402 profile with extreme but legal values (issue 19, items 6 and
 * 11): every division is defined and no product overflows; values saturate.
 * Under UBSan (tools/run-tests' sanitizer build) a division by zero or a
 * signed overflow aborts the test; on the plain build the checks below see
 * the wrapped or trapped result.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "co402_priv.h"
#include "t402.h"

static t402_t fx;
#define BUS (&fx.bus)
#define AX (&fx.ax)

/* Item 6: fewer encoder increments than motor revolutions (0x608F:1 <
 * 0x608F:2, both legal) made the increments per revolution 0, and the vl
 * velocity (rpm) a division by zero (SIGFPE). */
static void encoder_fewer_increments_than_revolutions(void **state)
{
    uint32_t *inc;
    uint32_t *rev;

    (void)state;
    t402_start(&fx, 1, 0, NULL);
    /* read-only objects: set by the application (or a description that
     * makes them writable) */
    inc = (uint32_t *)co_od_value_ptr(&fx.n.node, 0x608F, 1);
    rev = (uint32_t *)co_od_value_ptr(&fx.n.node, 0x608F, 2);
    assert_non_null(inc);
    assert_non_null(rev);
    *inc = 1U;
    *rev = 4U;
    assert_int_equal(co402_counts_per_rev(AX), 1U);
    t402_enable(&fx);
    t402_run(&fx, 20000);
    assert_int_equal(t402_get(&fx, 0x6044, 0), 0); /* vl velocity actual: at rest */
    *inc = 0U;
    *rev = 0xFFFFFFFFU;
    t402_run(&fx, 20000);
    assert_int_equal(t402_get(&fx, 0x6044, 0), 0);
}

/* Item 11: velocity encoder factor 0x6094:1 = 0x09090909: the scaled
 * values saturate at the 32-bit range in Q16, never wrap. */
static void velocity_factor_saturates(void **state)
{
    (void)state;
    t402_start(&fx, 1, 0, NULL);
    t402_set(&fx, 0x6094, 1, 0x09090909, 4);
    assert_true(co402_vel_in(AX, 1) == (int64_t)0x09090909 * CO402_Q16);
    assert_true(co402_vel_in(AX, INT32_MAX) == CO402_Q16_MAX);
    assert_true(co402_vel_in(AX, INT32_MIN) == -CO402_Q16_MAX);
    assert_true(co402_vel_in(AX, 1000) == CO402_Q16_MAX);
    /* profile velocity with it: the drive runs forward at its top speed */
    t402_set(&fx, 0x6060, 0, 3, 1);
    t402_enable(&fx);
    t402_set(&fx, 0x60FF, 0, INT32_MAX, 4);
    t402_run(&fx, 500000);
    assert_true(fx.sim.v > 0);
    t402_set(&fx, 0x60FF, 0, INT32_MIN, 4);
    t402_run(&fx, 1000000);
    assert_true(fx.sim.v < 0);
}

/* Item 11: a far CSP target (node 2, RPDO1 = controlword + 0x607A, frames
 * from the report): the simulated velocity loop saturates instead of its
 * integral overflowing, and the axis runs toward the target. */
static void csp_far_target(void **state)
{
    (void)state;
    t402_start(&fx, 2, 0, NULL);
    tb_xfer(BUS, "602 23 00 14 01 02 02 00 80", "582 60 00 14 01 00 00 00 00");
    tb_xfer(BUS, "602 2F 00 16 00 00 00 00 00", "582 60 00 16 00 00 00 00 00");
    tb_xfer(BUS, "602 23 00 16 01 10 00 40 60", "582 60 00 16 01 00 00 00 00");
    tb_xfer(BUS, "602 23 00 16 02 20 00 7A 60", "582 60 00 16 02 00 00 00 00");
    tb_xfer(BUS, "602 2F 00 16 00 02 00 00 00", "582 60 00 16 00 00 00 00 00");
    tb_xfer(BUS, "602 23 00 14 01 02 02 00 00", "582 60 00 14 01 00 00 00 00");
    tb_xfer(BUS, "602 2F 60 60 00 08 00 00 00", "582 60 60 60 00 00 00 00 00");
    t402_enable(&fx);
    tb_send(BUS, "000 01 02");
    tb_flush(BUS);
    tb_send(BUS, "202 0F 00 10 A3 E0 12"); /* target 0x12E0A310 */
    for (int k = 0; k < 2000; k++) {
        tb_send(BUS, "080");
        t402_run(&fx, 1000);
    }
    /* the jump is far beyond the following-error window: the drive faults
     * with 0x8611 (the defined reaction), and the plant's velocity stayed
     * within its top speed throughout (no wrapped product) */
    assert_int_equal(t402_sw(&fx) & 0x0008U, 0x0008U);
    assert_int_equal(t402_get(&fx, 0x603F, 0), 0x8611);
    assert_true(fx.sim.v <= (int64_t)fx.simcfg.speed_max * CO402_Q16);
    assert_true(fx.sim.v >= -(int64_t)fx.simcfg.speed_max * CO402_Q16);
    assert_true(t402_get(&fx, 0x6064, 0) > -100000);
    assert_true(t402_get(&fx, 0x6064, 0) < 100000);
}

/* Item 8: a stall of the caller's clock. Beyond 2^31 us the profile's next
 * tick looked 35 minutes ahead (the axis froze); below it the plant
 * simulated every 250 us of the stall (seconds of CPU). Now the profile
 * ticks at once and the plant catches up on the last second only. */
static void stall_profile_and_plant(void **state)
{
    const uint32_t stalls[2] = {40UL * 60UL * 1000000UL, 30UL * 60UL * 1000000UL};

    (void)state;
    for (int k = 0; k < 2; k++) {
        int64_t p0;
        int64_t p1;
        t402_start(&fx, 1, 0, NULL);
        t402_set(&fx, 0x6060, 0, 3, 1);
        t402_enable(&fx);
        t402_set(&fx, 0x60FF, 0, 5000, 4);
        t402_run(&fx, 500000);
        assert_between(t402_get(&fx, 0x606C, 0), 4990, 5010);
        p0 = t402_get(&fx, 0x6064, 0);
        fx.bus.now += stalls[k];
        t402_run(&fx, 10000);
        p1 = t402_get(&fx, 0x6064, 0);
        /* at 5000 increments/s: the last second caught up (below 2^31 us
         * also the profile's 1000 missed ticks, its own bound) and 10 ms run */
        assert_between(p1 - p0, 5000 + 40, (k == 0) ? (5000 + 60) : (10000 + 60));
        t402_run(&fx, 100000);
        assert_between(t402_get(&fx, 0x6064, 0) - p1, 490, 510);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(encoder_fewer_increments_than_revolutions),
        cmocka_unit_test(velocity_factor_saturates),
        cmocka_unit_test(csp_far_target),
        cmocka_unit_test(stall_profile_and_plant),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
