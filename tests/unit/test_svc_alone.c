/*
 * One service against the dictionary engine, nothing else of the core
 * compiled in: this executable links co_od.c and co_store.c only, with its
 * own service table (a recording service and parameter storage) and its own
 * small dictionary. Shows the hook chain (a service's check before the
 * application's hook, the service's written after the commit, a veto at any
 * step leaves the old value), which objects each slot of the const hook
 * table owns, the refusal of a second application hook on one object, and
 * storage acting on 0x1010 without the value being stored.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "co/co_endian.h"
#include "co_priv.h"

/* ---- what the engine and the storage service see of the node */

typedef struct ram {
    uint32_t v1005;   /* 0x1005: owned by the recording service, hook slot 0 */
    uint32_t v3000;   /* 0x3000: nobody's */
    uint32_t save[1]; /* 0x1010 sub1 */
    uint8_t save_n;   /* 0x1010 sub0 */
    co_od_hook_t hooks[1]; /* the hook table (co_dev_t.hooks_at; not an object) */
} ram_t;

/* the rows of 0x1005 (0), 0x1010 (1, 2) and 0x3000 (3) */
static const co_od_sub_t rows[] = {
    {0, CO_UNSIGNED32, CO_SUB_RW, 4, offsetof(ram_t, v1005), 0},
    {0, CO_UNSIGNED8, CO_SUB_R | CO_SUB_CONST | CO_SUB_ROM, 1, 0, 0},
    {1, CO_UNSIGNED32, CO_SUB_RW, 4, offsetof(ram_t, save), 0},
    {0, CO_UNSIGNED32, CO_SUB_RW, 4, offsetof(ram_t, v3000), 0},
};
static const co_od_entry_t od[] = {
    CO_OD_ENTRY(0x1005, 1, 1, CO_OBJ_VAR, 0),
    CO_OD_ENTRY(0x1010, 2, 0, CO_OBJ_ARRAY, 1),
    CO_OD_ENTRY(0x3000, 1, 0, CO_OBJ_VAR, 3),
};
static const uint8_t rom[1] = {1};
/* (co_od.h) v1005 = 0x11, v3000 = 0x22: two values of 4 bytes at 0 */
static const uint8_t defaults[] = {0U, CO_OD_DEF_RUN(2U, 2U), 0x11U, 0U, 0U, 0U, 0x22U, 0U, 0U, 0U};
typedef char alone_defaults_at[(offsetof(ram_t, v3000) == 4U) ? 1 : -1];
static const co_dev_t dev = {
    .od = od,
    .rows = rows,
    .od_count = 3,
    .ram_size = offsetof(ram_t, hooks),
    .comm_end = 0,
    .app_end = offsetof(ram_t, hooks),
    .defaults = defaults,
    .rom = rom,
    .n_hooks = 1,
    .hooks_at = offsetof(ram_t, hooks),
    .n_defaults = 1,
};

static int hal_send(void *ctx, const co_frame_t *f)
{
    (void)ctx;
    (void)f;
    fail_msg("the storage service sends nothing");
    return 0;
}
static const co_hal_ops_t hal_ops = {.send = hal_send};

/* ---- the recording service: owns 0x1005 */

static char trail[64];
static co_err_t svc_veto;
static co_err_t app_veto;

static void note(char c)
{
    size_t n = strlen(trail);
    if (n + 1U < sizeof trail) {
        trail[n] = c;
        trail[n + 1U] = '\0';
    }
}

static co_err_t rec_obj(co_node_t *node, uint8_t op, const co_od_entry_t *e,
                       const co_od_sub_t *s, const uint8_t *data, uint32_t len)
{
    (void)s;
    (void)data;
    assert_int_equal(e->index, 0x1005);
    if (op == CO_SVC_READ) {
        note('r');
        return CO_OK;
    }
    if (op == CO_SVC_CHECK) {
        assert_int_equal(len, 4);
        note('c');
        return svc_veto;
    }
    assert_int_equal(op, CO_SVC_WRITTEN);
    /* the value is committed when the service hears of it */
    assert_int_equal(((const ram_t *)(const void *)node->ram)->v1005, 0x12345678U);
    note('w');
    return CO_OK;
}

static const co_service_t rec_svc = {NULL, NULL, NULL};

/* (the core's table has CO_N_SERVICES rows; here only the first two) */
const co_service_t *const co_services[CO_N_SERVICES] = {[0] = &rec_svc, [1] = &co_svc_store};

/* the hook table: the recording service in the slot of 0x1005 (3), storage
 * in its own (6); no other service in this executable */
const co_svc_hook_t co_svc_hooks[CO_SVC_N_HOOKS] = {
    [2] = {CO_SVC_READ | CO_SVC_CHECK | CO_SVC_WRITTEN, 0U, rec_obj},
    [5] = {CO_SVC_COMMIT, 1U, co_store_obj},
};

/* ---- the application's hook on 0x1005 */

static co_err_t app_read(void *ctx, co_od_io_t *io)
{
    (void)ctx;
    (void)io;
    note('R');
    return CO_OK;
}

static co_err_t app_write(void *ctx, co_od_io_t *io)
{
    (void)ctx;
    (void)io;
    note('W');
    return app_veto;
}

/* ---- fixture: the node as co_node_init would leave it, done by hand */

static co_node_t node;
static ram_t ram;
#define hooks (ram.hooks)

static int setup(void **state)
{
    (void)state;
    memset(&node, 0, sizeof node);
    memset(&ram, 0, sizeof ram);
    node.dev = &dev;
    node.ram = (uint8_t *)&ram;
    node.hal.ops = &hal_ops;
    node.node_id = 1U;
    co_od_restore(&node, dev.ram_size);
    trail[0] = '\0';
    svc_veto = CO_OK;
    app_veto = CO_OK;
    return 0;
}

static void write_sub(uint16_t index, uint8_t sub, uint32_t v, co_err_t expect)
{
    uint8_t d[4];
    co_put_u32(d, v);
    assert_int_equal(co_od_write(&node, index, sub, d, 4U, false), expect);
}

static void write_u32(uint16_t index, uint32_t v, co_err_t expect)
{
    write_sub(index, 0U, v, expect);
}

/* service check, application hook, commit, service written; reads: the
 * service's read hook before the application's */
static void test_chain_order(void **state)
{
    co_od_hook_t h = {app_read, app_write, NULL};
    uint8_t buf[4];
    uint32_t len = 0U;

    (void)state;
    assert_int_equal(co_od_bind_hook(&node, 0x1005U, &h), CO_RESULT_OK);
    write_u32(0x1005U, 0x12345678U, CO_OK);
    assert_string_equal(trail, "cWw");
    trail[0] = '\0';
    assert_int_equal(co_od_read(&node, 0x1005U, 0U, buf, 4U, &len), CO_OK);
    assert_string_equal(trail, "rR");
    assert_int_equal(co_get_u32(buf), 0x12345678U);
    /* an object no service owns: no service hook at all */
    trail[0] = '\0';
    write_u32(0x3000U, 5U, CO_OK);
    assert_string_equal(trail, "");
    assert_int_equal(ram.v3000, 5U);
}

/* a veto of the service: the application's hook is not asked, the old value stays */
static void test_service_veto_first(void **state)
{
    co_od_hook_t h = {NULL, app_write, NULL};

    (void)state;
    assert_int_equal(co_od_bind_hook(&node, 0x1005U, &h), CO_RESULT_OK);
    svc_veto = CO_ERR_VALUE;
    write_u32(0x1005U, 0x12345678U, CO_ERR_VALUE);
    assert_string_equal(trail, "c");
    assert_int_equal(ram.v1005, 0x11U);
    /* a veto of the application: the service hears of no write */
    trail[0] = '\0';
    svc_veto = CO_OK;
    app_veto = CO_ERR_STORE_STATE;
    write_u32(0x1005U, 0x12345678U, CO_ERR_STORE_STATE);
    assert_string_equal(trail, "cW");
    assert_int_equal(ram.v1005, 0x11U);
}

/* which service's hook an object has is known from its index when the
 * table is compiled (CO_OD_SVC_OF): every range and nothing beside them */
static void test_owner_slots(void **state)
{
    static const struct {
        uint16_t index;
        unsigned slot;
    } owner[] = {
        {0x0FFFU, 0U}, {0x1000U, 0U}, {0x1002U, 0U}, {0x1003U, 1U}, {0x1004U, 0U},
        {0x1005U, 3U}, {0x1006U, 3U}, {0x1007U, 3U}, {0x1008U, 0U},
        {0x100CU, CO_NODE_GUARDING ? 4U : 0U}, {0x100DU, CO_NODE_GUARDING ? 4U : 0U},
        {0x100EU, 0U}, {0x100FU, 0U}, {0x1010U, 6U}, {0x1011U, 6U},
        {0x1012U, CO_TIME ? 8U : 0U}, {0x1013U, 0U}, {0x1014U, 2U}, {0x1015U, 2U},
        {0x1016U, 4U}, {0x1017U, 5U}, {0x1018U, 0U}, {0x1019U, 3U}, {0x101AU, 0U},
        {0x1028U, 0U}, {0x1029U, CO_ERROR_BEHAVIOUR ? (8U + (unsigned)CO_TIME) : 0U},
        {0x1200U, 0U}, {0x13FFU, 0U}, {0x1400U, 7U}, {0x1600U, 7U}, {0x1A03U, 7U},
        {0x1BFFU, 7U}, {0x1C00U, 0U}, {0x2000U, 0U}, {0xFFFFU, 0U},
    };

    (void)state;
    for (size_t k = 0U; k < sizeof owner / sizeof owner[0]; k++) {
        assert_int_equal(CO_OD_SVC_OF(owner[k].index), owner[k].slot);
        assert_true(owner[k].slot <= CO_SVC_N_HOOKS);
    }
    /* the table's entries carry it */
    assert_int_equal(co_od_svc(&od[0]), 3U);
    assert_int_equal(co_od_svc(&od[1]), 6U);
    assert_int_equal(co_od_svc(&od[2]), 0U);
}

/* two plug-ins on one object: the second bind is refused, the first hook stays */
static void test_bind_twice(void **state)
{
    co_od_hook_t first = {NULL, app_write, NULL};
    co_od_hook_t second = {app_read, NULL, NULL};

    (void)state;
    assert_int_equal(co_od_bind_hook(&node, 0x1005U, &first), CO_RESULT_OK);
    assert_int_equal(co_od_bind_hook(&node, 0x1005U, &second), CO_RESULT_HOOK_BOUND);
    assert_ptr_equal(hooks[0].write, app_write);
    assert_null(hooks[0].read);
    assert_int_equal(co_od_bind_hook(&node, 0x3000U, &second), CO_RESULT_NO_HOOK_SLOT);
    assert_int_equal(co_od_bind_hook(&node, 0x4000U, &second), CO_RESULT_NO_OBJECT);
}

/* storage acts on 0x1010 sub1 instead of storing it: without NV the answer
 * is 0x08000020 and the value read stays what the service set */
static void test_storage_acts(void **state)
{
    (void)state;
    write_sub(0x1010U, 1U, 0x65766173U /* "save" */, CO_ERR_STORE);
    assert_int_equal(ram.save[0], 0U);
    assert_string_equal(trail, "");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(test_chain_order, setup),
        cmocka_unit_test_setup(test_service_veto_first, setup),
        cmocka_unit_test_setup(test_owner_slots, setup),
        cmocka_unit_test_setup(test_bind_twice, setup),
        cmocka_unit_test_setup(test_storage_acts, setup),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
