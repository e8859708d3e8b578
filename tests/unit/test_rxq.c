/* ISR-to-loop receive queue: order, full, empty, wrap-around, any length,
 * bad sizes. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "co/co_rxq.h"
#include "test_frames.h"

/* A queue of @p len slots holds @p len frames, in order, over several laps
 * of its indices (each round starts one slot further on). */
static void fill_and_drain(uint16_t len)
{
    co_rxq_frame_t store[5];
    co_rxq_t q;
    co_frame_t f;
    uint32_t id = 0x100U;
    uint32_t out = 0x100U;
    assert_true(len <= 5U);
    assert_true(co_rxq_init(&q, store, len));
    assert_false(co_rxq_pop(&q, &f));
    for (uint32_t round = 0; round < 2U * len + 1U; round++) {
        for (uint32_t i = 0; i < len; i++) {
            co_frame_set(&f, id, (const uint8_t[]){(uint8_t)id}, 1);
            assert_true(co_rxq_push(&q, &f));
            id++;
        }
        co_frame_set(&f, 0x7FF, NULL, 0);
        assert_false(co_rxq_push(&q, &f)); /* full: no slot is left free */
        for (uint32_t i = 0; i < len; i++) {
            assert_true(co_rxq_pop(&q, &f));
            assert_int_equal(f.id, out);
            assert_int_equal(f.data[0], (uint8_t)out);
            out++;
        }
        assert_false(co_rxq_pop(&q, &f));
        /* the next round one slot further on */
        co_frame_set(&f, id, NULL, 0);
        assert_true(co_rxq_push(&q, &f));
        id++;
        assert_true(co_rxq_pop(&q, &f));
        assert_int_equal(f.id, out);
        out++;
    }
    assert_int_equal(q.dropped, 2U * len + 1U);
}

static void fifo_order_full_and_wrap(void **state)
{
    (void)state;
    /* every slot used (the firmware's 3-slot queue holds 3 frames), any
     * length, a power of two or not */
    for (uint16_t len = 1U; len <= 5U; len++) {
        fill_and_drain(len);
    }
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
    for (uint32_t i = 0; i < 4; i++) {
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
    assert_false(co_rxq_init(&q, store, 0));
    assert_false(co_rxq_init(&q, store, 32768U));
    assert_false(co_rxq_init(&q, NULL, 4));
    assert_true(co_rxq_init(&q, store, 6));
    assert_true(co_rxq_init(&q, store, 1));
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
