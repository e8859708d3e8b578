/* ISR-to-loop receive queue: order, full, empty, wrap-around, bad sizes. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "co/co_rxq.h"
#include "test_frames.h"

static void fifo_order_full_and_wrap(void **state)
{
    co_rxq_frame_t store[4];
    co_rxq_t q;
    co_frame_t f;
    (void)state;
    assert_true(co_rxq_init(&q, store, 4));
    assert_false(co_rxq_pop(&q, &f));
    for (uint32_t round = 0; round < 5; round++) {
        for (uint32_t i = 0; i < 3; i++) {
            co_frame_set(&f, 0x100U + round * 8U + i, (const uint8_t[]){(uint8_t)i}, 1);
            assert_true(co_rxq_push(&q, &f));
        }
        co_frame_set(&f, 0x7FF, NULL, 0);
        assert_false(co_rxq_push(&q, &f)); /* one slot stays free */
        for (uint32_t i = 0; i < 3; i++) {
            assert_true(co_rxq_pop(&q, &f));
            assert_int_equal(f.id, 0x100U + round * 8U + i);
            assert_int_equal(f.data[0], i);
        }
        assert_false(co_rxq_pop(&q, &f));
    }
    assert_int_equal(q.dropped, 5);
}

/* CO_RXQ_INIT: the same queue as co_rxq_init, made by a static initialiser. */
static void static_initialiser_is_the_init(void **state)
{
    static co_rxq_frame_t store[4];
    static co_rxq_t q = CO_RXQ_INIT(store, 4U);
    co_rxq_t r;
    co_frame_t f;
    (void)state;
    assert_true(co_rxq_init(&r, store, 4));
    assert_memory_equal(&q, &r, sizeof q);
    assert_false(co_rxq_pop(&q, &f));
    for (uint32_t i = 0; i < 3; i++) {
        co_frame_set(&f, 0x181U + i, NULL, 0);
        assert_true(co_rxq_push(&q, &f));
    }
    assert_false(co_rxq_push(&q, &f));
    assert_true(co_rxq_pop(&q, &f));
    assert_int_equal(f.id, 0x181U);
}

/* A frame comes out as it went in (identifier, RTR flag, length, the data
 * bytes it has), kept in 10 bytes; a 29-bit frame is not kept (the node
 * ignores them) and not counted as dropped. */
static void compact_frames_round_trip(void **state)
{
    co_rxq_frame_t store[4];
    co_rxq_t q;
    co_frame_t f;
    co_frame_t g;
    (void)state;
    assert_int_equal(sizeof store[0], 10);
    assert_true(co_rxq_init(&q, store, 4));
    f = tf_parse("7FF 01 02 03 04 05 06 07 08");
    assert_true(co_rxq_push(&q, &f));
    f = tf_parse("705 R");
    assert_true(co_rxq_push(&q, &f));
    f.id = 0x1ABCDEFUL | CO_FRAME_EFF;
    assert_true(co_rxq_push(&q, &f));
    assert_true(co_rxq_pop(&q, &g));
    TF_ASSERT_FRAME(&g, "7FF 01 02 03 04 05 06 07 08");
    assert_true(co_rxq_pop(&q, &g));
    assert_int_equal(g.id, 0x705U | CO_FRAME_RTR);
    assert_int_equal(g.dlc, 0U);
    assert_false(co_rxq_pop(&q, &g));
    assert_int_equal(q.dropped, 0);
}

static void rejects_bad_sizes(void **state)
{
    co_rxq_frame_t store[6];
    co_rxq_t q;
    (void)state;
    assert_false(co_rxq_init(&q, store, 6));
    assert_false(co_rxq_init(&q, store, 1));
    assert_false(co_rxq_init(&q, NULL, 4));
    assert_true(co_rxq_init(&q, store, 2));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(fifo_order_full_and_wrap),
        cmocka_unit_test(static_initialiser_is_the_init),
        cmocka_unit_test(compact_frames_round_trip),
        cmocka_unit_test(rejects_bad_sizes),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
