/*
 * EMCY producer (CiA 301 7.2.7): the frame layout, the error register 0x1001,
 * the pre-defined error field 0x1003, COB-ID 0x1014, inhibit time 0x1015,
 * and the personality options that change when EMCY 0x0000 goes out.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "test_bus.h"
#include "test_dev.h"

typedef struct fx {
    tb_bus_t bus;
    td_node_t n;
    co_dev_t dev;
} fx_t;

static int setup(void **state)
{
    static fx_t fx;
    memset(&fx, 0, sizeof fx);
    tb_init(&fx.bus);
    fx.dev = td_dev;
    td_start(&fx.n, &fx.bus, 0, 1, NULL);
    tb_flush(&fx.bus);
    *state = &fx;
    return 0;
}

#define FX ((fx_t *)*state)
#define BUS (&FX->bus)
#define NODE (&FX->n.node)
#define RAMV (FX->n.ram)

/* Restart the node with the fixture's device copy, personality @p set. */
static void restart_with(void **state, const co_settings_t *set)
{
    FX->dev.set = *set;
    td_start(&FX->n, BUS, 0, 1, &FX->dev);
    tb_expect(BUS, "701 00");
    tb_expect_none(BUS);
}

static const uint8_t MFR[5] = {0x01, 0x02, 0x03, 0x04, 0x05};

/* ------------------------------------------------------------- frames */

static void raise_and_clear_frames(void **state)
{
    /* code little-endian, error register, 5 manufacturer bytes */
    co_emcy_raise(NODE, 0x2310U, CO_ERREG_CURRENT, MFR);
    tb_expect(BUS, "081 10 23 03 01 02 03 04 05");
    tb_expect_none(BUS);
    assert_true(co_emcy_is_active(NODE, 0x2310U));
    tb_xfer(BUS, "601 40 01 10 00 00 00 00 00", "581 4F 01 10 00 03 00 00 00");
    co_emcy_clear(NODE, 0x2310U);
    tb_expect(BUS, "081 00 00 00 00 00 00 00 00");
    tb_expect_none(BUS);
    assert_false(co_emcy_is_active(NODE, 0x2310U));
    tb_xfer(BUS, "601 40 01 10 00 00 00 00 00", "581 4F 01 10 00 00 00 00 00");
    /* NULL manufacturer data: zeros; no register bits: generic only */
    co_emcy_raise(NODE, 0xFF01U, 0U, NULL);
    tb_expect(BUS, "081 01 FF 01 00 00 00 00 00");
    tb_expect_none(BUS);
}

static void emcy_cob_follows_node_id(void **state)
{
    td_start(&FX->n, BUS, 0, 0x23, NULL);
    tb_expect(BUS, "723 00");
    co_emcy_raise(NODE, 0x3210U, CO_ERREG_VOLTAGE, NULL);
    tb_expect(BUS, "0A3 10 32 05 00 00 00 00 00");
    tb_expect_none(BUS);
    tb_xfer(BUS, "623 40 14 10 00 00 00 00 00", "5A3 43 14 10 00 A3 00 00 00");
}

static void error_register_is_or_of_active_errors(void **state)
{
    co_emcy_raise(NODE, 0x2310U, CO_ERREG_CURRENT, NULL);
    tb_expect(BUS, "081 10 23 03 00 00 00 00 00");
    co_emcy_raise(NODE, 0x4210U, CO_ERREG_TEMPERATURE, NULL);
    tb_expect(BUS, "081 10 42 0B 00 00 00 00 00");
    co_emcy_raise(NODE, 0x8110U, CO_ERREG_COMM, NULL);
    tb_expect(BUS, "081 10 81 1B 00 00 00 00 00");
    tb_expect_none(BUS);
    tb_xfer(BUS, "601 40 01 10 00 00 00 00 00", "581 4F 01 10 00 1B 00 00 00");
    /* strict CiA 301: EMCY 0000 only when the last error clears */
    co_emcy_clear(NODE, 0x4210U);
    tb_expect_none(BUS);
    tb_xfer(BUS, "601 40 01 10 00 00 00 00 00", "581 4F 01 10 00 13 00 00 00");
    co_emcy_clear(NODE, 0x2310U);
    tb_expect_none(BUS);
    tb_xfer(BUS, "601 40 01 10 00 00 00 00 00", "581 4F 01 10 00 11 00 00 00");
    co_emcy_clear(NODE, 0x8110U);
    tb_expect(BUS, "081 00 00 00 00 00 00 00 00");
    tb_expect_none(BUS);
    tb_xfer(BUS, "601 40 01 10 00 00 00 00 00", "581 4F 01 10 00 00 00 00 00");
    /* 0x1001 is read-only */
    tb_xfer(BUS, "601 2F 01 10 00 00 00 00 00", "581 80 01 10 00 02 00 01 06");
}

static void shared_register_bit_stays_while_any_error_needs_it(void **state)
{
    co_emcy_raise(NODE, 0x2310U, CO_ERREG_CURRENT, NULL);
    co_emcy_raise(NODE, 0x2320U, CO_ERREG_CURRENT, NULL);
    tb_expect(BUS, "081 10 23 03 00 00 00 00 00");
    tb_expect(BUS, "081 20 23 03 00 00 00 00 00");
    co_emcy_clear(NODE, 0x2310U);
    tb_xfer(BUS, "601 40 01 10 00 00 00 00 00", "581 4F 01 10 00 03 00 00 00");
}

static void raising_an_active_code_does_nothing(void **state)
{
    co_emcy_raise(NODE, 0x2310U, CO_ERREG_CURRENT, MFR);
    tb_expect(BUS, "081 10 23 03 01 02 03 04 05");
    co_emcy_raise(NODE, 0x2310U, CO_ERREG_CURRENT, MFR);
    co_emcy_raise(NODE, 0x2310U, CO_ERREG_VOLTAGE, NULL); /* not even other bits */
    tb_expect_none(BUS);
    tb_xfer(BUS, "601 40 01 10 00 00 00 00 00", "581 4F 01 10 00 03 00 00 00");
    tb_xfer(BUS, "601 40 03 10 00 00 00 00 00", "581 4F 03 10 00 01 00 00 00");
    /* clearing something that is not active does nothing either */
    co_emcy_clear(NODE, 0x3210U);
    co_emcy_clear(NODE, 0x0000U);
    tb_expect_none(BUS);
    assert_true(co_emcy_is_active(NODE, 0x2310U));
    /* and 0x0000 is not an error code */
    co_emcy_raise(NODE, 0x0000U, CO_ERREG_CURRENT, NULL);
    tb_expect_none(BUS);
    assert_false(co_emcy_is_active(NODE, 0x0000U));
}

/* ------------------------------------------------------------ history */

static void history_newest_first(void **state)
{
    static const uint8_t m2[5] = {0xAA, 0xBB, 0xCC, 0xDD, 0xEE};
    co_emcy_raise(NODE, 0x2310U, CO_ERREG_CURRENT, MFR);
    co_emcy_raise(NODE, 0x5000U, CO_ERREG_MANUFACTURER, m2);
    tb_flush(BUS);
    tb_xfer(BUS, "601 40 03 10 00 00 00 00 00", "581 4F 03 10 00 02 00 00 00");
    /* bits 0..15 the code, 16..31 the first two manufacturer bytes */
    tb_xfer(BUS, "601 40 03 10 01 00 00 00 00", "581 43 03 10 01 00 50 AA BB");
    tb_xfer(BUS, "601 40 03 10 02 00 00 00 00", "581 43 03 10 02 10 23 01 02");
    /* beyond the number of errors: no data */
    tb_xfer(BUS, "601 40 03 10 03 00 00 00 00", "581 80 03 10 03 24 00 00 08");
    tb_xfer(BUS, "601 40 03 10 08 00 00 00 00", "581 80 03 10 08 24 00 00 08");
    /* beyond the array */
    tb_xfer(BUS, "601 40 03 10 09 00 00 00 00", "581 80 03 10 09 11 00 09 06");
    /* a cleared error stays in the history */
    co_emcy_clear(NODE, 0x2310U);
    co_emcy_clear(NODE, 0x5000U);
    tb_flush(BUS);
    tb_xfer(BUS, "601 40 03 10 00 00 00 00 00", "581 4F 03 10 00 02 00 00 00");
}

static void history_depth_eight(void **state)
{
    for (uint16_t i = 0; i < 10U; i++) {
        co_emcy_raise(NODE, (uint16_t)(0x1000U + i), 0U, NULL);
    }
    tb_flush(BUS);
    tb_xfer(BUS, "601 40 03 10 00 00 00 00 00", "581 4F 03 10 00 08 00 00 00");
    tb_xfer(BUS, "601 40 03 10 01 00 00 00 00", "581 43 03 10 01 09 10 00 00");
    tb_xfer(BUS, "601 40 03 10 02 00 00 00 00", "581 43 03 10 02 08 10 00 00");
    tb_xfer(BUS, "601 40 03 10 08 00 00 00 00", "581 43 03 10 08 02 10 00 00");
}

static void history_write_zero_clears(void **state)
{
    co_emcy_raise(NODE, 0x2310U, CO_ERREG_CURRENT, MFR);
    co_emcy_raise(NODE, 0x3210U, CO_ERREG_VOLTAGE, NULL);
    tb_flush(BUS);
    /* only 0 may be written */
    tb_xfer(BUS, "601 2F 03 10 00 01 00 00 00", "581 80 03 10 00 30 00 09 06");
    tb_xfer(BUS, "601 2F 03 10 00 02 00 00 00", "581 80 03 10 00 30 00 09 06");
    tb_xfer(BUS, "601 40 03 10 00 00 00 00 00", "581 4F 03 10 00 02 00 00 00");
    /* the entries are read-only */
    tb_xfer(BUS, "601 23 03 10 01 00 00 00 00", "581 80 03 10 01 02 00 01 06");
    tb_xfer(BUS, "601 2F 03 10 00 00 00 00 00", "581 60 03 10 00 00 00 00 00");
    tb_xfer(BUS, "601 40 03 10 00 00 00 00 00", "581 4F 03 10 00 00 00 00 00");
    tb_xfer(BUS, "601 40 03 10 01 00 00 00 00", "581 80 03 10 01 24 00 00 08");
    /* clearing the history does not clear the errors */
    assert_true(co_emcy_is_active(NODE, 0x2310U));
    tb_xfer(BUS, "601 40 01 10 00 00 00 00 00", "581 4F 01 10 00 07 00 00 00");
    tb_expect_none(BUS);
    /* it fills again from sub1 */
    co_emcy_raise(NODE, 0x4210U, CO_ERREG_TEMPERATURE, NULL);
    tb_flush(BUS);
    tb_xfer(BUS, "601 40 03 10 00 00 00 00 00", "581 4F 03 10 00 01 00 00 00");
    tb_xfer(BUS, "601 40 03 10 01 00 00 00 00", "581 43 03 10 01 10 42 00 00");
    tb_xfer(BUS, "601 40 03 10 02 00 00 00 00", "581 80 03 10 02 24 00 00 08");
}

/* ------------------------------------------------------------ options */

static void option_reset_partial(void **state)
{
    restart_with(state, &(co_settings_t){.emcy.reset = CO_EMCY_RESET_EACH_CLEAR});
    co_emcy_raise(NODE, 0x2310U, CO_ERREG_CURRENT, NULL);
    co_emcy_raise(NODE, 0x4210U, CO_ERREG_TEMPERATURE, NULL);
    tb_expect(BUS, "081 10 23 03 00 00 00 00 00");
    tb_expect(BUS, "081 10 42 0B 00 00 00 00 00");
    /* a partial clear: EMCY 0000 with what remains */
    co_emcy_clear(NODE, 0x2310U);
    tb_expect(BUS, "081 00 00 09 00 00 00 00 00");
    tb_expect_none(BUS);
    co_emcy_clear(NODE, 0x4210U);
    tb_expect(BUS, "081 00 00 00 00 00 00 00 00");
    tb_expect_none(BUS);
}

static void option_state_pair(void **state)
{
    restart_with(state, &(co_settings_t){.emcy.state_pair = 1U});
    /* Kollmorgen: every error EMCY is followed by EMCY 0000 with the register */
    co_emcy_raise(NODE, 0x2310U, CO_ERREG_CURRENT, MFR);
    tb_expect(BUS, "081 10 23 03 01 02 03 04 05");
    tb_expect(BUS, "081 00 00 03 00 00 00 00 00");
    tb_expect_none(BUS);
    co_emcy_raise(NODE, 0x4210U, CO_ERREG_TEMPERATURE, NULL);
    tb_expect(BUS, "081 10 42 0B 00 00 00 00 00");
    tb_expect(BUS, "081 00 00 0B 00 00 00 00 00");
    tb_expect_none(BUS);
    /* the error stays active */
    assert_true(co_emcy_is_active(NODE, 0x2310U));
    co_emcy_clear(NODE, 0x2310U);
    tb_expect_none(BUS);
    co_emcy_clear(NODE, 0x4210U);
    tb_expect(BUS, "081 00 00 00 00 00 00 00 00");
    tb_expect_none(BUS);
}

static void option_erreg_no_generic(void **state)
{
    restart_with(state, &(co_settings_t){.emcy.generic_bit = CO_ERREG_GENERIC_UNCLASSIFIED});
    /* Kollmorgen: an error sets the bits it names, not the generic bit */
    co_emcy_raise(NODE, 0x4310U, CO_ERREG_TEMPERATURE, NULL);
    tb_expect(BUS, "081 10 43 08 00 00 00 00 00");
    tb_xfer(BUS, "601 40 01 10 00 00 00 00 00", "581 4F 01 10 00 08 00 00 00");
    co_emcy_raise(NODE, 0x3110U, CO_ERREG_VOLTAGE, NULL);
    tb_expect(BUS, "081 10 31 0C 00 00 00 00 00");
    /* an error that names no bit: the generic bit stands for it */
    co_emcy_raise(NODE, 0x5400U, 0U, NULL);
    tb_expect(BUS, "081 00 54 0D 00 00 00 00 00");
    tb_expect_none(BUS);
    co_emcy_clear(NODE, 0x5400U);
    tb_xfer(BUS, "601 40 01 10 00 00 00 00 00", "581 4F 01 10 00 0C 00 00 00");
    co_emcy_clear(NODE, 0x4310U);
    tb_xfer(BUS, "601 40 01 10 00 00 00 00 00", "581 4F 01 10 00 04 00 00 00");
    co_emcy_clear(NODE, 0x3110U);
    tb_expect(BUS, "081 00 00 00 00 00 00 00 00");
    tb_expect_none(BUS);
    tb_xfer(BUS, "601 40 01 10 00 00 00 00 00", "581 4F 01 10 00 00 00 00 00");
}

static void option_erreg_no_generic_with_state_pair(void **state)
{
    static const uint8_t cat1[5] = {0x01, 0x00, 0x00, 0x00, 0x00};
    static const uint8_t cat2[5] = {0x02, 0x00, 0x00, 0x00, 0x00};

    /* the Kollmorgen EMCY example: 4310h with category 1, then the state
     * report with the register (08h, not 09h) */
    restart_with(state, &(co_settings_t){.emcy.generic_bit = CO_ERREG_GENERIC_UNCLASSIFIED, .emcy.state_pair = 1U, .emcy.reset = CO_EMCY_RESET_EACH_CLEAR, .emcy.history = CO_HISTORY_CODE_ONLY});
    co_emcy_raise(NODE, 0x4310U, CO_ERREG_TEMPERATURE, cat1);
    tb_expect(BUS, "081 10 43 08 01 00 00 00 00");
    tb_expect(BUS, "081 00 00 08 00 00 00 00 00");
    co_emcy_raise(NODE, 0x3110U, CO_ERREG_VOLTAGE, cat2);
    tb_expect(BUS, "081 10 31 0C 02 00 00 00 00");
    tb_expect(BUS, "081 00 00 0C 00 00 00 00 00");
    co_emcy_clear(NODE, 0x4310U);
    tb_expect(BUS, "081 00 00 04 00 00 00 00 00");
    tb_expect_none(BUS);
}

static void option_history_code_only(void **state)
{
    static const uint8_t cat[5] = {0x01, 0x00, 0x00, 0x00, 0x00};

    restart_with(state, &(co_settings_t){.emcy.history = CO_HISTORY_CODE_ONLY});
    /* the manufacturer bytes still go out in the EMCY ... */
    co_emcy_raise(NODE, 0x2310U, CO_ERREG_CURRENT, MFR);
    tb_expect(BUS, "081 10 23 03 01 02 03 04 05");
    co_emcy_raise(NODE, 0x4310U, CO_ERREG_TEMPERATURE, cat);
    tb_expect(BUS, "081 10 43 0B 01 00 00 00 00");
    tb_expect_none(BUS);
    /* ... but 0x1003 holds the bare code (CiA 301 would give 0x00014310
     * and 0x02012310) */
    tb_xfer(BUS, "601 40 03 10 00 00 00 00 00", "581 4F 03 10 00 02 00 00 00");
    tb_xfer(BUS, "601 40 03 10 01 00 00 00 00", "581 43 03 10 01 10 43 00 00");
    tb_xfer(BUS, "601 40 03 10 02 00 00 00 00", "581 43 03 10 02 10 23 00 00");
}

/* ------------------------------------------- manufacturer bytes callback */

static unsigned mfr_calls;

/* A device's emcy_mfr: code high byte, a marker, and 0x1001 as it is when
 * called (the error is already in it). */
static void fill_mfr(void *ctx, co_node_t *node, uint16_t code, uint8_t mfr[5])
{
    const uint8_t *reg = (const uint8_t *)co_od_value_ptr(node, 0x1001U, 0U);

    (void)ctx;
    mfr_calls++;
    assert_memory_equal(mfr, "\0\0\0\0\0", 5);
    mfr[0] = (uint8_t)(code >> 8);
    mfr[1] = 0xC0U;
    mfr[2] = *reg;
}

static void emcy_mfr_fills_the_cores_own_emcys(void **state)
{
    co_node_callbacks_t cb;

    memset(&cb, 0, sizeof cb);
    cb.emcy_mfr = fill_mfr;
    mfr_calls = 0U;
    td_start_cb(&FX->n, BUS, 0, 1, NULL, &cb);
    tb_expect(BUS, "701 00");
    /* a SYNC of the wrong length: the core's EMCY 0x8240 */
    tb_send(BUS, "080 01");
    tb_expect(BUS, "081 40 82 11 82 C0 11 00 00");
    tb_expect_none(BUS);
    assert_int_equal(mfr_calls, 1U);
    /* 0x1003: bytes 3-4 above the code */
    tb_xfer(BUS, "601 40 03 10 01 00 00 00 00", "581 43 03 10 01 40 82 82 C0");
    /* a heartbeat consumer (node 0x20, 100 ms) loses its producer: 0x8130 */
    tb_xfer(BUS, "601 23 16 10 01 64 00 20 00", "581 60 16 10 01 00 00 00 00");
    tb_send(BUS, "720 05");
    tb_advance(BUS, 100000 + 1023); /* (a consumer: within 1023 us, co_hb.c) */
    tb_expect(BUS, "081 30 81 11 81 C0 11 00 00");
    tb_expect_none(BUS);
    /* an error raised with its own data: not asked, the data as given */
    co_emcy_raise(NODE, 0x2310U, CO_ERREG_CURRENT, MFR);
    tb_expect(BUS, "081 10 23 13 01 02 03 04 05");
    /* one raised without data by the application: filled the same way */
    co_emcy_raise(NODE, 0x4210U, CO_ERREG_TEMPERATURE, NULL);
    tb_expect(BUS, "081 10 42 1B 42 C0 1B 00 00");
    tb_expect_none(BUS);
    assert_int_equal(mfr_calls, 3U);
    /* error resets (EMCY 0x0000) are not filled */
    co_emcy_clear(NODE, 0x2310U);
    co_emcy_clear(NODE, 0x4210U);
    co_emcy_clear(NODE, 0x8240U);
    tb_send(BUS, "720 05");
    tb_expect(BUS, "081 00 00 00 00 00 00 00 00");
    tb_expect_none(BUS);
    assert_int_equal(mfr_calls, 3U);
}

/* ---------------------------------------------------------- COB-ID 0x1014 */

static void cob_id_valid_bit(void **state)
{
    /* bit 31 set: the EMCY does not exist, nothing is sent */
    tb_xfer(BUS, "601 23 14 10 00 81 00 00 80", "581 60 14 10 00 00 00 00 00");
    co_emcy_raise(NODE, 0x2310U, CO_ERREG_CURRENT, NULL);
    tb_expect_none(BUS);
    /* the error is recorded all the same */
    tb_xfer(BUS, "601 40 01 10 00 00 00 00 00", "581 4F 01 10 00 03 00 00 00");
    tb_xfer(BUS, "601 40 03 10 01 00 00 00 00", "581 43 03 10 01 10 23 00 00");
    co_emcy_clear(NODE, 0x2310U);
    tb_expect_none(BUS);
    /* valid again */
    tb_xfer(BUS, "601 23 14 10 00 81 00 00 00", "581 60 14 10 00 00 00 00 00");
    co_emcy_raise(NODE, 0x2310U, CO_ERREG_CURRENT, NULL);
    tb_expect(BUS, "081 10 23 03 00 00 00 00 00");
    tb_expect_none(BUS);
}

static void cob_id_change_only_while_invalid(void **state)
{
    /* valid: the CAN-ID may not change */
    tb_xfer(BUS, "601 23 14 10 00 90 00 00 00", "581 80 14 10 00 30 00 09 06");
    tb_xfer(BUS, "601 40 14 10 00 00 00 00 00", "581 43 14 10 00 81 00 00 00");
    /* rewriting the same value is fine */
    tb_xfer(BUS, "601 23 14 10 00 81 00 00 00", "581 60 14 10 00 00 00 00 00");
    /* invalidate, then change */
    tb_xfer(BUS, "601 23 14 10 00 81 00 00 80", "581 60 14 10 00 00 00 00 00");
    tb_xfer(BUS, "601 23 14 10 00 90 00 00 80", "581 60 14 10 00 00 00 00 00");
    tb_xfer(BUS, "601 23 14 10 00 90 00 00 00", "581 60 14 10 00 00 00 00 00");
    tb_xfer(BUS, "601 40 14 10 00 00 00 00 00", "581 43 14 10 00 90 00 00 00");
    co_emcy_raise(NODE, 0x2310U, CO_ERREG_CURRENT, NULL);
    tb_expect(BUS, "090 10 23 03 00 00 00 00 00");
    co_emcy_clear(NODE, 0x2310U);
    tb_expect(BUS, "090 00 00 00 00 00 00 00 00");
    tb_expect_none(BUS);
    /* changing straight from invalid to a new valid ID is fine too */
    tb_xfer(BUS, "601 23 14 10 00 90 00 00 80", "581 60 14 10 00 00 00 00 00");
    tb_xfer(BUS, "601 23 14 10 00 A0 00 00 00", "581 60 14 10 00 00 00 00 00");
    co_emcy_raise(NODE, 0x2310U, CO_ERREG_CURRENT, NULL);
    tb_expect(BUS, "0A0 10 23 03 00 00 00 00 00");
    tb_expect_none(BUS);
}

static void cob_id_bad_values(void **state)
{
    /* bit 29 (29-bit CAN-ID): not supported */
    tb_xfer(BUS, "601 23 14 10 00 81 00 00 A0", "581 80 14 10 00 30 00 09 06");
    /* bits 11..28 must be 0 with an 11-bit CAN-ID */
    tb_xfer(BUS, "601 23 14 10 00 81 00 00 80", "581 60 14 10 00 00 00 00 00");
    tb_xfer(BUS, "601 23 14 10 00 81 08 00 00", "581 80 14 10 00 30 00 09 06");
    tb_xfer(BUS, "601 23 14 10 00 81 00 00 81", "581 80 14 10 00 30 00 09 06");
    tb_xfer(BUS, "601 40 14 10 00 00 00 00 00", "581 43 14 10 00 81 00 00 80");
    /* wrong size */
    tb_xfer(BUS, "601 2B 14 10 00 81 00 00 00", "581 80 14 10 00 10 00 07 06");
}

/* ------------------------------------------------------- inhibit 0x1015 */

static void inhibit_time_delays(void **state)
{
    /* 10 x 100 us = 1 ms */
    tb_xfer(BUS, "601 2B 15 10 00 0A 00 00 00", "581 60 15 10 00 00 00 00 00");
    co_emcy_raise(NODE, 0x2310U, CO_ERREG_CURRENT, NULL);
    tb_expect(BUS, "081 10 23 03 00 00 00 00 00");
    co_emcy_raise(NODE, 0x4210U, CO_ERREG_TEMPERATURE, NULL);
    co_emcy_clear(NODE, 0x2310U);
    co_emcy_clear(NODE, 0x4210U);
    tb_expect_none(BUS);
    /* one after the other, 1000 us apart, none dropped */
    tb_advance(BUS, 999U);
    tb_expect_none(BUS);
    tb_advance(BUS, 1U);
    tb_expect(BUS, "081 10 42 0B 00 00 00 00 00");
    tb_expect_none(BUS);
    tb_advance(BUS, 999U);
    tb_expect_none(BUS);
    tb_advance(BUS, 1U);
    tb_expect(BUS, "081 00 00 00 00 00 00 00 00");
    tb_expect_none(BUS);
    /* after the inhibit time an EMCY goes at once */
    tb_advance(BUS, 1000U);
    co_emcy_raise(NODE, 0x3210U, CO_ERREG_VOLTAGE, NULL);
    tb_expect(BUS, "081 10 32 05 00 00 00 00 00");
    tb_expect_none(BUS);
    /* in one long advance the queued ones come out too */
    co_emcy_raise(NODE, 0x3220U, CO_ERREG_VOLTAGE, NULL);
    co_emcy_raise(NODE, 0x3230U, CO_ERREG_VOLTAGE, NULL);
    tb_expect_none(BUS);
    tb_advance(BUS, 1000000U);
    tb_expect(BUS, "081 20 32 05 00 00 00 00 00");
    tb_expect(BUS, "081 30 32 05 00 00 00 00 00");
    tb_expect_none(BUS);
}

/* The inhibit time lowered while an EMCY waits: it goes at the next
 * processing, not when the old inhibit time would have ended. */
static void inhibit_time_lowered_releases_the_queue(void **state)
{
    tb_xfer(BUS, "601 2B 15 10 00 0A 00 00 00", "581 60 15 10 00 00 00 00 00");
    co_emcy_raise(NODE, 0x2310U, CO_ERREG_CURRENT, NULL);
    tb_expect(BUS, "081 10 23 03 00 00 00 00 00");
    co_emcy_raise(NODE, 0x4210U, CO_ERREG_TEMPERATURE, NULL);
    tb_advance(BUS, 0U);
    tb_expect_none(BUS);
    tb_xfer(BUS, "601 2B 15 10 00 00 00 00 00", "581 60 15 10 00 00 00 00 00");
    tb_advance(BUS, 0U);
    tb_expect(BUS, "081 10 42 0B 00 00 00 00 00");
    tb_expect_none(BUS);
}

static void inhibit_time_zero_is_none(void **state)
{
    for (uint16_t i = 0; i < 6U; i++) {
        co_emcy_raise(NODE, (uint16_t)(0x1000U + i), 0U, NULL);
    }
    for (uint16_t i = 0; i < 6U; i++) {
        assert_non_null(tb_next(BUS));
    }
    tb_expect_none(BUS);
}

static void inhibit_time_after_long_silence(void **state)
{
    tb_xfer(BUS, "601 2B 15 10 00 0A 00 00 00", "581 60 15 10 00 00 00 00 00");
    co_emcy_raise(NODE, 0x2310U, CO_ERREG_CURRENT, NULL);
    tb_expect(BUS, "081 10 23 03 00 00 00 00 00");
    /* more than 2^31 us (~36 min) without an EMCY: the last one is long past */
    tb_advance(BUS, 0x7FFFFFFFUL);
    tb_advance(BUS, 0x00100000UL);
    co_emcy_raise(NODE, 0x4210U, CO_ERREG_TEMPERATURE, NULL);
    tb_expect(BUS, "081 10 42 0B 00 00 00 00 00");
    tb_expect_none(BUS);
}

static void inhibit_queue_dropped_when_stopped(void **state)
{
    tb_xfer(BUS, "601 2B 15 10 00 0A 00 00 00", "581 60 15 10 00 00 00 00 00");
    co_emcy_raise(NODE, 0x2310U, CO_ERREG_CURRENT, NULL);
    co_emcy_raise(NODE, 0x4210U, CO_ERREG_TEMPERATURE, NULL);
    tb_expect(BUS, "081 10 23 03 00 00 00 00 00");
    tb_send(BUS, "000 02 01");
    tb_advance(BUS, 10000U);
    tb_expect_none(BUS);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(raise_and_clear_frames, setup),
        cmocka_unit_test_setup(emcy_cob_follows_node_id, setup),
        cmocka_unit_test_setup(error_register_is_or_of_active_errors, setup),
        cmocka_unit_test_setup(shared_register_bit_stays_while_any_error_needs_it, setup),
        cmocka_unit_test_setup(raising_an_active_code_does_nothing, setup),
        cmocka_unit_test_setup(history_newest_first, setup),
        cmocka_unit_test_setup(history_depth_eight, setup),
        cmocka_unit_test_setup(history_write_zero_clears, setup),
        cmocka_unit_test_setup(option_reset_partial, setup),
        cmocka_unit_test_setup(option_state_pair, setup),
        cmocka_unit_test_setup(option_erreg_no_generic, setup),
        cmocka_unit_test_setup(option_erreg_no_generic_with_state_pair, setup),
        cmocka_unit_test_setup(option_history_code_only, setup),
        cmocka_unit_test_setup(emcy_mfr_fills_the_cores_own_emcys, setup),
        cmocka_unit_test_setup(cob_id_valid_bit, setup),
        cmocka_unit_test_setup(cob_id_change_only_while_invalid, setup),
        cmocka_unit_test_setup(cob_id_bad_values, setup),
        cmocka_unit_test_setup(inhibit_time_delays, setup),
        cmocka_unit_test_setup(inhibit_time_lowered_releases_the_queue, setup),
        cmocka_unit_test_setup(inhibit_time_zero_is_none, setup),
        cmocka_unit_test_setup(inhibit_time_after_long_silence, setup),
        cmocka_unit_test_setup(inhibit_queue_dropped_when_stopped, setup),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
