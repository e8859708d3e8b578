/*
 * AnaGate Motion motor modules (devices/anagate-motion*.toml as CiA 402
 * devices, co402_devices.h): the manual's Lua example ("Beispiel CANopen - Lua",
 * digest /work/shared/spec/seed-003-anagate-motion.md section 6) replayed
 * frame by frame on node 0x02, the derived vectors of section 6.4, the
 * multi-axis layout at +0x800 (section 1.2), the velocity ramp (3.6) and
 * the PDOs of section 3.8, against the real device descriptions, the CiA
 * 402 profile and simulated motors.
 *
 * Statusword choices where the manual is open (section 3.5): bit 4 while
 * the power stage is on (Switched on, Operation enabled, Quick stop
 * active), bit 7 no warning, bit 9 unused, bit 10 once the ramp is at the
 * target. Tests of a state compare (sw & 0x6F) as the digest says, and the
 * whole statusword where our choice is asserted.
 *
 * No real drive values here: the speed is the simulated motor's, full
 * speed (1000 per mille) = 3000 rpm = 204800 increments/s.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "anagate_motion.h"
#include "anagate_motion_400vac.h"
#include "anagate_motion_bl.h"
#include "anagate_motion_desc.h"
#include "co_devices.h"
#include "seedrun.h"

static seedrun_t fx;
static union {
    anagate_motion_node_t bt;
    anagate_motion_bl_node_t bl;
    anagate_motion_400vac_node_t vac;
} node;
#define S (&fx)

#define PERMILLE(p) ((int32_t)(((int64_t)(p) * ANAGATE_FULL_SPEED) / 1000))

static int setup_bt4(void **state)
{
    (void)state;
    co_node_config_t cfg;

    anagate_motion_config(&node.bt, &cfg);
    sr_start(S, &co_device_anagate_motion, &cfg, &node.bt.node, NULL, 2);
    sr_run(S, 10);
    tb_expect_none(&S->bus);
    return 0;
}

static int setup_bt2(void **state)
{
    (void)state;
    co_node_config_t cfg;

    anagate_motion_config(&node.bt, &cfg);
    sr_start(S, &co_device_anagate_motion_bt2, &cfg, &node.bt.node, NULL, 2);
    sr_run(S, 10);
    return 0;
}

static int setup_bl(void **state)
{
    (void)state;
    co_node_config_t cfg;

    anagate_motion_bl_config(&node.bl, &cfg);
    sr_start(S, &co_device_anagate_motion_bl, &cfg, &node.bl.node, NULL, 2);
    sr_run(S, 10);
    return 0;
}

static int setup_400vac(void **state)
{
    (void)state;
    co_node_config_t cfg;

    anagate_motion_400vac_config(&node.vac, &cfg);
    sr_start(S, &co_device_anagate_motion_400vac, &cfg, &node.vac.node, NULL, 2);
    sr_run(S, 10);
    return 0;
}

static uint16_t sw_of(uint8_t motor)
{
    return (uint16_t)sr_get(S, (uint16_t)(0x6041U + (0x800U * (motor - 1U))), 0);
}

/* Speed of motor @p motor in increments/s (the simulated motor). */
static int32_t speed_of(uint8_t motor)
{
    return co402_sim_velocity(&S->sim[motor - 1U]);
}

/* NMT start; the core sends the event-driven T-PDO4 (inputs) once on
 * entering Operational (CiA 301; the manual is silent, digest 8.3 item 8). */
static void start_node(void)
{
    tb_send(&S->bus, "000 01 02");
    sr_poll(S);
    sr_expect(S, "482 00 00 00 00 00 00 00 00");
    tb_expect_none(&S->bus);
}

/* ------------------------------------------------------ Lua example */

/* Section 6.2, steps 3-15: motor 1 of node 0x02 to Operation enabled by
 * 2-byte R-PDO1 frames, 50 % without a ramp, 5 s, a 1000 ms deceleration
 * ramp, 0 %: standstill within 500 ms. */
static void lua_example(void **state)
{
    (void)state;
    /* 3: LS_CANOpenSendNMT(0x02, OPERATIONAL) */
    start_node();
    sr_run(S, 20); /* 4: LS_Sleep(20) */
    /* 5: R-PDO1 DLC 2 (function code 4): controlword motor 1 = Shutdown;
     * accepted although shorter than the mapping, no EMCY */
    tb_send(&S->bus, "202 06 00");
    sr_poll(S);
    tb_expect_none(&S->bus);
    assert_int_equal(sw_of(1) & 0x6F, 0x21);
    for (uint8_t m = 2; m <= 4; m++) {
        /* motors 2-4 untouched (a motor the module lacks reads 0) */
        assert_int_equal(sw_of(m), (co402_device_axis(&S->run, (uint8_t)(m - 1U)) != NULL) ? 0x0040 : 0x0000);
    }
    sr_run(S, 20);
    /* 7: Switch on */
    tb_send(&S->bus, "202 07 00");
    sr_poll(S);
    assert_int_equal(sw_of(1) & 0x6F, 0x23);
    assert_int_equal(sw_of(1), 0x0033); /* bit 4: the power stage is on */
    sr_run(S, 20);
    /* 9: Enable operation; at rest the ramp is at its target 0: bit 10 */
    tb_send(&S->bus, "202 0F 00");
    sr_poll(S);
    assert_int_equal(sw_of(1) & 0x6F, 0x27);
    sr_run(S, 20);
    tb_expect_none(&S->bus);
    assert_int_equal(sw_of(1), 0x0437);
    /* 11: 0x6080 = 500 per mille; 0x6083 = 0: a step to 500 */
    sr_sdo(S, "23 80 60 00 F4 01 00 00", "60 80 60 00 00 00 00 00");
    sr_run(S, 1);
    assert_int_equal(sw_of(1), 0x0437); /* the ramp is there at once */
    sr_run(S, 100);
    sr_between(speed_of(1), PERMILLE(500) - 200, PERMILLE(500) + 200);
    /* 12: LS_Sleep(5000): the motor runs at 500 per mille */
    sr_run(S, 4900);
    sr_between(speed_of(1), PERMILLE(500) - 50, PERMILLE(500) + 50);
    tb_expect_none(&S->bus);
    /* 13: 0x6084 = 1000 ms for a full-scale ramp */
    sr_sdo(S, "23 84 60 00 E8 03 00 00", "60 84 60 00 00 00 00 00");
    /* 14: 0x6080 = 0: down the deceleration ramp, 500 -> 0 in 500 ms */
    sr_sdo(S, "23 80 60 00 00 00 00 00", "60 80 60 00 00 00 00 00");
    sr_run(S, 1);
    assert_int_equal(sw_of(1) & 0x0400, 0); /* ramping: target not reached */
    sr_run(S, 249);
    sr_between(speed_of(1), PERMILLE(250) - 2000, PERMILLE(250) + 2000);
    assert_int_equal(sw_of(1) & 0x0400, 0);
    sr_run(S, 249);
    assert_int_equal(sw_of(1) & 0x0400, 0);
    sr_run(S, 2);
    assert_int_equal(sw_of(1), 0x0437); /* at 500 ms: at 0 */
    sr_run(S, 100);
    sr_between(speed_of(1), -100, 100); /* the motor has followed */
    /* 15: the node stays Operational, motor 1 in Operation enabled */
    assert_int_equal(co_node_nmt_state(S->node), CO_NMT_OPERATIONAL);
    assert_int_equal(co402_state(co402_device_axis(&S->run, 0U)), CO402_OPERATION_ENABLED);
    tb_expect_none(&S->bus);
}

/* The same script against the BL module (2 motors). */
static void lua_example_bl(void **state)
{
    lua_example(state);
}

/* Section 6.4: SYNC sends T-PDO1 (statuswords) then T-PDO2 (error codes). */
static void sync_pdos(void **state)
{
    (void)state;
    start_node();
    tb_send(&S->bus, "202 06 00");
    tb_send(&S->bus, "202 07 00");
    tb_send(&S->bus, "202 0F 00");
    sr_run(S, 5);
    tb_send(&S->bus, "080");
    sr_poll(S);
    /* motor 1 Operation enabled, speed reached, bit 4; motors 2-4 Switch on
     * disabled */
    sr_expect(S, "182 37 04 40 00 40 00 40 00");
    sr_expect(S, "282 00 00 00 00 00 00 00 00");
    tb_expect_none(&S->bus);
}

/* Section 6.4: SYNC on a 2-motor module: motors 3 and 4 read 0. */
static void sync_pdos_two_motors(void **state)
{
    (void)state;
    start_node();
    tb_send(&S->bus, "202 06 00 06 00 06 00 06 00");
    sr_poll(S);
    tb_send(&S->bus, "080");
    sr_poll(S);
    sr_expect(S, "182 21 00 21 00 00 00 00 00");
    sr_expect(S, "282 00 00 00 00 00 00 00 00");
    /* the controlwords of the missing motors are stored and do nothing */
    sr_sdo(S, "40 40 70 00 00 00 00 00", "4B 40 70 00 06 00 00 00");
    sr_sdo(S, "40 41 70 00 00 00 00 00", "4B 41 70 00 00 00 00 00");
}

/* Section 6.4 identity and access vectors; section 2.7 (0x1018 with the
 * vendor-ID in sub-index 0, device type 0). */
static void identity(void **state)
{
    (void)state;
    sr_sdo(S, "40 18 10 00 00 00 00 00", "43 18 10 00 EB 02 00 00");
    sr_sdo(S, "40 18 10 01 00 00 00 00", "43 18 10 01 01 00 00 00"); /* BT */
    sr_sdo(S, "40 18 10 02 00 00 00 00", "43 18 10 02 00 00 00 00");
    sr_sdo(S, "40 18 10 03 00 00 00 00", "80 18 10 03 11 00 09 06");
    sr_sdo(S, "40 00 10 00 00 00 00 00", "43 00 10 00 00 00 00 00");
    sr_sdo(S, "2B 41 60 00 00 00 00 00", "80 41 60 00 02 00 01 06");
    /* 0x6080 above 1000 per mille: too high (recommended 0x06090031) */
    sr_sdo(S, "23 80 60 00 E9 03 00 00", "80 80 60 00 31 00 09 06");
    /* the statusword after initialisation: Switch on disabled */
    sr_sdo(S, "40 41 60 00 00 00 00 00", "4B 41 60 00 40 00 00 00");
    /* 0x1008 is a VISIBLE_STRING read with a segmented upload */
    sr_sdo(S, "40 08 10 00 00 00 00 00", "41 08 10 00 1D 00 00 00");
}

static void identity_bl(void **state)
{
    (void)state;
    sr_sdo(S, "40 18 10 00 00 00 00 00", "43 18 10 00 EB 02 00 00");
    sr_sdo(S, "40 18 10 01 00 00 00 00", "43 18 10 01 02 00 00 00");
}

static void identity_400vac(void **state)
{
    (void)state;
    sr_sdo(S, "40 18 10 01 00 00 00 00", "43 18 10 01 03 00 00 00");
}

/* Section 6.4: a fault of motor 1 (raised by the simulation: over-current)
 * is reset by the rising edge of bit 7 in R-PDO1; the EMCY carries the
 * axis' 0x603F (digest 2.5 recommendation), T-PDO2 shows it at SYNC. */
static void fault_reset_by_rpdo(void **state)
{
    (void)state;
    start_node();
    tb_send(&S->bus, "202 06 00");
    tb_send(&S->bus, "202 07 00");
    tb_send(&S->bus, "202 0F 00");
    sr_run(S, 5);
    co402_fault_raise(co402_device_axis(&S->run, 0U), 0x2310);
    sr_expect(S, "082 10 23 03 00 00 00 00 00");
    sr_run(S, 200);
    assert_int_equal(sw_of(1) & 0x4F, 0x08);
    tb_send(&S->bus, "080");
    sr_poll(S);
    sr_expect(S, "182 08 00 40 00 40 00 40 00"); /* Fault: the power stage is off */
    sr_expect(S, "282 10 23 00 00 00 00 00 00");
    /* a rising edge while the over-current lasts: the fault stays */
    tb_send(&S->bus, "202 80 00");
    sr_run(S, 1);
    assert_int_equal(sw_of(1) & 0x4F, 0x08);
    co402_fault_clear(co402_device_axis(&S->run, 0U), 0x2310);
    /* the last controlword had bit 7 = 1: no edge, the axis stays in Fault */
    tb_send(&S->bus, "202 80 00");
    sr_run(S, 1);
    assert_int_equal(sw_of(1) & 0x4F, 0x08);
    /* bit 7 = 0 first, then the rising edge */
    tb_send(&S->bus, "202 00 00");
    tb_send(&S->bus, "202 80 00");
    sr_poll(S);
    assert_int_equal(sw_of(1) & 0x4F, 0x40);
    sr_run(S, 1);
    sr_expect(S, "082 00 00 00 00 00 00 00 00"); /* after the reset: no error left */
    tb_send(&S->bus, "080");
    sr_poll(S);
    sr_expect(S, "182 40 00 40 00 40 00 40 00");
    sr_expect(S, "282 00 00 00 00 00 00 00 00");
}

/* ------------------------------------------------ multi-axis (1.2) */

/* Section 1.2: motor n's objects at +0x800 * (n - 1): motor 2's speed at
 * 0x6880, motor 3's acceleration at 0x7083 (the manual's examples); an
 * 8-byte R-PDO1 drives all four, each with its own state machine. */
static void multi_axis(void **state)
{
    (void)state;
    start_node();
    sr_sdo(S, "23 80 68 00 E8 03 00 00", "60 80 68 00 00 00 00 00"); /* motor 2: 100 % */
    sr_sdo(S, "23 83 70 00 F4 01 00 00", "60 83 70 00 00 00 00 00"); /* motor 3: 500 ms */
    sr_sdo(S, "23 80 70 00 C8 00 00 00", "60 80 70 00 00 00 00 00"); /* motor 3: 20 % */
    sr_sdo(S, "2F 7E 78 00 40 00 00 00", "60 7E 78 00 00 00 00 00"); /* motor 4 reversed */
    sr_sdo(S, "23 80 78 00 64 00 00 00", "60 80 78 00 00 00 00 00"); /* motor 4: 10 % */
    /* motors 1-4 to Ready to switch on, then only 2-4 enabled (motor 1 gets
     * Disable voltage: 0x0000) */
    tb_send(&S->bus, "202 06 00 06 00 06 00 06 00");
    tb_send(&S->bus, "202 07 00 07 00 07 00 07 00");
    tb_send(&S->bus, "202 00 00 0F 00 0F 00 0F 00");
    sr_poll(S);
    assert_int_equal(sw_of(1), 0x0040);
    assert_int_equal(sw_of(2) & 0x6F, 0x27);
    assert_int_equal(sw_of(3) & 0x6F, 0x27);
    assert_int_equal(sw_of(4) & 0x6F, 0x27);
    sr_run(S, 1);
    /* motor 3 ramps: 200 per mille with 500 ms per full scale = 100 ms */
    assert_int_equal(sw_of(3), 0x0037);
    sr_run(S, 50);
    sr_between(speed_of(3), PERMILLE(100) - 2000, PERMILLE(100) + 2000);
    sr_run(S, 60);
    assert_int_equal(sw_of(3), 0x0437);
    sr_run(S, 400);
    sr_between(speed_of(1), -10, 10);
    sr_between(speed_of(2), PERMILLE(1000) - 500, PERMILLE(1000) + 500);
    sr_between(speed_of(3), PERMILLE(200) - 200, PERMILLE(200) + 200);
    sr_between(speed_of(4), -PERMILLE(100) - 200, -PERMILLE(100) + 200); /* bit 6 */
    /* SYNC: the four statuswords and error codes */
    tb_send(&S->bus, "080");
    sr_poll(S);
    sr_expect(S, "182 40 00 37 04 37 04 37 04");
    sr_expect(S, "282 00 00 00 00 00 00 00 00");
    /* a 4-byte R-PDO1 writes motors 1 and 2 only: motor 2 quick stop ends in
     * Switch on disabled (no transition back, digest 3.3) */
    tb_send(&S->bus, "202 00 00 0B 00");
    sr_poll(S);
    assert_int_equal(sw_of(2) & 0x6F, 0x07);
    sr_run(S, 1000);
    assert_int_equal(sw_of(2), 0x0040);
    assert_int_equal(sw_of(3), 0x0437);
    /* halt (bit 8) on motor 3: down with 0x7084 (0: at once), state kept */
    tb_send(&S->bus, "202 00 00 00 00 0F 01");
    sr_run(S, 100);
    assert_int_equal(sw_of(3) & 0x6F, 0x27);
    sr_between(speed_of(3), -200, 200);
    tb_send(&S->bus, "202 00 00 00 00 0F 00");
    sr_run(S, 300);
    sr_between(speed_of(3), PERMILLE(200) - 200, PERMILLE(200) + 200);
    tb_flush(&S->bus);
}

/* ---------------------------------------------------- PDOs (3.8/3.9) */

/* T-PDO4 on every change of the module's inputs (0x2000, ours). */
static void inputs_tpdo4(void **state)
{
    static const uint8_t in1[8] = {0x80, 0x05, 0x00, 0x03, 0x02, 0x00, 0x00, 0x10};
    (void)state;
    start_node();
    anagate_motion_set_inputs(S->node, in1); /* S1 on, E1 value 5, counts */
    sr_poll(S);
    sr_expect(S, "482 80 05 00 03 02 00 00 10");
    sr_run(S, 100);
    tb_expect_none(&S->bus);
    sr_sdo(S, "40 00 20 01 00 00 00 00", "4F 00 20 01 80 00 00 00");
}

/* 400 Vac: T-PDO3 with motors 1 and 2's phase currents every 100 ms. */
static void currents_400vac(void **state)
{
    (void)state;
    tb_send(&S->bus, "000 01 02");
    sr_poll(S);
    sr_expect(S, "382 00 00 00 00");
    sr_expect(S, "482 00 00 00 00 00 00 00 00");
    sr_run(S, 99);
    tb_expect_none(&S->bus);
    sr_run(S, 1);
    sr_expect(S, "382 00 00 00 00");
    /* motor 1 on at 100 % (on/off module): 1.50 A in phases U and W */
    sr_sdo(S, "23 80 60 00 E8 03 00 00", "60 80 60 00 00 00 00 00");
    tb_send(&S->bus, "202 06 00");
    tb_send(&S->bus, "202 07 00");
    tb_send(&S->bus, "202 0F 00");
    sr_run(S, 99);
    tb_expect_none(&S->bus); /* the change waits for the 100 ms period */
    sr_run(S, 1);
    sr_expect(S, "382 96 96 00 00");
    sr_run(S, 100);
    sr_expect(S, "382 96 96 00 00");
    /* off: Disable voltage */
    tb_send(&S->bus, "202 00 00");
    sr_run(S, 100);
    sr_expect(S, "382 00 00 00 00");
}

/* T-PDO3 is not valid on the BT module (no current measurement). */
static void no_tpdo3_on_bt(void **state)
{
    (void)state;
    start_node();
    sr_run(S, 300);
    tb_expect_none(&S->bus);
    sr_sdo(S, "40 02 18 01 00 00 00 00", "43 02 18 01 82 03 00 80");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(lua_example, setup_bt4),
        cmocka_unit_test_setup(lua_example_bl, setup_bl),
        cmocka_unit_test_setup(sync_pdos, setup_bt4),
        cmocka_unit_test_setup(sync_pdos_two_motors, setup_bt2),
        cmocka_unit_test_setup(identity, setup_bt4),
        cmocka_unit_test_setup(identity_bl, setup_bl),
        cmocka_unit_test_setup(identity_400vac, setup_400vac),
        cmocka_unit_test_setup(fault_reset_by_rpdo, setup_bt4),
        cmocka_unit_test_setup(multi_axis, setup_bt4),
        cmocka_unit_test_setup(inputs_tpdo4, setup_bt4),
        cmocka_unit_test_setup(currents_400vac, setup_400vac),
        cmocka_unit_test_setup(no_tpdo3_on_bt, setup_bt4),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
