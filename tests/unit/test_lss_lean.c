/*
 * LSS in a core that builds no personality deviations (CO_PERSONALITY=0,
 * CO_LSS=1) on the lss-test device: LSS is a service, not a deviation, so
 * such a core accepts an LSS slave and runs LSS for it. An unconfigured
 * node sends no boot-up, answers LSS, takes a node-ID and boots with it.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "lss_test.h"
#include "test_bus.h"

#if CO_PERSONALITY || !CO_LSS
#error "test_lss_lean is built against a core with LSS and without personality deviations"
#endif

static tb_bus_t bus;
static lss_test_node_t node;

static void unconfigured_node_answers_lss(void **state)
{
    co_node_config_t cfg;

    (void)state;
    memset(&node, 0, sizeof node);
    tb_init(&bus);
    lss_test_config(&node, &cfg);
    cfg.hal = tb_hal(&bus, 0);
    cfg.node_id = CO_NODE_ID_UNCONFIGURED;
    assert_int_equal(co_node_init(&node.node, &cfg, bus.now), CO_RESULT_OK);
    tb_attach(&bus, 0, &node.node);
    tb_expect_none(&bus); /* unconfigured: no boot-up */
    tb_send(&bus, "7E5 04 01 00 00 00 00 00 00"); /* switch state global: configuration */
    tb_expect_none(&bus);
    tb_xfer(&bus, "7E5 5E 00 00 00 00 00 00 00", "7E4 5E FF 00 00 00 00 00 00"); /* node-ID? */
    tb_xfer(&bus, "7E5 11 07 00 00 00 00 00 00", "7E4 11 00 00 00 00 00 00 00"); /* configure 7 */
    tb_send(&bus, "7E5 04 00 00 00 00 00 00 00"); /* back to waiting: initialises with 7 */
    tb_expect(&bus, "707 00");
    tb_expect_none(&bus);
    assert_int_equal(co_node_id(&node.node), 7U);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(unconfigured_node_answers_lss),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
