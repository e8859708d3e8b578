/*
 * PDOs whose mapped objects are plain values (no hook, no limits, index
 * 0x2000 and above, mapped whole at a byte boundary) are copied between
 * frame and RAM image without the dictionary's path; the resolution is made
 * when the mapping is enabled. These tests mix plain entries with entries
 * that must still go through the dictionary (hooks, limits, BOOLEAN, bit
 * mapping, dummies, more entries than are resolved) and change mappings
 * between plain and hooked objects, by SDO and by reset.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "cia401.h"
#include "pdo_fx.h"

static pfx_t fx;
#define BUS (&fx.bus)

/* Map TPDO1 (0x1A00, COB-ID 0x181) or RPDO1 (0x1600, COB-ID 0x201) to the
 * @p n entries of @p map, by SDO (invalid, count 0, entries, count, valid). */
static void map_pdo1(bool tx, const uint32_t *map, uint8_t n)
{
    uint8_t comm = tx ? 0x18U : 0x14U;
    uint8_t mapping = tx ? 0x1AU : 0x16U;
    unsigned cob = tx ? 0x181U : 0x201U;
    char req[64];
    char res[64];

    snprintf(req, sizeof req, "601 23 00 %02X 01 %02X %02X 00 80", comm, cob & 0xFFU, cob >> 8);
    snprintf(res, sizeof res, "581 60 00 %02X 01 00 00 00 00", comm);
    tb_xfer(BUS, req, res);
    snprintf(req, sizeof req, "601 2F 00 %02X 00 00 00 00 00", mapping);
    snprintf(res, sizeof res, "581 60 00 %02X 00 00 00 00 00", mapping);
    tb_xfer(BUS, req, res);
    for (uint8_t k = 0; k < n; k++) {
        snprintf(req, sizeof req, "601 23 00 %02X %02X %02X %02X %02X %02X", mapping, k + 1U,
                 (unsigned)(map[k] & 0xFFU), (unsigned)((map[k] >> 8) & 0xFFU),
                 (unsigned)((map[k] >> 16) & 0xFFU), (unsigned)(map[k] >> 24));
        snprintf(res, sizeof res, "581 60 00 %02X %02X 00 00 00 00", mapping, k + 1U);
        tb_xfer(BUS, req, res);
    }
    snprintf(req, sizeof req, "601 2F 00 %02X 00 %02X 00 00 00", mapping, n);
    snprintf(res, sizeof res, "581 60 00 %02X 00 00 00 00 00", mapping);
    tb_xfer(BUS, req, res);
    snprintf(req, sizeof req, "601 23 00 %02X 01 %02X %02X 00 00", comm, cob & 0xFFU, cob >> 8);
    snprintf(res, sizeof res, "581 60 00 %02X 01 00 00 00 00", comm);
    tb_xfer(BUS, req, res);
}

static void mixed_tpdo(void **state)
{
    /* plain U16, hooked U32 (the read hook refreshes it), plain U8 */
    static const uint32_t map[] = {0x20080010UL, 0x20200020UL, 0x20070008UL};
    (void)state;
    pfx_start(&fx, 1, NULL);
    map_pdo1(true, map, 3);
    pfx_set(&fx, 0x2008, 0, 0x1234, 2);
    pfx_set(&fx, 0x2007, 0, 0x56, 1);
    fx.hook_value = 0xA1B2C3D4UL;
    tb_send(BUS, "000 01 01");
    tb_expect(BUS, "181 34 12 D4 C3 B2 A1 56");
    fx.hook_value = 0x01020304UL;
    pfx_set(&fx, 0x2007, 0, 0x57, 1);
    tb_advance(BUS, 0);
    tb_expect(BUS, "181 34 12 04 03 02 01 57");
    tb_expect_none(BUS);
}

static void mixed_rpdo(void **state)
{
    /* plain U8, hooked U32, limited U16 (10..1000), plain I8 */
    static const uint32_t map[] = {0x20070008UL, 0x20200020UL, 0x20100010UL, 0x20010008UL};
    (void)state;
    pfx_start(&fx, 1, NULL);
    map_pdo1(false, map, 4);
    tb_send(BUS, "000 01 01");
    tb_flush(BUS);
    tb_send(BUS, "201 11 44 33 22 11 64 00 F0");
    assert_int_equal(pfx_get(&fx, 0x2007, 0) & 0xFF, 0x11);
    assert_int_equal(fx.hook_written, 0x11223344UL);
    assert_int_equal(pfx_get(&fx, 0x2010, 0) & 0xFFFF, 100);
    assert_int_equal(pfx_get(&fx, 0x2001, 0) & 0xFF, 0xF0);
    /* 0x2010 refuses 5: it keeps its value, the plain entries still apply */
    tb_send(BUS, "201 22 88 77 66 55 05 00 0F");
    assert_int_equal(pfx_get(&fx, 0x2007, 0) & 0xFF, 0x22);
    assert_int_equal(fx.hook_written, 0x55667788UL);
    assert_int_equal(pfx_get(&fx, 0x2010, 0) & 0xFFFF, 100);
    assert_int_equal(pfx_get(&fx, 0x2001, 0) & 0xFF, 0x0F);
    assert_int_equal(fx.hook_writes, 2);
    tb_expect_none(BUS);
}

static void rpdo_more_entries_than_resolved(void **state)
{
    /* I8, U8, I16, BOOLEAN as 8 bits (checked: 0/1), U16, dummy U8 */
    static const uint32_t map[] = {0x20010008UL, 0x20070008UL, 0x20020010UL,
                                   0x20000008UL, 0x20080010UL, 0x00050008UL};
    (void)state;
    pfx_start(&fx, 1, NULL);
    map_pdo1(false, map, 6);
    tb_send(BUS, "000 01 01");
    tb_flush(BUS);
    tb_send(BUS, "201 F1 07 34 12 01 78 56 99");
    assert_int_equal(pfx_get(&fx, 0x2001, 0) & 0xFF, 0xF1);
    assert_int_equal(pfx_get(&fx, 0x2007, 0) & 0xFF, 0x07);
    assert_int_equal(pfx_get(&fx, 0x2002, 0) & 0xFFFF, 0x1234);
    assert_int_equal(pfx_get(&fx, 0x2000, 0) & 0xFF, 1);
    assert_int_equal(pfx_get(&fx, 0x2008, 0) & 0xFFFF, 0x5678);
    /* a BOOLEAN of 2 is refused; every other entry takes effect */
    tb_send(BUS, "201 01 02 03 04 02 05 06 07");
    assert_int_equal(pfx_get(&fx, 0x2001, 0) & 0xFF, 0x01);
    assert_int_equal(pfx_get(&fx, 0x2007, 0) & 0xFF, 0x02);
    assert_int_equal(pfx_get(&fx, 0x2002, 0) & 0xFFFF, 0x0403);
    assert_int_equal(pfx_get(&fx, 0x2000, 0) & 0xFF, 1);
    assert_int_equal(pfx_get(&fx, 0x2008, 0) & 0xFFFF, 0x0605);
    tb_expect_none(BUS);
}

static void tpdo_more_entries_than_resolved(void **state)
{
    /* I8, U8, I16, U16, then the low 16 bits of a U32 */
    static const uint32_t map[] = {0x20010008UL, 0x20070008UL, 0x20020010UL, 0x20080010UL,
                                   0x20090010UL};
    (void)state;
    pfx_start(&fx, 1, NULL);
    map_pdo1(true, map, 5);
    pfx_set(&fx, 0x2001, 0, 0x81, 1);
    pfx_set(&fx, 0x2007, 0, 0x42, 1);
    pfx_set(&fx, 0x2002, 0, 0xBEEF, 2);
    pfx_set(&fx, 0x2008, 0, 0x1357, 2);
    pfx_set(&fx, 0x2009, 0, 0xAABBCCDDUL, 4);
    tb_send(BUS, "000 01 01");
    tb_expect(BUS, "181 81 42 EF BE 57 13 DD CC");
    tb_expect_none(BUS);
}

static void remap_plain_and_hooked(void **state)
{
    static const uint32_t plain[] = {0x20090020UL};
    static const uint32_t hooked[] = {0x20200020UL};
    static const uint32_t limited[] = {0x20100010UL};
    (void)state;
    pfx_start(&fx, 1, NULL);
    pfx_set(&fx, 0x2009, 0, 0x11223344UL, 4);
    fx.hook_value = 0xCAFEF00DUL;
    map_pdo1(true, plain, 1);
    map_pdo1(false, plain, 1);
    tb_send(BUS, "000 01 01");
    tb_expect(BUS, "181 44 33 22 11");
    tb_send(BUS, "201 01 02 03 04");
    assert_int_equal(pfx_get(&fx, 0x2009, 0), 0x04030201UL);
    tb_advance(BUS, 0);
    tb_expect(BUS, "181 01 02 03 04");
    /* remapped to the hooked object: the hook produces the data */
    tb_send(BUS, "000 80 01");
    map_pdo1(true, hooked, 1);
    map_pdo1(false, limited, 1);
    tb_send(BUS, "000 01 01");
    tb_expect(BUS, "181 0D F0 FE CA");
    tb_send(BUS, "201 05 00"); /* below the limit: refused (the default is 10) */
    assert_int_equal(pfx_get(&fx, 0x2010, 0) & 0xFFFF, 10);
    tb_send(BUS, "201 C8 00");
    assert_int_equal(pfx_get(&fx, 0x2010, 0) & 0xFFFF, 200);
    assert_int_equal(pfx_get(&fx, 0x2009, 0), 0x04030201UL);
    /* and back to the plain object */
    tb_send(BUS, "000 80 01");
    map_pdo1(true, plain, 1);
    tb_send(BUS, "000 01 01");
    tb_expect(BUS, "181 01 02 03 04");
    tb_expect_none(BUS);
}

static void reset_restores_plain_mapping(void **state)
{
    static const uint32_t hooked[] = {0x20200020UL};
    (void)state;
    pfx_start(&fx, 1, NULL);
    map_pdo1(true, hooked, 1);
    pfx_set(&fx, 0x6041, 0, 0x0237, 2);
    fx.hook_value = 0xCAFEF00DUL;
    tb_send(BUS, "000 01 01");
    tb_expect(BUS, "181 0D F0 FE CA");
    /* reset communication: the default mapping (0x6041, plain) is back */
    tb_send(BUS, "000 82 01");
    tb_expect(BUS, "701 00");
    fx.hook_reads = 0;
    tb_send(BUS, "000 01 01");
    tb_expect(BUS, "181 37 02");
    assert_int_equal(fx.hook_reads, 0);
    tb_expect_none(BUS);
}

static void short_rpdo_plain_entries(void **state)
{
    /* AnaGate option: a short frame writes only the entries it covers */
    static const uint32_t map[] = {0x20090020UL, 0x20080010UL};
    (void)state;
    pfx_start(&fx, 1, &(co_settings_t){.pdo.short_rpdo = CO_RPDO_SHORT_ACCEPT});
    map_pdo1(false, map, 2);
    tb_send(BUS, "000 01 01");
    tb_flush(BUS);
    tb_send(BUS, "201 01 02 03 04 05");
    assert_int_equal(pfx_get(&fx, 0x2009, 0), 0x04030201UL);
    assert_int_equal(pfx_get(&fx, 0x2008, 0) & 0xFFFF, 0);
    tb_send(BUS, "201 11 12 13");
    assert_int_equal(pfx_get(&fx, 0x2009, 0), 0x04030201UL);
    tb_send(BUS, "201 21 22 23 24 25 26");
    assert_int_equal(pfx_get(&fx, 0x2009, 0), 0x24232221UL);
    assert_int_equal(pfx_get(&fx, 0x2008, 0) & 0xFFFF, 0x2625);
    tb_expect_none(BUS);
}

/* Entries mapped in part (the low bytes of a longer value) are resolved
 * too: an RPDO extends them to the value's size by the sign (INTEGER32) or
 * with zeros (UNSIGNED32), a TPDO sends the low bytes; an INTEGER24 is
 * copied whole. Both directions also on a big-endian CPU (test-matrix). */
static void partial_entries(void **state)
{
    static const uint32_t map[] = {0x20040010UL, 0x20090008UL, 0x20030018UL};
    (void)state;
    pfx_start(&fx, 1, 0U);
    map_pdo1(false, map, 3);
    map_pdo1(true, map, 3);
    pfx_set(&fx, 0x2004, 0, 0x87654321UL, 4);
    pfx_set(&fx, 0x2009, 0, 0xAABBCCDDUL, 4);
    pfx_set(&fx, 0x2003, 0, 0x112233UL, 3);
    tb_send(BUS, "000 01 01");
    tb_expect(BUS, "181 21 43 DD 33 22 11");
    tb_send(BUS, "201 FE FF 80 01 02 83");
    assert_int_equal(pfx_get(&fx, 0x2004, 0), 0xFFFFFFFEUL);
    assert_int_equal(pfx_get(&fx, 0x2009, 0), 0x80UL);
    assert_int_equal(pfx_get(&fx, 0x2003, 0) & 0xFFFFFFUL, 0x830201UL);
    tb_advance(BUS, 0);
    tb_expect(BUS, "181 FE FF 80 01 02 83");
    tb_send(BUS, "201 34 12 7F 00 00 00");
    assert_int_equal(pfx_get(&fx, 0x2004, 0), 0x1234UL);
    assert_int_equal(pfx_get(&fx, 0x2009, 0), 0x7FUL);
    tb_advance(BUS, 0);
    tb_expect(BUS, "181 34 12 7F 00 00 00");
    tb_expect_none(BUS);
}

/* Values in the last 8 bytes of the RAM image (the cia401 inputs 0x6000):
 * a TPDO reads the bytes that end with them, next to an entry read from the
 * middle of the image (the analogue input 0x6401:01). */
static void tpdo_values_at_the_end_of_the_ram_image(void **state)
{
    static cia401_node_t n;
    static tb_bus_t bus;
    co_node_config_t cfg;
    co_node_t *node = &n.node;
    uint8_t *in1;
    uint8_t *in2;
    uint8_t *ain1;
    (void)state;
    tb_init(&bus);
    cia401_config(&n, &cfg);
    cfg.hal = tb_hal(&bus, 0);
    cfg.node_id = 1U;
    assert_int_equal(co_node_init(node, &cfg, 0U), CO_RESULT_OK);
    tb_attach(&bus, 0, node);
    tb_flush(&bus);
    in1 = (uint8_t *)co_od_value_ptr(node, 0x6000U, 1U);
    in2 = (uint8_t *)co_od_value_ptr(node, 0x6000U, 2U);
    ain1 = (uint8_t *)co_od_value_ptr(node, 0x6401U, 1U);
    assert_non_null(in1);
    assert_non_null(in2);
    assert_non_null(ain1);
    /* the layout the test is about */
    assert_true((size_t)(in1 - node->ram) + 8U > node->dev->ram_size);
    assert_true((size_t)(in2 - node->ram) + 8U > node->dev->ram_size);
    assert_true((size_t)(ain1 - node->ram) + 8U <= node->dev->ram_size);
    *in1 = 0x12U;
    *in2 = 0x34U;
    /* TPDO1: 0x6000:01, 0x6000:02 (the default) */
    tb_send(&bus, "000 01 01");
    tb_expect(&bus, "181 12 34");
    tb_expect(&bus, "281 00 00 00 00 00 00 00 00"); /* TPDO2: the analogue inputs */
    tb_expect_none(&bus);
    *in2 = 0x35U;
    tb_advance(&bus, 0);
    tb_expect(&bus, "181 12 35");
    tb_expect_none(&bus);
    /* 0x6000:02, 0x6401:01, 0x6000:01 */
    tb_send(&bus, "000 80 01");
    tb_xfer(&bus, "601 23 00 18 01 81 01 00 80", "581 60 00 18 01 00 00 00 00");
    tb_xfer(&bus, "601 2F 00 1A 00 00 00 00 00", "581 60 00 1A 00 00 00 00 00");
    tb_xfer(&bus, "601 23 00 1A 01 08 02 00 60", "581 60 00 1A 01 00 00 00 00");
    tb_xfer(&bus, "601 23 00 1A 02 10 01 01 64", "581 60 00 1A 02 00 00 00 00");
    tb_xfer(&bus, "601 23 00 1A 03 08 01 00 60", "581 60 00 1A 03 00 00 00 00");
    tb_xfer(&bus, "601 2F 00 1A 00 03 00 00 00", "581 60 00 1A 00 00 00 00 00");
    tb_xfer(&bus, "601 23 00 18 01 81 01 00 00", "581 60 00 18 01 00 00 00 00");
    (void)memcpy(ain1, &(const uint16_t){0x5678U}, 2U); /* in the CPU's order */
    tb_send(&bus, "000 01 01");
    tb_expect(&bus, "181 35 78 56 12");
    tb_expect(&bus, "281 78 56 00 00 00 00 00 00");
    tb_expect_none(&bus);
    *in1 = 0xA1U;
    tb_advance(&bus, 0);
    tb_expect(&bus, "181 35 78 56 A1");
    tb_expect_none(&bus);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(tpdo_values_at_the_end_of_the_ram_image),
        cmocka_unit_test(mixed_tpdo),
        cmocka_unit_test(mixed_rpdo),
        cmocka_unit_test(rpdo_more_entries_than_resolved),
        cmocka_unit_test(tpdo_more_entries_than_resolved),
        cmocka_unit_test(remap_plain_and_hooked),
        cmocka_unit_test(reset_restores_plain_mapping),
        cmocka_unit_test(short_rpdo_plain_entries),
        cmocka_unit_test(partial_entries),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
