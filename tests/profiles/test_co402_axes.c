/*
 * Several CiA 402 axes in one node: logical devices at index offsets of
 * 0x800 (CiA 301), one co402 axis and one plant each. Each axis has its own
 * state machine, mode and motion; a device that lacks an axis' objects
 * refuses to attach it.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "cia402_2axis.h"
#include "co/co402.h"
#include "co/co402_sim.h"
#include "co/co_profile.h"
#include "test_bus.h"

typedef struct fx {
    tb_bus_t bus;
    cia402_2axis_node_t n;
    co_profile_host_t host;
    co_profile_t slots[3];
    co402_axis_t ax[3];
    co402_sim_t sim[3];
} fx_t;

static fx_t fx;
#define BUS (&fx.bus)

static int setup(void **state)
{
    co_node_config_t cfg;
    co402_sim_config_t sc;
    (void)state;
    memset(&fx, 0, sizeof fx);
    tb_init(BUS);
    co_profile_host_init(&fx.host, fx.slots, 3, NULL);
    co402_sim_defaults(&sc);
    for (uint8_t i = 0; i < 2U; i++) {
        co402_config_t ac;
        co402_sim_init(&fx.sim[i], &sc, BUS->now);
        memset(&ac, 0, sizeof ac);
        ac.axis = i;
        ac.plant = co402_sim_plant(&fx.sim[i]);
        co402_init(&fx.ax[i], &ac);
        assert_int_equal(co_profile_add(&fx.host, &co402_profile_ops, &fx.ax[i]), CO_OK);
    }
    cia402_2axis_config(&fx.n, &cfg);
    cfg.hal = tb_hal(BUS, 0);
    cfg.node_id = 2;
    cfg.cb = co_profile_host_callbacks(&fx.host);
    tb_attach(BUS, 0, &fx.n.node);
    assert_int_equal(co_node_init(&fx.n.node, &cfg, BUS->now), CO_RESULT_OK);
    assert_int_equal(co_profile_host_attach(&fx.host, &fx.n.node, BUS->now), CO_OK);
    tb_expect(BUS, "702 00");
    return 0;
}

static void run(uint32_t us)
{
    uint32_t end = BUS->now + us;
    while ((int32_t)(end - BUS->now) > 0) {
        BUS->now += 1000U;
        (void)co_node_process(&fx.n.node, BUS->now);
        (void)co_profile_host_process(&fx.host, BUS->now);
    }
}

static void axes_are_independent(void **state)
{
    (void)state;
    /* both boot into Switch on disabled */
    tb_xfer(BUS, "602 40 41 60 00 00 00 00 00", "582 4B 41 60 00 50 02 00 00");
    tb_xfer(BUS, "602 40 41 68 00 00 00 00 00", "582 4B 41 68 00 50 02 00 00");
    /* axis 2 only */
    tb_xfer(BUS, "602 2B 40 68 00 06 00 00 00", "582 60 40 68 00 00 00 00 00");
    tb_xfer(BUS, "602 2B 40 68 00 0F 00 00 00", "582 60 40 68 00 00 00 00 00");
    tb_xfer(BUS, "602 40 41 68 00 00 00 00 00", "582 4B 41 68 00 37 02 00 00");
    tb_xfer(BUS, "602 40 41 60 00 00 00 00 00", "582 4B 41 60 00 50 02 00 00");
    assert_int_equal(co402_state(&fx.ax[0]), CO402_SWITCH_ON_DISABLED);
    assert_int_equal(co402_state(&fx.ax[1]), CO402_OPERATION_ENABLED);
    /* axis 2 in pv, axis 1 in pp: each moves its own plant */
    tb_xfer(BUS, "602 2F 60 68 00 03 00 00 00", "582 60 60 68 00 00 00 00 00");
    tb_xfer(BUS, "602 40 61 68 00 00 00 00 00", "582 4F 61 68 00 03 00 00 00");
    tb_xfer(BUS, "602 40 61 60 00 00 00 00 00", "582 4F 61 60 00 01 00 00 00");
    tb_xfer(BUS, "602 23 FF 68 00 30 F8 FF FF", "582 60 FF 68 00 00 00 00 00"); /* -2000 */
    tb_xfer(BUS, "602 2B 40 60 00 06 00 00 00", "582 60 40 60 00 00 00 00 00");
    tb_xfer(BUS, "602 2B 40 60 00 0F 00 00 00", "582 60 40 60 00 00 00 00 00");
    tb_xfer(BUS, "602 23 7A 60 00 E8 03 00 00", "582 60 7A 60 00 00 00 00 00"); /* 1000 */
    tb_xfer(BUS, "602 2B 40 60 00 1F 00 00 00", "582 60 40 60 00 00 00 00 00");
    tb_xfer(BUS, "602 40 41 60 00 00 00 00 00", "582 4B 41 60 00 37 12 00 00");
    tb_xfer(BUS, "602 2B 40 60 00 0F 00 00 00", "582 60 40 60 00 00 00 00 00");
    run(1000000);
    tb_xfer(BUS, "602 40 64 60 00 00 00 00 00", "582 43 64 60 00 E8 03 00 00");
    tb_xfer(BUS, "602 40 6C 68 00 00 00 00 00", "582 43 6C 68 00 30 F8 FF FF");
    assert_int_equal(co402_sim_position(&fx.sim[0]), 1000);
    assert_true(co402_sim_position(&fx.sim[1]) < -1500);
    /* a fault on axis 2 leaves axis 1 alone */
    co402_fault_raise(&fx.ax[1], 0x2310);
    run(100000);
    assert_int_equal(co402_state(&fx.ax[1]), CO402_FAULT);
    assert_int_equal(co402_state(&fx.ax[0]), CO402_OPERATION_ENABLED);
    tb_flush(BUS);
    tb_xfer(BUS, "602 40 41 68 00 00 00 00 00", "582 4B 41 68 00 18 02 00 00");
    /* what the device does not have, the axis does not offer */
    tb_xfer(BUS, "602 2F 60 68 00 06 00 00 00", "582 80 60 68 00 30 00 09 06"); /* homing */
    tb_xfer(BUS, "602 2F 60 60 00 03 00 00 00", "582 60 60 60 00 00 00 00 00");
}

static void missing_axis_is_refused(void **state)
{
    co402_config_t ac;
    co_profile_host_t h;
    co_profile_t slot;
    (void)state;
    memset(&ac, 0, sizeof ac);
    ac.axis = 2; /* 0x7040 does not exist */
    ac.plant = co402_sim_plant(&fx.sim[2]);
    co402_init(&fx.ax[2], &ac);
    co_profile_host_init(&h, &slot, 1, NULL);
    assert_int_equal(co_profile_add(&h, &co402_profile_ops, &fx.ax[2]), CO_OK);
    assert_int_equal(co_profile_host_attach(&h, &fx.n.node, BUS->now), CO_ERR_OD_MISSING);
    assert_int_equal(co_profile_host_process(&h, BUS->now), CO_NO_DEADLINE);
    /* axis numbers above 7 are no logical device at all */
    ac.axis = 8;
    co402_init(&fx.ax[2], &ac);
    assert_int_equal(co402_profile_ops.attach(&fx.ax[2], &fx.n.node, BUS->now), CO_ERR_VALUE);
    /* nor is an axis without a plant */
    ac.axis = 1;
    ac.plant.ops = NULL;
    co402_init(&fx.ax[2], &ac);
    assert_int_equal(co402_profile_ops.attach(&fx.ax[2], &fx.n.node, BUS->now), CO_ERR_VALUE);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(axes_are_independent, setup),
        cmocka_unit_test_setup(missing_axis_is_refused, setup),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
