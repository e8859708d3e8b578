/*
 * Seed 004, the WANDFLUH DSV valve electronics (digest
 * ../shared/spec/seed-004-wandfluh-dsv-dsp408.md): the derived test vectors
 * D1 .. D35 of digest 6.2 and the deviations of 8.1, replayed frame by frame
 * against devices/wandfluh-dsv.toml with the CiA 408 profile on the
 * simulated valve (one node, node-ID 1 unless a test says otherwise).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "co408_devices.h"
#include "test_bus.h"
#include "wandfluh_dsv.h"

static struct {
    tb_bus_t bus;
    wandfluh_dsv_node_t n;
    co408_unit_t u;
    co408_sim_t sim[CO408_UNIT_CHANNELS_MAX];
} fx;

#define BUS (&fx.bus)
#define NODE (&fx.n.node)

/* Power on node @p id (the NV memory of the bus stays as it is). */
static void power_on(uint8_t id)
{
    const co408_device_t *d = &co408_dev_wandfluh_dsv;
    co408_plant_t plants[CO408_UNIT_CHANNELS_MAX];
    co_node_config_t cfg;
    char boot[16];

    for (uint8_t i = 0U; i < d->channels; i++) {
        co408_sim_config_t sc;
        co408_device_sim_config(d, i, &sc);
        co408_sim_init(&fx.sim[i], &sc, fx.bus.now);
        plants[i] = co408_sim_plant(&fx.sim[i]);
    }
    assert_int_equal(co408_unit_init(&fx.u, d, plants, NULL), CO_OK);
    wandfluh_dsv_config(&fx.n, &cfg);
    cfg.hal = tb_hal(&fx.bus, 0);
    cfg.node_id = id;
    cfg.cb = co408_unit_callbacks(&fx.u);
    tb_attach(&fx.bus, 0, NODE);
    assert_int_equal(co_node_init(NODE, &cfg, fx.bus.now), CO_RESULT_OK);
    assert_int_equal(co408_unit_attach(&fx.u, NODE, fx.bus.now), CO_OK);
    snprintf(boot, sizeof boot, "%03X 00", 0x700U + NODE->node_id);
    tb_expect(BUS, boot); /* D1 */
}

static int setup(void **state)
{
    (void)state;
    memset(&fx, 0, sizeof fx);
    tb_init(&fx.bus);
    power_on(1);
    return 0;
}

/* The channels first, then the node: what a frame or a tick changed goes
 * out at once (the TPDO right after the RPDO). */
static void poll(void)
{
    (void)co408_unit_process(&fx.u, fx.bus.now);
    (void)co_node_process(NODE, fx.bus.now);
}

static void run_ms(uint32_t ms)
{
    for (uint32_t i = 0U; i < ms; i++) {
        fx.bus.now += 1000U;
        poll();
    }
}

/* A frame from the master, then the node processes. */
static void send(const char *text)
{
    tb_send(BUS, text);
    poll();
}

#define xfer(req, resp)                                                                          \
    do {                                                                                         \
        send(req);                                                                               \
        tb_expect(BUS, resp);                                                                    \
        tb_expect_none(BUS);                                                                     \
    } while (0)

/* ---------------------------------------------------------- identity */

static void d8_d12_identity_and_defaults(void **state)
{
    (void)state;
    xfer("601 40 00 10 00 00 00 00 00", "581 43 00 10 00 98 01 00 10"); /* D8, 8.1 item 1 */
    xfer("601 40 18 10 00 00 00 00 00", "581 4F 18 10 00 01 00 00 00"); /* D9, item 2 */
    xfer("601 40 18 10 01 00 00 00 00", "581 43 18 10 01 4D 01 00 00");
    xfer("601 40 18 10 04 00 00 00 00", "581 43 18 10 04 00 00 00 00");
    xfer("601 40 01 10 00 00 00 00 00", "581 4F 01 10 00 00 00 00 00"); /* D10 */
    xfer("601 40 05 10 00 00 00 00 00", "581 43 05 10 00 80 00 00 00"); /* D11 */
    xfer("601 40 14 10 00 00 00 00 00", "581 43 14 10 00 81 00 00 00");
    xfer("601 40 00 14 01 00 00 00 00", "581 43 00 14 01 01 02 00 00");
    xfer("601 40 00 18 01 00 00 00 00", "581 43 00 18 01 81 01 00 00");
    xfer("601 40 00 18 00 00 00 00 00", "581 4F 00 18 00 02 00 00 00"); /* D12, item 4 */
    xfer("601 40 00 18 02 00 00 00 00", "581 4F 00 18 02 FF 00 00 00");
    xfer("601 40 00 1A 00 00 00 00 00", "581 4F 00 1A 00 01 00 00 00");
    xfer("601 40 00 1A 01 00 00 00 00", "581 43 00 1A 01 10 00 41 60");
    xfer("601 40 00 16 01 00 00 00 00", "581 43 00 16 01 10 00 40 60");
    xfer("601 40 00 16 02 00 00 00 00", "581 43 00 16 02 10 01 00 63");
    xfer("601 40 00 14 00 00 00 00 00", "581 4F 00 14 00 02 00 00 00");
    /* channel 2 and PDO 3 / 4 (items 5, 18) */
    xfer("601 40 01 16 01 00 00 00 00", "581 43 01 16 01 10 00 40 68");
    xfer("601 40 01 1A 01 00 00 00 00", "581 43 01 1A 01 10 00 41 68");
    xfer("601 40 03 14 01 00 00 00 00", "581 43 03 14 01 01 05 00 00");
    xfer("601 40 03 18 01 00 00 00 00", "581 43 03 18 01 81 04 00 00");
    xfer("601 40 03 1A 00 00 00 00 00", "581 4F 03 1A 00 00 00 00 00");
    xfer("601 40 41 60 00 00 00 00 00", "581 4B 41 60 00 08 00 00 00"); /* INIT, item 21 */
    xfer("601 40 41 68 00 00 00 00 00", "581 4B 41 68 00 08 00 00 00");
}

/* D29 .. D31 and the deviations of the SDO server (items 3, 4, 6, 7, 14). */
static void aborts(void **state)
{
    (void)state;
    xfer("601 40 34 12 00 00 00 00 00", "581 80 34 12 00 00 00 02 06"); /* D29 */
    xfer("601 40 18 10 05 00 00 00 00", "581 80 18 10 05 11 00 09 06"); /* D30 */
    xfer("601 23 00 10 00 00 00 00 00", "581 80 00 10 00 00 00 01 06"); /* D31 */
    /* item 3: the RPDO COB-ID is read-only */
    xfer("601 23 00 14 01 01 02 00 80", "581 80 00 14 01 00 00 01 06");
    /* item 4: no inhibit time, no event timer */
    xfer("601 40 00 18 03 00 00 00 00", "581 80 00 18 03 11 00 09 06");
    xfer("601 2B 00 18 05 00 00 00 00", "581 80 00 18 05 11 00 09 06");
    /* item 6: four mapping entries */
    xfer("601 40 00 1A 05 00 00 00 00", "581 80 00 1A 05 11 00 09 06");
    /* item 14: objects the device does not have */
    xfer("601 40 06 10 00 00 00 00 00", "581 80 06 10 00 00 00 02 06");
    xfer("601 40 16 10 01 00 00 00 00", "581 80 16 10 01 00 00 02 06");
    xfer("601 40 15 10 00 00 00 00 00", "581 80 15 10 00 00 00 02 06");
    /* item 7: segmented download refused at its initiate */
    xfer("601 21 54 60 00 0B 00 00 00", "581 80 54 60 00 00 00 01 06");
}

/* D34: segmented upload of 0x6057. */
static void d34_segmented_upload(void **state)
{
    (void)state;
    xfer("601 40 57 60 00 00 00 00 00", "581 41 57 60 00 0B 00 00 00");
    xfer("601 60 00 00 00 00 00 00 00", "581 00 57 61 6E 64 66 6C 75");
    xfer("601 70 00 00 00 00 00 00 00", "581 17 68 20 41 47 00 00 00");
}

/* ----------------------------------------------------- error control */

/* D5, D6, D7: heartbeat, the guard-time refusal, node guarding. */
static void d5_d7_error_control(void **state)
{
    (void)state;
    xfer("601 2B 17 10 00 E8 03 00 00", "581 60 17 10 00 00 00 00 00"); /* D5 */
    run_ms(999);
    tb_expect_none(BUS);
    run_ms(1);
    tb_expect(BUS, "701 7F");
    xfer("601 2B 0C 10 00 64 00 00 00", "581 80 0C 10 00 23 00 0A 06"); /* D6, item 8 */
    xfer("601 2F 0D 10 00 03 00 00 00", "581 80 0D 10 00 23 00 0A 06");
    xfer("601 40 0C 10 00 00 00 00 00", "581 4B 0C 10 00 00 00 00 00"); /* unchanged */
    xfer("601 2B 17 10 00 00 00 00 00", "581 60 17 10 00 00 00 00 00");
    xfer("601 2B 0C 10 00 64 00 00 00", "581 60 0C 10 00 00 00 00 00"); /* D7 */
    xfer("601 2F 0D 10 00 03 00 00 00", "581 60 0D 10 00 00 00 00 00");
    xfer("701 R1", "701 7F");
    xfer("701 R1", "701 FF");
    xfer("701 R1", "701 7F");
    send("000 01 01");
    tb_flush(BUS);
    xfer("701 R1", "701 85");
    xfer("701 R1", "701 05");
}

/* -------------------------------------------------- store / restore */

static void d13_d17_store_restore(void **state)
{
    (void)state;
    xfer("601 40 10 10 01 00 00 00 00", "581 43 10 10 01 01 00 00 00"); /* D15 */
    xfer("601 40 10 10 00 00 00 00 00", "581 4F 10 10 00 03 00 00 00");
    xfer("601 23 10 10 01 00 00 00 00", "581 80 10 10 01 20 00 00 08"); /* D14, item 8 */
    xfer("601 2B 17 10 00 F4 01 00 00", "581 60 17 10 00 00 00 00 00");
    xfer("601 23 29 23 00 00 00 00 00", "581 60 29 23 00 00 00 00 00"); /* window 0.. */
    xfer("601 23 10 10 01 73 61 76 65", "581 60 10 10 01 00 00 00 00"); /* D13 */
    send("000 81 01");
    tb_expect(BUS, "701 00");
    xfer("601 40 17 10 00 00 00 00 00", "581 4B 17 10 00 F4 01 00 00");
    xfer("601 40 29 23 00 00 00 00 00", "581 43 29 23 00 00 00 00 00");
    /* D16: restore the defaults; they act after the reset */
    xfer("601 23 11 10 01 6C 6F 61 64", "581 60 11 10 01 00 00 00 00");
    xfer("601 40 17 10 00 00 00 00 00", "581 4B 17 10 00 F4 01 00 00");
    send("000 81 01");
    tb_expect(BUS, "701 00");
    xfer("601 40 17 10 00 00 00 00 00", "581 4B 17 10 00 00 00 00 00");
    xfer("601 40 29 23 00 00 00 00 00", "581 43 29 23 00 00 C0 FF FF");
    xfer("601 2F 03 10 00 00 00 00 00", "581 60 03 10 00 00 00 00 00"); /* D17 */
}

/* Item 9: the node-ID of 0x2000 takes effect at Reset Communication. */
static void node_id_on_reset_comm(void **state)
{
    (void)state;
    xfer("601 40 00 20 00 00 00 00 00", "581 4F 00 20 00 01 00 00 00");
    xfer("601 2F 00 20 00 05 00 00 00", "581 60 00 20 00 00 00 00 00");
    xfer("601 2B 01 20 00 F4 01 00 00", "581 60 01 20 00 00 00 00 00"); /* 500 kbit/s */
    xfer("601 2F 00 20 00 80 00 00 00", "581 80 00 20 00 31 00 09 06"); /* 1..127 */
    xfer("601 40 00 20 00 00 00 00 00", "581 4F 00 20 00 05 00 00 00");
    send("000 82 01");
    tb_expect(BUS, "705 00");
    tb_expect(BUS, "085 00 81 11 00 00 00 00 00"); /* the profile's 0x8100 (item 10) */
    tb_expect_none(BUS);
    send("601 40 00 10 00 00 00 00 00");
    tb_expect_none(BUS);
    xfer("605 40 14 10 00 00 00 00 00", "585 43 14 10 00 85 00 00 00");
    xfer("605 40 00 14 01 00 00 00 00", "585 43 00 14 01 05 02 00 00");
    /* stored, the node-ID holds over power-on */
    xfer("605 23 10 10 03 73 61 76 65", "585 60 10 10 03 00 00 00 00");
    power_on(1);
    xfer("605 40 00 20 00 00 00 00 00", "585 4F 00 20 00 05 00 00 00");
    xfer("605 40 01 20 00 00 00 00 00", "585 4B 01 20 00 F4 01 00 00");
}

/* ----------------------------------------------------------- the valve */

/* D18 .. D21, D32: commissioning by SDO, the chained enable, the mode
 * change refused while active. */
static void d18_d21_commissioning(void **state)
{
    (void)state;
    xfer("601 2F 4F 60 00 00 00 00 00", "581 60 4F 60 00 00 00 00 00"); /* D18 */
    xfer("601 2F 42 60 00 01 00 00 00", "581 60 42 60 00 00 00 00 00");
    xfer("601 2F 43 60 00 01 00 00 00", "581 60 43 60 00 00 00 00 00");
    xfer("601 2F 43 60 00 FB 00 00 00", "581 60 43 60 00 00 00 00 00"); /* D19: -5 */
    xfer("601 40 43 60 00 00 00 00 00", "581 4F 43 60 00 FB 00 00 00");
    xfer("601 2F 43 60 00 02 00 00 00", "581 80 43 60 00 43 00 04 06"); /* no mode 2 */
    xfer("601 2F 43 68 00 04 00 00 00", "581 80 43 68 00 43 00 04 06"); /* channel 2 */
    xfer("601 2F 43 60 00 01 00 00 00", "581 60 43 60 00 00 00 00 00");
    xfer("601 2B 40 60 00 07 00 00 00", "581 60 40 60 00 00 00 00 00"); /* D20 */
    xfer("601 40 41 60 00 00 00 00 00", "581 4B 41 60 00 0F 00 00 00");
    xfer("601 2F 42 60 00 02 00 00 00", "581 80 42 60 00 22 00 00 08"); /* D32 */
    xfer("601 2B 00 63 01 00 20 00 00", "581 60 00 63 01 00 00 00 00"); /* D21 */
    xfer("601 23 00 66 01 A0 86 01 00", "581 60 00 66 01 00 00 00 00");
    run_ms(400);
    assert_in_range(fx.sim[0].y >> 16, 8100, 8200); /* the valve opened to 50 % */
}

/* D22 .. D24: the set-point by RPDO, each answered by TPDO1 at once. */
static void d22_d24_pdo(void **state)
{
    (void)state;
    send("000 01 01"); /* D2 */
    tb_expect(BUS, "181 08 00");
    tb_expect(BUS, "281 08 00");
    tb_expect_none(BUS);
    send("201 07 00 00 20"); /* D22 */
    tb_expect(BUS, "181 0F 00");
    tb_expect_none(BUS);
    send("201 07 00 00 20"); /* nothing changed: the TPDO all the same (type 255) */
    tb_expect(BUS, "181 0F 00");
    tb_expect_none(BUS);
    run_ms(400);
    tb_expect_none(BUS);
    assert_in_range(fx.sim[0].y >> 16, 8100, 8200);
    send("201 03 00 00 20"); /* D23 */
    tb_expect(BUS, "181 0B 00");
    tb_expect_none(BUS);
    send("201 00 00 00 00"); /* D24 */
    tb_expect(BUS, "181 08 00");
    tb_expect_none(BUS);
    /* channel 2 by RPDO2 / TPDO2 */
    send("301 07 00 00 E0");
    tb_expect(BUS, "281 0F 00");
    tb_expect_none(BUS);
    run_ms(400);
    assert_in_range(fx.sim[1].y >> 16, -8200, -8100);
    /* D35: SYNC alone sends nothing (every PDO has type 255) */
    send("080");
    tb_expect_none(BUS);
}

/* D33: TPDO1 re-mapped to status word + vprc actual value. */
static void d33_remap(void **state)
{
    (void)state;
    xfer("601 23 00 18 01 81 01 00 80", "581 60 00 18 01 00 00 00 00");
    xfer("601 2F 00 1A 00 00 00 00 00", "581 60 00 1A 00 00 00 00 00");
    xfer("601 23 00 1A 01 10 00 41 60", "581 60 00 1A 01 00 00 00 00");
    xfer("601 23 00 1A 02 10 01 81 63", "581 60 00 1A 02 00 00 00 00");
    xfer("601 2F 00 1A 00 02 00 00 00", "581 60 00 1A 00 00 00 00 00");
    xfer("601 23 00 18 01 81 01 00 00", "581 60 00 18 01 00 00 00 00");
    xfer("601 2F 43 60 00 04 00 00 00", "581 60 43 60 00 00 00 00 00");
    xfer("601 2B 80 63 01 00 20 00 00", "581 60 80 63 01 00 00 00 00"); /* vprc: 50 % */
    send("000 01 01");
    tb_expect(BUS, "181 08 00 00 00");
    tb_expect(BUS, "281 08 00");
    send("201 07 00 00 20"); /* RPDO1 still maps the vpoc set-point: not used in vprc */
    tb_expect(BUS, "181 0F 00 00 00"); /* vprc closed loop: the pressure still 0 */
    tb_flush(BUS);
    run_ms(300);
    tb_flush(BUS);
    send("201 07 00 00 20");
    {
        const co_frame_t *f = tb_next(BUS);
        assert_non_null(f);
        assert_int_equal(f->id, 0x181);
        assert_int_equal(f->dlc, 4);
        assert_int_equal(f->data[0], 0x0F);
        assert_in_range((uint32_t)(f->data[2] | (f->data[3] << 8)), 8100, 8300);
    }
}

/* D25 .. D28: a solenoid cable break, the other EMCYs, the fault resets. */
static void d25_d28_faults(void **state)
{
    (void)state;
    xfer("601 2B 40 60 00 07 00 00 00", "581 60 40 60 00 00 00 00 00");
    co408_sim_inject(&fx.sim[0], CO408_SIM_SOL_A_OPEN);
    run_ms(1);
    tb_expect(BUS, "081 11 23 03 00 00 00 00 00"); /* D25 */
    tb_expect_none(BUS);
    xfer("601 40 03 10 01 00 00 00 00", "581 43 03 10 01 11 23 00 00");
    run_ms(1);
    xfer("601 40 41 60 00 00 00 00 00", "581 4B 41 60 00 03 00 00 00"); /* FAULT_HOLD */
    co408_sim_inject(&fx.sim[0], 0U);
    run_ms(1);
    xfer("601 2B 40 60 00 03 00 00 00", "581 60 40 60 00 00 00 00 00"); /* D28 */
    xfer("601 2B 40 60 00 0B 00 00 00", "581 60 40 60 00 00 00 00 00");
    xfer("601 40 41 60 00 00 00 00 00", "581 4B 41 60 00 0B 00 00 00");
    run_ms(1);
    tb_expect(BUS, "081 00 00 00 00 00 00 00 00");
    /* D26 */
    xfer("601 2B 40 60 00 01 00 00 00", "581 60 40 60 00 00 00 00 00");
    co408_sim_inject(&fx.sim[0], CO408_SIM_UNDERVOLT);
    run_ms(2);
    tb_expect(BUS, "081 12 34 05 00 00 00 00 00");
    xfer("601 40 41 60 00 00 00 00 00", "581 4B 41 60 00 01 00 00 00"); /* FAULT */
    co408_sim_inject(&fx.sim[0], CO408_SIM_SP_CABLE);
    run_ms(1);
    tb_expect(BUS, "081 22 34 05 00 00 00 00 00");
    co408_sim_inject(&fx.sim[0], 0U);
    run_ms(1);
    xfer("601 2B 40 60 00 09 00 00 00", "581 60 40 60 00 00 00 00 00"); /* D27 */
    xfer("601 40 41 60 00 00 00 00 00", "581 4B 41 60 00 09 00 00 00");
    run_ms(1);
    tb_expect(BUS, "081 00 00 00 00 00 00 00 00");
    tb_expect_none(BUS);
    xfer("601 2B 40 60 00 01 00 00 00", "581 60 40 60 00 00 00 00 00");
    xfer("601 2B 40 60 00 07 00 00 00", "581 60 40 60 00 00 00 00 00");
    xfer("601 40 41 60 00 00 00 00 00", "581 4B 41 60 00 0F 00 00 00");
    co408_fault_raise(co408_unit_valve(&fx.u, 0), 0x1000);
    tb_expect(BUS, "081 00 10 01 00 00 00 00 00");
}

/* D3, D4: NMT Stop and Reset Communication force the fault (item 10),
 * Reset Node INIT, Pre-operational nothing. */
static void d3_d4_nmt(void **state)
{
    (void)state;
    xfer("601 2B 40 60 00 07 00 00 00", "581 60 40 60 00 00 00 00 00");
    send("000 80 01");
    tb_expect_none(BUS);
    xfer("601 40 41 60 00 00 00 00 00", "581 4B 41 60 00 0F 00 00 00");
    send("000 02 01"); /* D3: no EMCY in Stopped */
    run_ms(10);
    tb_expect_none(BUS);
    send("000 80 01");
    tb_expect(BUS, "081 00 81 11 00 00 00 00 00");
    tb_expect_none(BUS);
    xfer("601 40 41 60 00 00 00 00 00", "581 4B 41 60 00 03 00 00 00");
    xfer("601 40 41 68 00 00 00 00 00", "581 4B 41 68 00 01 00 00 00");
    send("000 82 01"); /* D4: reset comm, TR_8 again */
    tb_expect(BUS, "701 00");
    tb_expect_none(BUS); /* 0x8100 is still active: no second EMCY */
    send("000 81 01"); /* reset node: INIT, the errors gone */
    tb_expect(BUS, "701 00");
    tb_expect_none(BUS);
    xfer("601 40 41 60 00 00 00 00 00", "581 4B 41 60 00 08 00 00 00");
    xfer("601 40 01 10 00 00 00 00 00", "581 4F 01 10 00 00 00 00 00");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(d8_d12_identity_and_defaults, setup),
        cmocka_unit_test_setup(aborts, setup),
        cmocka_unit_test_setup(d34_segmented_upload, setup),
        cmocka_unit_test_setup(d5_d7_error_control, setup),
        cmocka_unit_test_setup(d13_d17_store_restore, setup),
        cmocka_unit_test_setup(node_id_on_reset_comm, setup),
        cmocka_unit_test_setup(d18_d21_commissioning, setup),
        cmocka_unit_test_setup(d22_d24_pdo, setup),
        cmocka_unit_test_setup(d33_remap, setup),
        cmocka_unit_test_setup(d25_d28_faults, setup),
        cmocka_unit_test_setup(d3_d4_nmt, setup),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
