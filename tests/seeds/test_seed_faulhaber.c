/*
 * FAULHABER Motion Controller (devices/faulhaber-mc.toml as the CiA 402
 * device co_device_faulhaber_mc with its plug-in): the manual's worked examples from the digest
 * (/work/shared/spec/seed-001-faulhaber-motion-controller.md, section 7 and
 * the sections named below) replayed frame by frame on the in-memory bus,
 * against the real device description, the CiA 402 profile and the
 * simulated BL motor (3000 increments per revolution, rpm, 1/s^2).
 *
 * Where a drive's measured value cannot match (a real motor's position
 * drift, its -1 rpm at rest), the frame layout is asserted with the
 * simulation's value, and a comment says so.
 *
 * TPDOs (digest 4.3, 9.1 item 1): the only event of a type-255 TPDO is a
 * statusword change. The profile requests the TPDOs that map the statusword
 * on every change (CO402_OPT_TPDO_ON_SW); the core's own change detection is
 * off for this device (CO_TPDO_CHANGE_IGNORED), so nothing goes out on
 * NMT start or because a position or velocity changed, and TxPDO4 (no
 * statusword) only on RTR or SYNC. The tests assert every frame.
 */
#include <inttypes.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "co_devices.h"
#include "faulhaber_mc_desc.h"
#include "seedrun.h"

static seedrun_t fx;
static faulhaber_mc_node_t node;
#define S (&fx)

/* The unit of the manual's trace (section 7.1) stood at 13011 increments. */
static void trace_sim(co402_sim_config_t *c)
{
    co402_params_sim_config(co402_device_params(&co_device_faulhaber_mc), c);
    c->start_pos = 13011;
}

static int setup(void **state)
{
    (void)state;
    co_node_config_t cfg;

    faulhaber_mc_config(&node, &cfg);
    sr_start(S, &co_device_faulhaber_mc, &cfg, &node.node, NULL, 2);
    sr_run(S, 10);
    tb_expect_none(&S->bus);
    return 0;
}

static int setup_trace(void **state)
{
    (void)state;
    co_node_config_t cfg;

    co402_sim_config_t sc;

    trace_sim(&sc);
    faulhaber_mc_config(&node, &cfg);
    sr_start(S, &co_device_faulhaber_mc, &cfg, &node.node, &sc, 2);
    sr_run(S, 10);
    tb_expect_none(&S->bus);
    return 0;
}

/* NMT start of node 2: no TPDO goes out (the trace, 7.1 step 1, shows none;
 * a statusword change is the only event). */
static void start_node(void)
{
    tb_send(&S->bus, "000 01 02");
    sr_poll(S);
    tb_expect_none(&S->bus);
}

/* The three TPDOs of one statusword change, in PDO order (trace 7.1). */
static void expect_sw_pdos(uint16_t sw, int32_t pos, int32_t rpm)
{
    char f[64];
    uint32_t p = (uint32_t)pos;
    uint32_t v = (uint32_t)rpm;

    snprintf(f, sizeof f, "182 %02X %02X", sw & 0xFFU, sw >> 8);
    sr_expect(S, f);
    snprintf(f, sizeof f, "282 %02X %02X %02" PRIX32 " %02" PRIX32 " %02" PRIX32 " %02" PRIX32,
             sw & 0xFFU, sw >> 8, p & 0xFFU, (p >> 8) & 0xFFU, (p >> 16) & 0xFFU, p >> 24);
    sr_expect(S, f);
    snprintf(f, sizeof f, "382 %02X %02X %02" PRIX32 " %02" PRIX32 " %02" PRIX32 " %02" PRIX32,
             sw & 0xFFU, sw >> 8, v & 0xFFU, (v >> 8) & 0xFFU, (v >> 16) & 0xFFU, v >> 24);
    sr_expect(S, f);
}

/* The next frame is TPDO1 with statusword @p sw, then TPDO2 and TPDO3 with
 * the same statusword (their position / velocity are the simulation's). */
static void expect_sw_pdos_moving(uint16_t sw)
{
    const co_frame_t *f;

    for (uint16_t cob = 0x182U; cob <= 0x382U; cob = (uint16_t)(cob + 0x100U)) {
        f = tb_next(&S->bus);
        assert_non_null(f);
        assert_int_equal(f->id, cob);
        assert_int_equal(f->dlc, (cob == 0x182U) ? 2U : 6U);
        assert_int_equal(f->data[0] | (f->data[1] << 8), sw);
    }
}

/* Run until the TPDOs of the next statusword change come: statusword @p sw
 * (nothing else is sent in between). */
static void run_until_sw(uint16_t sw, uint32_t max_ms)
{
    (void)sr_run_until_frame(S, max_ms);
    expect_sw_pdos_moving(sw);
    tb_expect_none(&S->bus);
}

/* ------------------------------------------------------ identity, SDO */

/* Section 3 SDO frames, section 1 identity, section 5 object attributes. */
static void sdo_examples(void **state)
{
    (void)state;
    /* device type 0x00420192, vendor-ID 327, product code 3150 */
    sr_sdo(S, "40 00 10 00 00 00 00 00", "43 00 10 00 92 01 42 00");
    sr_sdo(S, "40 18 10 00 00 00 00 00", "4F 18 10 00 04 00 00 00");
    sr_sdo(S, "40 18 10 01 00 00 00 00", "43 18 10 01 47 01 00 00");
    sr_sdo(S, "40 18 10 02 00 00 00 00", "43 18 10 02 4E 0C 00 00");
    /* upload answers by size: 1 byte 0x4F, 2 bytes 0x4B, 4 bytes 0x43 */
    sr_sdo(S, "40 60 60 00 00 00 00 00", "4F 60 60 00 01 00 00 00");
    sr_sdo(S, "40 41 60 00 00 00 00 00", "4B 41 60 00 40 00 00 00");
    sr_sdo(S, "40 02 65 00 00 00 00 00", "43 02 65 00 25 00 00 00");
    sr_sdo(S, "40 21 23 01 00 00 00 00", "4B 21 23 01 FF FF 00 00");
    sr_sdo(S, "40 22 23 01 00 00 00 00", "4B 22 23 01 C8 00 00 00");
    sr_sdo(S, "40 00 24 00 00 00 00 00", "4F 00 24 00 FF 00 00 00"); /* auto-baud */
    sr_sdo(S, "40 98 60 00 00 00 00 00", "4F 98 60 00 14 00 00 00"); /* method 20 */
    sr_sdo(S, "40 99 60 01 00 00 00 00", "43 99 60 01 90 01 00 00"); /* 400 rpm */
    sr_sdo(S, "40 8F 60 01 00 00 00 00", "43 8F 60 01 B8 0B 00 00"); /* 3000 inc (BL) */
    /* downloads of 1, 2, 4 bytes: 0x2F, 0x2B, 0x23, confirmed with 0x60 */
    sr_sdo(S, "2F 60 60 00 03 00 00 00", "60 60 60 00 00 00 00 00");
    sr_sdo(S, "2B 68 60 00 64 00 00 00", "60 68 60 00 00 00 00 00");
    sr_sdo(S, "23 81 60 00 E8 03 00 00", "60 81 60 00 00 00 00 00");
    sr_sdo(S, "40 81 60 00 00 00 00 00", "43 81 60 00 E8 03 00 00");
    /* aborts (section 3): read-only, no object, no sub-index, too high,
     * a mode the device lacks (an assumption: 0x06090030) */
    sr_sdo(S, "2B 41 60 00 00 00 00 00", "80 41 60 00 02 00 01 06");
    sr_sdo(S, "40 00 30 00 00 00 00 00", "80 00 30 00 00 00 02 06");
    sr_sdo(S, "40 10 23 04 00 00 00 00", "80 10 23 04 11 00 09 06");
    sr_sdo(S, "23 83 60 00 41 7D 00 00", "80 83 60 00 31 00 09 06"); /* 32001 > 32000 */
    sr_sdo(S, "2F 60 60 00 08 00 00 00", "80 60 60 00 30 00 09 06"); /* csp */
    /* segmented upload only for the strings: 0x1008 "MCBL 3006 S CO" */
    sr_sdo(S, "40 08 10 00 00 00 00 00", "41 08 10 00 0E 00 00 00");
    sr_sdo(S, "60 00 00 00 00 00 00 00", "00 4D 43 42 4C 20 33 30");
    sr_sdo(S, "70 00 00 00 00 00 00 00", "11 30 36 20 53 20 43 4F");
    /* no block transfer (CO_SDO_XFER_BLOCK) */
    sr_sdo(S, "A0 08 10 00 7F 00 00 00", "80 08 10 00 01 00 04 05");
    /* 0x1200 server SDO COB-IDs, read-only */
    sr_sdo(S, "40 00 12 01 00 00 00 00", "43 00 12 01 02 06 00 00");
    sr_sdo(S, "40 00 12 02 00 00 00 00", "43 00 12 02 82 05 00 00");
}

/* Section 7.8: store and restore with the signatures. */
static void store_restore(void **state)
{
    (void)state;
    sr_sdo(S, "40 10 10 01 00 00 00 00", "43 10 10 01 01 00 00 00");
    sr_sdo(S, "40 11 10 01 00 00 00 00", "43 11 10 01 01 00 00 00");
    sr_sdo_write(S, 0x6081, 0, 1234, 4);
    sr_sdo(S, "23 10 10 01 73 61 76 65", "60 10 10 01 00 00 00 00");
    /* a wrong signature: CiA 301's 0x08000020 (the manual does not say) */
    sr_sdo(S, "23 10 10 01 73 61 76 66", "80 10 10 01 20 00 00 08");
    /* Reset Node: the saved value is the power-on value */
    tb_send(&S->bus, "000 81 02");
    sr_expect(S, "702 00");
    sr_sdo(S, "40 81 60 00 00 00 00 00", "43 81 60 00 D2 04 00 00");
    /* restore the factory set (allowed in Switch on disabled), then reset */
    sr_sdo(S, "23 11 10 01 6C 6F 61 64", "60 11 10 01 00 00 00 00");
    tb_send(&S->bus, "000 81 02");
    sr_expect(S, "702 00");
    sr_sdo(S, "40 81 60 00 00 00 00 00", "43 81 60 00 B8 0B 00 00");
    /* subs 4..6 restore the last saved set (section 8; CO_RESTORE_SAVED):
     * they read 1; the factory restore above kept the saved 1234, which
     * comes back at the next reset */
    sr_sdo(S, "40 11 10 04 00 00 00 00", "43 11 10 04 01 00 00 00");
    sr_sdo(S, "40 11 10 05 00 00 00 00", "43 11 10 05 01 00 00 00");
    sr_sdo(S, "40 11 10 06 00 00 00 00", "43 11 10 06 01 00 00 00");
    sr_sdo(S, "23 11 10 04 6C 6F 61 64", "60 11 10 04 00 00 00 00");
    sr_sdo(S, "40 81 60 00 00 00 00 00", "43 81 60 00 B8 0B 00 00");
    tb_send(&S->bus, "000 81 02");
    sr_expect(S, "702 00");
    sr_sdo(S, "40 81 60 00 00 00 00 00", "43 81 60 00 D2 04 00 00");
    /* the application group alone: factory (sub 3), then saved (sub 6) */
    sr_sdo(S, "23 11 10 03 6C 6F 61 64", "60 11 10 03 00 00 00 00");
    tb_send(&S->bus, "000 81 02");
    sr_expect(S, "702 00");
    sr_sdo(S, "40 81 60 00 00 00 00 00", "43 81 60 00 B8 0B 00 00");
    sr_sdo(S, "23 11 10 06 6C 6F 61 64", "60 11 10 06 00 00 00 00");
    tb_send(&S->bus, "000 81 02");
    sr_expect(S, "702 00");
    sr_sdo(S, "40 81 60 00 00 00 00 00", "43 81 60 00 D2 04 00 00");
    /* a wrong signature: 0x08000020 */
    sr_sdo(S, "23 11 10 05 73 61 76 65", "80 11 10 05 20 00 00 08");
}

/* Section 8 / 9.1 item 16: factory restore only in Switch on disabled. */
static void factory_restore_only_when_disabled(void **state)
{
    (void)state;
    start_node();
    sr_sdo_write(S, 0x6040, 0, 0x0006, 2);
    sr_poll(S);
    expect_sw_pdos(0x0021, 0, 0);
    sr_sdo(S, "23 11 10 01 6C 6F 61 64", "80 11 10 01 22 00 00 08");
    sr_sdo(S, "23 11 10 02 6C 6F 61 64", "80 11 10 02 22 00 00 08");
    /* saving is always allowed */
    sr_sdo(S, "23 10 10 01 73 61 76 65", "60 10 10 01 00 00 00 00");
}

/* ------------------------------------------------- trace (section 7.1) */

static void trace_velocity_mode(void **state)
{
    (void)state;
    /* 1: NMT start: no TPDO */
    start_node();
    /* 2-6: shutdown 0x000E -> Ready to switch on. The real drive sent
     * velocity -1 rpm (FF FF FF FF) at rest; the simulated motor stands: 0. */
    sr_sdo(S, "2B 40 60 00 0E 00 00 00", "60 40 60 00 00 00 00 00");
    sr_poll(S);
    expect_sw_pdos(0x0021, 13011, 0);
    tb_expect_none(&S->bus);
    /* 7-11: 0x000F moves one step only: Switched on */
    sr_sdo(S, "2B 40 60 00 0F 00 00 00", "60 40 60 00 00 00 00 00");
    sr_poll(S);
    expect_sw_pdos(0x0023, 13011, 0);
    tb_expect_none(&S->bus);
    /* 12-16: 0x000F again: Operation enabled (pp, bits 10 and 12 = 0); the
     * real position had crept to 13012, the simulated one holds 13011 */
    sr_sdo(S, "2B 40 60 00 0F 00 00 00", "60 40 60 00 00 00 00 00");
    sr_poll(S);
    expect_sw_pdos(0x0027, 13011, 0);
    sr_run(S, 500);
    tb_expect_none(&S->bus); /* pp: no target reached before a set-point */
    /* 17-21: profile velocity at rest: target reached and speed 0 together
     * (after the window times 0x606E / 0x6070, 200 ms) */
    sr_sdo(S, "2F 60 60 00 03 00 00 00", "60 60 60 00 00 00 00 00");
    sr_run_until_frame(S, 300);
    expect_sw_pdos(0x1427, 13011, 0);
    tb_expect_none(&S->bus);
    /* 22-26: 100 rpm: the new set-point clears target reached, speed 0
     * still set (the motor has not moved yet) */
    sr_sdo(S, "23 FF 60 00 64 00 00 00", "60 FF 60 00 00 00 00 00");
    sr_run_until_frame(S, 5);
    expect_sw_pdos(0x1027, 13011, 0);
    /* 27-29: moving; 30-32: target velocity reached (within 20 rpm for
     * 200 ms); positions and speeds are the simulation's */
    run_until_sw(0x0027, 50);
    run_until_sw(0x0427, 400);
    sr_between(sr_get(S, 0x606C, 0), 80, 120);
    sr_between(sr_get(S, 0x6064, 0), 13011 + 500, 13011 + 2000);
    /* TPDO4 (no statusword) is never a statusword-change frame */
}

/* --------------------------------------------- NMT, guarding, heartbeat */

/* Section 7.3 and 2.5/2.6: guarding replies with the toggle bit starting
 * at 0, heartbeat, and their exclusion (9.1 item 9). */
static void nmt_guarding_heartbeat(void **state)
{
    (void)state;
    tb_send(&S->bus, "702 R");
    sr_expect(S, "702 7F");
    tb_send(&S->bus, "702 R");
    sr_expect(S, "702 FF");
    start_node();
    tb_send(&S->bus, "702 R");
    sr_expect(S, "702 05");
    tb_send(&S->bus, "702 R");
    sr_expect(S, "702 85");
    /* guard time 100 ms, life time factor 3 */
    sr_sdo(S, "2B 0C 10 00 64 00 00 00", "60 0C 10 00 00 00 00 00");
    sr_sdo(S, "2F 0D 10 00 03 00 00 00", "60 0D 10 00 00 00 00 00");
    /* a producer heartbeat time > 0 forces both to 0 ... */
    sr_sdo(S, "2B 17 10 00 64 00 00 00", "60 17 10 00 00 00 00 00");
    sr_sdo(S, "40 0C 10 00 00 00 00 00", "4B 0C 10 00 00 00 00 00");
    sr_sdo(S, "40 0D 10 00 00 00 00 00", "4F 0D 10 00 00 00 00 00");
    /* ... and a guard time is refused while it runs */
    sr_sdo(S, "2B 0C 10 00 64 00 00 00", "80 0C 10 00 20 00 00 08");
    sr_sdo(S, "2B 0C 10 00 00 00 00 00", "60 0C 10 00 00 00 00 00");
    /* heartbeat "702 05" every 100 ms */
    sr_run(S, 100);
    sr_expect(S, "702 05");
    sr_run(S, 99);
    tb_expect_none(&S->bus);
    sr_run(S, 1);
    sr_expect(S, "702 05");
    /* Stop, Pre-operational: the state byte follows */
    tb_send(&S->bus, "000 02 02");
    sr_run(S, 100);
    sr_expect(S, "702 04");
    tb_send(&S->bus, "000 80 02");
    sr_run(S, 100);
    sr_expect(S, "702 7F");
    /* the producer off: guarding may be configured again */
    sr_sdo(S, "2B 17 10 00 00 00 00 00", "60 17 10 00 00 00 00 00");
    sr_sdo(S, "2B 0C 10 00 64 00 00 00", "60 0C 10 00 00 00 00 00");
}

/* Sections 2.6, 2.7, 7.9: the consumer watches master 0x7F for 1500 ms
 * (0x1016.1 = 0x007F05DC); its loss sets 0x2320 bit 0x0100, 0x1001 bit 4,
 * sends EMCY 0x8130 and, by 0x1029.1 = 0, goes to Pre-operational (the
 * core's error behaviour, in the same step as the EMCY). */
static void heartbeat_consumer_and_error_behaviour(void **state)
{
    (void)state;
    sr_sdo(S, "23 16 10 01 DC 05 7F 00", "60 16 10 01 00 00 00 00");
    start_node();
    tb_send(&S->bus, "77F 05");
    sr_run(S, 1000);
    tb_send(&S->bus, "77F 05");
    sr_run(S, 1499);
    tb_expect_none(&S->bus);
    sr_run(S, 2); /* (the consumer: within 1023 us, co_hb.c) */
    /* the core's EMCY 0x8130, with 0x2320 = 0x0100 in bytes 3-4 (the
     * plug-in's emcy_mfr) */
    sr_expect(S, "082 30 81 11 00 01 00 00 00");
    sr_run(S, 1);
    tb_expect_none(&S->bus);
    assert_int_equal(sr_get(S, 0x2320, 0), 0x0100);
    assert_int_equal(co_node_nmt_state(S->node), CO_NMT_PRE_OPERATIONAL);
    /* the master is back: the error ends */
    tb_send(&S->bus, "77F 05");
    sr_run(S, 1);
    sr_expect(S, "082 00 00 00 00 00 00 00 00");
    assert_int_equal(sr_get(S, 0x2320, 0), 0x0000);
    /* 0x1029.1 = 1: no state change */
    tb_send(&S->bus, "000 01 02");
    sr_poll(S);
    tb_expect_none(&S->bus);
    sr_sdo(S, "2F 29 10 01 01 00 00 00", "60 29 10 01 00 00 00 00");
    sr_sdo(S, "2F 29 10 01 03 00 00 00", "80 29 10 01 31 00 09 06");
    sr_run(S, 1500);
    sr_expect(S, "082 30 81 11 00 01 00 00 00");
    sr_run(S, 1);
    assert_int_equal(co_node_nmt_state(S->node), CO_NMT_OPERATIONAL);
}

/* 7.7: fault mask 0x2321.02 = 0x0101 puts the drive into Fault on
 * over-current and on a heartbeat / guarding loss. The loss is the core's
 * EMCY 0x8130 (0x2320 = 0x0100 in bytes 3-4, emcy_mfr), the Fault the
 * plug-in's reaction at its next step; 0x1029.1 = 1 keeps the node
 * Operational. The master's return ends the error; then a fault reset. */
static void heartbeat_loss_with_fault_mask(void **state)
{
    (void)state;
    sr_sdo(S, "2B 21 23 02 01 01 00 00", "60 21 23 02 00 00 00 00");
    sr_sdo(S, "2F 29 10 01 01 00 00 00", "60 29 10 01 00 00 00 00");
    sr_sdo(S, "23 16 10 01 DC 05 7F 00", "60 16 10 01 00 00 00 00");
    start_node();
    sr_sdo_write(S, 0x6040, 0, 0x0006, 2);
    sr_poll(S);
    expect_sw_pdos(0x0021, 0, 0);
    tb_send(&S->bus, "77F 05");
    sr_run(S, 1499);
    tb_expect_none(&S->bus);
    sr_run(S, 2); /* (the consumer: within 1023 us, co_hb.c) */
    sr_expect(S, "082 30 81 11 00 01 00 00 00");
    tb_expect_none(&S->bus);
    /* the plug-in's next step: Fault (the power stage is off in Ready to
     * switch on: no fault reaction to run); the fault is raised with
     * 0x8130, already the core's active error: no second EMCY */
    sr_run(S, 1);
    expect_sw_pdos(0x0008, 0, 0);
    tb_expect_none(&S->bus);
    assert_int_equal(co_node_nmt_state(S->node), CO_NMT_OPERATIONAL);
    assert_int_equal(sr_get(S, 0x2320, 0), 0x0100);
    /* a fault reset while the master is still silent does nothing */
    sr_sdo_write(S, 0x6040, 0, 0x0080, 2);
    sr_run(S, 1);
    tb_expect_none(&S->bus);
    /* the master is back: EMCY 0x0000, 0x2320 clear, the fault reset works */
    tb_send(&S->bus, "77F 05");
    sr_expect(S, "082 00 00 00 00 00 00 00 00");
    sr_run(S, 1);
    assert_int_equal(sr_get(S, 0x2320, 0), 0x0000);
    sr_sdo_write(S, 0x6040, 0, 0x0000, 2);
    sr_sdo_write(S, 0x6040, 0, 0x0080, 2);
    sr_poll(S);
    expect_sw_pdos(0x0040, 0, 0);
    tb_expect_none(&S->bus);
}

/* CO402_OPT_TPDO_ON_SW: every statusword change requests the TPDOs that map
 * the statusword (1, 2, 3; not TxPDO4), even when the statusword is back at
 * the value last sent before the node runs (0x23 -> 0x21 -> 0x23 between
 * two polls): they go out once, with the present data. The core's own
 * change detection is off (CO_TPDO_CHANGE_IGNORED): the request is
 * what sends them. */
static void statusword_change_requests_tpdos(void **state)
{
    (void)state;
    start_node();
    sr_sdo_write(S, 0x6040, 0, 0x0006, 2);
    sr_sdo_write(S, 0x6040, 0, 0x0007, 2);
    sr_poll(S);
    expect_sw_pdos(0x0023, 0, 0);
    tb_expect_none(&S->bus);
    sr_sdo_write(S, 0x6040, 0, 0x0006, 2);
    sr_sdo_write(S, 0x6040, 0, 0x0007, 2);
    sr_poll(S);
    expect_sw_pdos(0x0023, 0, 0);
    tb_expect_none(&S->bus);
    /* a write that changes nothing requests nothing */
    sr_sdo_write(S, 0x6040, 0, 0x0007, 2);
    sr_poll(S);
    tb_expect_none(&S->bus);
}

/* ------------------------------------------ device control (7.4, 6.1) */

/* Section 7.4 enable sequence by SDO with the statusword after each step,
 * and section 6.1: in Pre-operational the controlword does not move it. */
static void enable_by_sdo_and_rpdo(void **state)
{
    (void)state;
    /* Pre-operational: written, but the state machine does not react */
    sr_sdo(S, "2B 40 60 00 06 00 00 00", "60 40 60 00 00 00 00 00");
    sr_sdo(S, "40 41 60 00 00 00 00 00", "4B 41 60 00 40 00 00 00");
    sr_sdo(S, "40 40 60 00 00 00 00 00", "4B 40 60 00 06 00 00 00");
    start_node();
    sr_sdo(S, "2B 40 60 00 06 00 00 00", "60 40 60 00 00 00 00 00");
    sr_poll(S);
    expect_sw_pdos(0x0021, 0, 0);
    sr_sdo(S, "2B 40 60 00 07 00 00 00", "60 40 60 00 00 00 00 00");
    sr_poll(S);
    expect_sw_pdos(0x0023, 0, 0);
    sr_sdo(S, "2B 40 60 00 0F 00 00 00", "60 40 60 00 00 00 00 00");
    sr_poll(S);
    expect_sw_pdos(0x0027, 0, 0);
    tb_expect_none(&S->bus);
    /* disable voltage, then the same sequence through RxPDO1 */
    sr_sdo(S, "2B 40 60 00 00 00 00 00", "60 40 60 00 00 00 00 00");
    sr_poll(S);
    expect_sw_pdos(0x0040, 0, 0);
    tb_send(&S->bus, "202 06 00");
    sr_poll(S);
    expect_sw_pdos(0x0021, 0, 0);
    tb_send(&S->bus, "202 07 00");
    sr_poll(S);
    expect_sw_pdos(0x0023, 0, 0);
    tb_send(&S->bus, "202 0F 00");
    sr_poll(S);
    expect_sw_pdos(0x0027, 0, 0);
    /* quick stop: option code 6 behaviour, stays in Quick stop active
     * (0x0007) and returns with enable operation (transition 16) */
    tb_send(&S->bus, "202 0B 00");
    sr_poll(S);
    expect_sw_pdos(0x0007, 0, 0);
    sr_run(S, 50);
    expect_sw_pdos(0x0407, 0, 0); /* at rest: bit 10 */
    tb_send(&S->bus, "202 0F 00");
    sr_poll(S);
    expect_sw_pdos(0x0027, 0, 0);
    tb_expect_none(&S->bus);
    /* a PDO needs Operational: in Pre-operational RxPDO1 is ignored */
    tb_send(&S->bus, "000 80 02");
    tb_send(&S->bus, "202 06 00");
    sr_poll(S);
    tb_expect_none(&S->bus);
    sr_sdo(S, "40 41 60 00 00 00 00 00", "4B 41 60 00 27 00 00 00");
}

/* Sections 7.4 (fault reset), 7.6 (the EMCY example) and 7.7 (error
 * configuration): over-current with the fault mask set. */
static void fault_and_emcy_example(void **state)
{
    (void)state;
    start_node();
    /* 7.7: 0x2321.02 = 0x0001: over-current -> Fault; it also sets the bit
     * in the emergency mask (already set by default: 0xFFFF) */
    sr_sdo_write(S, 0x2321, 1, 0x0000, 2);
    sr_sdo_write(S, 0x2321, 2, 0x0001, 2);
    sr_sdo(S, "40 21 23 01 00 00 00 00", "4B 21 23 01 01 00 00 00");
    sr_sdo_write(S, 0x6040, 0, 0x0006, 2);
    sr_poll(S);
    expect_sw_pdos(0x0021, 0, 0);
    sr_sdo_write(S, 0x6040, 0, 0x0007, 2);
    sr_poll(S);
    expect_sw_pdos(0x0023, 0, 0);
    sr_sdo_write(S, 0x6040, 0, 0x000F, 2);
    sr_poll(S);
    expect_sw_pdos(0x0027, 0, 0);
    /* the continuous current limit is exceeded; the error delay 0x2322.01
     * = 200 (2 s) passes before it is reported */
    faulhaber_mc_error(&S->run, FAULHABER_ERR_OVERCURRENT, true);
    sr_run(S, 1999);
    tb_expect_none(&S->bus);
    sr_run(S, 1);
    /* 7.6: the manual prints "10 23 01 00 00 00 00 00", which contradicts
     * its own tables; sent is code 0x2310, error register 0x03 (current,
     * with CiA 301's generic bit) and 0x2320 = 0x0001 in bytes 3-4 */
    sr_expect(S, "082 10 23 03 01 00 00 00 00");
    /* the fault mask: Fault reaction active (0x6084 ramp, at rest at once),
     * then Fault */
    sr_poll(S);
    expect_sw_pdos(0x000F, 0, 0);
    sr_run(S, 1);
    expect_sw_pdos(0x0008, 0, 0);
    tb_expect_none(&S->bus);
    sr_sdo(S, "40 20 23 00 00 00 00 00", "4B 20 23 00 01 00 00 00");
    sr_sdo(S, "40 01 10 00 00 00 00 00", "4F 01 10 00 03 00 00 00");
    /* 0x1003: error code, upper word 0x2320 (the manual's "error register") */
    sr_sdo(S, "40 03 10 01 00 00 00 00", "43 03 10 01 10 23 01 00");
    /* a fault reset while the condition lasts does nothing */
    sr_sdo_write(S, 0x6040, 0, 0x0080, 2);
    sr_poll(S);
    tb_expect_none(&S->bus);
    /* the condition ends: EMCY 0x0000 */
    faulhaber_mc_error(&S->run, FAULHABER_ERR_OVERCURRENT, false);
    sr_expect(S, "082 00 00 00 00 00 00 00 00");
    /* 7.4 fault reset sequence: 0x0080 (a rising edge), 6, 7, F */
    sr_sdo_write(S, 0x6040, 0, 0x0000, 2);
    sr_sdo_write(S, 0x6040, 0, 0x0080, 2);
    sr_poll(S);
    expect_sw_pdos(0x0040, 0, 0);
    sr_sdo_write(S, 0x6040, 0, 0x0006, 2);
    sr_poll(S);
    expect_sw_pdos(0x0021, 0, 0);
    sr_sdo_write(S, 0x6040, 0, 0x0007, 2);
    sr_poll(S);
    expect_sw_pdos(0x0023, 0, 0);
    sr_sdo_write(S, 0x6040, 0, 0x000F, 2);
    sr_poll(S);
    expect_sw_pdos(0x0027, 0, 0);
    tb_expect_none(&S->bus);
}

/* 9.1 item 4: with the factory masks no error leads to Fault; errors are
 * EMCYs only. The emergency mask off: 0x2320 only. */
static void errors_do_not_fault_by_default(void **state)
{
    (void)state;
    start_node();
    faulhaber_mc_error(&S->run, FAULHABER_ERR_TEMPERATURE, true);
    sr_poll(S);
    sr_expect(S, "082 10 43 09 08 00 00 00 00");
    sr_sdo(S, "40 41 60 00 00 00 00 00", "4B 41 60 00 40 00 00 00");
    faulhaber_mc_error(&S->run, FAULHABER_ERR_TEMPERATURE, false);
    sr_expect(S, "082 00 00 00 00 00 00 00 00");
    sr_sdo_write(S, 0x2321, 1, 0xFFF7, 2);
    faulhaber_mc_error(&S->run, FAULHABER_ERR_TEMPERATURE, true);
    sr_run(S, 10);
    tb_expect_none(&S->bus);
    sr_sdo(S, "40 20 23 00 00 00 00 00", "4B 20 23 00 08 00 00 00");
    /* 0x2322.01 = 200 -> reported after 2 s (section 7.7) */
    sr_sdo(S, "40 22 23 01 00 00 00 00", "4B 22 23 01 C8 00 00 00");
}

/* ------------------------------------------- modes (7.5, 6.5-6.7) */

static void enable(void)
{
    sr_sdo_write(S, 0x6040, 0, 0x0006, 2);
    sr_sdo_write(S, 0x6040, 0, 0x0007, 2);
    sr_sdo_write(S, 0x6040, 0, 0x000F, 2);
    assert_int_equal(co402_state(co402_device_axis(&S->run, 0U)), CO402_OPERATION_ENABLED);
}

/* Section 7.5.3: relative move of 10000 increments with controlword
 * 0x007F, the set-point handshake on bits 4/12, target reached; a second
 * 0x007F adds 10000 to the previous target; then the same by RxPDO2. */
static void relative_move(void **state)
{
    (void)state;
    start_node();
    enable();
    sr_poll(S);
    expect_sw_pdos(0x0027, 0, 0); /* three writes, one poll: the last statusword */
    tb_expect_none(&S->bus);
    sr_sdo(S, "2F 60 60 00 01 00 00 00", "60 60 60 00 00 00 00 00");
    sr_sdo(S, "23 7A 60 00 10 27 00 00", "60 7A 60 00 00 00 00 00");
    sr_sdo(S, "2B 40 60 00 7F 00 00 00", "60 40 60 00 00 00 00 00");
    sr_poll(S);
    expect_sw_pdos_moving(0x1027); /* set-point acknowledged, moving */
    sr_sdo(S, "2B 40 60 00 6F 00 00 00", "60 40 60 00 00 00 00 00");
    sr_poll(S);
    expect_sw_pdos_moving(0x0027); /* bit 4 cleared: bit 12 follows */
    run_until_sw(0x0427, 2000);
    sr_between(sr_get(S, 0x6064, 0), 10000 - 20, 10000 + 20);
    /* a second 0x007F after the rising edge: +10000 from the last target */
    sr_sdo(S, "2B 40 60 00 7F 00 00 00", "60 40 60 00 00 00 00 00");
    sr_poll(S);
    expect_sw_pdos_moving(0x1027); /* target reached cleared by the set-point */
    sr_sdo(S, "2B 40 60 00 0F 00 00 00", "60 40 60 00 00 00 00 00");
    sr_poll(S);
    expect_sw_pdos_moving(0x0027);
    run_until_sw(0x0427, 2000);
    sr_between(sr_get(S, 0x6064, 0), 20000 - 20, 20000 + 20);
    /* the same through RxPDO2 (controlword + target): 0F then 7F */
    tb_send(&S->bus, "302 0F 00 10 27 00 00");
    tb_send(&S->bus, "302 7F 00 10 27 00 00");
    sr_poll(S);
    expect_sw_pdos_moving(0x1027);
    tb_send(&S->bus, "302 0F 00 10 27 00 00");
    sr_poll(S);
    expect_sw_pdos_moving(0x0027);
    run_until_sw(0x0427, 2000);
    sr_between(sr_get(S, 0x6064, 0), 30000 - 20, 30000 + 20);
}

/* Section 7.5.1-2: 500 rpm in profile velocity by SDO, by RxPDO3, then
 * stop with 0x60FF = 0 or with disable operation (0x0007). */
static void velocity_host_example(void **state)
{
    (void)state;
    start_node();
    enable();
    sr_poll(S);
    expect_sw_pdos(0x0027, 0, 0);
    /* pv and 500 rpm before the speed-0 window (200 ms) ends: the next
     * statusword change is target velocity reached */
    sr_sdo(S, "2F 60 60 00 03 00 00 00", "60 60 60 00 00 00 00 00");
    sr_sdo(S, "23 FF 60 00 F4 01 00 00", "60 FF 60 00 00 00 00 00");
    run_until_sw(0x0427, 500);
    sr_run(S, 200);
    tb_expect_none(&S->bus); /* turning at 500 rpm: no statusword change, no TPDO */
    sr_between(sr_get(S, 0x606C, 0), 490, 510);
    /* stop: 0x60FF = 0 -> the set-point clears target reached, then target
     * (0 rpm) reached, then speed 0 (bit 12) */
    sr_sdo(S, "23 FF 60 00 00 00 00 00", "60 FF 60 00 00 00 00 00");
    run_until_sw(0x0027, 10);
    run_until_sw(0x0427, 500);
    run_until_sw(0x1427, 500);
    /* RxPDO3: controlword + target velocity */
    tb_send(&S->bus, "402 0F 00 F4 01 00 00");
    run_until_sw(0x1027, 10);
    run_until_sw(0x0027, 100);
    run_until_sw(0x0427, 500);
    sr_between(sr_get(S, 0x606C, 0), 490, 510);
    /* stop by disable operation: Switched on after the ramp */
    sr_sdo(S, "2B 40 60 00 07 00 00 00", "60 40 60 00 00 00 00 00");
    run_until_sw(0x0023, 100);
    sr_run(S, 100);
    tb_expect_none(&S->bus);
    sr_between(sr_get(S, 0x606C, 0), -10, 10); /* stopped below 0x606F, then off */
}

/* Section 6.6: homing with method 20 (default) on the positive home
 * switch; homing attained drops when bit 4 is cleared; an abort by
 * clearing bit 4 sets bit 10 with bit 12 = 0. */
static void homing(void **state)
{
    (void)state;
    start_node();
    enable();
    sr_sdo(S, "2F 60 60 00 06 00 00 00", "60 60 60 00 00 00 00 00");
    sr_poll(S);
    expect_sw_pdos(0x0427, 0, 0); /* enabled, homing mode at rest: bit 10 */
    tb_expect_none(&S->bus);
    /* 0x2310 cannot change in homing mode (0x08000022, an assumption) */
    sr_sdo(S, "2F 10 23 03 01 00 00 00", "80 10 23 03 22 00 00 08");
    sr_sdo(S, "2B 40 60 00 1F 00 00 00", "60 40 60 00 00 00 00 00");
    sr_poll(S);
    expect_sw_pdos_moving(0x0027); /* started: bits 12 and 10 = 0 */
    /* home found: attained while the axis stops (0x1027), then target
     * reached at rest (0x1427) */
    run_until_sw(0x1027, 5000);
    run_until_sw(0x1427, 1000);
    /* the home switch edge (30000 in the plant) is 0; the axis stopped
     * behind it with 0x609A */
    sr_between(sr_get(S, 0x6064, 0), 1, 3000);
    tb_expect_none(&S->bus); /* TxPDO4 (no statusword) stays silent */
    sr_sdo(S, "2B 40 60 00 0F 00 00 00", "60 40 60 00 00 00 00 00");
    sr_poll(S);
    expect_sw_pdos(0x0427, (int32_t)sr_get(S, 0x6064, 0), 0);
    /* again, from the switch, and aborted while it runs */
    sr_sdo(S, "2B 40 60 00 1F 00 00 00", "60 40 60 00 00 00 00 00");
    sr_poll(S);
    expect_sw_pdos_moving(0x0027);
    sr_run(S, 100);
    tb_expect_none(&S->bus); /* searching: the statusword does not change */
    sr_sdo(S, "2B 40 60 00 0F 00 00 00", "60 40 60 00 00 00 00 00");
    run_until_sw(0x0427, 2000);
}

/* ------------------------------------------------- PDO set-up (4.4) */

static void pdo_setup_and_rtr(void **state)
{
    (void)state;
    start_node();
    /* TxPDO4 (position, velocity) has no statusword: fetched by RTR */
    tb_send(&S->bus, "482 R8");
    sr_poll(S);
    sr_expect(S, "482 00 00 00 00 00 00 00 00");
    /* by SYNC after its transmission type is set to 1 */
    sr_sdo(S, "2F 03 18 02 01 00 00 00", "60 03 18 02 00 00 00 00");
    tb_send(&S->bus, "080");
    sr_poll(S);
    sr_expect(S, "482 00 00 00 00 00 00 00 00");
    /* remap TxPDO4 to statusword + modes display (CiA 301 procedure):
     * invalidate, sub 0 = 0, entries, sub 0 = n, valid again */
    tb_send(&S->bus, "000 80 02");
    sr_sdo(S, "23 03 18 01 82 04 00 80", "60 03 18 01 00 00 00 00");
    sr_sdo(S, "2F 03 1A 00 00 00 00 00", "60 03 1A 00 00 00 00 00");
    sr_sdo(S, "23 03 1A 01 10 00 41 60", "60 03 1A 01 00 00 00 00");
    sr_sdo(S, "23 03 1A 02 08 00 61 60", "60 03 1A 02 00 00 00 00");
    /* not mappable (0x1000), or beyond 64 bits */
    sr_sdo(S, "23 03 1A 03 20 00 00 10", "80 03 1A 03 41 00 04 06");
    sr_sdo(S, "23 03 1A 03 20 00 64 60", "60 03 1A 03 00 00 00 00");
    sr_sdo(S, "23 03 1A 04 20 00 64 60", "60 03 1A 04 00 00 00 00");
    sr_sdo(S, "2F 03 1A 00 04 00 00 00", "80 03 1A 00 42 00 04 06");
    sr_sdo(S, "2F 03 1A 00 02 00 00 00", "60 03 1A 00 00 00 00 00");
    sr_sdo(S, "23 03 18 01 82 04 00 00", "60 03 18 01 00 00 00 00");
    tb_send(&S->bus, "000 01 02");
    sr_poll(S);
    tb_expect_none(&S->bus);
    tb_send(&S->bus, "080");
    sr_poll(S);
    sr_expect(S, "482 40 00 01");
    /* RxPDO length (section 4.4): too short -> not processed, EMCY 0x8210;
     * too long -> processed, EMCY 0x8220. The core raises both; the
     * plug-in puts 0x2320 (0x4000 / 0x2000) into bytes 3-4 (emcy_mfr). */
    tb_send(&S->bus, "202 06");
    sr_poll(S);
    sr_expect(S, "082 10 82 11 00 40 00 00 00");
    assert_int_equal(sr_get(S, 0x2320, 0), 0x4000);
    /* 0x1003: the code, 0x2320 above it */
    sr_sdo(S, "40 03 10 01 00 00 00 00", "43 03 10 01 10 82 00 40");
    tb_send(&S->bus, "202 06 00 00");
    sr_poll(S);
    sr_expect(S, "082 00 00 00 00 00 00 00 00"); /* the short one has ended */
    sr_expect(S, "082 20 82 11 00 20 00 00 00");
    assert_int_equal(sr_get(S, 0x2320, 0), 0x2000);
    /* the controlword 0x0006 of the long frame: Ready to switch on; TxPDO4
     * (now with the statusword, synchronous) waits for the SYNC */
    expect_sw_pdos(0x0021, 0, 0);
    tb_expect_none(&S->bus);
    tb_send(&S->bus, "080");
    sr_poll(S);
    sr_expect(S, "482 21 00 01");
    tb_expect_none(&S->bus);
}

/* ------------------------------------------------- factor group (4.2) */

/* Feed constant 360 -> 1 degree per user unit: 0x6093 = 3000/360 = 25/3;
 * a numerator of 2e9 or more is refused with 0x06040047. */
static void factor_group(void **state)
{
    (void)state;
    sr_sdo(S, "23 92 60 01 68 01 00 00", "60 92 60 01 00 00 00 00");
    sr_sdo(S, "40 93 60 01 00 00 00 00", "43 93 60 01 19 00 00 00");
    sr_sdo(S, "40 93 60 02 00 00 00 00", "43 93 60 02 03 00 00 00");
    sr_sdo(S, "23 91 60 01 40 42 0F 00", "80 91 60 01 47 00 04 06"); /* 1e6: 3e9 */
    sr_sdo(S, "40 91 60 01 00 00 00 00", "43 91 60 01 01 00 00 00");
    /* 0x257A in increments sets 0x607A in degrees */
    sr_sdo(S, "23 7A 25 00 B8 0B 00 00", "60 7A 25 00 00 00 00 00");
    sr_sdo(S, "40 7A 60 00 00 00 00 00", "43 7A 60 00 68 01 00 00");
    /* a move of 90 degrees is 750 increments */
    start_node();
    enable();
    sr_sdo_write(S, 0x607A, 0, 90, 4);
    sr_sdo_write(S, 0x6040, 0, 0x001F, 2);
    sr_run(S, 1000);
    sr_between(sr_get(S, 0x6063, 0), 750 - 20, 750 + 20);
    sr_between(sr_get(S, 0x6064, 0), 88, 92);
    /* the first TPDOs carry the acknowledged set-point (the enable
     * sequence had no poll of its own), then target reached */
    expect_sw_pdos_moving(0x1027);
    expect_sw_pdos_moving(0x1427);
    tb_expect_none(&S->bus);
}

/* 0x2400 "Baudrate set" (§1.4, §7.9): 0xFF, automatic detection, until
 * LSS puts a bit timing in force (configure 250 kbit/s, activate with a
 * 10 ms switch delay), then its index. */
static void baudrate_set_shows_the_lss_bit_timing(void **state)
{
    (void)state;
    sr_sdo(S, "40 00 24 00 00 00 00 00", "4F 00 24 00 FF 00 00 00");
    tb_send(&S->bus, "7E5 04 01 00 00 00 00 00 00"); /* switch state global: configuration */
    sr_poll(S);
    tb_expect_none(&S->bus);
    tb_send(&S->bus, "7E5 13 00 03 00 00 00 00 00"); /* configure bit timing 250 kbit/s */
    sr_poll(S);
    tb_expect(&S->bus, "7E4 13 00 00 00 00 00 00 00");
    sr_sdo(S, "40 00 24 00 00 00 00 00", "4F 00 24 00 FF 00 00 00"); /* not yet in force */
    tb_send(&S->bus, "7E5 15 0A 00 00 00 00 00 00"); /* activate, switch delay 10 ms */
    sr_poll(S);
    sr_run(S, 30);
    tb_send(&S->bus, "7E5 04 00 00 00 00 00 00 00"); /* back to waiting */
    sr_poll(S);
    tb_expect_none(&S->bus);
    sr_sdo(S, "40 00 24 00 00 00 00 00", "4F 00 24 00 03 00 00 00");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(sdo_examples, setup),
        cmocka_unit_test_setup(baudrate_set_shows_the_lss_bit_timing, setup),
        cmocka_unit_test_setup(store_restore, setup),
        cmocka_unit_test_setup(factory_restore_only_when_disabled, setup),
        cmocka_unit_test_setup(trace_velocity_mode, setup_trace),
        cmocka_unit_test_setup(nmt_guarding_heartbeat, setup),
        cmocka_unit_test_setup(heartbeat_consumer_and_error_behaviour, setup),
        cmocka_unit_test_setup(heartbeat_loss_with_fault_mask, setup),
        cmocka_unit_test_setup(statusword_change_requests_tpdos, setup),
        cmocka_unit_test_setup(enable_by_sdo_and_rpdo, setup),
        cmocka_unit_test_setup(fault_and_emcy_example, setup),
        cmocka_unit_test_setup(errors_do_not_fault_by_default, setup),
        cmocka_unit_test_setup(relative_move, setup),
        cmocka_unit_test_setup(velocity_host_example, setup),
        cmocka_unit_test_setup(homing, setup),
        cmocka_unit_test_setup(pdo_setup_and_rtr, setup),
        cmocka_unit_test_setup(factor_group, setup),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
