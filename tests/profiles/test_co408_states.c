/*
 * CiA 408 device control: every transition TR_0 .. TR_12 with its control
 * word and the exact status word, the chained evaluation, the fault reset
 * on the rising edge, the refusals of 0x6042 / 0x6043 / 0x604F and the
 * source arbitration, and the reactions to NMT commands.
 *
 * Node 1 of the cia408 device on the simulated valve, in Pre-operational
 * unless a test starts it (no PDOs then: every frame is an SDO answer, an
 * EMCY or an NMT error-control frame).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "t408.h"

static t408_t fx;
#define BUS (&fx.bus)
#define V (&fx.v)

static int setup(void **state)
{
    t408_start(&fx, 1);
    *state = &fx;
    return 0;
}

/* Inject @p faults into the valve and let one tick see them. */
static void inject(uint32_t faults)
{
    co408_sim_inject(&fx.sim, faults);
    t408_run(&fx, 1000U);
}

/* ----------------------------------------------------------- TR_0 .. TR_7 */

static void boot_is_init(void **state)
{
    (void)state;
    /* TR_0 and TR_1 ran at attach */
    assert_int_equal(co408_state(V), CO408_INIT);
    t408_expect_sw(&fx, 0x0008);
    tb_xfer(BUS, "601 40 41 60 00 00 00 00 00", "581 4B 41 60 00 08 00 00 00");
    tb_xfer(BUS, "601 40 5F 60 00 00 00 00 00", "581 43 5F 60 00 00 00 00 13");
    tb_xfer(BUS, "601 40 42 60 00 00 00 00 00", "581 4F 42 60 00 01 00 00 00");
    tb_xfer(BUS, "601 40 43 60 00 00 00 00 00", "581 4F 43 60 00 01 00 00 00");
    /* the status word is read-only */
    tb_xfer(BUS, "601 2B 41 60 00 00 00 00 00", "581 80 41 60 00 02 00 01 06");
}

static void single_transitions(void **state)
{
    (void)state;
    tb_xfer(BUS, "601 2B 40 60 00 01 00 00 00", "581 60 40 60 00 00 00 00 00"); /* TR_2 */
    tb_xfer(BUS, "601 40 41 60 00 00 00 00 00", "581 4B 41 60 00 09 00 00 00");
    assert_int_equal(co408_state(V), CO408_DISABLED);
    t408_cw(&fx, 0x0003); /* TR_3 */
    t408_expect_sw(&fx, 0x000B);
    t408_cw(&fx, 0x0007); /* TR_4 */
    t408_expect_sw(&fx, 0x000F);
    assert_int_equal(co408_state(V), CO408_ACTIVE);
    t408_cw(&fx, 0x0003); /* TR_5 */
    t408_expect_sw(&fx, 0x000B);
    t408_cw(&fx, 0x0001); /* TR_6 */
    t408_expect_sw(&fx, 0x0009);
    t408_cw(&fx, 0x0000); /* TR_7 */
    t408_expect_sw(&fx, 0x0008);
    assert_int_equal(co408_state(V), CO408_INIT);
}

static void chained_transitions(void **state)
{
    (void)state;
    t408_cw(&fx, 0x0007); /* TR_2, TR_3, TR_4 in one write */
    t408_expect_sw(&fx, 0x000F);
    t408_cw(&fx, 0x0000); /* TR_5, TR_6, TR_7 */
    t408_expect_sw(&fx, 0x0008);
    t408_cw(&fx, 0x0003); /* TR_2, TR_3 */
    t408_expect_sw(&fx, 0x000B);
    t408_cw(&fx, 0x0001); /* TR_6 only: D still set */
    t408_expect_sw(&fx, 0x0009);
}

/* Patterns that match no transition leave the state alone. */
static void patterns_without_transition(void **state)
{
    (void)state;
    t408_cw(&fx, 0x0006); /* INIT: D = 0 */
    t408_expect_sw(&fx, 0x0008);
    t408_cw(&fx, 0x0001);
    t408_cw(&fx, 0x0002); /* DISABLED: H without D, not x000 */
    t408_expect_sw(&fx, 0x0009);
    t408_cw(&fx, 0x0003);
    t408_cw(&fx, 0x0005); /* HOLD: M without H: neither TR_4 nor TR_6 */
    t408_expect_sw(&fx, 0x000B);
    t408_cw(&fx, 0x0007);
    t408_cw(&fx, 0x0006); /* ACTIVE: M still set */
    t408_expect_sw(&fx, 0x000F);
    t408_cw(&fx, 0x8007); /* bit 15 (manufacturer) and reserved bits are ignored */
    t408_expect_sw(&fx, 0x000F);
}

/* ------------------------------------------------------- TR_8 .. TR_12 */

/* TR_8 from DEVICE_MODE_ACTIVE with H set: FAULT_REACTION, then TR_9 to
 * FAULT_HOLD; TR_11 back to HOLD on the rising edge of R (D28). */
static void fault_hold_and_tr11(void **state)
{
    (void)state;
    t408_cw(&fx, 0x0007);
    inject(CO408_SIM_SOL_A_OPEN);
    tb_expect(BUS, "081 11 23 03 00 00 00 00 00"); /* current + generic (D25) */
    tb_expect_none(BUS);
    assert_int_equal(co408_state(V), CO408_FAULT_REACTION);
    t408_expect_sw(&fx, 0x0007);
    t408_run(&fx, 1000U); /* TR_9 */
    t408_expect_sw(&fx, 0x0003);
    tb_xfer(BUS, "601 40 03 10 01 00 00 00 00", "581 43 03 10 01 11 23 00 00");
    tb_xfer(BUS, "601 40 01 10 00 00 00 00 00", "581 4F 01 10 00 03 00 00 00");
    /* no other command acts in a fault state */
    t408_cw(&fx, 0x0007);
    t408_expect_sw(&fx, 0x0003);
    co408_sim_inject(&fx.sim, 0U);
    t408_run(&fx, 1000U);
    tb_expect_none(BUS);
    t408_cw(&fx, 0x0003);
    t408_cw(&fx, 0x000B); /* TR_11 */
    t408_expect_sw(&fx, 0x000B);
    assert_int_equal(co408_state(V), CO408_HOLD);
    t408_run(&fx, 1000U); /* the error ends after the answer */
    tb_expect(BUS, "081 00 00 00 00 00 00 00 00");
    tb_expect_none(BUS);
    tb_xfer(BUS, "601 40 01 10 00 00 00 00 00", "581 4F 01 10 00 00 00 00 00");
}

/* TR_8 from DISABLED, TR_12 to FAULT; a reset while the cause is present
 * is ignored; TR_10 to DISABLED, then enable again (D27). */
static void fault_and_tr10(void **state)
{
    (void)state;
    t408_cw(&fx, 0x0001);
    inject(CO408_SIM_UNDERVOLT);
    tb_expect(BUS, "081 12 34 05 00 00 00 00 00");
    t408_expect_sw(&fx, 0x0007);
    t408_run(&fx, 1000U); /* TR_12 */
    t408_expect_sw(&fx, 0x0001);
    assert_int_equal(co408_state(V), CO408_FAULT);
    t408_cw(&fx, 0x0009); /* cause still present */
    t408_expect_sw(&fx, 0x0001);
    co408_sim_inject(&fx.sim, 0U);
    t408_run(&fx, 1000U);
    t408_cw(&fx, 0x0009); /* no rising edge: R was already set */
    t408_expect_sw(&fx, 0x0001);
    t408_cw(&fx, 0x0001);
    t408_cw(&fx, 0x0009); /* TR_10 */
    t408_expect_sw(&fx, 0x0009);
    t408_run(&fx, 1000U);
    tb_expect(BUS, "081 00 00 00 00 00 00 00 00");
    t408_cw(&fx, 0x0001);
    t408_cw(&fx, 0x0007);
    t408_expect_sw(&fx, 0x000F);
}

/* From FAULT_HOLD with H = 0 the reset is TR_10 (DISABLED); a reset with
 * D, H, M set chains on to DEVICE_MODE_ACTIVE. */
static void fault_hold_tr10_and_chain(void **state)
{
    (void)state;
    t408_cw(&fx, 0x0003);
    inject(CO408_SIM_SOL_B_SHORT);
    tb_expect(BUS, "081 12 23 03 00 00 00 00 00");
    t408_run(&fx, 1000U);
    t408_expect_sw(&fx, 0x0003);
    co408_sim_inject(&fx.sim, 0U);
    t408_run(&fx, 1000U);
    t408_cw(&fx, 0x0001);
    t408_cw(&fx, 0x0009);
    t408_expect_sw(&fx, 0x0009);
    t408_run(&fx, 1000U);
    tb_expect(BUS, "081 00 00 00 00 00 00 00 00");
    /* again, reset with 0x000F: TR_11, then TR_4 */
    t408_cw(&fx, 0x0007);
    inject(CO408_SIM_SOL_A_SHORT);
    tb_expect(BUS, "081 11 23 03 00 00 00 00 00");
    t408_run(&fx, 1000U);
    co408_sim_inject(&fx.sim, 0U);
    t408_run(&fx, 1000U);
    t408_cw(&fx, 0x000F);
    t408_expect_sw(&fx, 0x000F);
}

/* TR_8 from INIT: the reaction ends in FAULT (no hold was active). */
static void fault_from_init(void **state)
{
    (void)state;
    co408_fault_raise(V, 0x1000);
    tb_expect(BUS, "081 00 10 01 00 00 00 00 00");
    t408_expect_sw(&fx, 0x0007);
    t408_run(&fx, 1000U);
    t408_expect_sw(&fx, 0x0001);
    t408_cw(&fx, 0x0008); /* cause present (application fault) */
    t408_expect_sw(&fx, 0x0001);
    co408_fault_clear(V, 0x1000);
    t408_cw(&fx, 0x0001);
    t408_cw(&fx, 0x0009); /* TR_10 */
    t408_expect_sw(&fx, 0x0009);
}

/* Cable-break monitoring off (0x2505 = 0): a broken solenoid-1 cable is
 * not a fault. */
static void monitoring_off(void **state)
{
    (void)state;
    t408_sdo_write(&fx, 0x2505, 0, 0, 1, 0);
    t408_cw(&fx, 0x0007);
    inject(CO408_SIM_SOL_A_OPEN);
    tb_expect_none(BUS);
    t408_expect_sw(&fx, 0x000F);
}

/* --------------------------------------------------------- refusals */

static void mode_writes_only_in_init_or_disabled(void **state)
{
    (void)state;
    /* INIT: D18 order */
    tb_xfer(BUS, "601 2F 4F 60 00 00 00 00 00", "581 60 4F 60 00 00 00 00 00");
    tb_xfer(BUS, "601 2F 42 60 00 01 00 00 00", "581 60 42 60 00 00 00 00 00");
    tb_xfer(BUS, "601 2F 43 60 00 04 00 00 00", "581 60 43 60 00 00 00 00 00");
    t408_cw(&fx, 0x0001);
    tb_xfer(BUS, "601 2F 43 60 00 01 00 00 00", "581 60 43 60 00 00 00 00 00"); /* DISABLED */
    t408_cw(&fx, 0x0003);
    /* HOLD and DEVICE_MODE_ACTIVE: 0x08000022, the old value stays (D32) */
    tb_xfer(BUS, "601 2F 43 60 00 04 00 00 00", "581 80 43 60 00 22 00 00 08");
    tb_xfer(BUS, "601 2F 42 60 00 02 00 00 00", "581 80 42 60 00 22 00 00 08");
    tb_xfer(BUS, "601 2F 4F 60 00 01 00 00 00", "581 80 4F 60 00 22 00 00 08");
    t408_cw(&fx, 0x0007);
    tb_xfer(BUS, "601 2F 42 60 00 02 00 00 00", "581 80 42 60 00 22 00 00 08");
    tb_xfer(BUS, "601 2F 43 60 00 04 00 00 00", "581 80 43 60 00 22 00 00 08");
    tb_xfer(BUS, "601 40 43 60 00 00 00 00 00", "581 4F 43 60 00 01 00 00 00");
    tb_xfer(BUS, "601 40 42 60 00 00 00 00 00", "581 4F 42 60 00 01 00 00 00");
    /* a fault state is not INIT / DISABLED either */
    co408_fault_raise(V, 0x1000);
    tb_expect(BUS, "081 00 10 01 00 00 00 00 00");
    t408_run(&fx, 1000U);
    tb_xfer(BUS, "601 2F 43 60 00 04 00 00 00", "581 80 43 60 00 22 00 00 08");
}

static void mode_values_refused(void **state)
{
    (void)state;
    /* modes the device does not offer: 3 (has 0x6380, not offered), 9 (no
     * 0x6600), -5; device mode 0 and 3; device local 2 */
    tb_xfer(BUS, "601 2F 43 60 00 03 00 00 00", "581 80 43 60 00 30 00 09 06");
    tb_xfer(BUS, "601 2F 43 60 00 09 00 00 00", "581 80 43 60 00 30 00 09 06");
    tb_xfer(BUS, "601 2F 43 60 00 FB 00 00 00", "581 80 43 60 00 30 00 09 06");
    tb_xfer(BUS, "601 2F 42 60 00 00 00 00 00", "581 80 42 60 00 30 00 09 06");
    tb_xfer(BUS, "601 2F 42 60 00 03 00 00 00", "581 80 42 60 00 30 00 09 06");
    tb_xfer(BUS, "601 2F 4F 60 00 02 00 00 00", "581 80 4F 60 00 30 00 09 06");
    tb_xfer(BUS, "601 40 43 60 00 00 00 00 00", "581 4F 43 60 00 01 00 00 00");
    tb_xfer(BUS, "601 40 42 60 00 00 00 00 00", "581 4F 42 60 00 01 00 00 00");
    tb_xfer(BUS, "601 40 4F 60 00 00 00 00 00", "581 4F 4F 60 00 00 00 00 00");
}

/* 604Fh = 1: the control word is local, a bus write is refused with
 * 0x08000021; 6042h = 2: the set-point is local, likewise. */
static void source_arbitration(void **state)
{
    (void)state;
    tb_xfer(BUS, "601 2F 4F 60 00 01 00 00 00", "581 60 4F 60 00 00 00 00 00");
    tb_xfer(BUS, "601 2B 40 60 00 07 00 00 00", "581 80 40 60 00 21 00 00 08");
    t408_expect_sw(&fx, 0x0008);
    tb_xfer(BUS, "601 2F 4F 60 00 00 00 00 00", "581 60 4F 60 00 00 00 00 00");
    tb_xfer(BUS, "601 2F 42 60 00 02 00 00 00", "581 60 42 60 00 00 00 00 00");
    tb_xfer(BUS, "601 2B 00 63 01 00 20 00 00", "581 80 00 63 01 21 00 00 08");
    tb_xfer(BUS, "601 40 00 63 01 00 00 00 00", "581 4B 00 63 01 00 00 00 00");
    tb_xfer(BUS, "601 2F 42 60 00 01 00 00 00", "581 60 42 60 00 00 00 00 00");
    tb_xfer(BUS, "601 2B 00 63 01 00 20 00 00", "581 60 00 63 01 00 00 00 00");
}

/* Local control: the enable input acts as D, H, M; its falling edge is
 * TR_567 to INIT. */
static void local_enable_input(void **state)
{
    (void)state;
    tb_xfer(BUS, "601 2F 4F 60 00 01 00 00 00", "581 60 4F 60 00 00 00 00 00");
    co408_sim_set_input(&fx.sim, CO408_IN_ENABLE, true);
    t408_run(&fx, 1000U);
    t408_expect_sw(&fx, 0x000F);
    co408_sim_set_input(&fx.sim, CO408_IN_ENABLE, false);
    t408_run(&fx, 1000U);
    t408_expect_sw(&fx, 0x0008);
}

/* -------------------------------------------------------------- NMT */

/* Stop forces TR_8; no EMCY in Stopped: 0x8100 goes out when the node
 * leaves Stopped. */
static void nmt_stop_forces_fault(void **state)
{
    (void)state;
    t408_cw(&fx, 0x0007);
    tb_send(BUS, "000 02 01");
    tb_expect_none(BUS);
    assert_int_equal(co408_state(V), CO408_FAULT_REACTION);
    t408_run(&fx, 5000U);
    tb_expect_none(BUS);
    assert_int_equal(co408_state(V), CO408_FAULT_HOLD);
    /* the device-mode writes are refused in Stopped anyway (no SDO) */
    tb_send(BUS, "601 40 41 60 00 00 00 00 00");
    tb_expect_none(BUS);
    tb_send(BUS, "000 80 01");
    tb_expect(BUS, "081 00 81 11 00 00 00 00 00");
    tb_expect_none(BUS);
    t408_expect_sw(&fx, 0x0003);
    tb_xfer(BUS, "601 40 03 10 01 00 00 00 00", "581 43 03 10 01 00 81 00 00");
    t408_cw(&fx, 0x0003);
    t408_cw(&fx, 0x000B);
    t408_expect_sw(&fx, 0x000B);
    t408_run(&fx, 1000U);
    tb_expect(BUS, "081 00 00 00 00 00 00 00 00");
    tb_expect_none(BUS);
}

/* Stop from Operational and back to Operational: the EMCY on the way out. */
static void nmt_stop_then_start(void **state)
{
    (void)state;
    tb_send(BUS, "000 01 01");
    tb_flush(BUS);
    tb_send(BUS, "000 02 01");
    t408_run(&fx, 2000U);
    assert_int_equal(co408_state(V), CO408_FAULT);
    tb_expect_none(BUS);
    tb_send(BUS, "000 01 01");
    /* entering Operational sends the event-driven TPDOs, then the node
     * tells its plug-ins: the EMCY follows them */
    tb_expect(BUS, "181 01 00 00 00");
    tb_expect(BUS, "281 01 00 00 00");
    tb_expect(BUS, "081 00 81 11 00 00 00 00 00");
    tb_expect_none(BUS);
}

/* Reset Communication forces TR_8; the EMCY follows the boot-up. */
static void nmt_reset_comm_forces_fault(void **state)
{
    (void)state;
    t408_cw(&fx, 0x0001);
    tb_send(BUS, "000 82 01");
    tb_expect(BUS, "701 00");
    tb_expect(BUS, "081 00 81 11 00 00 00 00 00");
    tb_expect_none(BUS);
    t408_expect_sw(&fx, 0x0007);
    t408_run(&fx, 1000U);
    t408_expect_sw(&fx, 0x0001);
    t408_cw(&fx, 0x0000);
    t408_cw(&fx, 0x0008); /* TR_10, then TR_7: D is not set */
    t408_expect_sw(&fx, 0x0008);
    t408_run(&fx, 1000U);
    tb_expect(BUS, "081 00 00 00 00 00 00 00 00");
}

/* Reset Node: TR_567 to INIT, no EMCY; Pre-operational: no change. */
static void nmt_reset_node_and_preop(void **state)
{
    (void)state;
    t408_cw(&fx, 0x0007);
    tb_send(BUS, "000 80 01");
    tb_expect_none(BUS);
    t408_expect_sw(&fx, 0x000F);
    tb_send(BUS, "000 01 01");
    tb_flush(BUS);
    tb_send(BUS, "000 80 01");
    tb_expect_none(BUS);
    t408_expect_sw(&fx, 0x000F);
    tb_send(BUS, "000 81 01");
    tb_expect(BUS, "701 00");
    tb_expect_none(BUS);
    t408_expect_sw(&fx, 0x0008);
    assert_int_equal(co408_state(V), CO408_INIT);
    /* a fault, then Reset Node: INIT again and no errors left */
    co408_fault_raise(V, 0x1000);
    tb_expect(BUS, "081 00 10 01 00 00 00 00 00");
    tb_send(BUS, "000 81 01");
    tb_expect(BUS, "701 00");
    tb_expect_none(BUS);
    t408_expect_sw(&fx, 0x0008);
    tb_xfer(BUS, "601 40 01 10 00 00 00 00 00", "581 4F 01 10 00 00 00 00 00");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(boot_is_init, setup),
        cmocka_unit_test_setup(single_transitions, setup),
        cmocka_unit_test_setup(chained_transitions, setup),
        cmocka_unit_test_setup(patterns_without_transition, setup),
        cmocka_unit_test_setup(fault_hold_and_tr11, setup),
        cmocka_unit_test_setup(fault_and_tr10, setup),
        cmocka_unit_test_setup(fault_hold_tr10_and_chain, setup),
        cmocka_unit_test_setup(fault_from_init, setup),
        cmocka_unit_test_setup(monitoring_off, setup),
        cmocka_unit_test_setup(mode_writes_only_in_init_or_disabled, setup),
        cmocka_unit_test_setup(mode_values_refused, setup),
        cmocka_unit_test_setup(source_arbitration, setup),
        cmocka_unit_test_setup(local_enable_input, setup),
        cmocka_unit_test_setup(nmt_stop_forces_fault, setup),
        cmocka_unit_test_setup(nmt_stop_then_start, setup),
        cmocka_unit_test_setup(nmt_reset_comm_forces_fault, setup),
        cmocka_unit_test_setup(nmt_reset_node_and_preop, setup),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
