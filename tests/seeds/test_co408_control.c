/*
 * The CiA 408 valves' way in for the control interface (co_device_set, the
 * daemon's `set INDEX SUB VALUE`, co/co408_device.h): faults of the
 * simulated valve by their EMCY code with the device's documented reaction
 * (digest seed-004 2.7 and 5.2: the EMCY frame, TR_8 to FAULT_HOLD or
 * FAULT, the reset only once the cause is gone), per channel on the
 * two-channel Wandfluh DSV; the enable input under local control and the
 * local set-point input on the cia408 valve. Frame by frame on the
 * in-memory bus through the device layer, node 1.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "cia408.h"
#include "co/co408_device.h"
#include "co_devices.h"
#include "seedrun.h"
#include "wandfluh_dsv.h"

static seedrun_t fx;
static wandfluh_dsv_node_t dsv;
static cia408_node_t std408;
#define S (&fx)

static co_err_t ctl_set(uint16_t index, uint8_t sub, int64_t value)
{
    return co_device_set(&S->run, index, sub, value);
}

static int setup_dsv(void **state)
{
    co_node_config_t cfg;

    (void)state;
    wandfluh_dsv_config(&dsv, &cfg);
    sr_start(S, &co_device_wandfluh_dsv, &cfg, &dsv.node, NULL, 1);
    sr_run(S, 2);
    tb_expect_none(&S->bus);
    return 0;
}

static int setup_cia408(void **state)
{
    co_node_config_t cfg;

    (void)state;
    cia408_config(&std408, &cfg);
    sr_start(S, &co_device_cia408, &cfg, &std408.node, NULL, 1);
    sr_run(S, 2);
    tb_expect_none(&S->bus);
    return 0;
}

/* Solenoid 1 cable break in DEVICE_MODE_ACTIVE: EMCY 0x2311 (register
 * generic + current), FAULT_HOLD (H was set); a reset while the cable is
 * still broken stays in the fault; repaired and reset (R rising): HOLD and
 * EMCY 0x0000. Then a supply under-voltage in DISABLED: EMCY 0x3412
 * (generic + voltage), FAULT. */
static void fault_reaction_and_reset(void **state)
{
    (void)state;
    sr_sdo(S, "2B 40 60 00 07 00 00 00", "60 40 60 00 00 00 00 00");
    sr_sdo(S, "40 41 60 00 00 00 00 00", "4B 41 60 00 0F 00 00 00");
    assert_int_equal(ctl_set(0x2311, 0, 1), CO_OK);
    sr_run(S, 2);
    sr_expect(S, "081 11 23 03 00 00 00 00 00");
    tb_expect_none(&S->bus);
    sr_sdo(S, "40 41 60 00 00 00 00 00", "4B 41 60 00 03 00 00 00");
    sr_sdo(S, "2B 40 60 00 03 00 00 00", "60 40 60 00 00 00 00 00");
    sr_sdo(S, "2B 40 60 00 0B 00 00 00", "60 40 60 00 00 00 00 00");
    sr_run(S, 1);
    sr_sdo(S, "40 41 60 00 00 00 00 00", "4B 41 60 00 03 00 00 00"); /* cause present */
    assert_int_equal(ctl_set(0x2311, 0, 0), CO_OK);                  /* repaired */
    sr_run(S, 1);
    sr_sdo(S, "2B 40 60 00 03 00 00 00", "60 40 60 00 00 00 00 00");
    sr_sdo(S, "2B 40 60 00 0B 00 00 00", "60 40 60 00 00 00 00 00");
    sr_sdo(S, "40 41 60 00 00 00 00 00", "4B 41 60 00 0B 00 00 00"); /* TR_11: HOLD */
    sr_run(S, 1);
    sr_expect(S, "081 00 00 00 00 00 00 00 00");
    sr_sdo(S, "2B 40 60 00 01 00 00 00", "60 40 60 00 00 00 00 00");
    assert_int_equal(ctl_set(0x3412, 1, 1), CO_OK); /* sub 1: channel 1 as well */
    sr_run(S, 2);
    sr_expect(S, "081 12 34 05 00 00 00 00 00");
    sr_sdo(S, "40 41 60 00 00 00 00 00", "4B 41 60 00 01 00 00 00"); /* FAULT */
    tb_expect_none(&S->bus);
}

/* Channel 2 (sub-index 2): its state machine (0x6841) takes the fault, the
 * first channel's does not. Out-of-range values and unknown channels are
 * refused; the faults are not objects of the dictionary. */
static void channels_and_refusals(void **state)
{
    (void)state;
    sr_sdo(S, "2B 40 68 00 01 00 00 00", "60 40 68 00 00 00 00 00");
    sr_sdo(S, "40 41 68 00 00 00 00 00", "4B 41 68 00 09 00 00 00");
    assert_int_equal(ctl_set(0x2312, 2, 2), CO_OK); /* solenoid 2 short, channel 2 */
    sr_run(S, 2);
    sr_expect(S, "081 12 23 03 00 00 00 00 00");
    sr_sdo(S, "40 41 68 00 00 00 00 00", "4B 41 68 00 01 00 00 00");
    sr_sdo(S, "40 41 60 00 00 00 00 00", "4B 41 60 00 08 00 00 00");
    assert_int_equal(ctl_set(0x2311, 0, 3), CO_ERR_VALUE);
    assert_int_equal(ctl_set(0x3412, 0, 2), CO_ERR_VALUE);
    assert_int_equal(ctl_set(0x3422, 0, -1), CO_ERR_VALUE);
    assert_int_equal(ctl_set(0x2311, 3, 1), CO_ERR_NO_OBJECT); /* no channel 3 */
    assert_int_equal(ctl_set(CO408_SIM_INPUTS + 1U, 3, 1), CO_ERR_NO_SUB);
    assert_int_equal(ctl_set(CO408_SIM_INPUTS, CO408_SIM_IN_ENABLE, 2), CO_ERR_VALUE);
    tb_expect_none(&S->bus);
}

/* Local control (0x604F = 1): the enable input is the control word (D, H,
 * M): on, DEVICE_MODE_ACTIVE; with the set-point local (0x6042 = 2) the
 * spool follows the local set-point input; off, INIT again. */
static void enable_input_and_local_set_point(void **state)
{
    int64_t spool;

    (void)state;
    sr_sdo(S, "2F 4F 60 00 01 00 00 00", "60 4F 60 00 00 00 00 00");
    sr_sdo(S, "2F 42 60 00 02 00 00 00", "60 42 60 00 00 00 00 00");
    assert_int_equal(ctl_set(CO408_SIM_INPUTS, CO408_SIM_IN_LOCAL_SP, 8192), CO_OK);
    assert_int_equal(ctl_set(CO408_SIM_INPUTS, CO408_SIM_IN_ENABLE, 1), CO_OK);
    sr_run(S, 1);
    assert_int_equal(sr_get(S, 0x6041, 0), 0x000F);
    sr_run(S, 300);
    spool = sr_get(S, 0x6301, 1);
    sr_between(spool, 8000, 8300);
    assert_int_equal(ctl_set(CO408_SIM_INPUTS, CO408_SIM_IN_LOCAL_SP, -4096), CO_OK);
    sr_run(S, 300);
    sr_between(sr_get(S, 0x6301, 1), -4200, -4000);
    assert_int_equal(ctl_set(CO408_SIM_INPUTS, CO408_SIM_IN_ENABLE, 0), CO_OK);
    sr_run(S, 1);
    assert_int_equal(sr_get(S, 0x6041, 0), 0x0008);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(fault_reaction_and_reset, setup_dsv),
        cmocka_unit_test_setup(channels_and_refusals, setup_dsv),
        cmocka_unit_test_setup(enable_input_and_local_set_point, setup_cia408),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
