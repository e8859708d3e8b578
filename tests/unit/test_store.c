/*
 * Parameter storage (CiA 301 0x1010 store / 0x1011 restore default): the
 * capability reads, save and restore of all / communication / application,
 * what NMT resets and a power cycle (a new co_node_init on the same NV) load,
 * wrong signatures, a HAL without NV, NV failures, foreign and corrupt sets,
 * a power cut at every byte of a save or restore, and the restore of the
 * saved set (0x1011 sub 4..6, CO_RESTORE_SAVED).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "generic_301.h"
#include "test_bus.h"
#include "test_frames.h"
#include "test_dev.h"

/* ------------------------------------------------------------ value sets */

typedef struct xfer {
    const char *req;
    const char *resp;
} xfer_t;

/* Two communication values (0x1015 EMCY inhibit, 0x100C guard time) and two
 * application values (0x2004 UNSIGNED32, 0x2002 UNSIGNED16): how to write
 * them and what reading them answers. */
typedef struct vset {
    xfer_t comm_w[2];
    xfer_t app_w[2];
    xfer_t comm_r[2];
    xfer_t app_r[2];
} vset_t;

static const vset_t DEF = {
    {{"601 2B 15 10 00 00 00 00 00", "581 60 15 10 00 00 00 00 00"},
     {"601 2B 0C 10 00 00 00 00 00", "581 60 0C 10 00 00 00 00 00"}},
    {{"601 23 04 20 00 EF BE AD DE", "581 60 04 20 00 00 00 00 00"},
     {"601 2B 02 20 00 34 12 00 00", "581 60 02 20 00 00 00 00 00"}},
    {{"601 40 15 10 00 00 00 00 00", "581 4B 15 10 00 00 00 00 00"},
     {"601 40 0C 10 00 00 00 00 00", "581 4B 0C 10 00 00 00 00 00"}},
    {{"601 40 04 20 00 00 00 00 00", "581 43 04 20 00 EF BE AD DE"},
     {"601 40 02 20 00 00 00 00 00", "581 4B 02 20 00 34 12 00 00"}},
};

static const vset_t SET_A = {
    {{"601 2B 15 10 00 64 00 00 00", "581 60 15 10 00 00 00 00 00"},
     {"601 2B 0C 10 00 F4 01 00 00", "581 60 0C 10 00 00 00 00 00"}},
    {{"601 23 04 20 00 11 11 11 11", "581 60 04 20 00 00 00 00 00"},
     {"601 2B 02 20 00 0A 0A 00 00", "581 60 02 20 00 00 00 00 00"}},
    {{"601 40 15 10 00 00 00 00 00", "581 4B 15 10 00 64 00 00 00"},
     {"601 40 0C 10 00 00 00 00 00", "581 4B 0C 10 00 F4 01 00 00"}},
    {{"601 40 04 20 00 00 00 00 00", "581 43 04 20 00 11 11 11 11"},
     {"601 40 02 20 00 00 00 00 00", "581 4B 02 20 00 0A 0A 00 00"}},
};

static const vset_t SET_B = {
    {{"601 2B 15 10 00 C8 00 00 00", "581 60 15 10 00 00 00 00 00"},
     {"601 2B 0C 10 00 E8 03 00 00", "581 60 0C 10 00 00 00 00 00"}},
    {{"601 23 04 20 00 22 22 22 22", "581 60 04 20 00 00 00 00 00"},
     {"601 2B 02 20 00 0B 0B 00 00", "581 60 02 20 00 00 00 00 00"}},
    {{"601 40 15 10 00 00 00 00 00", "581 4B 15 10 00 C8 00 00 00"},
     {"601 40 0C 10 00 00 00 00 00", "581 4B 0C 10 00 E8 03 00 00"}},
    {{"601 40 04 20 00 00 00 00 00", "581 43 04 20 00 22 22 22 22"},
     {"601 40 02 20 00 00 00 00 00", "581 4B 02 20 00 0B 0B 00 00"}},
};

static const vset_t SET_C = {
    {{"601 2B 15 10 00 2C 01 00 00", "581 60 15 10 00 00 00 00 00"},
     {"601 2B 0C 10 00 DC 05 00 00", "581 60 0C 10 00 00 00 00 00"}},
    {{"601 23 04 20 00 33 33 33 33", "581 60 04 20 00 00 00 00 00"},
     {"601 2B 02 20 00 0C 0C 00 00", "581 60 02 20 00 00 00 00 00"}},
    {{"601 40 15 10 00 00 00 00 00", "581 4B 15 10 00 2C 01 00 00"},
     {"601 40 0C 10 00 00 00 00 00", "581 4B 0C 10 00 DC 05 00 00"}},
    {{"601 40 04 20 00 00 00 00 00", "581 43 04 20 00 33 33 33 33"},
     {"601 40 02 20 00 00 00 00 00", "581 4B 02 20 00 0C 0C 00 00"}},
};

/* Commands: signature "save" = 73 61 76 65, "load" = 6C 6F 61 64. */
#define SAVE_ALL   "601 23 10 10 01 73 61 76 65"
#define SAVE_COMM  "601 23 10 10 02 73 61 76 65"
#define SAVE_APP   "601 23 10 10 03 73 61 76 65"
#define SAVED_ALL  "581 60 10 10 01 00 00 00 00"
#define SAVED_COMM "581 60 10 10 02 00 00 00 00"
#define SAVED_APP  "581 60 10 10 03 00 00 00 00"
#define LOAD_ALL   "601 23 11 10 01 6C 6F 61 64"
#define LOAD_COMM  "601 23 11 10 02 6C 6F 61 64"
#define LOAD_APP   "601 23 11 10 03 6C 6F 61 64"
#define LOADED_ALL  "581 60 11 10 01 00 00 00 00"
#define LOADED_COMM "581 60 11 10 02 00 00 00 00"
#define LOADED_APP  "581 60 11 10 03 00 00 00 00"

static void run2(tb_bus_t *bus, const xfer_t *x)
{
    for (int i = 0; i < 2; i++) {
        tb_xfer(bus, x[i].req, x[i].resp);
    }
}

static void write_set(tb_bus_t *bus, const vset_t *v)
{
    run2(bus, v->comm_w);
    run2(bus, v->app_w);
}

static void expect_comm(tb_bus_t *bus, const vset_t *v)
{
    run2(bus, v->comm_r);
}

static void expect_app(tb_bus_t *bus, const vset_t *v)
{
    run2(bus, v->app_r);
}

/* -------------------------------------------------------------- fixture */

typedef struct fx {
    tb_bus_t bus;
    td_node_t n;
    co_dev_t dev;
    generic_301_node_t g;
} fx_t;

static fx_t fx;

#define STORE_MAGIC_TEST 0x564E6F63UL /* "coNV", little-endian at bank offset 0 */

/* After a power cut the boot may report the newest set damaged (a header
 * cut short): EMCY 0x5530 after the boot-up. Allowed where this is set. */
static bool cut_allowed;
static bool cut_reported;

#define EMCY_DAMAGED "081 30 55 01 00 00 00 00 00"

/* Power on: a new co_node_init on the same NV; the boot-up is checked. */
static void power_cycle_dev(const co_dev_t *dev)
{
    const co_frame_t *f;

    tb_flush(&fx.bus);
    td_start(&fx.n, &fx.bus, 0, 1, dev);
    tb_expect(&fx.bus, "701 00");
    cut_reported = false;
    f = tb_next(&fx.bus);
    if ((f != NULL) && cut_allowed) {
        TF_ASSERT_FRAME(f, EMCY_DAMAGED);
        cut_reported = true;
        f = tb_next(&fx.bus);
    }
    if (f != NULL) {
        char txt[64];
        tf_format(f, txt, sizeof txt);
        print_error("after the boot-up: expected no frame, got %s\n", txt);
        fail();
    }
}

static void power_cycle(void)
{
    power_cycle_dev(NULL);
}

static void reset_node(void)
{
    tb_send(&fx.bus, "000 81 01");
    tb_expect(&fx.bus, "701 00");
    tb_expect_none(&fx.bus);
}

static void reset_comm(void)
{
    tb_send(&fx.bus, "000 82 01");
    tb_expect(&fx.bus, "701 00");
    tb_expect_none(&fx.bus);
}

static int setup(void **state)
{
    memset(&fx, 0, sizeof fx);
    tb_init(&fx.bus);
    fx.dev = td_dev;
    power_cycle();
    *state = &fx;
    return 0;
}

#define BUS (&fx.bus)

static bool nv_erased(void)
{
    for (size_t i = 0; i < TB_NV_SIZE; i++) {
        if (fx.bus.nv[i] != 0xFFU) {
            return false;
        }
    }
    return true;
}

static uint32_t bank_size(void)
{
    return (16U + td_dev.app_end + 3U) & ~3U;
}

/* ------------------------------------------------------ capability reads */

static void capability_reads_and_signature_does_not_change_them(void **state)
{
    (void)state;
    tb_xfer(BUS, "601 40 10 10 00 00 00 00 00", "581 4F 10 10 00 03 00 00 00");
    tb_xfer(BUS, "601 40 10 10 01 00 00 00 00", "581 43 10 10 01 01 00 00 00");
    tb_xfer(BUS, "601 40 10 10 02 00 00 00 00", "581 43 10 10 02 01 00 00 00");
    tb_xfer(BUS, "601 40 10 10 03 00 00 00 00", "581 43 10 10 03 01 00 00 00");
    tb_xfer(BUS, "601 40 11 10 00 00 00 00 00", "581 4F 11 10 00 06 00 00 00");
    tb_xfer(BUS, "601 40 11 10 01 00 00 00 00", "581 43 11 10 01 01 00 00 00");
    tb_xfer(BUS, "601 40 11 10 02 00 00 00 00", "581 43 11 10 02 01 00 00 00");
    tb_xfer(BUS, "601 40 11 10 03 00 00 00 00", "581 43 11 10 03 01 00 00 00");
    /* sub 4..6 (a manufacturer's) are not the core's without
     * CO_RESTORE_SAVED: they read 0 and refuse the signature */
    tb_xfer(BUS, "601 40 11 10 04 00 00 00 00", "581 43 11 10 04 00 00 00 00");
    tb_xfer(BUS, "601 40 11 10 06 00 00 00 00", "581 43 11 10 06 00 00 00 00");
    tb_xfer(BUS, "601 23 11 10 04 6C 6F 61 64", "581 80 11 10 04 20 00 00 08");
    /* writing the signatures (accepted ones and refused ones) changes nothing */
    tb_xfer(BUS, SAVE_ALL, SAVED_ALL);
    tb_xfer(BUS, SAVE_COMM, SAVED_COMM);
    tb_xfer(BUS, "601 23 10 10 03 00 00 00 00", "581 80 10 10 03 20 00 00 08");
    tb_xfer(BUS, LOAD_APP, LOADED_APP);
    tb_xfer(BUS, "601 40 10 10 01 00 00 00 00", "581 43 10 10 01 01 00 00 00");
    tb_xfer(BUS, "601 40 10 10 02 00 00 00 00", "581 43 10 10 02 01 00 00 00");
    tb_xfer(BUS, "601 40 10 10 03 00 00 00 00", "581 43 10 10 03 01 00 00 00");
    tb_xfer(BUS, "601 40 11 10 03 00 00 00 00", "581 43 11 10 03 01 00 00 00");
    assert_int_equal(fx.n.ram.store[0], 1U);
    assert_int_equal(fx.n.ram.restore[2], 1U);
    /* the application path acts the same way */
    assert_int_equal(co_od_write(&fx.n.node, 0x1010U, 1U, "save", 4U, true), CO_OK);
    assert_int_equal(co_od_write(&fx.n.node, 0x1010U, 1U, "SAVE", 4U, true), CO_ERR_STORE);
    assert_int_equal(fx.n.ram.store[0], 1U);
    tb_expect_none(BUS);
}

/* ------------------------------------------------------------ save */

static void save_all_survives_resets_and_power_cycle(void **state)
{
    (void)state;
    write_set(BUS, &SET_A);
    tb_xfer(BUS, SAVE_ALL, SAVED_ALL);
    write_set(BUS, &SET_B);
    /* reset node: everything from the stored set */
    reset_node();
    expect_comm(BUS, &SET_A);
    expect_app(BUS, &SET_A);
    /* reset communication: the communication values only */
    write_set(BUS, &SET_B);
    reset_comm();
    expect_comm(BUS, &SET_A);
    expect_app(BUS, &SET_B);
    /* power cycle */
    power_cycle();
    expect_comm(BUS, &SET_A);
    expect_app(BUS, &SET_A);
    /* NV use stays inside the documented size */
    assert_int_equal(co_store_nv_size(&td_dev), 2U * bank_size());
    assert_true(co_store_nv_size(&td_dev) <= TB_NV_SIZE);
    for (size_t i = co_store_nv_size(&td_dev); i < TB_NV_SIZE; i++) {
        assert_int_equal(fx.bus.nv[i], 0xFF);
    }
}

/* The COB-IDs the core reads are stored in their 16-bit forms (co_od.h,
 * CO_SUB_COB16): a saved set gives bits 31 and 30 and the CAN-ID back. */
static void cob_ids_in_16_bits_survive_reset_and_power_cycle(void **state)
{
    (void)state;
    /* EMCY not valid (bit 31), SYNC producer (bit 30; no period: none sent) */
    tb_xfer(BUS, "601 23 14 10 00 85 00 00 80", "581 60 14 10 00 00 00 00 00");
    tb_xfer(BUS, "601 23 05 10 00 80 00 00 40", "581 60 05 10 00 00 00 00 00");
    assert_int_equal(fx.n.ram.emcy_cob, 0x8085U);
    assert_int_equal(fx.n.ram.sync_cob, 0x4080U);
    tb_xfer(BUS, SAVE_COMM, SAVED_COMM);
    tb_xfer(BUS, "601 23 14 10 00 85 00 00 00", "581 60 14 10 00 00 00 00 00");
    tb_xfer(BUS, "601 23 05 10 00 80 00 00 00", "581 60 05 10 00 00 00 00 00");
    reset_node();
    tb_xfer(BUS, "601 40 14 10 00 00 00 00 00", "581 43 14 10 00 85 00 00 80");
    tb_xfer(BUS, "601 40 05 10 00 00 00 00 00", "581 43 05 10 00 80 00 00 40");
    power_cycle();
    tb_xfer(BUS, "601 40 14 10 00 00 00 00 00", "581 43 14 10 00 85 00 00 80");
    tb_xfer(BUS, "601 40 05 10 00 00 00 00 00", "581 43 05 10 00 80 00 00 40");
    assert_int_equal(fx.n.ram.emcy_cob, 0x8085U);
    assert_int_equal(fx.n.ram.sync_cob, 0x4080U);
}

static void save_comm_only(void **state)
{
    (void)state;
    write_set(BUS, &SET_A);
    tb_xfer(BUS, SAVE_COMM, SAVED_COMM);
    reset_node();
    expect_comm(BUS, &SET_A);
    expect_app(BUS, &DEF);
    power_cycle();
    expect_comm(BUS, &SET_A);
    expect_app(BUS, &DEF);
}

static void save_app_only(void **state)
{
    (void)state;
    write_set(BUS, &SET_A);
    tb_xfer(BUS, SAVE_APP, SAVED_APP);
    reset_comm();
    expect_comm(BUS, &DEF);
    expect_app(BUS, &SET_A);
    power_cycle();
    expect_comm(BUS, &DEF);
    expect_app(BUS, &SET_A);
}

static void partial_save_keeps_the_other_group(void **state)
{
    (void)state;
    write_set(BUS, &SET_A);
    tb_xfer(BUS, SAVE_ALL, SAVED_ALL);
    write_set(BUS, &SET_B);
    tb_xfer(BUS, SAVE_COMM, SAVED_COMM);
    power_cycle();
    expect_comm(BUS, &SET_B);
    expect_app(BUS, &SET_A);
    write_set(BUS, &SET_C);
    tb_xfer(BUS, SAVE_APP, SAVED_APP);
    power_cycle();
    expect_comm(BUS, &SET_B);
    expect_app(BUS, &SET_C);
    /* a set holding only one group keeps holding only that one */
    tb_init(BUS);
    power_cycle();
    write_set(BUS, &SET_A);
    tb_xfer(BUS, SAVE_APP, SAVED_APP);
    write_set(BUS, &SET_B);
    tb_xfer(BUS, SAVE_APP, SAVED_APP);
    power_cycle();
    expect_comm(BUS, &DEF);
    expect_app(BUS, &SET_B);
}

/* ---------------------------------------------------------- restore */

static void restore_all_takes_effect_at_reset(void **state)
{
    (void)state;
    write_set(BUS, &SET_A);
    tb_xfer(BUS, SAVE_ALL, SAVED_ALL);
    tb_xfer(BUS, LOAD_ALL, LOADED_ALL);
    /* nothing changes until a reset */
    expect_comm(BUS, &SET_A);
    expect_app(BUS, &SET_A);
    /* reset communication: no stored communication values any more */
    reset_comm();
    expect_comm(BUS, &DEF);
    expect_app(BUS, &SET_A);
    reset_node();
    expect_comm(BUS, &DEF);
    expect_app(BUS, &DEF);
    /* the restore itself is stored */
    power_cycle();
    expect_comm(BUS, &DEF);
    expect_app(BUS, &DEF);
    /* and a later save works as before */
    write_set(BUS, &SET_B);
    tb_xfer(BUS, SAVE_ALL, SAVED_ALL);
    power_cycle();
    expect_comm(BUS, &SET_B);
    expect_app(BUS, &SET_B);
}

static void restore_comm_at_reset_communication(void **state)
{
    (void)state;
    write_set(BUS, &SET_A);
    tb_xfer(BUS, SAVE_ALL, SAVED_ALL);
    tb_xfer(BUS, LOAD_COMM, LOADED_COMM);
    expect_comm(BUS, &SET_A);
    reset_comm();
    expect_comm(BUS, &DEF);
    expect_app(BUS, &SET_A);
    write_set(BUS, &SET_B);
    reset_node();
    expect_comm(BUS, &DEF);
    expect_app(BUS, &SET_A);
    power_cycle();
    expect_comm(BUS, &DEF);
    expect_app(BUS, &SET_A);
}

static void restore_app_at_reset_node(void **state)
{
    (void)state;
    write_set(BUS, &SET_A);
    tb_xfer(BUS, SAVE_ALL, SAVED_ALL);
    tb_xfer(BUS, LOAD_APP, LOADED_APP);
    reset_comm(); /* does not touch application values */
    expect_comm(BUS, &SET_A);
    expect_app(BUS, &SET_A);
    reset_node();
    expect_comm(BUS, &SET_A);
    expect_app(BUS, &DEF);
    power_cycle();
    expect_comm(BUS, &SET_A);
    expect_app(BUS, &DEF);
}

static void restore_without_stored_set_writes_nothing(void **state)
{
    (void)state;
    tb_xfer(BUS, LOAD_ALL, LOADED_ALL);
    tb_xfer(BUS, LOAD_COMM, LOADED_COMM);
    tb_xfer(BUS, LOAD_APP, LOADED_APP);
    assert_true(nv_erased());
    /* a restored group is not restored again (no NV write) */
    write_set(BUS, &SET_A);
    tb_xfer(BUS, SAVE_APP, SAVED_APP);
    {
        uint32_t written = fx.bus.nv_written;
        tb_xfer(BUS, LOAD_COMM, LOADED_COMM);
        assert_int_equal(fx.bus.nv_written, written);
        tb_xfer(BUS, LOAD_APP, LOADED_APP);
        assert_int_equal(fx.bus.nv_written, written + 16U); /* a header, no data */
        tb_xfer(BUS, LOAD_ALL, LOADED_ALL);
        assert_int_equal(fx.bus.nv_written, written + 16U);
    }
}

/* ------------------------------------- CO_RESTORE_SAVED (sub 4..6) */

#define LOAD_SAVED_ALL    "601 23 11 10 04 6C 6F 61 64"
#define LOAD_SAVED_COMM   "601 23 11 10 05 6C 6F 61 64"
#define LOAD_SAVED_APP    "601 23 11 10 06 6C 6F 61 64"
#define LOADED_SAVED_ALL  "581 60 11 10 04 00 00 00 00"
#define LOADED_SAVED_COMM "581 60 11 10 05 00 00 00 00"
#define LOADED_SAVED_APP  "581 60 11 10 06 00 00 00 00"

static void start_restore_saved(void)
{
    fx.dev.set = (co_settings_t){.store.restore = CO_RESTORE_SAVED};
    power_cycle_dev(&fx.dev);
}

/* Sub 4..6 read 1 like 1..3; a restore of the defaults keeps the saved
 * data; restoring the saved set brings it back at the next reset. */
static void restore_saved_undoes_a_restore(void **state)
{
    (void)state;
    start_restore_saved();
    tb_xfer(BUS, "601 40 11 10 04 00 00 00 00", "581 43 11 10 04 01 00 00 00");
    tb_xfer(BUS, "601 40 11 10 05 00 00 00 00", "581 43 11 10 05 01 00 00 00");
    tb_xfer(BUS, "601 40 11 10 06 00 00 00 00", "581 43 11 10 06 01 00 00 00");
    write_set(BUS, &SET_A);
    tb_xfer(BUS, SAVE_ALL, SAVED_ALL);
    /* the defaults at the next reset, as without the option */
    tb_xfer(BUS, LOAD_ALL, LOADED_ALL);
    expect_app(BUS, &SET_A);
    reset_node();
    expect_comm(BUS, &DEF);
    expect_app(BUS, &DEF);
    power_cycle_dev(&fx.dev);
    expect_comm(BUS, &DEF);
    expect_app(BUS, &DEF);
    /* the saved set again: SET_A at the next reset (and power-on) */
    write_set(BUS, &SET_B);
    tb_xfer(BUS, LOAD_SAVED_ALL, LOADED_SAVED_ALL);
    expect_comm(BUS, &SET_B);
    expect_app(BUS, &SET_B);
    reset_node();
    expect_comm(BUS, &SET_A);
    expect_app(BUS, &SET_A);
    power_cycle_dev(&fx.dev);
    expect_comm(BUS, &SET_A);
    expect_app(BUS, &SET_A);
}

/* The groups one by one; a restore of the saved set where nothing was
 * restored writes nothing; a save ends a group's restore. */
static void restore_saved_by_group(void **state)
{
    uint32_t written;

    (void)state;
    start_restore_saved();
    /* nothing stored yet: nothing to do, nothing written */
    tb_xfer(BUS, LOAD_SAVED_ALL, LOADED_SAVED_ALL);
    assert_true(nv_erased());
    write_set(BUS, &SET_A);
    tb_xfer(BUS, SAVE_ALL, SAVED_ALL);
    written = fx.bus.nv_written;
    tb_xfer(BUS, LOAD_SAVED_COMM, LOADED_SAVED_COMM);
    assert_int_equal(fx.bus.nv_written, written);
    /* both groups restored; the application's saved set back */
    tb_xfer(BUS, LOAD_ALL, LOADED_ALL);
    tb_xfer(BUS, LOAD_SAVED_APP, LOADED_SAVED_APP);
    reset_node();
    expect_comm(BUS, &DEF);
    expect_app(BUS, &SET_A);
    /* the communication group's too: at reset communication */
    write_set(BUS, &SET_B);
    tb_xfer(BUS, LOAD_SAVED_COMM, LOADED_SAVED_COMM);
    reset_comm();
    expect_comm(BUS, &SET_A);
    expect_app(BUS, &SET_B);
    /* a save of the restored group ends its restore (SET_C saved) */
    tb_xfer(BUS, LOAD_APP, LOADED_APP);
    write_set(BUS, &SET_C);
    tb_xfer(BUS, SAVE_APP, SAVED_APP);
    tb_xfer(BUS, LOAD_SAVED_APP, LOADED_SAVED_APP);
    power_cycle_dev(&fx.dev);
    expect_comm(BUS, &SET_A);
    expect_app(BUS, &SET_C);
    /* the save signature on a restore sub-index is refused */
    tb_xfer(BUS, "601 23 11 10 05 73 61 76 65", "581 80 11 10 05 20 00 00 08");
}

/* A power cut at every byte of a restore with the saved data kept and of
 * the restore of the saved set: the old or the new set, never a mix. */
static void restore_saved_power_cut(void **state)
{
    static const char *const cmds[2][2] = {{LOAD_ALL, LOADED_ALL},
                                           {LOAD_SAVED_ALL, LOADED_SAVED_ALL}};

    (void)state;
    for (int k = 0; k < 2; k++) {
        td_ram_t img_old;
        td_ram_t img_new;
        uint32_t total;

        /* prepare: SET_A saved (and for the second command restored) */
        tb_init(BUS);
        start_restore_saved();
        write_set(BUS, &SET_A);
        tb_xfer(BUS, SAVE_ALL, SAVED_ALL);
        if (k == 1) {
            tb_xfer(BUS, LOAD_ALL, LOADED_ALL);
        }
        start_restore_saved();
        memcpy(&img_old, &fx.n.ram, sizeof img_old);
        total = fx.bus.nv_written;
        tb_xfer(BUS, cmds[k][0], cmds[k][1]);
        total = fx.bus.nv_written - total;
        start_restore_saved();
        memcpy(&img_new, &fx.n.ram, sizeof img_new);
        assert_memory_not_equal(&img_old, &img_new, sizeof img_old);
        /* header and the kept data of both groups */
        assert_int_equal(total, 16U + td_dev.app_end);
        for (uint32_t cut = 0U; cut <= total; cut++) {
            tb_init(BUS);
            start_restore_saved();
            write_set(BUS, &SET_A);
            tb_xfer(BUS, SAVE_ALL, SAVED_ALL);
            if (k == 1) {
                tb_xfer(BUS, LOAD_ALL, LOADED_ALL);
            }
            tb_nv_cut(BUS, cut, (cut & 1U) != 0U);
            tb_send(BUS, cmds[k][0]);
            tb_nv_power_on(BUS);
            cut_allowed = true;
            start_restore_saved();
            cut_allowed = false;
            /* the stored values (a report changes 0x1001 / 0x1003, not stored) */
            assert_true((memcmp(&fx.n.ram, &img_old, td_dev.app_end) == 0) ||
                        (memcmp(&fx.n.ram, &img_new, td_dev.app_end) == 0));
            /* a reported cut fell back to the old set */
            assert_true(!cut_reported || (memcmp(&fx.n.ram, &img_new, td_dev.app_end) != 0));
            if (cut == total) {
                assert_memory_equal(&fx.n.ram, &img_new, sizeof img_new);
            }
        }
    }
}

/* ----------------------------------------------------------- refusals */

static void wrong_signature_aborts(void **state)
{
    (void)state;
    write_set(BUS, &SET_A);
    tb_xfer(BUS, "601 23 10 10 01 53 41 56 45", "581 80 10 10 01 20 00 00 08"); /* "SAVE" */
    tb_xfer(BUS, "601 23 10 10 02 6C 6F 61 64", "581 80 10 10 02 20 00 00 08"); /* "load" */
    tb_xfer(BUS, "601 23 10 10 03 65 76 61 73", "581 80 10 10 03 20 00 00 08"); /* reversed */
    tb_xfer(BUS, "601 23 11 10 01 73 61 76 65", "581 80 11 10 01 20 00 00 08"); /* "save" */
    tb_xfer(BUS, "601 23 11 10 02 00 00 00 00", "581 80 11 10 02 20 00 00 08");
    /* a signature of the wrong length is refused by the type check */
    tb_xfer(BUS, "601 2B 10 10 01 73 61 00 00", "581 80 10 10 01 10 00 07 06");
    /* sub-index 0 is the constant count; there is no sub-index 4 */
    tb_xfer(BUS, "601 2F 10 10 00 03 00 00 00", "581 80 10 10 00 02 00 01 06");
    tb_xfer(BUS, "601 23 10 10 04 73 61 76 65", "581 80 10 10 04 11 00 09 06");
    assert_true(nv_erased());
    reset_node();
    expect_comm(BUS, &DEF);
    expect_app(BUS, &DEF);
}

static void start_without_nv(td_node_t *n)
{
    co_node_config_t cfg;

    memset(n, 0, sizeof *n);
    memset(&cfg, 0, sizeof cfg);
    cfg.dev = &td_dev;
    cfg.hal = tb_hal(BUS, 0);
    cfg.hal.ops = &tb_hal_ops_no_nv;
    cfg.node_id = 1U;
    cfg.ram = &n->ram;
    tb_attach(BUS, 0, &n->node);
    assert_int_equal(co_node_init(&n->node, &cfg, fx.bus.now), CO_RESULT_OK);
}

static void hal_without_nv(void **state)
{
    (void)state;
    /* a valid stored set in the bus's NV is not seen by a node without NV */
    write_set(BUS, &SET_A);
    tb_xfer(BUS, SAVE_ALL, SAVED_ALL);
    tb_flush(BUS);
    start_without_nv(&fx.n);
    tb_expect(BUS, "701 00");
    expect_comm(BUS, &DEF);
    expect_app(BUS, &DEF);
    tb_xfer(BUS, "601 40 10 10 01 00 00 00 00", "581 43 10 10 01 00 00 00 00");
    tb_xfer(BUS, "601 40 10 10 02 00 00 00 00", "581 43 10 10 02 00 00 00 00");
    tb_xfer(BUS, "601 40 10 10 03 00 00 00 00", "581 43 10 10 03 00 00 00 00");
    tb_xfer(BUS, "601 40 11 10 01 00 00 00 00", "581 43 11 10 01 00 00 00 00");
    tb_xfer(BUS, "601 40 11 10 02 00 00 00 00", "581 43 11 10 02 00 00 00 00");
    tb_xfer(BUS, "601 40 11 10 03 00 00 00 00", "581 43 11 10 03 00 00 00 00");
    tb_xfer(BUS, SAVE_ALL, "581 80 10 10 01 20 00 00 08");
    tb_xfer(BUS, SAVE_COMM, "581 80 10 10 02 20 00 00 08");
    tb_xfer(BUS, LOAD_ALL, "581 80 11 10 01 20 00 00 08");
    tb_xfer(BUS, LOAD_APP, "581 80 11 10 03 20 00 00 08");
    /* resets still restore defaults, and the reads stay 0 */
    write_set(BUS, &SET_B);
    reset_node();
    expect_comm(BUS, &DEF);
    expect_app(BUS, &DEF);
    tb_xfer(BUS, "601 40 10 10 01 00 00 00 00", "581 43 10 10 01 00 00 00 00");
}

static void nv_failure_aborts_with_hardware_error(void **state)
{
    (void)state;
    write_set(BUS, &SET_A);
    tb_xfer(BUS, SAVE_ALL, SAVED_ALL);
    write_set(BUS, &SET_B);
    fx.bus.nv_fail_write = true;
    tb_xfer(BUS, SAVE_ALL, "581 80 10 10 01 00 00 06 06");
    tb_xfer(BUS, LOAD_ALL, "581 80 11 10 01 00 00 06 06");
    fx.bus.nv_fail_write = false;
    /* a save that cannot read the previous set (the group it keeps, the
     * free bank) writes nothing */
    fx.bus.nv_fail_read = true;
    tb_xfer(BUS, SAVE_COMM, "581 80 10 10 02 00 00 06 06");
    tb_xfer(BUS, SAVE_ALL, "581 80 10 10 01 00 00 06 06");
    fx.bus.nv_fail_read = false;
    power_cycle();
    expect_comm(BUS, &SET_A);
    expect_app(BUS, &SET_A);
    /* unreadable NV at boot: defaults */
    fx.bus.nv_fail_read = true;
    power_cycle();
    expect_comm(BUS, &DEF);
    expect_app(BUS, &DEF);
    tb_xfer(BUS, "601 40 10 10 01 00 00 00 00", "581 43 10 10 01 01 00 00 00");
    fx.bus.nv_fail_read = false;
    power_cycle();
    expect_comm(BUS, &SET_A);
    expect_app(BUS, &SET_A);
}

/* -------------------------------------------------- foreign and corrupt */

static void foreign_layout_ignored(void **state)
{
    (void)state;
    write_set(BUS, &SET_A);
    tb_xfer(BUS, SAVE_ALL, SAVED_ALL);
    /* another split of the image */
    fx.dev = td_dev;
    fx.dev.app_end = (uint16_t)(td_dev.app_end - 4U);
    power_cycle_dev(&fx.dev);
    expect_comm(BUS, &DEF);
    expect_app(BUS, &DEF);
    /* another RAM size */
    fx.dev = td_dev;
    fx.dev.ram_size = (uint16_t)(td_dev.ram_size - 4U);
    power_cycle_dev(&fx.dev);
    expect_comm(BUS, &DEF);
    expect_app(BUS, &DEF);
    /* same sizes, another dictionary (0x60FF left out) */
    fx.dev = td_dev;
    fx.dev.od_count = (uint16_t)(td_dev.od_count - 1U);
    power_cycle_dev(&fx.dev);
    expect_comm(BUS, &DEF);
    expect_app(BUS, &DEF);
    /* the own set is still there */
    power_cycle();
    expect_comm(BUS, &SET_A);
    expect_app(BUS, &SET_A);
}

static void corrupt_set_ignored(void **state)
{
    (void)state;
    write_set(BUS, &SET_A);
    tb_xfer(BUS, SAVE_ALL, SAVED_ALL); /* bank 0 */
    /* the only set damaged: defaults, reported (EMCY 0x5530, 0x1001, 0x1003) */
    fx.bus.nv[16U + 2U] ^= 0x01U;
    cut_allowed = true;
    power_cycle();
    assert_true(cut_reported);
    expect_comm(BUS, &DEF);
    expect_app(BUS, &DEF);
    tb_xfer(BUS, "601 40 01 10 00 00 00 00 00", "581 4F 01 10 00 01 00 00 00");
    tb_xfer(BUS, "601 40 03 10 01 00 00 00 00", "581 43 03 10 01 30 55 00 00");
    fx.bus.nv[16U + 2U] ^= 0x01U;
    power_cycle();
    assert_false(cut_reported);
    expect_comm(BUS, &SET_A);
    expect_app(BUS, &SET_A);
    /* a bad newer set: the older complete set is used, and reported */
    write_set(BUS, &SET_B);
    tb_xfer(BUS, SAVE_ALL, SAVED_ALL); /* bank 1 */
    power_cycle();
    expect_app(BUS, &SET_B);
    fx.bus.nv[bank_size() + 16U + td_dev.app_end - 1U] ^= 0x80U;
    power_cycle();
    assert_true(cut_reported);
    expect_comm(BUS, &SET_A);
    expect_app(BUS, &SET_A);
    fx.bus.nv[bank_size() + 16U + td_dev.app_end - 1U] ^= 0x80U;
    fx.bus.nv[bank_size() + 14U] ^= 0x10U; /* its CRC */
    power_cycle();
    assert_true(cut_reported);
    expect_app(BUS, &SET_A);
    fx.bus.nv[bank_size() + 14U] ^= 0x10U;
    /* no magic: an erased bank, not a damaged set */
    fx.bus.nv[bank_size() + 0U] = 0x00U;
    power_cycle();
    assert_false(cut_reported);
    expect_app(BUS, &SET_A);
    /* both bad */
    fx.bus.nv[3] = 0x00U;
    power_cycle();
    expect_comm(BUS, &DEF);
    expect_app(BUS, &DEF);
    /* damaged newer set; a save writes a whole one and ends the report */
    fx.bus.nv[3] = (uint8_t)(STORE_MAGIC_TEST >> 24);
    fx.bus.nv[bank_size() + 0U] = (uint8_t)STORE_MAGIC_TEST;
    fx.bus.nv[bank_size() + 14U] ^= 0x10U;
    power_cycle();
    assert_true(cut_reported);
    tb_xfer(BUS, "601 40 01 10 00 00 00 00 00", "581 4F 01 10 00 01 00 00 00");
    write_set(BUS, &SET_C);
    tb_send(BUS, SAVE_ALL);
    tb_expect(BUS, SAVED_ALL);
    tb_advance(BUS, 100000U); /* the EMCY inhibit time of the boot's report */
    tb_expect(BUS, "081 00 00 00 00 00 00 00 00");
    tb_expect_none(BUS);
    power_cycle();
    assert_false(cut_reported);
    expect_app(BUS, &SET_C);
    cut_allowed = false;
}

/* -------------------------------------------- power cut at every byte */

typedef struct scenario {
    const char *name;
    const vset_t *stored[2]; /* saved (all) first, in order; NULL: fewer */
    const vset_t *next;      /* written before the command (NULL: nothing) */
    const char *cmd;
    const char *ok;
} scenario_t;

static const scenario_t scenarios[] = {
    {"first save", {NULL, NULL}, &SET_A, SAVE_ALL, SAVED_ALL},
    {"second save (bank 1)", {&SET_A, NULL}, &SET_B, SAVE_ALL, SAVED_ALL},
    {"third save (over bank 0)", {&SET_A, &SET_B}, &SET_C, SAVE_ALL, SAVED_ALL},
    {"communication only", {&SET_A, NULL}, &SET_B, SAVE_COMM, SAVED_COMM},
    {"application only", {&SET_A, &SET_B}, &SET_C, SAVE_APP, SAVED_APP},
    {"restore all", {&SET_A, &SET_B}, NULL, LOAD_ALL, LOADED_ALL},
    {"restore communication", {&SET_A, NULL}, NULL, LOAD_COMM, LOADED_COMM},
};

static void prepare(const scenario_t *sc)
{
    tb_init(BUS);
    power_cycle();
    for (int i = 0; (i < 2) && (sc->stored[i] != NULL); i++) {
        write_set(BUS, sc->stored[i]);
        tb_xfer(BUS, SAVE_ALL, SAVED_ALL);
    }
    if (sc->next != NULL) {
        write_set(BUS, sc->next);
    }
}

static void power_cut_at_every_byte(void **state)
{
    (void)state;
    for (size_t k = 0; k < sizeof scenarios / sizeof scenarios[0]; k++) {
        const scenario_t *sc = &scenarios[k];
        td_ram_t img_old;
        td_ram_t img_new;
        uint32_t total;
        uint32_t n_old = 0U;
        uint32_t n_new = 0U;
        uint32_t n_reported = 0U;

        /* reference: what the device boots with before and after the command */
        prepare(sc);
        power_cycle();
        memcpy(&img_old, &fx.n.ram, sizeof img_old);
        prepare(sc);
        total = fx.bus.nv_written;
        tb_xfer(BUS, sc->cmd, sc->ok);
        total = fx.bus.nv_written - total;
        power_cycle();
        memcpy(&img_new, &fx.n.ram, sizeof img_new);
        assert_true(total >= 16U);
        assert_memory_not_equal(&img_old, &img_new, sizeof img_old);

        for (int tear = 0; tear < 2; tear++) {
            for (uint32_t cut = 0U; cut <= total; cut++) {
                bool is_old;
                bool is_new;
                prepare(sc);
                tb_nv_cut(BUS, cut, tear != 0);
                tb_send(BUS, sc->cmd);
                tb_nv_power_on(BUS);
                cut_allowed = true;
                power_cycle();
                cut_allowed = false;
                /* the stored values (a report changes 0x1001 / 0x1003, not stored) */
                is_old = memcmp(&fx.n.ram, &img_old, td_dev.app_end) == 0;
                is_new = memcmp(&fx.n.ram, &img_new, td_dev.app_end) == 0;
                /* reported only for a cut in the header (the last 16
                 * bytes), and then the old set loaded */
                if (cut_reported && !(is_old && (cut + 16U > total))) {
                    print_error("%s: cut %u of %u tear %d: reported, old %d new %d\n", sc->name,
                                (unsigned)cut, (unsigned)total, tear, is_old, is_new);
                }
                assert_true(!cut_reported || (is_old && (cut + 16U > total)));
                n_reported += cut_reported ? 1U : 0U;
                if (!is_old && !is_new) {
                    print_error("%s: cut after %u of %u bytes (%s): neither old nor new\n",
                                sc->name, (unsigned)cut, (unsigned)total,
                                tear ? "torn" : "lost");
                    fail();
                }
                if (cut == 0U) {
                    assert_true(is_old);
                }
                if (cut == total) {
                    assert_true(is_new);
                }
                n_old += is_old ? 1U : 0U;
                n_new += is_new ? 1U : 0U;
            }
        }
        print_message("%s: %u bytes; cut at 0..%u (lost, torn): %u old (%u reported), %u new\n",
                      sc->name, (unsigned)total, (unsigned)total, (unsigned)n_old,
                      (unsigned)n_reported, (unsigned)n_new);
        /* the header goes last: only a complete save (or one whose missing
         * bytes happen to be there already) yields the new set */
        assert_int_equal(n_old + n_new, 2U * (total + 1U));
        assert_true(n_new >= 2U);
        assert_true(n_old >= 2U * total - 4U);
    }
}

static void interrupted_save_then_complete_save(void **state)
{
    (void)state;
    write_set(BUS, &SET_A);
    tb_xfer(BUS, SAVE_ALL, SAVED_ALL);
    write_set(BUS, &SET_B);
    tb_nv_cut(BUS, 40U, false);
    /* (a device would not live to send this answer) */
    tb_xfer(BUS, SAVE_ALL, "581 80 10 10 01 00 00 06 06");
    tb_nv_power_on(BUS);
    power_cycle();
    expect_comm(BUS, &SET_A);
    expect_app(BUS, &SET_A);
    /* the next save completes */
    write_set(BUS, &SET_C);
    tb_xfer(BUS, SAVE_ALL, SAVED_ALL);
    power_cycle();
    expect_comm(BUS, &SET_C);
    expect_app(BUS, &SET_C);
    /* and the one after goes to the other bank, still atomic */
    write_set(BUS, &SET_B);
    tb_nv_cut(BUS, 20U, true);
    tb_send(BUS, SAVE_APP);
    tb_nv_power_on(BUS);
    power_cycle();
    expect_comm(BUS, &SET_C);
    expect_app(BUS, &SET_C);
    write_set(BUS, &SET_B);
    tb_xfer(BUS, SAVE_APP, SAVED_APP);
    power_cycle();
    expect_comm(BUS, &SET_C);
    expect_app(BUS, &SET_B);
    /* an interrupted restore (cut in its header: reported), then a
     * complete one, which ends the report */
    tb_nv_cut(BUS, 8U, false);
    tb_send(BUS, LOAD_ALL);
    tb_nv_power_on(BUS);
    cut_allowed = true;
    power_cycle();
    cut_allowed = false;
    assert_true(cut_reported);
    expect_app(BUS, &SET_B);
    tb_send(BUS, LOAD_ALL);
    tb_expect(BUS, LOADED_ALL);
    tb_advance(BUS, 100000U); /* the EMCY inhibit time of the boot's report */
    tb_expect(BUS, "081 00 00 00 00 00 00 00 00");
    tb_expect_none(BUS);
    power_cycle();
    expect_comm(BUS, &DEF);
    expect_app(BUS, &DEF);
}

/* ------------------------------------- asynchronous, flash-like NV (item 9) */

static int setup_async(void **state)
{
    memset(&fx, 0, sizeof fx);
    tb_init(&fx.bus);
    fx.bus.nv_async = true;
    fx.bus.nv_busy_each = 40U; /* each erase / write takes 40 polls (1 ms apart) */
    fx.dev = td_dev;
    power_cycle();
    *state = &fx;
    return 0;
}

/* A save on a HAL that erases and writes in the background: the node keeps
 * serving the bus (heartbeats keep their 10 ms period, SDO requests are
 * answered), the bank is erased once in whole units and written once, and
 * the SDO answer comes when the set is durable. */
static void async_save_serves_the_bus(void **state)
{
    uint32_t t0;
    unsigned beats = 0U;
    const co_frame_t *f;

    (void)state;
    assert_int_equal(co_store_nv_size_unit(&td_dev, TB_NV_ERASE_UNIT), 2U * TB_NV_ERASE_UNIT);
    write_set(BUS, &SET_A);
    tb_xfer(BUS, "601 2B 17 10 00 0A 00 00 00", "581 60 17 10 00 00 00 00 00");
    t0 = fx.bus.now;
    tb_send(BUS, SAVE_ALL);
    tb_expect_none(BUS);                 /* not durable yet: no answer */
    assert_int_equal(fx.bus.nv_erases, 1U);
    assert_int_equal(fx.bus.nv_erase_addr, 0U); /* no set yet: bank 0 */
    assert_int_equal(fx.bus.nv_erase_len, TB_NV_ERASE_UNIT);
    /* another save meanwhile: refused; another request: answered */
    tb_xfer(BUS, SAVE_APP, "581 80 10 10 03 22 00 00 08");
    tb_advance(BUS, 5000U);
    tb_xfer(BUS, "601 40 17 10 00 00 00 00 00", "581 80 17 10 00 22 00 00 08");
    /* 10 ms steps: a heartbeat in each until the answer */
    f = NULL;
    for (unsigned k = 0U; (k < 20U) && (f == NULL); k++) {
        tb_advance(BUS, 10000U);
        tb_expect(BUS, "701 7F");
        beats++;
        f = tb_next(BUS);
    }
    assert_non_null(f);
    TF_ASSERT_FRAME(f, SAVED_ALL);
    tb_expect_none(BUS);
    /* erase (40 polls) then data and header (40 polls): about 80 ms */
    assert_in_range(fx.bus.now - t0, 75000U, 100000U);
    assert_in_range(beats, 7U, 9U);
    assert_int_equal(fx.bus.nv_unerased, 0U);
    tb_advance(BUS, 10000U);
    tb_expect(BUS, "701 7F");
    tb_expect_none(BUS);
    power_cycle();
    expect_comm(BUS, &SET_A);
    expect_app(BUS, &SET_A);
    /* the next save erases and writes the other bank */
    tb_xfer(BUS, "601 2B 17 10 00 00 00 00 00", "581 60 17 10 00 00 00 00 00");
    write_set(BUS, &SET_B);
    tb_send(BUS, SAVE_ALL);
    tb_advance(BUS, 200000U);
    tb_expect(BUS, SAVED_ALL);
    assert_int_equal(fx.bus.nv_erases, 2U);
    assert_int_equal(fx.bus.nv_erase_addr, TB_NV_ERASE_UNIT);
    assert_int_equal(fx.bus.nv_unerased, 0U);
    power_cycle();
    expect_app(BUS, &SET_B);
}

/* The answer comes in the co_node_process call whose poll of the HAL finds
 * the set durable, not at the SDO server's next look one millisecond later
 * (the SDO row runs before the storage row in a pass: the end of the
 * command makes it run once more). */
static void async_save_answers_when_durable(void **state)
{
    unsigned steps = 0U;

    (void)state;
    write_set(BUS, &SET_A);
    tb_send(BUS, SAVE_ALL);
    tb_expect_none(BUS);
    while (co_store_busy(&fx.n.node) && (steps < 1000U)) {
        tb_expect_none(BUS);
        tb_advance(BUS, 1000U); /* the storage service polls the HAL every 1 ms */
        steps++;
    }
    assert_false(co_store_busy(&fx.n.node));
    tb_expect(BUS, SAVED_ALL); /* in that same step */
    tb_expect_none(BUS);
}

/* The HAL reports a failed write: the save answers 0x06060000, the old set stays. */
static void async_save_failure(void **state)
{
    (void)state;
    write_set(BUS, &SET_A);
    tb_send(BUS, SAVE_ALL);
    tb_advance(BUS, 200000U);
    tb_expect(BUS, SAVED_ALL);
    write_set(BUS, &SET_B);
    fx.bus.nv_fail_poll = true;
    tb_send(BUS, SAVE_ALL);
    tb_expect_none(BUS);
    tb_advance(BUS, 200000U);
    tb_expect(BUS, "581 80 10 10 01 00 00 06 06");
    tb_expect_none(BUS);
    fx.bus.nv_fail_poll = false;
    /* the client gave up meanwhile (abort): the save still ends, silently */
    tb_send(BUS, SAVE_ALL);
    tb_send(BUS, "601 80 10 10 01 00 00 04 05");
    tb_advance(BUS, 200000U);
    tb_expect_none(BUS);
    tb_send(BUS, SAVE_APP);
    tb_advance(BUS, 200000U);
    tb_expect(BUS, SAVED_APP);
    tb_expect_none(BUS);
}

/* ------------------------------------------------- the generated device */

static void start_generic(void)
{
    co_node_config_t cfg;

    memset(&fx.g, 0, sizeof fx.g);
    generic_301_config(&fx.g, &cfg);
    cfg.hal = tb_hal(BUS, 0);
    cfg.node_id = 5U;
    tb_attach(BUS, 0, &fx.g.node);
    tb_flush(BUS);
    assert_int_equal(co_node_init(&fx.g.node, &cfg, fx.bus.now), CO_RESULT_OK);
    tb_expect(BUS, "705 00");
    tb_expect_none(BUS);
}

static void generic_301_stores_and_restores(void **state)
{
    (void)state;
    assert_true(co_store_nv_size(&generic_301_dev) <= TB_NV_SIZE);
    start_generic();
    tb_xfer(BUS, "605 40 10 10 00 00 00 00 00", "585 4F 10 10 00 03 00 00 00");
    tb_xfer(BUS, "605 40 10 10 01 00 00 00 00", "585 43 10 10 01 01 00 00 00");
    tb_xfer(BUS, "605 40 11 10 03 00 00 00 00", "585 43 11 10 03 01 00 00 00");
    /* 0x1015 (communication), 0x200C (application) */
    tb_xfer(BUS, "605 2B 15 10 00 0A 00 00 00", "585 60 15 10 00 00 00 00 00");
    tb_xfer(BUS, "605 23 0C 20 00 78 56 34 12", "585 60 0C 20 00 00 00 00 00");
    tb_xfer(BUS, "605 23 10 10 01 73 61 76 65", "585 60 10 10 01 00 00 00 00");
    tb_xfer(BUS, "605 40 10 10 01 00 00 00 00", "585 43 10 10 01 01 00 00 00");
    start_generic();
    tb_xfer(BUS, "605 40 15 10 00 00 00 00 00", "585 4B 15 10 00 0A 00 00 00");
    tb_xfer(BUS, "605 40 0C 20 00 00 00 00 00", "585 43 0C 20 00 78 56 34 12");
    tb_xfer(BUS, "605 23 11 10 01 73 61 76 65", "585 80 11 10 01 20 00 00 08");
    tb_xfer(BUS, "605 23 11 10 01 6C 6F 61 64", "585 60 11 10 01 00 00 00 00");
    tb_send(BUS, "000 81 05");
    tb_expect(BUS, "705 00");
    tb_xfer(BUS, "605 40 15 10 00 00 00 00 00", "585 4B 15 10 00 00 00 00 00");
    tb_xfer(BUS, "605 40 0C 20 00 00 00 00 00", "585 43 0C 20 00 32 32 32 D0");
}

/* A PDO set up over SDO and stored is in effect after power on. */
static void stored_pdo_mapping_after_power_on(void **state)
{
    (void)state;
    start_generic();
    tb_xfer(BUS, "605 23 00 18 01 85 01 00 80", "585 60 00 18 01 00 00 00 00");
    tb_xfer(BUS, "605 2F 00 1A 00 00 00 00 00", "585 60 00 1A 00 00 00 00 00");
    tb_xfer(BUS, "605 23 00 1A 01 10 00 01 21", "585 60 00 1A 01 00 00 00 00");
    tb_xfer(BUS, "605 2F 00 1A 00 01 00 00 00", "585 60 00 1A 00 00 00 00 00");
    tb_xfer(BUS, "605 2F 00 18 02 01 00 00 00", "585 60 00 18 02 00 00 00 00");
    tb_xfer(BUS, "605 23 00 18 01 85 01 00 00", "585 60 00 18 01 00 00 00 00");
    tb_xfer(BUS, "605 23 10 10 02 73 61 76 65", "585 60 10 10 02 00 00 00 00");
    start_generic();
    /* (the entry is stored in its 16-bit form, co_od.h: read back whole) */
    tb_xfer(BUS, "605 40 00 1A 01 00 00 00 00", "585 43 00 1A 01 10 00 01 21");
    tb_xfer(BUS, "605 2B 01 21 00 34 12 00 00", "585 60 01 21 00 00 00 00 00");
    tb_send(BUS, "000 01 05");
    tb_expect(BUS, "285 00 00 00 00 00 00 00 00"); /* TPDO2, event-driven */
    tb_expect_none(BUS); /* TPDO1 is synchronous now: nothing at start */
    tb_send(BUS, "080");
    tb_expect(BUS, "185 34 12");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(capability_reads_and_signature_does_not_change_them, setup),
        cmocka_unit_test_setup(save_all_survives_resets_and_power_cycle, setup),
        cmocka_unit_test_setup(cob_ids_in_16_bits_survive_reset_and_power_cycle, setup),
        cmocka_unit_test_setup(save_comm_only, setup),
        cmocka_unit_test_setup(save_app_only, setup),
        cmocka_unit_test_setup(partial_save_keeps_the_other_group, setup),
        cmocka_unit_test_setup(restore_all_takes_effect_at_reset, setup),
        cmocka_unit_test_setup(restore_comm_at_reset_communication, setup),
        cmocka_unit_test_setup(restore_app_at_reset_node, setup),
        cmocka_unit_test_setup(restore_without_stored_set_writes_nothing, setup),
        cmocka_unit_test_setup(restore_saved_undoes_a_restore, setup),
        cmocka_unit_test_setup(restore_saved_by_group, setup),
        cmocka_unit_test_setup(restore_saved_power_cut, setup),
        cmocka_unit_test_setup(wrong_signature_aborts, setup),
        cmocka_unit_test_setup(hal_without_nv, setup),
        cmocka_unit_test_setup(nv_failure_aborts_with_hardware_error, setup),
        cmocka_unit_test_setup(foreign_layout_ignored, setup),
        cmocka_unit_test_setup(corrupt_set_ignored, setup),
        cmocka_unit_test_setup(power_cut_at_every_byte, setup),
        cmocka_unit_test_setup(interrupted_save_then_complete_save, setup),
        cmocka_unit_test_setup(generic_301_stores_and_restores, setup),
        cmocka_unit_test_setup(stored_pdo_mapping_after_power_on, setup),
        cmocka_unit_test_setup(async_save_serves_the_bus, setup_async),
        cmocka_unit_test_setup(async_save_failure, setup_async),
        cmocka_unit_test_setup(async_save_answers_when_durable, setup_async),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
