/*
 * The profile-neutral plug-in host (co_profile.h): attach order and errors,
 * the node's callbacks fanned out to every instance and then to the
 * application, and the earliest deadline of all instances. Two recording
 * plug-ins on a generic-301 node.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "co/co_profile.h"
#include "generic_301.h"
#include "test_bus.h"

typedef struct rec {
    char log[512];
    co_node_t *node;
    uint32_t deadline;  /* what process returns */
    co_err_t attach_err;
    uint32_t last_time;
    int id;
    uint8_t clear[8];   /* tpdo_event: the changed bits this instance masks */
} rec_t;

static char order[1024];

static void note(rec_t *r, const char *what, uint32_t t)
{
    char b[64];
    snprintf(b, sizeof b, "%d:%s ", r->id, what);
    strncat(r->log, b, sizeof r->log - strlen(r->log) - 1U);
    strncat(order, b, sizeof order - strlen(order) - 1U);
    r->last_time = t;
}

static co_err_t p_attach(void *inst, co_node_t *node, uint32_t now)
{
    rec_t *r = (rec_t *)inst;
    r->node = node;
    note(r, "attach", now);
    return r->attach_err;
}

static uint32_t p_process(void *inst, uint32_t now)
{
    rec_t *r = (rec_t *)inst;
    r->last_time = now;
    return r->deadline;
}

static void p_sync(void *inst, uint8_t counter, uint32_t now)
{
    char b[16];
    snprintf(b, sizeof b, "sync%u", counter);
    note((rec_t *)inst, b, now);
}

static void p_nmt(void *inst, co_nmt_state_t st, uint32_t now)
{
    char b[16];
    snprintf(b, sizeof b, "nmt%02X", (unsigned)st);
    note((rec_t *)inst, b, now);
}

static void p_reset(void *inst, co_reset_t kind, uint32_t now)
{
    note((rec_t *)inst, (kind == CO_RESET_NODE) ? "reset-node" : "reset-comm", now);
}

static void p_errctl(void *inst, co_hb_event_t ev, uint8_t id, uint32_t now)
{
    char b[16];
    snprintf(b, sizeof b, "hb%d/%u", (int)ev, id);
    note((rec_t *)inst, b, now);
}

/* Recording plug-in 1 puts 0x11 into byte 3, plug-in 2 byte 3 + 1 into byte 4
 * (so the order shows in the frame). */
static void p_emcy_mfr(void *inst, uint16_t code, uint8_t mfr[5])
{
    rec_t *r = (rec_t *)inst;
    char b[16];

    snprintf(b, sizeof b, "mfr%04X", (unsigned)code);
    note(r, b, co_node_now(r->node));
    if (r->id == 1) {
        mfr[0] = 0x11U;
    } else {
        mfr[1] = (uint8_t)(mfr[0] + 1U);
    }
}

static void p_rpdo(void *inst, uint16_t n, uint32_t now)
{
    char b[16];
    snprintf(b, sizeof b, "rpdo%u", (unsigned)n);
    note((rec_t *)inst, b, now);
}

static void p_tpdo_event(void *inst, uint16_t n, const uint8_t last[8], const uint8_t now[8],
                         uint8_t changed[8])
{
    rec_t *r = (rec_t *)inst;
    char b[16];
    snprintf(b, sizeof b, "tpdo%u:%02X>%02X", (unsigned)n, last[1], now[1]);
    note(r, b, r->node->now);
    for (unsigned k = 0; k < 8U; k++) {
        changed[k] = (uint8_t)(changed[k] & ~r->clear[k]);
    }
}

static void p_nmt_cmd(void *inst, uint8_t cs, uint32_t now)
{
    rec_t *r = (rec_t *)inst;
    char b[16];
    snprintf(b, sizeof b, "cmd%02X/%02X", cs, (unsigned)co_node_nmt_state(r->node));
    note(r, b, now);
}

static void p_err_class(void *inst, uint8_t sub, uint32_t now)
{
    char b[16];
    snprintf(b, sizeof b, "err%u", sub);
    note((rec_t *)inst, b, now);
}

static const co_profile_ops_t ops = {
    .name = "rec",
    .attach = p_attach,
    .process = p_process,
    .sync = p_sync,
    .nmt_state = p_nmt,
    .reset = p_reset,
    .error_control = p_errctl,
    .emcy_mfr = p_emcy_mfr,
    .rpdo = p_rpdo,
    .tpdo_event = p_tpdo_event,
    .nmt_command = p_nmt_cmd,
    .error_class = p_err_class,
};
static const co_profile_ops_t ops_min = {.name = "min", .attach = p_attach};

static void a_sync(void *ctx, co_node_t *node, uint8_t counter)
{
    (void)node;
    (void)ctx;
    strncat(order, counter ? "app:sync1 " : "app:sync0 ", sizeof order - strlen(order) - 1U);
}

static void a_nmt(void *ctx, co_node_t *node, co_nmt_state_t st)
{
    (void)ctx;
    (void)node;
    (void)st;
    strncat(order, "app:nmt ", sizeof order - strlen(order) - 1U);
}

static void a_rpdo(void *ctx, co_node_t *node, uint16_t n)
{
    (void)ctx;
    (void)node;
    (void)n;
    strncat(order, "app:rpdo ", sizeof order - strlen(order) - 1U);
}

static void a_nmt_cmd(void *ctx, co_node_t *node, uint8_t cs)
{
    (void)ctx;
    (void)node;
    (void)cs;
    strncat(order, "app:cmd ", sizeof order - strlen(order) - 1U);
}

static void a_err_class(void *ctx, co_node_t *node, uint8_t sub)
{
    (void)ctx;
    (void)node;
    (void)sub;
    strncat(order, "app:err ", sizeof order - strlen(order) - 1U);
}

static void a_emcy_mfr(void *ctx, co_node_t *node, uint16_t code, uint8_t mfr[5])
{
    (void)ctx;
    (void)node;
    (void)code;
    mfr[4] = 0x55U;
    strncat(order, "app:mfr ", sizeof order - strlen(order) - 1U);
}

typedef struct fx {
    tb_bus_t bus;
    generic_301_node_t n;
    co_profile_host_t host;
    co_profile_t slots[3];
    rec_t a, b;
} fx_t;

static fx_t fx;

static void start(bool with_app)
{
    co_node_config_t cfg;
    co_node_callbacks_t app;

    memset(&fx, 0, sizeof fx);
    memset(order, 0, sizeof order);
    tb_init(&fx.bus);
    fx.a.id = 1;
    fx.b.id = 2;
    fx.a.deadline = CO_NO_DEADLINE;
    fx.b.deadline = CO_NO_DEADLINE;
    memset(&app, 0, sizeof app);
    app.sync = a_sync;
    app.nmt_state = a_nmt;
    app.emcy_mfr = a_emcy_mfr;
    app.rpdo = a_rpdo;
    app.nmt_command = a_nmt_cmd;
    app.error_class = a_err_class;
    co_profile_host_init(&fx.host, fx.slots, 2, with_app ? &app : NULL);
    assert_int_equal(co_profile_add(&fx.host, &ops, &fx.a), CO_OK);
    assert_int_equal(co_profile_add(&fx.host, &ops, &fx.b), CO_OK);
    assert_int_equal(co_profile_add(&fx.host, &ops, &fx.b), CO_ERR_NO_MEMORY);
    generic_301_config(&fx.n, &cfg);
    cfg.hal = tb_hal(&fx.bus, 0);
    cfg.node_id = 3;
    cfg.cb = co_profile_host_callbacks(&fx.host);
    tb_attach(&fx.bus, 0, &fx.n.node);
    assert_int_equal(co_node_init(&fx.n.node, &cfg, fx.bus.now), CO_RESULT_OK);
    tb_expect(&fx.bus, "703 00");
}

static void callbacks_before_attach_go_to_the_application_only(void **state)
{
    (void)state;
    start(true);
    /* co_node_init entered Pre-operational before the plug-ins were attached */
    assert_string_equal(order, "app:nmt ");
    assert_int_equal(co_profile_host_process(&fx.host, fx.bus.now), CO_NO_DEADLINE);
    assert_string_equal(fx.a.log, "");
}

static void attach_in_order_then_fan_out(void **state)
{
    (void)state;
    start(true);
    memset(order, 0, sizeof order);
    fx.bus.now = 5000;
    assert_int_equal(co_profile_host_attach(&fx.host, &fx.n.node, fx.bus.now), CO_OK);
    assert_ptr_equal(fx.a.node, &fx.n.node);
    assert_string_equal(order, "1:attach 2:attach ");
    memset(order, 0, sizeof order);
    fx.bus.now = 6000;
    tb_send(&fx.bus, "080");
    assert_string_equal(order, "1:sync0 2:sync0 app:sync0 ");
    assert_int_equal(fx.a.last_time, 6000);
    memset(order, 0, sizeof order);
    fx.bus.now = 7000;
    tb_send(&fx.bus, "000 01 03");
    assert_string_equal(order, "1:cmd01/7F 2:cmd01/7F app:cmd 1:nmt05 2:nmt05 app:nmt ");
    assert_int_equal(fx.b.last_time, 7000);
    memset(order, 0, sizeof order);
    tb_send(&fx.bus, "000 81 00");
    assert_string_equal(order, "1:cmd81/05 2:cmd81/05 app:cmd 1:reset-node 2:reset-node "
                               "1:nmt7F 2:nmt7F app:nmt ");
    memset(order, 0, sizeof order);
    tb_send(&fx.bus, "000 82 03");
    assert_string_equal(order, "1:cmd82/7F 2:cmd82/7F app:cmd 1:reset-comm 2:reset-comm "
                               "1:nmt7F 2:nmt7F app:nmt ");
    /* heartbeat consumer of node 0x20, 100 ms: started, then lost */
    tb_flush(&fx.bus);
    tb_xfer(&fx.bus, "603 23 16 10 01 64 00 20 00", "583 60 16 10 01 00 00 00 00");
    memset(order, 0, sizeof order);
    tb_send(&fx.bus, "720 05");
    tb_advance(&fx.bus, 100000 + 1023); /* (within 1023 us: co_hb.c) */
    assert_string_equal(order,
                        "1:hb0/32 2:hb0/32 1:mfr8130 2:mfr8130 app:mfr 1:hb1/32 2:hb1/32 ");
}

/* The EMCYs the core raises itself: the plug-ins fill the manufacturer
 * bytes in turn, then the application; an EMCY raised with manufacturer
 * data is not asked about. */
static void emcy_mfr_fanned_out(void **state)
{
    static const uint8_t own[5] = {1, 2, 3, 4, 5};

    (void)state;
    start(true);
    assert_int_equal(co_profile_host_attach(&fx.host, &fx.n.node, fx.bus.now), CO_OK);
    tb_xfer(&fx.bus, "603 23 16 10 01 64 00 20 00", "583 60 16 10 01 00 00 00 00");
    tb_send(&fx.bus, "720 05");
    memset(order, 0, sizeof order);
    tb_advance(&fx.bus, 100000 + 1023); /* (a consumer: within 1023 us, co_hb.c) */
    /* 0x8130 with 11 12 00 00 55 in bytes 3..7; the error comes before the event */
    tb_expect(&fx.bus, "083 30 81 11 11 12 00 00 55");
    tb_expect_none(&fx.bus);
    assert_string_equal(order, "1:mfr8130 2:mfr8130 app:mfr 1:hb1/32 2:hb1/32 ");
    /* 0x1003 holds bytes 3..4 above the code */
    tb_xfer(&fx.bus, "603 40 03 10 01 00 00 00 00", "583 43 03 10 01 30 81 11 12");
    memset(order, 0, sizeof order);
    co_emcy_raise(&fx.n.node, 0x5000U, CO_ERREG_MANUFACTURER, own);
    tb_expect(&fx.bus, "083 00 50 91 01 02 03 04 05");
    assert_string_equal(order, "");
    /* the application's own error without data is filled the same way */
    co_emcy_raise(&fx.n.node, 0x5001U, CO_ERREG_MANUFACTURER, NULL);
    tb_expect(&fx.bus, "083 01 50 91 11 12 00 00 55");
    tb_expect_none(&fx.bus);
}

static void earliest_deadline(void **state)
{
    (void)state;
    start(false);
    assert_int_equal(co_profile_host_attach(&fx.host, &fx.n.node, 1000), CO_OK);
    assert_int_equal(co_profile_host_process(&fx.host, 1000), CO_NO_DEADLINE);
    fx.a.deadline = 9000;
    assert_int_equal(co_profile_host_process(&fx.host, 1000), 9000);
    fx.b.deadline = 3000;
    assert_int_equal(co_profile_host_process(&fx.host, 1000), 3000);
    assert_int_equal(fx.a.last_time, 1000);
    /* wrap-safe: 0xFFFFFF00 + 0x200 comes after 0xFFFFFF00 + 0x100 */
    fx.a.deadline = 0x00000100UL;
    fx.b.deadline = 0xFFFFFFF0UL;
    assert_int_equal(co_profile_host_process(&fx.host, 0xFFFFFF00UL), 0xFFFFFFF0UL);
    /* an application without callbacks: the node's events still reach the plug-ins */
    memset(order, 0, sizeof order);
    tb_send(&fx.bus, "080");
    assert_string_equal(order, "1:sync0 2:sync0 ");
}

/* The operations for I/O and valve devices: an RPDO after its objects are
 * written, the change of an event-driven TPDO filtered by the instances'
 * masks, the notice before an NMT command (still in the old state) and a
 * serious error reported by co_node_error_behaviour. generic-301: RPDO1
 * maps 0x2100 (8), 0x2101 (16), 0x2102 (32); TPDO1 (type 255) 0x1001 (8),
 * 0x2100 (8), 0x2101 (16), 0x2104 (32). */
static void io_operations_fanned_out(void **state)
{
    (void)state;
    start(true);
    assert_int_equal(co_profile_host_attach(&fx.host, &fx.n.node, fx.bus.now), CO_OK);
    memset(order, 0, sizeof order);
    tb_send(&fx.bus, "000 01 03");
    assert_string_equal(order, "1:cmd01/7F 2:cmd01/7F app:cmd 1:nmt05 2:nmt05 app:nmt ");
    memset(order, 0, sizeof order);
    tb_send(&fx.bus, "000 01 03"); /* no change: no notice */
    tb_send(&fx.bus, "000 03 03"); /* no command */
    assert_string_equal(order, "");
    tb_advance(&fx.bus, 1000);
    tb_expect(&fx.bus, "183 00 00 00 00 00 00 00 00"); /* first in Operational: not asked */
    tb_flush(&fx.bus); /* TPDO2..4 */
    assert_string_equal(order, "");
    /* RPDO1: the instances after the objects are written, then the application */
    tb_send(&fx.bus, "203 11 00 00 44 55 66 77");
    assert_string_equal(order, "1:rpdo0 2:rpdo0 app:rpdo ");
    assert_int_equal(*(uint8_t *)co_od_value_ptr(&fx.n.node, 0x2100U, 0U), 0x11U);
    /* 0x2100 changed (TPDO byte 1): instance 1 masks byte 1, so no TPDO */
    fx.a.clear[1] = 0xFFU;
    memset(order, 0, sizeof order);
    tb_advance(&fx.bus, 1000);
    tb_expect_none(&fx.bus);
    /* asked at every process while the data differs from what was sent */
    assert_int_equal(strncmp(order, "1:tpdo0:00>11 2:tpdo0:00>11 ", 28), 0);
    /* a change instance 1 does not mask (0x2101, bytes 2..3) sends all */
    tb_send(&fx.bus, "203 11 23 00 44 55 66 77");
    tb_advance(&fx.bus, 1000);
    tb_expect(&fx.bus, "183 00 11 23 00 00 00 00 00");
    /* a serious error of class 1 (bus-off as the port reports it) */
    memset(order, 0, sizeof order);
    co_node_error_behaviour(&fx.n.node, CO_ERRBEH_COMM, fx.bus.now);
    assert_string_equal(order, "1:err1 2:err1 app:err ");
    /* stop: the notice comes while the node is still Operational */
    memset(order, 0, sizeof order);
    tb_send(&fx.bus, "000 02 00");
    assert_string_equal(order, "1:cmd02/05 2:cmd02/05 app:cmd 1:nmt04 2:nmt04 app:nmt ");
    memset(order, 0, sizeof order);
    tb_send(&fx.bus, "000 81 03");
    assert_string_equal(order, "1:cmd81/04 2:cmd81/04 app:cmd 1:reset-node 2:reset-node "
                               "1:nmt7F 2:nmt7F app:nmt ");
}

static void attach_error_stops(void **state)
{
    co_profile_host_t h;
    co_profile_t slots[2];
    rec_t r1, r2;
    (void)state;
    start(false);
    memset(&r1, 0, sizeof r1);
    memset(&r2, 0, sizeof r2);
    r1.id = 1;
    r2.id = 2;
    r1.attach_err = CO_ERR_OD_MISSING;
    co_profile_host_init(&h, slots, 2, NULL);
    assert_int_equal(co_profile_add(&h, &ops_min, &r1), CO_OK);
    assert_int_equal(co_profile_add(&h, &ops_min, &r2), CO_OK);
    assert_int_equal(co_profile_add(&h, NULL, &r2), CO_ERR_VALUE);
    assert_int_equal(co_profile_host_attach(&h, &fx.n.node, 1000), CO_ERR_OD_MISSING);
    assert_string_equal(r2.log, "");
    assert_int_equal(co_profile_host_process(&h, 1000), CO_NO_DEADLINE);
    /* a plug-in without optional operations */
    r1.attach_err = CO_OK;
    assert_int_equal(co_profile_host_attach(&h, &fx.n.node, 1000), CO_OK);
    assert_int_equal(co_profile_host_process(&h, 1000), CO_NO_DEADLINE);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(callbacks_before_attach_go_to_the_application_only),
        cmocka_unit_test(attach_in_order_then_fan_out),
        cmocka_unit_test(emcy_mfr_fanned_out),
        cmocka_unit_test(earliest_deadline),
        cmocka_unit_test(io_operations_fanned_out),
        cmocka_unit_test(attach_error_stops),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
