/*
 * The node's service table: its documented order (docs/core.md) and what
 * the order means on the bus: timers run in table order, so frames that
 * fall due at the same co_node_process leave as heartbeat (error control),
 * then a held-back EMCY, then the SYNC. Also the public names: the node's
 * time and the NMT command constants.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "co_priv.h"
#include "test_bus.h"
#include "test_dev.h"


static tb_bus_t bus;
static td_node_t n;

#define BUS (&bus)
#define NODE (&n.node)

static int setup(void **state)
{
    (void)state;
    tb_init(&bus);
    td_start(&n, &bus, 0, 1, NULL);
    tb_expect(BUS, "701 00");
    return 0;
}

static void test_table_order(void **state)
{
    const co_service_t *const want[] = {
#if CO_LSS
                                        &co_svc_lss, /* first: alone while unconfigured */
#endif
                                        &co_svc_nmt,  &co_svc_sdo,  &co_svc_errctl,
                                        &co_svc_emcy, &co_svc_sync, &co_svc_time,
                                        &co_svc_pdo,  &co_svc_store};

    (void)state;
    assert_int_equal(CO_N_SERVICES, sizeof want / sizeof want[0]);
    /* co_node_t.svc_run (co_svc_bits_t, co_node.h) has a bit for every row
     * and is the narrowest such type (its formula matches the table) */
    assert_true(CO_N_SERVICES <= 8U * sizeof(co_svc_bits_t));
    assert_true(CO_N_SERVICES > 8U * (sizeof(co_svc_bits_t) - 1U));
    for (uint8_t k = 0U; k < CO_N_SERVICES; k++) {
        assert_ptr_equal(co_services[k], want[k]);
    }
    /* every row of co_binds[] given (a row left out would be zeros: no
     * object 0x1000 is bound) */
    for (uint8_t k = 0U; k < CO_N_BINDS; k++) {
        assert_int_not_equal(co_binds[k].index, 0U);
    }
    /* every service's objects have its hook, from the const table */
    {
        static const struct {
            uint16_t index;
            uint8_t row;
        } own[] = {
            {0x1003U, CO_ROW_EMCY},   {0x1014U, CO_ROW_EMCY},   {0x1015U, CO_ROW_EMCY},
            {0x1005U, CO_ROW_SYNC},   {0x1007U, CO_ROW_SYNC},   {0x1019U, CO_ROW_SYNC},
#if CO_NODE_GUARDING
            {0x100CU, CO_ROW_ERRCTL}, {0x100DU, CO_ROW_ERRCTL},
#endif
            {0x1016U, CO_ROW_ERRCTL}, {0x1017U, CO_ROW_ERRCTL}, {0x1010U, CO_ROW_STORE},
            {0x1011U, CO_ROW_STORE},
#if CO_TIME
            {0x1012U, CO_ROW_TIME},
#endif
#if CO_ERROR_BEHAVIOUR
            {0x1029U, CO_ROW_NMT},
#endif
            {0x1400U, CO_ROW_PDO},    {0x1BFFU, CO_ROW_PDO},
        };
        for (size_t k = 0U; k < sizeof own / sizeof own[0]; k++) {
            unsigned slot = CO_OD_SVC_OF(own[k].index);
            assert_true((slot >= 1U) && (slot <= CO_SVC_N_HOOKS));
            assert_int_equal(co_svc_hooks[slot - 1U].row, own[k].row);
        }
        for (size_t k = 0U; k < CO_SVC_N_HOOKS; k++) {
            assert_non_null(co_svc_hooks[k].fn);
            assert_int_not_equal(co_svc_hooks[k].ops, 0U);
        }
    }
}

static void put(uint16_t index, uint32_t v, uint32_t len)
{
    uint8_t d[4] = {(uint8_t)v, (uint8_t)(v >> 8), (uint8_t)(v >> 16), (uint8_t)(v >> 24)};
    assert_int_equal(co_od_write(NODE, index, 0U, d, len, true), CO_OK);
}

/* heartbeat, held-back EMCY and SYNC due at the same time: table order */
static void test_process_order(void **state)
{
    (void)state;
    put(0x1015U, 10U, 2U);          /* EMCY inhibit 1 ms */
    put(0x1017U, 1U, 2U);           /* heartbeat every 1 ms */
    put(0x1005U, 0x40000080UL, 4U); /* this node produces SYNC */
    put(0x1006U, 1000U, 4U);        /* every 1 ms */
    co_emcy_raise(NODE, 0x1000U, 0U, NULL);
    tb_expect(BUS, "081 00 10 01 00 00 00 00 00");
    co_emcy_raise(NODE, 0x5000U, CO_ERREG_CURRENT, NULL); /* held back by the inhibit time */
    tb_expect_none(BUS);
    tb_advance(BUS, 1000U);
    tb_expect(BUS, "701 7F");                       /* error control */
    tb_expect(BUS, "081 00 50 03 00 00 00 00 00");  /* EMCY */
    tb_expect(BUS, "080");                          /* SYNC */
    tb_expect_none(BUS);
}

/* the NMT command names and the node's time */
/* co_node_init copies the head of the configuration (dev .. cb) into the
 * node at once: the same fields in the same places in both. */
static void test_config_head(void **state)
{
    (void)state;
    assert_int_equal(offsetof(co_node_config_t, dev), offsetof(co_node_t, dev));
    assert_int_equal(offsetof(co_node_config_t, hal), offsetof(co_node_t, hal));
    assert_int_equal(offsetof(co_node_config_t, ram), offsetof(co_node_t, ram));
    assert_int_equal(offsetof(co_node_config_t, cb), offsetof(co_node_t, cb));
    assert_int_equal(offsetof(co_node_config_t, node_id),
                     offsetof(co_node_t, cb) + sizeof(((co_node_t *)0)->cb));
}

static void test_public_names(void **state)
{
    (void)state;
    co_node_nmt_command(NODE, CO_NMT_CMD_START, 1234U);
    assert_int_equal(co_node_nmt_state(NODE), CO_NMT_OPERATIONAL);
    assert_int_equal(co_node_now(NODE), 1234U);
    co_node_nmt_command(NODE, CO_NMT_CMD_STOP, 1300U);
    assert_int_equal(co_node_nmt_state(NODE), CO_NMT_STOPPED);
    co_node_nmt_command(NODE, CO_NMT_CMD_PRE_OPERATIONAL, 1400U);
    assert_int_equal(co_node_nmt_state(NODE), CO_NMT_PRE_OPERATIONAL);
    co_node_nmt_command(NODE, CO_NMT_CMD_RESET_COMMUNICATION, 1500U);
    tb_expect(BUS, "701 00");
    co_node_nmt_command(NODE, CO_NMT_CMD_RESET_NODE, 1600U);
    tb_expect(BUS, "701 00");
    assert_int_equal(co_node_now(NODE), 1600U);
    tb_send(BUS, "000 01 01");
    assert_int_equal(co_node_now(NODE), bus.now);
    assert_int_equal(co_node_nmt_state(NODE), CO_NMT_OPERATIONAL);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(test_table_order, setup),
        cmocka_unit_test_setup(test_process_order, setup),
        cmocka_unit_test_setup(test_public_names, setup),
        cmocka_unit_test(test_config_head),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
