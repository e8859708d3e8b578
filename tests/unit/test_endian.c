/* Little-endian packing: exact byte images, sign handling, unaligned access. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "co/co_endian.h"

static void get_reads_lsb_first(void **state)
{
    static const uint8_t b[9] = {0xAA, 0x92, 0x01, 0x02, 0x00, 0x73, 0x61, 0x76, 0x65};
    (void)state;
    assert_int_equal(co_get_u16(&b[1]), 0x0192);
    assert_int_equal(co_get_u24(&b[1]), 0x020192);
    assert_int_equal(co_get_u32(&b[1]), 0x00020192UL);
    /* "save" signature as it arrives in an SDO download */
    assert_int_equal(co_get_u32(&b[5]), 0x65766173UL);
    assert_true(co_get_u64(&b[1]) == 0x6576617300020192ULL);
}

static void put_writes_lsb_first(void **state)
{
    uint8_t b[10];
    static const uint8_t want16[] = {0x0A, 0x01};
    static const uint8_t want24[] = {0x56, 0x34, 0x12};
    static const uint8_t want32[] = {0x00, 0x00, 0x01, 0x06};
    static const uint8_t want64[] = {0x08, 0x07, 0x06, 0x05, 0x04, 0x03, 0x02, 0x01};
    (void)state;

    memset(b, 0xEE, sizeof b);
    co_put_u16(&b[1], 0x010A); /* 266 from the Kollmorgen digest, 2.2 */
    assert_memory_equal(&b[1], want16, 2);
    assert_int_equal(b[0], 0xEE);
    assert_int_equal(b[3], 0xEE);

    co_put_u24(&b[1], 0x123456UL);
    assert_memory_equal(&b[1], want24, 3);
    assert_int_equal(b[4], 0xEE);

    co_put_u32(&b[1], 0x06010000UL); /* abort code as on the wire */
    assert_memory_equal(&b[1], want32, 4);

    co_put_u64(&b[1], 0x0102030405060708ULL);
    assert_memory_equal(&b[1], want64, 8);
    assert_int_equal(b[9], 0xEE);
}

static void signed_values_round_trip(void **state)
{
    uint8_t b[8];
    (void)state;
    /* INTEGER16 -266 is F6 FE on the wire (Kollmorgen digest 2.2) */
    co_put_u16(b, (uint16_t)(int16_t)-266);
    assert_int_equal(b[0], 0xF6);
    assert_int_equal(b[1], 0xFE);
    assert_int_equal((int16_t)co_get_u16(b), -266);

    co_put_u32(b, (uint32_t)(int32_t)-100000);
    assert_int_equal((int32_t)co_get_u32(b), -100000);

    co_put_u64(b, (uint64_t)(int64_t)-5);
    assert_true((int64_t)co_get_u64(b) == -5);
    assert_int_equal(b[7], 0xFF);
}

static void round_trip_all_widths(void **state)
{
    uint8_t b[8];
    (void)state;
    for (uint32_t v = 0; v < 0x10000U; v += 0x0101U) {
        co_put_u16(b, (uint16_t)v);
        assert_int_equal(co_get_u16(b), v);
        co_put_u32(b, v * 0x10001U);
        assert_int_equal(co_get_u32(b), v * 0x10001U);
        co_put_u24(b, (v << 8U) | 0x5AU);
        assert_int_equal(co_get_u24(b), ((v << 8U) | 0x5AU) & 0xFFFFFFU);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(get_reads_lsb_first),
        cmocka_unit_test(put_writes_lsb_first),
        cmocka_unit_test(signed_values_round_trip),
        cmocka_unit_test(round_trip_all_widths),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
