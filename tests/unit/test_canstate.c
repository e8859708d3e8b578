/*
 * CAN controller state in the core (co/co_canstate.h): error passive,
 * bus-off and overrun give the CiA 301 EMCY codes with the communication bit
 * in 0x1001, bus-off applies 0x1029 sub 1 once per entry into bus-off, and
 * the EMCY raised while the bus is off leaves when the controller is back.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "co/co_canstate.h"
#include "test_bus.h"
#include "test_dev.h"

typedef struct fx {
    tb_bus_t bus;
    td_node_t n;
} fx_t;

static int setup(void **state)
{
    static fx_t fx;
    memset(&fx, 0, sizeof fx);
    tb_init(&fx.bus);
    td_start(&fx.n, &fx.bus, 0, 1, NULL);
    tb_flush(&fx.bus);
    *state = &fx;
    return 0;
}

#define FX ((fx_t *)*state)
#define BUS (&FX->bus)
#define NODE (&FX->n.node)

static void error_passive_and_back(void **state)
{
    co_node_can_state(NODE, CO_CAN_ERROR_PASSIVE, BUS->now);
    tb_expect(BUS, "081 20 81 11 00 00 00 00 00");
    tb_expect_none(BUS);
    co_node_can_state(NODE, CO_CAN_ERROR_PASSIVE, BUS->now); /* again: nothing */
    tb_expect_none(BUS);
    tb_xfer(BUS, "601 40 01 10 00 00 00 00 00", "581 4F 01 10 00 11 00 00 00");
    co_node_can_state(NODE, CO_CAN_ERROR_ACTIVE, BUS->now);
    tb_expect(BUS, "081 00 00 00 00 00 00 00 00");
    tb_expect_none(BUS);
    co_node_can_state(NODE, CO_CAN_ERROR_ACTIVE, BUS->now);
    tb_expect_none(BUS);
}

static void bus_off_applies_error_behaviour_once(void **state)
{
    tb_send(BUS, "000 01 01"); /* Operational */
    tb_flush(BUS);
    assert_int_equal(co_node_nmt_state(NODE), CO_NMT_OPERATIONAL);
    BUS->refuse = 1000U;       /* the controller is off the bus */
    co_node_can_state(NODE, CO_CAN_BUS_OFF, BUS->now);
    /* 0x1029 sub 1 = 0: Operational -> Pre-operational */
    assert_int_equal(co_node_nmt_state(NODE), CO_NMT_PRE_OPERATIONAL);
    tb_advance(BUS, 1000U);
    tb_expect_none(BUS);       /* held back while the bus is off */
    co_node_nmt_command(NODE, 0x01U, BUS->now);
    co_node_can_state(NODE, CO_CAN_BUS_OFF, BUS->now); /* still off: no new behaviour */
    assert_int_equal(co_node_nmt_state(NODE), CO_NMT_OPERATIONAL);
    BUS->refuse = 0U;          /* back on the bus */
    tb_advance(BUS, 1000U);
    tb_expect(BUS, "081 40 81 11 00 00 00 00 00");
    tb_expect_none(BUS);
    co_node_can_state(NODE, CO_CAN_ERROR_ACTIVE, BUS->now);
    tb_expect(BUS, "081 00 00 00 00 00 00 00 00");
    tb_expect_none(BUS);
}

static void passive_after_bus_off_clears_it(void **state)
{
    co_node_can_state(NODE, CO_CAN_BUS_OFF, BUS->now);
    tb_expect(BUS, "081 40 81 11 00 00 00 00 00");
    co_node_can_state(NODE, CO_CAN_ERROR_PASSIVE, BUS->now);
    tb_expect(BUS, "081 20 81 11 00 00 00 00 00"); /* 0x8140 cleared, 0x8120 remains */
    tb_expect_none(BUS);
    assert_false(co_emcy_is_active(NODE, CO_EMCY_CAN_BUSOFF));
    assert_true(co_emcy_is_active(NODE, CO_EMCY_CAN_PASSIVE));
}

static void overrun_is_an_event(void **state)
{
    co_node_can_overrun(NODE, false);
    tb_expect_none(BUS);
    co_node_can_overrun(NODE, true);
    tb_expect(BUS, "081 10 81 11 00 00 00 00 00");
    co_node_can_overrun(NODE, true);
    tb_expect_none(BUS);
    co_node_can_overrun(NODE, false);
    tb_expect(BUS, "081 00 00 00 00 00 00 00 00");
    tb_expect_none(BUS);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(error_passive_and_back, setup),
        cmocka_unit_test_setup(bus_off_applies_error_behaviour_once, setup),
        cmocka_unit_test_setup(passive_after_bus_off_clears_it, setup),
        cmocka_unit_test_setup(overrun_is_an_event, setup),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
