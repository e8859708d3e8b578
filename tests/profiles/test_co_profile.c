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

static const co_profile_ops_t ops = {"rec",   p_attach, p_process, p_sync, p_nmt,
                                     p_reset, p_errctl, p_emcy_mfr};
static const co_profile_ops_t ops_min = {"min", p_attach, NULL, NULL, NULL, NULL, NULL, NULL};

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
    assert_string_equal(order, "1:nmt05 2:nmt05 app:nmt ");
    assert_int_equal(fx.b.last_time, 7000);
    memset(order, 0, sizeof order);
    tb_send(&fx.bus, "000 81 00");
    assert_string_equal(order, "1:reset-node 2:reset-node 1:nmt7F 2:nmt7F app:nmt ");
    memset(order, 0, sizeof order);
    tb_send(&fx.bus, "000 82 03");
    assert_string_equal(order, "1:reset-comm 2:reset-comm 1:nmt7F 2:nmt7F app:nmt ");
    /* heartbeat consumer of node 0x20, 100 ms: started, then lost */
    tb_flush(&fx.bus);
    tb_xfer(&fx.bus, "603 23 16 10 01 64 00 20 00", "583 60 16 10 01 00 00 00 00");
    memset(order, 0, sizeof order);
    tb_send(&fx.bus, "720 05");
    tb_advance(&fx.bus, 100001);
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
    tb_advance(&fx.bus, 100001);
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
        cmocka_unit_test(attach_error_stops),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
