/*
 * The core built with the minimal slave's options and also without block SDO
 * and without node guarding (CO_SDO_BLOCK=0, CO_NODE_GUARDING=0) on the
 * lean-test device: block requests answer 0x05040001 like an unknown
 * command, a guarding RTR gets no answer, the expedited and segmented SDO
 * and the heartbeat keep working, and a device with 0x100C/0x100D is refused.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "lean_test.h"
#include "test_bus.h"
#include "test_dev.h"

#if CO_SDO_BLOCK || CO_NODE_GUARDING
#error "test_bare is built against a core without block SDO and node guarding"
#endif

static tb_bus_t bus;
static lean_test_node_t lean;
#define BUS (&bus)

static int setup(void **state)
{
    co_node_config_t cfg;

    (void)state;
    memset(&lean, 0, sizeof lean);
    tb_init(&bus);
    lean_test_config(&lean, &cfg);
    cfg.hal = tb_hal(&bus, 0);
    cfg.node_id = 1;
    assert_int_equal(co_node_init(&lean.node, &cfg, bus.now), CO_RESULT_OK);
    tb_attach(&bus, 0, &lean.node);
    tb_expect(BUS, "701 00");
    return 0;
}

static void block_sdo_left_out(void **state)
{
    (void)state;
    /* block upload and block download initiate: unknown command */
    tb_xfer(BUS, "601 A4 08 10 00 7F 00 00 00", "581 80 08 10 00 01 00 04 05");
    tb_xfer(BUS, "601 C6 00 22 00 04 00 00 00", "581 80 00 22 00 01 00 04 05");
    /* expedited and segmented stay */
    tb_xfer(BUS, "601 40 08 10 00 00 00 00 00", "581 47 08 10 00 6D 69 6E 00");
    tb_xfer(BUS, "601 21 00 22 00 04 00 00 00", "581 60 00 22 00 00 00 00 00");
    tb_xfer(BUS, "601 07 44 33 22 11 00 00 00", "581 20 00 00 00 00 00 00 00");
}

static void guarding_left_out(void **state)
{
    (void)state;
    tb_send(BUS, "701 R1");
    tb_expect_none(BUS);
    /* the heartbeat producer stays */
    tb_xfer(BUS, "601 2B 17 10 00 64 00 00 00", "581 60 17 10 00 00 00 00 00");
    tb_advance(BUS, 100000);
    tb_expect(BUS, "701 7F");
}

static void guarding_device_refused(void **state)
{
    td_node_t td;
    co_node_config_t cfg;

    (void)state;
    /* td_dev has 0x100C / 0x100D (and TIME, SYNC producer) */
    memset(&td, 0, sizeof td);
    memset(&cfg, 0, sizeof cfg);
    cfg.dev = &td_dev;
    cfg.hal = tb_hal(&bus, 1);
    cfg.node_id = 2;
    cfg.ram = &td.ram;
    cfg.hooks = td.hooks;
    assert_int_equal(co_node_init(&td.node, &cfg, bus.now), CO_RESULT_DEV_INCOMPAT);
    tb_expect_none(BUS);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(block_sdo_left_out, setup),
        cmocka_unit_test_setup(guarding_left_out, setup),
        cmocka_unit_test_setup(guarding_device_refused, setup),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
