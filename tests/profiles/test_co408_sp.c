/*
 * CiA 408 set-point path: bus-window scaling, dead band, the four ramps and
 * status bit 9, HOLD keeping the set-point, the actual value following, the
 * closed loop with control deviation, following-error window (bit 11, fault
 * with type -2) and target window (bit 12), and the set-point by RPDO.
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

static void vpoc_sp(int16_t sp)
{
    t408_sdo_write(&fx, 0x6300, 1, sp, 2, 0);
}

/* ------------------------------------------------------------ scaling */

static void bus_window_scaling(void **state)
{
    (void)state;
    t408_cw(&fx, 0x0007);
    vpoc_sp(8192); /* default window -16384..16384: 1:1 (D21) */
    t408_run(&fx, 1000U);
    assert_int_equal(co408_output(V), 8192);
    vpoc_sp(-4096);
    t408_run(&fx, 1000U);
    assert_int_equal(co408_output(V), -4096);
    /* window 0..10000 (unipolar): 5000 is 50 % */
    t408_cw(&fx, 0x0001);
    t408_sdo_write(&fx, 0x2329, 0, 0, 4, 0);
    t408_sdo_write(&fx, 0x232A, 0, 10000, 4, 0);
    t408_cw(&fx, 0x0007);
    vpoc_sp(5000);
    t408_run(&fx, 1000U);
    assert_int_equal(co408_output(V), 8192);
    vpoc_sp(12000); /* beyond the window: 100 % */
    t408_run(&fx, 1000U);
    assert_int_equal(co408_output(V), 16384);
    vpoc_sp(-100); /* below: 0 .. */
    t408_run(&fx, 1000U);
    assert_int_equal(co408_output(V), -164); /* rounded down */
    /* window -10000..10000 (bipolar) */
    t408_sdo_write(&fx, 0x2329, 0, -10000, 4, 0);
    vpoc_sp(-5000);
    t408_run(&fx, 1000U);
    assert_int_equal(co408_output(V), -8192);
}

static void dead_band(void **state)
{
    (void)state;
    t408_sdo_write(&fx, 0x232E, 0, 1638, 2, 0);
    t408_sdo_write(&fx, 0x232D, 0, 1, 1, 0);
    t408_sdo_write(&fx, 0x232E, 0, 16385, 2, 0x06090031); /* 0..16384 */
    t408_cw(&fx, 0x0007);
    vpoc_sp(8192);
    t408_run(&fx, 1000U);
    assert_int_equal(co408_output(V), 1638 + 7373); /* past the overlap, range compressed */
    vpoc_sp(-8192);
    t408_run(&fx, 1000U);
    assert_int_equal(co408_output(V), -(1638 + 7373));
    vpoc_sp(0);
    t408_run(&fx, 1000U);
    assert_int_equal(co408_output(V), 0);
    vpoc_sp(1);
    t408_run(&fx, 1000U);
    assert_int_equal(co408_output(V), 1638);
    t408_sdo_write(&fx, 0x232D, 0, 0, 1, 0); /* off */
    vpoc_sp(8192);
    t408_run(&fx, 1000U);
    assert_int_equal(co408_output(V), 8192);
}

/* ------------------------------------------------------------- ramps */

static void ramps_and_bit9(void **state)
{
    (void)state;
    t408_sdo_write(&fx, 0x6330, 0, 3, 1, 0);
    t408_sdo_write(&fx, 0x6332, 1, 1000, 2, 0); /* A up: 1 s per 100 % */
    t408_sdo_write(&fx, 0x6333, 1, 500, 2, 0);  /* A down */
    t408_sdo_write(&fx, 0x6335, 1, 2000, 2, 0); /* B up */
    t408_sdo_write(&fx, 0x6336, 1, 250, 2, 0);  /* B down */
    t408_sdo_write(&fx, 0x6332, 1, 51001, 2, 0x06090031);
    t408_cw(&fx, 0x0007);
    vpoc_sp(16384);
    t408_run(&fx, 500000U);
    assert_between(co408_output(V), 8180, 8200);
    t408_expect_sw(&fx, 0x020F); /* bit 9: ramp running */
    t408_run(&fx, 501000U);
    assert_int_equal(co408_output(V), 16384);
    t408_expect_sw(&fx, 0x000F);
    vpoc_sp(0); /* A down: 500 ms */
    t408_run(&fx, 250000U);
    assert_between(co408_output(V), 8180, 8200);
    t408_run(&fx, 251000U);
    assert_int_equal(co408_output(V), 0);
    vpoc_sp(-16384); /* B up: 2 s */
    t408_run(&fx, 1000000U);
    assert_between(co408_output(V), -8200, -8180);
    t408_expect_sw(&fx, 0x020F);
    t408_run(&fx, 1001000U);
    assert_int_equal(co408_output(V), -16384);
    /* crossing zero: B down (250 ms for 100 %) to 0, then A up */
    vpoc_sp(8192);
    t408_run(&fx, 250000U);
    assert_between(co408_output(V), 0, 20);
    t408_run(&fx, 250000U);
    assert_between(co408_output(V), 4080, 4110);
    t408_run(&fx, 300000U);
    assert_int_equal(co408_output(V), 8192);
    /* ramp type 0: a step */
    t408_sdo_write(&fx, 0x6330, 0, 0, 1, 0);
    vpoc_sp(-16384);
    t408_run(&fx, 1000U);
    assert_int_equal(co408_output(V), -16384);
    t408_expect_sw(&fx, 0x000F);
}

/* HOLD keeps the last set-point; leaving HOLD the ramp starts from it. */
static void hold_keeps_setpoint(void **state)
{
    (void)state;
    t408_cw(&fx, 0x0007);
    vpoc_sp(8192);
    t408_run(&fx, 100000U);
    assert_between(t408_get(&fx, 0x6301, 1), 8100, 8200); /* the spool followed */
    t408_cw(&fx, 0x0003);
    vpoc_sp(-8192);
    t408_run(&fx, 100000U);
    assert_between(t408_get(&fx, 0x6301, 1), 8100, 8200);
    t408_cw(&fx, 0x0007);
    t408_run(&fx, 100000U);
    assert_between(t408_get(&fx, 0x6301, 1), -8200, -8100);
    t408_cw(&fx, 0x0001); /* DISABLED: solenoids off */
    t408_run(&fx, 100000U);
    assert_int_equal(t408_get(&fx, 0x6301, 1), 0);
    t408_cw(&fx, 0x0003); /* HOLD from DISABLED: nothing held */
    t408_run(&fx, 100000U);
    assert_int_equal(t408_get(&fx, 0x6301, 1), 0);
}

/* The spool stays shut until the current passes Imin, then follows. */
static void actual_follows(void **state)
{
    (void)state;
    t408_cw(&fx, 0x0007);
    vpoc_sp(16384);
    t408_run(&fx, 1000U);
    assert_int_equal(t408_get(&fx, 0x6301, 1), 0); /* 1 ms: current still below Imin */
    t408_run(&fx, 4000U);
    assert_between(t408_get(&fx, 0x6301, 1), 8000, 12000);
    t408_run(&fx, 45000U);
    assert_between(t408_get(&fx, 0x6301, 1), 16300, 16384);
}

/* ------------------------------------------------------- closed loop */

static void closed_loop(void **state)
{
    (void)state;
    tb_xfer(BUS, "601 2F 43 60 00 04 00 00 00", "581 60 43 60 00 00 00 00 00");
    t408_sdo_write(&fx, 0x2402, 0, 2, 1, 0);   /* target window on */
    t408_sdo_write(&fx, 0x2403, 0, 10, 2, 0);  /* 10 ms */
    t408_sdo_write(&fx, 0x2404, 0, 164, 4, 0); /* 1 % */
    t408_sdo_write(&fx, 0x63D1, 0, 2, 1, 0);   /* following-error monitoring */
    t408_sdo_write(&fx, 0x63D2, 1, 5, 2, 0);   /* 5 ms */
    t408_sdo_write(&fx, 0x63D3, 1, 1638, 2, 0);/* 10 % */
    t408_cw(&fx, 0x0007);
    t408_sdo_write(&fx, 0x6380, 1, 8192, 2, 0);
    t408_run(&fx, 1000U);
    assert_int_equal(t408_get(&fx, 0x63D0, 1), 8192 - t408_get(&fx, 0x6381, 1));
    t408_expect_sw(&fx, 0x000F);
    t408_run(&fx, 5000U); /* 6 ms beyond the window: bit 11 */
    t408_expect_sw(&fx, 0x080F);
    t408_run(&fx, 300000U);
    assert_between(t408_get(&fx, 0x6381, 1), 8192 - 164, 8192 + 164);
    assert_between(t408_get(&fx, 0x63D0, 1), -164, 164);
    t408_expect_sw(&fx, 0x100F); /* in the target window, no following error */
    /* a step beyond reach for the moment: bit 12 goes, bit 11 comes */
    t408_sdo_write(&fx, 0x6380, 1, -8192, 2, 0);
    t408_run(&fx, 1000U);
    t408_expect_sw(&fx, 0x000F);
    t408_run(&fx, 5000U);
    t408_expect_sw(&fx, 0x080F);
    /* HOLD: no windows */
    t408_cw(&fx, 0x0003);
    t408_expect_sw(&fx, 0x000B);
}

static void following_error_fault(void **state)
{
    (void)state;
    tb_xfer(BUS, "601 2F 43 60 00 04 00 00 00", "581 60 43 60 00 00 00 00 00");
    t408_sdo_write(&fx, 0x63D1, 0, -2, 1, 0);
    t408_sdo_write(&fx, 0x63D2, 1, 5, 2, 0);
    t408_cw(&fx, 0x0007);
    t408_sdo_write(&fx, 0x6380, 1, 16384, 2, 0);
    t408_run(&fx, 5000U);
    tb_expect_none(BUS);
    t408_run(&fx, 1000U);
    tb_expect(BUS, "081 00 10 01 00 00 00 00 00");
    t408_run(&fx, 1000U);
    t408_expect_sw(&fx, 0x0003);
    /* a reset ends it: the cause was an event */
    t408_cw(&fx, 0x0003);
    t408_cw(&fx, 0x000B);
    t408_expect_sw(&fx, 0x000B);
    t408_run(&fx, 1000U);
    tb_expect(BUS, "081 00 00 00 00 00 00 00 00");
}

/* ----------------------------------------------------------- by PDO */

static void setpoint_by_rpdo(void **state)
{
    const co_frame_t *f;

    (void)state;
    tb_send(BUS, "000 01 01");
    tb_expect(BUS, "181 08 00 00 00");
    tb_expect(BUS, "281 08 00 00 00");
    t408_run(&fx, 10000U); /* the TPDOs' inhibit time (10 ms) */
    tb_send(BUS, "201 07 00 00 20"); /* D, H, M and 50 % (D22) */
    t408_run(&fx, 1000U);
    f = tb_next(BUS);
    assert_non_null(f);
    assert_int_equal(f->id, 0x181);
    assert_int_equal(f->data[0], 0x0F);
    assert_int_equal(f->data[1], 0x00);
    tb_flush(BUS);
    t408_run(&fx, 100000U);
    assert_between(t408_get(&fx, 0x6301, 1), 8100, 8200);
    tb_flush(BUS);
    t408_run(&fx, 100000U); /* at rest: nothing changes, nothing sent */
    tb_expect_none(BUS);
    tb_send(BUS, "201 03 00 00 20"); /* TR_5 (D23) */
    t408_run(&fx, 1000U);
    tb_expect(BUS, "181 0B 00 00 20"); /* status, spool at 50 % */
    tb_expect(BUS, "281 0B 00 00 00"); /* status, vprc actual */
    t408_run(&fx, 10000U);
    tb_expect_none(BUS);
    tb_send(BUS, "201 00 00 00 00"); /* TR_5, 6, 7 (D24) */
    t408_run(&fx, 1000U);
    f = tb_next(BUS);
    assert_non_null(f);
    assert_int_equal(f->data[0], 0x08);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(bus_window_scaling, setup),
        cmocka_unit_test_setup(dead_band, setup),
        cmocka_unit_test_setup(ramps_and_bit9, setup),
        cmocka_unit_test_setup(hold_keeps_setpoint, setup),
        cmocka_unit_test_setup(actual_follows, setup),
        cmocka_unit_test_setup(closed_loop, setup),
        cmocka_unit_test_setup(following_error_fault, setup),
        cmocka_unit_test_setup(setpoint_by_rpdo, setup),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
