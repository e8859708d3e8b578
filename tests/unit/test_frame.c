/* The frame type and the test notation used by every other test. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "co/co_frame.h"
#include "test_frames.h"

static void set_copies_and_zero_fills(void **state)
{
    static const uint8_t d[3] = {1, 2, 3};
    co_frame_t f;
    (void)state;
    memset(&f, 0xEE, sizeof f);
    co_frame_set(&f, 0x181, d, 3);
    assert_int_equal(f.id, 0x181);
    assert_int_equal(f.dlc, 3);
    assert_memory_equal(f.data, d, 3);
    for (int i = 3; i < 8; i++) {
        assert_int_equal(f.data[i], 0);
    }
    {
        static const uint8_t big[12] = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12};
        co_frame_set(&f, 0x181, big, 12); /* clamped to 8 */
        assert_int_equal(f.dlc, 8);
        assert_int_equal(f.data[7], 8);
    }
}

static void equal_ignores_bytes_beyond_dlc(void **state)
{
    co_frame_t a;
    co_frame_t b;
    (void)state;
    co_frame_set(&a, 0x701, (const uint8_t[]){0x7F}, 1);
    b = a;
    b.data[5] = 0x55;
    assert_true(co_frame_equal(&a, &b));
    b.data[0] = 0xFF;
    assert_false(co_frame_equal(&a, &b));
    b = a;
    b.dlc = 2;
    assert_false(co_frame_equal(&a, &b));
    b = a;
    b.id |= CO_FRAME_RTR;
    assert_false(co_frame_equal(&a, &b));
}

static void parse_and_format_sdo_notation(void **state)
{
    char txt[64];
    co_frame_t f = tf_parse("581 43 00 10 00 92 01 02 00");
    (void)state;
    assert_int_equal(co_frame_cob(&f), 0x581);
    assert_false(co_frame_is_rtr(&f));
    assert_int_equal(f.dlc, 8);
    assert_int_equal(f.data[4], 0x92);
    tf_format(&f, txt, sizeof txt);
    assert_string_equal(txt, "581 43 00 10 00 92 01 02 00");

    f = tf_parse("080");
    assert_int_equal(f.dlc, 0);
    tf_format(&f, txt, sizeof txt);
    assert_string_equal(txt, "080");
}

static void parse_rtr(void **state)
{
    co_frame_t f = tf_parse("701 R1");
    (void)state;
    assert_true(co_frame_is_rtr(&f));
    assert_int_equal(co_frame_cob(&f), 0x701);
    assert_int_equal(f.dlc, 1);
    TF_ASSERT_FRAME(&f, "701 R1");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(set_copies_and_zero_fills),
        cmocka_unit_test(equal_ignores_bytes_beyond_dlc),
        cmocka_unit_test(parse_and_format_sdo_notation),
        cmocka_unit_test(parse_rtr),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
