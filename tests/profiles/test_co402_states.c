/*
 * CiA 402 device control: every transition 0..16 with its controlword
 * command and the exact statusword, option codes 0x605A..0x605E, fault
 * handling (0x603F, EMCY, fault reset edge), the abort connection option
 * 0x6007, and the device-deviation options.
 *
 * Node 1 of the cia402 device on the simulated plant; statusword values
 * include bit 4 (DC-link voltage present) and bit 9 (remote).
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

/* SDO: read the statusword and expect @p sw. */
static void expect_sw(uint16_t sw)
{
    char resp[64];
    snprintf(resp, sizeof resp, "581 4B 41 60 00 %02X %02X 00 00", sw & 0xFFU, sw >> 8);
    tb_xfer(BUS, "601 40 41 60 00 00 00 00 00", resp);
}

/* SDO: write the controlword, expect the confirmation. */
static void sdo_cw(uint16_t cw)
{
    char req[64];
    snprintf(req, sizeof req, "601 2B 40 60 00 %02X %02X 00 00", cw & 0xFFU, cw >> 8);
    tb_xfer(BUS, req, "581 60 40 60 00 00 00 00 00");
}

/* ---------------------------------------------------------------- boot */

static void boot_is_switch_on_disabled(void **state)
{
    (void)state;
    /* transitions 0 and 1 ran at attach: Switch on disabled, voltage, remote */
    assert_int_equal(co402_state(AX), CO402_SWITCH_ON_DISABLED);
    expect_sw(0x0250);
    tb_xfer(BUS, "601 40 61 60 00 00 00 00 00", "581 4F 61 60 00 01 00 00 00");
    tb_xfer(BUS, "601 40 3F 60 00 00 00 00 00", "581 4B 3F 60 00 00 00 00 00");
    tb_xfer(BUS, "601 40 02 65 00 00 00 00 00", "581 43 02 65 00 EF 03 00 00");
    /* the statusword is read-only */
    tb_xfer(BUS, "601 2B 41 60 00 00 00 00 00", "581 80 41 60 00 02 00 01 06");
}

/* An axis at rest with its power stage off asks to be woken only every
 * 100 ms (CO402_IDLE_US); a controlword frame in between acts at once, and
 * an enabled axis wants its 1 ms control tick again. */
static void idle_axis_wakes_rarely(void **state)
{
    uint32_t next;

    (void)state;
    next = co_profile_host_process(&fx.host, fx.bus.now);
    assert_int_equal(next - fx.bus.now, 100000U);
    fx.bus.now += 350000U; /* nothing ran for 350 ms */
    sdo_cw(0x0006);
    expect_sw(0x0231);
    next = co_profile_host_process(&fx.host, fx.bus.now);
    assert_int_equal(next - fx.bus.now, 100000U); /* Ready to switch on: still at rest */
    sdo_cw(0x0007);
    sdo_cw(0x000F);
    expect_sw(0x0237);
    next = co_profile_host_process(&fx.host, fx.bus.now);
    assert_true(next - fx.bus.now <= 1000U); /* Operation enabled: every tick */
    t402_run(&fx, 11000);
    expect_sw(0x0637); /* pp at rest: target reached after the window time */
    sdo_cw(0x0000);    /* 9: disable voltage */
    expect_sw(0x0250);
    next = co_profile_host_process(&fx.host, fx.bus.now);
    assert_int_equal(next - fx.bus.now, 100000U);
    tb_expect_none(BUS);
}

/* ----------------------------------------------------- 2, 3, 4 by SDO */

static void enable_step_by_step(void **state)
{
    (void)state;
    sdo_cw(0x0006); /* 2: shutdown */
    expect_sw(0x0231);
    sdo_cw(0x0007); /* 3: switch on */
    expect_sw(0x0233);
    sdo_cw(0x000F); /* 4: enable operation */
    expect_sw(0x0237);
    assert_int_equal(co402_state(AX), CO402_OPERATION_ENABLED);
    /* pp at rest: target reached after the position window time (10 ms) */
    t402_run(&fx, 9000);
    expect_sw(0x0237);
    t402_run(&fx, 2000);
    expect_sw(0x0637);
    tb_expect_none(BUS);
}

static void switch_on_and_enable_in_one_write(void **state)
{
    (void)state;
    sdo_cw(0x0006);
    sdo_cw(0x000F); /* 3 + 4 */
    expect_sw(0x0237);
}

static void one_transition_per_write(void **state)
{
    (void)state;
    t402_start(&fx, 1, CO402_OPT_ONE_TRANSITION, NULL);
    sdo_cw(0x000E); /* shutdown (bit 3 is don't care) */
    expect_sw(0x0231);
    sdo_cw(0x000F); /* only 3 */
    expect_sw(0x0233);
    sdo_cw(0x000F); /* now 4 */
    expect_sw(0x0237);
}

static void commands_out_of_sequence_are_ignored(void **state)
{
    (void)state;
    sdo_cw(0x000F); /* enable operation in Switch on disabled: no transition */
    expect_sw(0x0250);
    sdo_cw(0x0007); /* switch on: no transition either */
    expect_sw(0x0250);
    sdo_cw(0x0006);
    sdo_cw(0x0006); /* shutdown again: stays */
    expect_sw(0x0231);
    sdo_cw(0x0080); /* fault reset outside Fault: nothing */
    expect_sw(0x0231);
}

/* ------------------------------------------------------ 5, 6, 7, 8, 9, 10 */

static void transition_5_disable_operation(void **state)
{
    (void)state;
    t402_enable(&fx);
    /* 0x605C = 1 (default): slow down first; at rest this takes one tick */
    sdo_cw(0x0007);
    expect_sw(0x0237);
    t402_run(&fx, 1000);
    expect_sw(0x0233);
    /* 0x605C = 0: at once */
    tb_xfer(BUS, "601 2B 5C 60 00 00 00 00 00", "581 60 5C 60 00 00 00 00 00");
    sdo_cw(0x000F);
    sdo_cw(0x0007);
    expect_sw(0x0233);
    assert_int_equal(co402_state(AX), CO402_SWITCHED_ON);
}

static void transition_6_7_10(void **state)
{
    (void)state;
    sdo_cw(0x0006);
    sdo_cw(0x0007);
    sdo_cw(0x0006); /* 6 */
    expect_sw(0x0231);
    sdo_cw(0x0000); /* 7 by disable voltage */
    expect_sw(0x0250);
    sdo_cw(0x0006);
    sdo_cw(0x0002); /* 7 by quick stop */
    expect_sw(0x0250);
    sdo_cw(0x0006);
    sdo_cw(0x0007);
    sdo_cw(0x0000); /* 10 by disable voltage */
    expect_sw(0x0250);
    sdo_cw(0x0006);
    sdo_cw(0x0007);
    sdo_cw(0x000B); /* 10 by quick stop (bit 2 clear) */
    expect_sw(0x0250);
}

static void transition_8_shutdown(void **state)
{
    (void)state;
    t402_enable(&fx);
    sdo_cw(0x0006); /* 0x605B = 0 (default): power off at once */
    expect_sw(0x0231);
    /* 0x605B = 1: slow down first */
    tb_xfer(BUS, "601 2B 5B 60 00 01 00 00 00", "581 60 5B 60 00 00 00 00 00");
    sdo_cw(0x000F);
    sdo_cw(0x000F);
    expect_sw(0x0237);
    sdo_cw(0x0006);
    expect_sw(0x0237);
    t402_run(&fx, 1000);
    expect_sw(0x0231);
    /* out of range option code */
    tb_xfer(BUS, "601 2B 5B 60 00 02 00 00 00", "581 80 5B 60 00 31 00 09 06");
}

static void transition_9_disable_voltage(void **state)
{
    (void)state;
    t402_enable(&fx);
    sdo_cw(0x0000);
    expect_sw(0x0250);
    assert_int_equal(co402_state(AX), CO402_SWITCH_ON_DISABLED);
}

/* -------------------------------------------------- 11, 12, 16 (quick stop) */

static void transition_11_12_quick_stop_to_disabled(void **state)
{
    (void)state;
    t402_enable(&fx);
    /* 0x605A = 2: quick stop ramp, then Switch on disabled (12) */
    sdo_cw(0x000B);
    expect_sw(0x0217);
    assert_int_equal(co402_state(AX), CO402_QUICK_STOP_ACTIVE);
    t402_run(&fx, 1000);
    expect_sw(0x0250);
    /* 0x605A = 0: disable the drive function at once */
    tb_xfer(BUS, "601 2B 5A 60 00 00 00 00 00", "581 60 5A 60 00 00 00 00 00");
    t402_enable(&fx);
    sdo_cw(0x0002);
    expect_sw(0x0250);
}

static void transition_16_back_from_quick_stop(void **state)
{
    (void)state;
    tb_xfer(BUS, "601 2B 5A 60 00 06 00 00 00", "581 60 5A 60 00 00 00 00 00");
    t402_enable(&fx);
    sdo_cw(0x0002);
    expect_sw(0x0217);
    t402_run(&fx, 1000);
    expect_sw(0x0617); /* at rest, stays in Quick stop active */
    t402_run(&fx, 50000);
    expect_sw(0x0617);
    sdo_cw(0x000F); /* 16 */
    expect_sw(0x0237);
    assert_int_equal(co402_state(AX), CO402_OPERATION_ENABLED);
    sdo_cw(0x0002);
    sdo_cw(0x0000); /* 12 by disable voltage */
    expect_sw(0x0250);
}

static void no_transition_16_with_option_below_5(void **state)
{
    (void)state;
    tb_xfer(BUS, "601 2B 5A 60 00 01 00 00 00", "581 60 5A 60 00 00 00 00 00");
    t402_enable(&fx);
    /* move, so that the stop takes a while */
    t402_set(&fx, 0x6060, 0, 3, 1);
    t402_set(&fx, 0x60FF, 0, 20000, 4);
    t402_run(&fx, 400000);
    sdo_cw(0x0002);
    expect_sw(0x0217);
    sdo_cw(0x000F); /* not with 0x605A = 1 */
    expect_sw(0x0217);
    t402_run_until(&fx, 0xFFFF, 0x0250, 1000000);
}

/* --------------------------------------------------------- 13, 14, 15 */

static void transition_13_14_15_fault(void **state)
{
    (void)state;
    t402_enable(&fx);
    tb_flush(BUS);
    co402_fault_raise(AX, 0x2310); /* over-current: 13 */
    tb_expect(BUS, "081 10 23 03 00 00 00 00 00");
    expect_sw(0x021F); /* Fault reaction active */
    tb_xfer(BUS, "601 40 3F 60 00 00 00 00 00", "581 4B 3F 60 00 10 23 00 00");
    t402_run(&fx, 1000); /* at rest: the reaction ends (14) */
    expect_sw(0x0218);
    assert_int_equal(co402_state(AX), CO402_FAULT);
    /* commands other than fault reset do nothing */
    sdo_cw(0x0006);
    sdo_cw(0x000F);
    expect_sw(0x0218);
    /* fault reset while the cause is still there: stays */
    sdo_cw(0x0080);
    expect_sw(0x0218);
    co402_fault_clear(AX, 0x2310);
    sdo_cw(0x0080); /* no rising edge: bit 7 was already set */
    expect_sw(0x0218);
    sdo_cw(0x0000);
    sdo_cw(0x0080); /* 15 */
    expect_sw(0x0250);
    tb_xfer(BUS, "601 40 3F 60 00 00 00 00 00", "581 4B 3F 60 00 00 00 00 00");
    t402_run(&fx, 1000); /* the error ends after the answer */
    tb_expect(BUS, "081 00 00 00 00 00 00 00 00");
    tb_xfer(BUS, "601 40 01 10 00 00 00 00 00", "581 4F 01 10 00 00 00 00 00");
    assert_int_equal(co402_state(AX), CO402_SWITCH_ON_DISABLED);
    /* with bit 7 still set, shutdown is not decoded */
    sdo_cw(0x0086);
    expect_sw(0x0250);
    sdo_cw(0x0006);
    expect_sw(0x0231);
}

static void fault_when_not_energised_is_at_once(void **state)
{
    (void)state;
    tb_flush(BUS);
    co402_fault_event(AX, 0x4310); /* temperature, an event: no lasting cause */
    tb_expect(BUS, "081 10 43 09 00 00 00 00 00");
    expect_sw(0x0218);
    sdo_cw(0x0080);
    expect_sw(0x0250);
    t402_run(&fx, 1000);
    tb_expect(BUS, "081 00 00 00 00 00 00 00 00");
}

static void fault_in_every_state(void **state)
{
    static const uint16_t to[] = {0x0000, 0x0006, 0x0007, 0x000F};
    (void)state;
    for (unsigned i = 0; i < 4U; i++) {
        t402_start(&fx, 1, 0, NULL);
        for (unsigned k = 0; k <= i; k++) {
            t402_cw(&fx, to[k]);
        }
        co402_fault_event(AX, 0x5530);
        t402_run(&fx, 2000);
        assert_int_equal(co402_state(AX), CO402_FAULT);
        assert_int_equal(t402_get(&fx, 0x603F, 0), 0x5530);
    }
    /* from Quick stop active too */
    t402_start(&fx, 1, 0, NULL);
    t402_set(&fx, 0x605A, 0, 6, 2);
    t402_cw(&fx, 0x0006);
    t402_cw(&fx, 0x000F);
    t402_cw(&fx, 0x0002);
    t402_run(&fx, 2000);
    assert_int_equal(co402_state(AX), CO402_QUICK_STOP_ACTIVE);
    co402_fault_event(AX, 0x5530);
    t402_run(&fx, 2000);
    assert_int_equal(co402_state(AX), CO402_FAULT);
}

/* ----------------------------------------------- stop reactions in motion */

/* Runs in pv at 40000 inc/s, then @p action; returns the time to rest and
 * the distance covered meanwhile. */
static void stop_from_speed(uint16_t obj, int16_t code, uint16_t cw, uint32_t *ms, int32_t *dist)
{
    int32_t p0;
    uint32_t t = 0;

    t402_start(&fx, 1, 0, NULL);
    t402_set(&fx, 0x6060, 0, 3, 1);
    t402_set(&fx, 0x6083, 0, 400000, 4);
    t402_set(&fx, 0x6084, 0, 100000, 4);  /* slow down ramp */
    t402_set(&fx, 0x6085, 0, 1000000, 4); /* quick stop ramp */
    t402_set(&fx, obj, 0, code, 2);
    t402_cw(&fx, 0x0006);
    t402_cw(&fx, 0x000F);
    t402_set(&fx, 0x60FF, 0, 40000, 4);
    t402_run(&fx, 300000);
    assert_between(co402_sim_velocity(&fx.sim), 39900, 40100);
    p0 = co402_sim_position(&fx.sim);
    if (cw != 0xFFFFU) {
        t402_cw(&fx, cw);
    } else {
        co402_fault_event(AX, 0x2310);
    }
    while (co402_sim_velocity(&fx.sim) > 4) {
        t402_run(&fx, 1000);
        t += 1;
        assert_true(t < 5000);
    }
    *ms = t;
    *dist = co402_sim_position(&fx.sim) - p0;
}

/* Option code 0: the power goes off at once and the motor coasts down on
 * friction alone (1/s: 40000 -> 32749 increments/s in 200 ms). */
static void coast(uint16_t obj, uint16_t cw)
{
    t402_start(&fx, 1, 0, NULL);
    t402_set(&fx, 0x6060, 0, 3, 1);
    t402_set(&fx, 0x6083, 0, 400000, 4);
    t402_set(&fx, obj, 0, 0, 2);
    t402_cw(&fx, 0x0006);
    t402_cw(&fx, 0x000F);
    t402_set(&fx, 0x60FF, 0, 40000, 4);
    t402_run(&fx, 300000);
    if (cw != 0xFFFFU) {
        t402_cw(&fx, cw);
    } else {
        co402_fault_event(AX, 0x2310);
    }
    t402_run(&fx, 200000);
    assert_between(co402_sim_velocity(&fx.sim), 32500, 33000);
}

static void quick_stop_option_codes(void **state)
{
    uint32_t t1, t2, t3;
    int32_t d1, d2, d3;
    (void)state;
    stop_from_speed(0x605A, 1, 0x000B, &t1, &d1); /* slow down ramp 100000: 400 ms */
    assert_between(t1, 395, 420);
    assert_between(d1, 7800, 8200); /* v^2 / 2a = 8000 */
    t402_run_until(&fx, 0xFFFF, 0x0250, 20000);
    stop_from_speed(0x605A, 2, 0x000B, &t2, &d2); /* quick stop ramp 1000000: 40 ms */
    assert_between(t2, 38, 50);
    assert_between(d2, 750, 900);
    t402_run_until(&fx, 0xFFFF, 0x0250, 20000);
    stop_from_speed(0x605A, 3, 0x000B, &t3, &d3); /* current limit: faster still */
    assert_true(t3 < t2);
    assert_true(d3 < d2);
    t402_run_until(&fx, 0xFFFF, 0x0250, 20000);
    coast(0x605A, 0x000B); /* 0: no torque at once, the motor coasts on friction */
    assert_int_equal(t402_sw(&fx), 0x0250);
    /* 5..8 stop the same way and stay in Quick stop active */
    stop_from_speed(0x605A, 6, 0x000B, &t2, &d2);
    assert_between(t2, 38, 50);
    t402_run(&fx, 20000);
    assert_int_equal(t402_sw(&fx), 0x0617);
    stop_from_speed(0x605A, 5, 0x000B, &t1, &d1);
    assert_between(t1, 395, 420);
    t402_run(&fx, 20000);
    assert_int_equal(t402_sw(&fx), 0x0617);
}

static void fault_reaction_option_codes(void **state)
{
    uint32_t t1, t2;
    int32_t d1, d2;
    (void)state;
    stop_from_speed(0x605E, 1, 0xFFFF, &t1, &d1);
    assert_between(t1, 395, 420);
    t402_run(&fx, 2000);
    assert_int_equal(t402_sw(&fx), 0x0218);
    stop_from_speed(0x605E, 2, 0xFFFF, &t2, &d2);
    assert_between(t2, 38, 50);
    coast(0x605E, 0xFFFF);
    assert_int_equal(t402_sw(&fx), 0x0218); /* in Fault at once */
    (void)d1;
    (void)d2;
}

static void fault_reaction_active_while_braking(void **state)
{
    uint32_t t;
    (void)state;
    t402_set(&fx, 0x6060, 0, 3, 1);
    t402_set(&fx, 0x6085, 0, 100000, 4);
    t402_cw(&fx, 0x0006);
    t402_cw(&fx, 0x000F);
    t402_set(&fx, 0x60FF, 0, 20000, 4);
    t402_run(&fx, 500000);
    co402_fault_event(AX, 0x7500);
    assert_int_equal(t402_sw(&fx), 0x021F);
    t402_run(&fx, 100000);
    assert_int_equal(t402_sw(&fx), 0x021F); /* still braking: 200 ms */
    t = t402_run_until(&fx, 0xFFFF, 0x0218, 200000);
    assert_between(t, 90000, 120000);
}

static void disable_operation_ramps_down_first(void **state)
{
    uint32_t t;
    (void)state;
    t402_set(&fx, 0x6060, 0, 3, 1);
    t402_set(&fx, 0x6084, 0, 100000, 4);
    t402_cw(&fx, 0x0006);
    t402_cw(&fx, 0x000F);
    t402_set(&fx, 0x60FF, 0, 20000, 4);
    t402_run(&fx, 500000);
    t402_cw(&fx, 0x0007); /* 5 with 0x605C = 1 */
    t402_run(&fx, 100000);
    assert_int_equal(co402_state(AX), CO402_OPERATION_ENABLED);
    t = t402_run_until(&fx, 0x006F, 0x0023, 300000);
    assert_between(t, 90000, 120000);
    /* enable operation again during the ramp calls 5 off */
    t402_cw(&fx, 0x000F);
    t402_set(&fx, 0x60FF, 0, 20000, 4);
    t402_run(&fx, 500000);
    t402_cw(&fx, 0x0007);
    t402_run(&fx, 50000);
    t402_cw(&fx, 0x000F);
    t402_run(&fx, 500000);
    assert_int_equal(co402_state(AX), CO402_OPERATION_ENABLED);
    assert_between(co402_sim_velocity(&fx.sim), 19900, 20100);
}

/* ------------------------------------------------------ hardware inputs */

static void hardware_enable_gates_switch_on(void **state)
{
    (void)state;
    co402_sim_set_level(&fx.sim, CO402_IN_ENABLE, false);
    t402_run(&fx, 1000);
    sdo_cw(0x0006);
    sdo_cw(0x0007); /* 3 needs the enable input */
    expect_sw(0x0231);
    co402_sim_set_level(&fx.sim, CO402_IN_ENABLE, true);
    t402_run(&fx, 1000);
    sdo_cw(0x0007);
    expect_sw(0x0233);
    sdo_cw(0x000F);
    tb_flush(BUS);
    /* losing it while energised is a fault (0x5441) until it is back */
    co402_sim_set_level(&fx.sim, CO402_IN_ENABLE, false);
    t402_run(&fx, 1000);
    tb_expect(BUS, "081 41 54 01 00 00 00 00 00");
    expect_sw(0x0218);
    sdo_cw(0x0080);
    expect_sw(0x0218);
    co402_sim_set_level(&fx.sim, CO402_IN_ENABLE, true);
    t402_run(&fx, 1000);
    sdo_cw(0x0000);
    sdo_cw(0x0080);
    expect_sw(0x0250);
    t402_run(&fx, 1000);
    tb_expect(BUS, "081 00 00 00 00 00 00 00 00");
}

static void dc_link_voltage_is_bit_4(void **state)
{
    (void)state;
    co402_sim_set_level(&fx.sim, CO402_IN_VOLTAGE, false);
    t402_run(&fx, 1000);
    expect_sw(0x0240);
    sdo_cw(0x0006);
    expect_sw(0x0221);
}

static void plant_fault(void **state)
{
    (void)state;
    t402_enable(&fx);
    tb_flush(BUS);
    co402_sim_set_fault(&fx.sim, 0x3210); /* DC-link over-voltage */
    t402_run(&fx, 1000);
    tb_expect(BUS, "081 10 32 05 00 00 00 00 00");
    assert_int_equal(co402_state(AX), CO402_FAULT); /* no torque: at once */
    sdo_cw(0x0080);
    expect_sw(0x0218);
    co402_sim_set_fault(&fx.sim, 0);
    t402_run(&fx, 1000);
    sdo_cw(0x0000);
    sdo_cw(0x0080);
    expect_sw(0x0250);
}

/* ------------------------------------------------- 0x6007, NMT, reset */

static void abort_connection_on_nmt_stop(void **state)
{
    (void)state;
    tb_send(BUS, "000 01 01");
    tb_expect(BUS, "181 50 02"); /* event-driven TPDOs on entering Operational */
    tb_expect(BUS, "281 50 02 01");
    t402_enable(&fx);
    tb_flush(BUS);
    tb_send(BUS, "000 02 01"); /* 0x6007 = 1: fault */
    assert_int_equal(co402_state(AX), CO402_FAULT_REACTION);
    t402_run(&fx, 2000);
    assert_int_equal(co402_state(AX), CO402_FAULT);
    assert_int_equal(t402_get(&fx, 0x603F, 0), 0x8100);
    tb_expect_none(BUS); /* no EMCY in Stopped */

    t402_start(&fx, 1, 0, NULL);
    t402_set(&fx, 0x6007, 0, 2, 2); /* disable voltage */
    tb_send(BUS, "000 01 01");
    tb_expect(BUS, "181 50 02"); /* event-driven TPDOs on entering Operational */
    tb_expect(BUS, "281 50 02 01");
    t402_enable(&fx);
    tb_send(BUS, "000 02 01");
    assert_int_equal(co402_state(AX), CO402_SWITCH_ON_DISABLED);

    t402_start(&fx, 1, 0, NULL);
    t402_set(&fx, 0x6007, 0, 3, 2); /* quick stop */
    tb_send(BUS, "000 01 01");
    tb_expect(BUS, "181 50 02"); /* event-driven TPDOs on entering Operational */
    tb_expect(BUS, "281 50 02 01");
    t402_enable(&fx);
    tb_send(BUS, "000 02 01");
    assert_int_equal(co402_state(AX), CO402_QUICK_STOP_ACTIVE);

    t402_start(&fx, 1, 0, NULL);
    t402_set(&fx, 0x6007, 0, 0, 2); /* nothing */
    tb_send(BUS, "000 01 01");
    tb_expect(BUS, "181 50 02"); /* event-driven TPDOs on entering Operational */
    tb_expect(BUS, "281 50 02 01");
    t402_enable(&fx);
    tb_send(BUS, "000 02 01");
    assert_int_equal(co402_state(AX), CO402_OPERATION_ENABLED);
}

static void abort_connection_on_heartbeat_loss(void **state)
{
    (void)state;
    /* consume the heartbeat of node 0x7F, 100 ms */
    tb_xfer(BUS, "601 23 16 10 01 64 00 7F 00", "581 60 16 10 01 00 00 00 00");
    tb_send(BUS, "77F 05");
    t402_enable(&fx);
    tb_flush(BUS);
    t402_run(&fx, 101000);
    tb_expect(BUS, "081 30 81 11 00 00 00 00 00");
    assert_int_equal(co402_state(AX), CO402_FAULT);
    assert_int_equal(t402_get(&fx, 0x603F, 0), 0x8130);
}

/* CO402_OPT_LOSS_WARN_STOP (Kollmorgen n04): a heartbeat loss is a warning,
 * statusword bits 7 and 11, not 0x6007's fault; the axis brakes on the
 * quick-stop ramp and holds in Operation enabled; new set-points and enable
 * commands do not move it until a fault reset (bit 7 rising edge) ends the
 * warning, then the mode runs again. */
static void loss_warning_stops_until_fault_reset(void **state)
{
    uint32_t t = 0;

    (void)state;
    t402_start(&fx, 1, CO402_OPT_LOSS_WARN_STOP, NULL);
    t402_set(&fx, 0x6060, 0, 3, 1);
    t402_set(&fx, 0x6083, 0, 400000, 4);
    t402_set(&fx, 0x6085, 0, 1000000, 4);
    t402_cw(&fx, 0x0006);
    t402_cw(&fx, 0x000F);
    t402_set(&fx, 0x60FF, 0, 40000, 4);
    t402_run(&fx, 300000);
    assert_between(co402_sim_velocity(&fx.sim), 39900, 40100);
    expect_sw(0x0637); /* pv, target velocity reached */
    /* consume node 0x7F's heartbeat (100 ms); it comes once, then stops */
    tb_xfer(BUS, "601 23 16 10 01 64 00 7F 00", "581 60 16 10 01 00 00 00 00");
    tb_send(BUS, "77F 05");
    t402_run(&fx, 100000 + 1023); /* (a consumer: within 1023 us, co_hb.c) */
    tb_expect(BUS, "081 30 81 11 00 00 00 00 00");
    tb_expect_none(BUS);
    assert_int_equal(co402_state(AX), CO402_OPERATION_ENABLED);
    assert_true(co402_connection_lost(AX));
    assert_int_equal(t402_sw(&fx) & 0x0880U, 0x0880U);
    /* the quick-stop ramp: 40000 inc/s at 1000000 inc/s^2, about 40 ms */
    while (co402_sim_velocity(&fx.sim) > 4) {
        t402_run(&fx, 1000);
        t += 1U;
        assert_true(t < 1000U);
    }
    assert_between(t, 35, 50);
    t402_run(&fx, 100000);
    expect_sw(0x0EB7); /* enabled, warning, target (at rest), internal limit */
    /* set-points and enable operation do not move it; 0x6007 is not used */
    t402_set(&fx, 0x60FF, 0, 20000, 4);
    sdo_cw(0x000F);
    t402_run(&fx, 200000);
    assert_between(co402_sim_velocity(&fx.sim), -4, 4);
    assert_int_equal(co402_state(AX), CO402_OPERATION_ENABLED);
    /* the master is back: the EMCY ends, the warning stays (monitoring
     * off from here) */
    tb_send(BUS, "77F 05");
    tb_expect(BUS, "081 00 00 00 00 00 00 00 00");
    tb_xfer(BUS, "601 23 16 10 01 00 00 00 00", "581 60 16 10 01 00 00 00 00");
    t402_run(&fx, 100000);
    assert_between(co402_sim_velocity(&fx.sim), -4, 4);
    expect_sw(0x0EB7);
    /* fault reset: the warning ends, pv runs to the new set-point */
    sdo_cw(0x008F);
    assert_false(co402_connection_lost(AX));
    t402_run(&fx, 300000);
    assert_between(co402_sim_velocity(&fx.sim), 19900, 20100);
    sdo_cw(0x000F);
    expect_sw(0x0637);
    /* a loss outside Operation enabled: warning only; enabling later holds
     * the axis at rest until the fault reset */
    sdo_cw(0x0006);
    tb_xfer(BUS, "601 23 16 10 01 64 00 7F 00", "581 60 16 10 01 00 00 00 00");
    tb_send(BUS, "77F 05");
    tb_flush(BUS);
    t402_run(&fx, 101000);
    tb_expect(BUS, "081 30 81 11 00 00 00 00 00");
    expect_sw(0x0AB1); /* ready to switch on, warning, internal limit */
    sdo_cw(0x0007);
    sdo_cw(0x000F);
    t402_run(&fx, 200000);
    assert_between(co402_sim_velocity(&fx.sim), -4, 4);
    sdo_cw(0x008F);
    t402_run(&fx, 300000);
    assert_between(co402_sim_velocity(&fx.sim), 19900, 20100);
}

static void reset_node_starts_the_axis_over(void **state)
{
    (void)state;
    t402_enable(&fx);
    t402_set(&fx, 0x6060, 0, 3, 1);
    tb_flush(BUS);
    tb_send(BUS, "000 81 01");
    tb_expect(BUS, "701 00");
    assert_int_equal(co402_state(AX), CO402_SWITCH_ON_DISABLED);
    expect_sw(0x0250);
    tb_xfer(BUS, "601 40 61 60 00 00 00 00 00", "581 4F 61 60 00 01 00 00 00");
    tb_xfer(BUS, "601 40 40 60 00 00 00 00 00", "581 4B 40 60 00 00 00 00 00");
    /* reset communication leaves the axis alone */
    t402_enable(&fx);
    tb_send(BUS, "000 82 01");
    tb_expect(BUS, "701 00");
    assert_int_equal(co402_state(AX), CO402_OPERATION_ENABLED);
}

static void modes_are_checked(void **state)
{
    (void)state;
    tb_xfer(BUS, "601 2F 60 60 00 05 00 00 00", "581 80 60 60 00 30 00 09 06"); /* reserved */
    tb_xfer(BUS, "601 2F 60 60 00 0B 00 00 00", "581 80 60 60 00 30 00 09 06");
    tb_xfer(BUS, "601 2F 60 60 00 FF 00 00 00", "581 80 60 60 00 30 00 09 06");
    tb_xfer(BUS, "601 2F 60 60 00 08 00 00 00", "581 60 60 60 00 00 00 00 00");
    tb_xfer(BUS, "601 40 61 60 00 00 00 00 00", "581 4F 61 60 00 08 00 00 00");
    tb_xfer(BUS, "601 2F 98 60 00 0F 00 00 00", "581 80 98 60 00 30 00 09 06"); /* method 15 */
    tb_xfer(BUS, "601 2F 98 60 00 24 00 00 00", "581 80 98 60 00 30 00 09 06"); /* 36 */
    tb_xfer(BUS, "601 2F 98 60 00 25 00 00 00", "581 60 98 60 00 00 00 00 00"); /* 37 */
}

/* ---------------------------------------------------- device options */

static void option_nmt_operational(void **state)
{
    (void)state;
    t402_start(&fx, 1, CO402_OPT_NMT_OPERATIONAL, NULL);
    sdo_cw(0x0006); /* Pre-operational: written, not acted on */
    expect_sw(0x0250);
    tb_send(BUS, "000 01 01");
    tb_expect(BUS, "181 50 02"); /* event-driven TPDOs on entering Operational */
    tb_expect(BUS, "281 50 02 01");
    sdo_cw(0x0006);
    expect_sw(0x0231);
}

static void option_status_bits(void **state)
{
    (void)state;
    t402_start(&fx, 1, CO402_OPT_NO_VOLTAGE_BIT | CO402_OPT_NO_REMOTE_BIT, NULL);
    expect_sw(0x0040);
    sdo_cw(0x0006);
    expect_sw(0x0021);
    sdo_cw(0x0007);
    expect_sw(0x0023);
    sdo_cw(0x000F);
    expect_sw(0x0027);

    t402_start(&fx, 1, CO402_OPT_VOLTAGE_WHEN_ON, NULL);
    expect_sw(0x0240);
    sdo_cw(0x0006);
    expect_sw(0x0221);
    sdo_cw(0x0007);
    expect_sw(0x0233);
    sdo_cw(0x000F);
    expect_sw(0x0237);
}

static void option_remote_is_enable(void **state)
{
    (void)state;
    t402_start(&fx, 1, CO402_OPT_REMOTE_IS_ENABLE | CO402_OPT_NO_VOLTAGE_BIT, NULL);
    co402_sim_set_level(&fx.sim, CO402_IN_ENABLE, false);
    t402_run(&fx, 1000);
    expect_sw(0x0040);
    sdo_cw(0x0006); /* not without remote */
    expect_sw(0x0040);
    co402_sim_set_level(&fx.sim, CO402_IN_ENABLE, true);
    t402_run(&fx, 1000);
    expect_sw(0x0240);
    sdo_cw(0x0006);
    sdo_cw(0x000F);
    expect_sw(0x0227);
    /* losing the enable input ends in Switch on disabled, no fault */
    tb_flush(BUS);
    co402_sim_set_level(&fx.sim, CO402_IN_ENABLE, false);
    t402_run(&fx, 1000);
    expect_sw(0x0040);
    tb_expect_none(BUS);
}

static void option_bit7_dont_care(void **state)
{
    (void)state;
    t402_start(&fx, 1, CO402_OPT_BIT7_DONT_CARE, NULL);
    sdo_cw(0x0086);
    expect_sw(0x0231);
    sdo_cw(0x008F);
    expect_sw(0x0237);
}

static void option_setpoint_bit15(void **state)
{
    (void)state;
    t402_start(&fx, 1, CO402_OPT_SW15_MIRRORS_12 | CO402_OPT_NO_VOLTAGE_BIT, NULL);
    t402_enable(&fx);
    t402_run(&fx, 20000);
    expect_sw(0x0627);
    t402_set(&fx, 0x607A, 0, 100000, 4);
    sdo_cw(0x005F); /* new set-point, relative (SSD 630 example) */
    expect_sw(0x9227);
    sdo_cw(0x000F);
    expect_sw(0x0227);
}

static void option_mode_change_at_rest(void **state)
{
    (void)state;
    t402_start(&fx, 1, CO402_OPT_MODE_AT_REST, NULL);
    t402_set(&fx, 0x6060, 0, 3, 1);
    t402_enable(&fx);
    t402_set(&fx, 0x60FF, 0, 5000, 4);
    t402_run(&fx, 200000);
    tb_xfer(BUS, "601 2F 60 60 00 01 00 00 00", "581 80 60 60 00 22 00 00 08");
    t402_set(&fx, 0x60FF, 0, 0, 4);
    tb_xfer(BUS, "601 2F 60 60 00 01 00 00 00", "581 80 60 60 00 22 00 00 08"); /* still moving */
    t402_run(&fx, 200000);
    tb_xfer(BUS, "601 2F 60 60 00 01 00 00 00", "581 60 60 60 00 00 00 00 00");
}

static void option_fault_holds_zero(void **state)
{
    (void)state;
    t402_start(&fx, 1, CO402_OPT_FAULT_HOLDS_ZERO, NULL);
    t402_set(&fx, 0x6060, 0, 3, 1);
    t402_enable(&fx);
    t402_set(&fx, 0x60FF, 0, 20000, 4);
    t402_run(&fx, 300000);
    co402_fault_event(AX, 0x2310);
    t402_run_until(&fx, 0x004F, 0x0008, 100000);
    /* in Fault the power stage holds the axis (no coasting) */
    assert_int_equal(fx.sim.d.kind, CO402_DEMAND_POSITION);
    t402_run(&fx, 100000);
    assert_int_equal(co402_sim_velocity(&fx.sim), 0);
    tb_expect(BUS, "081 10 23 03 00 00 00 00 00");
    sdo_cw(0x0080);
    expect_sw(0x0250);
    t402_run(&fx, 1000);
    assert_int_equal(fx.sim.d.kind, CO402_DEMAND_OFF);
}

static void option_quick_stop_clears_targets(void **state)
{
    (void)state;
    t402_start(&fx, 1, CO402_OPT_QS_CLEARS_TARGET, NULL);
    t402_set(&fx, 0x6060, 0, 3, 1);
    t402_enable(&fx);
    t402_set(&fx, 0x60FF, 0, 20000, 4);
    t402_set(&fx, 0x607A, 0, 1234, 4);
    t402_run(&fx, 100000);
    sdo_cw(0x0002);
    assert_int_equal(t402_get(&fx, 0x60FF, 0), 0);
    assert_int_equal(t402_get(&fx, 0x607A, 0), 0);
    /* halt keeps them */
    t402_start(&fx, 1, CO402_OPT_QS_CLEARS_TARGET, NULL);
    t402_set(&fx, 0x6060, 0, 3, 1);
    t402_enable(&fx);
    t402_set(&fx, 0x60FF, 0, 20000, 4);
    sdo_cw(0x010F);
    assert_int_equal(t402_get(&fx, 0x60FF, 0), 20000);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(boot_is_switch_on_disabled, setup),
        cmocka_unit_test_setup(enable_step_by_step, setup),
        cmocka_unit_test_setup(idle_axis_wakes_rarely, setup),
        cmocka_unit_test_setup(switch_on_and_enable_in_one_write, setup),
        cmocka_unit_test_setup(one_transition_per_write, setup),
        cmocka_unit_test_setup(commands_out_of_sequence_are_ignored, setup),
        cmocka_unit_test_setup(transition_5_disable_operation, setup),
        cmocka_unit_test_setup(transition_6_7_10, setup),
        cmocka_unit_test_setup(transition_8_shutdown, setup),
        cmocka_unit_test_setup(transition_9_disable_voltage, setup),
        cmocka_unit_test_setup(transition_11_12_quick_stop_to_disabled, setup),
        cmocka_unit_test_setup(transition_16_back_from_quick_stop, setup),
        cmocka_unit_test_setup(no_transition_16_with_option_below_5, setup),
        cmocka_unit_test_setup(transition_13_14_15_fault, setup),
        cmocka_unit_test_setup(fault_when_not_energised_is_at_once, setup),
        cmocka_unit_test_setup(fault_in_every_state, setup),
        cmocka_unit_test_setup(quick_stop_option_codes, setup),
        cmocka_unit_test_setup(fault_reaction_option_codes, setup),
        cmocka_unit_test_setup(fault_reaction_active_while_braking, setup),
        cmocka_unit_test_setup(disable_operation_ramps_down_first, setup),
        cmocka_unit_test_setup(hardware_enable_gates_switch_on, setup),
        cmocka_unit_test_setup(dc_link_voltage_is_bit_4, setup),
        cmocka_unit_test_setup(plant_fault, setup),
        cmocka_unit_test_setup(abort_connection_on_nmt_stop, setup),
        cmocka_unit_test_setup(abort_connection_on_heartbeat_loss, setup),
        cmocka_unit_test_setup(loss_warning_stops_until_fault_reset, setup),
        cmocka_unit_test_setup(reset_node_starts_the_axis_over, setup),
        cmocka_unit_test_setup(modes_are_checked, setup),
        cmocka_unit_test_setup(option_nmt_operational, setup),
        cmocka_unit_test_setup(option_status_bits, setup),
        cmocka_unit_test_setup(option_remote_is_enable, setup),
        cmocka_unit_test_setup(option_bit7_dont_care, setup),
        cmocka_unit_test_setup(option_setpoint_bit15, setup),
        cmocka_unit_test_setup(option_mode_change_at_rest, setup),
        cmocka_unit_test_setup(option_fault_holds_zero, setup),
        cmocka_unit_test_setup(option_quick_stop_clears_targets, setup),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
