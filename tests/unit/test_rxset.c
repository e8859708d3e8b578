/*
 * The COB-ID set for hardware filters: co_node_rx_cob lists the CAN-IDs the
 * node acts on, and the rx_set callback says when that set was made anew
 * (init, a heartbeat consumer, a PDO made valid or not).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "co/co_node.h"
#include "generic_301.h"
#include "test_bus.h"

typedef struct fx {
    tb_bus_t bus;
    generic_301_node_t n;
    unsigned notices;
    co_node_callbacks_t cb;
} fx_t;

static void on_rx_set(void *ctx, co_node_t *node)
{
    (void)node;
    ((fx_t *)ctx)->notices++;
}

static int setup(void **state)
{
    static fx_t fx;
    co_node_config_t cfg;
    memset(&fx, 0, sizeof fx);
    tb_init(&fx.bus);
    generic_301_config(&fx.n, &cfg);
    cfg.hal = tb_hal(&fx.bus, 0);
    cfg.node_id = 5U;
    fx.cb.ctx = &fx;
    fx.cb.rx_set = on_rx_set;
    cfg.cb = &fx.cb;
    assert_int_equal(co_node_init(&fx.n.node, &cfg, 0U), CO_RESULT_OK);
    tb_attach(&fx.bus, 0, &fx.n.node);
    tb_flush(&fx.bus);
    *state = &fx;
    return 0;
}

#define FX ((fx_t *)*state)
#define BUS (&FX->bus)
#define NODE (&FX->n.node)

static int cmp(const void *a, const void *b)
{
    return (int)*(const uint16_t *)a - (int)*(const uint16_t *)b;
}

/* the set, sorted, as text "000 080 ..." */
static void set_text(const co_node_t *node, char *out)
{
    uint16_t cobs[64];
    uint16_t n = 0U;
    while (co_node_rx_cob(node, n, &cobs[n])) {
        n++;
        assert_true(n < 64U);
    }
    qsort(cobs, n, sizeof cobs[0], cmp);
    out[0] = '\0';
    for (uint16_t k = 0; k < n; k++) {
        char w[8];
        snprintf(w, sizeof w, (k == 0U) ? "%03X" : " %03X", (unsigned)cobs[k]);
        strcat(out, w);
    }
}

static void set_follows_the_configuration(void **state)
{
    char text[512];
    assert_int_equal(FX->notices, 1U); /* at init */
    set_text(NODE, text);
    /* NMT, SYNC, TPDO1/2 (RTR), RPDO1/2, SDO, guarding, LSS (generic-301 is an LSS slave) */
    assert_string_equal(text, "000 080 185 205 285 305 605 705 7E5");
    /* heartbeat consumer of node 9: 0x709 joins */
    tb_xfer(BUS, "605 23 16 10 01 E8 03 09 00", "585 60 16 10 01 00 00 00 00");
    assert_int_equal(FX->notices, 2U);
    set_text(NODE, text);
    assert_string_equal(text, "000 080 185 205 285 305 605 705 709 7E5");
    /* RPDO2 not valid: 0x305 leaves */
    tb_xfer(BUS, "605 23 01 14 01 05 03 00 80", "585 60 01 14 01 00 00 00 00");
    assert_true(FX->notices >= 3U);
    set_text(NODE, text);
    assert_string_equal(text, "000 080 185 205 285 605 705 709 7E5");
}

/* The receive dispatch by function code (COB-ID >> 7): a frame reaches its
 * slot whether the function code has one slot (a neighbouring COB-ID of it
 * is another node's) or several (a service and a PDO, several services),
 * also the first frame after an application's COB-ID change. */
static void frames_reach_their_slot(void **state)
{
    static const uint8_t sync_1f0[4] = {0xF0, 0x01, 0x00, 0x00};
    /* TPDO1 synchronous (type 1), Operational */
    tb_xfer(BUS, "605 2F 00 18 02 01 00 00 00", "585 60 00 18 02 00 00 00 00");
    tb_send(BUS, "000 01 05");
    tb_flush(BUS);
    /* one slot per function code: 0x204 and 0x206 are not RPDO1's */
    tb_send(BUS, "204 11 22 00 33 00 00 00");
    tb_send(BUS, "206 11 22 00 33 00 00 00");
    tb_xfer(BUS, "605 40 00 21 00 00 00 00 00", "585 4F 00 21 00 00 00 00 00");
    tb_send(BUS, "205 11 22 00 33 00 00 00");
    tb_xfer(BUS, "605 40 00 21 00 00 00 00 00", "585 4F 00 21 00 11 00 00 00");
    tb_send(BUS, "080");
    tb_expect(BUS, "185 00 11 22 00 00 00 00 00");
    tb_expect_none(BUS);
    /* SYNC on 0x1F0 (written by the application: the first frame finds the
     * table stale) shares function code 3 with TPDO1's remote requests */
    assert_int_equal(co_od_write(NODE, 0x1005U, 0U, sync_1f0, 4U, false), CO_OK);
    tb_send(BUS, "1F0");
    tb_expect(BUS, "185 00 11 22 00 00 00 00 00");
    tb_expect_none(BUS);
    tb_send(BUS, "080");
    tb_send(BUS, "1F1");
    tb_send(BUS, "186 R8");
    tb_expect_none(BUS);
    tb_send(BUS, "185 R8");
    tb_expect(BUS, "185 00 11 22 00 00 00 00 00");
    tb_send(BUS, "1F0");
    tb_expect(BUS, "185 00 11 22 00 00 00 00 00");
    tb_expect_none(BUS);
    /* guarding (0x705) and a heartbeat consumer (0x709) share function code
     * 14: each frame reaches its own */
    tb_xfer(BUS, "605 23 16 10 01 64 00 09 00", "585 60 16 10 01 00 00 00 00");
    tb_send(BUS, "709 05");
    tb_send(BUS, "706 R1");
    tb_expect_none(BUS);
    tb_send(BUS, "705 R1");
    tb_expect(BUS, "705 05");
    tb_expect_none(BUS);
    /* node 9's heartbeat stops: the consumer (100 ms) reports it */
    tb_advance(BUS, 100000U + 1023U); /* (within 1023 us: co_hb.c) */
    tb_expect(BUS, "085 30 81 11 00 00 00 00 00");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(set_follows_the_configuration, setup),
        cmocka_unit_test_setup(frames_reach_their_slot, setup),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
