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
    cfg.cb.ctx = &fx;
    cfg.cb.rx_set = on_rx_set;
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

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(set_follows_the_configuration, setup),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
