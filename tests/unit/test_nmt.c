/*
 * NMT slave (CiA 301 7.2.8.3.1 and 7.3.2): boot-up, the state machine, the
 * commands for the own node-ID and broadcast, malformed frames, which
 * services work in which state, the two resets, the application callbacks,
 * the boot personality options and two nodes on one bus.
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
    int n_state;
    co_nmt_state_t states[REC_MAX];
    int n_reset;
    co_reset_t resets[REC_MAX];
    size_t log_at_reset[REC_MAX]; /* frames logged when the reset callback ran */
    uint16_t hb_prod_at_reset[REC_MAX];
    uint32_t u32_at_reset[REC_MAX];
    int n_hb;
    co_hb_event_t hb_ev[REC_MAX];
    uint8_t hb_id[REC_MAX];
    co_nmt_state_t hb_state[REC_MAX];
    tb_bus_t *bus;
    td_node_t *owner;
} rec_t;

static void on_state(void *ctx, co_node_t *node, co_nmt_state_t st)
{
    rec_t *r = (rec_t *)ctx;
    assert_ptr_equal(node, &r->owner->node);
    assert_true(r->n_state < REC_MAX);
    r->states[r->n_state++] = st;
}

static void on_reset(void *ctx, co_node_t *node, co_reset_t kind)
{
    rec_t *r = (rec_t *)ctx;
    assert_ptr_equal(node, &r->owner->node);
    assert_true(r->n_reset < REC_MAX);
    r->resets[r->n_reset] = kind;
    r->log_at_reset[r->n_reset] = r->bus->n_log;
    r->hb_prod_at_reset[r->n_reset] = r->owner->ram.hb_prod;
    r->u32_at_reset[r->n_reset] = r->owner->ram.u32;
    r->n_reset++;
}

static void on_hb(void *ctx, co_node_t *node, co_hb_event_t ev, uint8_t id, co_nmt_state_t st)
{
    rec_t *r = (rec_t *)ctx;
    assert_ptr_equal(node, &r->owner->node);
    assert_true(r->n_hb < REC_MAX);
    r->hb_ev[r->n_hb] = ev;
    r->hb_id[r->n_hb] = id;
    r->hb_state[r->n_hb] = st;
    r->n_hb++;
}

/* td_start without callbacks is not enough here: fill the config ourselves. */
static void start_cb(td_node_t *n, rec_t *r, tb_bus_t *bus, uint8_t idx, uint8_t id,
                     const co_dev_t *dev)
{
    co_node_callbacks_t cb;

    memset(r, 0, sizeof *r);
    memset(&cb, 0, sizeof cb);
    r->bus = bus;
    r->owner = n;
    cb.ctx = r;
    cb.nmt_state = on_state;
    cb.nmt_reset = on_reset;
    cb.hb_event = on_hb;
    td_start_cb(n, bus, idx, id, dev, &cb);
}

/* -------------------------------------------------------------- fixture */

typedef struct fx {
    tb_bus_t bus;
    td_node_t n;
    td_node_t n2;
    rec_t r;
    rec_t r2;
    co_dev_t dev;
} fx_t;

static int setup(void **state)
{
    static fx_t fx;
    memset(&fx, 0, sizeof fx);
    tb_init(&fx.bus);
    start_cb(&fx.n, &fx.r, &fx.bus, 0, 1, NULL);
    tb_flush(&fx.bus);
    fx.r.n_state = 0; /* the boot itself is checked in bootup_then_pre_operational */
    *state = &fx;
    return 0;
}

/* A bus with nothing on it yet: the test starts its own node(s). */
static int setup_empty(void **state)
{
    static fx_t fx;
    memset(&fx, 0, sizeof fx);
    tb_init(&fx.bus);
    fx.dev = td_dev;
    *state = &fx;
    return 0;
}

#define FX ((fx_t *)*state)
#define BUS (&FX->bus)
#define NODE (&FX->n.node)
#define RAMV (FX->n.ram)
#define REC (FX->r)

/* ------------------------------------------------------------ boot-up */

static void bootup_then_pre_operational(void **state)
{
    fx_t *fx = FX;
    start_cb(&fx->n, &fx->r, BUS, 0, 1, NULL);
    /* boot-up: COB-ID 0x700 + node-ID, one byte 0x00 */
    tb_expect(BUS, "701 00");
    tb_expect_none(BUS);
    assert_int_equal(co_node_nmt_state(NODE), CO_NMT_PRE_OPERATIONAL);
    /* the application sees Pre-operational once, and no reset */
    assert_int_equal(REC.n_state, 1);
    assert_int_equal(REC.states[0], CO_NMT_PRE_OPERATIONAL);
    assert_int_equal(REC.n_reset, 0);
    /* nothing else happens by itself: no heartbeat (0x1017 = 0), no EMCY */
    tb_advance(BUS, 5000000U);
    tb_expect_none(BUS);
}

static void bootup_uses_own_node_id(void **state)
{
    fx_t *fx = FX;
    start_cb(&fx->n, &fx->r, BUS, 0, 0x7F, NULL);
    tb_expect(BUS, "77F 00");
    tb_expect_none(BUS);
    tb_xfer(BUS, "67F 40 0B 10 00 00 00 00 00", "5FF 43 0B 10 00 7F 00 00 00");
}

static void init_rejects_bad_node_id(void **state)
{
    fx_t *fx = FX;
    co_node_config_t cfg;

    memset(&cfg, 0, sizeof cfg);
    cfg.dev = &td_dev;
    cfg.hal = tb_hal(BUS, 0);
    cfg.ram = &fx->n.ram;
    cfg.node_id = 0;
    assert_int_equal(co_node_init(&fx->n.node, &cfg, BUS->now), CO_RESULT_BAD_NODE_ID);
    cfg.node_id = 128;
    assert_int_equal(co_node_init(&fx->n.node, &cfg, BUS->now), CO_RESULT_BAD_NODE_ID);
    tb_expect_none(BUS);
}

/* ------------------------------------------------------------ commands */

static void commands_for_own_id(void **state)
{
    tb_send(BUS, "000 01 01");
    assert_int_equal(co_node_nmt_state(NODE), CO_NMT_OPERATIONAL);
    tb_send(BUS, "000 02 01");
    assert_int_equal(co_node_nmt_state(NODE), CO_NMT_STOPPED);
    tb_send(BUS, "000 80 01");
    assert_int_equal(co_node_nmt_state(NODE), CO_NMT_PRE_OPERATIONAL);
    tb_send(BUS, "000 02 01");
    assert_int_equal(co_node_nmt_state(NODE), CO_NMT_STOPPED);
    tb_send(BUS, "000 01 01");
    assert_int_equal(co_node_nmt_state(NODE), CO_NMT_OPERATIONAL);
    /* a state change alone sends nothing */
    tb_expect_none(BUS);
    /* reset communication and reset node: boot-up, back in Pre-operational */
    tb_send(BUS, "000 82 01");
    tb_expect(BUS, "701 00");
    tb_expect_none(BUS);
    assert_int_equal(co_node_nmt_state(NODE), CO_NMT_PRE_OPERATIONAL);
    tb_send(BUS, "000 02 01");
    tb_send(BUS, "000 81 01");
    tb_expect(BUS, "701 00");
    tb_expect_none(BUS);
    assert_int_equal(co_node_nmt_state(NODE), CO_NMT_PRE_OPERATIONAL);
    /* the same command twice is one state change */
    tb_send(BUS, "000 01 01");
    tb_send(BUS, "000 01 01");
    assert_int_equal(REC.n_state, 9);
    assert_int_equal(REC.states[0], CO_NMT_OPERATIONAL);
    assert_int_equal(REC.states[1], CO_NMT_STOPPED);
    assert_int_equal(REC.states[2], CO_NMT_PRE_OPERATIONAL);
    assert_int_equal(REC.states[3], CO_NMT_STOPPED);
    assert_int_equal(REC.states[4], CO_NMT_OPERATIONAL);
    assert_int_equal(REC.states[5], CO_NMT_PRE_OPERATIONAL); /* after reset comm */
    assert_int_equal(REC.states[6], CO_NMT_STOPPED);
    assert_int_equal(REC.states[7], CO_NMT_PRE_OPERATIONAL); /* after reset node */
    assert_int_equal(REC.states[8], CO_NMT_OPERATIONAL);
}

static void commands_broadcast(void **state)
{
    tb_send(BUS, "000 01 00");
    assert_int_equal(co_node_nmt_state(NODE), CO_NMT_OPERATIONAL);
    tb_send(BUS, "000 02 00");
    assert_int_equal(co_node_nmt_state(NODE), CO_NMT_STOPPED);
    tb_send(BUS, "000 80 00");
    assert_int_equal(co_node_nmt_state(NODE), CO_NMT_PRE_OPERATIONAL);
    tb_expect_none(BUS);
    tb_send(BUS, "000 81 00");
    tb_expect(BUS, "701 00");
    tb_expect_none(BUS);
    tb_send(BUS, "000 01 00");
    tb_send(BUS, "000 82 00");
    tb_expect(BUS, "701 00");
    tb_expect_none(BUS);
    assert_int_equal(co_node_nmt_state(NODE), CO_NMT_PRE_OPERATIONAL);
    assert_int_equal(REC.n_reset, 2);
    assert_int_equal(REC.resets[0], CO_RESET_NODE);
    assert_int_equal(REC.resets[1], CO_RESET_COMMUNICATION);
}

static void commands_for_other_nodes_ignored(void **state)
{
    tb_send(BUS, "000 01 02");
    tb_send(BUS, "000 01 7F");
    tb_send(BUS, "000 01 81"); /* 0x81 is not node 1 (no masking to 7 bits) */
    assert_int_equal(co_node_nmt_state(NODE), CO_NMT_PRE_OPERATIONAL);
    tb_send(BUS, "000 01 01");
    tb_send(BUS, "000 02 02");
    tb_send(BUS, "000 80 03");
    assert_int_equal(co_node_nmt_state(NODE), CO_NMT_OPERATIONAL);
    tb_send(BUS, "000 81 02");
    tb_send(BUS, "000 82 7F");
    tb_expect_none(BUS);
    assert_int_equal(co_node_nmt_state(NODE), CO_NMT_OPERATIONAL);
    assert_int_equal(REC.n_state, 1);
    assert_int_equal(REC.n_reset, 0);
}

static void malformed_nmt_ignored(void **state)
{
    co_frame_t eff;
    static const uint8_t start[2] = {0x01, 0x01};

    tb_send(BUS, "000 01");             /* DLC 1 */
    tb_send(BUS, "000 01 01 00");       /* DLC 3 */
    tb_send(BUS, "000 01 01 00 00 00 00 00 00"); /* DLC 8 */
    tb_send(BUS, "000");                /* DLC 0 */
    tb_send(BUS, "000 R2");             /* remote request with DLC 2 */
    tb_send(BUS, "000 R");
    co_frame_set(&eff, CO_FRAME_EFF | 0x000U, start, 2U); /* 29-bit identifier 0 */
    tb_send_frame(BUS, &eff);
    assert_int_equal(co_node_nmt_state(NODE), CO_NMT_PRE_OPERATIONAL);
    tb_send(BUS, "000 81");
    tb_send(BUS, "000 82 01 01");
    tb_send(BUS, "000 R2");
    tb_expect_none(BUS);
    /* unknown command specifiers: ignored, no answer */
    tb_send(BUS, "000 00 01");
    tb_send(BUS, "000 03 01");
    tb_send(BUS, "000 04 01");
    tb_send(BUS, "000 FF 00");
    tb_expect_none(BUS);
    assert_int_equal(co_node_nmt_state(NODE), CO_NMT_PRE_OPERATIONAL);
    assert_int_equal(REC.n_state, 0);
    assert_int_equal(REC.n_reset, 0);
}

static void local_command_same_as_received(void **state)
{
    co_node_nmt_command(NODE, 0x01U, BUS->now);
    assert_int_equal(co_node_nmt_state(NODE), CO_NMT_OPERATIONAL);
    co_node_nmt_command(NODE, 0x82U, BUS->now);
    tb_expect(BUS, "701 00");
    tb_expect_none(BUS);
    assert_int_equal(co_node_nmt_state(NODE), CO_NMT_PRE_OPERATIONAL);
}

/* ------------------------------------------------------ service matrix */

static void sdo_only_in_pre_operational_and_operational(void **state)
{
    /* Pre-operational */
    tb_xfer(BUS, "601 40 00 10 00 00 00 00 00", "581 43 00 10 00 92 01 02 00");
    /* Operational */
    tb_send(BUS, "000 01 01");
    tb_xfer(BUS, "601 40 00 10 00 00 00 00 00", "581 43 00 10 00 92 01 02 00");
    tb_xfer(BUS, "601 23 04 20 00 04 03 02 01", "581 60 04 20 00 00 00 00 00");
    /* Stopped: no answer at all, and no write happens */
    tb_send(BUS, "000 02 01");
    tb_send(BUS, "601 40 00 10 00 00 00 00 00");
    tb_send(BUS, "601 23 04 20 00 AA BB CC DD");
    tb_send(BUS, "601 40 00 10 00"); /* not even the abort for a bad length */
    tb_expect_none(BUS);
    assert_int_equal(RAMV.u32, 0x01020304UL);
    /* back to Pre-operational: SDO answers again */
    tb_send(BUS, "000 80 01");
    tb_xfer(BUS, "601 40 04 20 00 00 00 00 00", "581 43 04 20 00 04 03 02 01");
}

static void stop_ends_an_open_sdo_transfer_silently(void **state)
{
    tb_xfer(BUS, "601 21 12 20 00 0A 00 00 00", "581 60 12 20 00 00 00 00 00");
    tb_send(BUS, "000 02 01");
    tb_expect_none(BUS);
    /* no SDO timeout abort later either */
    tb_advance(BUS, 3000000U);
    tb_expect_none(BUS);
    tb_send(BUS, "000 80 01");
    /* the server is idle: a new request is served (an open transfer would
     * refuse it with 0x05040001) */
    tb_xfer(BUS, "601 40 12 20 00 00 00 00 00", "581 41 12 20 00 05 00 00 00");
    tb_xfer(BUS, "601 60 00 00 00 00 00 00 00", "581 05 68 65 6C 6C 6F 00 00");
    assert_string_equal(RAMV.vstr, "hello");
}

static void emcy_not_in_stopped(void **state)
{
    tb_send(BUS, "000 02 01");
    co_emcy_raise(NODE, 0x5000U, CO_ERREG_MANUFACTURER, NULL);
    tb_expect_none(BUS);
    /* the error is active and recorded all the same */
    assert_true(co_emcy_is_active(NODE, 0x5000U));
    assert_int_equal(RAMV.errreg, 0x81);
    assert_int_equal(RAMV.hist_n, 1);
    co_emcy_clear(NODE, 0x5000U);
    tb_expect_none(BUS);
    /* and nothing is sent late when the node leaves Stopped */
    tb_send(BUS, "000 01 01");
    tb_advance(BUS, 1000000U);
    tb_expect_none(BUS);
    co_emcy_raise(NODE, 0x5000U, CO_ERREG_MANUFACTURER, NULL);
    tb_expect(BUS, "081 00 50 81 00 00 00 00 00");
    tb_expect_none(BUS);
}

static void error_control_works_in_stopped(void **state)
{
    tb_xfer(BUS, "601 2B 17 10 00 64 00 00 00", "581 60 17 10 00 00 00 00 00");
    tb_send(BUS, "000 02 01");
    tb_advance(BUS, 100000U);
    tb_expect(BUS, "701 04");
    tb_expect_none(BUS);
    tb_send(BUS, "000 01 01");
    tb_advance(BUS, 100000U);
    tb_expect(BUS, "701 05");
    tb_expect_none(BUS);
}

/* --------------------------------------------------------------- resets */

static void reset_communication_restores_communication_objects(void **state)
{
    /* change communication parameters and an application value */
    tb_xfer(BUS, "601 2B 17 10 00 64 00 00 00", "581 60 17 10 00 00 00 00 00");
    tb_xfer(BUS, "601 23 14 10 00 85 00 00 80", "581 60 14 10 00 00 00 00 00");
    tb_xfer(BUS, "601 2B 0C 10 00 E8 03 00 00", "581 60 0C 10 00 00 00 00 00");
    tb_xfer(BUS, "601 23 16 10 01 F4 01 05 00", "581 60 16 10 01 00 00 00 00");
    tb_xfer(BUS, "601 23 04 20 00 04 03 02 01", "581 60 04 20 00 00 00 00 00");
    tb_send(BUS, "000 01 01");
    tb_advance(BUS, 100000U);
    tb_expect(BUS, "701 05");
    tb_expect_none(BUS);

    tb_send(BUS, "000 82 01");
    tb_expect(BUS, "701 00");
    tb_expect_none(BUS);
    assert_int_equal(co_node_nmt_state(NODE), CO_NMT_PRE_OPERATIONAL);
    /* 0x1000..0x1FFF: back to their defaults */
    tb_xfer(BUS, "601 40 17 10 00 00 00 00 00", "581 4B 17 10 00 00 00 00 00");
    tb_xfer(BUS, "601 40 14 10 00 00 00 00 00", "581 43 14 10 00 81 00 00 00");
    tb_xfer(BUS, "601 40 0C 10 00 00 00 00 00", "581 4B 0C 10 00 00 00 00 00");
    tb_xfer(BUS, "601 40 16 10 01 00 00 00 00", "581 43 16 10 01 00 00 00 00");
    /* application values: kept */
    tb_xfer(BUS, "601 40 04 20 00 00 00 00 00", "581 43 04 20 00 04 03 02 01");
    /* the heartbeat has stopped, the EMCY is valid again on 0x81 */
    tb_advance(BUS, 1000000U);
    tb_expect_none(BUS);
    co_emcy_raise(NODE, 0x6100U, 0U, NULL);
    tb_expect(BUS, "081 00 61 01 00 00 00 00 00");
    tb_expect_none(BUS);
    assert_int_equal(REC.n_reset, 1);
    assert_int_equal(REC.resets[0], CO_RESET_COMMUNICATION);
}

static void reset_communication_keeps_errors_and_history(void **state)
{
    static const uint8_t mfr[5] = {0x11, 0x22, 0x33, 0x44, 0x55};
    co_emcy_raise(NODE, 0x5000U, CO_ERREG_MANUFACTURER, mfr);
    tb_expect(BUS, "081 00 50 81 11 22 33 44 55");
    tb_send(BUS, "000 82 01");
    tb_expect(BUS, "701 00");
    tb_expect_none(BUS);
    /* the application's error is still there, and so is the history
     * (0x1001 and 0x1003 are not reset by a communication reset) */
    assert_true(co_emcy_is_active(NODE, 0x5000U));
    tb_xfer(BUS, "601 40 01 10 00 00 00 00 00", "581 4F 01 10 00 81 00 00 00");
    tb_xfer(BUS, "601 40 03 10 00 00 00 00 00", "581 4F 03 10 00 01 00 00 00");
    tb_xfer(BUS, "601 40 03 10 01 00 00 00 00", "581 43 03 10 01 00 50 11 22");
    co_emcy_clear(NODE, 0x5000U);
    tb_expect(BUS, "081 00 00 00 00 00 00 00 00");
    tb_expect_none(BUS);
}

static void reset_node_restores_everything(void **state)
{
    tb_xfer(BUS, "601 23 04 20 00 04 03 02 01", "581 60 04 20 00 00 00 00 00");
    tb_xfer(BUS, "601 2B 17 10 00 64 00 00 00", "581 60 17 10 00 00 00 00 00");
    tb_xfer(BUS, "601 2B 02 20 00 CD AB 00 00", "581 60 02 20 00 00 00 00 00");
    co_emcy_raise(NODE, 0x2310U, CO_ERREG_CURRENT, NULL);
    co_emcy_raise(NODE, 0x4210U, CO_ERREG_TEMPERATURE, NULL);
    tb_expect(BUS, "081 10 23 03 00 00 00 00 00");
    tb_expect(BUS, "081 10 42 0B 00 00 00 00 00");
    tb_expect_none(BUS);
    tb_xfer(BUS, "601 40 03 10 00 00 00 00 00", "581 4F 03 10 00 02 00 00 00");

    tb_send(BUS, "000 81 01");
    /* boot-up only: no EMCY 0000 for errors that a node reset forgets */
    tb_expect(BUS, "701 00");
    tb_expect_none(BUS);
    tb_xfer(BUS, "601 40 04 20 00 00 00 00 00", "581 43 04 20 00 EF BE AD DE");
    tb_xfer(BUS, "601 40 02 20 00 00 00 00 00", "581 4B 02 20 00 34 12 00 00");
    tb_xfer(BUS, "601 40 17 10 00 00 00 00 00", "581 4B 17 10 00 00 00 00 00");
    /* no active error, empty history */
    assert_false(co_emcy_is_active(NODE, 0x2310U));
    assert_false(co_emcy_is_active(NODE, 0x4210U));
    tb_xfer(BUS, "601 40 01 10 00 00 00 00 00", "581 4F 01 10 00 00 00 00 00");
    tb_xfer(BUS, "601 40 03 10 00 00 00 00 00", "581 4F 03 10 00 00 00 00 00");
    tb_xfer(BUS, "601 40 03 10 01 00 00 00 00", "581 80 03 10 01 24 00 00 08");
    /* the same code may be raised again and is sent again */
    co_emcy_raise(NODE, 0x2310U, CO_ERREG_CURRENT, NULL);
    tb_expect(BUS, "081 10 23 03 00 00 00 00 00");
    tb_expect_none(BUS);
    assert_int_equal(REC.n_reset, 1);
    assert_int_equal(REC.resets[0], CO_RESET_NODE);
}

/* ------------------------------------------------------------ callbacks */

static void reset_callback_runs_after_restore_before_bootup(void **state)
{
    tb_xfer(BUS, "601 2B 17 10 00 64 00 00 00", "581 60 17 10 00 00 00 00 00");
    tb_xfer(BUS, "601 23 04 20 00 04 03 02 01", "581 60 04 20 00 00 00 00 00");
    REC.n_state = 0;

    tb_send(BUS, "000 82 01");
    assert_int_equal(REC.n_reset, 1);
    assert_int_equal(REC.resets[0], CO_RESET_COMMUNICATION);
    assert_int_equal(REC.hb_prod_at_reset[0], 0);          /* already restored */
    assert_int_equal(REC.u32_at_reset[0], 0x01020304UL);   /* not touched */
    assert_int_equal(REC.log_at_reset[0], BUS->read_pos); /* boot-up not yet sent */
    tb_expect(BUS, "701 00");
    tb_expect_none(BUS);

    tb_send(BUS, "000 81 01");
    assert_int_equal(REC.n_reset, 2);
    assert_int_equal(REC.resets[1], CO_RESET_NODE);
    assert_int_equal(REC.u32_at_reset[1], 0xDEADBEEFUL);
    assert_int_equal(REC.log_at_reset[1], BUS->read_pos);
    tb_expect(BUS, "701 00");
    tb_expect_none(BUS);
    /* each reset ends in Pre-operational, reported once */
    assert_int_equal(REC.n_state, 2);
    assert_int_equal(REC.states[0], CO_NMT_PRE_OPERATIONAL);
    assert_int_equal(REC.states[1], CO_NMT_PRE_OPERATIONAL);
}

static void state_callback_sees_new_state(void **state)
{
    tb_send(BUS, "000 02 00");
    assert_int_equal(REC.n_state, 1);
    assert_int_equal(REC.states[0], CO_NMT_STOPPED);
    assert_int_equal(co_node_nmt_state(NODE), CO_NMT_STOPPED);
    /* unchanged state: no callback */
    tb_send(BUS, "000 02 01");
    assert_int_equal(REC.n_state, 1);
}

/* -------------------------------------------------------------- options */

static void option_no_bootup(void **state)
{
    fx_t *fx = FX;
    fx->dev.set = (co_settings_t){.nmt.bootup = CO_BOOTUP_NONE};
    start_cb(&fx->n, &fx->r, BUS, 0, 1, &fx->dev);
    tb_expect_none(BUS);
    assert_int_equal(co_node_nmt_state(NODE), CO_NMT_PRE_OPERATIONAL);
    tb_send(BUS, "000 01 01");
    tb_send(BUS, "000 82 01");
    tb_send(BUS, "000 81 01");
    tb_expect_none(BUS);
    assert_int_equal(co_node_nmt_state(NODE), CO_NMT_PRE_OPERATIONAL);
    /* everything else is unchanged */
    tb_xfer(BUS, "601 40 00 10 00 00 00 00 00", "581 43 00 10 00 92 01 02 00");
}

static void option_boot_emcy(void **state)
{
    fx_t *fx = FX;
    static const uint8_t v819d[5] = {'V', '8', '1', '9', 'd'};
    fx->dev.set = (co_settings_t){.nmt.boot_emcy = 1U};
    fx->dev.boot_emcy_data = v819d;
    start_cb(&fx->n, &fx->r, BUS, 0, 1, &fx->dev);
    /* SSD 630: boot-up, then EMCY 0000 carrying the firmware version */
    tb_expect(BUS, "701 00");
    tb_expect(BUS, "081 00 00 00 56 38 31 39 64");
    tb_expect_none(BUS);
    /* after every reset too */
    tb_send(BUS, "000 82 01");
    tb_expect(BUS, "701 00");
    tb_expect(BUS, "081 00 00 00 56 38 31 39 64");
    tb_expect_none(BUS);
    tb_send(BUS, "000 81 01");
    tb_expect(BUS, "701 00");
    tb_expect(BUS, "081 00 00 00 56 38 31 39 64");
    tb_expect_none(BUS);
    /* it is not an error: nothing recorded */
    tb_xfer(BUS, "601 40 03 10 00 00 00 00 00", "581 4F 03 10 00 00 00 00 00");
}

static void option_boot_emcy_with_bootup_suppressed(void **state)
{
    fx_t *fx = FX;
    static const uint8_t v819d[5] = {'V', '8', '1', '9', 'd'};
    fx->dev.set = (co_settings_t){.nmt.boot_emcy = 1U, .nmt.bootup = CO_BOOTUP_NONE};
    fx->dev.boot_emcy_data = v819d;
    start_cb(&fx->n, &fx->r, BUS, 0, 3, &fx->dev);
    tb_expect(BUS, "083 00 00 00 56 38 31 39 64");
    tb_expect_none(BUS);
}

/* ------------------------------------------------------------ two nodes */

static void two_nodes_on_one_bus(void **state)
{
    fx_t *fx = FX;
    start_cb(&fx->n, &fx->r, BUS, 0, 1, NULL);
    start_cb(&fx->n2, &fx->r2, BUS, 1, 2, NULL);
    tb_expect(BUS, "701 00");
    tb_expect(BUS, "702 00");
    tb_expect_none(BUS);

    /* each answers its own SDO only */
    tb_xfer(BUS, "601 40 0B 10 00 00 00 00 00", "581 43 0B 10 00 01 00 00 00");
    tb_xfer(BUS, "602 40 0B 10 00 00 00 00 00", "582 43 0B 10 00 02 00 00 00");
    tb_send(BUS, "603 40 0B 10 00 00 00 00 00");
    tb_expect_none(BUS);
    /* separate dictionaries */
    tb_xfer(BUS, "602 23 04 20 00 02 00 00 00", "582 60 04 20 00 00 00 00 00");
    tb_xfer(BUS, "601 40 04 20 00 00 00 00 00", "581 43 04 20 00 EF BE AD DE");
    tb_xfer(BUS, "602 40 04 20 00 00 00 00 00", "582 43 04 20 00 02 00 00 00");

    /* broadcast NMT reaches both, addressed NMT only one */
    tb_send(BUS, "000 01 00");
    assert_int_equal(co_node_nmt_state(&fx->n.node), CO_NMT_OPERATIONAL);
    assert_int_equal(co_node_nmt_state(&fx->n2.node), CO_NMT_OPERATIONAL);
    tb_send(BUS, "000 02 02");
    assert_int_equal(co_node_nmt_state(&fx->n.node), CO_NMT_OPERATIONAL);
    assert_int_equal(co_node_nmt_state(&fx->n2.node), CO_NMT_STOPPED);
    tb_send(BUS, "602 40 0B 10 00 00 00 00 00");
    tb_expect_none(BUS);
    tb_send(BUS, "000 01 00");
    tb_send(BUS, "000 82 00");
    tb_expect(BUS, "701 00");
    tb_expect(BUS, "702 00");
    tb_expect_none(BUS);
    assert_int_equal(co_node_nmt_state(&fx->n.node), CO_NMT_PRE_OPERATIONAL);
    assert_int_equal(co_node_nmt_state(&fx->n2.node), CO_NMT_PRE_OPERATIONAL);
    tb_pump(BUS); /* the boot-ups reach the other node: nobody listens yet */
    tb_expect_none(BUS);

    /* node 2 consumes node 1's heartbeat: 0x1016 sub1 = node 1, 250 ms */
    tb_xfer(BUS, "602 23 16 10 01 FA 00 01 00", "582 60 16 10 01 00 00 00 00");
    tb_xfer(BUS, "601 2B 17 10 00 64 00 00 00", "581 60 17 10 00 00 00 00 00");
    tb_send(BUS, "000 01 00");
    for (int i = 0; i < 5; i++) {
        tb_advance(BUS, 100000U);
        tb_expect(BUS, "701 05");
        tb_pump(BUS);
    }
    tb_expect_none(BUS);
    assert_int_equal(FX->r2.n_hb, 1);
    assert_int_equal(FX->r2.hb_ev[0], CO_HB_STARTED);
    assert_int_equal(FX->r2.hb_id[0], 1);
    assert_int_equal(FX->r2.hb_state[0], CO_NMT_OPERATIONAL);
    /* node 1 reports Pre-operational: node 2 sees the state change */
    tb_send(BUS, "000 80 01");
    tb_advance(BUS, 100000U);
    tb_expect(BUS, "701 7F");
    tb_pump(BUS);
    assert_int_equal(FX->r2.n_hb, 2);
    assert_int_equal(FX->r2.hb_ev[1], CO_HB_STATE);
    assert_int_equal(FX->r2.hb_state[1], CO_NMT_PRE_OPERATIONAL);
    /* node 1 stops its heartbeat: node 2 times out 250 ms after the last one */
    tb_xfer(BUS, "601 2B 17 10 00 00 00 00 00", "581 60 17 10 00 00 00 00 00");
    tb_advance(BUS, 249999U);
    tb_expect_none(BUS);
    tb_advance(BUS, 1U + 1023U); /* (within 1023 us: co_hb.c) */
    tb_expect(BUS, "082 30 81 11 00 00 00 00 00");
    tb_expect_none(BUS);
    assert_int_equal(FX->r2.n_hb, 3);
    assert_int_equal(FX->r2.hb_ev[2], CO_HB_TIMEOUT);
    assert_int_equal(FX->r2.hb_id[2], 1);
    /* node 1 is not affected */
    assert_false(co_emcy_is_active(&fx->n.node, CO_EMCY_HB_GUARD));
    assert_true(co_emcy_is_active(&fx->n2.node, CO_EMCY_HB_GUARD));
    /* node 1 resets (boot-up): node 2 recovers */
    tb_send(BUS, "000 82 01");
    tb_expect(BUS, "701 00");
    tb_pump(BUS);
    tb_expect(BUS, "082 00 00 00 00 00 00 00 00");
    tb_expect_none(BUS);
    assert_int_equal(FX->r2.hb_ev[3], CO_HB_RECOVERED);
    assert_int_equal(FX->r2.hb_ev[4], CO_HB_STATE);
    assert_int_equal(FX->r2.hb_state[4], CO_NMT_INITIALISING);
    assert_int_equal(FX->r.n_hb, 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(bootup_then_pre_operational, setup_empty),
        cmocka_unit_test_setup(bootup_uses_own_node_id, setup_empty),
        cmocka_unit_test_setup(init_rejects_bad_node_id, setup_empty),
        cmocka_unit_test_setup(commands_for_own_id, setup),
        cmocka_unit_test_setup(commands_broadcast, setup),
        cmocka_unit_test_setup(commands_for_other_nodes_ignored, setup),
        cmocka_unit_test_setup(malformed_nmt_ignored, setup),
        cmocka_unit_test_setup(local_command_same_as_received, setup),
        cmocka_unit_test_setup(sdo_only_in_pre_operational_and_operational, setup),
        cmocka_unit_test_setup(stop_ends_an_open_sdo_transfer_silently, setup),
        cmocka_unit_test_setup(emcy_not_in_stopped, setup),
        cmocka_unit_test_setup(error_control_works_in_stopped, setup),
        cmocka_unit_test_setup(reset_communication_restores_communication_objects, setup),
        cmocka_unit_test_setup(reset_communication_keeps_errors_and_history, setup),
        cmocka_unit_test_setup(reset_node_restores_everything, setup),
        cmocka_unit_test_setup(reset_callback_runs_after_restore_before_bootup, setup),
        cmocka_unit_test_setup(state_callback_sees_new_state, setup),
        cmocka_unit_test_setup(option_no_bootup, setup_empty),
        cmocka_unit_test_setup(option_boot_emcy, setup_empty),
        cmocka_unit_test_setup(option_boot_emcy_with_bootup_suppressed, setup_empty),
        cmocka_unit_test_setup(two_nodes_on_one_bus, setup_empty),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
