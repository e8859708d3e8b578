/*
 * The core built with the minimal slave's options (no storage, no TIME, no
 * SYNC producer, no value limits, no personality options, 4 heartbeat
 * consumers;
 * targets/cortex-m/minimal-config.cmake) on the lean-test device: the
 * services it keeps work with exact frames, 0x1010/0x1011 behave as without
 * non-volatile memory, and devices that need what is left out are refused.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "co/co_endian.h"
#include "lean_test.h"
#include "test_bus.h"
#include "test_dev.h"

static tb_bus_t bus;
static lean_test_node_t lean;
#define BUS (&bus)

static co_result_t start_id(const co_dev_t *dev, uint8_t id)
{
    co_node_config_t cfg;
    co_result_t err;

    memset(&lean, 0, sizeof lean);
    tb_init(&bus);
    lean_test_config(&lean, &cfg);
    cfg.dev = dev;
    cfg.hal = tb_hal(&bus, 0);
    cfg.node_id = id;
    err = co_node_init(&lean.node, &cfg, bus.now);
    if (err == CO_RESULT_OK) {
        tb_attach(&bus, 0, &lean.node);
    }
    return err;
}

static co_result_t start(const co_dev_t *dev)
{
    return start_id(dev, 1U);
}

static uint32_t get_u32(uint16_t index, uint8_t sub)
{
    uint8_t b[4] = {0};
    uint32_t len = 0;
    assert_int_equal(co_od_read(&lean.node, index, sub, b, sizeof b, &len), CO_OK);
    return co_get_u32(b);
}

static void storage_left_out(void **state)
{
    (void)state;
    assert_int_equal(start(&lean_test_dev), CO_RESULT_OK);
    tb_expect(BUS, "701 00");
    /* capability 0 on a HAL with NV; save and restore answer 0x08000020 */
    tb_xfer(BUS, "601 40 10 10 01 00 00 00 00", "581 43 10 10 01 00 00 00 00");
    tb_xfer(BUS, "601 40 11 10 03 00 00 00 00", "581 43 11 10 03 00 00 00 00");
    tb_xfer(BUS, "601 23 10 10 01 73 61 76 65", "581 80 10 10 01 20 00 00 08");
    tb_xfer(BUS, "601 23 11 10 01 6C 6F 61 64", "581 80 11 10 01 20 00 00 08");
    assert_int_equal(bus.nv_written, 0U);
    tb_expect_none(BUS);
    {
        /* the commands need no RAM in such a build: one writable const 0
         * (odgen), whose writes the store service refuses, the
         * application's as well; the sub-index 0 stays read-only */
        static const uint8_t save[4] = {0x73U, 0x61U, 0x76U, 0x65U};
        const co_od_entry_t *st = co_od_find(lean_test_dev.od, lean_test_dev.od_count, 0x1010U);
        assert_non_null(st);
        co_od_sub_t d;
        assert_non_null(co_od_find_sub(&lean_test_dev, st, 1U, &d));
        assert_int_equal(d.flags & (CO_SUB_ROM | CO_SUB_W), CO_SUB_ROM | CO_SUB_W);
        assert_null(co_od_value_ptr(&lean.node, 0x1011U, 2U));
        assert_int_equal(co_od_write(&lean.node, 0x1010U, 1U, save, 4U, true), CO_ERR_STORE);
        assert_int_equal(co_od_write(&lean.node, 0x1010U, 0U, save, 1U, true), CO_ERR_READ_ONLY);
        tb_xfer(BUS, "601 2F 10 10 00 01 00 00 00", "581 80 10 10 00 02 00 01 06");
        tb_xfer(BUS, "601 40 10 10 03 00 00 00 00", "581 43 10 10 03 00 00 00 00");
    }
}

/* The application's write hook: the writes it was asked about. */
static co_err_t count_writes(void *ctx, co_od_io_t *io)
{
    (void)io;
    (*(uint32_t *)ctx)++;
    return CO_OK;
}

/* A build without storage refuses a save or restore command in the store
 * service's check, before an application's hook on 0x1010 is asked (the
 * device here: lean-test with a hook slot on 0x1010; the command's value is
 * never read or written). */
static void store_command_refused_before_app_hook(void **state)
{
    static co_od_entry_t od[64];
    static co_dev_t dev;
    /* the node's storage: the RAM image, then the hook table */
    typedef struct {
        lean_test_ram_t ram;
        co_od_hook_t hooks[1];
    } store_t;
    static store_t store;
    co_node_config_t cfg;
    uint32_t asked = 0U;
    bool hooked = false;
    (void)state;
    assert_true(lean_test_dev.od_count <= 64U);
    memcpy(od, lean_test_dev.od, lean_test_dev.od_count * sizeof od[0]);
    for (uint16_t i = 0U; i < lean_test_dev.od_count; i++) {
        if (od[i].index == 0x1010U) {
            od[i].tag = (uint8_t)(od[i].tag | CO_OD_TAG_HOOK);
            od[i].base = 0U; /* its slot */
            hooked = true;
        }
    }
    assert_true(hooked);
    dev = lean_test_dev;
    dev.od = od;
    dev.n_hooks = 1U;
    dev.hooks_at = (uint16_t)offsetof(store_t, hooks);
    memset(&lean, 0, sizeof lean);
    memset(&store, 0, sizeof store);
    tb_init(&bus);
    lean_test_config(&lean, &cfg);
    cfg.dev = &dev;
    cfg.hal = tb_hal(&bus, 0);
    cfg.node_id = 1U;
    cfg.ram = &store;
    assert_int_equal(co_node_init(&lean.node, &cfg, bus.now), CO_RESULT_OK);
    store.hooks[0].write = count_writes; /* (the node's init clears the slots) */
    store.hooks[0].ctx = &asked;
    tb_attach(&bus, 0, &lean.node);
    tb_expect(BUS, "701 00");
    tb_xfer(BUS, "601 23 10 10 01 73 61 76 65", "581 80 10 10 01 20 00 00 08");
    tb_xfer(BUS, "601 23 10 10 02 73 61 76 65", "581 80 10 10 02 20 00 00 08");
    assert_int_equal(asked, 0U);
    assert_int_equal(bus.nv_written, 0U);
    tb_expect_none(BUS);
}

static void services_kept(void **state)
{
    uint8_t v[4];
    (void)state;
    assert_int_equal(start(&lean_test_dev), CO_RESULT_OK);
    tb_expect(BUS, "701 00");
    /* SDO: expedited, and a segmented download of a mapping entry */
    tb_xfer(BUS, "601 40 08 10 00 00 00 00 00", "581 47 08 10 00 6D 69 6E 00");
    tb_xfer(BUS, "601 21 00 22 00 04 00 00 00", "581 60 00 22 00 00 00 00 00");
    tb_xfer(BUS, "601 07 44 33 22 11 00 00 00", "581 20 00 00 00 00 00 00 00");
    assert_int_equal(get_u32(0x2200, 0), 0x11223344UL);
    /* PDO: RPDO1 (255) into 0x2100, TPDO1 (SYNC) from 0x2200 */
    tb_send(BUS, "000 01 01");
    tb_send(BUS, "201 01 02 03 04");
    assert_int_equal(get_u32(0x2100, 0), 0x04030201UL);
    tb_send(BUS, "080");
    tb_expect(BUS, "181 44 33 22 11");
    co_put_u32(v, 0x55667788UL);
    assert_int_equal(co_od_write(&lean.node, 0x2200, 0, v, 4, true), CO_OK);
    tb_send(BUS, "080");
    tb_expect(BUS, "181 88 77 66 55");
    /* heartbeat consumer 4 of 4: node 5 every 100 ms, lost: EMCY 0x8130 */
    tb_xfer(BUS, "601 23 16 10 04 64 00 05 00", "581 60 16 10 04 00 00 00 00");
    tb_send(BUS, "705 05");
    tb_advance(BUS, 150000);
    tb_expect(BUS, "081 30 81 11 00 00 00 00 00");
    assert_int_equal(get_u32(0x1003, 1), 0x00008130UL);
    tb_send(BUS, "705 05");
    tb_expect(BUS, "081 00 00 00 00 00 00 00 00");
    /* TIME is left out */
    assert_int_equal(co_time_send(&lean.node, 0, 0), CO_ERR_NO_ACCESS);
    tb_expect_none(BUS);
}

/* The generated dictionary of a build without value limits: sub-entries
 * without a limit index (8 bytes each) and sparse defaults (only the values
 * that are not zero, co_dev_t.defaults); a reset communication restores
 * values of both kinds and the $NODEID-relative ones. */
static void compact_dictionary(void **state)
{
    uint16_t subs = 0U;
    (void)state;
    assert_int_equal(sizeof(co_od_sub_t), 8U);
    for (uint16_t i = 0U; i < lean_test_dev.od_count; i++) {
        subs = (uint16_t)(subs + lean_test_dev.od[i].nsubs);
    }
    assert_non_null(lean_test_dev.defaults);
    assert_true((lean_test_dev.n_defaults > 0U) && (lean_test_dev.n_defaults < subs / 2U));
    assert_int_equal(start(&lean_test_dev), CO_RESULT_OK);
    tb_expect(BUS, "701 00");
    tb_xfer(BUS, "601 23 05 10 00 81 00 00 00", "581 60 05 10 00 00 00 00 00");
    tb_xfer(BUS, "601 23 16 10 01 00 00 07 00", "581 60 16 10 01 00 00 00 00");
    tb_xfer(BUS, "601 23 00 14 01 01 02 00 80", "581 60 00 14 01 00 00 00 00");
    assert_int_equal(get_u32(0x1005, 0), 0x81UL);
    assert_int_equal(get_u32(0x1016, 1), 0x00070000UL);
    tb_send(BUS, "000 82 01");
    tb_expect(BUS, "701 00");
    assert_int_equal(get_u32(0x1005, 0), 0x80UL);
    assert_int_equal(get_u32(0x1016, 1), 0UL);
    assert_int_equal(get_u32(0x1400, 1), 0x201UL);
    assert_int_equal(get_u32(0x1600, 1), 0x21000020UL);
}

/* Objects of the same shape share one table of sub-entries whose RAM
 * offsets count from each entry's base: RPDO1 and TPDO1 here (their
 * communication parameters, and their mapping parameters), 0x1010 and
 * 0x1011. Every value still has a place
 * of its own: SDO writes land in the right field of the RAM image and a
 * reset communication restores each PDO's own defaults. */
static void shared_sub_tables(void **state)
{
    const co_od_entry_t *r = co_od_find(lean_test_dev.od, lean_test_dev.od_count, 0x1400U);
    const co_od_entry_t *t = co_od_find(lean_test_dev.od, lean_test_dev.od_count, 0x1800U);
    const co_od_entry_t *rm = co_od_find(lean_test_dev.od, lean_test_dev.od_count, 0x1600U);
    const co_od_entry_t *tm = co_od_find(lean_test_dev.od, lean_test_dev.od_count, 0x1A00U);
    const co_od_entry_t *st = co_od_find(lean_test_dev.od, lean_test_dev.od_count, 0x1010U);
    const co_od_entry_t *rs = co_od_find(lean_test_dev.od, lean_test_dev.od_count, 0x1011U);
    (void)state;
    assert_non_null(r);
    assert_non_null(t);
    assert_non_null(rm);
    assert_non_null(tm);
    assert_non_null(st);
    assert_non_null(rs);
    assert_int_equal(r->rows, t->rows);
    assert_int_equal(rm->rows, tm->rows);
    assert_int_equal(st->rows, rs->rows);
    assert_int_equal(r->base, offsetof(lean_test_ram_t, x1400_cob_id_used_by_rpdo));
    assert_int_equal(t->base, offsetof(lean_test_ram_t, x1800_cob_id_used_by_tpdo));
    assert_int_equal(rm->base, offsetof(lean_test_ram_t, x1600_rpdo1_mapping_parameter));
    assert_int_equal(tm->base, offsetof(lean_test_ram_t, x1A00_tpdo1_mapping_parameter));
    assert_int_equal(co_od_code(r), CO_OBJ_RECORD);
    assert_int_equal(co_od_code(st), CO_OBJ_ARRAY);
    assert_int_equal(start(&lean_test_dev), CO_RESULT_OK);
    tb_expect(BUS, "701 00");
    /* each PDO's own defaults ($NODEID + 0x200 / 0x180) */
    assert_int_equal(lean.ram.x1400_cob_id_used_by_rpdo, 0x201UL);
    assert_int_equal(lean.ram.x1800_cob_id_used_by_tpdo, 0x181UL);
    /* writes through the shared tables reach the values of their own PDO */
    tb_xfer(BUS, "601 23 00 18 01 81 01 00 80", "581 60 00 18 01 00 00 00 00");
    tb_xfer(BUS, "601 2F 00 18 02 05 00 00 00", "581 60 00 18 02 00 00 00 00");
    tb_xfer(BUS, "601 2F 00 1A 00 00 00 00 00", "581 60 00 1A 00 00 00 00 00");
    tb_xfer(BUS, "601 23 00 1A 01 10 00 00 22", "581 60 00 1A 01 00 00 00 00");
    /* (a COB-ID in its 16-bit form, co_od.h CO_SUB_COB16) */
    assert_int_equal(lean.ram.x1800_cob_id_used_by_tpdo, 0x8181U);
    assert_int_equal(co_od_cob_u32(lean.ram.x1800_cob_id_used_by_tpdo), 0x80000181UL);
    /* bits 29..11 have no 16-bit form: refused, the old value stays */
    tb_xfer(BUS, "601 23 00 18 01 81 09 00 80", "581 80 00 18 01 30 00 09 06");
    tb_xfer(BUS, "601 23 00 18 01 81 01 00 A0", "581 80 00 18 01 30 00 09 06");
    assert_int_equal(lean.ram.x1800_cob_id_used_by_tpdo, 0x8181U);
    assert_int_equal(lean.ram.x1800_transmission_type, 5U);
    /* (a mapping entry in its 16-bit form, co_od.h) */
    assert_int_equal(co_od_map_u32(&lean_test_dev, lean.ram.x1A00_tpdo1_mapping_parameter[0]),
                     0x22000010UL);
    assert_int_equal(lean.ram.x1A00_number_of_mapped_objects, 0U);
    assert_int_equal(lean.ram.x1400_cob_id_used_by_rpdo, 0x201UL);
    assert_int_equal(get_u32(0x1600, 1), 0x21000020UL);
    tb_xfer(BUS, "601 40 00 18 01 00 00 00 00", "581 43 00 18 01 81 01 00 80");
    tb_xfer(BUS, "601 40 00 14 01 00 00 00 00", "581 43 00 14 01 01 02 00 00");
    tb_xfer(BUS, "601 40 00 1A 01 00 00 00 00", "581 43 00 1A 01 10 00 00 22");
    /* and a reset communication gives each its own default back */
    tb_send(BUS, "000 82 01");
    tb_expect(BUS, "701 00");
    assert_int_equal(lean.ram.x1800_cob_id_used_by_tpdo, 0x181UL);
    assert_int_equal(lean.ram.x1400_cob_id_used_by_rpdo, 0x201UL);
    tb_expect_none(BUS);
}

static void refuses_what_is_left_out(void **state)
{
    static const co_od_limit_t limits[1] = {{0, 10}};
    co_dev_t dev = lean_test_dev;
    td_node_t td;
    co_node_config_t cfg;
    (void)state;
    /* a personality option or an LSS slave: a core without personality
     * and LSS has no co_dev_t.set; a dictionary that needs one does not
     * compile against it (tests/gen/test_build_options.py
     * test_personality_guard_without_build). The unconfigured node-ID
     * (0xFF) is no node-ID for a build without LSS. */
    assert_int_equal(start_id(&dev, CO_NODE_ID_UNCONFIGURED), CO_RESULT_BAD_NODE_ID);
    tb_expect_none(BUS);
    /* value limits */
    dev.limits = limits;
    assert_int_equal(start(&dev), CO_RESULT_DEV_INCOMPAT);
    tb_expect_none(BUS);
    dev.limits = NULL;
    /* a node-ID object (a manufacturer's deviation, Wandfluh's 0x2000) */
    dev.nodeid_index = 0x2000U;
    assert_int_equal(start(&dev), CO_RESULT_DEV_INCOMPAT);
    tb_expect_none(BUS);
    dev.nodeid_index = 0U;
    /* error behaviour 0x1029 (the description's entries plus one) */
    {
        /* (its row after the description's rows) */
        static co_od_sub_t rows[256];
        static co_od_entry_t od[64];
        uint16_t n = 0U;
        uint16_t n_rows = 0U;
        bool added = false;
        assert_true(lean_test_dev.od_count < 64U);
        for (uint16_t i = 0U; i < lean_test_dev.od_count; i++) {
            const co_od_entry_t *e = &lean_test_dev.od[i];
            if ((uint16_t)(e->rows + e->nsubs) > n_rows) {
                n_rows = (uint16_t)(e->rows + e->nsubs);
            }
        }
        assert_true(n_rows < 256U);
        memcpy(rows, lean_test_dev.rows, n_rows * sizeof rows[0]);
        rows[n_rows] = (co_od_sub_t)CO_OD_SUB(1U, (uint8_t)CO_UNSIGNED8, CO_SUB_RW, 1U, 0U, 0U);
        for (uint16_t i = 0U; i < lean_test_dev.od_count; i++) {
            if (!added && (lean_test_dev.od[i].index > 0x1029U)) {
                od[n] = lean_test_dev.od[i];
                od[n].index = 0x1029U;
                od[n].nsubs = 1U;
                od[n].base = 0U;
                od[n].tag = CO_OD_TAG(0x1029U, CO_OBJ_ARRAY, false);
                od[n].rows = n_rows;
                n++;
                added = true;
            }
            od[n++] = lean_test_dev.od[i];
        }
        assert_true(added);
        dev.od = od;
        dev.rows = rows;
        dev.od_count = n;
        assert_int_equal(start(&dev), CO_RESULT_DEV_INCOMPAT);
        tb_expect_none(BUS);
        dev.od = lean_test_dev.od;
        dev.rows = lean_test_dev.rows;
        dev.od_count = lean_test_dev.od_count;
    }
    assert_int_equal(start(&dev), CO_OK);
    tb_expect(BUS, "701 00");
    /* the test device has TIME (0x1012) and a SYNC producer (0x1006) */
    memset(&td, 0, sizeof td);
    memset(&cfg, 0, sizeof cfg);
    cfg.dev = &td_dev;
    cfg.hal = tb_hal(&bus, 1);
    cfg.node_id = 2;
    cfg.ram = &td.ram;
    assert_int_equal(co_node_init(&td.node, &cfg, bus.now), CO_RESULT_DEV_INCOMPAT);
    tb_expect_none(BUS);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(storage_left_out),
        cmocka_unit_test(store_command_refused_before_app_hook),
        cmocka_unit_test(services_kept),
        cmocka_unit_test(compact_dictionary),
        cmocka_unit_test(shared_sub_tables),
        cmocka_unit_test(refuses_what_is_left_out),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
