/*
 * AnaGate Motion Digital IO module (devices/anagate-dio.toml, the CiA 401
 * profile on 0x8000 / 0x8001 with data in sub 0 and 1, loopback
 * simulation): the digest's DSP401 vectors (/work/shared/spec/seed-003,
 * section 4) frame by frame on the in-memory bus, node 5.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "anagate_dio.h"
#include "co/co401_device.h"
#include "co_devices.h"
#include "seedrun.h"

static seedrun_t fx;
static anagate_dio_node_t node;
#define S (&fx)

static int setup(void **state)
{
    co_node_config_t cfg;

    (void)state;
    anagate_dio_config(&node, &cfg);
    sr_start(S, &co_device_anagate_dio, &cfg, &node.node, NULL, 5);
    sr_run(S, 5);
    tb_expect_none(&S->bus);
    return 0;
}

static void operational(void)
{
    tb_send(&S->bus, "000 01 05");
    sr_run(S, 1);
    sr_expect(S, "485 00 00"); /* T-PDO4, first transmission in Operational */
    tb_expect_none(&S->bus);
}

/* Identity (section 2.7, 8.1 items 1 and 2): vendor-ID in 0x1018 sub 0,
 * product code 0x10, device type 0. */
static void identity(void **state)
{
    (void)state;
    sr_sdo(S, "40 18 10 00 00 00 00 00", "43 18 10 00 EB 02 00 00");
    sr_sdo(S, "40 18 10 01 00 00 00 00", "43 18 10 01 10 00 00 00");
    sr_sdo(S, "40 00 10 00 00 00 00 00", "43 00 10 00 00 00 00 00");
    /* 0x8000 is read-only (the live inputs) */
    sr_sdo(S, "2F 00 80 00 01 00 00 00", "80 00 80 00 02 00 01 06");
}

/* Section 4.2: setting outputs 1 and 16 is 0x405 [01 80]; 0x8001 sub 0
 * reads 0x01 and sub 1 0x80. The loopback brings them to the inputs:
 * T-PDO4 0x485 [01 80]. */
static void rpdo3_sets_outputs_tpdo4_reports_inputs(void **state)
{
    uint8_t n = 0U;
    const uint8_t *out;

    (void)state;
    operational();
    tb_send(&S->bus, "405 01 80");
    out = co401_outputs(co401_device_module(&S->run, 0U), &n);
    assert_int_equal(n, 2);
    assert_int_equal(out[0], 0x01);
    assert_int_equal(out[1], 0x80);
    sr_sdo(S, "40 01 80 00 00 00 00 00", "4F 01 80 00 01 00 00 00");
    sr_sdo(S, "40 01 80 01 00 00 00 00", "4F 01 80 01 80 00 00 00");
    sr_run(S, 1);
    sr_expect(S, "485 01 80");
    tb_expect_none(&S->bus);
    assert_int_equal(sr_sdo_read(S, 0x8000, 0), 0x01);
    /* no change: no T-PDO4 */
    tb_send(&S->bus, "405 01 80");
    sr_run(S, 20);
    tb_expect_none(&S->bus);
}

/* Table 38 names R-PDO4 for the outputs: the same layout on 0x505. */
static void rpdo4_also_sets_outputs(void **state)
{
    (void)state;
    operational();
    tb_send(&S->bus, "505 FF 00");
    sr_run(S, 1);
    sr_expect(S, "485 FF 00");
    tb_expect_none(&S->bus);
}

/* Writing 0x8001 by SDO drives the outputs at once (digest 4.1,
 * recommended); an input set from outside sends T-PDO4; Reset Node sets
 * the outputs back to 0x00. */
static void sdo_outputs_inputs_and_reset(void **state)
{
    (void)state;
    operational();
    sr_sdo_write(S, 0x8001, 1, 0x42, 1);
    sr_run(S, 1);
    sr_expect(S, "485 00 42");
    assert_int_equal(co_device_set(&S->run, 0x8000, 0, 0x07), CO_OK);
    sr_run(S, 1);
    sr_expect(S, "485 07 42");
    tb_expect_none(&S->bus);
    tb_send(&S->bus, "000 81 05");
    sr_expect(S, "705 00");
    sr_run(S, 1);
    assert_int_equal(sr_sdo_read(S, 0x8001, 1), 0x00);
    assert_int_equal(sr_sdo_read(S, 0x8000, 1), 0x00); /* the loopback of 0 */
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(identity, setup),
        cmocka_unit_test_setup(rpdo3_sets_outputs_tpdo4_reports_inputs, setup),
        cmocka_unit_test_setup(rpdo4_also_sets_outputs, setup),
        cmocka_unit_test_setup(sdo_outputs_inputs_and_reset, setup),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
