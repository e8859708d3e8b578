/*
 * TX hold-back and the TX-ready notice (co_node_tx_ready): frames the HAL
 * refuses wait in CAN priority order (lowest CAN-ID first, one identifier in
 * order), a full queue loses its lowest-priority frame, and the notice sends
 * them, and resumes a block upload stalled on the full TX path, at once
 * instead of at the next 1 ms look.
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
    BUS->refuse = 1000U;
    tb_send(BUS, "601 40 00 10 00 00 00 00 00");          /* 581: SDO answer */
    co_node_can_overrun(NODE, true);                      /* 081: EMCY */
    tb_send(BUS, "601 40 01 10 00 00 00 00 00");          /* 581 again, after the first */
    tb_expect_none(BUS);
    BUS->refuse = 0U;
    co_node_tx_ready(NODE, BUS->now);                     /* no co_node_process */
    tb_expect(BUS, "081 10 81 11 00 00 00 00 00");
    tb_expect(BUS, "581 43 00 10 00 92 01 02 00");
    tb_expect(BUS, "581 4F 01 10 00 11 00 00 00");
    tb_expect_none(BUS);
}

static void full_queue_loses_the_lowest_priority(void **state)
{
    BUS->refuse = 1000U;
    for (int i = 0; i < 4; i++) {                         /* CO_TXQ_LEN SDO answers */
        tb_send(BUS, "601 40 00 10 00 00 00 00 00");
    }
    co_node_can_overrun(NODE, true);                      /* EMCY displaces one 581 */
    tb_send(BUS, "601 40 00 10 00 00 00 00 00");          /* a fifth 581: lost */
    BUS->refuse = 0U;
    co_node_tx_ready(NODE, BUS->now);
    tb_expect(BUS, "081 10 81 11 00 00 00 00 00");
    for (int i = 0; i < 3; i++) {
        tb_expect(BUS, "581 43 00 10 00 92 01 02 00");
    }
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
        cmocka_unit_test_setup(full_queue_loses_the_lowest_priority, setup),
        cmocka_unit_test_setup(notice_resumes_a_block_upload, setup),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
