/*
 * A generated device without the core's objects that have places in the
 * RAM image (co_node.h, CO_RAM_*) but 0x1001 (tests/unit/devices/
 * absent-test.toml): odgen leaves zeros in their places, and the node
 * behaves as without them: no SYNC consumer (and the window always open),
 * no heartbeat producer or consumers, EMCY on 0x80 + node-ID without an
 * inhibit time, no error history (0x1003 absent, the register 0x1001 at its
 * place still counts the errors).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "absent_test.h"
#include "test_bus.h"

static tb_bus_t bus;
static absent_test_node_t abs_node;
static unsigned syncs;
#define BUS (&bus)

static void on_sync(void *ctx, co_node_t *node, uint8_t counter)
{
    (void)ctx;
    (void)node;
    (void)counter;
    syncs++;
}

static const co_node_callbacks_t cbs = {.sync = on_sync};

static int setup(void **state)
{
    co_node_config_t cfg;

    (void)state;
    memset(&abs_node, 0, sizeof abs_node);
    syncs = 0U;
    tb_init(&bus);
    absent_test_config(&abs_node, &cfg);
    cfg.hal = tb_hal(&bus, 0);
    cfg.node_id = 5;
    cfg.cb = &cbs;
    assert_int_equal(co_node_init(&abs_node.node, &cfg, bus.now), CO_RESULT_OK);
    tb_attach(&bus, 0, &abs_node.node);
    tb_expect(BUS, "705 00");
    return 0;
}

/* The places hold zeros (no default is restored there), and no object
 * answers for them. */
static void places_hold_zeros(void **state)
{
    static const uint16_t absent[] = {0x1003U, 0x1005U, 0x1007U, 0x1014U,
                                      0x1015U, 0x1016U, 0x1017U, 0x1019U};
    const uint8_t *ram = (const uint8_t *)&abs_node.ram;
    uint8_t zeros[CO_RAM_1019 + 1U];

    (void)state;
    memset(zeros, 0, sizeof zeros);
    assert_memory_equal(ram, zeros, sizeof zeros);
    assert_int_equal(abs_node.ram.core_x1003, 0U);
    assert_ptr_equal(co_od_value_ptr(&abs_node.node, 0x1001U, 0U),
                     &ram[absent_test_dev.app_end + CO_RAM_END_1001]);
    for (size_t k = 0U; k < sizeof absent / sizeof absent[0]; k++) {
        assert_null(co_od_value_ptr(&abs_node.node, absent[k], 0U));
    }
    tb_xfer(BUS, "605 40 03 10 00 00 00 00 00", "585 80 03 10 00 00 00 02 06");
    tb_xfer(BUS, "605 40 19 10 00 00 00 00 00", "585 80 19 10 00 00 00 02 06");
    /* the device's own value after the head keeps its default */
    tb_xfer(BUS, "605 40 00 20 00 00 00 00 00", "585 43 00 20 00 44 33 22 11");
}

/* No SYNC consumer (0x1005's place 0: CAN-ID 0 is NMT's), and no heartbeat
 * consumer: the node acts on NMT, SDO, and its guarding identifier only; a
 * SYNC does nothing, the window is always open; no heartbeat goes out. */
static void no_sync_no_heartbeat(void **state)
{
    uint16_t cob;
    uint16_t n = 0U;

    (void)state;
    for (uint16_t i = 0U; co_node_rx_cob(&abs_node.node, i, &cob); i++) {
        /* NMT, SDO and (with guarding) its own error control identifier:
         * no SYNC, no heartbeat consumer */
        assert_true((cob == 0x000U) || (cob == 0x605U) || (cob == 0x705U));
        n++;
    }
    assert_int_equal(n, 2U + (unsigned)CO_NODE_GUARDING);
    tb_send(BUS, "000 01 05");
    tb_send(BUS, "080");
    tb_send(BUS, "080 01");
    assert_int_equal(syncs, 0U);
    assert_true(co_sync_window_open(&abs_node.node));
    tb_advance(BUS, 10000000U);
    assert_true(co_sync_window_open(&abs_node.node));
    tb_expect_none(BUS);
}

/* EMCY on 0x80 + node-ID, one right after the other (no inhibit time);
 * 0x1001 at its place has the bits; no history to read. */
static void emcy_without_its_objects(void **state)
{
    (void)state;
    co_emcy_raise(&abs_node.node, 0x1000U, 0U, NULL);
    tb_expect(BUS, "085 00 10 01 00 00 00 00 00");
    co_emcy_raise(&abs_node.node, 0x8110U, CO_ERREG_COMM, NULL);
    tb_expect(BUS, "085 10 81 11 00 00 00 00 00");
    tb_expect_none(BUS);
    tb_xfer(BUS, "605 40 01 10 00 00 00 00 00", "585 4F 01 10 00 11 00 00 00");
    assert_int_equal(abs_node.ram.core_x1003, 0U);
    co_emcy_clear(&abs_node.node, 0x1000U);
    co_emcy_clear(&abs_node.node, 0x8110U);
    tb_expect(BUS, "085 00 00 00 00 00 00 00 00");
    tb_xfer(BUS, "605 40 01 10 00 00 00 00 00", "585 4F 01 10 00 00 00 00 00");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(places_hold_zeros, setup),
        cmocka_unit_test_setup(no_sync_no_heartbeat, setup),
        cmocka_unit_test_setup(emcy_without_its_objects, setup),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
