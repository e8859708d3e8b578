/*
 * SSD Drives 630 (devices/ssd-630.toml with the CiA 402 profile on the
 * simulated motor): the worked examples of the CANopen-630 manual §14 as the
 * digest shared/spec/seed-002-ssd-drives-630.md lists them (D§7.1 ..
 * D§7.13), frame by frame, node 1. Frames printed with 7 bytes are sent
 * normalised to 8 (D§7). Where the digest corrects a frame, the printed one
 * is sent first when the digest names the strict answer to it, then the
 * corrected one. Measured values of a real drive are replaced by the
 * simulated ones the dictionary holds, with the layout asserted. Frames the
 * manual does not print but the device must send are asserted too, with the
 * reason. D§8.4's derived vectors and the deviations of D§8.1 follow.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "co_devices.h"
#include "ssd_630.h"
#include "test_frames.h"
#include "tseed.h"

static tseed_t fx;
static ssd_630_node_t sn[TSEED_NODES];
#define BUS (&fx.bus)
#define AX (tseed_axis(&fx, 0))

/* Power on node @p id in slot @p k; expects the boot-up and the boot EMCY
 * with the firmware string "V819d". */
static void power_on(unsigned k, uint8_t id, const co402_sim_config_t *sim)
{
    co_node_config_t cfg;

    ssd_630_config(&sn[k], &cfg);
    tseed_start(&fx, k, &co_device_ssd_630, &cfg, &sn[k].node, id, sim);
    tseed_expectf(BUS, "%03X 00", 0x700U + id);
    tseed_expectf(BUS, "%03X 00 00 00 56 38 31 39 64", 0x80U + id);
}

static void sim_at(co402_sim_config_t *c, int32_t start)
{
    co402_params_sim_config(co402_device_params(&co_device_ssd_630), c);
    c->start_pos = start;
}

static int setup(void **state)
{
    (void)state;
    tseed_init(&fx);
    memset(sn, 0, sizeof sn);
    power_on(0, 1, NULL);
    return 0;
}

static void dl(const char *data)
{
    char req[64];
    char resp[64];

    snprintf(req, sizeof req, "601 %s", data);
    snprintf(resp, sizeof resp, "581 60 %.8s 00 00 00 00", &data[3]);
    tb_xfer(BUS, req, resp);
}

static void expect_sw(uint16_t sw)
{
    char resp[64];

    snprintf(resp, sizeof resp, "581 4B 41 60 00 %02X %02X 00 00", sw & 0xFFU, sw >> 8);
    tb_xfer(BUS, "601 40 41 60 00 00 00 00 00", resp);
}

/* D§7.8, the reconstructed "steps 1-4": Switch on disabled + remote, then
 * Shutdown, Switch on, Enable operation; at rest in pp: target reached. */
static void steps_1_to_4(void)
{
    expect_sw(0x0240);
    dl("2B 40 60 00 06 00 00 00");
    expect_sw(0x0221);
    dl("2B 40 60 00 07 00 00 00");
    expect_sw(0x0223);
    dl("2B 40 60 00 0F 00 00 00");
    tseed_run(&fx, 2000);
    expect_sw(0x0627);
    assert_int_equal(co402_state(AX), CO402_OPERATION_ENABLED);
}

/* ------------------------------------------------------------ boot */

static void boot_and_error_control(void **state)
{
    (void)state;
    /* D§1.4: Pre-operational by itself, mode 1 after power-on, 0x0240 */
    assert_int_equal(co_node_nmt_state(&sn[0].node), CO_NMT_PRE_OPERATIONAL);
    tb_xfer(BUS, "601 40 61 60 00 00 00 00 00", "581 4F 61 60 00 01 00 00 00");
    tb_xfer(BUS, "601 40 60 60 00 00 00 00 00", "581 4F 60 60 00 01 00 00 00");
    expect_sw(0x0240);
    /* D§8.4: guarding replies, toggling (life guarding is never armed) */
    tb_xfer(BUS, "701 R", "701 7F");
    tb_xfer(BUS, "701 R", "701 FF");
    /* guard time and life time factor read 0, not writable (§11) */
    tb_xfer(BUS, "601 40 0C 10 00 00 00 00 00", "581 4B 0C 10 00 00 00 00 00");
    tb_xfer(BUS, "601 40 0D 10 00 00 00 00 00", "581 4F 0D 10 00 00 00 00 00");
    tb_xfer(BUS, "601 2B 0C 10 00 64 00 00 00", "581 80 0C 10 00 00 00 01 06");
    /* no heartbeat: 1016h/1017h do not exist (answered 0x06010000) */
    tb_xfer(BUS, "601 40 17 10 00 00 00 00 00", "581 80 17 10 00 00 00 01 06");
    tb_xfer(BUS, "601 40 16 10 00 00 00 00 00", "581 80 16 10 00 00 00 01 06");
    /* old CiA 301 objects: 1004h (sub 0 UNSIGNED32: 4 RPDOs, 4 TPDOs), 100Bh */
    tb_xfer(BUS, "601 40 04 10 00 00 00 00 00", "581 43 04 10 00 04 00 04 00");
    tb_xfer(BUS, "601 40 0B 10 00 00 00 00 00", "581 43 0B 10 00 01 00 00 00");
    tb_xfer(BUS, "601 40 04 48 01 00 00 00 00", "581 4F 04 48 01 01 00 00 00");
    tb_xfer(BUS, "601 40 04 48 05 00 00 00 00", "581 4F 04 48 05 04 00 00 00");
    /* no block transfer: a block upload request is refused */
    tb_xfer(BUS, "601 A0 08 10 00 7F 00 00 00", "581 80 08 10 00 01 00 04 05");
    /* D3.2: no segmented download (expedited and segmented upload only):
     * its initiate is refused with 0x06010000, the drive's "not supported"
     * (D3.3 lists no 0x0504xxxx code); the same value expedited is taken */
    tb_xfer(BUS, "601 21 81 60 00 04 00 00 00", "581 80 81 60 00 00 00 01 06");
    tb_xfer(BUS, "601 20 81 60 00 00 00 00 00", "581 80 81 60 00 00 00 01 06");
    tb_xfer(BUS, "601 23 81 60 00 E8 03 00 00", "581 60 81 60 00 00 00 00 00");
    tb_xfer(BUS, "601 40 81 60 00 00 00 00 00", "581 43 81 60 00 E8 03 00 00");
    /* PDOs do not run in Pre-operational */
    tb_send(BUS, "201 06 00");
    tseed_run(&fx, 2000);
    tb_expect_none(BUS);
    assert_int_equal(co402_state(AX), CO402_SWITCH_ON_DISABLED);
    /* reset communication: boot-up and the boot EMCY again */
    tb_send(BUS, "000 82 01");
    tb_expect(BUS, "701 00");
    tb_expect(BUS, "081 00 00 00 56 38 31 39 64");
    tb_expect_none(BUS);
}

/* ------------------------------------------------ D§7.1 .. D§7.7: SDO */

static void ex141_to_147_sdo(void **state)
{
    co402_sim_config_t c;

    (void)state;
    /* 14.1: a missing index answers "access not supported" */
    tb_xfer(BUS, "601 40 34 12 00 00 00 00 00", "581 80 34 12 00 00 00 01 06");
    /* 14.2: modes of operation 9 is refused */
    tb_xfer(BUS, "601 2F 60 60 00 09 00 00 00", "581 80 60 60 00 30 00 09 06");
    /* 14.3: device type */
    tb_xfer(BUS, "601 40 00 10 00 00 00 00 00", "581 43 00 10 00 92 01 02 00");
    /* 14.4: the frame reads 1018h sub 0; printed with the value 0, the
     * identity has 4 entries. The error register the title means: */
    tb_xfer(BUS, "601 40 18 10 00 00 00 00 00", "581 4F 18 10 00 04 00 00 00");
    tb_xfer(BUS, "601 40 01 10 00 00 00 00 00", "581 4F 01 10 00 00 00 00 00");
    /* 14.5: manufacturer status register 0 (drive enabled, no error) */
    tb_xfer(BUS, "601 40 02 10 00 00 00 00 00", "581 43 02 10 00 00 00 00 00");
    /* 14.6: the node-ID; printed on 601h with the answer 4: node 4 answers
     * on 604h/584h, node 1 reads 1 */
    sim_at(&c, 0);
    power_on(1, 4, &c);
    tb_xfer(BUS, "604 40 0B 10 00 00 00 00 00", "584 43 0B 10 00 04 00 00 00");
    tb_xfer(BUS, "601 40 0B 10 00 00 00 00 00", "581 43 0B 10 00 01 00 00 00");
    /* 14.7: segmented upload of "631_402"; the segment request carries
     * index and sub-index in bytes 1..3, which the server ignores */
    tb_xfer(BUS, "601 40 08 10 00 00 00 00 00", "581 41 08 10 00 07 00 00 00");
    tb_xfer(BUS, "601 60 08 10 00 00 00 00 00", "581 01 36 33 31 5F 34 30 32");
    tb_xfer(BUS, "601 40 0A 10 00 00 00 00 00", "581 41 0A 10 00 05 00 00 00");
    tb_xfer(BUS, "601 60 00 00 00 00 00 00 00", "581 05 56 38 31 39 64 00 00");
}

/* ----------------------------------- D§7.8 / D§7.9: pp through SDO */

static void ex149_pp_by_sdo(void **state)
{
    (void)state;
    steps_1_to_4();
    dl("23 81 60 00 E8 03 00 00"); /* 5: 1000 rpm */
    /* 6: printed with 2B (2 bytes) and "68" for 86: the strict answer is a
     * length error; then 0x607A = 100000 */
    tb_xfer(BUS, "601 2B 7A 60 00 A0 68 01 00", "581 80 7A 60 00 10 00 07 06");
    dl("23 7A 60 00 A0 86 01 00");
    expect_sw(0x0627);
    dl("2B 40 60 00 5F 00 00 00"); /* 7: new set-point, relative */
    tseed_run(&fx, 5000);
    expect_sw(0x9227); /* acknowledged, moving */
    dl("2B 40 60 00 0F 00 00 00"); /* 8 */
    tseed_run(&fx, 1000);
    expect_sw(0x0227);
    /* 100000 increments at 1000 rpm (68267 increments/s): 1.6 s */
    (void)tseed_run_until(&fx, 0, 0x0400, 0x0400, 3000000);
    expect_sw(0x0627);
    assert_between(tseed_get(&fx, 0, 0x6064, 0), 100000 - 100, 100000 + 100);
    dl("23 81 60 00 64 00 00 00"); /* 9: 100 rpm */
    /* 10: printed with 2B; -100000 */
    tb_xfer(BUS, "601 2B 7A 60 00 60 79 FE FF", "581 80 7A 60 00 10 00 07 06");
    dl("23 7A 60 00 60 79 FE FF");
    expect_sw(0x0627);
    dl("2B 40 60 00 5F 00 00 00"); /* 11 */
    tseed_run(&fx, 5000);
    expect_sw(0x9227);
    dl("2B 40 60 00 0F 00 00 00"); /* 12 */
    /* back at 100 rpm (6827 increments/s): 14.6 s */
    (void)tseed_run_until(&fx, 0, 0x0400, 0x0400, 16000000);
    expect_sw(0x0627);
    assert_between(tseed_get(&fx, 0, 0x6064, 0), -100, 100);
    tb_expect_none(BUS);
}

/* --------------------------------------------- D§7.10: homing through SDO */

static void ex1410_homing_by_sdo(void **state)
{
    co402_sim_config_t c;

    (void)state;
    tseed_init(&fx);
    sim_at(&c, 1000); /* index pulses every 4096 increments */
    power_on(0, 1, &c);
    steps_1_to_4();
    /* 5: the stray 03 in byte 5 is not part of a 1-byte download */
    dl("2F 60 60 00 06 03 00 00");
    tb_xfer(BUS, "601 40 61 60 00 00 00 00 00", "581 4F 61 60 00 06 00 00 00");
    dl("23 99 60 01 32 00 00 00"); /* 7: 50 rpm */
    dl("2F 98 60 00 E8 00 00 00"); /* 8: -24, next zero pulse, positive */
    dl("2B 40 60 00 1F 00 00 00"); /* 9: start */
    tseed_run(&fx, 5000);
    expect_sw(0x0227); /* searching */
    /* home found: 0x9227 while the axis stops, then at rest 0x9627 */
    (void)tseed_run_until(&fx, 0, 0x1000, 0x1000, 3000000);
    expect_sw(0x9227);
    (void)tseed_run_until(&fx, 0, 0x1400, 0x1400, 100000);
    /* 10: homing attained, target reached, bit 15 with bit 12 */
    tb_xfer(BUS, "601 40 41 60 00 00 00 00 00", "581 4B 41 60 00 27 96 00 00");
    /* the zero pulse at 4096 is now position 0 (home offset 0) */
    assert_int_equal(tseed_get(&fx, 0, 0x6064, 0), co402_sim_position(&fx.n[0].sim) - 4096);
    assert_between(tseed_get(&fx, 0, 0x6064, 0), 0, 200);
    dl("2B 40 60 00 0F 00 00 00"); /* 11 */
    /* 12: printed as a 1-byte write to the controlword: a length error;
     * meant is 0x6060 = 1 */
    tb_xfer(BUS, "601 2F 40 60 00 01 00 00 00", "581 80 40 60 00 10 00 07 06");
    dl("2F 60 60 00 01 00 00 00");
    tb_xfer(BUS, "601 40 61 60 00 00 00 00 00", "581 4F 61 60 00 01 00 00 00");
    tb_expect_none(BUS);
}

/* ------------------------------------------ D§7.11: pp through PDO */

static void ex1411_pp_by_pdo(void **state)
{
    (void)state;
    steps_1_to_4();
    dl("23 00 14 01 01 02 00 00");
    dl("23 00 18 01 81 01 00 00");
    dl("23 81 60 00 E8 03 00 00");
    dl("23 7A 60 00 A0 86 01 00");
    /* 5: start. The event-driven TPDO1 and TPDO2 (valid by default, both
     * with the statusword) send their data once on entering Operational;
     * the manual's trace shows TPDO1's changes only. */
    tb_send(BUS, "000 01 01");
    tb_expect(BUS, "181 27 06");
    tb_expect(BUS, "281 27 06 01");
    tb_expect_none(BUS);
    tb_send(BUS, "201 5F 00"); /* 6 */
    tseed_run(&fx, 1000);
    tb_expect(BUS, "181 27 96"); /* 7: acknowledged, target reached still set */
    tb_expect(BUS, "281 27 96 01");
    tseed_run(&fx, 1000);
    tb_expect(BUS, "181 27 92"); /* 8: moving */
    tb_expect(BUS, "281 27 92 01");
    tb_expect_none(BUS);
    (void)tseed_run_until(&fx, 0, 0x0400, 0x0400, 3000000);
    tseed_run(&fx, 1000);
    tb_expect(BUS, "181 27 96"); /* 9: target reached */
    tb_expect(BUS, "281 27 96 01");
    tb_expect_none(BUS);
    /* 10: printed on 180h, which is not this drive's: nothing happens */
    tb_send(BUS, "180 4F 00");
    tseed_run(&fx, 2000);
    tb_expect_none(BUS);
    tb_send(BUS, "201 4F 00");
    tseed_run(&fx, 1000);
    tb_expect(BUS, "181 27 06"); /* 11 */
    tb_expect(BUS, "281 27 06 01");
    tb_expect_none(BUS);
    /* 12: printed as a read of 6061h (with junk data): answered as a read;
     * meant is 607Ah = -100000 */
    tb_xfer(BUS, "601 40 61 60 00 60 79 FE FF", "581 4F 61 60 00 01 00 00 00");
    dl("23 7A 60 00 60 79 FE FF");
    /* 13: again as in step 6: relative -100000, back to 0 */
    tb_send(BUS, "201 5F 00");
    tseed_run(&fx, 2000);
    tb_expect(BUS, "181 27 96");
    tb_expect(BUS, "281 27 96 01");
    tb_expect(BUS, "181 27 92");
    tb_expect(BUS, "281 27 92 01");
    (void)tseed_run_until(&fx, 0, 0x0400, 0x0400, 3000000);
    tb_flush(BUS);
    assert_between(tseed_get(&fx, 0, 0x6064, 0), -100, 100);
}

/* §11 (D§4.4): the transmit masks 2014h..2017h apply to transmission type
 * 254 (CO_TPDO_MASK_254). 14.11 again with TPDO1 of type 254 and 2014h
 * sub 1 = 0000006Fh, the state bits of the statusword: the set-point
 * handshake (bits 10, 12, 15) sends nothing, a state change does. TPDO2
 * (type 255) sends every change, as before. */
static void tpdo_masks_type_254(void **state)
{
    (void)state;
    steps_1_to_4();
    dl("23 00 14 01 01 02 00 00");
    dl("23 00 18 01 81 01 00 00");
    dl("2F 00 18 02 FE 00 00 00");
    tb_xfer(BUS, "601 40 14 20 01 00 00 00 00", "581 43 14 20 01 FF FF FF FF"); /* default */
    dl("23 14 20 01 6F 00 00 00");
    dl("23 81 60 00 E8 03 00 00");
    dl("23 7A 60 00 A0 86 01 00");
    tb_send(BUS, "000 01 01");
    tb_expect(BUS, "181 27 06"); /* the first transmission is not filtered */
    tb_expect(BUS, "281 27 06 01");
    tb_expect_none(BUS);
    tb_send(BUS, "201 5F 00");
    tseed_run(&fx, 1000);
    tb_expect(BUS, "281 27 96 01"); /* set-point acknowledged: TPDO2 only */
    tseed_run(&fx, 1000);
    tb_expect(BUS, "281 27 92 01");
    tb_expect_none(BUS);
    (void)tseed_run_until(&fx, 0, 0x0400, 0x0400, 3000000);
    tseed_run(&fx, 1000);
    tb_expect(BUS, "281 27 96 01");
    tb_send(BUS, "201 4F 00");
    tseed_run(&fx, 1000);
    tb_expect(BUS, "281 27 06 01");
    tb_expect_none(BUS);
    /* a state change: Shutdown -> Ready to switch on */
    tb_send(BUS, "201 06 00");
    tseed_run(&fx, 1000);
    tb_expect(BUS, "181 21 02");
    tb_expect(BUS, "281 21 02 01");
    tb_expect_none(BUS);
}

/* ------------------------------ D§7.12: sync PDOs, interpolated position */

static void ex1412_to_1414_ip(void **state)
{
    co402_sim_config_t c;
    const co_frame_t *f;

    (void)state;
    tseed_init(&fx);
    sim_at(&c, 5); /* 4.1 reports position 5 */
    power_on(0, 1, &c);
    /* 1.1 .. 1.6: RPDO1 = controlword + 60C1h sub 1, synchronous. The
     * printed answer "4F 00 16 01 06" to 1.2 is an upload response copied in
     * error; a download is confirmed with 60. */
    dl("2F 00 16 00 00 00 00 00");
    dl("23 00 16 01 10 00 40 60");
    dl("23 00 16 02 20 01 C1 60");
    dl("2F 00 16 00 02 00 00 00");
    dl("2F 00 14 02 01 00 00 00");
    dl("23 00 14 01 01 02 00 00");
    /* 1.7 .. 1.12: TPDO1 = statusword + 6063h, synchronous */
    dl("2F 00 1A 00 00 00 00 00");
    dl("23 00 1A 01 10 00 41 60");
    dl("23 00 1A 02 20 00 63 60");
    dl("2F 00 1A 00 02 00 00 00");
    dl("2F 00 18 02 01 00 00 00");
    /* 1.12 printed 0x00001801, not an 11-bit CAN-ID: refused; meant 181h */
    tb_xfer(BUS, "601 23 00 18 01 01 18 00 00", "581 80 00 18 01 30 00 09 06");
    dl("23 00 18 01 81 01 00 00");
    dl("23 06 10 00 88 13 00 00"); /* 2.1: 5000 us */
    steps_1_to_4();
    dl("2F 60 60 00 07 00 00 00"); /* 3.1 */
    tb_xfer(BUS, "601 40 61 60 00 00 00 00 00", "581 4F 61 60 00 07 00 00 00");
    tseed_run(&fx, 2000);
    /* 3.3: start; TPDO2 (event-driven, statusword + mode) sends once */
    tb_send(BUS, "000 01 01");
    tb_expect(BUS, "281 27 06 07");
    tb_expect_none(BUS);
    tb_send(BUS, "080"); /* 4.1 */
    tb_expect(BUS, "181 27 06 05 00 00 00");
    tb_expect_none(BUS);
    /* 4.2: printed on 200h with 7 bytes: not this drive's, nothing happens;
     * meant is RPDO1 (201h, 6 bytes): enable ip, set-point 5 */
    tb_send(BUS, "200 1F 00 05 00 00 00 00");
    tseed_run(&fx, 5000);
    tb_expect_none(BUS);
    tb_send(BUS, "201 1F 00 05 00 00 00");
    tb_expect_none(BUS); /* synchronous: taken at the next SYNC */
    assert_int_equal(tseed_get(&fx, 0, 0x60C1, 1), 0);
    tb_send(BUS, "080"); /* 4.3: set-point taken, TPDO1 again: ip active */
    tb_expect(BUS, "181 27 92 05 00 00 00");
    tb_expect_none(BUS);
    assert_int_equal(tseed_get(&fx, 0, 0x60C1, 1), 5);
    tseed_run(&fx, 1000);
    tb_expect(BUS, "281 27 92 07");
    /* the cycle goes on every 5 ms: +50 increments per cycle */
    for (int32_t k = 1; k <= 20; k++) {
        char rx[40];
        tseed_run(&fx, 4000);
        snprintf(rx, sizeof rx, "201 1F 00 %02X %02X 00 00", (unsigned)((5 + (50 * k)) & 0xFF),
                 (unsigned)((5 + (50 * k)) >> 8));
        tb_send(BUS, rx);
        tseed_run(&fx, 1000);
        tb_send(BUS, "080");
        f = tseed_frame(BUS, 0x181, 6);
        assert_int_equal(tseed_i16(f, 0), (int16_t)0x9227);
        assert_int_equal(tseed_i32(f, 2), tseed_get(&fx, 0, 0x6063, 0));
        /* the axis follows one cycle behind the set-points */
        assert_between(tseed_i32(f, 2), 5 + (50 * (k - 1)) - 30, 5 + (50 * (k - 1)) + 30);
    }
    tb_expect_none(BUS);
}

/* ------------------------------------------ D§7.13: profile velocity */

static void ex1415_pv(void **state)
{
    (void)state;
    steps_1_to_4();
    dl("23 FF 60 00 00 00 00 00"); /* 2.1 */
    /* "3.2": printed for index 6006h ("= 0"): a missing index; meant 6060h = 3 */
    tb_xfer(BUS, "601 2F 06 60 00 03 00 00 00", "581 80 06 60 00 00 00 01 06");
    dl("2F 60 60 00 03 00 00 00");
    dl("23 FF 60 00 E8 03 00 00"); /* 2.3: 1000 rpm */
    tseed_run(&fx, 500000);
    assert_between(tseed_get(&fx, 0, 0x606C, 0), 999, 1001);
    /* 0x60FF must be 0 before the mode changes */
    tb_xfer(BUS, "601 2F 60 60 00 01 00 00 00", "581 80 60 60 00 22 00 00 08");
    dl("23 FF 60 00 00 00 00 00");
    tseed_run(&fx, 500000);
    assert_between(tseed_get(&fx, 0, 0x606C, 0), -1, 1);
    dl("2F 60 60 00 01 00 00 00");
    tb_expect_none(BUS);
}

/* ------------------------------------------ velocity mode (vl, rpm) */

static void vl_mode(void **state)
{
    (void)state;
    steps_1_to_4();
    dl("2F 60 60 00 02 00 00 00");
    dl("2B 42 60 00 F4 01 00 00"); /* 500 rpm */
    dl("2B 40 60 00 7F 00 00 00"); /* ramp enabled, unlocked, reference used */
    /* 0x6048: 1000 rpm per s, up and down (there is no 0x6049) */
    tseed_run(&fx, 250000);
    assert_between(tseed_get(&fx, 0, 0x6043, 0), 240, 260);
    tseed_run(&fx, 500000);
    assert_int_equal(tseed_get(&fx, 0, 0x6043, 0), 500);
    assert_between(tseed_get(&fx, 0, 0x6044, 0), 499, 501);
    dl("2B 42 60 00 00 00 00 00");
    tseed_run(&fx, 250000);
    assert_between(tseed_get(&fx, 0, 0x6043, 0), 240, 260);
}

/* ----------------------------------------------- D§8.4 derived vectors */

static void derived_vectors(void **state)
{
    (void)state;
    tb_xfer(BUS, "601 40 01 10 00 00 00 00 00", "581 4F 01 10 00 00 00 00 00");
    tb_xfer(BUS, "601 2F 03 10 00 00 00 00 00", "581 60 03 10 00 00 00 00 00");
    tb_xfer(BUS, "601 40 10 10 01 00 00 00 00", "581 43 10 10 01 01 00 00 00");
    tb_xfer(BUS, "601 23 10 10 01 73 61 76 65", "581 60 10 10 01 00 00 00 00");
    tb_xfer(BUS, "601 23 11 10 01 6C 6F 61 64", "581 60 11 10 01 00 00 00 00");
    /* §11 prints "load" as 73 61 61 64: not the signature */
    tb_xfer(BUS, "601 23 11 10 01 73 61 61 64", "581 80 11 10 01 20 00 00 08");
    tb_xfer(BUS, "601 40 18 10 05 00 00 00 00", "581 80 18 10 05 11 00 09 06");
    tb_xfer(BUS, "601 23 00 10 00 00 00 00 00", "581 80 00 10 00 00 00 01 06");
    tb_xfer(BUS, "601 2F 40 60 00 0F 00 00 00", "581 80 40 60 00 10 00 07 06");
    /* mapping: only the objects of §7 (6083h is not one), at most 64 bits */
    dl("2F 00 16 00 00 00 00 00");
    tb_xfer(BUS, "601 23 00 16 01 20 00 83 60", "581 80 00 16 01 41 00 04 06");
    for (unsigned k = 1U; k <= 5U; k++) {
        char d[40];
        snprintf(d, sizeof d, "23 00 16 %02X 20 00 7A 60", k);
        dl(d);
    }
    tb_xfer(BUS, "601 2F 00 16 00 05 00 00 00", "581 80 00 16 00 42 00 04 06");
    dl("2F 00 16 00 02 00 00 00");
    /* PDO configuration only in Pre-operational (§7): mapping and
     * communication parameters alike (CO_PDO_WRITES_PREOP) */
    tb_send(BUS, "000 01 01");
    tb_flush(BUS);
    tb_xfer(BUS, "601 2F 00 16 00 00 00 00 00", "581 80 00 16 00 22 00 00 08");
    tb_xfer(BUS, "601 2F 00 18 02 01 00 00 00", "581 80 00 18 02 22 00 00 08");
    tb_xfer(BUS, "601 2B 00 18 05 0A 00 00 00", "581 80 00 18 05 22 00 00 08");
    tb_xfer(BUS, "601 23 00 18 01 81 01 00 80", "581 80 00 18 01 22 00 00 08");
    tb_xfer(BUS, "601 23 00 14 01 01 02 00 00", "581 80 00 14 01 22 00 00 08");
    tb_xfer(BUS, "601 40 00 18 02 00 00 00 00", "581 4F 00 18 02 FF 00 00 00");
    /* back in Pre-operational: taken */
    tb_send(BUS, "000 80 01");
    dl("2F 00 18 02 01 00 00 00");
    dl("23 00 18 01 81 01 00 80");
}

/* --------------------------------------------------- EMCY (D§2.6) */

static void emcy_codes_and_history(void **state)
{
    (void)state;
    /* 3210h DC-link over-voltage: register 05h, manufacturer field zero */
    co402_sim_set_fault(&fx.n[0].sim, 0x3210);
    tseed_run(&fx, 1000);
    tb_expect(BUS, "081 10 32 05 00 00 00 00 00");
    /* 8611h following error (transition 3): register 21h, or-ed: 25h */
    co402_fault_raise(AX, 0x8611);
    tb_expect(BUS, "081 11 86 25 00 00 00 00 00");
    /* 5441h (drive-enable contact): register 81h as in §9's table */
    co402_fault_raise(AX, 0x5441);
    tb_expect(BUS, "081 41 54 A5 00 00 00 00 00");
    tb_expect_none(BUS);
    tb_xfer(BUS, "601 40 03 10 00 00 00 00 00", "581 4F 03 10 00 03 00 00 00");
    tb_xfer(BUS, "601 40 03 10 01 00 00 00 00", "581 43 03 10 01 41 54 00 00");
    tb_xfer(BUS, "601 40 03 10 03 00 00 00 00", "581 43 03 10 03 10 32 00 00");
    /* all causes gone; a fault reset ends them: an EMCY 0000h with the
     * register still active after each (transitions 2, then 4) */
    co402_sim_set_fault(&fx.n[0].sim, 0);
    co402_fault_clear(AX, 0x8611);
    co402_fault_clear(AX, 0x5441);
    tseed_run(&fx, 1000);
    dl("2B 40 60 00 80 00 00 00");
    tseed_run(&fx, 1000);
    tb_expect(BUS, "081 00 00 A1 00 00 00 00 00");
    tb_expect(BUS, "081 00 00 81 00 00 00 00 00");
    tb_expect(BUS, "081 00 00 00 00 00 00 00 00");
    tb_expect_none(BUS);
    expect_sw(0x0240);
    /* only 0 may be written to 1003h sub 0 */
    tb_xfer(BUS, "601 2F 03 10 00 02 00 00 00", "581 80 03 10 00 30 00 09 06");
    tb_xfer(BUS, "601 2F 03 10 00 00 00 00 00", "581 60 03 10 00 00 00 00 00");
    tb_xfer(BUS, "601 40 03 10 00 00 00 00 00", "581 4F 03 10 00 00 00 00 00");
}

/* ------------------------------------ D§6: the drive-enable input, remote */

static void enable_input_and_remote(void **state)
{
    co402_sim_t *sim = &fx.n[0].sim;

    (void)state;
    steps_1_to_4();
    /* the input drops (remote -> local): Switch on disabled, no remote, no
     * fault (0x2019 = 0) */
    co402_sim_set_level(sim, CO402_IN_ENABLE, false);
    tseed_run(&fx, 2000);
    expect_sw(0x0040);
    assert_int_equal(co402_state(AX), CO402_SWITCH_ON_DISABLED);
    tb_expect_none(BUS);
    /* without remote, Shutdown is not taken */
    dl("2B 40 60 00 06 00 00 00");
    expect_sw(0x0040);
    co402_sim_set_level(sim, CO402_IN_ENABLE, true);
    tseed_run(&fx, 2000);
    expect_sw(0x0240);
    dl("2B 40 60 00 06 00 00 00");
    expect_sw(0x0221);
}

/* ------------------------ 0x2018: Operational straight after power-on */

static void autostart_after_power_on(void **state)
{
    (void)state;
    dl("2B 18 20 00 01 00 00 00");
    tb_xfer(BUS, "601 23 10 10 01 73 61 76 65", "581 60 10 10 01 00 00 00 00");
    /* power off and on (the same non-volatile memory) */
    power_on(0, 1, NULL);
    assert_int_equal(co_node_nmt_state(&sn[0].node), CO_NMT_OPERATIONAL);
    tb_expect(BUS, "181 40 02");
    tb_expect(BUS, "281 40 02 01");
    tb_expect_none(BUS);
    /* a reset node is no power-on: Pre-operational, as CiA 301 says */
    tb_send(BUS, "000 81 01");
    tb_expect(BUS, "701 00");
    tb_expect(BUS, "081 00 00 00 56 38 31 39 64");
    tb_expect_none(BUS);
    assert_int_equal(co_node_nmt_state(&sn[0].node), CO_NMT_PRE_OPERATIONAL);
    /* restore the defaults ("load"), power on: Pre-operational again */
    tb_xfer(BUS, "601 23 11 10 01 6C 6F 61 64", "581 60 11 10 01 00 00 00 00");
    power_on(0, 1, NULL);
    assert_int_equal(co_node_nmt_state(&sn[0].node), CO_NMT_PRE_OPERATIONAL);
    tb_expect_none(BUS);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(boot_and_error_control, setup),
        cmocka_unit_test_setup(ex141_to_147_sdo, setup),
        cmocka_unit_test_setup(ex149_pp_by_sdo, setup),
        cmocka_unit_test_setup(ex1410_homing_by_sdo, setup),
        cmocka_unit_test_setup(ex1411_pp_by_pdo, setup),
        cmocka_unit_test_setup(tpdo_masks_type_254, setup),
        cmocka_unit_test_setup(ex1412_to_1414_ip, setup),
        cmocka_unit_test_setup(ex1415_pv, setup),
        cmocka_unit_test_setup(vl_mode, setup),
        cmocka_unit_test_setup(derived_vectors, setup),
        cmocka_unit_test_setup(emcy_codes_and_history, setup),
        cmocka_unit_test_setup(enable_input_and_remote, setup),
        cmocka_unit_test_setup(autostart_after_power_on, setup),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
