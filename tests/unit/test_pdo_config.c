/*
 * PDO configuration over SDO: the CiA 301 mapping procedure and each of its
 * aborts, COB-ID, transmission type, inhibit time and start value rules, the
 * option for devices that remap valid PDOs (SSD 630, Kollmorgen), and the
 * seed manuals' mapping telegrams (SSD 630 14.12/14.13, Kollmorgen 5.3/6.3.5).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "pdo_fx.h"

static pfx_t fx;
#define BUS (&fx.bus)

static void mapping_needs_invalid_pdo(void **state)
{
    (void)state;
    pfx_start(&fx, 1, NULL);
    /* TPDO1 is valid: its mapping is locked (0x08000022) */
    tb_xfer(BUS, "601 2F 00 1A 00 00 00 00 00", "581 80 00 1A 00 22 00 00 08");
    tb_xfer(BUS, "601 23 00 1A 01 10 00 41 60", "581 80 00 1A 01 22 00 00 08");
    /* invalidate TPDO1 (bit 31) */
    tb_xfer(BUS, "601 23 00 18 01 81 01 00 80", "581 60 00 18 01 00 00 00 00");
    /* entries are fixed while sub0 != 0 (0x06010000) */
    tb_xfer(BUS, "601 23 00 1A 01 10 00 41 60", "581 80 00 1A 01 00 00 01 06");
    tb_xfer(BUS, "601 2F 00 1A 00 00 00 00 00", "581 60 00 1A 00 00 00 00 00");
    tb_xfer(BUS, "601 23 00 1A 01 20 00 13 20", "581 80 00 1A 01 41 00 04 06"); /* not mappable */
    tb_xfer(BUS, "601 23 00 1A 01 10 00 99 99", "581 80 00 1A 01 00 00 02 06"); /* no object */
    tb_xfer(BUS, "601 23 00 1A 01 10 01 41 60", "581 80 00 1A 01 41 00 04 06"); /* no sub 1 */
    tb_xfer(BUS, "601 23 00 1A 01 40 00 14 20", "581 80 00 1A 01 41 00 04 06"); /* a string */
    tb_xfer(BUS, "601 23 00 1A 01 10 00 40 60", "581 80 00 1A 01 41 00 04 06"); /* RPDO-only */
    tb_xfer(BUS, "601 23 00 1A 01 08 00 05 00", "581 80 00 1A 01 41 00 04 06"); /* dummy in TPDO */
    tb_xfer(BUS, "601 23 00 1A 01 20 00 41 60", "581 80 00 1A 01 43 00 04 06"); /* 32 > 16 bits */
    tb_xfer(BUS, "601 23 00 1A 01 00 00 41 60", "581 80 00 1A 01 43 00 04 06"); /* 0 bits */
    /* 64 + 8 bits: each entry is fine, the sum is not (0x06040042) */
    tb_xfer(BUS, "601 23 00 1A 01 40 00 05 20", "581 60 00 1A 01 00 00 00 00");
    tb_xfer(BUS, "601 23 00 1A 02 08 00 07 20", "581 60 00 1A 02 00 00 00 00");
    tb_xfer(BUS, "601 2F 00 1A 00 02 00 00 00", "581 80 00 1A 00 42 00 04 06");
    tb_xfer(BUS, "601 2F 00 1A 00 09 00 00 00", "581 80 00 1A 00 42 00 04 06"); /* > 8 entries */
    tb_xfer(BUS, "601 40 00 1A 00 00 00 00 00", "581 4F 00 1A 00 00 00 00 00");
    /* one entry fits; the PDO becomes valid again */
    tb_xfer(BUS, "601 2F 00 1A 00 01 00 00 00", "581 60 00 1A 00 00 00 00 00");
    tb_xfer(BUS, "601 23 00 18 01 81 01 00 00", "581 60 00 18 01 00 00 00 00");
    tb_xfer(BUS, "601 40 00 1A 00 00 00 00 00", "581 4F 00 1A 00 01 00 00 00");
    tb_xfer(BUS, "601 40 00 1A 01 00 00 00 00", "581 43 00 1A 01 40 00 05 20");
}

/* A frame "601 23 II II SS BB ss ii ii" (download of mapping entry @p sub of
 * @p index: @p v) or its answer, as tb_xfer's text. */
static void entry_frame(char *out, size_t cap, const char *head, uint16_t index, uint8_t sub,
                        uint32_t v)
{
    (void)snprintf(out, cap, "%s %02X %02X %02X %02X %02X %02X %02X", head,
                   (unsigned)(index & 0xFFU), (unsigned)(index >> 8U), (unsigned)sub,
                   (unsigned)(v & 0xFFU), (unsigned)((v >> 8U) & 0xFFU),
                   (unsigned)((v >> 16U) & 0xFFU), (unsigned)(v >> 24U));
}

/* The mapping entries live in the RAM image in 16-bit forms (co_od.h), a
 * reference into the device's mappable-object table: over SDO each reads
 * back as the UNSIGNED32 written, for the objects at both ends of the table
 * and a dummy entry; a refused write leaves the entry as it was; the
 * generator's table is the one co_od_map_table makes from the dictionary. */
static void mapping_entry_forms(void **state)
{
    const co_dev_t *dev = &pdo_test_dev;
    co_od_map_t rows[64];
    uint32_t n = co_od_map_table(dev, rows, 64U);
    char req[64];
    char ans[64];
    (void)state;
    assert_int_equal(n, dev->n_maps);
    assert_true((n >= 2U) && (n <= 64U));
    for (uint32_t k = 0U; k < n; k++) {
        assert_int_equal(rows[k].index, dev->maps[k].index);
        assert_int_equal(rows[k].sub, dev->maps[k].sub);
        assert_int_equal(rows[k].info, dev->maps[k].info);
        assert_int_equal(rows[k].off, dev->maps[k].off);
        if (k > 0U) {
            assert_true(((uint32_t)rows[k - 1U].index << 8U | rows[k - 1U].sub) <
                        ((uint32_t)rows[k].index << 8U | rows[k].sub));
        }
    }
    pfx_start(&fx, 1, NULL);
    tb_xfer(BUS, "601 23 00 14 01 01 02 00 80", "581 60 00 14 01 00 00 00 00");
    tb_xfer(BUS, "601 23 00 18 01 81 01 00 80", "581 60 00 18 01 00 00 00 00");
    tb_xfer(BUS, "601 2F 00 16 00 00 00 00 00", "581 60 00 16 00 00 00 00 00");
    tb_xfer(BUS, "601 2F 00 1A 00 00 00 00 00", "581 60 00 1A 00 00 00 00 00");
    for (uint32_t k = 0U; k < n; k += n - 1U) {
        const co_od_map_t *m = &dev->maps[k];
        const co_od_entry_t *e = co_od_find(dev->od, dev->od_count, m->index);
        co_od_sub_t sd;
        const co_od_sub_t *s = (e != NULL) ? co_od_find_sub(dev, e, m->sub, &sd) : NULL;
        uint16_t map;
        uint32_t v = ((uint32_t)m->index << 16U) | ((uint32_t)m->sub << 8U) |
                     (8U * ((m->info & CO_OD_MAP_SIZE) + 1U));
        assert_non_null(s);
        if (s == NULL) {
            return;
        }
        map = ((s->flags & CO_SUB_MAP_R) != 0U) ? 0x1600U : 0x1A00U;
        entry_frame(req, sizeof req, "601 23", map, 1U, v);
        entry_frame(ans, sizeof ans, "581 60", map, 1U, 0U);
        tb_xfer(BUS, req, ans);
        entry_frame(req, sizeof req, "601 40", map, 1U, 0U);
        entry_frame(ans, sizeof ans, "581 43", map, 1U, v);
        tb_xfer(BUS, req, ans);
        assert_int_equal(pfx_get(&fx, map, 1U), v);
        {
            /* a part of it: its low bytes (the wire image) */
            uint8_t b[2] = {0U, 0U};
            uint32_t len = 0U;
            assert_int_equal(co_od_read(&fx.n.node, map, 1U, b, 2U, &len), CO_ERR_TYPE_TOO_LONG);
            assert_int_equal(len, 2U);
            assert_int_equal(b[0], v & 0xFFU);
            assert_int_equal(b[1], (v >> 8U) & 0xFFU);
        }
        /* refused (no such object: 0x06020000): the entry stays */
        entry_frame(req, sizeof req, "601 23", map, 1U, 0x99990010UL);
        entry_frame(ans, sizeof ans, "581 80", map, 1U, 0x06020000UL);
        tb_xfer(BUS, req, ans);
        entry_frame(req, sizeof req, "601 40", map, 1U, 0U);
        entry_frame(ans, sizeof ans, "581 43", map, 1U, v);
        tb_xfer(BUS, req, ans);
    }
    /* a dummy entry (UNSIGNED16 gap) reads back as written */
    tb_xfer(BUS, "601 23 00 16 02 10 00 06 00", "581 60 00 16 02 00 00 00 00");
    tb_xfer(BUS, "601 40 00 16 02 00 00 00 00", "581 43 00 16 02 10 00 06 00");
    /* and 0 as 0 */
    tb_xfer(BUS, "601 23 00 16 02 00 00 00 00", "581 60 00 16 02 00 00 00 00");
    tb_xfer(BUS, "601 40 00 16 02 00 00 00 00", "581 43 00 16 02 00 00 00 00");
}

static void rpdo_mapping_rules(void **state)
{
    (void)state;
    pfx_start(&fx, 1, NULL);
    tb_xfer(BUS, "601 23 00 14 01 01 02 00 80", "581 60 00 14 01 00 00 00 00");
    tb_xfer(BUS, "601 2F 00 16 00 00 00 00 00", "581 60 00 16 00 00 00 00 00");
    tb_xfer(BUS, "601 23 00 16 01 10 00 41 60", "581 80 00 16 01 41 00 04 06"); /* TPDO-only */
    tb_xfer(BUS, "601 23 00 16 01 10 00 11 20", "581 80 00 16 01 41 00 04 06"); /* rwr */
    tb_xfer(BUS, "601 23 00 16 01 10 00 12 20", "581 60 00 16 01 00 00 00 00"); /* rww */
    tb_xfer(BUS, "601 23 00 16 02 08 00 05 00", "581 60 00 16 02 00 00 00 00"); /* dummy U8 */
    tb_xfer(BUS, "601 23 00 16 03 10 00 05 00", "581 80 00 16 03 43 00 04 06"); /* dummy too long */
    tb_xfer(BUS, "601 23 00 16 03 01 00 01 00", "581 60 00 16 03 00 00 00 00"); /* dummy bit */
    tb_xfer(BUS, "601 2F 00 16 00 03 00 00 00", "581 60 00 16 00 00 00 00 00");
    tb_xfer(BUS, "601 23 00 14 01 01 02 00 00", "581 60 00 14 01 00 00 00 00");
}

static void cob_id_rules(void **state)
{
    (void)state;
    pfx_start(&fx, 1, NULL);
    /* the same CAN-ID while valid is fine (SSD 630 14.11 step 1) */
    tb_xfer(BUS, "601 23 00 14 01 01 02 00 00", "581 60 00 14 01 00 00 00 00");
    tb_xfer(BUS, "601 23 00 18 01 81 01 00 00", "581 60 00 18 01 00 00 00 00");
    /* another CAN-ID only while invalid */
    tb_xfer(BUS, "601 23 00 18 01 82 01 00 00", "581 80 00 18 01 30 00 09 06");
    /* 29-bit frames (bit 29) and bits 11..28 are refused */
    tb_xfer(BUS, "601 23 00 18 01 81 01 00 20", "581 80 00 18 01 30 00 09 06");
    tb_xfer(BUS, "601 23 00 18 01 01 18 00 00", "581 80 00 18 01 30 00 09 06"); /* SSD 1.12 as printed */
    tb_xfer(BUS, "601 23 00 18 01 81 01 00 80", "581 60 00 18 01 00 00 00 00");
    /* restricted identifiers cannot be made valid (CiA 301 7.3.5) */
    tb_xfer(BUS, "601 23 00 18 01 01 06 00 00", "581 80 00 18 01 30 00 09 06"); /* 601 */
    tb_xfer(BUS, "601 23 00 18 01 01 07 00 00", "581 80 00 18 01 30 00 09 06"); /* 701 */
    tb_xfer(BUS, "601 23 00 18 01 00 00 00 00", "581 80 00 18 01 30 00 09 06"); /* 000 */
    tb_xfer(BUS, "601 23 00 18 01 F0 06 00 00", "581 80 00 18 01 30 00 09 06"); /* 6F0 */
    /* but an invalid PDO may hold any identifier, and a free one is taken */
    tb_xfer(BUS, "601 23 00 18 01 01 06 00 80", "581 60 00 18 01 00 00 00 00");
    tb_xfer(BUS, "601 23 00 18 01 A1 01 00 40", "581 60 00 18 01 00 00 00 00");
    tb_xfer(BUS, "601 40 00 18 01 00 00 00 00", "581 43 00 18 01 A1 01 00 40");
}

/* set.pdo.cob_id_while_valid (Kollmorgen, digest D7.13 step 9): the CAN-ID
 * of a valid PDO changes without invalidating it first; the PDO runs on the
 * new identifier at once. The other COB-ID rules stay. */
static void cob_id_while_valid_option(void **state)
{
    (void)state;
    /* strict CiA 301: refused (0x06090030) */
    pfx_start(&fx, 1, NULL);
    tb_xfer(BUS, "601 23 00 14 01 10 02 00 00", "581 80 00 14 01 30 00 09 06");
    tb_xfer(BUS, "601 23 00 18 01 90 01 00 00", "581 80 00 18 01 30 00 09 06");
    /* with the option: taken */
    pfx_start(&fx, 1, &(co_settings_t){.pdo.cob_id_while_valid = 1U});
    tb_xfer(BUS, "601 23 00 14 01 10 02 00 00", "581 60 00 14 01 00 00 00 00");
    tb_xfer(BUS, "601 40 00 14 01 00 00 00 00", "581 43 00 14 01 10 02 00 00");
    tb_xfer(BUS, "601 23 00 18 01 90 01 00 00", "581 60 00 18 01 00 00 00 00");
    /* still refused: a restricted identifier, a 29-bit one */
    tb_xfer(BUS, "601 23 00 18 01 01 06 00 00", "581 80 00 18 01 30 00 09 06");
    tb_xfer(BUS, "601 23 00 18 01 90 01 00 20", "581 80 00 18 01 30 00 09 06");
    pfx_set(&fx, 0x6041, 0, 0x0237, 2);
    tb_send(BUS, "000 01 01");
    tb_expect(BUS, "190 37 02"); /* TPDO1 on its new identifier */
    tb_expect_none(BUS);
    tb_send(BUS, "201 0F 00"); /* the old RPDO1 identifier: nobody's */
    assert_int_equal(pfx_get(&fx, 0x6040, 0), 0);
    tb_send(BUS, "210 0F 00");
    assert_int_equal(pfx_get(&fx, 0x6040, 0), 0x000F);
    /* in Operational too: the valid TPDO moves, and sends its data there */
    tb_xfer(BUS, "601 23 00 18 01 91 01 00 00", "581 60 00 18 01 00 00 00 00");
    tb_advance(BUS, 0);
    tb_expect(BUS, "191 37 02");
    tb_expect_none(BUS);
}

static void comm_parameter_rules(void **state)
{
    (void)state;
    pfx_start(&fx, 1, NULL);
    /* transmission types: TPDO 241..251 reserved; RPDO also 252/253 */
    tb_xfer(BUS, "601 2F 00 18 02 F1 00 00 00", "581 80 00 18 02 30 00 09 06");
    tb_xfer(BUS, "601 2F 00 18 02 FB 00 00 00", "581 80 00 18 02 30 00 09 06");
    tb_xfer(BUS, "601 2F 00 18 02 FC 00 00 00", "581 60 00 18 02 00 00 00 00");
    tb_xfer(BUS, "601 2F 00 18 02 FD 00 00 00", "581 60 00 18 02 00 00 00 00");
    tb_xfer(BUS, "601 2F 00 18 02 00 00 00 00", "581 60 00 18 02 00 00 00 00");
    tb_xfer(BUS, "601 2F 00 14 02 FC 00 00 00", "581 80 00 14 02 30 00 09 06");
    tb_xfer(BUS, "601 2F 00 14 02 FD 00 00 00", "581 80 00 14 02 30 00 09 06");
    tb_xfer(BUS, "601 2F 00 14 02 F0 00 00 00", "581 60 00 14 02 00 00 00 00");
    tb_xfer(BUS, "601 2F 00 14 02 FE 00 00 00", "581 60 00 14 02 00 00 00 00");
    /* inhibit time and start value only while the TPDO is invalid */
    tb_xfer(BUS, "601 2B 00 18 03 0A 00 00 00", "581 80 00 18 03 30 00 09 06");
    tb_xfer(BUS, "601 2F 00 18 06 03 00 00 00", "581 80 00 18 06 30 00 09 06");
    tb_xfer(BUS, "601 2B 00 18 03 00 00 00 00", "581 60 00 18 03 00 00 00 00"); /* unchanged */
    tb_xfer(BUS, "601 23 00 18 01 81 01 00 80", "581 60 00 18 01 00 00 00 00");
    tb_xfer(BUS, "601 2B 00 18 03 0A 00 00 00", "581 60 00 18 03 00 00 00 00");
    tb_xfer(BUS, "601 2F 00 18 06 03 00 00 00", "581 60 00 18 06 00 00 00 00");
    tb_xfer(BUS, "601 2F 00 18 06 F1 00 00 00", "581 80 00 18 06 30 00 09 06");
    /* the event timer may change at any time */
    tb_xfer(BUS, "601 23 00 18 01 81 01 00 00", "581 60 00 18 01 00 00 00 00");
    tb_xfer(BUS, "601 2B 00 18 05 64 00 00 00", "581 60 00 18 05 00 00 00 00");
}

static void mapping_locked_in_operational(void **state)
{
    (void)state;
    /* even with the SSD/Kollmorgen option: no remapping of a valid PDO in
     * Operational */
    pfx_start(&fx, 1, &(co_settings_t){.pdo.mapping_while_valid = 1U});
    tb_send(BUS, "000 01 01");
    tb_flush(BUS);
    tb_xfer(BUS, "601 2F 00 16 00 00 00 00 00", "581 80 00 16 00 22 00 00 08");
    /* an invalid one may be remapped in Operational (CiA 301) */
    tb_xfer(BUS, "601 23 00 14 01 01 02 00 80", "581 60 00 14 01 00 00 00 00");
    tb_xfer(BUS, "601 2F 00 16 00 00 00 00 00", "581 60 00 16 00 00 00 00 00");
}

/* CO_PDO_WRITES_PREOP (SSD 630 §7, digest D§2.3 and D§8.4): PDO
 * communication and mapping parameters are written in Pre-operational only;
 * in Operational (and Stopped) every write answers 0x08000022, reads work. */
static void pdo_config_preop_only_option(void **state)
{
    uint8_t t = 1U;

    (void)state;
    /* CiA 301: communication parameters may change in Operational */
    pfx_start(&fx, 1, NULL);
    tb_send(BUS, "000 01 01");
    tb_flush(BUS);
    tb_xfer(BUS, "601 2F 00 18 02 01 00 00 00", "581 60 00 18 02 00 00 00 00");
    tb_xfer(BUS, "601 2B 00 18 05 64 00 00 00", "581 60 00 18 05 00 00 00 00");
    tb_xfer(BUS, "601 23 00 14 01 01 02 00 80", "581 60 00 14 01 00 00 00 00");
    tb_xfer(BUS, "601 2F 02 16 00 00 00 00 00", "581 60 02 16 00 00 00 00 00"); /* invalid RPDO3 */
    /* the device's option: none of these in Operational */
    pfx_start(&fx, 1, &(co_settings_t){.pdo.parameter_writes = CO_PDO_WRITES_PREOP, .pdo.mapping_while_valid = 1U});
    tb_send(BUS, "000 01 01");
    tb_flush(BUS);
    tb_xfer(BUS, "601 2F 00 18 02 01 00 00 00", "581 80 00 18 02 22 00 00 08");
    tb_xfer(BUS, "601 2B 00 18 05 64 00 00 00", "581 80 00 18 05 22 00 00 08");
    tb_xfer(BUS, "601 23 00 14 01 01 02 00 80", "581 80 00 14 01 22 00 00 08");
    tb_xfer(BUS, "601 23 00 14 01 01 02 00 00", "581 80 00 14 01 22 00 00 08"); /* unchanged */
    tb_xfer(BUS, "601 2F 02 16 00 00 00 00 00", "581 80 02 16 00 22 00 00 08");
    tb_xfer(BUS, "601 2F 00 16 00 00 00 00 00", "581 80 00 16 00 22 00 00 08");
    /* the size is checked first; reads and other objects are not affected */
    tb_xfer(BUS, "601 2B 00 18 02 01 00 00 00", "581 80 00 18 02 10 00 07 06");
    tb_xfer(BUS, "601 40 00 18 02 00 00 00 00", "581 4F 00 18 02 FF 00 00 00");
    tb_xfer(BUS, "601 23 7A 60 00 A0 86 01 00", "581 60 7A 60 00 00 00 00 00");
    /* Stopped: the application is refused too */
    tb_send(BUS, "000 02 01");
    assert_int_equal(co_od_write(&fx.n.node, 0x1800, 2, &t, 1, true), CO_ERR_STORE_STATE);
    /* Pre-operational: all of it */
    tb_send(BUS, "000 80 01");
    tb_flush(BUS);
    assert_int_equal(co_od_write(&fx.n.node, 0x1800, 2, &t, 1, true), CO_OK);
    tb_xfer(BUS, "601 2B 00 18 05 64 00 00 00", "581 60 00 18 05 00 00 00 00");
    tb_xfer(BUS, "601 2F 00 16 00 00 00 00 00", "581 60 00 16 00 00 00 00 00");
    tb_xfer(BUS, "601 2F 00 16 00 01 00 00 00", "581 60 00 16 00 00 00 00 00");
    tb_xfer(BUS, "601 23 00 14 01 01 02 00 80", "581 60 00 14 01 00 00 00 00");
}

/* CO_PDO_MAP_BYTES (Kollmorgen §5.3.1.2/§5.3.2.2, digest D4.1: "mappings
 * are only taken over byte-wise"): an entry's length must be whole bytes
 * (0x06040041 otherwise); a whole-byte part of an object is still allowed. */
static void byte_granularity_option(void **state)
{
    (void)state;
    /* CiA 301 bit granularity: one bit of a BOOLEAN is an entry */
    pfx_start(&fx, 1, NULL);
    tb_xfer(BUS, "601 2F 02 16 00 00 00 00 00", "581 60 02 16 00 00 00 00 00");
    tb_xfer(BUS, "601 23 02 16 01 01 00 00 20", "581 60 02 16 01 00 00 00 00");
    /* granularity 8 */
    pfx_start(&fx, 1, &(co_settings_t){.pdo.granularity = CO_PDO_MAP_BYTES});
    tb_xfer(BUS, "601 2F 02 16 00 00 00 00 00", "581 60 02 16 00 00 00 00 00");
    tb_xfer(BUS, "601 23 02 16 01 01 00 00 20", "581 80 02 16 01 41 00 04 06"); /* 1 bit */
    tb_xfer(BUS, "601 23 02 16 01 04 00 01 20", "581 80 02 16 01 41 00 04 06"); /* 4 of 8 */
    tb_xfer(BUS, "601 23 02 16 01 0C 00 02 20", "581 80 02 16 01 41 00 04 06"); /* 12 of 16 */
    tb_xfer(BUS, "601 23 02 16 01 01 00 01 00", "581 80 02 16 01 41 00 04 06"); /* dummy bit */
    /* a length the object cannot have stays 0x06040043 */
    tb_xfer(BUS, "601 23 02 16 01 00 00 02 20", "581 80 02 16 01 43 00 04 06");
    tb_xfer(BUS, "601 23 02 16 01 11 00 02 20", "581 80 02 16 01 43 00 04 06");
    /* whole bytes: a BOOLEAN, the low byte of an INTEGER16, 3 of 4 bytes, a dummy byte */
    tb_xfer(BUS, "601 23 02 16 01 08 00 00 20", "581 60 02 16 01 00 00 00 00");
    tb_xfer(BUS, "601 23 02 16 02 08 00 02 20", "581 60 02 16 02 00 00 00 00");
    tb_xfer(BUS, "601 23 02 16 03 18 00 09 20", "581 60 02 16 03 00 00 00 00");
    tb_xfer(BUS, "601 23 02 16 04 08 00 05 00", "581 60 02 16 04 00 00 00 00");
    tb_xfer(BUS, "601 2F 02 16 00 04 00 00 00", "581 60 02 16 00 00 00 00 00");
    tb_xfer(BUS, "601 23 02 14 01 01 04 00 00", "581 60 02 14 01 00 00 00 00");
    tb_send(BUS, "000 01 01");
    tb_flush(BUS);
    tb_send(BUS, "401 01 B4 56 78 9A FF");
    assert_int_equal(pfx_get(&fx, 0x2000, 0), 1);
    assert_int_equal(pfx_get(&fx, 0x2002, 0) & 0xFFFF, 0xFFB4); /* signed: extended */
    assert_int_equal(pfx_get(&fx, 0x2009, 0), 0x009A7856UL);
}

/* SSD 630 14.12/14.13 (corrected frames, digest 7.12): remapping valid PDOs in
 * Pre-operational, the device's documented deviation. */
static void ssd_630_sync_pdo_setup(void **state)
{
    (void)state;
    pfx_start(&fx, 1, &(co_settings_t){.pdo.mapping_while_valid = 1U});
    tb_xfer(BUS, "601 2F 00 16 00 00 00 00 00", "581 60 00 16 00 00 00 00 00"); /* 1.1 */
    tb_xfer(BUS, "601 23 00 16 01 10 00 40 60", "581 60 00 16 01 00 00 00 00"); /* 1.2 */
    tb_xfer(BUS, "601 23 00 16 02 20 01 C1 60", "581 60 00 16 02 00 00 00 00"); /* 1.3 */
    tb_xfer(BUS, "601 2F 00 16 00 02 00 00 00", "581 60 00 16 00 00 00 00 00"); /* 1.4 */
    tb_xfer(BUS, "601 2F 00 14 02 01 00 00 00", "581 60 00 14 02 00 00 00 00"); /* 1.5 */
    tb_xfer(BUS, "601 23 00 14 01 01 02 00 00", "581 60 00 14 01 00 00 00 00"); /* 1.6 */
    tb_xfer(BUS, "601 2F 00 1A 00 00 00 00 00", "581 60 00 1A 00 00 00 00 00"); /* 1.7 */
    tb_xfer(BUS, "601 23 00 1A 01 10 00 41 60", "581 60 00 1A 01 00 00 00 00"); /* 1.8 */
    tb_xfer(BUS, "601 23 00 1A 02 20 00 63 60", "581 60 00 1A 02 00 00 00 00"); /* 1.9 */
    tb_xfer(BUS, "601 2F 00 1A 00 02 00 00 00", "581 60 00 1A 00 00 00 00 00"); /* 1.10 */
    tb_xfer(BUS, "601 2F 00 18 02 01 00 00 00", "581 60 00 18 02 00 00 00 00"); /* 1.11 */
    tb_xfer(BUS, "601 23 00 18 01 01 18 00 00", "581 80 00 18 01 30 00 09 06"); /* 1.12 printed */
    tb_xfer(BUS, "601 23 00 18 01 81 01 00 00", "581 60 00 18 01 00 00 00 00"); /* 1.12 meant */
    tb_xfer(BUS, "601 23 06 10 00 88 13 00 00", "581 60 06 10 00 00 00 00 00"); /* 2.1 */
    /* the same first step on a strict device is refused */
    pfx_start(&fx, 1, NULL);
    tb_xfer(BUS, "601 2F 00 16 00 00 00 00 00", "581 80 00 16 00 22 00 00 08");
}

/* Kollmorgen 5.3 (digest 7.1): free mapping of TPDO1, node 1, without
 * invalidating the PDO first (the device's documented deviation). */
static void kollmorgen_free_mapping(void **state)
{
    (void)state;
    pfx_start(&fx, 1, &(co_settings_t){.pdo.mapping_while_valid = 1U});
    tb_xfer(BUS, "601 2F 00 1A 00 00 00 00 00", "581 60 00 1A 00 00 00 00 00");
    tb_xfer(BUS, "601 23 00 1A 01 10 00 41 60", "581 60 00 1A 01 00 00 00 00");
    tb_xfer(BUS, "601 23 00 1A 02 20 00 02 10", "581 60 00 1A 02 00 00 00 00");
    tb_xfer(BUS, "601 2F 00 1A 00 02 00 00 00", "581 60 00 1A 00 00 00 00 00");
    /* and the mapping is in effect: statusword + 0x1002 when Operational */
    pfx_set(&fx, 0x6041, 0, 0x0240, 2);
    pfx_set(&fx, 0x1002, 0, 0x12345678UL, 4);
    tb_send(BUS, "000 01 01");
    tb_expect(BUS, "181 40 02 78 56 34 12");
}

/* SSD 630 14.15 (digest 7.13): profile velocity by SDO, corrected frames;
 * the printed step 2.2 addresses 0x6006, which the SSD answers 0x06010000. */
static void ssd_630_profile_velocity(void **state)
{
    (void)state;
    pfx_start(&fx, 1, &(co_settings_t){.sdo.unknown_object = CO_SDO_ABORT_NO_ACCESS, .pdo.mapping_while_valid = 1U});
    tb_xfer(BUS, "601 23 FF 60 00 00 00 00 00", "581 60 FF 60 00 00 00 00 00");
    tb_xfer(BUS, "601 2F 06 60 00 03 00 00 00", "581 80 06 60 00 00 00 01 06");
    tb_xfer(BUS, "601 2F 60 60 00 03 00 00 00", "581 60 60 60 00 00 00 00 00");
    tb_xfer(BUS, "601 23 FF 60 00 E8 03 00 00", "581 60 FF 60 00 00 00 00 00");
    assert_int_equal(pfx_get(&fx, 0x60FF, 0), 1000);
    assert_int_equal(pfx_get(&fx, 0x6060, 0), 3);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(mapping_needs_invalid_pdo),
        cmocka_unit_test(rpdo_mapping_rules),
        cmocka_unit_test(cob_id_rules),
        cmocka_unit_test(cob_id_while_valid_option),
        cmocka_unit_test(comm_parameter_rules),
        cmocka_unit_test(mapping_locked_in_operational),
        cmocka_unit_test(pdo_config_preop_only_option),
        cmocka_unit_test(byte_granularity_option),
        cmocka_unit_test(ssd_630_sync_pdo_setup),
        cmocka_unit_test(kollmorgen_free_mapping),
        cmocka_unit_test(ssd_630_profile_velocity),
        cmocka_unit_test(mapping_entry_forms),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
