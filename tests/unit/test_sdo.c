/*
 * SDO server: expedited and segmented transfers, every abort code the access
 * path produces, and the SDO telegrams of the seed digests (SSD 630 §14.1-14.7,
 * FAULHABER and Kollmorgen), with the digests' corrections.
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
#define RAMV (FX->n.ram)

/* ---------------------------------------------------------- SSD 630 §14 */

static void ssd_14_3_read_device_type(void **state)
{
    tb_xfer(BUS, "601 40 00 10 00 00 00 00 00", "581 43 00 10 00 92 01 02 00");
}

static void ssd_14_4_corrected_error_register_and_identity_count(void **state)
{
    tb_xfer(BUS, "601 40 01 10 00 00 00 00 00", "581 4F 01 10 00 00 00 00 00");
    tb_xfer(BUS, "601 40 18 10 00 00 00 00 00", "581 4F 18 10 00 04 00 00 00");
}

static void ssd_14_5_manufacturer_status(void **state)
{
    tb_xfer(BUS, "601 40 02 10 00 00 00 00 00", "581 43 02 10 00 00 00 00 00");
}

static void ssd_14_6_node_id_corrected(void **state)
{
    tb_xfer(BUS, "601 40 0B 10 00 00 00 00 00", "581 43 0B 10 00 01 00 00 00");
}

static void ssd_14_7_segmented_upload_device_name(void **state)
{
    tb_xfer(BUS, "601 40 08 10 00 00 00 00 00", "581 41 08 10 00 07 00 00 00");
    /* the master fills reserved bytes 1..3; the server ignores them */
    tb_xfer(BUS, "601 60 08 10 00 00 00 00 00", "581 01 36 33 31 5F 34 30 32");
}

static void ssd_14_1_unknown_index_strict_and_630(void **state)
{
    static td_node_t ssd;
    co_dev_t dev = td_dev;
    /* strict CiA 301: object does not exist */
    tb_xfer(BUS, "601 40 34 12 00 00 00 00 00", "581 80 34 12 00 00 00 02 06");
    /* SSD 630 personality option: access not supported */
    dev.set = (co_settings_t){.sdo.unknown_object = CO_SDO_ABORT_NO_ACCESS, .sdo.read_only = CO_SDO_ABORT_NO_ACCESS};
    td_start(&ssd, BUS, 1, 4, &dev);
    tb_expect(BUS, "704 00");
    tb_xfer(BUS, "604 40 34 12 00 00 00 00 00", "584 80 34 12 00 00 00 01 06");
    tb_xfer(BUS, "604 23 00 10 00 00 00 00 00", "584 80 00 10 00 00 00 01 06");
    tb_xfer(BUS, "604 40 0B 10 00 00 00 00 00", "584 43 0B 10 00 04 00 00 00");
    BUS->nodes[1] = NULL;
}

/* SSD 630 (D3.2): expedited up- and download and segmented upload only; a
 * segmented download is refused at its initiate with 0x06010000 (the
 * drive's abort list has no 0x0504xxxx code), after the object's own
 * errors. */
static void ssd_no_segmented_download(void **state)
{
    static td_node_t ssd;
    co_dev_t dev = td_dev;

    dev.set = (co_settings_t){.sdo.refused = CO_SDO_XFER_SEG_DOWNLOAD};
    td_start(&ssd, BUS, 1, 4, &dev);
    tb_expect(BUS, "704 00");
    /* size indicated or not, a string or a fixed-size value */
    tb_xfer(BUS, "604 21 12 20 00 0A 00 00 00", "584 80 12 20 00 00 00 01 06");
    tb_xfer(BUS, "604 20 06 20 00 00 00 00 00", "584 80 06 20 00 00 00 01 06");
    tb_xfer(BUS, "604 21 04 20 00 04 00 00 00", "584 80 04 20 00 00 00 01 06");
    /* nothing is open: a segment afterwards has no transfer */
    tb_xfer(BUS, "604 00 43 41 4E 6F 70 65 6E", "584 80 00 00 00 01 00 04 05");
    assert_string_equal(ssd.ram.vstr, "hello");
    /* the object's own errors first */
    tb_xfer(BUS, "604 21 34 12 00 04 00 00 00", "584 80 34 12 00 00 00 02 06");
    tb_xfer(BUS, "604 21 00 10 00 04 00 00 00", "584 80 00 10 00 02 00 01 06");
    tb_xfer(BUS, "604 21 04 20 00 08 00 00 00", "584 80 04 20 00 10 00 07 06");
    /* expedited download, segmented upload as before */
    tb_xfer(BUS, "604 23 04 20 00 78 56 34 12", "584 60 04 20 00 00 00 00 00");
    assert_int_equal(ssd.ram.u32, 0x12345678UL);
    tb_xfer(BUS, "604 40 08 10 00 00 00 00 00", "584 41 08 10 00 07 00 00 00");
    tb_xfer(BUS, "604 60 00 00 00 00 00 00 00", "584 01 36 33 31 5F 34 30 32");
    /* CiA 301 (node 1, no option): the same initiate opens the transfer */
    tb_xfer(BUS, "601 21 12 20 00 0A 00 00 00", "581 60 12 20 00 00 00 00 00");
    BUS->nodes[1] = NULL;
}

static void ssd_derived_vectors(void **state)
{
    /* unknown sub-index */
    tb_xfer(BUS, "601 40 18 10 05 00 00 00 00", "581 80 18 10 05 11 00 09 06");
    /* write to a read-only object, strict */
    tb_xfer(BUS, "601 23 00 10 00 00 00 00 00", "581 80 00 10 00 02 00 01 06");
    /* 1-byte write to the 16-bit controlword */
    tb_xfer(BUS, "601 2F 40 60 00 0F 00 00 00", "581 80 40 60 00 10 00 07 06");
    /* clear the error history */
    tb_xfer(BUS, "601 2F 03 10 00 00 00 00 00", "581 60 03 10 00 00 00 00 00");
}

/* ---------------------------------------------------------- FAULHABER */

/* FAULHABER digest 7.4/7.5 host examples, frames derived for node 2; the
 * profile's reaction is the CiA 402 issue's, the SDO layer's answer is here. */
static void faulhaber_7_5_host_examples_node2(void **state)
{
    static td_node_t fh;
    td_start(&fh, BUS, 1, 2, NULL);
    tb_expect(BUS, "702 00");
    tb_xfer(BUS, "602 2B 40 60 00 06 00 00 00", "582 60 40 60 00 00 00 00 00");
    tb_xfer(BUS, "602 2F 60 60 00 03 00 00 00", "582 60 60 60 00 00 00 00 00");
    tb_xfer(BUS, "602 23 FF 60 00 F4 01 00 00", "582 60 FF 60 00 00 00 00 00");
    assert_int_equal(fh.ram.target_vel, 500);
    tb_xfer(BUS, "602 2F 60 60 00 01 00 00 00", "582 60 60 60 00 00 00 00 00");
    tb_xfer(BUS, "602 23 7A 60 00 10 27 00 00", "582 60 7A 60 00 00 00 00 00");
    assert_int_equal(fh.ram.target_pos, 10000);
    tb_xfer(BUS, "602 2B 40 60 00 7F 00 00 00", "582 60 40 60 00 00 00 00 00");
    assert_int_equal(fh.ram.cw, 0x007F);
    /* 7.9: consumer heartbeat of master 0x7F with 1500 ms */
    tb_xfer(BUS, "602 23 16 10 01 DC 05 7F 00", "582 60 16 10 01 00 00 00 00");
    tb_xfer(BUS, "602 40 16 10 01 00 00 00 00", "582 43 16 10 01 DC 05 7F 00");
    /* node 1 did not answer any of it */
    BUS->nodes[1] = NULL;
}

/* ---------------------------------------------------------- Kollmorgen */

/* Kollmorgen digest 7.3/7.9 (node 3): expedited-only SDO server. */
static void kollmorgen_7_9_expedited_only_node3(void **state)
{
    static td_node_t ko;
    co_dev_t dev = td_dev;
    dev.set = (co_settings_t){.sdo.refused = CO_SDO_EXPEDITED_ONLY};
    td_start(&ko, BUS, 1, 3, &dev);
    tb_expect(BUS, "703 00");
    tb_xfer(BUS, "603 2F 60 60 00 03 00 00 00", "583 60 60 60 00 00 00 00 00");
    tb_xfer(BUS, "603 23 FF 60 00 00 41 00 00", "583 60 FF 60 00 00 00 00 00");
    assert_int_equal(ko.ram.target_vel, 0x4100);
    tb_xfer(BUS, "603 2B 40 60 00 0F 01 00 00", "583 60 40 60 00 00 00 00 00");
    /* step 23/24: 72000 exceeds the object's maximum */
    tb_xfer(BUS, "603 23 99 60 01 40 19 01 00", "583 80 99 60 01 31 00 09 06");
    assert_int_equal(ko.ram.homing_speed[0], 0);
    tb_xfer(BUS, "603 23 99 60 01 A0 8C 00 00", "583 60 99 60 01 00 00 00 00");
    /* no segmented or block transfer on this device */
    tb_xfer(BUS, "603 21 12 20 00 0A 00 00 00", "583 80 12 20 00 01 00 04 05");
    tb_xfer(BUS, "603 C6 12 20 00 0A 00 00 00", "583 80 12 20 00 01 00 04 05");
    tb_xfer(BUS, "603 40 08 10 00 00 00 00 00", "583 80 08 10 00 00 00 01 06");
    BUS->nodes[1] = NULL;
}

/* ---------------------------------------------------------- expedited */

static void expedited_download_all_sizes(void **state)
{
    tb_xfer(BUS, "601 2F 00 20 00 AB 00 00 00", "581 60 00 20 00 00 00 00 00");
    assert_int_equal(RAMV.u8, 0xAB);
    tb_xfer(BUS, "601 2B 02 20 00 34 12 00 00", "581 60 02 20 00 00 00 00 00");
    assert_int_equal(RAMV.u16, 0x1234);
    tb_xfer(BUS, "601 27 0B 20 00 01 02 03 00", "581 60 0B 20 00 00 00 00 00");
    assert_memory_equal(RAMV.u24, "\x01\x02\x03", 3);
    tb_xfer(BUS, "601 23 05 20 00 60 79 FE FF", "581 60 05 20 00 00 00 00 00");
    assert_int_equal(RAMV.i32, -100000);
    /* size not indicated: the object's size is used */
    tb_xfer(BUS, "601 22 04 20 00 78 56 34 12", "581 60 04 20 00 00 00 00 00");
    assert_int_equal(RAMV.u32, 0x12345678UL);
    tb_xfer(BUS, "601 22 03 20 00 F6 FE 00 00", "581 60 03 20 00 00 00 00 00");
    assert_int_equal(RAMV.i16, -266);
}

/* An expedited download is written straight from the request (no transfer
 * state, no staging copy): the answer, the value, and each refusal it can
 * give, every one of which leaves the old value. */
static void expedited_download_answers_and_refusals(void **state)
{
    /* 0x1017, an object with a service hook (heartbeat producer) */
    tb_xfer(BUS, "601 2B 17 10 00 E8 03 00 00", "581 60 17 10 00 00 00 00 00");
    assert_int_equal(RAMV.hb_prod, 1000);
    /* size not indicated: the object's two bytes, the rest ignored */
    tb_xfer(BUS, "601 22 17 10 00 F4 01 FF FF", "581 60 17 10 00 00 00 00 00");
    assert_int_equal(RAMV.hb_prod, 500);
    /* 1, 3 or 4 bytes to a 16-bit object; 4 bytes without an indication to
     * a 64-bit one: 0x06070010 */
    tb_xfer(BUS, "601 2F 17 10 00 01 00 00 00", "581 80 17 10 00 10 00 07 06");
    tb_xfer(BUS, "601 27 17 10 00 01 00 00 00", "581 80 17 10 00 10 00 07 06");
    tb_xfer(BUS, "601 23 17 10 00 01 00 00 00", "581 80 17 10 00 10 00 07 06");
    assert_int_equal(RAMV.hb_prod, 500);
    RAMV.u64 = 7U;
    tb_xfer(BUS, "601 22 06 20 00 01 00 00 00", "581 80 06 20 00 10 00 07 06");
    assert_true(RAMV.u64 == 7U);
    /* the service's check refuses (one consumer entry per producer) */
    tb_xfer(BUS, "601 23 16 10 01 2C 01 05 00", "581 60 16 10 01 00 00 00 00");
    tb_xfer(BUS, "601 23 16 10 02 F4 01 05 00", "581 80 16 10 02 43 00 04 06");
    assert_int_equal(RAMV.hb_cons[1], 0);
    /* a value out of the type's range, a limit */
    RAMV.b = 1U;
    tb_xfer(BUS, "601 2F 0A 20 00 02 00 00 00", "581 80 0A 20 00 30 00 09 06");
    assert_int_equal(RAMV.b, 1);
    /* not writable, not there */
    tb_xfer(BUS, "601 23 00 10 00 00 00 00 00", "581 80 00 10 00 02 00 01 06");
    tb_xfer(BUS, "601 23 23 20 00 00 00 00 00", "581 80 23 20 00 02 00 01 06");
    tb_xfer(BUS, "601 2B 34 12 00 00 00 00 00", "581 80 34 12 00 00 00 02 06");
    tb_xfer(BUS, "601 2B 17 10 01 00 00 00 00", "581 80 17 10 01 11 00 09 06");
    assert_int_equal(RAMV.hb_prod, 500);
    /* a string: the bytes given, the rest of the object zeroed */
    tb_xfer(BUS, "601 23 12 20 00 41 42 43 44", "581 60 12 20 00 00 00 00 00");
    assert_string_equal(RAMV.vstr, "ABCD");
    tb_xfer(BUS, "601 2B 12 20 00 58 59 43 44", "581 60 12 20 00 00 00 00 00");
    assert_string_equal(RAMV.vstr, "XY");
    /* an abort shorter than 8 bytes while nothing is open: no answer */
    tb_send(BUS, "601 80 17 10 00");
    tb_expect_none(BUS);
}

static void expedited_upload_all_sizes(void **state)
{
    RAMV.u8 = 0x7F;
    RAMV.i16 = -266;
    RAMV.u32 = 0x01020304UL;
    tb_xfer(BUS, "601 40 00 20 00 00 00 00 00", "581 4F 00 20 00 7F 00 00 00");
    tb_xfer(BUS, "601 40 03 20 00 00 00 00 00", "581 4B 03 20 00 F6 FE 00 00");
    tb_xfer(BUS, "601 40 04 20 00 00 00 00 00", "581 43 04 20 00 04 03 02 01");
    memcpy(RAMV.i24, "\xAA\xBB\xCC", 3);
    tb_xfer(BUS, "601 40 0C 20 00 00 00 00 00", "581 47 0C 20 00 AA BB CC 00");
    /* data in sub-index 0 of a record */
    tb_xfer(BUS, "601 40 00 23 00 00 00 00 00", "581 43 00 23 00 44 33 22 11");
    tb_xfer(BUS, "601 40 00 23 01 00 00 00 00", "581 4B 00 23 01 07 00 00 00");
}

static void boolean_accepts_only_0_and_1(void **state)
{
    tb_xfer(BUS, "601 2F 0A 20 00 01 00 00 00", "581 60 0A 20 00 00 00 00 00");
    tb_xfer(BUS, "601 2F 0A 20 00 02 00 00 00", "581 80 0A 20 00 30 00 09 06");
    assert_int_equal(RAMV.b, 1);
}


static void limits_checked(void **state)
{
    /* 0x2020 u16 10..1000 */
    tb_xfer(BUS, "601 2B 20 20 00 E8 03 00 00", "581 60 20 20 00 00 00 00 00");
    assert_int_equal(RAMV.lim_u16, 1000);
    tb_xfer(BUS, "601 2B 20 20 00 E9 03 00 00", "581 80 20 20 00 31 00 09 06");
    tb_xfer(BUS, "601 2B 20 20 00 09 00 00 00", "581 80 20 20 00 32 00 09 06");
    assert_int_equal(RAMV.lim_u16, 1000);
    /* 0x2021 i16 -100..100, signed comparison */
    tb_xfer(BUS, "601 2B 21 20 00 9C FF 00 00", "581 60 21 20 00 00 00 00 00");
    assert_int_equal(RAMV.lim_i16, -100);
    tb_xfer(BUS, "601 2B 21 20 00 9B FF 00 00", "581 80 21 20 00 32 00 09 06");
    tb_xfer(BUS, "601 2B 21 20 00 65 00 00 00", "581 80 21 20 00 31 00 09 06");
    assert_int_equal(RAMV.lim_i16, -100);
}

static void access_aborts(void **state)
{
    /* write-only read */
    tb_xfer(BUS, "601 40 22 20 00 00 00 00 00", "581 80 22 20 00 01 00 01 06");
    tb_xfer(BUS, "601 23 22 20 00 01 00 00 00", "581 60 22 20 00 00 00 00 00");
    assert_int_equal(RAMV.wo_u32, 1);
    /* const */
    tb_xfer(BUS, "601 23 23 20 00 00 00 00 00", "581 80 23 20 00 02 00 01 06");
    tb_xfer(BUS, "601 40 23 20 00 00 00 00 00", "581 43 23 20 00 0D F0 FE CA");
    /* 0x1003 sub0 accepts only 0 */
    tb_xfer(BUS, "601 2F 03 10 00 01 00 00 00", "581 80 03 10 00 30 00 09 06");
    /* 0x1003 sub1 without a recorded error: no data */
    tb_xfer(BUS, "601 40 03 10 01 00 00 00 00", "581 80 03 10 01 24 00 00 08");
    /* history entries are read-only */
    tb_xfer(BUS, "601 23 03 10 01 00 00 00 00", "581 80 03 10 01 02 00 01 06");
}

static void size_aborts(void **state)
{
    /* 4 bytes to a 16-bit object, 2 bytes to a 32-bit object */
    tb_xfer(BUS, "601 23 02 20 00 01 00 00 00", "581 80 02 20 00 10 00 07 06");
    tb_xfer(BUS, "601 2B 04 20 00 01 00 00 00", "581 80 04 20 00 10 00 07 06");
    /* segmented initiate announcing 40 bytes to a 32-byte string */
    tb_xfer(BUS, "601 21 12 20 00 28 00 00 00", "581 80 12 20 00 12 00 07 06");
    /* segmented initiate announcing 3 bytes for a 64-bit value */
    tb_xfer(BUS, "601 21 06 20 00 03 00 00 00", "581 80 06 20 00 10 00 07 06");
    assert_int_equal(RAMV.u16, 0x1234);
}

static void unknown_command_specifier(void **state)
{
    tb_xfer(BUS, "601 E0 00 10 00 00 00 00 00", "581 80 00 10 00 01 00 04 05");
    /* a download segment without an initiate */
    tb_xfer(BUS, "601 00 43 41 4E 6F 70 65 6E", "581 80 00 00 00 01 00 04 05");
    /* upload segment request without an initiate */
    tb_xfer(BUS, "601 60 00 00 00 00 00 00 00", "581 80 00 00 00 01 00 04 05");
    /* short SDO frame */
    tb_xfer(BUS, "601 40 00 10 00", "581 80 00 10 00 01 00 04 05");
    /* an abort from the client while idle gets no answer */
    tb_send(BUS, "601 80 00 10 00 00 00 00 00");
    tb_expect_none(BUS);
}

/* ---------------------------------------------------------- segmented */

static void segmented_download_string(void **state)
{
    tb_xfer(BUS, "601 21 12 20 00 0A 00 00 00", "581 60 12 20 00 00 00 00 00");
    tb_xfer(BUS, "601 00 43 41 4E 6F 70 65 6E", "581 20 00 00 00 00 00 00 00");
    tb_xfer(BUS, "601 19 20 34 32 00 00 00 00", "581 30 00 00 00 00 00 00 00");
    assert_string_equal(RAMV.vstr, "CANopen 42");
    /* read it back: 10 bytes, segmented */
    tb_xfer(BUS, "601 40 12 20 00 00 00 00 00", "581 41 12 20 00 0A 00 00 00");
    tb_xfer(BUS, "601 60 00 00 00 00 00 00 00", "581 00 43 41 4E 6F 70 65 6E");
    tb_xfer(BUS, "601 70 00 00 00 00 00 00 00", "581 19 20 34 32 00 00 00 00");
}

static void segmented_download_u64_without_size(void **state)
{
    tb_xfer(BUS, "601 20 06 20 00 00 00 00 00", "581 60 06 20 00 00 00 00 00");
    tb_xfer(BUS, "601 00 01 02 03 04 05 06 07", "581 20 00 00 00 00 00 00 00");
    tb_xfer(BUS, "601 1D 08 00 00 00 00 00 00", "581 30 00 00 00 00 00 00 00");
    assert_true(RAMV.u64 == 0x0807060504030201ULL);
    tb_xfer(BUS, "601 40 06 20 00 00 00 00 00", "581 41 06 20 00 08 00 00 00");
    tb_xfer(BUS, "601 60 00 00 00 00 00 00 00", "581 00 01 02 03 04 05 06 07");
    tb_xfer(BUS, "601 70 00 00 00 00 00 00 00", "581 1D 08 00 00 00 00 00 00");
}

static void segmented_toggle_error(void **state)
{
    tb_xfer(BUS, "601 21 12 20 00 0A 00 00 00", "581 60 12 20 00 00 00 00 00");
    tb_xfer(BUS, "601 10 43 41 4E 6F 70 65 6E", "581 80 12 20 00 00 00 03 05");
    /* upload toggle */
    tb_xfer(BUS, "601 40 08 10 00 00 00 00 00", "581 41 08 10 00 07 00 00 00");
    tb_xfer(BUS, "601 70 00 00 00 00 00 00 00", "581 80 08 10 00 00 00 03 05");
    assert_string_equal(RAMV.vstr, "hello");
}

static void segmented_length_mismatch(void **state)
{
    /* announced 10, last segment ends at 7: too short */
    tb_xfer(BUS, "601 21 12 20 00 0A 00 00 00", "581 60 12 20 00 00 00 00 00");
    tb_xfer(BUS, "601 01 43 41 4E 6F 70 65 6E", "581 80 12 20 00 13 00 07 06");
    /* announced 3, first segment carries 7: too long */
    tb_xfer(BUS, "601 21 12 20 00 03 00 00 00", "581 60 12 20 00 00 00 00 00");
    tb_xfer(BUS, "601 00 43 41 4E 6F 70 65 6E", "581 80 12 20 00 12 00 07 06");
}

static void segmented_timeout(void **state)
{
    tb_xfer(BUS, "601 21 12 20 00 0A 00 00 00", "581 60 12 20 00 00 00 00 00");
    tb_advance(BUS, 999000U);
    tb_expect_none(BUS);
    tb_advance(BUS, 2000U);
    tb_expect(BUS, "581 80 12 20 00 00 00 04 05");
    tb_expect_none(BUS);
    /* the server is idle again */
    tb_xfer(BUS, "601 40 00 10 00 00 00 00 00", "581 43 00 10 00 92 01 02 00");
}

/* co_node_config_t.sdo_timeout_ms (the node keeps it in 2 bytes): an open
 * transfer is aborted that many ms after the last request; the largest,
 * 65,535 ms, holds as well (0: 1 s, segmented_timeout) */
static void configured_timeout(void **state)
{
    static const uint16_t ms[] = {250U, 65535U};

    for (uint32_t k = 0U; k < 2U; k++) {
        static td_node_t n;
        co_node_config_t cfg;
        memset(&n, 0, sizeof n);
        memset(&cfg, 0, sizeof cfg);
        cfg.dev = &td_dev;
        cfg.hal = tb_hal(BUS, 1);
        cfg.node_id = 4U;
        cfg.ram = &n.ram;
        cfg.sdo_timeout_ms = ms[k];
        tb_attach(BUS, 1, &n.node);
        assert_int_equal(co_node_init(&n.node, &cfg, BUS->now), CO_RESULT_OK);
        tb_expect(BUS, "704 00");
        tb_xfer(BUS, "604 21 12 20 00 0A 00 00 00", "584 60 12 20 00 00 00 00 00");
        /* a segment restarts the timer (and the toggle alternates) */
        tb_advance(BUS, 1000U * ms[k] - 1U);
        tb_xfer(BUS, "604 00 43 41 4E 6F 70 65 6E", "584 20 00 00 00 00 00 00 00");
        tb_advance(BUS, 1000U * ms[k] - 1U);
        tb_expect_none(BUS);
        tb_advance(BUS, 1U);
        tb_expect(BUS, "584 80 12 20 00 00 00 04 05");
        tb_expect_none(BUS);
        BUS->nodes[1] = NULL;
    }
}

static void new_request_during_transfer_is_refused(void **state)
{
    tb_xfer(BUS, "601 21 12 20 00 0A 00 00 00", "581 60 12 20 00 00 00 00 00");
    tb_xfer(BUS, "601 40 00 10 00 00 00 00 00", "581 80 12 20 00 01 00 04 05");
    /* client abort ends a transfer silently */
    tb_xfer(BUS, "601 21 12 20 00 0A 00 00 00", "581 60 12 20 00 00 00 00 00");
    tb_send(BUS, "601 80 12 20 00 00 00 04 05");
    tb_expect_none(BUS);
    tb_xfer(BUS, "601 40 00 10 00 00 00 00 00", "581 43 00 10 00 92 01 02 00");
}

static void empty_and_short_strings(void **state)
{
    /* expedited write of a 2-byte string */
    tb_xfer(BUS, "601 2B 12 20 00 48 69 00 00", "581 60 12 20 00 00 00 00 00");
    assert_string_equal(RAMV.vstr, "Hi");
    tb_xfer(BUS, "601 40 12 20 00 00 00 00 00", "581 4B 12 20 00 48 69 00 00");
    /* empty string: segmented, size 0, one empty last segment */
    memset(RAMV.vstr, 0, sizeof RAMV.vstr);
    tb_xfer(BUS, "601 40 12 20 00 00 00 00 00", "581 41 12 20 00 00 00 00 00");
    tb_xfer(BUS, "601 60 00 00 00 00 00 00 00", "581 0F 00 00 00 00 00 00 00");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(ssd_14_3_read_device_type, setup),
        cmocka_unit_test_setup(ssd_14_4_corrected_error_register_and_identity_count, setup),
        cmocka_unit_test_setup(ssd_14_5_manufacturer_status, setup),
        cmocka_unit_test_setup(ssd_14_6_node_id_corrected, setup),
        cmocka_unit_test_setup(ssd_14_7_segmented_upload_device_name, setup),
        cmocka_unit_test_setup(ssd_14_1_unknown_index_strict_and_630, setup),
        cmocka_unit_test_setup(ssd_no_segmented_download, setup),
        cmocka_unit_test_setup(ssd_derived_vectors, setup),
        cmocka_unit_test_setup(faulhaber_7_5_host_examples_node2, setup),
        cmocka_unit_test_setup(kollmorgen_7_9_expedited_only_node3, setup),
        cmocka_unit_test_setup(expedited_download_all_sizes, setup),
        cmocka_unit_test_setup(expedited_download_answers_and_refusals, setup),
        cmocka_unit_test_setup(expedited_upload_all_sizes, setup),
        cmocka_unit_test_setup(boolean_accepts_only_0_and_1, setup),
        cmocka_unit_test_setup(limits_checked, setup),
        cmocka_unit_test_setup(access_aborts, setup),
        cmocka_unit_test_setup(size_aborts, setup),
        cmocka_unit_test_setup(unknown_command_specifier, setup),
        cmocka_unit_test_setup(segmented_download_string, setup),
        cmocka_unit_test_setup(segmented_download_u64_without_size, setup),
        cmocka_unit_test_setup(segmented_toggle_error, setup),
        cmocka_unit_test_setup(segmented_length_mismatch, setup),
        cmocka_unit_test_setup(segmented_timeout, setup),
        cmocka_unit_test_setup(configured_timeout, setup),
        cmocka_unit_test_setup(new_request_during_transfer_is_refused, setup),
        cmocka_unit_test_setup(empty_and_short_strings, setup),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
