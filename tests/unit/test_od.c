/*
 * Object dictionary: lookup, the single access path for the application,
 * hooks (refresh, veto, streamed I/O), defaults and $NODEID, and the abort
 * codes that only a hook can produce, each seen on the wire.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "co/co_endian.h"
#include "test_bus.h"
#include "test_dev.h"

typedef struct fx {
    tb_bus_t bus;
    td_node_t n;
    co_err_t veto;        /* what the 0x2100 write hook answers */
    co_err_t read_err;    /* what the 0x2100 read hook answers */
    uint32_t refresh;     /* value the 0x2100 read hook stores before a read */
    unsigned reads;
    unsigned writes;
    uint32_t seen;        /* value the write hook was offered */
    uint32_t computed;    /* 0x2201 (hook I/O) */
    bool scribble;        /* the 0x2100 read hook sets its chunk's len, total and last */
    uint32_t read_offset; /* the offset the 0x2100 read hook saw */
} fx_t;

static fx_t fx;

static co_err_t h2100_read(void *ctx, co_od_io_t *io)
{
    fx_t *f = (fx_t *)ctx;
    f->reads++;
    f->read_offset = io->offset;
    if (f->scribble) {
        io->len = 1U;
        io->total = 1U;
        io->last = true;
    }
    if (f->read_err == CO_OK) {
        *(uint32_t *)io->value = f->refresh;
    }
    return f->read_err;
}

static co_err_t h2100_write(void *ctx, co_od_io_t *io)
{
    fx_t *f = (fx_t *)ctx;
    f->writes++;
    assert_int_equal(io->len, 4);
    assert_int_equal(io->entry->index, 0x2100);
    f->seen = co_get_u32(io->buf);
    return f->veto;
}

static co_err_t h2201_read(void *ctx, co_od_io_t *io)
{
    fx_t *f = (fx_t *)ctx;
    assert_null(io->value);
    assert_true(io->len >= 4U);
    co_put_u32(io->buf, f->computed);
    io->len = 4U;
    io->total = 4U;
    io->last = true;
    return CO_OK;
}

static co_err_t h2201_write(void *ctx, co_od_io_t *io)
{
    fx_t *f = (fx_t *)ctx;
    if (io->len != 4U) {
        return CO_ERR_TYPE_MISMATCH;
    }
    f->computed = co_get_u32(io->buf) * 2U;
    return CO_OK;
}

static int setup(void **state)
{
    co_od_hook_t h1 = {h2100_read, h2100_write, &fx};
    co_od_hook_t h3 = {h2201_read, h2201_write, &fx};
    memset(&fx, 0, sizeof fx);
    tb_init(&fx.bus);
    td_start(&fx.n, &fx.bus, 0, 5, NULL);
    tb_flush(&fx.bus);
    assert_int_equal(co_od_bind_hook(&fx.n.node, 0x2100, &h1), CO_RESULT_OK);
    assert_int_equal(co_od_bind_hook(&fx.n.node, 0x2201, &h3), CO_RESULT_OK);
    fx.refresh = 0x0BADCAFEUL;
    *state = &fx;
    return 0;
}

#define BUS (&fx.bus)
#define NODE (&fx.n.node)

static void find_every_entry_and_reject_gaps(void **state)
{
    const co_dev_t *dev = &td_dev;
    (void)state;
    for (uint16_t i = 0; i < dev->od_count; i++) {
        const co_od_entry_t *e = co_od_find(dev->od, dev->od_count, dev->od[i].index);
        assert_ptr_equal(e, &dev->od[i]);
        if (i > 0U) {
            assert_true(dev->od[i - 1U].index < dev->od[i].index); /* sorted */
            if ((uint16_t)(dev->od[i - 1U].index + 1U) < dev->od[i].index) {
                assert_null(co_od_find(dev->od, dev->od_count,
                                       (uint16_t)(dev->od[i - 1U].index + 1U)));
            }
        }
    }
    assert_null(co_od_find(dev->od, dev->od_count, 0x0000));
    assert_null(co_od_find(dev->od, dev->od_count, 0xFFFF));
    assert_null(co_od_find(dev->od, 0, 0x1000));
}

/* A row that is a run (0x1003 sub 1..8, 0x6099 sub 1..2 with a limit in
 * td_dev): each sub-index its own descriptor, value and limit; nothing
 * past the run. */
static void run_rows_describe_each_sub_index(void **state)
{
    const co_od_entry_t *e = co_od_find(td_dev.od, td_dev.od_count, 0x1003);
    co_od_sub_t d;
    uint8_t b[4] = {0x10, 0x20, 0x30, 0x40};
    uint32_t v = 0U;
    uint32_t len = 0U;
    (void)state;
    assert_non_null(e);
    assert_int_equal(e->nsubs, 2); /* sub 0, and one row for 1..8 */
    fx.n.ram.hist_n = 8U; /* (entries past the count read as no data: EMCY) */
    for (uint8_t k = 1U; k <= 8U; k++) {
        assert_ptr_equal(co_od_find_sub(&td_dev, e, k, &d), &d);
        assert_int_equal(d.sub, k);
        assert_int_equal(d.type, CO_UNSIGNED32);
        assert_int_equal(d.flags, CO_SUB_RO); /* (no run bits) */
        assert_int_equal(d.size, 4);
        assert_int_equal(d.off, offsetof(td_ram_t, hist) + (4U * (k - 1U)));
        assert_ptr_equal(co_od_value_ptr(NODE, 0x1003, k), &fx.n.ram.hist[k - 1U]);
        fx.n.ram.hist[k - 1U] = 0x1000U + k;
        assert_int_equal(co_od_read(NODE, 0x1003, k, &v, 4U, &len), CO_OK);
        assert_int_equal(len, 4);
        assert_int_equal(co_get_u32((const uint8_t *)&v), 0x1000U + k);
    }
    assert_null(co_od_find_sub(&td_dev, e, 9, &d));
    assert_null(co_od_find_sub(&td_dev, e, 0xFF, &d));
    assert_int_equal(co_od_read(NODE, 0x1003, 9, &v, 4U, &len), CO_ERR_NO_SUB);
    /* 0x6099 sub 2: the run's limit 0..60000 (sub 1 written, sub 2 kept) */
    co_put_u32(b, 60001U);
    assert_int_equal(co_od_write(NODE, 0x6099, 2, b, 4U, true), CO_ERR_VALUE_HIGH);
    co_put_u32(b, 60000U);
    assert_int_equal(co_od_write(NODE, 0x6099, 2, b, 4U, true), CO_OK);
    co_put_u32(b, 7U);
    assert_int_equal(co_od_write(NODE, 0x6099, 1, b, 4U, true), CO_OK);
    assert_int_equal(fx.n.ram.homing_speed[0], 7U);
    assert_int_equal(fx.n.ram.homing_speed[1], 60000U);
    /* the services bound the runs' lengths (co_od_array_len; 0x1003's depth,
     * looked up when an error comes: test_emcy history_depth_eight) */
    assert_int_equal(fx.n.node.n_hb_cons, 4);
}

/* A run of const values (CO_SUB_ROM): one value, at the row's offset, for
 * every sub-index of the run (odgen: the identity's zeros, the store
 * commands' 0). */
static void rom_run_is_one_value(void **state)
{
    static const co_od_sub_t rows[] = {
        CO_OD_SUB(0U, (uint8_t)CO_UNSIGNED8, CO_SUB_RO | CO_SUB_CONST | CO_SUB_ROM, 1U, 0U, 0U),
        CO_OD_RUN(1U, 4U, (uint8_t)CO_UNSIGNED32, CO_SUB_RO | CO_SUB_ROM, 4U, 8U, 0U),
        CO_OD_SUB(7U, (uint8_t)CO_UNSIGNED16, CO_SUB_RW, 2U, 2U, 0U),
    };
    static const co_od_entry_t e = CO_OD_ENTRY(0x3000U, 3U, 0U, (uint8_t)CO_OBJ_RECORD, 0U);
    static const co_dev_t dev = {.od = &e, .rows = rows, .od_count = 1U};
    co_od_sub_t d;
    (void)state;
    for (uint8_t k = 1U; k <= 4U; k++) {
        assert_ptr_equal(co_od_find_sub(&dev, &e, k, &d), &d);
        assert_int_equal(d.sub, k);
        assert_int_equal(d.flags, CO_SUB_RO | CO_SUB_ROM);
        assert_int_equal(d.size, 4);
        assert_int_equal(d.off, 8);
        assert_ptr_equal(co_od_row_sub(&rows[1], k - 1U, &d), &d);
        assert_int_equal(d.sub, k);
        assert_int_equal(d.off, 8);
    }
    assert_int_equal(co_od_run_len(&rows[1]), 4);
    assert_null(co_od_find_sub(&dev, &e, 5U, &d));
    assert_non_null(co_od_find_sub(&dev, &e, 7U, &d));
    assert_int_equal(d.type, CO_UNSIGNED16);
    assert_int_equal(d.off, 2);
    assert_non_null(co_od_find_sub(&dev, &e, 0U, &d));
    assert_int_equal(d.type, CO_UNSIGNED8);
}

static void type_sizes(void **state)
{
    (void)state;
    assert_int_equal(co_type_size(CO_BOOLEAN), 1);
    assert_int_equal(co_type_size(CO_INTEGER24), 3);
    assert_int_equal(co_type_size(CO_UNSIGNED40), 5);
    assert_int_equal(co_type_size(CO_INTEGER48), 6);
    assert_int_equal(co_type_size(CO_UNSIGNED56), 7);
    assert_int_equal(co_type_size(CO_REAL64), 8);
    assert_int_equal(co_type_size(CO_TIME_OF_DAY), 6);
    assert_int_equal(co_type_size(CO_VISIBLE_STRING), 0);
    assert_int_equal(co_type_size(CO_DOMAIN), 0);
    assert_int_equal(co_type_size(0xEE), 0);
    assert_int_equal(co_type_size(0x21), 0); /* (not BOOLEAN's size: no type) */
    assert_int_equal(co_type_size(0x1C), 0);
}

static void nodeid_relative_defaults(void **state)
{
    (void)state;
    assert_int_equal(fx.n.ram.emcy_cob, 0x85);
    assert_int_equal(fx.n.ram.node_id, 5);
    tb_xfer(BUS, "605 40 14 10 00 00 00 00 00", "585 43 14 10 00 85 00 00 00");
}

static void app_access_path(void **state)
{
    uint8_t w[4];
    uint32_t len = 0;
    char s[40];
    (void)state;
    /* co_od_write takes the value as wire bytes (little-endian), never a
     * native integer: on a big-endian CPU these must still mean 0x55AA */
    co_put_u32(w, 0x55AAU);
    /* the application may set read-only values, SDO may not */
    assert_int_equal(co_od_write(NODE, 0x1002, 0, w, 4, true), CO_OK);
    assert_int_equal(co_od_write(NODE, 0x1002, 0, w, 4, false), CO_ERR_READ_ONLY);
    assert_int_equal(fx.n.ram.mfr_status, 0x55AA);
    /* ... but never a ROM constant */
    assert_int_equal(co_od_write(NODE, 0x1000, 0, w, 4, true), CO_ERR_READ_ONLY);
    /* limits apply to the application too */
    co_put_u16(w, 5000U);
    assert_int_equal(co_od_write(NODE, 0x2020, 0, w, 2, true), CO_ERR_VALUE_HIGH);
    /* co_od_read gives wire bytes too */
    assert_int_equal(co_od_read(NODE, 0x1000, 0, w, sizeof w, &len), CO_OK);
    assert_int_equal(len, 4);
    assert_int_equal(co_get_u32(w), 0x00020192UL);
    assert_int_equal(w[0], 0x92);
    assert_int_equal(co_od_read(NODE, 0x1008, 0, s, sizeof s, &len), CO_OK);
    assert_int_equal(len, 7);
    assert_memory_equal(s, "631_402", 7);
    /* a buffer that is too small */
    assert_int_equal(co_od_read(NODE, 0x1008, 0, s, 3, &len), CO_ERR_TYPE_TOO_LONG);
    assert_int_equal(co_od_read(NODE, 0x1234, 0, s, 3, &len), CO_ERR_NO_OBJECT);
    assert_int_equal(co_od_read(NODE, 0x1000, 1, s, 3, &len), CO_ERR_NO_SUB);
    /* direct pointers for the application's own use */
    assert_ptr_equal(co_od_value_ptr(NODE, 0x2004, 0), &fx.n.ram.u32);
    assert_null(co_od_value_ptr(NODE, 0x1000, 0));  /* ROM */
    assert_null(co_od_value_ptr(NODE, 0x2200, 0));  /* hook I/O */
    assert_null(co_od_value_ptr(NODE, 0x4321, 0));
}

static void bind_hook_errors(void **state)
{
    co_od_hook_t h = {NULL, NULL, NULL};
    (void)state;
    assert_int_equal(co_od_bind_hook(NODE, 0x4321, &h), CO_RESULT_NO_OBJECT);
    assert_int_equal(co_od_bind_hook(NODE, 0x2004, &h), CO_RESULT_NO_HOOK_SLOT); /* no slot */
}

static void read_hook_refreshes_value(void **state)
{
    (void)state;
    tb_xfer(BUS, "605 40 00 21 00 00 00 00 00", "585 43 00 21 00 FE CA AD 0B");
    assert_int_equal(fx.reads, 1);
    assert_int_equal(fx.n.ram.hooked, 0x0BADCAFEUL);
}

/* The read hook of a stored value runs once, at offset 0, on the reader's
 * chunk: what it sets there (len, total, last) does not cut the value,
 * which is read after it. */
static void read_hook_leaves_the_chunk_to_the_value(void **state)
{
    uint8_t b[8] = {0};
    uint32_t len = 0U;
    (void)state;
    fx.scribble = true;
    fx.read_offset = 0xFFFFFFFFUL;
    tb_xfer(BUS, "605 40 00 21 00 00 00 00 00", "585 43 00 21 00 FE CA AD 0B");
    assert_int_equal(fx.read_offset, 0);
    fx.refresh = 0x01020304UL;
    assert_int_equal(co_od_read(NODE, 0x2100, 0, b, sizeof b, &len), CO_OK);
    assert_int_equal(len, 4);
    assert_int_equal(co_get_u32(b), 0x01020304UL);
    assert_int_equal(fx.reads, 2);
}

static void write_hook_sees_value_and_vetoes(void **state)
{
    (void)state;
    tb_xfer(BUS, "605 23 00 21 00 44 33 22 11", "585 60 00 21 00 00 00 00 00");
    assert_int_equal(fx.seen, 0x11223344UL);
    assert_int_equal(fx.n.ram.hooked, 0x11223344UL);
    fx.veto = CO_ERR_VALUE;
    tb_xfer(BUS, "605 23 00 21 00 01 00 00 00", "585 80 00 21 00 30 00 09 06");
    assert_int_equal(fx.n.ram.hooked, 0x11223344UL); /* not committed */
    assert_int_equal(fx.writes, 2);
}

/* Codes only an application or profile can have a reason for: each one a
 * hook returns reaches the master unchanged. */
static void hook_codes_reach_the_wire(void **state)
{
    static const struct {
        co_err_t code;
        const char *abort;
    } cases[] = {
        {CO_ERR_NO_MEMORY, "585 80 00 21 00 05 00 04 05"},
        {CO_ERR_NO_MAP, "585 80 00 21 00 41 00 04 06"},
        {CO_ERR_MAP_LEN, "585 80 00 21 00 42 00 04 06"},
        {CO_ERR_PARAM_INCOMPAT, "585 80 00 21 00 43 00 04 06"},
        {CO_ERR_DEV_INCOMPAT, "585 80 00 21 00 47 00 04 06"},
        {CO_ERR_HW, "585 80 00 21 00 00 00 06 06"},
        {CO_ERR_MAX_LT_MIN, "585 80 00 21 00 36 00 09 06"},
        {CO_ERR_GENERAL, "585 80 00 21 00 00 00 00 08"},
        {CO_ERR_STORE, "585 80 00 21 00 20 00 00 08"},
        {CO_ERR_STORE_LOCAL, "585 80 00 21 00 21 00 00 08"},
        {CO_ERR_STORE_STATE, "585 80 00 21 00 22 00 00 08"},
        {CO_ERR_OD_MISSING, "585 80 00 21 00 23 00 00 08"},
        {CO_ERR_NO_DATA, "585 80 00 21 00 24 00 00 08"},
    };
    (void)state;
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        fx.veto = cases[i].code;
        tb_xfer(BUS, "605 23 00 21 00 01 00 00 00", cases[i].abort);
        fx.veto = CO_OK;
        fx.read_err = cases[i].code;
        tb_send(BUS, "605 40 00 21 00 00 00 00 00");
        tb_expect(BUS, cases[i].abort);
        tb_expect_none(BUS);
        fx.read_err = CO_OK;
    }
}

static void hook_io_value(void **state)
{
    (void)state;
    fx.computed = 0x01020304UL;
    tb_xfer(BUS, "605 40 01 22 00 00 00 00 00", "585 43 01 22 00 04 03 02 01");
    tb_xfer(BUS, "605 23 01 22 00 10 00 00 00", "585 60 01 22 00 00 00 00 00");
    assert_int_equal(fx.computed, 0x20);
    tb_xfer(BUS, "605 2B 01 22 00 10 00 00 00", "585 80 01 22 00 10 00 07 06");
}

static void hook_io_without_hook_is_no_access(void **state)
{
    (void)state;
    /* the DOMAIN 0x2200 has no hook bound in this fixture */
    tb_xfer(BUS, "605 40 00 22 00 00 00 00 00", "585 80 00 22 00 00 00 01 06");
    tb_xfer(BUS, "605 21 00 22 00 10 00 00 00", "585 60 00 22 00 00 00 00 00");
    tb_xfer(BUS, "605 00 01 02 03 04 05 06 07", "585 80 00 22 00 00 00 01 06");
}

static void every_type_round_trips_little_endian(void **state)
{
    (void)state;
    tb_xfer(BUS, "605 23 08 20 00 00 00 80 3F", "585 60 08 20 00 00 00 00 00"); /* 1.0f */
    tb_xfer(BUS, "605 40 08 20 00 00 00 00 00", "585 43 08 20 00 00 00 80 3F");
    assert_int_equal(fx.n.ram.r32, 0x3F800000UL);
    tb_xfer(BUS, "605 2F 01 20 00 FE 00 00 00", "585 60 01 20 00 00 00 00 00");
    assert_int_equal(fx.n.ram.i8, -2);
    /* 40-bit: segmented (5 bytes) */
    tb_xfer(BUS, "605 21 0D 20 00 05 00 00 00", "585 60 0D 20 00 00 00 00 00");
    tb_xfer(BUS, "605 05 01 02 03 04 05 00 00", "585 20 00 00 00 00 00 00 00");
    assert_memory_equal(fx.n.ram.u40, "\x01\x02\x03\x04\x05", 5);
    tb_xfer(BUS, "605 40 0D 20 00 00 00 00 00", "585 41 0D 20 00 05 00 00 00");
    tb_xfer(BUS, "605 60 00 00 00 00 00 00 00", "585 05 01 02 03 04 05 00 00");
    /* TIME_OF_DAY, 6 bytes */
    tb_xfer(BUS, "605 21 10 20 00 06 00 00 00", "585 60 10 20 00 00 00 00 00");
    tb_xfer(BUS, "605 03 10 20 30 40 50 60 00", "585 20 00 00 00 00 00 00 00");
    assert_memory_equal(fx.n.ram.tod, "\x10\x20\x30\x40\x50\x60", 6);
    /* OCTET_STRING is not cut at a zero byte */
    tb_xfer(BUS, "605 21 13 20 00 0A 00 00 00", "585 60 13 20 00 00 00 00 00");
    tb_xfer(BUS, "605 00 00 01 00 02 00 03 00", "585 20 00 00 00 00 00 00 00");
    tb_xfer(BUS, "605 19 04 00 05 00 00 00 00", "585 30 00 00 00 00 00 00 00");
    tb_xfer(BUS, "605 40 13 20 00 00 00 00 00", "585 41 13 20 00 0A 00 00 00");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(find_every_entry_and_reject_gaps, setup),
        cmocka_unit_test_setup(run_rows_describe_each_sub_index, setup),
        cmocka_unit_test_setup(rom_run_is_one_value, setup),
        cmocka_unit_test_setup(type_sizes, setup),
        cmocka_unit_test_setup(nodeid_relative_defaults, setup),
        cmocka_unit_test_setup(app_access_path, setup),
        cmocka_unit_test_setup(bind_hook_errors, setup),
        cmocka_unit_test_setup(read_hook_refreshes_value, setup),
        cmocka_unit_test_setup(read_hook_leaves_the_chunk_to_the_value, setup),
        cmocka_unit_test_setup(write_hook_sees_value_and_vetoes, setup),
        cmocka_unit_test_setup(hook_codes_reach_the_wire, setup),
        cmocka_unit_test_setup(hook_io_value, setup),
        cmocka_unit_test_setup(hook_io_without_hook_is_no_access, setup),
        cmocka_unit_test_setup(every_type_round_trips_little_endian, setup),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
