/*
 * Kollmorgen S300/S700 (devices/kollmorgen-s300-s700.toml with the CiA 402
 * profile on the simulated motor): the worked examples of the vendor's
 * CANopen manual, as the digest shared/spec/seed-000-kollmorgen-s300-s700.md
 * lists them (D7.1 .. D7.13), replayed frame by frame. Where the digest
 * corrects a frame, the corrected one is sent and the reason is given here.
 * Where the drive's real values cannot match (measured positions, speeds,
 * currents), the frame layout is asserted together with the simulated value
 * the dictionary holds at that moment, and the comment says so. Frames the
 * manual does not print but the device must send (event-driven TPDOs after a
 * change) are asserted too, with the reason.
 *
 * Node 3 (SDO 603/583, RPDO1 203, TPDO1 183) unless stated otherwise.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "co_devices.h"
#include "kollmorgen_s300_s700.h"
#include "test_frames.h"
#include "tseed.h"

static tseed_t fx;
static kollmorgen_s300_s700_node_t kn[TSEED_NODES];
#define BUS (&fx.bus)

#define REV 1048576 /* increments per revolution (2^20) */

static void start_with(unsigned k, uint8_t id, const co402_sim_config_t *sim)
{
    co_node_config_t cfg;

    kollmorgen_s300_s700_config(&kn[k], &cfg);
    tseed_start(&fx, k, &co_device_kollmorgen_s300_s700, &cfg, &kn[k].node, id, sim);
    tseed_expectf(BUS, "%03X 00", 0x700U + id); /* boot-up */
}

static int setup(void **state)
{
    (void)state;
    tseed_init(&fx);
    memset(kn, 0, sizeof kn);
    start_with(0, 3, NULL);
    return 0;
}

/* SDO download of @p data ("2B 40 60 00 06 00 00 00") to node @p id: the
 * confirmation echoes index and sub-index. */
static void dl(uint8_t id, const char *data)
{
    char req[64];
    char resp[64];

    snprintf(req, sizeof req, "%03X %s", 0x600U + id, data);
    snprintf(resp, sizeof resp, "%03X 60 %.8s 00 00 00 00", 0x580U + id, &data[3]);
    tb_xfer(BUS, req, resp);
}

static void sim_cfg(co402_sim_config_t *c)
{
    co402_params_sim_config(co402_device_params(&co_device_kollmorgen_s300_s700), c);
}

/* ------------------------------------------------------------ identity */

/* §3.5: the first communication test (boot-up, then 0x1000); D1.1, D5.1. */
static void identity(void **state)
{
    (void)state;
    /* 0x1000 reads 0x00002192 as printed (the layout would give 0x00020192) */
    tb_xfer(BUS, "603 40 00 10 00 00 00 00 00", "583 43 00 10 00 92 21 00 00");
    tb_xfer(BUS, "603 40 18 10 00 00 00 00 00", "583 4F 18 10 00 04 00 00 00");
    tb_xfer(BUS, "603 40 18 10 01 00 00 00 00", "583 43 18 10 01 6A 00 00 00");
    tb_xfer(BUS, "603 40 18 10 02 00 00 00 00", "583 43 18 10 02 32 01 00 00"); /* 306 */
    /* revision: CAN part 0.34 (0x22), firmware 1.21 (0x79) */
    tb_xfer(BUS, "603 40 18 10 03 00 00 00 00", "583 43 18 10 03 79 00 22 00");
    /* the strings fit in 4 bytes: expedited ("S306", "1.00", "0.34") */
    tb_xfer(BUS, "603 40 08 10 00 00 00 00 00", "583 43 08 10 00 53 33 30 36");
    tb_xfer(BUS, "603 40 09 10 00 00 00 00 00", "583 43 09 10 00 31 2E 30 30");
    tb_xfer(BUS, "603 40 0A 10 00 00 00 00 00", "583 43 0A 10 00 30 2E 33 34");
    /* 6502h = 0x6D: pp, pv, tq, hm, ip */
    tb_xfer(BUS, "603 40 02 65 00 00 00 00 00", "583 43 02 65 00 6D 00 00 00");
    /* 1010h sub 1 reads 1 (saves on command) */
    tb_xfer(BUS, "603 40 10 10 01 00 00 00 00", "583 43 10 10 01 01 00 00 00");
    tb_xfer(BUS, "603 40 10 10 00 00 00 00 00", "583 4F 10 10 00 01 00 00 00");
    /* D8.1-2: segmented transfer is not supported (every object fits in 4
     * bytes); the manual documents no answer, the core gives 0x05040001 */
    tb_xfer(BUS, "603 21 40 60 00 02 00 00 00", "583 80 40 60 00 01 00 04 05");
    /* the documented abort codes: missing object, read-only object */
    tb_xfer(BUS, "603 40 34 12 00 00 00 00 00", "583 80 34 12 00 00 00 02 06");
    tb_xfer(BUS, "603 23 00 10 00 00 00 00 00", "583 80 00 10 00 02 00 01 06");
    /* no TIME, no EMCY inhibit, no SYNC window, no heartbeat consumer 2 */
    tb_xfer(BUS, "603 40 12 10 00 00 00 00 00", "583 80 12 10 00 00 00 02 06");
    tb_xfer(BUS, "603 40 15 10 00 00 00 00 00", "583 80 15 10 00 00 00 02 06");
    tb_xfer(BUS, "603 40 07 10 00 00 00 00 00", "583 80 07 10 00 00 00 02 06");
    tb_xfer(BUS, "603 40 16 10 02 00 00 00 00", "583 80 16 10 02 11 00 09 06");
    /* SYNC consumer only: bits 11..31 of 1005h stay 0 */
    tb_xfer(BUS, "603 23 05 10 00 80 00 00 40", "583 80 05 10 00 31 00 09 06");
    /* manufacturer modes 0x80..0x88 are not simulated: refused */
    tb_xfer(BUS, "603 2F 60 60 00 88 00 00 00", "583 80 60 60 00 30 00 09 06");
    /* homing methods not simulated (mechanical stop, SSI) are refused */
    tb_xfer(BUS, "603 2F 98 60 00 F9 00 00 00", "583 80 98 60 00 30 00 09 06");
    tb_xfer(BUS, "603 2F 98 60 00 F8 00 00 00", "583 80 98 60 00 30 00 09 06");
    tb_xfer(BUS, "603 2F 98 60 00 03 00 00 00", "583 80 98 60 00 30 00 09 06");
    tb_xfer(BUS, "603 2F 98 60 00 FE 00 00 00", "583 60 98 60 00 00 00 00 00");
}

/* ------------------------------------------ D7.1 free mapping of TPDO1 */

static void d71_free_mapping(void **state)
{
    const co_frame_t *f;

    (void)state;
    start_with(1, 1, NULL); /* the example's node 1 */
    /* the answers are not printed: each is the download confirmation */
    dl(1, "2F 00 1A 00 00 00 00 00");
    dl(1, "23 00 1A 01 10 00 41 60");
    dl(1, "23 00 1A 02 20 00 02 10");
    /* step 4 is described, not printed: 2 entries */
    dl(1, "2F 00 1A 00 02 00 00 00");
    tseed_set(&fx, 1, 0x1002, 0, 0x00000400, 4); /* the application's status */
    tb_send(BUS, "000 01 01");
    f = tseed_frame(BUS, 0x181, 6);
    TF_ASSERT_FRAME(f, "181 40 02 00 04 00 00");
    tb_flush(BUS);
}

/* ------------------------------------------------- D7.2 state machine */

static void d72_state_machine_by_sdo(void **state)
{
    (void)state;
    /* step 1 is printed with data "40 00 00 00": the request's data bytes
     * are reserved, a server answers the read either way */
    tb_xfer(BUS, "603 40 41 60 00 40 00 00 00", "583 4B 41 60 00 40 02 00 00");
    tb_xfer(BUS, "603 40 41 60 00 00 00 00 00", "583 4B 41 60 00 40 02 00 00");
    tb_xfer(BUS, "603 2B 40 60 00 06 00 00 00", "583 60 40 60 00 00 00 00 00");
    tb_xfer(BUS, "603 2B 40 60 00 07 00 00 00", "583 60 40 60 00 00 00 00 00");
    tb_xfer(BUS, "603 40 41 60 00 00 00 00 00", "583 4B 41 60 00 33 02 00 00");
    assert_int_equal(co402_state(tseed_axis(&fx, 0)), CO402_SWITCHED_ON);
    tb_expect_none(BUS);
}

/* ------------------------------------------------------ D7.3 pv by SDO */

static void d73_jog_by_sdo(void **state)
{
    (void)state;
    tb_xfer(BUS, "603 2F 60 60 00 03 00 00 00", "583 60 60 60 00 00 00 00 00");
    tb_xfer(BUS, "603 23 FF 60 00 00 00 00 00", "583 60 FF 60 00 00 00 00 00");
    tb_xfer(BUS, "603 2B 40 60 00 06 00 00 00", "583 60 40 60 00 00 00 00 00");
    tb_xfer(BUS, "603 2B 40 60 00 07 00 00 00", "583 60 40 60 00 00 00 00 00");
    tb_xfer(BUS, "603 2B 40 60 00 0F 00 00 00", "583 60 40 60 00 00 00 00 00");
    tb_xfer(BUS, "603 23 FF 60 00 00 41 00 00", "583 60 FF 60 00 00 00 00 00");
    /* the motor turns at 16640 units/s (increments/s with 0x6093 = 1:1;
     * the manual's PGEARI = 10000 configuration makes it 1.664 rev/s) */
    tseed_run(&fx, 200000);
    assert_between(tseed_get(&fx, 0, 0x606C, 0), 16600, 16680);
    tb_xfer(BUS, "603 2B 40 60 00 0F 01 00 00", "583 60 40 60 00 00 00 00 00");
    tseed_run(&fx, 200000);
    /* halt: the axis stands, the set-point is kept */
    assert_between(tseed_get(&fx, 0, 0x606C, 0), -50, 50);
    assert_int_equal(tseed_get(&fx, 0, 0x60FF, 0), 16640);
    assert_int_equal(tseed_sw(&fx, 0), 0x0637);
    tb_expect_none(BUS);
}

/* ------------------------------------------------------ D7.4 tq by SDO */

static void d74_torque_by_sdo(void **state)
{
    (void)state;
    tb_xfer(BUS, "603 2F 60 60 00 04 00 00 00", "583 60 60 60 00 00 00 00 00");
    tb_xfer(BUS, "603 2B 71 60 00 00 00 00 00", "583 60 71 60 00 00 00 00 00");
    /* step 5: command byte printed "28" (OCR); 2B as in every other step */
    tb_xfer(BUS, "603 2B 40 60 00 06 00 00 00", "583 60 40 60 00 00 00 00 00");
    tb_xfer(BUS, "603 2B 40 60 00 07 00 00 00", "583 60 40 60 00 00 00 00 00");
    tb_xfer(BUS, "603 2B 40 60 00 0F 00 00 00", "583 60 40 60 00 00 00 00 00");
    tb_xfer(BUS, "603 2B 71 60 00 90 01 00 00", "583 60 71 60 00 00 00 00 00");
    /* 400 per mille of the rated torque at the motor */
    tseed_run(&fx, 5000);
    assert_int_equal(tseed_get(&fx, 0, 0x6077, 0), 400);
    assert_true(tseed_get(&fx, 0, 0x606C, 0) > 0);
    tb_xfer(BUS, "603 2B 40 60 00 0F 01 00 00", "583 60 40 60 00 00 00 00 00");
    tseed_run(&fx, 500000);
    assert_between(tseed_get(&fx, 0, 0x606C, 0), -2000, 2000);
    assert_int_equal(tseed_get(&fx, 0, 0x6071, 0), 400); /* kept under halt */
    tb_expect_none(BUS);
}

/* Switch off TPDO2..4 and RPDO2..4 as D7.5/D7.6 do (node 3). */
static void unused_pdos_off(void)
{
    dl(3, "23 01 18 01 83 02 00 C0");
    dl(3, "23 02 18 01 83 03 00 C0");
    dl(3, "23 03 18 01 83 04 00 C0");
    dl(3, "23 01 14 01 03 03 00 80");
    dl(3, "23 02 14 01 03 04 00 80");
    dl(3, "23 03 14 01 03 05 00 80");
}

static void enable_by_sdo(void)
{
    dl(3, "2B 40 60 00 06 00 00 00");
    dl(3, "2B 40 60 00 07 00 00 00");
    dl(3, "2B 40 60 00 0F 00 00 00");
}

/* ------------------------------------------------------ D7.5 pv by PDO */

static void d75_jog_by_pdo(void **state)
{
    const co_frame_t *f;

    (void)state;
    dl(3, "2F 60 60 00 03 00 00 00");
    dl(3, "2F 00 16 00 00 00 00 00");
    dl(3, "23 00 16 01 20 00 FF 60");
    dl(3, "2F 00 16 00 01 00 00 00");
    dl(3, "2F 00 1A 00 00 00 00 00");
    /* step 11: data printed "2000864 60" (OCR): 0x60640020 */
    dl(3, "23 00 1A 01 20 00 64 60");
    dl(3, "23 00 1A 02 20 00 6C 60");
    dl(3, "2F 00 1A 00 02 00 00 00");
    dl(3, "2F 00 18 02 01 00 00 00");
    /* step 30's index byte printed "74" (OCR): 0x1403 */
    unused_pdos_off();
    tb_send(BUS, "000 01 03");
    tseed_run(&fx, 1000);
    tb_expect_none(BUS); /* TPDO1 is synchronous now, the others are off */
    enable_by_sdo();
    /* step 38: printed "00 40"; the 32-bit mapping needs 4 bytes */
    tb_send(BUS, "203 00 40 00 00");
    tseed_run(&fx, 200000);
    tb_send(BUS, "080");
    /* step 40: position and speed as the motor has them: the manual shows
     * 83454 / 1747878 of a real drive; the simulation turns at 16384 units/s */
    f = tseed_frame(BUS, 0x183, 8);
    assert_int_equal(tseed_i32(f, 0), tseed_get(&fx, 0, 0x6064, 0));
    assert_int_equal(tseed_i32(f, 4), tseed_get(&fx, 0, 0x606C, 0));
    assert_between(tseed_i32(f, 4), 16340, 16420);
    assert_between(tseed_i32(f, 0), 16384 / 5 - 200, 16384 / 5 + 200);
    tb_expect_none(BUS);
    dl(3, "2B 40 60 00 0F 01 00 00");
}

/* ------------------------------------------------------ D7.6 tq by PDO */

static void d76_torque_by_pdo(void **state)
{
    const co_frame_t *f;

    (void)state;
    dl(3, "2F 60 60 00 04 00 00 00");
    dl(3, "2F 00 16 00 00 00 00 00");
    dl(3, "23 00 16 01 10 00 71 60");
    dl(3, "2F 00 16 00 01 00 00 00");
    dl(3, "2F 00 1A 00 00 00 00 00");
    dl(3, "23 00 1A 01 10 00 77 60");
    dl(3, "2F 00 1A 00 01 00 00 00");
    dl(3, "2F 00 18 02 01 00 00 00");
    dl(3, "23 01 18 01 83 02 00 C0");
    dl(3, "23 02 18 01 83 03 00 C0");
    /* step 21 is printed "83 04 00 00": a valid COB-ID 0x483 (the same
     * CAN-ID, so the drive accepts it and TPDO4 stays on); D7.5 switches it
     * off with C0. The printed frame, then the corrected one: */
    dl(3, "23 03 18 01 83 04 00 00");
    assert_int_equal(tseed_get(&fx, 0, 0x1803, 1), 0x00000483);
    dl(3, "23 03 18 01 83 04 00 C0");
    dl(3, "23 01 14 01 03 03 00 80");
    dl(3, "23 02 14 01 03 04 00 80");
    dl(3, "23 03 14 01 03 05 00 80");
    tb_send(BUS, "000 01 03");
    tseed_run(&fx, 1000);
    tb_expect_none(BUS);
    enable_by_sdo();
    tb_send(BUS, "203 12 02"); /* 530 per mille of the rated torque */
    tseed_run(&fx, 10000);
    tb_send(BUS, "080");
    /* step 38: the torque actual value. The manual's drive measures 537;
     * the simulated motor produces what it is told: 530 */
    f = tseed_frame(BUS, 0x183, 2);
    assert_int_equal(tseed_i16(f, 0), tseed_get(&fx, 0, 0x6077, 0));
    assert_int_equal(tseed_i16(f, 0), 530);
    tb_expect_none(BUS);
    dl(3, "2B 40 60 00 0F 01 00 00");
}

/* Plant with a negative limit switch and index pulses for D7.7. */
static void limit_switch_plant(co402_sim_config_t *c)
{
    sim_cfg(c);
    c->switches = CO402_IN_NEG_LIMIT;
    c->neg_limit = -60000;
    c->index_offset = -30000; /* index pulses at -30000 + k * 2^20 */
}

/* ------------------------------------------------- D7.7 homing by SDO */

static void d77_homing_by_sdo(void **state)
{
    co402_sim_config_t c;
    int32_t home;

    (void)state;
    /* power on with limit switches (the fixture's node is replaced) */
    tseed_init(&fx);
    limit_switch_plant(&c);
    start_with(0, 3, &c); /* step 1: boot-up 703 00 */
    tb_xfer(BUS, "603 40 41 60 00 00 00 00 00", "583 4B 41 60 00 40 02 00 00");
    tb_xfer(BUS, "603 23 99 60 01 10 27 00 00", "583 60 99 60 01 00 00 00 00");
    tb_xfer(BUS, "603 23 99 60 02 88 13 00 00", "583 60 99 60 02 00 00 00 00");
    tb_xfer(BUS, "603 23 9A 60 00 10 27 00 00", "583 60 9A 60 00 00 00 00 00");
    tb_xfer(BUS, "603 23 7C 60 00 A8 61 00 00", "583 60 7C 60 00 00 00 00 00");
    /* the manual has a row "homing method (6098h)" without a telegram; with
     * the inputs configured as limit switches: method 1 (negative limit
     * switch, then the zero mark) */
    tb_xfer(BUS, "603 2F 98 60 00 01 00 00 00", "583 60 98 60 00 00 00 00 00");
    tb_xfer(BUS, "603 2F 60 60 00 06 00 00 00", "583 60 60 60 00 00 00 00 00");
    /* step 15: 0x0240 (the comment's "0250h" contradicts the value) */
    tb_xfer(BUS, "603 40 41 60 00 00 00 00 00", "583 4B 41 60 00 40 02 00 00");
    tb_xfer(BUS, "603 2B 40 60 00 06 00 00 00", "583 60 40 60 00 00 00 00 00");
    tb_xfer(BUS, "603 2B 40 60 00 07 00 00 00", "583 60 40 60 00 00 00 00 00");
    tb_xfer(BUS, "603 2B 40 60 00 0F 00 00 00", "583 60 40 60 00 00 00 00 00");
    tb_xfer(BUS, "603 40 41 60 00 00 00 00 00", "583 4B 41 60 00 37 02 00 00");
    tb_xfer(BUS, "603 2B 40 60 00 1F 00 00 00", "583 60 40 60 00 00 00 00 00");
    tseed_run(&fx, 100000);
    tb_xfer(BUS, "603 40 41 60 00 00 00 00 00", "583 4B 41 60 00 37 02 00 00");
    /* 10000 counts/s to the limit switch, 5000 counts/s to the zero mark */
    (void)tseed_run_until(&fx, 0, 0x1400, 0x1400, 30000000);
    tb_xfer(BUS, "603 40 41 60 00 00 00 00 00", "583 4B 41 60 00 37 16 00 00");
    /* the zero mark (-30000) is now the home offset 25000; the axis stopped
     * past it: 5000^2 / (2 * 10000) = 1250 counts */
    home = co402_sim_position(&fx.n[0].sim) + 30000 + 25000;
    assert_int_equal(tseed_get(&fx, 0, 0x6064, 0), home);
    assert_between(home, 25000 + 1200, 25000 + 1300);
    tb_expect_none(BUS);
}

/* --------------------------------------------- D7.8 motion task by SDO */

static void d78_motion_task_by_sdo(void **state)
{
    (void)state;
    tb_xfer(BUS, "603 2F 60 60 00 01 00 00 00", "583 60 60 60 00 00 00 00 00");
    tb_xfer(BUS, "603 2B 40 60 00 06 00 00 00", "583 60 40 60 00 00 00 00 00");
    tb_xfer(BUS, "603 2B 40 60 00 07 00 00 00", "583 60 40 60 00 00 00 00 00");
    tb_xfer(BUS, "603 2B 40 60 00 0F 00 00 00", "583 60 40 60 00 00 00 00 00");
    tb_xfer(BUS, "603 2B 80 20 00 03 00 00 00", "583 60 80 20 00 00 00 00 00");
    tb_xfer(BUS, "603 2B 40 60 00 3F 00 00 00", "583 60 40 60 00 00 00 00 00");
    /* steps 13/14: the drive reports task 3 running. The motion-task memory
     * (tasks defined with DRIVEGUI) is not simulated: 0x2080/0x2081 are
     * plain values, no task runs, and 0x2081 still reads 0. */
    tb_xfer(BUS, "603 40 81 20 00 00 00 00 00", "583 4B 81 20 00 00 00 00 00");
    tb_xfer(BUS, "603 40 80 20 00 00 00 00 00", "583 4B 80 20 00 03 00 00 00");
}

/* Plant with a home switch for D7.9 (method 12: its upper edge approached
 * from above, then the next zero mark below it). */
static void home_switch_plant(co402_sim_config_t *c)
{
    sim_cfg(c);
    c->switches = CO402_IN_HOME;
    c->home_lo = -2 * REV;
    c->home_hi = -REV - 100000;
    c->index_offset = -1200000;
}

/* ----------------------------- D7.9 profile position by PDO, homing first */

static void d79_profile_position_by_pdo(void **state)
{
    co402_sim_config_t c;
    const co_frame_t *f;
    int64_t pos;

    (void)state;
    tseed_init(&fx);
    home_switch_plant(&c);
    start_with(0, 3, &c);
    dl(3, "2F 01 16 00 00 00 00 00");
    dl(3, "23 01 16 01 20 00 7A 60");
    dl(3, "23 01 16 02 20 00 81 60");
    dl(3, "2F 01 16 00 02 00 00 00");
    dl(3, "2F 00 1A 00 00 00 00 00");
    dl(3, "23 00 1A 01 10 00 41 60");
    dl(3, "2F 00 1A 00 01 00 00 00");
    dl(3, "2F 01 1A 00 00 00 00 00");
    dl(3, "23 01 1A 01 20 00 64 60");
    dl(3, "23 01 1A 02 20 00 6C 60");
    dl(3, "2F 01 1A 00 02 00 00 00");
    dl(3, "2F 01 18 02 01 00 00 00");
    dl(3, "23 02 18 01 83 03 00 C0");
    dl(3, "23 03 18 01 83 04 00 C0");
    dl(3, "23 02 14 01 03 04 00 80");
    dl(3, "23 03 14 01 03 05 00 80");
    dl(3, "23 93 60 01 00 00 10 00"); /* 2^20 increments ... */
    dl(3, "23 93 60 02 A0 8C 00 00"); /* ... are 36000 um */
    tb_send(BUS, "000 01 03");
    tb_expect(BUS, "183 40 02"); /* step 20: event-driven TPDO1 at once */
    dl(3, "2F 60 60 00 06 00 00 00");
    dl(3, "2F 98 60 00 0C 00 00 00");
    /* step 24: 72000 um/s refused, printed exactly so; the example goes on
     * with the stored homing speeds (36000 / 4500 um/s = 1 / 0.125 rev/s) */
    tb_xfer(BUS, "603 23 99 60 01 40 19 01 00", "583 80 99 60 01 31 00 09 06");
    dl(3, "2B 40 60 00 06 00 00 00");
    tseed_run(&fx, 1000);
    tb_expect(BUS, "183 21 02");
    dl(3, "2B 40 60 00 07 00 00 00");
    tseed_run(&fx, 1000);
    tb_expect(BUS, "183 33 02");
    dl(3, "2B 40 60 00 0F 00 00 00");
    tseed_run(&fx, 1000);
    tb_expect(BUS, "183 37 02");
    tb_expect_none(BUS);
    dl(3, "2B 40 60 00 1F 00 00 00");
    /* homing runs with 0x0237 (no TPDO); at home and at rest 0x0637, one
     * tick later 0x1637 */
    (void)tseed_run_until(&fx, 0, 0x1000, 0x1000, 20000000);
    tseed_run(&fx, 1000);
    tb_expect(BUS, "183 37 06");
    tb_expect(BUS, "183 37 16");
    tb_expect_none(BUS);
    pos = tseed_get(&fx, 0, 0x6064, 0); /* at the zero mark + overshoot: 0 um */
    assert_between(pos, -100, 100);
    tb_send(BUS, "203 0F 00");
    tseed_run(&fx, 1000);
    tb_expect_none(BUS); /* homing attained stays */
    dl(3, "2F 60 60 00 01 00 00 00");
    /* The manual prints no TPDO1 between steps 38 and 45, but the mode
     * change ends "homing attained" (bit 12) and so changes the statusword:
     * 0x0237, then target reached at rest after the position window time
     * (0x6068, 10 ms): 0x0637. */
    tseed_run(&fx, 1000);
    tb_expect(BUS, "183 37 02");
    tseed_run(&fx, 12000);
    tb_expect(BUS, "183 37 06");
    /* 50 um/s^2 as the factor group reads it (ACCUNIT 3; the manual's
     * comment calls it a 50 ms ramp time, another ACCUNIT setting) */
    dl(3, "23 83 60 00 32 00 00 00");
    dl(3, "23 84 60 00 32 00 00 00");
    /* step 42: only "20 4E 00 00" printed; the target 0x8CA0 from the comment */
    tb_send(BUS, "303 A0 8C 00 00 20 4E 00 00");
    tb_send(BUS, "080");
    /* step 44: printed "BB F8 FF FF ..." (a real drive's -1861 um); here the
     * simulated axis at home: position and velocity as the dictionary has them */
    f = tseed_frame(BUS, 0x283, 8);
    assert_int_equal(tseed_i32(f, 0), tseed_get(&fx, 0, 0x6064, 0));
    assert_int_equal(tseed_i32(f, 4), tseed_get(&fx, 0, 0x606C, 0));
    assert_between(tseed_i32(f, 0), -100, 100);
    tb_expect_none(BUS);
    tb_send(BUS, "203 1F 00");
    tseed_run(&fx, 1000);
    tb_expect(BUS, "183 37 12");
    tb_send(BUS, "203 0F 00");
    tseed_run(&fx, 1000);
    tb_expect(BUS, "183 37 02");
    tb_expect_none(BUS);
    /* 36000 um at 50 um/s^2: a triangle of 2 * sqrt(36000 / 50) = 53.7 s */
    (void)tseed_run_until(&fx, 0, 0x0400, 0x0400, 60000000);
    tseed_run(&fx, 1000);
    tb_expect(BUS, "183 37 06");
    tb_expect_none(BUS);
    tb_send(BUS, "080");
    /* step 51: printed "92 FC FF FF" (garbled); here: at the target */
    f = tseed_frame(BUS, 0x283, 8);
    assert_int_equal(tseed_i32(f, 0), tseed_get(&fx, 0, 0x6064, 0));
    assert_between(tseed_i32(f, 0), 36000 - 4000, 36000 + 4000);
    assert_between(tseed_i32(f, 4), -100, 100);
    tb_expect_none(BUS);
}

/* ------------------------------------------ D7.10 ASCII channel 0x1026 */

static void d710_ascii_channel(void **state)
{
    static const char *const chars[] = {"47", "56", "20", "36", "0D", "0A"}; /* "GV 6\r\n" */
    char req[64];

    (void)state;
    for (size_t i = 0U; i < (sizeof chars / sizeof chars[0]); i++) {
        snprintf(req, sizeof req, "603 2F 26 10 01 %s 00 00 00", chars[i]);
        tb_xfer(BUS, req, "583 60 26 10 01 00 00 00 00");
    }
    /* StdOut is read-only; the ASCII interpreter behind it is not simulated */
    tb_xfer(BUS, "603 40 26 10 02 00 00 00 00", "583 4F 26 10 02 00 00 00 00");
    tb_xfer(BUS, "603 2F 26 10 02 41 00 00 00", "583 80 26 10 02 02 00 01 06");
}

/* ------------------------------------------- D7.11 SYNC test and EMCY */

static void d711_sync_and_emcy(void **state)
{
    co402_sim_t *sim = &fx.n[0].sim;
    unsigned t1[7] = {0};
    unsigned t2[7] = {0};

    (void)state;
    dl(3, "2F 01 16 00 00 00 00 00");
    dl(3, "23 01 16 01 20 00 7A 60");
    dl(3, "23 01 16 02 20 00 81 60");
    dl(3, "2F 01 16 00 02 00 00 00");
    dl(3, "2F 00 1A 00 00 00 00 00");
    dl(3, "23 00 1A 01 20 00 64 60");
    dl(3, "2F 00 1A 00 01 00 00 00");
    dl(3, "2F 00 18 02 02 00 00 00");
    dl(3, "2F 01 1A 00 00 00 00 00");
    dl(3, "23 01 1A 01 10 00 41 60");
    dl(3, "23 01 1A 02 20 00 02 10");
    /* step 12 is printed for 1601h ("2F 01 16 00 02"): meant is TPDO2's
     * count, 1A01h (the digest's correction) */
    dl(3, "2F 01 1A 00 02 00 00 00");
    dl(3, "2F 01 18 02 03 00 00 00");
    /* The example sends SYNCs without starting the node; PDOs need
     * Operational. On entering it, the still valid event-driven TPDO3 and
     * TPDO4 (statusword + position / velocity) send once. */
    tb_send(BUS, "000 01 03");
    tb_expect(BUS, "383 40 02 00 00 00 00");
    tb_expect(BUS, "483 40 02 00 00 00 00");
    tb_expect_none(BUS);
    /* "TPDO1 on every 2nd SYNC, TPDO2 on every 3rd" (the manual's 181/281
     * are node 1's COB-IDs; node 3 sends 183/283) */
    for (unsigned n = 1U; n <= 6U; n++) {
        const co_frame_t *f;
        tb_send(BUS, "080");
        while ((f = tb_next(BUS)) != NULL) {
            if (f->id == 0x183U) {
                t1[n]++;
                assert_int_equal(f->dlc, 4);
            } else if (f->id == 0x283U) {
                t2[n]++;
                assert_int_equal(f->dlc, 6);
                assert_int_equal(tseed_i16(f, 0), 0x0240);
            } else {
                fail_msg("unexpected frame %03X", (unsigned)f->id);
            }
        }
        tseed_run(&fx, 1000);
    }
    for (unsigned n = 1U; n <= 6U; n++) {
        assert_int_equal(t1[n], (n % 2U) == 0U);
        assert_int_equal(t2[n], (n % 3U) == 0U);
    }
    /* The EMCY example (resolver unplugged): error 4310h motor temperature,
     * category 1, then the state report with the register 08h as the manual
     * prints it (7 bytes, node 1; D2.8's example has the same pair with
     * category 01): the temperature bit only, not the generic bit 0
     * (CO_ERREG_GENERIC_UNCLASSIFIED; CiA 301 would give 09h). */
    tb_send(BUS, "000 80 03"); /* Pre-operational: no PDOs in between */
    co402_sim_set_fault(sim, 0x4310);
    tseed_run(&fx, 1000);
    tb_expect(BUS, "083 10 43 08 01 00 00 00 00");
    tb_expect(BUS, "083 00 00 08 00 00 00 00 00");
    tb_expect_none(BUS);
    assert_int_equal(co402_state(tseed_axis(&fx, 0)), CO402_FAULT);
    /* a further error (D2.8 transition 3): its EMCY, then the report */
    co402_sim_set_fault(sim, 0x3110);
    tseed_run(&fx, 1000);
    tb_expect(BUS, "083 10 31 0C 02 00 00 00 00");
    tb_expect(BUS, "083 00 00 0C 00 00 00 00 00");
    /* 1003h: newest first, the bare EMCY code (D8.1-9; the category is in
     * the EMCY only, CO_HISTORY_CODE_ONLY) */
    tb_xfer(BUS, "603 40 03 10 00 00 00 00 00", "583 4F 03 10 00 02 00 00 00");
    tb_xfer(BUS, "603 40 03 10 01 00 00 00 00", "583 43 03 10 01 10 31 00 00");
    tb_xfer(BUS, "603 40 03 10 02 00 00 00 00", "583 43 03 10 02 10 43 00 00");
    tb_xfer(BUS, "603 40 01 10 00 00 00 00 00", "583 4F 01 10 00 0C 00 00 00");
    /* causes gone, fault reset (bit 7): transition 2 (one cleared, register
     * shows the rest) and 4 (all cleared) */
    co402_sim_set_fault(sim, 0);
    tseed_run(&fx, 1000);
    dl(3, "2B 40 60 00 80 00 00 00");
    tseed_run(&fx, 1000);
    {
        const co_frame_t *a = tseed_frame(BUS, 0x083, 8);
        const co_frame_t *b = tseed_frame(BUS, 0x083, 8);
        TF_ASSERT_FRAME(a, "083 00 00 04 00 00 00 00 00"); /* 3110h remains */
        TF_ASSERT_FRAME(b, "083 00 00 00 00 00 00 00 00");
    }
    tb_expect_none(BUS);
    tb_xfer(BUS, "603 2F 03 10 00 00 00 00 00", "583 60 03 10 00 00 00 00 00");
    tb_xfer(BUS, "603 40 03 10 00 00 00 00 00", "583 4F 03 10 00 00 00 00 00");
}

/* ------------------------------------- D7.12 electronic gearing (no frames) */

static void d712_gearing_parameters(void **state)
{
    (void)state;
    /* GEARI 2040h sub 1 (default 1024), GEARO sub 2 (default 1), IN20TRIG
     * 20B0h, the actual values 2041h; mode 0x84 itself is not simulated */
    tb_xfer(BUS, "603 40 40 20 01 00 00 00 00", "583 43 40 20 01 00 04 00 00");
    tb_xfer(BUS, "603 40 40 20 02 00 00 00 00", "583 43 40 20 02 01 00 00 00");
    dl(3, "23 40 20 01 00 08 00 00");
    dl(3, "23 40 20 02 03 00 00 00");
    dl(3, "23 B0 20 00 10 27 00 00");
    tb_xfer(BUS, "603 40 41 20 03 00 00 00 00", "583 4F 41 20 03 00 00 00 00");
    tb_xfer(BUS, "603 2F 60 60 00 84 00 00 00", "583 80 60 60 00 30 00 09 06");
}

/* ------------------------------- D7.13 interpolated position, two axes */

static void ip_config_axis(uint8_t id)
{
    /* communication parameters (steps 1..20), "same for axis 2" */
    char d[40];
    dl(id, "2F 01 14 02 01 00 00 00");
    dl(id, "2F 01 18 02 01 00 00 00");
    snprintf(d, sizeof d, "23 02 18 01 %02X 03 00 C0", 0x80U + id);
    dl(id, d);
    snprintf(d, sizeof d, "23 03 18 01 %02X 04 00 C0", 0x80U + id);
    dl(id, d);
    dl(id, "2F 60 60 00 07 00 00 00");
    dl(id, "2F C2 60 01 01 00 00 00");
    /* "60C1" in the text: the period is 60C2h sub 2 = -3 (1 ms) */
    dl(id, "2F C2 60 02 FD 00 00 00");
}

static void ip_start_axis(uint8_t id)
{
    char rx[16];
    char tx[16];
    static const char *const steps[][2] = {
        {"06 00", "21 02"}, {"07 00", "33 02"}, {"0F 00", "37 02"}, {"1F 00", "37 12"}};

    for (size_t i = 0U; i < 4U; i++) {
        snprintf(rx, sizeof rx, "%03X %s", 0x200U + id, steps[i][0]);
        snprintf(tx, sizeof tx, "%03X %s", 0x180U + id, steps[i][1]);
        tb_send(BUS, rx);
        tseed_run(&fx, 1000);
        tb_expect(BUS, tx);
        tb_expect_none(BUS);
    }
}

static void d713_ip_two_axes(void **state)
{
    co402_sim_config_t c;
    const co_frame_t *f;

    (void)state;
    tseed_init(&fx);
    sim_cfg(&c);
    start_with(0, 1, &c);
    start_with(1, 2, &c);
    /* RPDO2 of axis 1: its set-point in bytes 0..3, the write dummy after */
    dl(1, "2F 01 16 00 00 00 00 00");
    dl(1, "23 01 16 01 20 01 C1 60");
    dl(1, "23 01 16 02 20 00 00 21");
    dl(1, "2F 01 16 00 02 00 00 00");
    /* axis 2: the dummy first, its set-point in bytes 4..7 */
    dl(2, "2F 01 16 00 00 00 00 00");
    dl(2, "23 01 16 01 20 00 00 21");
    dl(2, "23 01 16 02 20 01 C1 60");
    dl(2, "2F 01 16 00 02 00 00 00");
    /* step 9: axis 2 listens on axis 1's COB-ID 301h. The S300 takes the new
     * CAN-ID while RPDO2 is valid (set.pdo.cob_id_while_valid; CiA 301
     * would want it invalid first, 0x06090030) */
    tb_xfer(BUS, "602 23 01 14 01 01 03 00 00", "582 60 01 14 01 00 00 00 00");
    assert_int_equal(tseed_get(&fx, 1, 0x1401, 1), 0x00000301);
    /* TPDO2 of both axes: 6063h and the manufacturer status 1002h (the
     * manual's comment "dummy" is misprinted) */
    for (uint8_t id = 1U; id <= 2U; id++) {
        dl(id, "2F 01 1A 00 00 00 00 00");
        dl(id, "23 01 1A 01 20 00 63 60");
        dl(id, "23 01 1A 02 20 00 02 10");
        dl(id, "2F 01 1A 00 02 00 00 00");
    }
    ip_config_axis(1);
    ip_config_axis(2);
    /* NMT: printed "01 01" with the comment "for all axes"; node-ID 1 starts
     * node 1 only. The strict answer to the printed frame: */
    tb_send(BUS, "000 01 01");
    tb_expect(BUS, "181 40 02"); /* TPDO1 (statusword, event-driven) at once, as D7.9 step 20 */
    tb_expect_none(BUS);
    assert_int_equal(co_node_nmt_state(&kn[1].node), CO_NMT_PRE_OPERATIONAL);
    /* "for all axes" needs node-ID 0 */
    tb_send(BUS, "000 01 00");
    tb_expect(BUS, "182 40 02");
    tb_expect_none(BUS);
    /* Ready to switch on is printed 0x0231 here but 0x0221 in D7.9: bit 4 is
     * the power stage (0x0240 at boot in both); the device answers 0x0221 */
    ip_start_axis(1);
    ip_start_axis(2); /* "shown for axis 1" */
    /* cyclic operation: 500 and 1000 increments, taken at the SYNC */
    tb_send(BUS, "301 F4 01 00 00 E8 03 00 00");
    tb_expect_none(BUS);
    assert_int_equal(tseed_get(&fx, 0, 0x60C1, 1), 0);
    tb_send(BUS, "080");
    assert_int_equal(tseed_get(&fx, 0, 0x60C1, 1), 500);
    assert_int_equal(tseed_get(&fx, 1, 0x60C1, 1), 1000);
    /* The answers are printed on 181h/182h but are TPDO2 (281h/282h); the
     * positions 0x123 / 0x2A5 and status 0x44030000 are a real drive's. At
     * this SYNC the axes still stand where they were: 6063h as the
     * dictionary holds it, 1002h 0 (the manufacturer status is not simulated) */
    f = tseed_frame(BUS, 0x281, 8);
    assert_int_equal(tseed_i32(f, 0), tseed_get(&fx, 0, 0x6063, 0));
    assert_int_equal(tseed_i32(f, 4), 0);
    f = tseed_frame(BUS, 0x282, 8);
    assert_int_equal(tseed_i32(f, 0), tseed_get(&fx, 1, 0x6063, 0));
    tb_expect_none(BUS);
    /* the set-points are reached within the period (1 ms), the position
     * loop has settled 200 ms later */
    tseed_run(&fx, 200000);
    tb_send(BUS, "080");
    f = tseed_frame(BUS, 0x281, 8);
    assert_between(tseed_i32(f, 0), 495, 505);
    f = tseed_frame(BUS, 0x282, 8);
    assert_between(tseed_i32(f, 0), 995, 1005);
    tb_expect_none(BUS);
    /* EMCY during the run as printed: 4310h on axis 1, register 08h,
     * category 01, then the state report with register 08h; the fault
     * reaction changes the statusword of TPDO1 */
    co402_sim_set_fault(&fx.n[0].sim, 0x4310);
    tseed_run(&fx, 1000);
    tb_expect(BUS, "081 10 43 08 01 00 00 00 00");
    tb_expect(BUS, "081 00 00 08 00 00 00 00 00");
    /* the axis stands: the fault reaction (quick-stop ramp) ends in the
     * same tick, Fault with the power stage off */
    tseed_run(&fx, 1000);
    tb_expect(BUS, "181 08 02");
    tseed_run(&fx, 100000);
    tb_expect_none(BUS);
    assert_int_equal(co402_state(tseed_axis(&fx, 0)), CO402_FAULT);
    assert_int_equal(co402_state(tseed_axis(&fx, 1)), CO402_OPERATION_ENABLED);
}

/* --------------------------------------- D2.4, D2.5: response monitoring */

/* Node guarding with guard time 100 ms x life time factor 3, armed by the
 * first request (§5.2.1.10). On expiry the drive shows warning n04 (2000h
 * bit 3; statusword bits 7 and 11), brakes on the quick-stop ramp 6085h and
 * blocks further motion; no NMT change (no 1029h, D8.1-22). The manual
 * lists no EMCY code for it: the core sends CiA 301's 8130h (error register
 * 10h, communication, no generic bit), paired with the state report.
 * Controlword bit 7 (fault reset) clears n04 (D6.2), then the drive moves
 * again. */
static void guarding_loss_is_warning_n04(void **state)
{
    (void)state;
    /* TPDO3 / TPDO4 (actual values on every change) off, as the examples do */
    dl(3, "23 02 18 01 83 03 00 C0");
    dl(3, "23 03 18 01 83 04 00 C0");
    dl(3, "2B 0C 10 00 64 00 00 00");
    dl(3, "2F 0D 10 00 03 00 00 00");
    dl(3, "2F 60 60 00 03 00 00 00");
    dl(3, "23 85 60 00 00 00 10 00"); /* 2^20 units/s^2 */
    dl(3, "2B 40 60 00 06 00 00 00");
    dl(3, "2B 40 60 00 07 00 00 00");
    dl(3, "2B 40 60 00 0F 00 00 00");
    dl(3, "23 FF 60 00 00 00 01 00"); /* 65536 units/s */
    /* Operational: TPDO1 and TPDO2 (statusword, mode) send once */
    tb_send(BUS, "000 01 03");
    tb_expect(BUS, "183 37 02");
    tb_expect(BUS, "283 37 02 03");
    tb_expect_none(BUS);
    /* the first guarding request arms life guarding (Operational: 05) */
    tb_xfer(BUS, "703 R1", "703 05");
    tseed_run(&fx, 100000);
    assert_between(tseed_get(&fx, 0, 0x606C, 0), 65000, 66000);
    assert_int_equal(tseed_sw(&fx, 0), 0x0637);
    tb_flush(BUS);
    tseed_run(&fx, 199000);
    tb_expect_none(BUS);
    tseed_run(&fx, 1000);
    tb_expect(BUS, "083 30 81 10 00 00 00 00 00");
    tb_expect(BUS, "083 00 00 10 00 00 00 00 00");
    /* n04: warning (bit 7) and internal limit (bit 11) in the statusword */
    tb_expect(BUS, "183 B7 0E");
    tb_expect(BUS, "283 B7 0E 03");
    tb_expect_none(BUS);
    assert_int_equal(co_node_nmt_state(&kn[0].node), CO_NMT_OPERATIONAL);
    assert_int_equal(co402_state(tseed_axis(&fx, 0)), CO402_OPERATION_ENABLED);
    assert_int_equal(tseed_get(&fx, 0, 0x2000, 0), 0x00000008);
    /* the quick-stop ramp: 65536 units/s at 2^20 units/s^2, 62.5 ms */
    tseed_run(&fx, 70000);
    assert_between(tseed_get(&fx, 0, 0x606C, 0), -1000, 1000);
    tb_expect_none(BUS);
    /* further motion is blocked: a new set-point, enable operation again */
    dl(3, "23 FF 60 00 00 80 00 00"); /* 32768 units/s */
    dl(3, "2B 40 60 00 0F 00 00 00");
    tseed_run(&fx, 100000);
    assert_between(tseed_get(&fx, 0, 0x606C, 0), -1000, 1000);
    tb_expect_none(BUS);
    /* the master guards again: the EMCY ends (error register 00h), n04 stays */
    tb_send(BUS, "703 R1");
    tb_expect(BUS, "703 85");
    tb_expect(BUS, "083 00 00 00 00 00 00 00 00");
    tb_expect_none(BUS);
    tseed_run(&fx, 1000);
    assert_int_equal(tseed_get(&fx, 0, 0x2000, 0), 0x00000008);
    assert_int_equal(tseed_sw(&fx, 0), 0x0EB7);
    /* fault reset (bit 7; 0x008F decodes as enable operation, bit 7 don't
     * care): n04 ends, the statusword shows it, the axis takes the set-point */
    dl(3, "2B 40 60 00 8F 00 00 00");
    tseed_run(&fx, 1000);
    tb_expect(BUS, "183 37 02");
    tb_expect(BUS, "283 37 02 03");
    assert_int_equal(tseed_get(&fx, 0, 0x2000, 0), 0);
    tb_send(BUS, "703 R1");
    tb_expect(BUS, "703 05");
    tseed_run(&fx, 100000);
    tb_flush(BUS);
    assert_between(tseed_get(&fx, 0, 0x606C, 0), 32268, 33268);
}

/* -------------------------------------------- D8.1: further deviations */

static void quick_stop_and_bit7(void **state)
{
    co402_axis_t *ax = tseed_axis(&fx, 0);

    (void)state;
    /* device-control commands with bit 7 set: decoded as without it */
    dl(3, "2B 40 60 00 86 00 00 00");
    assert_int_equal(co402_state(ax), CO402_READY);
    dl(3, "2B 40 60 00 07 00 00 00");
    dl(3, "2B 40 60 00 0F 00 00 00");
    /* quick stop in pv: the emergency ramp (6085h), stay in Quick stop
     * active (0x0617 at rest), the set-points deleted; bit 2 again: 16 */
    dl(3, "2F 60 60 00 03 00 00 00");
    dl(3, "23 85 60 00 00 00 10 00"); /* 2^20 units/s^2 */
    dl(3, "23 FF 60 00 00 00 01 00"); /* 65536 units/s */
    tseed_run(&fx, 100000);
    assert_between(tseed_get(&fx, 0, 0x606C, 0), 65000, 66000);
    dl(3, "2B 40 60 00 0B 00 00 00");
    assert_int_equal(co402_state(ax), CO402_QUICK_STOP_ACTIVE);
    assert_int_equal(tseed_get(&fx, 0, 0x60FF, 0), 0);
    tseed_run(&fx, 200000);
    assert_int_equal(tseed_sw(&fx, 0), 0x0617);
    assert_int_equal(co402_state(ax), CO402_QUICK_STOP_ACTIVE);
    assert_between(tseed_get(&fx, 0, 0x606C, 0), -100, 100);
    dl(3, "2B 40 60 00 0F 00 00 00");
    assert_int_equal(co402_state(ax), CO402_OPERATION_ENABLED);
    tseed_run(&fx, 100000);
    assert_between(tseed_get(&fx, 0, 0x606C, 0), -100, 100); /* no set-point left */
}

static void event_timer_and_mapping(void **state)
{
    (void)state;
    /* the TPDO event timer counts in 100 us: 20 = 2 ms */
    dl(3, "2B 00 18 05 14 00 00 00");
    tb_send(BUS, "000 01 03");
    tb_expect(BUS, "183 40 02");
    tb_expect(BUS, "283 40 02 01");
    tb_expect(BUS, "383 40 02 00 00 00 00");
    tb_expect(BUS, "483 40 02 00 00 00 00");
    for (unsigned i = 0U; i < 3U; i++) {
        tseed_run(&fx, 1000);
        tb_expect_none(BUS);
        tseed_run(&fx, 1000);
        tb_expect(BUS, "183 40 02");
        tb_expect_none(BUS);
    }
    /* TPDOs answer no RTR (COB-ID bit 30) */
    tb_send(BUS, "183 R");
    tb_expect_none(BUS);
    /* mapping entries are written with the PDO valid (outside Operational) */
    tb_send(BUS, "000 80 03");
    dl(3, "2F 00 1A 00 00 00 00 00");
    dl(3, "23 00 1A 01 10 00 41 60");
    dl(3, "23 00 1A 02 20 00 02 10");
    dl(3, "2F 00 1A 00 02 00 00 00");
    /* ... but not in Operational */
    tb_send(BUS, "000 01 03");
    tb_flush(BUS);
    tb_xfer(BUS, "603 2F 00 1A 00 00 00 00 00", "583 80 00 1A 00 22 00 00 08");
    /* objects that may not be mapped: 0604 0041h */
    tb_send(BUS, "000 80 03");
    dl(3, "2F 00 1A 00 00 00 00 00");
    tb_xfer(BUS, "603 23 00 1A 01 20 00 10 10", "583 80 00 1A 01 41 00 04 06");
    /* mappings are taken over byte-wise only (D4.1, CO_PDO_MAP_BYTES):
     * 4 or 12 bits of the statusword are refused (the manual names no code
     * for it; 0604 0041h, "cannot be mapped", is in its list), whole bytes
     * of it are taken */
    tb_xfer(BUS, "603 23 00 1A 01 04 00 41 60", "583 80 00 1A 01 41 00 04 06");
    tb_xfer(BUS, "603 23 00 1A 01 0C 00 41 60", "583 80 00 1A 01 41 00 04 06");
    dl(3, "23 00 1A 01 08 00 41 60");
    dl(3, "2F 00 1A 00 01 00 00 00");
    tb_send(BUS, "000 01 03");
    tb_expect(BUS, "183 40");
    tb_flush(BUS);
}

/* D4.5: the TPDO change masks 2014h..2017h (CO_TPDO_MASK_255). The
 * manual's purpose: report a position only once per revolution by masking
 * its low bits. TPDO3 (statusword + position, type FFh) with 2016h sub 1 =
 * 0000FFFFh (bytes 0..3: the statusword, not the position's low word) and
 * sub 2 = 0000FFF0h (bytes 4..5: position bits 20..31, whole revolutions of
 * 2^20 increments). */
static void d45_tpdo_masks(void **state)
{
    const co_frame_t *f;
    int32_t last_rev = 0;
    uint16_t last_sw = 0x0240;
    unsigned revs = 0U;

    (void)state;
    dl(3, "23 01 18 01 83 02 00 C0"); /* TPDO2 and TPDO4 off (D7.5) */
    dl(3, "23 03 18 01 83 04 00 C0");
    tb_xfer(BUS, "603 40 16 20 01 00 00 00 00", "583 43 16 20 01 FF FF FF FF"); /* default */
    dl(3, "23 16 20 01 FF FF 00 00");
    dl(3, "23 16 20 02 F0 FF 00 00");
    dl(3, "2F 60 60 00 03 00 00 00");
    tb_send(BUS, "000 01 03");
    tb_expect(BUS, "183 40 02");
    tb_expect(BUS, "383 40 02 00 00 00 00"); /* the first one is always sent */
    tb_expect_none(BUS);
    enable_by_sdo();
    dl(3, "23 FF 60 00 00 00 10 00"); /* 2^20 units/s: one revolution per second */
    tseed_run(&fx, 3500000);
    /* every TPDO3 is a statusword change (with TPDO1) or a new revolution */
    while ((f = tb_next(BUS)) != NULL) {
        uint16_t sw = (uint16_t)tseed_i16(f, 0);
        if (f->id == 0x183U) {
            assert_int_equal(f->dlc, 2); /* TPDO1: each statusword change */
            assert_int_not_equal(sw, last_sw);
            f = tseed_frame(BUS, 0x383, 6); /* TPDO3 with it */
            assert_int_equal(tseed_i16(f, 0), (int16_t)sw);
        } else {
            /* TPDO3 alone: not the statusword, a new revolution just begun */
            assert_int_equal(f->id, 0x383U);
            assert_int_equal(f->dlc, 6);
            assert_int_equal(sw, last_sw);
            assert_int_equal(tseed_i32(f, 2) >> 20, last_rev + 1);
            assert_between(tseed_i32(f, 2) & 0xFFFFF, 0, 2000);
            revs++;
        }
        last_sw = sw;
        last_rev = tseed_i32(f, 2) >> 20;
    }
    /* 3.5 s at 1 rev/s after the acceleration: revolutions 1, 2, 3 */
    assert_int_equal(tseed_get(&fx, 0, 0x6064, 0) >> 20, 3);
    assert_int_equal(revs, 3U);
    /* the masks are plain rw values: 0 silences position changes entirely */
    dl(3, "23 16 20 02 00 00 00 00");
    tseed_run(&fx, 1500000);
    tb_expect_none(BUS);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(identity, setup),
        cmocka_unit_test_setup(d71_free_mapping, setup),
        cmocka_unit_test_setup(d72_state_machine_by_sdo, setup),
        cmocka_unit_test_setup(d73_jog_by_sdo, setup),
        cmocka_unit_test_setup(d74_torque_by_sdo, setup),
        cmocka_unit_test_setup(d75_jog_by_pdo, setup),
        cmocka_unit_test_setup(d76_torque_by_pdo, setup),
        cmocka_unit_test_setup(d77_homing_by_sdo, setup),
        cmocka_unit_test_setup(d78_motion_task_by_sdo, setup),
        cmocka_unit_test_setup(d79_profile_position_by_pdo, setup),
        cmocka_unit_test_setup(d710_ascii_channel, setup),
        cmocka_unit_test_setup(d711_sync_and_emcy, setup),
        cmocka_unit_test_setup(d712_gearing_parameters, setup),
        cmocka_unit_test_setup(d713_ip_two_axes, setup),
        cmocka_unit_test_setup(guarding_loss_is_warning_n04, setup),
        cmocka_unit_test_setup(quick_stop_and_bit7, setup),
        cmocka_unit_test_setup(event_timer_and_mapping, setup),
        cmocka_unit_test_setup(d45_tpdo_masks, setup),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
