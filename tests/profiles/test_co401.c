/*
 * The CiA 401 profile (co/co401.h) on the cia401 device (devices/cia401.toml:
 * 16 DI at 0x6000 sub 1..2, 16 DO at 0x6200 sub 1..2, 4 AI 0x6401, 2 AO
 * 0x6411; TPDO1 DI, RPDO1 DO, TPDO2 AI, RPDO2 AO, type 255) and its loopback
 * simulation, node 5 on the in-memory bus, frame by frame: outputs by RPDO
 * and SDO, loopback inputs by TPDO only for interrupt-enabled changes (any
 * change, low-to-high, high-to-low masks, global enable), polarity, input
 * filter, output filter mask, the error values on every communication
 * error and before NMT Stopped, analog limits and deltas.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "cia401.h"
#include "co/co401_device.h"
#include "co_devices.h"
#include "seedrun.h"

static seedrun_t fx;
static cia401_node_t node;
#define S (&fx)

static co401_t *module(void)
{
    return co401_device_module(&S->run, 0U);
}

static void outputs_are(uint8_t b0, uint8_t b1)
{
    uint8_t n = 0U;
    const uint8_t *o = co401_outputs(module(), &n);

    assert_int_equal(n, 2);
    assert_int_equal(o[0], b0);
    assert_int_equal(o[1], b1);
}

/* Set a physical input through the control interface's path. */
static void set_in(uint16_t index, uint8_t sub, int64_t value)
{
    assert_int_equal(co_device_set(&S->run, index, sub, value), CO_OK);
}

static int setup(void **state)
{
    co_node_config_t cfg;

    (void)state;
    cia401_config(&node, &cfg);
    sr_start(S, &co_device_cia401, &cfg, &node.node, NULL, 5);
    sr_run(S, 5);
    tb_expect_none(&S->bus);
    /* Operational: the first transmission of each event-driven TPDO */
    tb_send(&S->bus, "000 01 05");
    sr_run(S, 1);
    sr_expect(S, "185 00 00");
    sr_expect(S, "285 00 00 00 00 00 00 00 00");
    tb_expect_none(&S->bus);
    return 0;
}

/* CiA 401 objects as the description gives them, device type 0x000F0191. */
static void identity_and_objects(void **state)
{
    (void)state;
    assert_int_equal(sr_sdo_read(S, 0x1000, 0), 0x000F0191);
    assert_int_equal(sr_sdo_read(S, 0x6000, 0), 2);
    assert_int_equal(sr_sdo_read(S, 0x6006, 1), 0xFF);
    assert_int_equal(sr_sdo_read(S, 0x6206, 2), 0xFF);
    assert_int_equal(sr_sdo_read(S, 0x6401, 0), 4);
    assert_int_equal(sr_sdo_read(S, 0x6411, 0), 2);
    /* inputs are read-only */
    sr_sdo(S, "2F 00 60 01 55 00 00 00", "80 00 60 01 02 00 01 06");
}

/* RPDO1 sets the outputs at once, all of them; the loopback brings them to
 * the inputs, whose change sends TPDO1. An SDO write does the same. */
static void outputs_by_rpdo_and_sdo(void **state)
{
    (void)state;
    tb_send(&S->bus, "205 55 AA");
    outputs_are(0x55, 0xAA);
    tb_expect_none(&S->bus);
    sr_run(S, 1);
    sr_expect(S, "185 55 AA");
    tb_expect_none(&S->bus);
    assert_int_equal(sr_get(S, 0x6000, 1), 0x55);
    sr_sdo_write(S, 0x6200, 2, 0x0F, 1);
    sr_run(S, 1);
    outputs_are(0x55, 0x0F);
    sr_expect(S, "185 55 0F");
    tb_expect_none(&S->bus);
    /* an input set from outside (the control interface) */
    set_in(0x6000, 2, 0x81);
    sr_run(S, 1);
    sr_expect(S, "185 55 81");
    tb_expect_none(&S->bus);
}

/* The interrupt masks: any change (0x6006), low-to-high (0x6007),
 * high-to-low (0x6008), the global enable (0x6005). A masked change sends
 * nothing; the next unmasked one sends all inputs. */
static void interrupt_masks(void **state)
{
    (void)state;
    sr_sdo_write(S, 0x6006, 1, 0x0F, 1); /* any change: bits 0..3 */
    sr_sdo_write(S, 0x6007, 1, 0x10, 1); /* bit 4 rising */
    sr_sdo_write(S, 0x6008, 1, 0x20, 1); /* bit 5 falling */
    set_in(0x6000, 1, 0x80);             /* bit 7: masked */
    sr_run(S, 20);
    tb_expect_none(&S->bus);
    assert_int_equal(sr_get(S, 0x6000, 1), 0x80);
    set_in(0x6000, 1, 0x90); /* bit 4 rises */
    sr_run(S, 1);
    sr_expect(S, "185 90 00");
    set_in(0x6000, 1, 0x80); /* bit 4 falls: not enabled */
    set_in(0x6000, 1, 0xA0); /* bit 5 rises: not enabled */
    sr_run(S, 20);
    tb_expect_none(&S->bus);
    set_in(0x6000, 1, 0x80); /* bit 5 falls */
    sr_run(S, 1);
    sr_expect(S, "185 80 00");
    set_in(0x6000, 1, 0x81); /* bit 0: any change */
    sr_run(S, 1);
    sr_expect(S, "185 81 00");
    set_in(0x6000, 1, 0x80);
    sr_run(S, 1);
    sr_expect(S, "185 80 00");
    /* block 2 keeps the default mask: any change */
    set_in(0x6000, 2, 0x40);
    sr_run(S, 1);
    sr_expect(S, "185 80 40");
    /* global interrupt enable off: no change sends */
    sr_sdo_write(S, 0x6005, 0, 0, 1);
    set_in(0x6000, 2, 0x00);
    set_in(0x6000, 1, 0x81);
    sr_run(S, 20);
    tb_expect_none(&S->bus);
    /* enabled again: what changed meanwhile was no interrupt; the next is */
    sr_sdo_write(S, 0x6005, 0, 1, 1);
    sr_run(S, 20);
    tb_expect_none(&S->bus);
    set_in(0x6000, 1, 0x80);
    sr_run(S, 1);
    sr_expect(S, "185 80 00");
    tb_expect_none(&S->bus);
}

/* Polarity: 0x6002 inverts an input, 0x6202 an output. */
static void polarity(void **state)
{
    (void)state;
    sr_sdo_write(S, 0x6002, 1, 0xFF, 1);
    sr_run(S, 1);
    sr_expect(S, "185 FF 00");
    sr_sdo_write(S, 0x6202, 2, 0x0F, 1);
    sr_run(S, 1);
    outputs_are(0x00, 0x0F); /* object 0x00, physical inverted where set */
    sr_expect(S, "185 FF 0F"); /* loopback of the physical level */
    tb_send(&S->bus, "205 01 0F");
    outputs_are(0x01, 0x00);
    sr_run(S, 1);
    sr_expect(S, "185 FE 00");
    tb_expect_none(&S->bus);
}

/* Filter constant 0x6003: a change of a filtered input counts after 3 ms. */
static void input_filter(void **state)
{
    (void)state;
    sr_sdo_write(S, 0x6003, 1, 0x01, 1);
    set_in(0x6000, 1, 0x03); /* bit 1 unfiltered: at once; bit 0 waits */
    sr_run(S, 1);
    sr_expect(S, "185 02 00");
    set_in(0x6000, 1, 0x02); /* a glitch of bit 0 shorter than the filter time */
    sr_run(S, 5);
    tb_expect_none(&S->bus);
    set_in(0x6000, 1, 0x03);
    sr_run(S, 2);
    tb_expect_none(&S->bus);
    assert_int_equal(sr_get(S, 0x6000, 1), 0x02);
    sr_run(S, 2);
    sr_expect(S, "185 03 00");
    tb_expect_none(&S->bus);
}

/* Filter mask 0x6208: a cleared bit keeps the output at its present value. */
static void output_filter_mask(void **state)
{
    (void)state;
    tb_send(&S->bus, "205 F0 00");
    outputs_are(0xF0, 0x00);
    sr_sdo_write(S, 0x6208, 1, 0x0F, 1);
    tb_send(&S->bus, "205 0F 00");
    outputs_are(0xFF, 0x00); /* bits 4..7 kept */
    tb_send(&S->bus, "205 00 00");
    outputs_are(0xF0, 0x00);
}

static void set_outputs_for_error(void)
{
    sr_sdo_write(S, 0x6206, 1, 0x0F, 1); /* bits 0..3 take their error value */
    sr_sdo_write(S, 0x6207, 1, 0x05, 1);
    sr_sdo_write(S, 0x6443, 2, 0, 1);    /* analog output 2 keeps its value */
    sr_sdo_write(S, 0x6444, 1, 1234, 4);
    tb_send(&S->bus, "205 F0 FF");
    tb_send(&S->bus, "305 10 00 20 00");
    outputs_are(0xF0, 0xFF);
    assert_false(co401_in_error(module()));
    sr_run(S, 1);
    tb_flush(&S->bus);
}

static void error_values_applied(void)
{
    assert_true(co401_in_error(module()));
    outputs_are(0xF5, 0x00); /* byte 1: error mode 0xFF, error value 0 */
    sr_run(S, 1);
    assert_int_equal(sr_get(S, 0x6401, 1), 1234); /* loopback of the analog outputs */
    assert_int_equal(sr_get(S, 0x6401, 2), 0x20);
    /* the objects keep the master's values */
    assert_int_equal(sr_get(S, 0x6200, 1), 0xF0);
}

/* Heartbeat consumer timeout of the master: EMCY 0x8130, error values. */
static void error_mode_heartbeat_loss(void **state)
{
    (void)state;
    set_outputs_for_error();
    sr_sdo_write(S, 0x1016, 1, 0x00010064, 4); /* node 1, 100 ms */
    tb_send(&S->bus, "701 05");
    sr_run(S, 99);
    outputs_are(0xF0, 0xFF);
    sr_run(S, 2);
    sr_expect(S, "085 30 81 11 00 00 00 00 00");
    error_values_applied();
    /* the next RPDO ends the error state */
    tb_send(&S->bus, "205 F0 FF");
    outputs_are(0xF0, 0xFF);
    assert_false(co401_in_error(module()));
}

/* Life guarding: the master's guarding requests stop. */
static void error_mode_guarding_loss(void **state)
{
    (void)state;
    set_outputs_for_error();
    sr_sdo_write(S, 0x100C, 0, 50, 2); /* 50 ms x 2 */
    sr_sdo_write(S, 0x100D, 0, 2, 1);
    tb_send(&S->bus, "705 R1");
    sr_expect(S, "705 05");
    sr_run(S, 99);
    outputs_are(0xF0, 0xFF);
    sr_run(S, 2);
    sr_expect(S, "085 30 81 11 00 00 00 00 00");
    error_values_applied();
}

/* Bus-off as the port reports it: a communication error (0x1029 class 1). */
static void error_mode_bus_off(void **state)
{
    (void)state;
    set_outputs_for_error();
    co_node_error_behaviour(&node.node, CO_ERRBEH_COMM, S->bus.now);
    error_values_applied();
}

/* NMT Stopped: the error values before the state changes; an SDO change of
 * an output after Pre-operational ends it. */
static void error_mode_nmt_stop(void **state)
{
    (void)state;
    set_outputs_for_error();
    tb_send(&S->bus, "000 02 05");
    error_values_applied();
    tb_send(&S->bus, "000 80 05");
    sr_sdo_write(S, 0x6200, 1, 0x33, 1);
    sr_run(S, 1);
    outputs_are(0x33, 0xFF);
    assert_false(co401_in_error(module()));
}

/* Reset node: the objects are back at their defaults and applied. */
static void reset_node_defaults(void **state)
{
    (void)state;
    tb_send(&S->bus, "205 12 34");
    outputs_are(0x12, 0x34);
    tb_send(&S->bus, "000 81 05");
    sr_expect(S, "705 00");
    sr_run(S, 1);
    outputs_are(0x00, 0x00);
    assert_int_equal(sr_get(S, 0x6000, 1), 0x00);
}

/* Analog inputs: no TPDO2 while the global enable 0x6423 is off; then
 * the trigger selection 0x6421 with the limits and deltas. */
static void analog_limits_and_deltas(void **state)
{
    (void)state;
    set_in(0x6401, 1, 500);
    sr_run(S, 20);
    tb_expect_none(&S->bus);
    assert_int_equal(sr_get(S, 0x6401, 1), 500);
    sr_sdo_write(S, 0x6426, 1, 100, 4); /* delta 100 */
    sr_sdo_write(S, 0x6424, 1, 1000, 4);
    sr_sdo_write(S, 0x6425, 1, (uint32_t)-1000, 4);
    sr_sdo_write(S, 0x6423, 0, 1, 1);
    sr_run(S, 1);
    sr_expect(S, "285 F4 01 00 00 00 00 00 00"); /* 0 -> 500 > delta */
    set_in(0x6401, 1, 600); /* by 100: not more than delta */
    sr_run(S, 20);
    tb_expect_none(&S->bus);
    set_in(0x6401, 1, 601);
    sr_run(S, 1);
    sr_expect(S, "285 59 02 00 00 00 00 00 00");
    /* upper limit only */
    sr_sdo_write(S, 0x6421, 1, 0x01, 1);
    set_in(0x6401, 1, 1000);
    sr_run(S, 20);
    tb_expect_none(&S->bus);
    set_in(0x6401, 1, 1001);
    sr_run(S, 1);
    sr_expect(S, "285 E9 03 00 00 00 00 00 00");
    set_in(0x6401, 1, 3000); /* above already: no crossing */
    sr_run(S, 20);
    tb_expect_none(&S->bus);
    /* lower limit only */
    sr_sdo_write(S, 0x6421, 1, 0x02, 1);
    set_in(0x6401, 1, -1000);
    sr_run(S, 20);
    tb_expect_none(&S->bus);
    set_in(0x6401, 1, -1001);
    sr_run(S, 1);
    sr_expect(S, "285 17 FC 00 00 00 00 00 00");
    /* negative delta 50: a decrease by more sends, an increase does not */
    sr_sdo_write(S, 0x6421, 1, 0x08, 1);
    sr_sdo_write(S, 0x6427, 1, 50, 4);
    set_in(0x6401, 1, -900);
    sr_run(S, 20);
    tb_expect_none(&S->bus);
    set_in(0x6401, 1, -1100); /* -1001 -> -1100: by 99 */
    sr_run(S, 1);
    sr_expect(S, "285 B4 FB 00 00 00 00 00 00");
    /* positive delta 50 */
    sr_sdo_write(S, 0x6421, 1, 0x10, 1);
    sr_sdo_write(S, 0x6428, 1, 50, 4);
    set_in(0x6401, 1, -1200);
    sr_run(S, 20);
    tb_expect_none(&S->bus);
    set_in(0x6401, 1, -1049); /* -1100 -> -1049: up by 51 */
    sr_run(S, 1);
    sr_expect(S, "285 E7 FB 00 00 00 00 00 00");
    tb_expect_none(&S->bus);
    /* the other channels keep the default 0x07 with limits 0: any change */
    set_in(0x6401, 3, -1);
    sr_run(S, 1);
    sr_expect(S, "285 E7 FB 00 00 FF FF 00 00");
}

/* Analog outputs by RPDO2, looped back to the analog inputs. */
static void analog_outputs(void **state)
{
    (void)state;
    tb_send(&S->bus, "305 E8 03 18 FC");
    sr_run(S, 1);
    assert_int_equal(sr_get(S, 0x6401, 1), 1000);
    assert_int_equal(sr_get(S, 0x6401, 2), -1000);
    assert_int_equal(sr_get(S, 0x6401, 3), 0);
    tb_expect_none(&S->bus); /* global analog interrupt enable is off */
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(identity_and_objects, setup),
        cmocka_unit_test_setup(outputs_by_rpdo_and_sdo, setup),
        cmocka_unit_test_setup(interrupt_masks, setup),
        cmocka_unit_test_setup(polarity, setup),
        cmocka_unit_test_setup(input_filter, setup),
        cmocka_unit_test_setup(output_filter_mask, setup),
        cmocka_unit_test_setup(error_mode_heartbeat_loss, setup),
        cmocka_unit_test_setup(error_mode_guarding_loss, setup),
        cmocka_unit_test_setup(error_mode_bus_off, setup),
        cmocka_unit_test_setup(error_mode_nmt_stop, setup),
        cmocka_unit_test_setup(reset_node_defaults, setup),
        cmocka_unit_test_setup(analog_limits_and_deltas, setup),
        cmocka_unit_test_setup(analog_outputs, setup),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
