/*
 * Error control (CiA 301 7.2.8.3.2): heartbeat producer 0x1017, heartbeat
 * consumer 0x1016, node guarding and life guarding 0x100C/0x100D, and the
 * EMCY 0x8130 the core raises for a lost producer or guarding master, and
 * the NMT reaction of 0x1029 error behaviour to them and to bus-off.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "test_bus.h"
#include "test_dev.h"

/* ------------------------------------------------------------ callbacks */

#define REC_MAX 32

typedef struct rec {
    int n;
    co_hb_event_t ev[REC_MAX];
    uint8_t id[REC_MAX];
    co_nmt_state_t st[REC_MAX];
} rec_t;

static void on_hb(void *ctx, co_node_t *node, co_hb_event_t ev, uint8_t id, co_nmt_state_t st)
{
    rec_t *r = (rec_t *)ctx;
    (void)node;
    assert_true(r->n < REC_MAX);
    r->ev[r->n] = ev;
    r->id[r->n] = id;
    r->st[r->n] = st;
    r->n++;
}

static void start_cb(td_node_t *n, rec_t *r, tb_bus_t *bus, uint8_t idx, uint8_t id,
                     const co_dev_t *dev)
{
    co_node_callbacks_t cb;

    memset(r, 0, sizeof *r);
    memset(&cb, 0, sizeof cb);
    cb.ctx = r;
    cb.hb_event = on_hb;
    td_start_cb(n, bus, idx, id, dev, &cb);
}

/* -------------------------------------------------------------- fixture */

typedef struct fx {
    tb_bus_t bus;
    td_node_t n;
    rec_t r;
    co_dev_t dev;
} fx_t;

static int setup(void **state)
{
    static fx_t fx;
    memset(&fx, 0, sizeof fx);
    tb_init(&fx.bus);
    fx.dev = td_dev;
    start_cb(&fx.n, &fx.r, &fx.bus, 0, 1, NULL);
    tb_flush(&fx.bus);
    *state = &fx;
    return 0;
}

#define FX ((fx_t *)*state)
#define BUS (&FX->bus)
#define NODE (&FX->n.node)
#define RAMV (FX->n.ram)
#define REC (FX->r)

static void expect_event(const rec_t *r, int i, co_hb_event_t ev, uint8_t id, co_nmt_state_t st)
{
    assert_true(i < r->n);
    assert_int_equal(r->ev[i], ev);
    assert_int_equal(r->id[i], id);
    assert_int_equal(r->st[i], st);
}

/* -------------------------------------------------- heartbeat producer */

static void heartbeat_producer_period(void **state)
{
    tb_xfer(BUS, "601 2B 17 10 00 64 00 00 00", "581 60 17 10 00 00 00 00 00");
    tb_xfer(BUS, "601 40 17 10 00 00 00 00 00", "581 4B 17 10 00 64 00 00 00");
    /* exactly every 100000 us, counted from the write */
    for (int i = 0; i < 10; i++) {
        tb_advance(BUS, 99999U);
        tb_expect_none(BUS);
        tb_advance(BUS, 1U);
        tb_expect(BUS, "701 7F");
        tb_expect_none(BUS);
    }
    /* one long advance: still one heartbeat per period, none skipped */
    tb_advance(BUS, 1000000U);
    for (int i = 0; i < 10; i++) {
        tb_expect(BUS, "701 7F");
    }
    tb_expect_none(BUS);
}

static void heartbeat_state_follows_nmt(void **state)
{
    tb_xfer(BUS, "601 2B 17 10 00 64 00 00 00", "581 60 17 10 00 00 00 00 00");
    tb_advance(BUS, 100000U);
    tb_expect(BUS, "701 7F");
    tb_send(BUS, "000 01 01");
    tb_advance(BUS, 100000U);
    tb_expect(BUS, "701 05");
    tb_send(BUS, "000 02 01");
    tb_advance(BUS, 100000U);
    tb_expect(BUS, "701 04");
    tb_send(BUS, "000 80 01");
    tb_advance(BUS, 100000U);
    tb_expect(BUS, "701 7F");
    tb_expect_none(BUS);
}

static void heartbeat_producer_zero_stops(void **state)
{
    tb_xfer(BUS, "601 2B 17 10 00 64 00 00 00", "581 60 17 10 00 00 00 00 00");
    tb_advance(BUS, 250000U);
    tb_expect(BUS, "701 7F");
    tb_expect(BUS, "701 7F");
    tb_expect_none(BUS);
    tb_xfer(BUS, "601 2B 17 10 00 00 00 00 00", "581 60 17 10 00 00 00 00 00");
    tb_advance(BUS, 5000000U);
    tb_expect_none(BUS);
    /* a new period starts from its write */
    tb_xfer(BUS, "601 2B 17 10 00 C8 00 00 00", "581 60 17 10 00 00 00 00 00");
    tb_advance(BUS, 199999U);
    tb_expect_none(BUS);
    tb_advance(BUS, 1U);
    tb_expect(BUS, "701 7F");
    tb_expect_none(BUS);
}

/* CiA 301: 0x1017 is the producer's cycle time. Written again while the
 * producer runs, the cycle goes on (a master writing it every millisecond
 * must not silence the node, issue 15): the next heartbeat is due one (new)
 * period after the last one, at once if that has passed. A change of the
 * NMT state sends no heartbeat of its own (CiA 301 defines the heartbeat as
 * cyclic; only the boot-up marks a transition): the next one carries the
 * new state. */
static void heartbeat_rewrite_keeps_cycle(void **state)
{
    tb_xfer(BUS, "601 2B 17 10 00 64 00 00 00", "581 60 17 10 00 00 00 00 00");
    /* the same 100 ms written every millisecond for 250 ms */
    for (int i = 1; i <= 250; i++) {
        tb_advance(BUS, 1000U);
        if ((i % 100) == 0) {
            tb_expect(BUS, "701 7F");
        }
        tb_xfer(BUS, "601 2B 17 10 00 64 00 00 00", "581 60 17 10 00 00 00 00 00");
    }
    /* 50 ms after the last heartbeat: 200 ms, due 200 ms after that one */
    tb_xfer(BUS, "601 2B 17 10 00 C8 00 00 00", "581 60 17 10 00 00 00 00 00");
    tb_advance(BUS, 149999U);
    tb_expect_none(BUS);
    tb_advance(BUS, 1U);
    tb_expect(BUS, "701 7F");
    tb_expect_none(BUS);
    /* 50 ms after it: 10 ms, already past: at once, then every 10 ms */
    tb_advance(BUS, 50000U);
    tb_xfer(BUS, "601 2B 17 10 00 0A 00 00 00", "581 60 17 10 00 00 00 00 00");
    tb_advance(BUS, 0U);
    tb_expect(BUS, "701 7F");
    tb_expect_none(BUS);
    /* a state change: no heartbeat of its own, the next one has the state */
    tb_advance(BUS, 4000U);
    tb_send(BUS, "000 01 01");
    tb_advance(BUS, 0U);
    tb_expect_none(BUS);
    tb_advance(BUS, 5999U);
    tb_expect_none(BUS);
    tb_advance(BUS, 1U);
    tb_expect(BUS, "701 05");
    tb_advance(BUS, 10000U);
    tb_expect(BUS, "701 05");
    tb_expect_none(BUS);
}

/* Fault injection: muted, the node sends no heartbeat but still answers
 * SDO (0x1017 unchanged) and sends its boot-up after a reset; resumed, the
 * first heartbeat goes out at once, then one per period again. */
static void heartbeat_muted_and_resumed(void **state)
{
    tb_xfer(BUS, "601 2B 17 10 00 64 00 00 00", "581 60 17 10 00 00 00 00 00");
    tb_advance(BUS, 100000U);
    tb_expect(BUS, "701 7F");
    co_node_hb_mute(NODE, true, BUS->now);
    tb_advance(BUS, 1000000U);
    tb_expect_none(BUS);
    tb_xfer(BUS, "601 40 17 10 00 00 00 00 00", "581 4B 17 10 00 64 00 00 00");
    tb_send(BUS, "000 82 01");
    tb_expect(BUS, "701 00");
    tb_xfer(BUS, "601 2B 17 10 00 64 00 00 00", "581 60 17 10 00 00 00 00 00");
    tb_advance(BUS, 500000U);
    tb_expect_none(BUS);
    tb_advance(BUS, 50000U);
    co_node_hb_mute(NODE, false, BUS->now);
    tb_advance(BUS, 0U);
    tb_expect(BUS, "701 7F");
    tb_advance(BUS, 99999U);
    tb_expect_none(BUS);
    tb_advance(BUS, 1U);
    tb_expect(BUS, "701 7F");
    /* muting twice and resuming twice change nothing more */
    co_node_hb_mute(NODE, false, BUS->now);
    tb_advance(BUS, 0U);
    tb_expect_none(BUS);
}

/* -------------------------------------------------- heartbeat consumer */

/* A consumer timeout is detected at its consumer time or up to 1023 us
 * later, never before (co_hb.c: its deadline in units of 1024 us). */
#define HBC_LATE 1023U

/* Silence from now: nothing until @p us, then (by the consumer's rounding
 * up, at most HBC_LATE later) EMCY 0x8130 and event @p k of the recorder,
 * producer @p id timed out in Operational. */
static void expect_lost_after(void **state, uint32_t us, int k, uint8_t id)
{
    tb_advance(BUS, us - 1U);
    tb_expect_none(BUS);
    tb_advance(BUS, 1U + HBC_LATE);
    tb_expect(BUS, "081 30 81 11 00 00 00 00 00");
    tb_expect_none(BUS);
    assert_int_equal(REC.n, k + 1);
    expect_event(&REC, k, CO_HB_TIMEOUT, id, CO_NMT_OPERATIONAL);
}

static void heartbeat_consumer_timeout_and_recovery(void **state)
{
    /* sub1: producer 5, 200 ms */
    tb_xfer(BUS, "601 23 16 10 01 C8 00 05 00", "581 60 16 10 01 00 00 00 00");
    tb_xfer(BUS, "601 40 16 10 01 00 00 00 00", "581 43 16 10 01 C8 00 05 00");
    tb_xfer(BUS, "601 40 16 10 00 00 00 00 00", "581 4F 16 10 00 04 00 00 00");
    /* monitoring starts with the first heartbeat only */
    tb_advance(BUS, 2000000U);
    tb_expect_none(BUS);
    assert_int_equal(REC.n, 0);

    tb_send(BUS, "705 05");
    assert_int_equal(REC.n, 1);
    expect_event(&REC, 0, CO_HB_STARTED, 5, CO_NMT_OPERATIONAL);
    /* regular heartbeats keep it alive */
    for (int i = 0; i < 10; i++) {
        tb_advance(BUS, 150000U);
        tb_send(BUS, "705 05");
    }
    tb_expect_none(BUS);
    assert_int_equal(REC.n, 1);
    /* silence: timeout exactly 200 ms after the last heartbeat */
    expect_lost_after(state, 200000U, 1, 5U);
    tb_xfer(BUS, "601 40 01 10 00 00 00 00 00", "581 4F 01 10 00 11 00 00 00");
    tb_xfer(BUS, "601 40 03 10 01 00 00 00 00", "581 43 03 10 01 30 81 00 00");
    /* no repetition while it stays lost */
    tb_advance(BUS, 2000000U);
    tb_expect_none(BUS);
    assert_int_equal(REC.n, 2);

    /* heartbeats resume */
    tb_send(BUS, "705 05");
    tb_expect(BUS, "081 00 00 00 00 00 00 00 00");
    tb_expect_none(BUS);
    assert_int_equal(REC.n, 3);
    expect_event(&REC, 2, CO_HB_RECOVERED, 5, CO_NMT_OPERATIONAL);
    tb_xfer(BUS, "601 40 01 10 00 00 00 00 00", "581 4F 01 10 00 00 00 00 00");
    /* and are monitored again */
    tb_advance(BUS, 200000U + HBC_LATE);
    tb_expect(BUS, "081 30 81 11 00 00 00 00 00");
    tb_expect_none(BUS);
}

static void heartbeat_consumer_state_changes(void **state)
{
    tb_xfer(BUS, "601 23 16 10 02 F4 01 09 00", "581 60 16 10 02 00 00 00 00");
    tb_send(BUS, "709 00"); /* boot-up counts as the first heartbeat */
    expect_event(&REC, 0, CO_HB_STARTED, 9, CO_NMT_INITIALISING);
    tb_send(BUS, "709 7F");
    expect_event(&REC, 1, CO_HB_STATE, 9, CO_NMT_PRE_OPERATIONAL);
    tb_send(BUS, "709 7F");
    tb_send(BUS, "709 05");
    expect_event(&REC, 2, CO_HB_STATE, 9, CO_NMT_OPERATIONAL);
    assert_int_equal(REC.n, 3);
    /* remote requests, other producers and empty frames are not heartbeats */
    tb_send(BUS, "709 R1");
    tb_send(BUS, "709");
    tb_send(BUS, "708 04");
    expect_lost_after(state, 500000U, 3, 9U);
}

static void heartbeat_consumer_two_producers_one_error(void **state)
{
    tb_xfer(BUS, "601 23 16 10 01 64 00 05 00", "581 60 16 10 01 00 00 00 00");
    tb_xfer(BUS, "601 23 16 10 03 C8 00 06 00", "581 60 16 10 03 00 00 00 00");
    tb_send(BUS, "705 05");
    tb_send(BUS, "706 05");
    /* 5 times out first: one EMCY */
    tb_advance(BUS, 100000U + HBC_LATE);
    tb_expect(BUS, "081 30 81 11 00 00 00 00 00");
    tb_expect_none(BUS);
    /* 6 times out too: the error is already active */
    tb_advance(BUS, 100000U);
    tb_expect_none(BUS);
    expect_event(&REC, 3, CO_HB_TIMEOUT, 6, CO_NMT_OPERATIONAL);
    /* 5 comes back, 6 is still lost: no EMCY 0000 yet */
    tb_send(BUS, "705 05");
    tb_expect_none(BUS);
    expect_event(&REC, 4, CO_HB_RECOVERED, 5, CO_NMT_OPERATIONAL);
    /* 6 comes back: error gone */
    tb_send(BUS, "706 7F");
    tb_expect(BUS, "081 00 00 00 00 00 00 00 00");
    tb_expect_none(BUS);
    expect_event(&REC, 5, CO_HB_RECOVERED, 6, CO_NMT_PRE_OPERATIONAL);
    expect_event(&REC, 6, CO_HB_STATE, 6, CO_NMT_PRE_OPERATIONAL);
    assert_int_equal(REC.n, 7);
}

static void heartbeat_consumer_entry_checks(void **state)
{
    tb_xfer(BUS, "601 23 16 10 01 C8 00 05 00", "581 60 16 10 01 00 00 00 00");
    /* CiA 301: the same producer in a second entry */
    tb_xfer(BUS, "601 23 16 10 02 2C 01 05 00", "581 80 16 10 02 43 00 04 06");
    tb_xfer(BUS, "601 40 16 10 02 00 00 00 00", "581 43 16 10 02 00 00 00 00");
    /* ... is fine with time 0 (entry not used) */
    tb_xfer(BUS, "601 23 16 10 02 00 00 05 00", "581 60 16 10 02 00 00 00 00");
    /* rewriting the producer's own entry is fine */
    tb_xfer(BUS, "601 23 16 10 01 2C 01 05 00", "581 60 16 10 01 00 00 00 00");
    /* another producer is fine */
    tb_xfer(BUS, "601 23 16 10 04 2C 01 06 00", "581 60 16 10 04 00 00 00 00");
    /* node-ID 128 and the reserved bits 24..31 */
    tb_xfer(BUS, "601 23 16 10 03 2C 01 80 00", "581 80 16 10 03 30 00 09 06");
    tb_xfer(BUS, "601 23 16 10 03 2C 01 07 01", "581 80 16 10 03 30 00 09 06");
    /* nor may entry 1 move to the producer entry 4 monitors */
    tb_xfer(BUS, "601 23 16 10 01 2C 01 06 00", "581 80 16 10 01 43 00 04 06");
    tb_xfer(BUS, "601 40 16 10 01 00 00 00 00", "581 43 16 10 01 2C 01 05 00");
    /* no fifth entry */
    tb_xfer(BUS, "601 23 16 10 05 2C 01 08 00", "581 80 16 10 05 11 00 09 06");
    /* sub0 is const */
    tb_xfer(BUS, "601 2F 16 10 00 01 00 00 00", "581 80 16 10 00 02 00 01 06");
}

static void heartbeat_consumer_disabled_entry_clears_error(void **state)
{
    tb_xfer(BUS, "601 23 16 10 01 64 00 05 00", "581 60 16 10 01 00 00 00 00");
    tb_send(BUS, "705 05");
    tb_advance(BUS, 100000U + HBC_LATE);
    tb_expect(BUS, "081 30 81 11 00 00 00 00 00");
    tb_expect_none(BUS);
    /* the master stops monitoring 5: nothing is lost any more */
    tb_send(BUS, "601 23 16 10 01 00 00 00 00");
    tb_expect(BUS, "081 00 00 00 00 00 00 00 00");
    tb_expect(BUS, "581 60 16 10 01 00 00 00 00");
    tb_expect_none(BUS);
    tb_send(BUS, "705 05");
    tb_advance(BUS, 1000000U);
    tb_expect_none(BUS);
    assert_false(co_emcy_is_active(NODE, CO_EMCY_HB_GUARD));
}

static void heartbeat_consumer_write_restarts_that_entry_only(void **state)
{
    tb_xfer(BUS, "601 23 16 10 01 64 00 05 00", "581 60 16 10 01 00 00 00 00");
    tb_xfer(BUS, "601 23 16 10 02 C8 00 06 00", "581 60 16 10 02 00 00 00 00");
    tb_send(BUS, "705 05");
    tb_send(BUS, "706 05");
    tb_advance(BUS, 50000U);
    /* the master changes entry 2: entry 1 keeps its deadline */
    tb_xfer(BUS, "601 23 16 10 02 2C 01 06 00", "581 60 16 10 02 00 00 00 00");
    expect_lost_after(state, 50000U, 2, 5U);
    /* a write to entry 2 while 5 is lost does not end 5's error */
    tb_xfer(BUS, "601 23 16 10 02 90 01 06 00", "581 60 16 10 02 00 00 00 00");
    tb_advance(BUS, 1000000U);
    tb_expect_none(BUS);
    assert_true(co_emcy_is_active(NODE, CO_EMCY_HB_GUARD));
    assert_int_equal(REC.n, 3); /* entry 2 waits for 6's next heartbeat */
    /* rewriting entry 1 itself does: 5 is no longer monitored until it speaks */
    tb_send(BUS, "601 23 16 10 01 64 00 05 00");
    tb_expect(BUS, "081 00 00 00 00 00 00 00 00");
    tb_expect(BUS, "581 60 16 10 01 00 00 00 00");
    tb_expect_none(BUS);
    tb_advance(BUS, 1000000U);
    tb_expect_none(BUS);
    tb_send(BUS, "705 05");
    expect_event(&REC, 3, CO_HB_STARTED, 5, CO_NMT_OPERATIONAL);
}

static void timers_across_the_clock_wrap(void **state)
{
    /* bring the clock to 150 ms before it wraps around 2^32 us */
    tb_advance(BUS, 0x7FFFFFFFUL);
    tb_advance(BUS, (uint32_t)(0xFFFFFFFFUL - 149999UL - BUS->now));
    assert_int_equal(BUS->now, 0xFFFFFFFFUL - 149999UL);
    tb_xfer(BUS, "601 2B 17 10 00 64 00 00 00", "581 60 17 10 00 00 00 00 00");
    tb_xfer(BUS, "601 23 16 10 01 C8 00 05 00", "581 60 16 10 01 00 00 00 00");
    tb_send(BUS, "705 05");
    for (uint32_t i = 0; i < 4U; i++) {
        uint32_t late = (i == 2U) ? HBC_LATE : 0U;
        tb_advance(BUS, 99999U - late);
        tb_expect_none(BUS);
        tb_advance(BUS, 1U);
        tb_expect(BUS, "701 7F");
        if (i == 1U) {
            /* the consumer times out 200 ms after the heartbeat, past the
             * wrap (within 1023 us after) */
            tb_advance(BUS, HBC_LATE);
            tb_expect(BUS, "081 30 81 11 00 00 00 00 00");
            expect_event(&REC, 1, CO_HB_TIMEOUT, 5, CO_NMT_OPERATIONAL);
        }
    }
    tb_expect_none(BUS);
    assert_true(BUS->now < 1000000UL);
}

/* An entry that is not used (consumer time 0) names the producer a used
 * entry monitors: the heartbeats go to the used one, through its states
 * (waiting, active, lost, recovered). */
static void heartbeat_consumer_unused_entry_same_producer(void **state)
{
    tb_xfer(BUS, "601 23 16 10 01 00 00 05 00", "581 60 16 10 01 00 00 00 00");
    tb_xfer(BUS, "601 23 16 10 02 64 00 05 00", "581 60 16 10 02 00 00 00 00");
    tb_advance(BUS, 1000000U);
    assert_int_equal(REC.n, 0);
    tb_send(BUS, "705 05");
    assert_int_equal(REC.n, 1);
    expect_event(&REC, 0, CO_HB_STARTED, 5, CO_NMT_OPERATIONAL);
    expect_lost_after(state, 100000U, 1, 5U);
    tb_advance(BUS, 1000000U);
    assert_int_equal(REC.n, 2);
    tb_send(BUS, "705 7F");
    tb_expect(BUS, "081 00 00 00 00 00 00 00 00");
    tb_expect_none(BUS);
    assert_int_equal(REC.n, 4);
    expect_event(&REC, 2, CO_HB_RECOVERED, 5, CO_NMT_PRE_OPERATIONAL);
    expect_event(&REC, 3, CO_HB_STATE, 5, CO_NMT_PRE_OPERATIONAL);
}

/* At any phase of a heartbeat's time stamp (the deadlines count in units of
 * 1024 us from a time base the service moves), the timeout comes never
 * before the consumer time and at most 1023 us after it, exactly at the
 * deadline co_node_process returned; a call just before it finds nothing. */
static void heartbeat_consumer_timeout_within_a_ms(void **state)
{
    tb_xfer(BUS, "601 23 16 10 01 C8 00 05 00", "581 60 16 10 01 00 00 00 00");
    for (uint32_t i = 0U; i < 14U; i++) {
        uint32_t t;
        uint32_t d;

        tb_advance(BUS, 1000U + (97U * i)); /* (a phase of its own each time) */
        t = BUS->now;
        tb_send(BUS, "705 05");
        if (i > 0U) {
            tb_expect(BUS, "081 00 00 00 00 00 00 00 00"); /* recovered */
        }
        d = co_node_process(NODE, t + 199999U);
        tb_expect_none(BUS);
        assert_in_range(d - t, 200000U, 200000U + HBC_LATE);
        assert_int_equal(co_node_process(NODE, d - 1U), d);
        tb_expect_none(BUS);
        BUS->now = d;
        tb_advance(BUS, 0U);
        tb_expect(BUS, "081 30 81 11 00 00 00 00 00");
        tb_expect_none(BUS);
        assert_int_equal(REC.n, 1 + (2 * (int)i) + 1);
        expect_event(&REC, REC.n - 1, CO_HB_TIMEOUT, 5, CO_NMT_OPERATIONAL);
    }
}

/* A port that calls co_node_process late (70 s without a call, more than
 * the 2^16 units of 1024 us the deadlines count): the consumers whose time
 * has passed time out at that call (also one whose heartbeat came within
 * the 70 s but longer ago than its time), one whose heartbeat came since
 * (65,535 ms, the longest consumer time) does not, and comes due at its
 * own time; an entry still waiting for its first heartbeat reports
 * nothing. */
static void heartbeat_consumer_after_70_s_without_process(void **state)
{
    uint32_t t0;
    uint32_t d;

    tb_xfer(BUS, "601 23 16 10 01 E8 03 05 00", "581 60 16 10 01 00 00 00 00");
    tb_xfer(BUS, "601 23 16 10 02 FF FF 06 00", "581 60 16 10 02 00 00 00 00");
    tb_xfer(BUS, "601 23 16 10 03 FF FF 07 00", "581 60 16 10 03 00 00 00 00");
    tb_xfer(BUS, "601 23 16 10 04 64 00 08 00", "581 60 16 10 04 00 00 00 00");
    tb_advance(BUS, 333U);
    t0 = BUS->now;
    tb_send(BUS, "705 05");
    tb_send(BUS, "706 05");
    tb_send(BUS, "708 05");
    assert_int_equal(REC.n, 3);
    /* no call of co_node_process: 8 speaks again after 67.5 s, 6 after 69 s */
    BUS->now = t0 + 67500000U;
    tb_send(BUS, "708 7F");
    BUS->now = t0 + 69000000U;
    tb_send(BUS, "706 05");
    assert_int_equal(REC.n, 4); /* (8's new state) */
    expect_event(&REC, 3, CO_HB_STATE, 8, CO_NMT_PRE_OPERATIONAL);
    /* at 70 s: 5 (1 s after 0.3 ms) and 8 (100 ms after 67.5 s) time out */
    BUS->now = t0 + 70000000U;
    tb_advance(BUS, 0U);
    tb_expect(BUS, "081 30 81 11 00 00 00 00 00");
    tb_expect_none(BUS);
    assert_int_equal(REC.n, 6);
    expect_event(&REC, 4, CO_HB_TIMEOUT, 5, CO_NMT_OPERATIONAL);
    expect_event(&REC, 5, CO_HB_TIMEOUT, 8, CO_NMT_PRE_OPERATIONAL);
    /* 6: 65,535 ms after 69 s, within 1023 us */
    d = co_node_process(NODE, BUS->now);
    assert_in_range(d - (t0 + 69000000U), 65535000U, 65535000U + HBC_LATE);
    BUS->now = d - 1U;
    tb_advance(BUS, 0U);
    assert_int_equal(REC.n, 6);
    /* and again no call for 70 s: it times out at the late call */
    BUS->now = d + 70000000U;
    tb_advance(BUS, 0U);
    assert_int_equal(REC.n, 7);
    expect_event(&REC, 6, CO_HB_TIMEOUT, 6, CO_NMT_OPERATIONAL);
    tb_expect_none(BUS);
    assert_int_equal(co_node_process(NODE, BUS->now), CO_NO_DEADLINE);
}

/* The time base is only kept while a deadline is ahead: a first heartbeat
 * 71 minutes after the service last ran (2^32 - 2^25 us: as many as a time
 * stamp 33.5 s in the past would be) still gets its whole consumer time. */
static void heartbeat_consumer_first_after_71_min(void **state)
{
    tb_xfer(BUS, "601 23 16 10 01 C8 00 05 00", "581 60 16 10 01 00 00 00 00");
    tb_advance(BUS, 0U);
    for (int i = 0; i < 7; i++) {
        tb_advance(BUS, 600000000U); /* (no stall: 10 minutes at a time) */
    }
    tb_advance(BUS, (uint32_t)(0xFFFFFFFFUL - 0x1FFFFFFUL - 4200000000UL));
    tb_expect_none(BUS);
    tb_send(BUS, "705 05");
    expect_event(&REC, 0, CO_HB_STARTED, 5, CO_NMT_OPERATIONAL);
    expect_lost_after(state, 200000U, 1, 5U);
}

static void reset_communication_ends_monitoring(void **state)
{
    tb_xfer(BUS, "601 23 16 10 01 64 00 05 00", "581 60 16 10 01 00 00 00 00");
    tb_send(BUS, "705 05");
    tb_advance(BUS, 100000U + HBC_LATE);
    tb_expect(BUS, "081 30 81 11 00 00 00 00 00");
    tb_expect_none(BUS);
    /* reset communication: 0x1016 back to its default (unused). The boot-up
     * is the first frame; the error it no longer monitors is reset after it
     * (EMCY 0000 in Pre-operational). */
    tb_send(BUS, "000 82 01");
    tb_expect(BUS, "701 00");
    tb_expect(BUS, "081 00 00 00 00 00 00 00 00");
    tb_expect_none(BUS);
    assert_false(co_emcy_is_active(NODE, CO_EMCY_HB_GUARD));
    tb_send(BUS, "705 05");
    tb_advance(BUS, 1000000U);
    tb_expect_none(BUS);
}

/* -------------------------------------------------------- node guarding */

static void node_guarding_toggle(void **state)
{
    tb_xfer(BUS, "701 R1", "701 7F");
    tb_xfer(BUS, "701 R1", "701 FF");
    tb_xfer(BUS, "701 R1", "701 7F");
    tb_send(BUS, "000 01 01");
    tb_xfer(BUS, "701 R1", "701 85");
    tb_xfer(BUS, "701 R1", "701 05");
    tb_send(BUS, "000 02 01");
    tb_xfer(BUS, "701 R1", "701 84");
    tb_xfer(BUS, "701 R0", "701 04"); /* the RTR's DLC is not checked */
    tb_send(BUS, "000 01 01");
    tb_xfer(BUS, "701 R1", "701 85");
    /* a data frame on the node's own error-control COB-ID is not a request */
    tb_send(BUS, "701 05");
    tb_expect_none(BUS);
    /* another node's request */
    tb_send(BUS, "702 R1");
    tb_expect_none(BUS);
    /* reset communication resets the toggle bit */
    tb_send(BUS, "000 82 01");
    tb_expect(BUS, "701 00");
    tb_xfer(BUS, "701 R1", "701 7F");
    tb_xfer(BUS, "701 R1", "701 FF");
    /* reset node too */
    tb_send(BUS, "000 81 01");
    tb_expect(BUS, "701 00");
    tb_xfer(BUS, "701 R1", "701 7F");
}

static void node_guarding_not_answered_with_heartbeat(void **state)
{
    tb_xfer(BUS, "601 2B 17 10 00 E8 03 00 00", "581 60 17 10 00 00 00 00 00");
    tb_send(BUS, "701 R1");
    tb_expect_none(BUS);
    tb_xfer(BUS, "601 2B 17 10 00 00 00 00 00", "581 60 17 10 00 00 00 00 00");
    tb_xfer(BUS, "701 R1", "701 7F");
}

static void node_guarding_with_heartbeat_option(void **state)
{
    fx_t *fx = FX;
    fx->dev.set = (co_settings_t){.nmt.guarding_with_hb = 1U};
    start_cb(&fx->n, &fx->r, BUS, 0, 1, &fx->dev);
    tb_expect(BUS, "701 00");
    tb_xfer(BUS, "601 2B 17 10 00 64 00 00 00", "581 60 17 10 00 00 00 00 00");
    tb_xfer(BUS, "701 R1", "701 7F");
    tb_xfer(BUS, "701 R1", "701 FF");
    /* the heartbeat itself carries no toggle bit */
    tb_advance(BUS, 100000U);
    tb_expect(BUS, "701 7F");
    tb_expect_none(BUS);
}

/* -------------------------------------------------------- life guarding */

static void configure_life_guarding(void **state)
{
    /* guard time 100 ms, life time factor 3: life time 300 ms */
    tb_xfer(BUS, "601 2B 0C 10 00 64 00 00 00", "581 60 0C 10 00 00 00 00 00");
    tb_xfer(BUS, "601 2F 0D 10 00 03 00 00 00", "581 60 0D 10 00 00 00 00 00");
}

static void life_guarding(void **state)
{
    configure_life_guarding(state);
    /* no life guarding before the first guarding request */
    tb_advance(BUS, 3000000U);
    tb_expect_none(BUS);
    tb_xfer(BUS, "701 R1", "701 7F");
    /* requests within the life time keep it alive */
    for (int i = 0; i < 10; i++) {
        tb_advance(BUS, 299999U);
        tb_xfer(BUS, "701 R1", (i % 2 == 0) ? "701 FF" : "701 7F");
    }
    /* the last request was answered with 7F */
    tb_advance(BUS, 299999U);
    tb_expect_none(BUS);
    tb_advance(BUS, 1U);
    tb_expect(BUS, "081 30 81 11 00 00 00 00 00");
    tb_expect_none(BUS);
    assert_int_equal(REC.n, 1);
    expect_event(&REC, 0, CO_GUARD_LOST, 0, CO_NMT_PRE_OPERATIONAL);
    tb_advance(BUS, 3000000U);
    tb_expect_none(BUS);
    /* the next request: answer, then the error is reset */
    tb_send(BUS, "701 R1");
    tb_expect(BUS, "701 FF");
    tb_expect(BUS, "081 00 00 00 00 00 00 00 00");
    tb_expect_none(BUS);
    assert_int_equal(REC.n, 2);
    expect_event(&REC, 1, CO_GUARD_RECOVERED, 0, CO_NMT_PRE_OPERATIONAL);
    /* and it is guarded again */
    tb_advance(BUS, 300000U);
    tb_expect(BUS, "081 30 81 11 00 00 00 00 00");
    tb_expect_none(BUS);
}

static void life_guarding_reconfigured_while_lost(void **state)
{
    configure_life_guarding(state);
    tb_xfer(BUS, "701 R1", "701 7F");
    tb_advance(BUS, 300000U);
    tb_expect(BUS, "081 30 81 11 00 00 00 00 00");
    tb_expect_none(BUS);
    /* the master writes a new guard time and resumes guarding: the next
     * request still ends the error */
    tb_xfer(BUS, "601 2B 0C 10 00 32 00 00 00", "581 60 0C 10 00 00 00 00 00");
    tb_send(BUS, "701 R1");
    tb_expect(BUS, "701 FF");
    tb_expect(BUS, "081 00 00 00 00 00 00 00 00");
    tb_expect_none(BUS);
    /* new life time: 50 ms * 3 */
    tb_advance(BUS, 149999U);
    tb_expect_none(BUS);
    tb_advance(BUS, 1U);
    tb_expect(BUS, "081 30 81 11 00 00 00 00 00");
    tb_expect_none(BUS);
}

static void life_guarding_disabled_while_lost(void **state)
{
    configure_life_guarding(state);
    tb_xfer(BUS, "701 R1", "701 7F");
    tb_advance(BUS, 300000U);
    tb_expect(BUS, "081 30 81 11 00 00 00 00 00");
    tb_expect_none(BUS);
    /* life time factor 0: life guarding is off, so nothing is lost any more */
    tb_send(BUS, "601 2F 0D 10 00 00 00 00 00");
    tb_expect(BUS, "581 60 0D 10 00 00 00 00 00");
    tb_advance(BUS, 0U);
    tb_expect(BUS, "081 00 00 00 00 00 00 00 00");
    tb_expect_none(BUS);
    assert_false(co_emcy_is_active(NODE, CO_EMCY_HB_GUARD));
    expect_event(&REC, 1, CO_GUARD_RECOVERED, 0, CO_NMT_PRE_OPERATIONAL);
    tb_xfer(BUS, "701 R1", "701 FF");
    tb_advance(BUS, 3000000U);
    tb_expect_none(BUS);
}

static void life_guarding_stops_when_heartbeat_starts(void **state)
{
    configure_life_guarding(state);
    tb_xfer(BUS, "701 R1", "701 7F");
    /* the master switches to heartbeat: guarding requests are no longer
     * answered, so the node must not report their absence as an error */
    tb_xfer(BUS, "601 2B 17 10 00 E8 03 00 00", "581 60 17 10 00 00 00 00 00");
    tb_send(BUS, "701 R1");
    tb_expect_none(BUS);
    tb_advance(BUS, 900000U);
    tb_expect_none(BUS);
    tb_advance(BUS, 100000U);
    tb_expect(BUS, "701 7F");
    tb_expect_none(BUS);
    assert_false(co_emcy_is_active(NODE, CO_EMCY_HB_GUARD));
    assert_int_equal(REC.n, 0);
}

static void reset_communication_ends_life_guarding(void **state)
{
    configure_life_guarding(state);
    tb_xfer(BUS, "701 R1", "701 7F");
    tb_advance(BUS, 300000U);
    tb_expect(BUS, "081 30 81 11 00 00 00 00 00");
    tb_send(BUS, "000 82 01");
    tb_expect(BUS, "701 00");
    tb_expect(BUS, "081 00 00 00 00 00 00 00 00");
    tb_expect_none(BUS);
    /* 0x100C/0x100D back to 0: plain node guarding, no life time */
    tb_xfer(BUS, "701 R1", "701 7F");
    tb_advance(BUS, 3000000U);
    tb_expect_none(BUS);
}

static void heartbeat_and_guarding_errors_share_the_code(void **state)
{
    configure_life_guarding(state);
    tb_xfer(BUS, "601 23 16 10 01 F4 01 05 00", "581 60 16 10 01 00 00 00 00");
    tb_send(BUS, "705 05");
    tb_xfer(BUS, "701 R1", "701 7F");
    tb_advance(BUS, 300000U);
    tb_expect(BUS, "081 30 81 11 00 00 00 00 00");
    tb_expect_none(BUS);
    tb_advance(BUS, 200000U + HBC_LATE); /* heartbeat of 5 lost as well */
    tb_expect_none(BUS);
    /* guarding resumes: 5 is still lost */
    tb_xfer(BUS, "701 R1", "701 FF");
    tb_send(BUS, "705 05");
    tb_expect(BUS, "081 00 00 00 00 00 00 00 00");
    tb_expect_none(BUS);
}

/* ------------------------------------------------ 0x1029 error behaviour */

/* Heartbeat consumer of node 0x20, 100 ms; its first heartbeat at once. */
static void consume_node_20(void **state)
{
    tb_xfer(BUS, "601 23 16 10 01 64 00 20 00", "581 60 16 10 01 00 00 00 00");
    tb_send(BUS, "720 05");
    tb_expect_none(BUS);
}

/* The NMT state as a guarding reply shows it (toggle bit masked). */
static uint8_t guarded_state(void **state)
{
    const co_frame_t *f;

    tb_send(BUS, "701 R1");
    f = tb_next(BUS);
    assert_non_null(f);
    assert_int_equal(f->id, 0x701U);
    assert_int_equal(f->dlc, 1U);
    tb_expect_none(BUS);
    return (uint8_t)(f->data[0] & 0x7FU);
}

static void error_behaviour_object(void **state)
{
    /* 0x1029: sub 0 = 3; the communication error defaults to 0 (CiA 301) */
    tb_xfer(BUS, "601 40 29 10 00 00 00 00 00", "581 4F 29 10 00 03 00 00 00");
    tb_xfer(BUS, "601 40 29 10 01 00 00 00 00", "581 4F 29 10 01 00 00 00 00");
    /* 0, 1, 2 and the manufacturer-specific 0x80..0xFF; 3..0x7F are reserved */
    tb_xfer(BUS, "601 2F 29 10 01 02 00 00 00", "581 60 29 10 01 00 00 00 00");
    tb_xfer(BUS, "601 2F 29 10 01 03 00 00 00", "581 80 29 10 01 30 00 09 06");
    tb_xfer(BUS, "601 2F 29 10 01 7F 00 00 00", "581 80 29 10 01 30 00 09 06");
    tb_xfer(BUS, "601 2F 29 10 02 80 00 00 00", "581 60 29 10 02 00 00 00 00");
    tb_xfer(BUS, "601 2F 29 10 03 FF 00 00 00", "581 60 29 10 03 00 00 00 00");
    tb_xfer(BUS, "601 40 29 10 01 00 00 00 00", "581 4F 29 10 01 02 00 00 00");
}

/* 0: a heartbeat consumer timeout in Operational -> Pre-operational, after
 * the EMCY and the event; the callback still sees Operational. */
static void heartbeat_timeout_enters_pre_operational(void **state)
{
    tb_send(BUS, "000 01 01");
    consume_node_20(state);
    assert_int_equal(guarded_state(state), 0x05);
    tb_advance(BUS, 100000U + HBC_LATE);
    tb_expect(BUS, "081 30 81 11 00 00 00 00 00");
    tb_expect_none(BUS);
    assert_int_equal(co_node_nmt_state(NODE), CO_NMT_PRE_OPERATIONAL);
    assert_int_equal(guarded_state(state), 0x7F);
    expect_event(&REC, 1, CO_HB_TIMEOUT, 0x20, CO_NMT_OPERATIONAL);
    /* the producer is back: the error ends, the state stays */
    tb_send(BUS, "720 05");
    tb_expect(BUS, "081 00 00 00 00 00 00 00 00");
    tb_expect_none(BUS);
    assert_int_equal(guarded_state(state), 0x7F);
    /* 0 from Pre-operational or Stopped: no change */
    tb_advance(BUS, 100000U + HBC_LATE);
    tb_expect(BUS, "081 30 81 11 00 00 00 00 00");
    assert_int_equal(guarded_state(state), 0x7F);
    tb_send(BUS, "720 05");
    tb_expect(BUS, "081 00 00 00 00 00 00 00 00");
    tb_send(BUS, "000 02 01");
    tb_advance(BUS, 100000U);
    tb_expect_none(BUS); /* no EMCY in Stopped */
    assert_int_equal(guarded_state(state), 0x04);
}

/* 1: no change; 2: Stopped (from Operational and from Pre-operational). */
static void heartbeat_timeout_no_change_or_stopped(void **state)
{
    tb_xfer(BUS, "601 2F 29 10 01 01 00 00 00", "581 60 29 10 01 00 00 00 00");
    tb_send(BUS, "000 01 01");
    consume_node_20(state);
    tb_advance(BUS, 100000U + HBC_LATE);
    tb_expect(BUS, "081 30 81 11 00 00 00 00 00");
    tb_expect_none(BUS);
    assert_int_equal(guarded_state(state), 0x05);
    tb_send(BUS, "720 05");
    tb_expect(BUS, "081 00 00 00 00 00 00 00 00");
    tb_xfer(BUS, "601 2F 29 10 01 02 00 00 00", "581 60 29 10 01 00 00 00 00");
    tb_advance(BUS, 100000U + HBC_LATE);
    tb_expect(BUS, "081 30 81 11 00 00 00 00 00");
    tb_expect_none(BUS);
    assert_int_equal(co_node_nmt_state(NODE), CO_NMT_STOPPED);
    assert_int_equal(guarded_state(state), 0x04);
    /* Stopped: no SDO answer */
    tb_send(BUS, "601 40 29 10 01 00 00 00 00");
    tb_expect_none(BUS);
    tb_send(BUS, "000 80 01");
    tb_send(BUS, "720 05");
    tb_expect(BUS, "081 00 00 00 00 00 00 00 00");
    tb_advance(BUS, 100000U + HBC_LATE);
    tb_expect(BUS, "081 30 81 11 00 00 00 00 00");
    tb_expect_none(BUS);
    assert_int_equal(guarded_state(state), 0x04);
    /* manufacturer-specific values: the core changes nothing */
    tb_send(BUS, "000 01 01");
    tb_send(BUS, "720 05");
    tb_expect(BUS, "081 00 00 00 00 00 00 00 00");
    tb_xfer(BUS, "601 2F 29 10 01 80 00 00 00", "581 60 29 10 01 00 00 00 00");
    tb_advance(BUS, 100000U + HBC_LATE);
    tb_expect(BUS, "081 30 81 11 00 00 00 00 00");
    assert_int_equal(guarded_state(state), 0x05);
}

/* Life guarding is a communication error too. */
static void life_guarding_loss_enters_pre_operational(void **state)
{
    configure_life_guarding(state);
    tb_send(BUS, "000 01 01");
    tb_xfer(BUS, "701 R1", "701 05");
    tb_advance(BUS, 300000U);
    tb_expect(BUS, "081 30 81 11 00 00 00 00 00");
    tb_expect_none(BUS);
    expect_event(&REC, 0, CO_GUARD_LOST, 0, CO_NMT_OPERATIONAL);
    assert_int_equal(co_node_nmt_state(NODE), CO_NMT_PRE_OPERATIONAL);
    /* the next request: Pre-operational in the answer, the error ends */
    tb_send(BUS, "701 R1");
    tb_expect(BUS, "701 FF");
    tb_expect(BUS, "081 00 00 00 00 00 00 00 00");
    tb_expect_none(BUS);
    /* 2: Stopped, and guarding goes on answering */
    tb_xfer(BUS, "601 2F 29 10 01 02 00 00 00", "581 60 29 10 01 00 00 00 00");
    tb_advance(BUS, 300000U);
    tb_expect(BUS, "081 30 81 11 00 00 00 00 00");
    tb_expect_none(BUS);
    tb_xfer(BUS, "701 R1", "701 04");
}

/* Bus-off (reported by the port) and the device-specific classes go
 * through co_node_error_behaviour. */
static void bus_off_and_device_classes(void **state)
{
    tb_send(BUS, "000 01 01");
    co_node_error_behaviour(NODE, CO_ERRBEH_COMM, BUS->now);
    assert_int_equal(co_node_nmt_state(NODE), CO_NMT_PRE_OPERATIONAL);
    tb_expect_none(BUS);
    assert_int_equal(guarded_state(state), 0x7F);
    tb_send(BUS, "000 01 01");
    /* class 2 defaults to 1 here: no change; written 2: Stopped */
    co_node_error_behaviour(NODE, 2U, BUS->now);
    assert_int_equal(co_node_nmt_state(NODE), CO_NMT_OPERATIONAL);
    tb_xfer(BUS, "601 2F 29 10 02 02 00 00 00", "581 60 29 10 02 00 00 00 00");
    co_node_error_behaviour(NODE, 2U, BUS->now);
    assert_int_equal(co_node_nmt_state(NODE), CO_NMT_STOPPED);
    /* a class the device does not have, or sub-index 0: nothing */
    tb_send(BUS, "000 01 01");
    co_node_error_behaviour(NODE, 4U, BUS->now);
    co_node_error_behaviour(NODE, 0U, BUS->now);
    assert_int_equal(co_node_nmt_state(NODE), CO_NMT_OPERATIONAL);
    tb_expect_none(BUS);
}

/* A device without 0x1029 keeps its NMT state on a communication error. */
static void without_error_behaviour_object(void **state)
{
    static co_od_entry_t od[64];
    uint16_t n = 0U;

    for (uint16_t i = 0U; i < td_dev.od_count; i++) {
        if (td_dev.od[i].index != 0x1029U) {
            assert_true(n < 64U);
            od[n++] = td_dev.od[i];
        }
    }
    FX->dev.od = od;
    FX->dev.od_count = n;
    start_cb(&FX->n, &FX->r, BUS, 0, 1, &FX->dev);
    tb_expect(BUS, "701 00");
    tb_send(BUS, "000 01 01");
    consume_node_20(state);
    tb_advance(BUS, 100000U + HBC_LATE);
    tb_expect(BUS, "081 30 81 11 00 00 00 00 00");
    tb_expect_none(BUS);
    assert_int_equal(co_node_nmt_state(NODE), CO_NMT_OPERATIONAL);
    co_node_error_behaviour(NODE, CO_ERRBEH_COMM, BUS->now);
    assert_int_equal(co_node_nmt_state(NODE), CO_NMT_OPERATIONAL);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(heartbeat_producer_period, setup),
        cmocka_unit_test_setup(heartbeat_state_follows_nmt, setup),
        cmocka_unit_test_setup(heartbeat_rewrite_keeps_cycle, setup),
        cmocka_unit_test_setup(heartbeat_producer_zero_stops, setup),
        cmocka_unit_test_setup(heartbeat_muted_and_resumed, setup),
        cmocka_unit_test_setup(heartbeat_consumer_timeout_and_recovery, setup),
        cmocka_unit_test_setup(heartbeat_consumer_state_changes, setup),
        cmocka_unit_test_setup(heartbeat_consumer_two_producers_one_error, setup),
        cmocka_unit_test_setup(heartbeat_consumer_entry_checks, setup),
        cmocka_unit_test_setup(heartbeat_consumer_disabled_entry_clears_error, setup),
        cmocka_unit_test_setup(heartbeat_consumer_write_restarts_that_entry_only, setup),
        cmocka_unit_test_setup(timers_across_the_clock_wrap, setup),
        cmocka_unit_test_setup(heartbeat_consumer_unused_entry_same_producer, setup),
        cmocka_unit_test_setup(heartbeat_consumer_timeout_within_a_ms, setup),
        cmocka_unit_test_setup(heartbeat_consumer_after_70_s_without_process, setup),
        cmocka_unit_test_setup(heartbeat_consumer_first_after_71_min, setup),
        cmocka_unit_test_setup(reset_communication_ends_monitoring, setup),
        cmocka_unit_test_setup(node_guarding_toggle, setup),
        cmocka_unit_test_setup(node_guarding_not_answered_with_heartbeat, setup),
        cmocka_unit_test_setup(node_guarding_with_heartbeat_option, setup),
        cmocka_unit_test_setup(life_guarding, setup),
        cmocka_unit_test_setup(life_guarding_reconfigured_while_lost, setup),
        cmocka_unit_test_setup(life_guarding_disabled_while_lost, setup),
        cmocka_unit_test_setup(life_guarding_stops_when_heartbeat_starts, setup),
        cmocka_unit_test_setup(reset_communication_ends_life_guarding, setup),
        cmocka_unit_test_setup(heartbeat_and_guarding_errors_share_the_code, setup),
        cmocka_unit_test_setup(error_behaviour_object, setup),
        cmocka_unit_test_setup(heartbeat_timeout_enters_pre_operational, setup),
        cmocka_unit_test_setup(heartbeat_timeout_no_change_or_stopped, setup),
        cmocka_unit_test_setup(life_guarding_loss_enters_pre_operational, setup),
        cmocka_unit_test_setup(bus_off_and_device_classes, setup),
        cmocka_unit_test_setup(without_error_behaviour_object, setup),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
