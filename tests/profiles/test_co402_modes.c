/*
 * CiA 402 modes of operation on the simulated axis: every mode really moves
 * it. Profile position (set-point handshake, buffered and immediate
 * set-points, relative moves, software limits, halt, following error),
 * profile velocity, velocity mode (vl), profile torque, interpolated
 * position and the cyclic synchronous modes (set-points taken at SYNC),
 * and bumpless mode changes.
 *
 * Units of the cia402 device: increments (4096 per revolution),
 * increments/s, increments/s^2, per mille of rated torque, rpm for vl.
 */
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

static int setup(void **state)
{
    t402_start(&fx, 1, 0, NULL);
    *state = &fx;
    return 0;
}

static void expect_sw(uint16_t sw)
{
    char resp[64];
    snprintf(resp, sizeof resp, "581 4B 41 60 00 %02X %02X 00 00", sw & 0xFFU, sw >> 8);
    tb_xfer(BUS, "601 40 41 60 00 00 00 00 00", resp);
}

static void sdo_cw(uint16_t cw)
{
    char req[64];
    snprintf(req, sizeof req, "601 2B 40 60 00 %02X %02X 00 00", cw & 0xFFU, cw >> 8);
    tb_xfer(BUS, req, "581 60 40 60 00 00 00 00 00");
}

static int32_t pos(void)
{
    return (int32_t)t402_get(&fx, 0x6064, 0);
}

static int32_t vel(void)
{
    return (int32_t)t402_get(&fx, 0x606C, 0);
}

/* ------------------------------------------------------ profile position */

static void pp_move_reaches_target(void **state)
{
    uint32_t t;
    int32_t vmax = 0;
    (void)state;
    t402_enable(&fx);
    t402_run(&fx, 20000);
    expect_sw(0x0637); /* at rest in its window */
    tb_xfer(BUS, "601 23 7A 60 00 20 4E 00 00", "581 60 7A 60 00 00 00 00 00"); /* 20000 */
    sdo_cw(0x001F); /* new set-point */
    expect_sw(0x1237); /* acknowledged, target not reached */
    sdo_cw(0x000F);
    expect_sw(0x0237); /* handshake done, moving */
    /* trapezoid: 0.1 s up at 100000/s^2 to 10000/s, 1.9 s at speed, 0.1 s down */
    t402_run(&fx, 50000);
    assert_between(vel(), 4800, 5200);
    t402_run(&fx, 100000);
    assert_between(vel(), 9950, 10050);
    assert_between(t402_get(&fx, 0x60F4, 0), -20, 20); /* following error */
    for (t = 150000; (t402_sw(&fx) & 0x0400U) == 0U; t += 1000) {
        t402_run(&fx, 1000);
        if (vel() > vmax) {
            vmax = vel();
        }
        assert_true(t < 3000000);
    }
    assert_between(vmax, 9950, 10100);
    assert_between(t, 2100000, 2130000); /* 2.1 s + the 10 ms window time */
    expect_sw(0x0637);
    tb_xfer(BUS, "601 40 64 60 00 00 00 00 00", "581 43 64 60 00 20 4E 00 00");
    tb_xfer(BUS, "601 40 62 60 00 00 00 00 00", "581 43 62 60 00 20 4E 00 00");
    tb_xfer(BUS, "601 40 63 60 00 00 00 00 00", "581 43 63 60 00 20 4E 00 00");
    assert_int_equal(co402_sim_position(&fx.sim), 20000);
}

static void pp_setpoint_while_acknowledged_is_ignored(void **state)
{
    (void)state;
    t402_enable(&fx);
    t402_set(&fx, 0x607A, 0, 3000, 4);
    t402_cw(&fx, 0x001F);
    assert_int_equal(t402_sw(&fx) & 0x1000, 0x1000);
    /* bit 4 held: a new target is not taken */
    t402_set(&fx, 0x607A, 0, -3000, 4);
    t402_cw(&fx, 0x001F);
    t402_run_until(&fx, 0x0400, 0x0400, 2000000);
    assert_int_equal(pos(), 3000);
    assert_int_equal(t402_sw(&fx), 0x1637); /* still acknowledged: bit 4 still set */
    t402_cw(&fx, 0x000F);
    assert_int_equal(t402_sw(&fx), 0x0637);
}

static void pp_buffered_setpoint(void **state)
{
    int32_t top = 0;
    (void)state;
    t402_enable(&fx);
    t402_set(&fx, 0x607A, 0, 8000, 4);
    t402_cw(&fx, 0x001F);
    t402_cw(&fx, 0x000F); /* ack back to 0: room for one more */
    t402_run(&fx, 300000);
    t402_set(&fx, 0x607A, 0, 1000, 4);
    t402_cw(&fx, 0x001F); /* bit 5 = 0: buffered until the first is done */
    t402_cw(&fx, 0x000F);
    assert_int_equal(t402_sw(&fx), 0x1237); /* buffer full: ack stays */
    t402_set(&fx, 0x607A, 0, 5000, 4);
    t402_cw(&fx, 0x001F); /* not taken: acknowledged */
    t402_cw(&fx, 0x000F);
    while ((t402_sw(&fx) & 0x1000U) != 0U) {
        t402_run(&fx, 1000);
        if (pos() > top) {
            top = pos();
        }
    }
    assert_int_equal(top, 8000); /* the first target was reached, at rest */
    t402_run_until(&fx, 0x0400, 0x0400, 2000000);
    assert_int_equal(pos(), 1000);
    assert_int_equal(t402_sw(&fx), 0x0637);
}

static void pp_change_set_immediately(void **state)
{
    int32_t top = 0;
    (void)state;
    t402_enable(&fx);
    t402_set(&fx, 0x607A, 0, 20000, 4);
    t402_cw(&fx, 0x001F);
    t402_cw(&fx, 0x000F);
    t402_run(&fx, 1000000);
    assert_between(pos(), 9000, 10000);
    t402_set(&fx, 0x607A, 0, 5000, 4);
    t402_cw(&fx, 0x003F); /* bit 5: now */
    assert_int_equal(t402_sw(&fx), 0x1237);
    t402_cw(&fx, 0x002F);
    while ((t402_sw(&fx) & 0x0400U) == 0U) {
        t402_run(&fx, 1000);
        if (pos() > top) {
            top = pos();
        }
    }
    assert_between(top, 9500, 11000); /* turned round after 0.1 s of braking */
    assert_int_equal(pos(), 5000);
}

static void pp_relative(void **state)
{
    (void)state;
    t402_enable(&fx);
    t402_set(&fx, 0x607A, 0, 2000, 4);
    t402_cw(&fx, 0x005F); /* relative to the last target (0) */
    t402_cw(&fx, 0x004F);
    t402_run_until(&fx, 0x0400, 0x0400, 2000000);
    assert_int_equal(pos(), 2000);
    t402_set(&fx, 0x607A, 0, -500, 4);
    t402_cw(&fx, 0x005F);
    t402_cw(&fx, 0x004F);
    /* a second relative set-point while moving adds to the buffered one */
    t402_set(&fx, 0x607A, 0, 100, 4);
    t402_cw(&fx, 0x005F);
    t402_cw(&fx, 0x004F);
    t402_run_until(&fx, 0x1400, 0x0400, 2000000);
    assert_int_equal(pos(), 1600);
}

static void pp_relative_to_actual(void **state)
{
    (void)state;
    t402_start(&fx, 1, CO402_OPT_PP_REL_ACTUAL, NULL);
    t402_enable(&fx);
    t402_set(&fx, 0x607A, 0, 4000, 4);
    t402_cw(&fx, 0x001F);
    t402_cw(&fx, 0x000F);
    t402_run(&fx, 300000);
    t402_set(&fx, 0x607A, 0, 100, 4);
    t402_cw(&fx, 0x007F); /* relative to where the axis is, now */
    t402_cw(&fx, 0x006F);
    t402_run_until(&fx, 0x0400, 0x0400, 2000000);
    assert_between(pos(), 2100, 2700); /* about 2.5 s worth of 10000/s... of 0.3 s */
}

static void pp_software_limits(void **state)
{
    (void)state;
    t402_set(&fx, 0x607D, 1, -1000, 4);
    t402_set(&fx, 0x607D, 2, 3000, 4);
    t402_enable(&fx);
    t402_set(&fx, 0x607A, 0, 20000, 4);
    t402_cw(&fx, 0x001F);
    t402_cw(&fx, 0x000F);
    t402_run(&fx, 10000);
    assert_int_equal(t402_sw(&fx), 0x0A37); /* internal limit active */
    t402_run_until(&fx, 0x0400, 0x0400, 2000000);
    assert_int_equal(pos(), 3000);
    assert_int_equal(t402_sw(&fx), 0x0637);
    t402_set(&fx, 0x607A, 0, -5000, 4);
    t402_cw(&fx, 0x001F);
    t402_cw(&fx, 0x000F);
    t402_run_until(&fx, 0x0400, 0x0400, 2000000);
    assert_int_equal(pos(), -1000);
}

static void pp_halt_and_resume(void **state)
{
    uint32_t t;
    int32_t p;
    (void)state;
    t402_enable(&fx);
    t402_set(&fx, 0x607A, 0, 20000, 4);
    t402_cw(&fx, 0x001F);
    t402_cw(&fx, 0x000F);
    t402_run(&fx, 1000000);
    t402_cw(&fx, 0x010F); /* halt: 0x605D = 1, profile deceleration */
    t = t402_run_until(&fx, 0x0400, 0x0400, 1000000);
    assert_between(t, 100000, 110000);
    p = pos();
    t402_run(&fx, 200000);
    assert_int_equal(pos(), p);
    assert_int_equal(t402_sw(&fx), 0x0637); /* velocity 0 reached */
    t402_cw(&fx, 0x000F); /* the target is kept: on to it */
    t402_run(&fx, 20000);
    assert_int_equal(t402_sw(&fx) & 0x0400, 0);
    t402_run_until(&fx, 0x0400, 0x0400, 2000000);
    assert_int_equal(pos(), 20000);
}

static void pp_following_error(void **state)
{
    co402_sim_config_t sc;
    (void)state;
    /* a weak motor: 3 % of rated torque gives 61440 increments/s^2, not 100000 */
    t402_sim_defaults(&sc);
    sc.torque_max = 30;
    t402_start(&fx, 1, 0, &sc);
    t402_set(&fx, 0x6065, 0, 200, 4);
    t402_enable(&fx);
    t402_set(&fx, 0x607A, 0, 50000, 4);
    t402_cw(&fx, 0x001F);
    t402_cw(&fx, 0x000F);
    tb_flush(BUS);
    t402_run_until(&fx, 0x004F, 0x000F, 1000000); /* fault reaction */
    tb_expect(BUS, "081 11 86 21 00 00 00 00 00");
    assert_int_equal(t402_get(&fx, 0x603F, 0), 0x8611);
    assert_true(t402_get(&fx, 0x60F4, 0) > 200);
    t402_run_until(&fx, 0x004F, 0x0008, 1000000);

    /* warning only: statusword bit 13 while the error lasts */
    t402_start(&fx, 1, CO402_OPT_FE_WARN_ONLY, &sc);
    t402_set(&fx, 0x6065, 0, 200, 4);
    t402_enable(&fx);
    t402_set(&fx, 0x607A, 0, 50000, 4);
    t402_cw(&fx, 0x001F);
    t402_cw(&fx, 0x000F);
    t402_run_until(&fx, 0x2000, 0x2000, 1000000);
    assert_int_equal(co402_state(AX), CO402_OPERATION_ENABLED);
    t402_run_until(&fx, 0x2400, 0x0400, 8000000); /* catches up and arrives */
    assert_between(pos(), 49990, 50010);
    t402_run(&fx, 500000);
    assert_int_equal(pos(), 50000);
}

static void pp_position_window_time(void **state)
{
    uint32_t t;
    (void)state;
    t402_set(&fx, 0x6068, 0, 100, 2);
    t402_enable(&fx);
    t402_set(&fx, 0x607A, 0, 1000, 4);
    t402_cw(&fx, 0x001F);
    t402_cw(&fx, 0x000F);
    t = t402_run_until(&fx, 0x0400, 0x0400, 2000000);
    /* 1000 increments: 0.1 s up, 0.1 s down (triangle peaks at 10000/s), then 100 ms */
    assert_between(t, 295000, 320000);
}

static void pp_target_reached_only_after_a_move(void **state)
{
    (void)state;
    t402_start(&fx, 1, CO402_OPT_PP_TR_AFTER_MOVE, NULL);
    t402_enable(&fx);
    t402_run(&fx, 50000);
    expect_sw(0x0237);
    t402_set(&fx, 0x607A, 0, 500, 4);
    t402_cw(&fx, 0x001F);
    t402_cw(&fx, 0x000F);
    t402_run_until(&fx, 0x0400, 0x0400, 2000000);
    expect_sw(0x0637);
}

static void pp_always_immediate(void **state)
{
    int32_t top = 0;
    (void)state;
    t402_start(&fx, 1, CO402_OPT_PP_ALWAYS_NOW, NULL);
    t402_enable(&fx);
    t402_set(&fx, 0x607A, 0, 20000, 4);
    t402_cw(&fx, 0x001F);
    t402_cw(&fx, 0x000F);
    t402_run(&fx, 500000);
    t402_set(&fx, 0x607A, 0, 0, 4);
    t402_cw(&fx, 0x001F); /* bit 5 clear, acts at once all the same */
    t402_cw(&fx, 0x000F);
    while ((t402_sw(&fx) & 0x0400U) == 0U) {
        t402_run(&fx, 1000);
        if (pos() > top) {
            top = pos();
        }
    }
    assert_true(top < 6000);
    assert_int_equal(pos(), 0);
}

/* ------------------------------------------------------ profile velocity */

static void pv_reaches_speed(void **state)
{
    uint32_t t;
    (void)state;
    tb_xfer(BUS, "601 2F 60 60 00 03 00 00 00", "581 60 60 60 00 00 00 00 00");
    tb_xfer(BUS, "601 23 FF 60 00 00 00 00 00", "581 60 FF 60 00 00 00 00 00");
    t402_enable(&fx);
    t402_run(&fx, 11000);
    expect_sw(0x1637); /* at the target 0 and at speed 0 */
    tb_xfer(BUS, "601 23 FF 60 00 20 4E 00 00", "581 60 FF 60 00 00 00 00 00"); /* 20000 */
    t402_run(&fx, 5000);
    expect_sw(0x0237);
    t = t402_run_until(&fx, 0x0400, 0x0400, 1000000);
    assert_between(t, 190000, 215000); /* 0.2 s ramp + window time */
    assert_between(vel(), 19980, 20020);
    tb_xfer(BUS, "601 40 6B 60 00 00 00 00 00", "581 43 6B 60 00 20 4E 00 00");
    /* reverse: down with 0x6084, up with 0x6083 */
    t402_set(&fx, 0x60FF, 0, -10000, 4);
    t402_run(&fx, 200000);
    assert_between(vel(), -300, 300); /* through zero after 0.2 s */
    t = t402_run_until(&fx, 0x0400, 0x0400, 1000000);
    assert_between(t, 95000, 115000);
    assert_between(vel(), -10020, -9980);
    /* halt */
    t402_cw(&fx, 0x010F);
    t = t402_run_until(&fx, 0x1400, 0x1400, 1000000);
    assert_between(t, 95000, 125000);
    t402_cw(&fx, 0x000F);
    t402_run_until(&fx, 0x1400, 0x0400, 1000000);
    assert_between(vel(), -10020, -9980);
}

static void pv_stops_at_software_limit(void **state)
{
    (void)state;
    t402_set(&fx, 0x607D, 1, -100000, 4);
    t402_set(&fx, 0x607D, 2, 5000, 4);
    t402_set(&fx, 0x6060, 0, 3, 1);
    t402_enable(&fx);
    t402_set(&fx, 0x60FF, 0, 10000, 4);
    t402_run_until(&fx, 0x0800, 0x0800, 2000000);
    t402_run(&fx, 200000);
    assert_between(pos(), 5000, 5600);
    assert_between(vel(), -20, 20);
    t402_set(&fx, 0x60FF, 0, -10000, 4); /* away from it: allowed */
    t402_run(&fx, 200000);
    assert_int_equal(t402_sw(&fx) & 0x0800, 0);
    assert_true(pos() < 5000);
}

/* ------------------------------------------------------ velocity mode (vl) */

static void vl_ramps_in_rpm(void **state)
{
    (void)state;
    t402_set(&fx, 0x6060, 0, 2, 1);
    t402_cw(&fx, 0x0006);
    t402_cw(&fx, 0x007F); /* enable operation + rfg enable, unlock, use reference */
    t402_set(&fx, 0x6042, 0, 600, 2);
    /* 3000 rpm per s: 600 rpm in 0.2 s; 600 rpm = 40960 increments/s */
    t402_run(&fx, 100000);
    assert_between(t402_get(&fx, 0x6043, 0), 290, 310);
    t402_run(&fx, 150000);
    assert_int_equal(t402_get(&fx, 0x6043, 0), 600);
    assert_between(t402_get(&fx, 0x6044, 0), 599, 601);
    assert_between(vel(), 40900, 41020);
    assert_int_equal(t402_sw(&fx) & 0x0400, 0x0400);
    /* ramp locked (bit 5 clear): the output stays */
    t402_set(&fx, 0x6042, 0, 0, 2);
    t402_cw(&fx, 0x005F);
    t402_run(&fx, 100000);
    assert_int_equal(t402_get(&fx, 0x6043, 0), 600);
    t402_cw(&fx, 0x007F);
    t402_run(&fx, 250000);
    assert_int_equal(t402_get(&fx, 0x6043, 0), 0);
    /* min amount: a small target becomes the minimum */
    t402_set(&fx, 0x6046, 1, 100, 4);
    t402_set(&fx, 0x6042, 0, -30, 2);
    t402_run(&fx, 100000);
    assert_int_equal(t402_get(&fx, 0x6043, 0), -100);
    /* max amount */
    t402_set(&fx, 0x6046, 2, 300, 4);
    t402_set(&fx, 0x6042, 0, 1000, 2);
    t402_run(&fx, 300000);
    assert_int_equal(t402_get(&fx, 0x6043, 0), 300);
    /* reference off (bit 6): ramps to 0 */
    t402_cw(&fx, 0x003F);
    t402_run(&fx, 200000);
    assert_int_equal(t402_get(&fx, 0x6043, 0), 0);
}

/* ------------------------------------------------------ profile torque */

static void tq_torque_ramp_and_limit(void **state)
{
    (void)state;
    t402_set(&fx, 0x6060, 0, 4, 1);
    t402_enable(&fx);
    t402_set(&fx, 0x6071, 0, 100, 2); /* 10 % rated, slope 10000 per mille/s: 10 ms */
    t402_run(&fx, 5000);
    assert_between(t402_get(&fx, 0x6074, 0), 40, 60);
    assert_int_equal(t402_sw(&fx) & 0x0400, 0);
    t402_run(&fx, 10000);
    assert_int_equal(t402_get(&fx, 0x6074, 0), 100);
    assert_int_equal(t402_sw(&fx), 0x0637);
    assert_between(t402_get(&fx, 0x6077, 0), 99, 100);
    /* the unloaded motor accelerates: 204800 increments/s^2 less friction */
    t402_run(&fx, 100000);
    assert_between(vel(), 19000, 21500);
    /* max torque limits the demand */
    t402_set(&fx, 0x6072, 0, 50, 2);
    t402_set(&fx, 0x6071, 0, -400, 2);
    t402_run(&fx, 200000);
    assert_int_equal(t402_get(&fx, 0x6074, 0), -50);
    assert_int_equal(t402_get(&fx, 0x6077, 0), -50);
}

/* ------------------------------------------------ interpolated position */

static void ip_follows_setpoints_at_sync(void **state)
{
    (void)state;
    t402_set(&fx, 0x60C2, 1, 5, 1); /* 5 * 10^-3 s */
    tb_xfer(BUS, "601 2F 60 60 00 07 00 00 00", "581 60 60 60 00 00 00 00 00");
    t402_enable(&fx);
    expect_sw(0x0237);
    sdo_cw(0x001F); /* enable ip */
    expect_sw(0x1237);
    for (int k = 1; k <= 40; k++) {
        t402_set(&fx, 0x60C1, 1, 50 * k, 4); /* 10000 increments/s */
        tb_send(BUS, "080");
        t402_run(&fx, 2000);
        /* 2 ms into a 5 ms segment from 50(k-1) to 50k */
        assert_between(t402_get(&fx, 0x6062, 0), 50 * (k - 1) + 19, 50 * (k - 1) + 21);
        t402_run(&fx, 3000);
    }
    assert_between(pos(), 1995, 2005);
    assert_between(vel(), 9900, 10100);
    /* without new set-points the axis stays at the last */
    tb_send(BUS, "080");
    t402_run(&fx, 100000);
    assert_int_equal(pos(), 2000);
    /* ip disabled: SYNC moves nothing */
    sdo_cw(0x000F);
    expect_sw(0x0237);
    t402_set(&fx, 0x60C1, 1, 9000, 4);
    tb_send(BUS, "080");
    t402_run(&fx, 100000);
    assert_int_equal(pos(), 2000);
}

/* -------------------------------------------------- cyclic synchronous */

static void csp_takes_targets_at_sync(void **state)
{
    (void)state;
    tb_xfer(BUS, "601 2F 60 60 00 08 00 00 00", "581 60 60 60 00 00 00 00 00");
    t402_enable(&fx);
    expect_sw(0x1237); /* target position used */
    /* SYNC every 2 ms, no 0x60C2: the measured interval is the period */
    tb_send(BUS, "080");
    t402_run(&fx, 2000);
    for (int k = 1; k <= 100; k++) {
        t402_set(&fx, 0x607A, 0, 20 * k, 4);
        if (k == 50) {
            /* written, but not yet taken: no SYNC since */
            t402_run(&fx, 1000);
            assert_between(t402_get(&fx, 0x6062, 0), 20 * 48, 20 * 49);
            t402_run(&fx, 1000);
            tb_send(BUS, "080");
            continue;
        }
        tb_send(BUS, "080");
        t402_run(&fx, 2000);
    }
    t402_run(&fx, 150000);
    assert_int_equal(pos(), 2000);
    /* position offset 0x60B0 adds to the target */
    t402_set(&fx, 0x60B0, 0, 100, 4);
    tb_send(BUS, "080");
    t402_run(&fx, 300000);
    assert_int_equal(pos(), 2100);
}

static void csv_takes_velocity_at_sync(void **state)
{
    (void)state;
    t402_set(&fx, 0x6060, 0, 9, 1);
    t402_enable(&fx);
    assert_int_equal(t402_sw(&fx), 0x1237);
    t402_set(&fx, 0x60FF, 0, 5000, 4);
    t402_run(&fx, 50000);
    assert_between(vel(), -5, 5); /* not before a SYNC */
    tb_send(BUS, "080");
    t402_run(&fx, 200000);
    assert_between(vel(), 4990, 5010);
    t402_set(&fx, 0x60B1, 0, -2000, 4);
    tb_send(BUS, "080");
    t402_run(&fx, 200000);
    assert_between(vel(), 2990, 3010);
}

static void cst_takes_torque_at_sync(void **state)
{
    (void)state;
    t402_set(&fx, 0x6060, 0, 10, 1);
    t402_enable(&fx);
    t402_set(&fx, 0x6071, 0, 200, 2);
    t402_run(&fx, 10000);
    assert_int_equal(t402_get(&fx, 0x6077, 0), 0);
    tb_send(BUS, "080");
    t402_run(&fx, 10000);
    assert_int_equal(t402_get(&fx, 0x6077, 0), 200);
    assert_int_equal(t402_get(&fx, 0x6074, 0), 200);
    t402_set(&fx, 0x60B2, 0, -150, 2);
    tb_send(BUS, "080");
    t402_run(&fx, 2000); /* commanded at the next tick, measured at the one after */
    assert_int_equal(t402_get(&fx, 0x6077, 0), 50);
    assert_true(vel() > 0);
}

/* ------------------------------------------------------ mode changes */

static void mode_change_is_bumpless(void **state)
{
    int32_t v0;
    int32_t p0;
    (void)state;
    t402_set(&fx, 0x6060, 0, 3, 1);
    t402_enable(&fx);
    t402_set(&fx, 0x60FF, 0, 20000, 4);
    t402_run(&fx, 300000);
    v0 = vel();
    p0 = pos();
    tb_xfer(BUS, "601 2F 60 60 00 01 00 00 00", "581 60 60 60 00 00 00 00 00");
    tb_xfer(BUS, "601 40 61 60 00 00 00 00 00", "581 4F 61 60 00 01 00 00 00");
    t402_run(&fx, 1000);
    /* pp without a set-point: brakes with 0x6084 and holds, no jump */
    assert_between(vel(), v0 - 300, v0 + 100);
    t402_run_until(&fx, 0x0400, 0x0400, 1000000);
    t402_run(&fx, 50000);
    assert_between(vel(), -10, 10);
    assert_between(pos() - p0, 1900, 2100); /* v^2 / 2a = 2000 */
    /* and a profile position move from there */
    t402_set(&fx, 0x607A, 0, 0, 4);
    t402_cw(&fx, 0x001F);
    t402_cw(&fx, 0x000F);
    t402_run_until(&fx, 0x0400, 0x0400, 3000000);
    assert_int_equal(pos(), 0);
}

static void no_mode(void **state)
{
    (void)state;
    t402_set(&fx, 0x6060, 0, 0, 1);
    t402_enable(&fx);
    t402_set(&fx, 0x607A, 0, 5000, 4);
    t402_cw(&fx, 0x001F);
    t402_run(&fx, 100000);
    assert_int_equal(pos(), 0);
    assert_int_equal(t402_sw(&fx), 0x0237);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(pp_move_reaches_target, setup),
        cmocka_unit_test_setup(pp_setpoint_while_acknowledged_is_ignored, setup),
        cmocka_unit_test_setup(pp_buffered_setpoint, setup),
        cmocka_unit_test_setup(pp_change_set_immediately, setup),
        cmocka_unit_test_setup(pp_relative, setup),
        cmocka_unit_test_setup(pp_relative_to_actual, setup),
        cmocka_unit_test_setup(pp_software_limits, setup),
        cmocka_unit_test_setup(pp_halt_and_resume, setup),
        cmocka_unit_test_setup(pp_following_error, setup),
        cmocka_unit_test_setup(pp_position_window_time, setup),
        cmocka_unit_test_setup(pp_target_reached_only_after_a_move, setup),
        cmocka_unit_test_setup(pp_always_immediate, setup),
        cmocka_unit_test_setup(pv_reaches_speed, setup),
        cmocka_unit_test_setup(pv_stops_at_software_limit, setup),
        cmocka_unit_test_setup(vl_ramps_in_rpm, setup),
        cmocka_unit_test_setup(tq_torque_ramp_and_limit, setup),
        cmocka_unit_test_setup(ip_follows_setpoints_at_sync, setup),
        cmocka_unit_test_setup(csp_takes_targets_at_sync, setup),
        cmocka_unit_test_setup(csv_takes_velocity_at_sync, setup),
        cmocka_unit_test_setup(cst_takes_torque_at_sync, setup),
        cmocka_unit_test_setup(mode_change_is_bumpless, setup),
        cmocka_unit_test_setup(no_mode, setup),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
