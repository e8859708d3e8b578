/*
 * PDO transmission and reception with exact frames and pushed time: every
 * transmission type, inhibit time and event timer, RTR, the synchronous
 * window, SYNC counter and start value, length and timeout EMCYs, bit and
 * byte mapping, the dictionary path (limits, hooks), and the seed manuals'
 * PDO examples (SSD 630 14.11/14.14, Kollmorgen 6.3.5).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "co/co_endian.h"
#include "pdo_fx.h"

static pfx_t fx;
#define BUS (&fx.bus)

static void start_operational(uint8_t id, const co_settings_t *set)
{
    char nmt[16];
    pfx_start(&fx, id, set);
    snprintf(nmt, sizeof nmt, "000 01 %02X", id);
    tb_send(BUS, nmt);
}

/* SSD 630 14.11 (digest 7.11): RPDO1 controlword, TPDO1 statusword, both 255. */
static void ssd_630_event_driven(void **state)
{
    (void)state;
    pfx_start(&fx, 1, NULL);
    tb_xfer(BUS, "601 23 00 14 01 01 02 00 00", "581 60 00 14 01 00 00 00 00");
    tb_xfer(BUS, "601 23 00 18 01 81 01 00 00", "581 60 00 18 01 00 00 00 00");
    tb_xfer(BUS, "601 23 81 60 00 E8 03 00 00", "581 60 81 60 00 00 00 00 00");
    tb_xfer(BUS, "601 23 7A 60 00 A0 86 01 00", "581 60 7A 60 00 00 00 00 00");
    pfx_set(&fx, 0x6041, 0, 0x0627, 2);
    tb_send(BUS, "000 01 01");
    tb_expect(BUS, "181 27 06"); /* event-driven: the current data once on start */
    tb_expect_none(BUS);
    tb_send(BUS, "201 5F 00");
    assert_int_equal(pfx_get(&fx, 0x6040, 0), 0x005F);
    /* the drive's statusword changes; each change is one TPDO */
    pfx_set(&fx, 0x6041, 0, 0x9627, 2);
    tb_advance(BUS, 0);
    tb_expect(BUS, "181 27 96");
    pfx_set(&fx, 0x6041, 0, 0x9227, 2);
    tb_advance(BUS, 0);
    tb_expect(BUS, "181 27 92");
    tb_advance(BUS, 1000);
    tb_expect_none(BUS); /* no change, no frame */
    pfx_set(&fx, 0x6041, 0, 0x9627, 2);
    tb_advance(BUS, 0);
    tb_expect(BUS, "181 27 96");
    tb_send(BUS, "180 4F 00"); /* step 10 as printed: not this node's RPDO */
    assert_int_equal(pfx_get(&fx, 0x6040, 0), 0x005F);
    tb_send(BUS, "201 4F 00");
    assert_int_equal(pfx_get(&fx, 0x6040, 0), 0x004F);
    pfx_set(&fx, 0x6041, 0, 0x0627, 2);
    tb_advance(BUS, 0);
    tb_expect(BUS, "181 27 06");
    /* step 12 as meant: SDO works in Operational */
    tb_xfer(BUS, "601 23 7A 60 00 60 79 FE FF", "581 60 7A 60 00 00 00 00 00");
    tb_expect_none(BUS);
}

/* SSD 630 14.12-14.14 (digest 7.12): synchronous RPDO1/TPDO1. */
static void ssd_630_interpolated_position(void **state)
{
    (void)state;
    pfx_start(&fx, 1, &(co_settings_t){.pdo.mapping_while_valid = 1U});
    tb_xfer(BUS, "601 2F 00 16 00 00 00 00 00", "581 60 00 16 00 00 00 00 00");
    tb_xfer(BUS, "601 23 00 16 01 10 00 40 60", "581 60 00 16 01 00 00 00 00");
    tb_xfer(BUS, "601 23 00 16 02 20 01 C1 60", "581 60 00 16 02 00 00 00 00");
    tb_xfer(BUS, "601 2F 00 16 00 02 00 00 00", "581 60 00 16 00 00 00 00 00");
    tb_xfer(BUS, "601 2F 00 14 02 01 00 00 00", "581 60 00 14 02 00 00 00 00");
    tb_xfer(BUS, "601 23 00 14 01 01 02 00 00", "581 60 00 14 01 00 00 00 00");
    tb_xfer(BUS, "601 2F 00 1A 00 00 00 00 00", "581 60 00 1A 00 00 00 00 00");
    tb_xfer(BUS, "601 23 00 1A 01 10 00 41 60", "581 60 00 1A 01 00 00 00 00");
    tb_xfer(BUS, "601 23 00 1A 02 20 00 63 60", "581 60 00 1A 02 00 00 00 00");
    tb_xfer(BUS, "601 2F 00 1A 00 02 00 00 00", "581 60 00 1A 00 00 00 00 00");
    tb_xfer(BUS, "601 2F 00 18 02 01 00 00 00", "581 60 00 18 02 00 00 00 00");
    tb_xfer(BUS, "601 23 00 18 01 81 01 00 00", "581 60 00 18 01 00 00 00 00");
    tb_xfer(BUS, "601 23 06 10 00 88 13 00 00", "581 60 06 10 00 00 00 00 00");
    tb_xfer(BUS, "601 2F 60 60 00 07 00 00 00", "581 60 60 60 00 00 00 00 00");
    pfx_set(&fx, 0x6061, 0, 7, 1);
    tb_xfer(BUS, "601 40 61 60 00 00 00 00 00", "581 4F 61 60 00 07 00 00 00");
    pfx_set(&fx, 0x6041, 0, 0x0627, 2);
    pfx_set(&fx, 0x6063, 0, 5, 4);
    tb_send(BUS, "000 01 01");
    tb_expect_none(BUS); /* synchronous TPDOs wait for SYNC */
    tb_send(BUS, "080");
    tb_expect(BUS, "181 27 06 05 00 00 00");
    tb_expect(BUS, "281 00 00 00"); /* TPDO2 of this device, type 1 too */
    /* 4.2 as printed (COB-ID 0x200) is not ours; as meant it is buffered */
    tb_send(BUS, "200 1F 00 05 00 00 00 00");
    tb_send(BUS, "201 1F 00 05 00 00 00");
    assert_int_equal(pfx_get(&fx, 0x6040, 0), 0);
    assert_int_equal(pfx_get(&fx, 0x60C1, 1), 0);
    tb_send(BUS, "080"); /* takes effect at the next SYNC */
    assert_int_equal(pfx_get(&fx, 0x6040, 0), 0x001F);
    assert_int_equal(pfx_get(&fx, 0x60C1, 1), 5);
    tb_expect(BUS, "181 27 06 05 00 00 00");
    tb_expect(BUS, "281 00 00 00");
    tb_expect_none(BUS);
}

/* Kollmorgen 6.3.5 (digest 7.5), node 3: jog by PDO. */
static void kollmorgen_jog_by_pdo(void **state)
{
    (void)state;
    pfx_start(&fx, 3, &(co_settings_t){.pdo.mapping_while_valid = 1U});
    tb_xfer(BUS, "603 2F 60 60 00 03 00 00 00", "583 60 60 60 00 00 00 00 00");
    tb_xfer(BUS, "603 2F 00 16 00 00 00 00 00", "583 60 00 16 00 00 00 00 00");
    tb_xfer(BUS, "603 23 00 16 01 20 00 FF 60", "583 60 00 16 01 00 00 00 00");
    tb_xfer(BUS, "603 2F 00 16 00 01 00 00 00", "583 60 00 16 00 00 00 00 00");
    tb_xfer(BUS, "603 2F 00 1A 00 00 00 00 00", "583 60 00 1A 00 00 00 00 00");
    tb_xfer(BUS, "603 23 00 1A 01 20 00 64 60", "583 60 00 1A 01 00 00 00 00");
    tb_xfer(BUS, "603 23 00 1A 02 20 00 6C 60", "583 60 00 1A 02 00 00 00 00");
    tb_xfer(BUS, "603 2F 00 1A 00 02 00 00 00", "583 60 00 1A 00 00 00 00 00");
    tb_xfer(BUS, "603 2F 00 18 02 01 00 00 00", "583 60 00 18 02 00 00 00 00");
    tb_xfer(BUS, "603 23 01 18 01 83 02 00 C0", "583 60 01 18 01 00 00 00 00");
    tb_xfer(BUS, "603 23 02 18 01 83 03 00 C0", "583 60 02 18 01 00 00 00 00");
    tb_xfer(BUS, "603 23 03 18 01 83 04 00 C0", "583 60 03 18 01 00 00 00 00");
    tb_xfer(BUS, "603 23 01 14 01 03 03 00 80", "583 60 01 14 01 00 00 00 00");
    tb_xfer(BUS, "603 23 02 14 01 03 04 00 80", "583 60 02 14 01 00 00 00 00");
    tb_xfer(BUS, "603 23 03 14 01 03 05 00 80", "583 60 03 14 01 00 00 00 00");
    tb_send(BUS, "000 01 03");
    tb_expect_none(BUS);
    tb_xfer(BUS, "603 2B 40 60 00 06 00 00 00", "583 60 40 60 00 00 00 00 00");
    tb_xfer(BUS, "603 2B 40 60 00 07 00 00 00", "583 60 40 60 00 00 00 00 00");
    tb_xfer(BUS, "603 2B 40 60 00 0F 00 00 00", "583 60 40 60 00 00 00 00 00");
    tb_send(BUS, "203 00 40 00 00");
    assert_int_equal(pfx_get(&fx, 0x60FF, 0), 0x4000);
    pfx_set(&fx, 0x6064, 0, 0x000145FEUL, 4);
    pfx_set(&fx, 0x606C, 0, 0x001AABA6UL, 4);
    tb_send(BUS, "080");
    tb_expect(BUS, "183 FE 45 01 00 A6 AB 1A 00");
    /* the manual's printed 2-byte RPDO is too short for the 32-bit mapping */
    tb_send(BUS, "203 00 40");
    tb_expect(BUS, "083 10 82 11 00 00 00 00 00");
    tb_xfer(BUS, "603 2B 40 60 00 0F 01 00 00", "583 60 40 60 00 00 00 00 00");
}

static void sync_every_nth(void **state)
{
    (void)state;
    pfx_start(&fx, 2, NULL);
    tb_xfer(BUS, "602 2F 01 18 02 03 00 00 00", "582 60 01 18 02 00 00 00 00");
    tb_send(BUS, "000 01 02");
    tb_flush(BUS); /* TPDO1's start frame */
    pfx_set(&fx, 0x2008, 0, 0x1234, 2);
    pfx_set(&fx, 0x2007, 0, 0x08, 1);
    for (int cycle = 0; cycle < 2; cycle++) {
        tb_send(BUS, "080");
        tb_send(BUS, "080");
        tb_expect_none(BUS);
        tb_send(BUS, "080");
        tb_expect(BUS, "282 34 12 08");
        tb_expect_none(BUS);
    }
}

static void acyclic_sync_type0(void **state)
{
    (void)state;
    pfx_start(&fx, 2, NULL);
    tb_xfer(BUS, "602 2F 01 18 02 00 00 00 00", "582 60 01 18 02 00 00 00 00");
    tb_send(BUS, "000 01 02");
    tb_flush(BUS);
    tb_send(BUS, "080");
    tb_expect(BUS, "282 00 00 00"); /* the first SYNC: nothing sent before */
    tb_send(BUS, "080");
    tb_expect_none(BUS); /* no change */
    pfx_set(&fx, 0x2008, 0, 0x0001, 2);
    tb_advance(BUS, 1000);
    tb_expect_none(BUS); /* a change waits for the SYNC */
    tb_send(BUS, "080");
    tb_expect(BUS, "282 01 00 00");
    assert_int_equal(co_tpdo_request(&fx.n.node, 1), CO_OK);
    tb_send(BUS, "080");
    tb_expect(BUS, "282 01 00 00"); /* requested: sent unchanged */
    tb_send(BUS, "080");
    tb_expect_none(BUS);
    assert_int_equal(co_tpdo_request(&fx.n.node, 2), CO_ERR_STORE_STATE); /* invalid */
    assert_int_equal(co_tpdo_request(&fx.n.node, 4), CO_ERR_NO_OBJECT);
}

static void counter_and_start_value(void **state)
{
    (void)state;
    pfx_start(&fx, 2, NULL);
    tb_xfer(BUS, "602 2F 19 10 00 05 00 00 00", "582 60 19 10 00 00 00 00 00");
    tb_xfer(BUS, "602 23 01 18 01 82 02 00 80", "582 60 01 18 01 00 00 00 00");
    tb_xfer(BUS, "602 2F 01 18 02 02 00 00 00", "582 60 01 18 02 00 00 00 00");
    tb_xfer(BUS, "602 2F 01 18 06 03 00 00 00", "582 60 01 18 06 00 00 00 00");
    tb_xfer(BUS, "602 23 01 18 01 82 02 00 00", "582 60 01 18 01 00 00 00 00");
    tb_send(BUS, "000 01 02");
    tb_flush(BUS);
    tb_send(BUS, "080 01");
    tb_send(BUS, "080 02");
    tb_expect_none(BUS);
    tb_send(BUS, "080 03"); /* the start value: first transmission */
    tb_expect(BUS, "282 00 00 00");
    tb_send(BUS, "080 04");
    tb_expect_none(BUS);
    tb_send(BUS, "080 05"); /* then every 2nd */
    tb_expect(BUS, "282 00 00 00");
    tb_send(BUS, "080 01");
    tb_expect_none(BUS);
    tb_send(BUS, "080 02");
    tb_expect(BUS, "282 00 00 00");
    tb_expect_none(BUS);
    /* without a SYNC counter the start value has no meaning */
    pfx_start(&fx, 2, NULL);
    tb_xfer(BUS, "602 23 01 18 01 82 02 00 80", "582 60 01 18 01 00 00 00 00");
    tb_xfer(BUS, "602 2F 01 18 06 03 00 00 00", "582 60 01 18 06 00 00 00 00");
    tb_xfer(BUS, "602 23 01 18 01 82 02 00 00", "582 60 01 18 01 00 00 00 00");
    tb_send(BUS, "000 01 02");
    tb_flush(BUS);
    tb_send(BUS, "080");
    tb_expect(BUS, "282 00 00 00");
}

static void rtr_types(void **state)
{
    (void)state;
    pfx_start(&fx, 2, NULL);
    /* TPDO2: 253, RTR only, the data of the moment */
    tb_xfer(BUS, "602 2F 01 18 02 FD 00 00 00", "582 60 01 18 02 00 00 00 00");
    tb_send(BUS, "000 01 02");
    tb_flush(BUS);
    pfx_set(&fx, 0x2008, 0, 0x0011, 2);
    tb_send(BUS, "080");
    tb_advance(BUS, 1000);
    tb_expect_none(BUS);
    tb_send(BUS, "282 R3");
    tb_expect(BUS, "282 11 00 00");
    tb_expect_none(BUS);
    /* 252: sampled at SYNC, sent on request */
    tb_send(BUS, "000 80 02");
    tb_xfer(BUS, "602 2F 01 18 02 FC 00 00 00", "582 60 01 18 02 00 00 00 00");
    tb_send(BUS, "000 01 02");
    tb_flush(BUS);
    tb_send(BUS, "282 R3"); /* before any SYNC: the data of now */
    tb_expect(BUS, "282 11 00 00");
    tb_send(BUS, "080");
    tb_expect_none(BUS);
    pfx_set(&fx, 0x2008, 0, 0x0022, 2);
    tb_send(BUS, "282 R3");
    tb_expect(BUS, "282 11 00 00"); /* what the SYNC sampled */
    tb_send(BUS, "080");
    tb_send(BUS, "282 R3");
    tb_expect(BUS, "282 22 00 00");
    /* 255 answers an RTR too; a TPDO with bit 30 (no RTR) does not */
    pfx_set(&fx, 0x6041, 0, 0x0033, 2);
    tb_send(BUS, "182 R2");
    tb_expect(BUS, "182 33 00");
    tb_send(BUS, "000 80 02");
    tb_xfer(BUS, "602 23 00 18 01 82 01 00 C0", "582 60 00 18 01 00 00 00 00");
    tb_xfer(BUS, "602 23 00 18 01 82 01 00 40", "582 60 00 18 01 00 00 00 00");
    tb_send(BUS, "000 01 02");
    tb_flush(BUS);
    tb_send(BUS, "182 R2");
    tb_expect_none(BUS);
    /* RTRs are for Operational only */
    tb_send(BUS, "000 80 02");
    tb_send(BUS, "282 R3");
    tb_expect_none(BUS);
}

static void inhibit_and_event_timer(void **state)
{
    (void)state;
    pfx_start(&fx, 1, NULL);
    tb_xfer(BUS, "601 23 00 18 01 81 01 00 80", "581 60 00 18 01 00 00 00 00");
    tb_xfer(BUS, "601 2B 00 18 03 64 00 00 00", "581 60 00 18 03 00 00 00 00"); /* 10 ms */
    tb_xfer(BUS, "601 2B 00 18 05 32 00 00 00", "581 60 00 18 05 00 00 00 00"); /* 50 ms */
    tb_xfer(BUS, "601 23 00 18 01 81 01 00 00", "581 60 00 18 01 00 00 00 00");
    tb_send(BUS, "000 01 01");
    tb_expect(BUS, "181 00 00");
    /* a change 1 ms later waits for the end of the inhibit time */
    tb_advance(BUS, 1000);
    pfx_set(&fx, 0x6041, 0, 0x0001, 2);
    tb_advance(BUS, 8999);
    tb_expect_none(BUS);
    tb_advance(BUS, 1);
    tb_expect(BUS, "181 01 00");
    /* two changes within the inhibit time: only the latest goes out */
    pfx_set(&fx, 0x6041, 0, 0x0002, 2);
    tb_advance(BUS, 2000);
    pfx_set(&fx, 0x6041, 0, 0x0003, 2);
    tb_advance(BUS, 7999);
    tb_expect_none(BUS);
    tb_advance(BUS, 1);
    tb_expect(BUS, "181 03 00");
    tb_expect_none(BUS);
    /* no change: the event timer sends 50 ms after the last one */
    tb_advance(BUS, 49999);
    tb_expect_none(BUS);
    tb_advance(BUS, 1);
    tb_expect(BUS, "181 03 00");
    tb_advance(BUS, 50000);
    tb_expect(BUS, "181 03 00");
    tb_expect_none(BUS);
}

static void event_timer_unit_option(void **state)
{
    (void)state;
    /* Kollmorgen counts the event timer in 100 us */
    pfx_start(&fx, 1, &(co_settings_t){.pdo.event_timer_unit = CO_PDO_TIMER_100US});
    tb_xfer(BUS, "601 2B 00 18 05 0A 00 00 00", "581 60 00 18 05 00 00 00 00");
    tb_send(BUS, "000 01 01");
    tb_expect(BUS, "181 00 00");
    tb_advance(BUS, 999);
    tb_expect_none(BUS);
    tb_advance(BUS, 1);
    tb_expect(BUS, "181 00 00");
}

/* CO_TPDO_CHANGE_IGNORED (FAULHABER §3.2, digest 4.3: "the only event
 * is a change of the statusword", which its profile requests): TPDOs of
 * type 254/255 go out on co_tpdo_request, the event timer or an RTR, never
 * because their data changed, and not on entering Operational. */
static void no_change_detect_option(void **state)
{
    (void)state;
    /* CiA 301: the data once on start, then every change */
    start_operational(1, NULL);
    tb_expect(BUS, "181 00 00");
    pfx_set(&fx, 0x6041, 0, 0x0021, 2);
    tb_advance(BUS, 0);
    tb_expect(BUS, "181 21 00");
    tb_expect_none(BUS);
    /* the option: silent until asked */
    start_operational(1, &(co_settings_t){.tpdo.change_detection = CO_TPDO_CHANGE_IGNORED});
    tb_advance(BUS, 0);
    tb_expect_none(BUS);
    pfx_set(&fx, 0x6041, 0, 0x0021, 2);
    tb_advance(BUS, 100000);
    tb_expect_none(BUS);
    assert_int_equal(co_tpdo_request(&fx.n.node, 0U), CO_OK);
    tb_advance(BUS, 0);
    tb_expect(BUS, "181 21 00"); /* the data of the moment it goes out */
    tb_expect_none(BUS);
    /* a request is one transmission, also with unchanged data */
    assert_int_equal(co_tpdo_request(&fx.n.node, 0U), CO_OK);
    tb_advance(BUS, 0);
    tb_expect(BUS, "181 21 00");
    tb_advance(BUS, 1000);
    tb_expect_none(BUS);
    /* an RTR is answered with the present data */
    pfx_set(&fx, 0x6041, 0, 0x0023, 2);
    tb_send(BUS, "181 R2");
    tb_expect(BUS, "181 23 00");
    tb_expect_none(BUS);
    /* the inhibit time holds a request back; the data are sampled when it ends */
    tb_send(BUS, "000 80 01");
    tb_xfer(BUS, "601 23 00 18 01 81 01 00 80", "581 60 00 18 01 00 00 00 00");
    tb_xfer(BUS, "601 2B 00 18 03 64 00 00 00", "581 60 00 18 03 00 00 00 00"); /* 10 ms */
    tb_xfer(BUS, "601 23 00 18 01 81 01 00 00", "581 60 00 18 01 00 00 00 00");
    tb_send(BUS, "000 01 01");
    tb_advance(BUS, 0);
    tb_expect_none(BUS);
    assert_int_equal(co_tpdo_request(&fx.n.node, 0U), CO_OK);
    tb_advance(BUS, 0);
    tb_expect(BUS, "181 23 00");
    assert_int_equal(co_tpdo_request(&fx.n.node, 0U), CO_OK);
    pfx_set(&fx, 0x6041, 0, 0x0027, 2);
    tb_advance(BUS, 9999);
    tb_expect_none(BUS);
    tb_advance(BUS, 1);
    tb_expect(BUS, "181 27 00");
    tb_expect_none(BUS);
    /* the event timer sends without a change */
    tb_xfer(BUS, "601 2B 00 18 05 14 00 00 00", "581 60 00 18 05 00 00 00 00"); /* 20 ms */
    tb_advance(BUS, 19999);
    tb_expect_none(BUS);
    tb_advance(BUS, 1);
    tb_expect(BUS, "181 27 00");
    tb_advance(BUS, 20000);
    tb_expect(BUS, "181 27 00");
    tb_expect_none(BUS);
    /* synchronous TPDOs are not affected: TPDO2 (type 1) at every SYNC */
    tb_send(BUS, "080");
    tb_expect(BUS, "281 00 00 00");
    tb_expect_none(BUS);
}

/* The inhibit time of an event-driven TPDO ends once, whatever time passes
 * before the next event: a request 40 minutes (more than 2^31 us) after the
 * last transmission goes out at once. The inhibit time is a deadline of its
 * own: were it looked at only when the next event comes, its end would by
 * then look 2^32 us - 40 min (about 32 min) ahead, and the TPDO would wait
 * for it. Without change detection and without an event timer nothing else
 * runs the TPDO in between. */
static void inhibit_after_long_silence(void **state)
{
    (void)state;
    start_operational(1, &(co_settings_t){.tpdo.change_detection = CO_TPDO_CHANGE_IGNORED});
    /* an inhibit time of 0 */
    assert_int_equal(co_tpdo_request(&fx.n.node, 0U), CO_OK);
    tb_advance(BUS, 0);
    tb_expect(BUS, "181 00 00");
    for (uint32_t m = 0U; m < 40U; m++) {
        tb_advance(BUS, 60000000U);
    }
    assert_int_equal(co_tpdo_request(&fx.n.node, 0U), CO_OK);
    tb_advance(BUS, 0);
    tb_expect(BUS, "181 00 00");
    /* 10 ms */
    tb_send(BUS, "000 80 01");
    tb_xfer(BUS, "601 23 00 18 01 81 01 00 80", "581 60 00 18 01 00 00 00 00");
    tb_xfer(BUS, "601 2B 00 18 03 64 00 00 00", "581 60 00 18 03 00 00 00 00");
    tb_xfer(BUS, "601 23 00 18 01 81 01 00 00", "581 60 00 18 01 00 00 00 00");
    tb_send(BUS, "000 01 01");
    assert_int_equal(co_tpdo_request(&fx.n.node, 0U), CO_OK);
    tb_advance(BUS, 0);
    tb_expect(BUS, "181 00 00");
    for (uint32_t m = 0U; m < 40U; m++) {
        tb_advance(BUS, 60000000U);
    }
    tb_expect_none(BUS);
    pfx_set(&fx, 0x6041, 0, 0x0031, 2);
    assert_int_equal(co_tpdo_request(&fx.n.node, 0U), CO_OK);
    tb_advance(BUS, 0);
    tb_expect(BUS, "181 31 00");
    /* and the next one waits for the inhibit time as ever */
    assert_int_equal(co_tpdo_request(&fx.n.node, 0U), CO_OK);
    tb_advance(BUS, 9999);
    tb_expect_none(BUS);
    tb_advance(BUS, 1);
    tb_expect(BUS, "181 31 00");
    tb_expect_none(BUS);
}

/* set.tpdo.change_mask (Kollmorgen D4.5 for 255, SSD 630 D§4.4 for 254):
 * the change masks (here 0x2030.. for TPDO1..; sub 1 PDO bytes 0..3, sub 2
 * bytes 4..7) decide which changed bits send an event-driven TPDO. The
 * first transmission, requests, RTRs and the event timer are not filtered. */
static void tpdo_change_masks(void **state)
{
    (void)state;
    /* CiA 301: the masks mean nothing, every change is sent */
    pfx_start(&fx, 1, NULL);
    tb_xfer(BUS, "601 23 30 20 01 00 FF 00 00", "581 60 30 20 01 00 00 00 00");
    tb_send(BUS, "000 01 01");
    tb_expect(BUS, "181 00 00");
    pfx_set(&fx, 0x6041, 0, 0x0021, 2);
    tb_advance(BUS, 0);
    tb_expect(BUS, "181 21 00");
    /* type 255 filtered: only the statusword's high byte counts */
    pfx_start(&fx, 1, &(co_settings_t){.tpdo.change_mask = CO_TPDO_MASK_255});
    tb_xfer(BUS, "601 23 30 20 01 00 FF 00 00", "581 60 30 20 01 00 00 00 00");
    tb_send(BUS, "000 01 01");
    tb_expect(BUS, "181 00 00"); /* the first one is not a change: always sent */
    pfx_set(&fx, 0x6041, 0, 0x0021, 2);
    tb_advance(BUS, 1000);
    tb_expect_none(BUS);
    pfx_set(&fx, 0x6041, 0, 0x0121, 2);
    tb_advance(BUS, 0);
    tb_expect(BUS, "181 21 01"); /* all the data of now */
    pfx_set(&fx, 0x6041, 0, 0x0127, 2);
    tb_advance(BUS, 1000);
    tb_expect_none(BUS);
    /* compared with what was sent last, not with the last sample */
    pfx_set(&fx, 0x6041, 0, 0x0227, 2);
    tb_advance(BUS, 0);
    tb_expect(BUS, "181 27 02");
    /* a request and an RTR are not filtered */
    pfx_set(&fx, 0x6041, 0, 0x0237, 2);
    assert_int_equal(co_tpdo_request(&fx.n.node, 0U), CO_OK);
    tb_advance(BUS, 0);
    tb_expect(BUS, "181 37 02");
    pfx_set(&fx, 0x6041, 0, 0x0233, 2);
    tb_send(BUS, "181 R2");
    tb_expect(BUS, "181 33 02");
    tb_expect_none(BUS);
    /* a mask of 0: only requests, RTRs and the event timer */
    tb_xfer(BUS, "601 23 30 20 01 00 00 00 00", "581 60 30 20 01 00 00 00 00");
    pfx_set(&fx, 0x6041, 0, 0xFFFF, 2);
    tb_advance(BUS, 1000);
    tb_expect_none(BUS);
    /* type 254 is not filtered by TPDO_MASK_255 ... */
    tb_xfer(BUS, "601 2F 00 18 02 FE 00 00 00", "581 60 00 18 02 00 00 00 00");
    tb_advance(BUS, 0);
    tb_expect(BUS, "181 FF FF"); /* a new type: sent once */
    pfx_set(&fx, 0x6041, 0, 0x0001, 2);
    tb_advance(BUS, 0);
    tb_expect(BUS, "181 01 00");
    tb_expect_none(BUS);
    /* ... but by TPDO_MASK_254 (SSD 630), and 255 then is not */
    pfx_start(&fx, 1, &(co_settings_t){.tpdo.change_mask = CO_TPDO_MASK_254});
    tb_xfer(BUS, "601 23 30 20 01 00 FF 00 00", "581 60 30 20 01 00 00 00 00");
    tb_send(BUS, "000 01 01");
    tb_expect(BUS, "181 00 00");
    pfx_set(&fx, 0x6041, 0, 0x0021, 2);
    tb_advance(BUS, 0);
    tb_expect(BUS, "181 21 00");
    tb_xfer(BUS, "601 2F 00 18 02 FE 00 00 00", "581 60 00 18 02 00 00 00 00");
    tb_advance(BUS, 0);
    tb_expect(BUS, "181 21 00");
    pfx_set(&fx, 0x6041, 0, 0x0027, 2);
    tb_advance(BUS, 1000);
    tb_expect_none(BUS);
    pfx_set(&fx, 0x6041, 0, 0x0127, 2);
    tb_advance(BUS, 0);
    tb_expect(BUS, "181 27 01");
    tb_expect_none(BUS);
}

/* Kollmorgen D4.5's use: a position reported once per 2^16 increments. TPDO3
 * (statusword, position) with mask sub 1 = 0 (bytes 0..3: the statusword and
 * the position's low word) and sub 2 = 1 (byte 4 bit 0: position bit 16). */
static void tpdo_mask_high_bytes(void **state)
{
    (void)state;
    pfx_start(&fx, 1, &(co_settings_t){.tpdo.change_mask = CO_TPDO_MASK_255});
    tb_xfer(BUS, "601 23 32 20 01 00 00 00 00", "581 60 32 20 01 00 00 00 00");
    tb_xfer(BUS, "601 23 32 20 02 01 00 00 00", "581 60 32 20 02 00 00 00 00");
    tb_xfer(BUS, "601 23 02 18 01 81 03 00 00", "581 60 02 18 01 00 00 00 00");
    pfx_set(&fx, 0x6041, 0, 0x00E8, 2);
    tb_send(BUS, "000 01 01");
    tb_expect(BUS, "181 E8 00");
    tb_expect(BUS, "381 E8 00 00 00 00 00");
    tb_expect_none(BUS);
    for (int32_t pos = 1000; pos < 65536; pos += 1000) {
        pfx_set(&fx, 0x6064, 0, (uint32_t)pos, 4);
        tb_advance(BUS, 1000);
        tb_expect_none(BUS);
    }
    pfx_set(&fx, 0x6064, 0, 66000, 4);
    tb_advance(BUS, 0);
    tb_expect(BUS, "381 E8 00 D0 01 01 00"); /* 66000 = 0x000101D0 */
    pfx_set(&fx, 0x6064, 0, 130000, 4); /* 0x0001FBD0: bit 16 unchanged */
    tb_advance(BUS, 1000);
    tb_expect_none(BUS);
    pfx_set(&fx, 0x6064, 0, 140000, 4); /* 0x000222E0: bit 16 now clear */
    tb_advance(BUS, 0);
    tb_expect(BUS, "381 E8 00 E0 22 02 00");
    tb_expect_none(BUS);
}

static void sync_window(void **state)
{
    (void)state;
    pfx_start(&fx, 2, NULL);
    tb_xfer(BUS, "602 23 07 10 00 DC 05 00 00", "582 60 07 10 00 00 00 00 00"); /* 1500 us */
    tb_send(BUS, "000 01 02");
    tb_flush(BUS);
    /* the TX path is full at the SYNC: the TPDO goes out when it frees up,
     * inside the window */
    fx.bus.refuse = 2;
    tb_send(BUS, "080");
    tb_expect_none(BUS);
    tb_advance(BUS, 1000);
    tb_expect(BUS, "282 00 00 00");
    assert_int_equal(fx.bus.refused, 2);
    /* ... but not once the window has closed */
    tb_xfer(BUS, "602 23 07 10 00 F4 01 00 00", "582 60 07 10 00 00 00 00 00"); /* 500 us */
    fx.bus.refuse = 2;
    tb_send(BUS, "080");
    tb_advance(BUS, 5000);
    tb_expect_none(BUS);
    assert_int_equal(fx.bus.refused, 4);
    /* a synchronous RPDO after the window is discarded */
    tb_send(BUS, "080");
    tb_flush(BUS);
    fx.bus.now += 600;
    tb_send(BUS, "302 34 12 05");
    tb_send(BUS, "080");
    assert_int_equal(pfx_get(&fx, 0x6040, 0), 0);
    fx.bus.now += 400;
    tb_send(BUS, "302 34 12 05");
    tb_send(BUS, "080");
    assert_int_equal(pfx_get(&fx, 0x6040, 0), 0x1234);
    assert_int_equal(pfx_get(&fx, 0x6060, 0), 5);
}

static void rpdo_length_emcy(void **state)
{
    (void)state;
    start_operational(1, NULL);
    tb_flush(BUS);
    tb_send(BUS, "201 5F");
    tb_expect(BUS, "081 10 82 11 00 00 00 00 00"); /* too short: not processed */
    assert_int_equal(pfx_get(&fx, 0x6040, 0), 0);
    tb_send(BUS, "201 5F");
    tb_expect_none(BUS); /* still the same error */
    tb_send(BUS, "201 5F 00 77");
    tb_expect(BUS, "081 00 00 00 00 00 00 00 00"); /* 0x8210 ends */
    tb_expect(BUS, "081 20 82 11 00 00 00 00 00"); /* too long: processed, reported */
    assert_int_equal(pfx_get(&fx, 0x6040, 0), 0x005F);
    tb_send(BUS, "201 60 00");
    tb_expect(BUS, "081 00 00 00 00 00 00 00 00");
    assert_int_equal(pfx_get(&fx, 0x6040, 0), 0x0060);
    tb_expect_none(BUS);
    tb_xfer(BUS, "601 40 03 10 01 00 00 00 00", "581 43 03 10 01 20 82 00 00");
    tb_xfer(BUS, "601 40 03 10 02 00 00 00 00", "581 43 03 10 02 10 82 00 00");
}

static void rpdo_short_option(void **state)
{
    (void)state;
    /* AnaGate: a short RPDO writes the entries it covers, no EMCY */
    start_operational(1, &(co_settings_t){.pdo.short_rpdo = CO_RPDO_SHORT_ACCEPT});
    tb_flush(BUS);
    tb_send(BUS, "301 06 00"); /* RPDO2: 0x6040 (16) + 0x6060 (8), type 1 */
    tb_send(BUS, "080");
    assert_int_equal(pfx_get(&fx, 0x6040, 0), 6);
    assert_int_equal(pfx_get(&fx, 0x6060, 0), 0);
    tb_send(BUS, "201 0F");
    tb_send(BUS, "080");
    assert_int_equal(pfx_get(&fx, 0x6040, 0), 6);
    tb_expect(BUS, "281 00 00 00"); /* the SYNC's TPDO2, no EMCY */
    tb_expect(BUS, "281 00 00 00");
    tb_expect_none(BUS);
}

static void rpdo_timeout(void **state)
{
    (void)state;
    pfx_start(&fx, 1, NULL);
    tb_xfer(BUS, "601 2B 00 14 05 64 00 00 00", "581 60 00 14 05 00 00 00 00"); /* 100 ms */
    tb_send(BUS, "000 01 01");
    tb_flush(BUS);
    tb_advance(BUS, 300000);
    tb_expect_none(BUS); /* monitoring starts with the first RPDO */
    tb_send(BUS, "201 01 00");
    tb_advance(BUS, 99999);
    tb_expect_none(BUS);
    tb_advance(BUS, 1);
    tb_expect(BUS, "081 50 82 11 00 00 00 00 00");
    tb_advance(BUS, 500000);
    tb_expect_none(BUS);
    tb_send(BUS, "201 02 00");
    tb_expect(BUS, "081 00 00 00 00 00 00 00 00");
    assert_int_equal(pfx_get(&fx, 0x6040, 0), 2);
    /* a reset communication ends monitoring and the error */
    tb_advance(BUS, 100000);
    tb_expect(BUS, "081 50 82 11 00 00 00 00 00");
    tb_send(BUS, "000 82 01");
    tb_expect(BUS, "701 00");
    tb_expect(BUS, "081 00 00 00 00 00 00 00 00");
    tb_expect_none(BUS);
}

static void bit_and_byte_mapping(void **state)
{
    (void)state;
    pfx_start(&fx, 1, NULL);
    /* RPDO3: dummy U8, BOOLEAN 1 bit, INTEGER8 in 4 bits, INTEGER16 in 3 bits */
    tb_xfer(BUS, "601 2F 02 16 00 00 00 00 00", "581 60 02 16 00 00 00 00 00");
    tb_xfer(BUS, "601 23 02 16 01 08 00 05 00", "581 60 02 16 01 00 00 00 00");
    tb_xfer(BUS, "601 23 02 16 02 01 00 00 20", "581 60 02 16 02 00 00 00 00");
    tb_xfer(BUS, "601 23 02 16 03 04 00 01 20", "581 60 02 16 03 00 00 00 00");
    tb_xfer(BUS, "601 23 02 16 04 03 00 02 20", "581 60 02 16 04 00 00 00 00");
    tb_xfer(BUS, "601 2F 02 16 00 04 00 00 00", "581 60 02 16 00 00 00 00 00");
    tb_xfer(BUS, "601 23 02 14 01 01 04 00 00", "581 60 02 14 01 00 00 00 00");
    /* TPDO3: the same bits back, then a U64 does not fit; a REAL32 does */
    tb_xfer(BUS, "601 2F 02 1A 00 00 00 00 00", "581 60 02 1A 00 00 00 00 00");
    tb_xfer(BUS, "601 23 02 1A 01 01 00 00 20", "581 60 02 1A 01 00 00 00 00");
    tb_xfer(BUS, "601 23 02 1A 02 04 00 01 20", "581 60 02 1A 02 00 00 00 00");
    tb_xfer(BUS, "601 23 02 1A 03 03 00 02 20", "581 60 02 1A 03 00 00 00 00");
    tb_xfer(BUS, "601 23 02 1A 04 18 00 03 20", "581 60 02 1A 04 00 00 00 00");
    tb_xfer(BUS, "601 23 02 1A 05 20 00 06 20", "581 60 02 1A 05 00 00 00 00");
    tb_xfer(BUS, "601 2F 02 1A 00 05 00 00 00", "581 60 02 1A 00 00 00 00 00");
    tb_xfer(BUS, "601 23 02 18 01 81 03 00 00", "581 60 02 18 01 00 00 00 00");
    pfx_set(&fx, 0x2003, 0, 0xABCDEF, 3);
    pfx_set(&fx, 0x2006, 0, 0x3F800000UL, 4); /* 1.0f */
    tb_send(BUS, "000 01 01");
    tb_flush(BUS);
    /* byte 1 = 0x3D: bool 1, then 0b1110 = -2, then 0b001 = 1 */
    tb_send(BUS, "401 AA 3D");
    assert_int_equal(pfx_get(&fx, 0x2000, 0), 1);
    assert_int_equal(pfx_get(&fx, 0x2001, 0) & 0xFF, 0xFE);
    assert_int_equal(pfx_get(&fx, 0x2002, 0) & 0xFFFF, 0x0001);
    tb_advance(BUS, 0);
    /* 1 | (0xE << 1) | (1 << 5) = 0x3D, then 24 bits EF CD AB, then 1.0f */
    tb_expect(BUS, "381 3D EF CD AB 00 00 80 3F");
    /* a negative value in 3 bits is sign-extended into INTEGER16 */
    tb_send(BUS, "401 00 C0");
    assert_int_equal(pfx_get(&fx, 0x2002, 0) & 0xFFFF, 0xFFFE);
}

static void full_size_values(void **state)
{
    (void)state;
    pfx_start(&fx, 1, NULL);
    tb_xfer(BUS, "601 23 03 14 01 01 05 00 80", "581 60 03 14 01 00 00 00 00");
    tb_xfer(BUS, "601 2F 03 16 00 00 00 00 00", "581 60 03 16 00 00 00 00 00");
    tb_xfer(BUS, "601 23 03 16 01 40 00 05 20", "581 60 03 16 01 00 00 00 00");
    tb_xfer(BUS, "601 2F 03 16 00 01 00 00 00", "581 60 03 16 00 00 00 00 00");
    tb_xfer(BUS, "601 23 03 14 01 01 05 00 00", "581 60 03 14 01 00 00 00 00");
    tb_xfer(BUS, "601 23 03 18 01 81 04 00 80", "581 60 03 18 01 00 00 00 00");
    tb_xfer(BUS, "601 2F 03 1A 00 00 00 00 00", "581 60 03 1A 00 00 00 00 00");
    tb_xfer(BUS, "601 23 03 1A 01 40 00 05 20", "581 60 03 1A 01 00 00 00 00");
    tb_xfer(BUS, "601 2F 03 1A 00 01 00 00 00", "581 60 03 1A 00 00 00 00 00");
    tb_xfer(BUS, "601 23 03 18 01 81 04 00 00", "581 60 03 18 01 00 00 00 00");
    tb_send(BUS, "000 01 01");
    tb_flush(BUS);
    tb_send(BUS, "501 01 02 03 04 05 06 07 88");
    tb_xfer(BUS, "601 40 05 20 00 00 00 00 00", "581 41 05 20 00 08 00 00 00");
    tb_advance(BUS, 0);
    tb_expect(BUS, "481 01 02 03 04 05 06 07 88");
}

static void dictionary_path(void **state)
{
    (void)state;
    pfx_start(&fx, 1, NULL);
    /* RPDO1 -> limited 0x2010 (10..1000) and hooked 0x2020 */
    tb_xfer(BUS, "601 23 00 14 01 01 02 00 80", "581 60 00 14 01 00 00 00 00");
    tb_xfer(BUS, "601 2F 00 16 00 00 00 00 00", "581 60 00 16 00 00 00 00 00");
    tb_xfer(BUS, "601 23 00 16 01 10 00 10 20", "581 60 00 16 01 00 00 00 00");
    tb_xfer(BUS, "601 23 00 16 02 20 00 20 20", "581 60 00 16 02 00 00 00 00");
    tb_xfer(BUS, "601 2F 00 16 00 02 00 00 00", "581 60 00 16 00 00 00 00 00");
    tb_xfer(BUS, "601 23 00 14 01 01 02 00 00", "581 60 00 14 01 00 00 00 00");
    /* TPDO1 <- hooked 0x2020 (the read hook refreshes it) */
    tb_xfer(BUS, "601 23 00 18 01 81 01 00 80", "581 60 00 18 01 00 00 00 00");
    tb_xfer(BUS, "601 2F 00 1A 00 00 00 00 00", "581 60 00 1A 00 00 00 00 00");
    tb_xfer(BUS, "601 23 00 1A 01 20 00 20 20", "581 60 00 1A 01 00 00 00 00");
    tb_xfer(BUS, "601 2F 00 1A 00 01 00 00 00", "581 60 00 1A 00 00 00 00 00");
    tb_xfer(BUS, "601 23 00 18 01 81 01 00 00", "581 60 00 18 01 00 00 00 00");
    fx.hook_value = 0xA1B2C3D4UL;
    tb_send(BUS, "000 01 01");
    tb_expect(BUS, "181 D4 C3 B2 A1");
    assert_true(fx.hook_reads > 0U);
    fx.hook_value = 0x01020304UL;
    tb_advance(BUS, 0);
    tb_expect(BUS, "181 04 03 02 01");
    /* in limits: both written through the path (the write hook sees it) */
    tb_send(BUS, "201 64 00 44 33 22 11");
    assert_int_equal(pfx_get(&fx, 0x2010, 0), 100);
    assert_int_equal(fx.hook_written, 0x11223344UL);
    /* out of limits: 0x2010 keeps its value, the other entry still applies */
    tb_send(BUS, "201 05 00 88 77 66 55");
    assert_int_equal(pfx_get(&fx, 0x2010, 0), 100);
    assert_int_equal(fx.hook_written, 0x55667788UL);
    /* a hook's veto drops that value */
    fx.hook_veto = CO_ERR_STORE_LOCAL;
    tb_send(BUS, "201 C8 00 00 00 00 00");
    assert_int_equal(pfx_get(&fx, 0x2010, 0), 200);
    assert_int_equal(fx.hook_written, 0x55667788UL);
    assert_int_equal(fx.hook_writes, 3);
}

/* The SDO server's COB-IDs, read-only, in 16 bits (co_od.h CO_SUB_COB16):
 * read as their UNSIGNED32, a TPDO copies the low byte directly or reads
 * the whole value through the dictionary, the application's value without
 * a 16-bit form is refused and leaves the old one. */
static void sdo_server_cob_ids_in_16_bits(void **state)
{
    uint8_t v[4];

    (void)state;
    pfx_start(&fx, 5, NULL);
    tb_xfer(BUS, "605 40 00 12 01 00 00 00 00", "585 43 00 12 01 05 06 00 00");
    tb_xfer(BUS, "605 40 00 12 02 00 00 00 00", "585 43 00 12 02 85 05 00 00");
    assert_int_equal(fx.n.ram.x1200_cob_id_client_to_server_rx, 0x0605U);
    tb_xfer(BUS, "605 23 00 12 01 05 06 00 80", "585 80 00 12 01 02 00 01 06");
    co_put_u32(v, 0x00000E05UL); /* bit 11 */
    assert_int_equal(co_od_write(&fx.n.node, 0x1200U, 1U, v, 4U, true), CO_ERR_VALUE);
    co_put_u32(v, 0x20000605UL); /* bit 29 */
    assert_int_equal(co_od_write(&fx.n.node, 0x1200U, 1U, v, 4U, true), CO_ERR_VALUE);
    tb_xfer(BUS, "605 40 00 12 01 00 00 00 00", "585 43 00 12 01 05 06 00 00");
    co_put_u32(v, 0xC0000605UL);
    assert_int_equal(co_od_write(&fx.n.node, 0x1200U, 1U, v, 4U, true), CO_OK);
    assert_int_equal(fx.n.ram.x1200_cob_id_client_to_server_rx, 0xC605U);
    tb_xfer(BUS, "605 40 00 12 01 00 00 00 00", "585 43 00 12 01 05 06 00 C0");
    /* TPDO1: the low byte of 0x1200:02 (8 bits: copied directly) */
    tb_xfer(BUS, "605 23 00 18 01 85 01 00 80", "585 60 00 18 01 00 00 00 00");
    tb_xfer(BUS, "605 2F 00 1A 00 00 00 00 00", "585 60 00 1A 00 00 00 00 00");
    tb_xfer(BUS, "605 23 00 1A 01 08 02 00 12", "585 60 00 1A 01 00 00 00 00");
    tb_xfer(BUS, "605 2F 00 1A 00 01 00 00 00", "585 60 00 1A 00 00 00 00 00");
    tb_xfer(BUS, "605 23 00 18 01 85 01 00 00", "585 60 00 18 01 00 00 00 00");
    tb_send(BUS, "000 01 05");
    tb_expect(BUS, "185 85");
    tb_expect_none(BUS);
    /* then the whole 0x1200:01 (through the dictionary) and its low 16 bits */
    tb_send(BUS, "000 80 05");
    tb_xfer(BUS, "605 23 00 18 01 85 01 00 80", "585 60 00 18 01 00 00 00 00");
    tb_xfer(BUS, "605 2F 00 1A 00 00 00 00 00", "585 60 00 1A 00 00 00 00 00");
    tb_xfer(BUS, "605 23 00 1A 01 20 01 00 12", "585 60 00 1A 01 00 00 00 00");
    tb_xfer(BUS, "605 23 00 1A 02 10 02 00 12", "585 60 00 1A 02 00 00 00 00");
    tb_xfer(BUS, "605 2F 00 1A 00 02 00 00 00", "585 60 00 1A 00 00 00 00 00");
    tb_xfer(BUS, "605 23 00 18 01 85 01 00 00", "585 60 00 18 01 00 00 00 00");
    tb_send(BUS, "000 01 05");
    tb_expect(BUS, "185 05 06 00 C0 85 05");
    tb_expect_none(BUS);
}

static void nmt_states(void **state)
{
    (void)state;
    pfx_start(&fx, 1, NULL);
    /* Pre-operational: no PDO in or out */
    tb_send(BUS, "201 11 00");
    tb_send(BUS, "301 22 00 01");
    tb_send(BUS, "080");
    tb_send(BUS, "181 R2");
    tb_advance(BUS, 1000);
    tb_expect_none(BUS);
    assert_int_equal(pfx_get(&fx, 0x6040, 0), 0);
    /* Operational: event-driven TPDO1 sends at once */
    tb_send(BUS, "000 01 01");
    tb_expect(BUS, "181 00 00");
    tb_send(BUS, "301 22 00 01"); /* buffered until SYNC ... */
    tb_send(BUS, "000 02 01"); /* ... and dropped by Stopped */
    tb_send(BUS, "080");
    tb_send(BUS, "201 11 00");
    pfx_set(&fx, 0x6041, 0, 0x0040, 2);
    tb_advance(BUS, 1000);
    tb_expect_none(BUS);
    assert_int_equal(pfx_get(&fx, 0x6040, 0), 0);
    tb_send(BUS, "000 01 01");
    tb_expect(BUS, "181 40 00");
    tb_send(BUS, "080");
    tb_expect(BUS, "281 00 00 00"); /* TPDO2 (0x2008, 0x2007) at the SYNC */
    assert_int_equal(pfx_get(&fx, 0x6040, 0), 0);
}

static void cob_change_and_reset(void **state)
{
    (void)state;
    pfx_start(&fx, 1, NULL);
    tb_xfer(BUS, "601 23 00 14 01 01 02 00 80", "581 60 00 14 01 00 00 00 00");
    tb_xfer(BUS, "601 23 00 14 01 A1 02 00 00", "581 60 00 14 01 00 00 00 00");
    tb_send(BUS, "000 01 01");
    tb_flush(BUS);
    tb_send(BUS, "201 11 00");
    assert_int_equal(pfx_get(&fx, 0x6040, 0), 0);
    tb_send(BUS, "2A1 22 00");
    assert_int_equal(pfx_get(&fx, 0x6040, 0), 0x22);
    /* remapped TPDO1 is back to its default after a reset communication */
    tb_send(BUS, "000 80 01");
    tb_xfer(BUS, "601 23 00 18 01 81 01 00 80", "581 60 00 18 01 00 00 00 00");
    tb_xfer(BUS, "601 2F 00 1A 00 00 00 00 00", "581 60 00 1A 00 00 00 00 00");
    tb_send(BUS, "000 82 01");
    tb_expect(BUS, "701 00");
    tb_xfer(BUS, "601 40 00 1A 00 00 00 00 00", "581 4F 00 1A 00 01 00 00 00");
    tb_xfer(BUS, "601 40 00 18 01 00 00 00 00", "581 43 00 18 01 81 01 00 00");
    tb_send(BUS, "000 01 01");
    tb_expect(BUS, "181 00 00");
    tb_send(BUS, "201 33 00");
    assert_int_equal(pfx_get(&fx, 0x6040, 0), 0x33);
}

/* set.pdo.tpdo_after_rpdo (Wandfluh DSV): an applied RPDO n requests TPDO n
 * when that has type 255, with the data of then, also when they did not
 * change; not a TPDO of another type, nor one that is not valid. */
static void tpdo_after_rpdo(void **state)
{
    const co_settings_t set = {.pdo.tpdo_after_rpdo = 1U};

    (void)state;
    start_operational(1, &set);
    tb_expect(BUS, "181 00 00"); /* entering Operational */
    tb_send(BUS, "201 05 00");
    assert_int_equal(pfx_get(&fx, 0x6040, 0), 5);
    tb_advance(BUS, 0);
    tb_expect(BUS, "181 00 00"); /* the statusword did not change: requested */
    tb_expect_none(BUS);
    pfx_set(&fx, 0x6041, 0, 0x0007, 2);
    tb_send(BUS, "201 06 00");
    tb_advance(BUS, 0);
    tb_expect(BUS, "181 07 00"); /* a change too: one frame */
    tb_expect_none(BUS);
    /* CiA 301: no request */
    start_operational(1, NULL);
    tb_expect(BUS, "181 00 00");
    tb_send(BUS, "201 05 00");
    tb_advance(BUS, 0);
    tb_expect_none(BUS);
    /* type 254: not requested */
    start_operational(1, &set);
    tb_expect(BUS, "181 00 00");
    tb_xfer(BUS, "601 2F 00 18 02 FE 00 00 00", "581 60 00 18 02 00 00 00 00");
    tb_advance(BUS, 0);
    tb_expect(BUS, "181 00 00"); /* a new type: sent once */
    tb_send(BUS, "201 05 00");
    tb_advance(BUS, 0);
    tb_expect_none(BUS);
    /* TPDO1 not valid: nothing */
    start_operational(1, &set);
    tb_expect(BUS, "181 00 00");
    tb_xfer(BUS, "601 23 00 18 01 81 01 00 80", "581 60 00 18 01 00 00 00 00");
    tb_send(BUS, "201 05 00");
    assert_int_equal(pfx_get(&fx, 0x6040, 0), 5);
    tb_advance(BUS, 0);
    tb_expect_none(BUS);
}

static void tx_path_full(void **state)
{
    (void)state;
    start_operational(1, NULL);
    tb_expect(BUS, "181 00 00");
    /* the HAL refuses: the TPDO stays due and goes with the data of then */
    fx.bus.refuse = 1;
    pfx_set(&fx, 0x6041, 0, 0x0005, 2);
    tb_advance(BUS, 0);
    tb_expect_none(BUS);
    assert_int_equal(fx.bus.refused, 1);
    pfx_set(&fx, 0x6041, 0, 0x0006, 2);
    tb_advance(BUS, 1000);
    tb_expect(BUS, "181 06 00");
    tb_expect_none(BUS);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(ssd_630_event_driven),
        cmocka_unit_test(ssd_630_interpolated_position),
        cmocka_unit_test(kollmorgen_jog_by_pdo),
        cmocka_unit_test(sync_every_nth),
        cmocka_unit_test(acyclic_sync_type0),
        cmocka_unit_test(counter_and_start_value),
        cmocka_unit_test(rtr_types),
        cmocka_unit_test(inhibit_and_event_timer),
        cmocka_unit_test(event_timer_unit_option),
        cmocka_unit_test(no_change_detect_option),
        cmocka_unit_test(inhibit_after_long_silence),
        cmocka_unit_test(tpdo_change_masks),
        cmocka_unit_test(tpdo_mask_high_bytes),
        cmocka_unit_test(sync_window),
        cmocka_unit_test(rpdo_length_emcy),
        cmocka_unit_test(rpdo_short_option),
        cmocka_unit_test(rpdo_timeout),
        cmocka_unit_test(tpdo_after_rpdo),
        cmocka_unit_test(bit_and_byte_mapping),
        cmocka_unit_test(full_size_values),
        cmocka_unit_test(dictionary_path),
        cmocka_unit_test(sdo_server_cob_ids_in_16_bits),
        cmocka_unit_test(nmt_states),
        cmocka_unit_test(cob_change_and_reset),
        cmocka_unit_test(tx_path_full),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
