/*
 * The full TX path and the TX-ready notice (co_node_tx_ready): a frame the
 * HAL refuses waits as its producer's state (co_priv.h, CO_TXH_*) and is made
 * again when the path takes it, in CAN priority order (lowest CAN-ID first,
 * one identifier in the order the frames were made): the EMCYs of the EMCY
 * queue, the SDO answer (one: a newer one replaces it), boot-up, heartbeat
 * (the state when it goes, the period keeping its times), guarding reply,
 * the SYNC producer's SYNC; TIME is sent at once or refused. The notice sends
 * what waits, and resumes a block upload stalled on the full TX path, at
 * once instead of at the next 1 ms look.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "co/co_canstate.h"
#include "test_bus.h"
#include "test_dev.h"

typedef struct fx {
    tb_bus_t bus;
    td_node_t n;
} fx_t;

static int setup(void **state)
{
    static fx_t fx;
    memset(&fx, 0, sizeof fx);
    tb_init(&fx.bus);
    td_start(&fx.n, &fx.bus, 0, 1, NULL);
    tb_flush(&fx.bus);
    *state = &fx;
    return 0;
}

#define FX ((fx_t *)*state)
#define BUS (&FX->bus)
#define NODE (&FX->n.node)
#define RAMV (FX->n.ram)

static void held_back_in_priority_order(void **state)
{
    tb_xfer(BUS, "601 2B 17 10 00 0A 00 00 00", "581 60 17 10 00 00 00 00 00"); /* 10 ms */
    BUS->refuse = 1000U;
    tb_send(BUS, "601 40 00 10 00 00 00 00 00");          /* 581: SDO answer */
    tb_advance(BUS, 10000U);                              /* 701: the heartbeat due */
    co_node_can_overrun(NODE, true);                      /* 081: EMCY, the last made */
    tb_expect_none(BUS);
    BUS->refuse = 0U;
    co_node_tx_ready(NODE, BUS->now);                     /* no co_node_process */
    tb_expect(BUS, "081 10 81 11 00 00 00 00 00");
    tb_expect(BUS, "581 43 00 10 00 92 01 02 00");
    tb_expect(BUS, "701 7F");
    tb_expect_none(BUS);
    tb_advance(BUS, 9999U);                               /* the period kept its times */
    tb_expect_none(BUS);
    tb_advance(BUS, 1U);
    tb_expect(BUS, "701 7F");
    tb_expect_none(BUS);
}

/* Without the notice: co_node_process looks again every 1 ms. An EMCY goes
 * before the answer that waited, the frames of one producer in their order. */
static void retried_by_process(void **state)
{
    BUS->refuse = 1000U;
    tb_send(BUS, "601 40 00 10 00 00 00 00 00");
    co_node_can_overrun(NODE, true);                      /* 0x8110 */
    co_node_can_overrun(NODE, false);                     /* its EMCY 0x0000 */
    tb_advance(BUS, 3000U);
    tb_expect_none(BUS);
    BUS->refuse = 1U;                                     /* one frame taken, the next not */
    BUS->refuse_after = 1U;
    tb_advance(BUS, 0U);
    tb_expect(BUS, "081 10 81 11 00 00 00 00 00");
    tb_expect_none(BUS);
    tb_advance(BUS, 1000U);                               /* the next look */
    tb_expect(BUS, "081 00 00 00 00 00 00 00 00");
    tb_expect(BUS, "581 43 00 10 00 92 01 02 00");
    tb_expect_none(BUS);
}

/* A request/response service has one answer outstanding: a client that
 * asks again while the answer waits gets the newest (the server's state). */
static void a_newer_answer_replaces_the_held_one(void **state)
{
    BUS->refuse = 1000U;
    tb_send(BUS, "601 40 00 10 00 00 00 00 00");          /* 0x1000 */
    co_node_can_overrun(NODE, true);
    tb_send(BUS, "601 40 01 10 00 00 00 00 00");          /* 0x1001: replaces it */
    BUS->refuse = 0U;
    co_node_tx_ready(NODE, BUS->now);
    tb_expect(BUS, "081 10 81 11 00 00 00 00 00");
    tb_expect(BUS, "581 4F 01 10 00 11 00 00 00");
    tb_expect_none(BUS);
}

/* The heartbeat carries the state when it goes; heartbeats due while one
 * waits are that one (no burst), and the cycle keeps its times. */
static void heartbeat_made_when_it_goes(void **state)
{
    tb_xfer(BUS, "601 2B 17 10 00 0A 00 00 00", "581 60 17 10 00 00 00 00 00"); /* 10 ms */
    BUS->refuse = 1000U;
    tb_advance(BUS, 25000U);                              /* due at 10 and 20 ms */
    tb_send(BUS, "000 01 01");                            /* Operational */
    tb_advance(BUS, 10000U);                              /* and at 30 ms */
    tb_expect_none(BUS);
    BUS->refuse = 0U;
    co_node_tx_ready(NODE, BUS->now);                     /* 35 ms */
    tb_expect(BUS, "701 05");
    tb_expect_none(BUS);
    tb_advance(BUS, 4999U);
    tb_expect_none(BUS);
    tb_advance(BUS, 1U);                                  /* 40 ms */
    tb_expect(BUS, "701 05");
    tb_expect_none(BUS);
}

/* A reset while the path is full: the boot-up waits (the frames the other
 * producers had waiting start over with them), goes after what outranks
 * it, and before the heartbeats of the same CAN-ID. */
static void boot_up_waits_after_a_reset(void **state)
{
    BUS->refuse = 1000U;
    tb_send(BUS, "000 82 01");                            /* reset communication */
    tb_send(BUS, "601 40 00 10 00 00 00 00 00");
    co_node_can_overrun(NODE, true);
    co_od_write(NODE, 0x1017U, 0U, "\x0A\x00", 2U, true); /* heartbeat 10 ms */
    tb_advance(BUS, 10000U);
    tb_expect_none(BUS);
    BUS->refuse = 0U;
    co_node_tx_ready(NODE, BUS->now);
    tb_expect(BUS, "081 10 81 11 00 00 00 00 00");
    tb_expect(BUS, "581 43 00 10 00 92 01 02 00");
    tb_expect(BUS, "701 00");
    tb_expect(BUS, "701 7F");
    tb_expect_none(BUS);
}

/* A guarding reply is made when it goes: the toggle bit changes with each
 * reply sent; a request while a reply waits is answered by that one. */
static void guarding_reply_waits(void **state)
{
    BUS->refuse = 1000U;
    tb_send(BUS, "701 R1");
    tb_send(BUS, "701 R1");
    tb_send(BUS, "000 01 01");
    BUS->refuse = 0U;
    co_node_tx_ready(NODE, BUS->now);
    tb_expect(BUS, "701 05");
    tb_expect_none(BUS);
    tb_xfer(BUS, "701 R1", "701 85");
    tb_xfer(BUS, "701 R1", "701 05");
}

/* The SYNC producer: a refused SYNC goes when the path takes it, with the
 * counter it had; the period keeps its times. */
static void sync_waits_and_keeps_its_period(void **state)
{
    tb_xfer(BUS, "601 2F 19 10 00 03 00 00 00", "581 60 19 10 00 00 00 00 00");
    tb_xfer(BUS, "601 23 06 10 00 10 27 00 00", "581 60 06 10 00 00 00 00 00"); /* 10 ms */
    tb_xfer(BUS, "601 23 05 10 00 80 00 00 40", "581 60 05 10 00 00 00 00 00");
    BUS->refuse = 1000U;
    tb_advance(BUS, 13000U);
    co_node_can_overrun(NODE, true);                      /* 081: after the SYNC */
    tb_expect_none(BUS);
    BUS->refuse = 0U;
    co_node_tx_ready(NODE, BUS->now);
    tb_expect(BUS, "080 01");
    tb_expect(BUS, "081 10 81 11 00 00 00 00 00");
    tb_expect_none(BUS);
    tb_advance(BUS, 6999U);
    tb_expect_none(BUS);
    tb_advance(BUS, 1U);                                  /* 20 ms */
    tb_expect(BUS, "080 02");
    tb_expect_none(BUS);
    /* one that waits when the next is due is that one */
    BUS->refuse = 1000U;
    tb_advance(BUS, 25000U);                              /* due at 30, 40 ms */
    BUS->refuse = 0U;
    tb_advance(BUS, 1000U);
    tb_expect(BUS, "080 03");
    tb_expect_none(BUS);
    /* dropped when the producer stops */
    BUS->refuse = 1000U;
    tb_advance(BUS, 10000U);                              /* due at 50 ms */
    co_od_write(NODE, 0x1005U, 0U, "\x80\x00\x00\x00", 4U, true);
    BUS->refuse = 0U;
    tb_advance(BUS, 20000U);
    tb_expect_none(BUS);
}

/* TIME carries the caller's time: sent at once, or refused. */
static void time_now_or_refused(void **state)
{
    tb_xfer(BUS, "601 23 12 10 00 00 01 00 40", "581 60 12 10 00 00 00 00 00");
    BUS->refuse = 1U;
    assert_int_equal(co_time_send(NODE, 43200000UL, 15000), CO_ERR_RESOURCE);
    tb_expect_none(BUS);
    assert_int_equal(co_time_send(NODE, 43200000UL, 15000), CO_OK);
    tb_expect(BUS, "100 00 2E 93 02 98 3A");
    tb_expect_none(BUS);
}

static void notice_resumes_a_block_upload(void **state)
{
    memcpy(RAMV.vstr, "CANopen block transfer, 32 bytes", 32U);
    tb_xfer(BUS, "601 A4 12 20 00 7F 00 00 00", "581 C6 12 20 00 20 00 00 00");
    BUS->refuse = 1U;                                     /* the first segment finds it full */
    tb_send(BUS, "601 A3 00 00 00 00 00 00 00");
    tb_expect_none(BUS);
    co_node_tx_ready(NODE, BUS->now);                     /* same time: no 1 ms wait */
    tb_expect(BUS, "581 01 43 41 4E 6F 70 65 6E");
    tb_expect(BUS, "581 02 20 62 6C 6F 63 6B 20");
    tb_expect(BUS, "581 03 74 72 61 6E 73 66 65");
    tb_expect(BUS, "581 04 72 2C 20 33 32 20 62");
    tb_expect(BUS, "581 85 79 74 65 73 00 00 00");
    tb_expect_none(BUS);
    tb_xfer(BUS, "601 A2 05 7F 00 00 00 00 00", "581 CD E1 4A 00 00 00 00 00");
    tb_send(BUS, "601 A1 00 00 00 00 00 00 00");
    tb_expect_none(BUS);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(held_back_in_priority_order, setup),
        cmocka_unit_test_setup(retried_by_process, setup),
        cmocka_unit_test_setup(a_newer_answer_replaces_the_held_one, setup),
        cmocka_unit_test_setup(heartbeat_made_when_it_goes, setup),
        cmocka_unit_test_setup(boot_up_waits_after_a_reset, setup),
        cmocka_unit_test_setup(guarding_reply_waits, setup),
        cmocka_unit_test_setup(sync_waits_and_keeps_its_period, setup),
        cmocka_unit_test_setup(time_now_or_refused, setup),
        cmocka_unit_test_setup(notice_resumes_a_block_upload, setup),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
