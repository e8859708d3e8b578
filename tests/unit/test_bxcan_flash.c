/*
 * Parameter storage in STM32 flash (port/bxcan/src/flash.c) against a
 * register-level model of the flash interface and its array: FLASH_KEYR's
 * unlock sequence and FLASH_CR.LOCK (a locked CR ignores writes), page
 * erase by address (F1: PER, AR, STRT) and sector erase by number (F4: SER,
 * SNB, STRT), FLASH_SR.BSY for a number of status reads while an erase
 * runs, EOP and the error flags (write 1 to clear), programming that needs
 * CR.PG, F1 half-words only onto erased half-words (PGERR otherwise), F4
 * half-words or words by CR.PSIZE (PGPERR on a mismatch, PGAERR when
 * unaligned), and an array that programming can only clear bits of.
 *
 * Then a generic-301 node on it (issue 13): a 0x1010 save erases the bank's
 * units in the background while the node serves the bus (heartbeats), the
 * SDO answer comes when the set is in flash, the next save goes to the
 * other bank, a restart loads the set from the array, and a flash error
 * answers 0x06060000 and keeps the previous set.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "co/co_endian.h"
#include "co/co_node.h"
#include "co_bxcan/flash.h"
#include "generic_301.h"
#include "test_bus.h"
#include "test_frames.h"

#define FLASH_ORG  0x08000000UL
#define MODEL_SIZE (128U * 1024U)

typedef struct model {
    uint8_t family;
    uint32_t unit;          /* erase unit of the model's array */
    uint32_t sector0;       /* F4: FLASH_CR.SNB of the unit at FLASH_ORG */
    uint8_t mem[MODEL_SIZE];
    uint32_t sr;
    uint32_t cr;
    uint32_t ar;
    bool locked;
    uint8_t key_step;       /* KEY1 seen */
    unsigned busy_reads;    /* SR reads BSY stays set for */
    unsigned erase_reads;   /* an erase keeps BSY this many reads */
    unsigned erases;
    uint32_t erased[16];    /* absolute address of each erase, in order */
    unsigned programs;
    unsigned locked_writes; /* CR writes ignored because CR was locked */
    uint32_t fail_next;     /* error flag the next erase or program raises */
} model_t;

static model_t md;

static uint32_t bsy(void)
{
    return (md.family == (uint8_t)CO_FLASH_F4) ? CO_FLASH_F4_SR_BSY : CO_FLASH_F1_SR_BSY;
}

static uint32_t eop(void)
{
    return (md.family == (uint8_t)CO_FLASH_F4) ? CO_FLASH_F4_SR_EOP : CO_FLASH_F1_SR_EOP;
}

static uint32_t lockbit(void)
{
    return (md.family == (uint8_t)CO_FLASH_F4) ? CO_FLASH_F4_CR_LOCK : CO_FLASH_F1_CR_LOCK;
}

static uint32_t m_reg_read(void *ctx, uint32_t off)
{
    (void)ctx;
    if (off == CO_FLASH_SR) {
        uint32_t v = md.sr;
        if (md.busy_reads > 0U) {
            md.busy_reads--;
            if (md.busy_reads == 0U) {
                md.sr = (md.sr & ~bsy()) | eop();
            }
        }
        return v;
    }
    if (off == CO_FLASH_CR) {
        return md.cr | (md.locked ? lockbit() : 0U);
    }
    return 0U;
}

static void erase_at(uint32_t abs)
{
    assert_true((abs >= FLASH_ORG) && ((abs - FLASH_ORG + md.unit) <= MODEL_SIZE));
    assert_int_equal((abs - FLASH_ORG) % md.unit, 0U);
    assert_true(md.erases < 16U);
    md.erased[md.erases++] = abs;
    if (md.fail_next != 0U) {
        md.sr |= md.fail_next; /* e.g. write protection: nothing erased */
        md.fail_next = 0U;
        return;
    }
    memset(&md.mem[abs - FLASH_ORG], 0xFF, md.unit);
    md.sr |= bsy();
    md.busy_reads = md.erase_reads;
}

static void m_reg_write(void *ctx, uint32_t off, uint32_t v)
{
    (void)ctx;
    if (off == CO_FLASH_KEYR) {
        if ((md.key_step == 0U) && (v == CO_FLASH_KEY1)) {
            md.key_step = 1U;
        } else if ((md.key_step == 1U) && (v == CO_FLASH_KEY2)) {
            md.locked = false;
            md.key_step = 0U;
        } else {
            fail_msg("FLASH_KEYR: wrong key sequence (locks the interface until reset)");
        }
    } else if (off == CO_FLASH_SR) {
        md.sr &= ~(v & ~bsy()); /* write 1 to clear */
    } else if (off == CO_FLASH_AR) {
        assert_false(md.locked);
        md.ar = v;
    } else if (off == CO_FLASH_CR) {
        if (md.locked) {
            md.locked_writes++;
            return;
        }
        assert_true((md.sr & bsy()) == 0U || (v & lockbit()) != 0U); /* no change while busy */
        if ((v & lockbit()) != 0U) {
            md.locked = true;
            md.cr = 0U;
            return;
        }
        md.cr = v;
        if (md.family == (uint8_t)CO_FLASH_F4) {
            if ((v & (CO_FLASH_F4_CR_SER | CO_FLASH_F4_CR_STRT)) ==
                (CO_FLASH_F4_CR_SER | CO_FLASH_F4_CR_STRT)) {
                uint32_t snb = (v >> CO_FLASH_F4_CR_SNB_SHIFT) & 0x1FU;
                assert_true(snb >= md.sector0);
                erase_at(FLASH_ORG + (snb - md.sector0) * md.unit);
            }
        } else if ((v & (CO_FLASH_F1_CR_PER | CO_FLASH_F1_CR_STRT)) ==
                   (CO_FLASH_F1_CR_PER | CO_FLASH_F1_CR_STRT)) {
            erase_at(md.ar);
        } else {
            /* PG, or the first half of an erase request */
        }
    } else {
        fail_msg("write to an unmodelled flash register");
    }
}

static void m_mem_read(void *ctx, uint32_t addr, uint8_t *buf, uint32_t len)
{
    (void)ctx;
    assert_true((addr >= FLASH_ORG) && ((addr - FLASH_ORG + len) <= MODEL_SIZE));
    memcpy(buf, &md.mem[addr - FLASH_ORG], len);
}

/* Program @p n bytes of @p v at @p addr, as the interface does. */
static void program(uint32_t addr, uint32_t v, uint32_t n)
{
    uint8_t *p = &md.mem[addr - FLASH_ORG];
    bool f4 = (md.family == (uint8_t)CO_FLASH_F4);
    uint32_t psize = md.cr & (CO_FLASH_F4_CR_PSIZE16 | CO_FLASH_F4_CR_PSIZE32);

    assert_false(md.locked);
    assert_true((md.cr & CO_FLASH_F1_CR_PG) != 0U); /* PG: bit 0 in both */
    assert_true((md.sr & bsy()) == 0U);
    assert_true((addr >= FLASH_ORG) && ((addr - FLASH_ORG + n) <= MODEL_SIZE));
    md.programs++;
    if (md.fail_next != 0U) {
        md.sr |= md.fail_next;
        md.fail_next = 0U;
        return;
    }
    if ((addr % n) != 0U) {
        md.sr |= f4 ? CO_FLASH_F4_SR_PGAERR : CO_FLASH_F1_SR_PGERR;
        return;
    }
    if (f4 && (psize != ((n == 4U) ? CO_FLASH_F4_CR_PSIZE32 : CO_FLASH_F4_CR_PSIZE16))) {
        md.sr |= CO_FLASH_F4_SR_PGPERR;
        return;
    }
    if (!f4 && ((p[0] != 0xFFU) || (p[1] != 0xFFU))) {
        md.sr |= CO_FLASH_F1_SR_PGERR; /* F1: only onto an erased half-word */
        return;
    }
    for (uint32_t i = 0U; i < n; i++) {
        p[i] &= (uint8_t)(v >> (8U * i)); /* programming only clears bits */
    }
    md.sr |= bsy();
    md.busy_reads = 1U;
}

static void m_mem_write16(void *ctx, uint32_t addr, uint16_t v)
{
    (void)ctx;
    program(addr, v, 2U);
}

static void m_mem_write32(void *ctx, uint32_t addr, uint32_t v)
{
    (void)ctx;
    assert_int_equal(md.family, (uint8_t)CO_FLASH_F4); /* F1 programs half-words only */
    program(addr, v, 4U);
}

static const co_bxcan_flash_io_t m_io = {m_reg_read, m_reg_write, m_mem_read, m_mem_write16,
                                         m_mem_write32};

static void model_reset(co_flash_family_t family, uint32_t unit, uint32_t sector0)
{
    memset(&md, 0, sizeof md);
    memset(md.mem, 0x5A, sizeof md.mem); /* not erased: the driver must erase */
    md.family = (uint8_t)family;
    md.unit = unit;
    md.sector0 = sector0;
    md.locked = true;
    md.erase_reads = 40U;
}

/* ------------------------------------------------ the driver alone */

static co_bxcan_flash_t fl;

static void driver_f1_pages_and_half_words(void **state)
{
    uint8_t b[8];
    const uint8_t data[5] = {0x11, 0x22, 0x33, 0x44, 0x55};

    (void)state;
    model_reset(CO_FLASH_F1, 1024U, 0U);
    /* an area not made of whole aligned units is refused */
    assert_int_equal(co_bxcan_flash_init(&fl, CO_FLASH_F1, 0U, &m_io, NULL, FLASH_ORG + 512U,
                                         4096U, 1024U, 0U), -1);
    assert_int_equal(co_bxcan_flash_init(&fl, CO_FLASH_F1, 0U, &m_io, NULL, FLASH_ORG, 1000U,
                                         1024U, 0U), -1);
    assert_int_equal(co_bxcan_flash_init(&fl, CO_FLASH_F1, 0U, &m_io, NULL, FLASH_ORG + 4096U,
                                         4096U, 1024U, 0U), 0);
    /* an erase of two pages: by address, one after the other, in the
     * background (busy while BSY), locked at the end */
    assert_int_equal(co_bxcan_flash_erase(&fl, 1024U, 1000U), -1); /* not whole pages */
    assert_int_equal(co_bxcan_flash_erase(&fl, 1024U, 2048U), 0);
    assert_int_equal(md.erases, 1U);
    assert_int_equal(md.erased[0], FLASH_ORG + 4096U + 1024U);
    assert_int_equal(co_bxcan_flash_write(&fl, 1024U, data, 2U), -1); /* erase not done */
    for (unsigned k = 0U; k < 40U; k++) { /* BSY for 40 status reads */
        assert_int_equal(co_bxcan_flash_poll(&fl), CO_NV_BUSY);
    }
    assert_int_equal(md.erases, 1U);
    assert_int_equal(co_bxcan_flash_poll(&fl), CO_NV_BUSY); /* the second page starts */
    assert_int_equal(md.erases, 2U);
    assert_int_equal(md.erased[1], FLASH_ORG + 4096U + 2048U);
    while (co_bxcan_flash_poll(&fl) == CO_NV_BUSY) {
    }
    assert_int_equal(co_bxcan_flash_poll(&fl), 0);
    assert_true(md.locked);
    assert_int_equal(md.locked_writes, 0U);
    /* half-words; an odd start and end padded with 0xFF, never two
     * programs of one half-word (PGERR in the model) */
    assert_int_equal(co_bxcan_flash_write(&fl, 1025U, data, 5U), 0);
    assert_int_equal(md.programs, 3U);
    assert_int_equal(md.sr & CO_FLASH_F1_SR_PGERR, 0U);
    assert_int_equal(co_bxcan_flash_read(&fl, 1024U, b, 8U), 0);
    assert_int_equal(b[0], 0xFF);
    assert_memory_equal(&b[1], data, 5U);
    assert_int_equal(b[6], 0xFF);
    assert_true(md.locked);
    /* outside the area */
    assert_int_equal(co_bxcan_flash_read(&fl, 4090U, b, 8U), -1);
    assert_int_equal(co_bxcan_flash_write(&fl, 4095U, data, 2U), -1);
    /* write protection: the program fails, nv_write reports it */
    md.fail_next = CO_FLASH_F1_SR_WRPRTERR;
    assert_int_equal(co_bxcan_flash_write(&fl, 2048U, data, 2U), -1);
    assert_true(md.locked);
}

static void driver_f4_sectors_and_words(void **state)
{
    uint8_t b[12];
    const uint8_t data[9] = {1, 2, 3, 4, 5, 6, 7, 8, 9};
    unsigned programs;

    (void)state;
    model_reset(CO_FLASH_F4, 16384U, 0U);
    /* sectors 2 and 3 of 16 KiB (SNB 2, 3) */
    assert_int_equal(co_bxcan_flash_init(&fl, CO_FLASH_F4, 0U, &m_io, NULL, FLASH_ORG + 32768U,
                                         32768U, 16384U, 2U), 0);
    assert_int_equal(co_bxcan_flash_erase(&fl, 16384U, 16384U), 0);
    assert_int_equal(md.erased[0], FLASH_ORG + 49152U); /* SNB 3 */
    while (co_bxcan_flash_poll(&fl) == CO_NV_BUSY) {
    }
    assert_true(md.locked);
    /* words where 4-aligned and whole, half-words elsewhere (PSIZE set to
     * match: PGPERR in the model otherwise) */
    programs = md.programs;
    assert_int_equal(co_bxcan_flash_write(&fl, 16386U, data, 9U), 0);
    /* 16386: half-word; 16388, 16392: words; 16396: half-word (padded) */
    assert_int_equal(md.programs - programs, 4U);
    assert_int_equal(md.sr & (CO_FLASH_F4_SR_PGPERR | CO_FLASH_F4_SR_PGAERR), 0U);
    assert_int_equal(co_bxcan_flash_read(&fl, 16384U, b, 12U), 0);
    assert_int_equal(b[0], 0xFF);
    assert_int_equal(b[1], 0xFF);
    assert_memory_equal(&b[2], data, 9U);
    assert_int_equal(b[11], 0xFF);
    /* an erase error (write protection): nv_poll reports it */
    md.fail_next = CO_FLASH_F4_SR_WRPERR;
    assert_int_equal(co_bxcan_flash_erase(&fl, 0U, 16384U), 0);
    assert_int_equal(co_bxcan_flash_poll(&fl), -1);
    assert_true(md.locked);
    assert_int_equal(co_bxcan_flash_poll(&fl), 0);
}

/* ------------------------------------------------ a node on it */

static tb_bus_t bus;
static generic_301_node_t gn;

static int t_send(void *ctx, const co_frame_t *f)
{
    (void)ctx;
    return tb_hal_ops.send(&bus.ports[0], f);
}

#define SAVE_ALL  "601 23 10 10 01 73 61 76 65"
#define SAVED_ALL "581 60 10 10 01 00 00 00 00"

/* The frames sent since the last look, heartbeats (10 ms) aside: exactly
 * @p text. */
static void expect_besides_heartbeats(const char *text)
{
    const co_frame_t *f;
    unsigned n = 0U;

    while ((f = tb_next(&bus)) != NULL) {
        if (f->id != 0x701U) {
            TF_ASSERT_FRAME(f, text);
            n++;
        }
    }
    assert_int_equal(n, 1U);
}

static void start_node(const co_hal_ops_t *ops)
{
    co_node_config_t cfg;

    (void)tb_hal(&bus, 0);
    generic_301_config(&gn, &cfg);
    cfg.hal.ops = ops;
    cfg.hal.ctx = &fl;
    cfg.node_id = 1U;
    assert_int_equal(co_node_init(&gn.node, &cfg, bus.now), CO_RESULT_OK);
    tb_attach(&bus, 0, &gn.node);
    tb_expect(&bus, "701 00");
}

/* A save with @p ops (erase unit @p unit) on the model: heartbeats every
 * 10 ms while the bank's units are erased, the answer when the set is in
 * flash; saves alternate banks; a restart loads the set. */
static void node_saves(const co_hal_ops_t *ops, uint32_t unit)
{
    uint32_t size = co_store_nv_size_unit(&generic_301_dev, unit);
    uint32_t bank = (size - 2U * unit) / 2U; /* LSS records: a unit each at the end */
    unsigned beats = 0U;
    bool answered = false;
    const co_frame_t *f;

    assert_int_equal(bank % unit, 0U);
    assert_true(size <= MODEL_SIZE / 2U);
    tb_init(&bus);
    start_node(ops);
    tb_xfer(&bus, "601 2B 17 10 00 0A 00 00 00", "581 60 17 10 00 00 00 00 00");
    tb_xfer(&bus, "601 23 02 21 00 78 56 34 12", "581 60 02 21 00 00 00 00 00");
    md.erase_reads = 30U; /* 30 polls (1 ms apart) per unit */
    tb_send(&bus, SAVE_ALL);
    tb_expect_none(&bus);
    assert_int_equal(md.erases, 1U);
    assert_int_equal(md.erased[0], fl.base); /* no set yet: bank 0 */
    for (unsigned k = 0U; (k < 40U) && !answered; k++) {
        tb_advance(&bus, 10000U);
        while ((f = tb_next(&bus)) != NULL) {
            if (f->id == 0x701U) {
                TF_ASSERT_FRAME(f, "701 7F");
                beats++;
            } else {
                TF_ASSERT_FRAME(f, SAVED_ALL);
                answered = true;
            }
        }
    }
    assert_true(answered);
    /* every unit of the bank erased, one after the other, 30 ms each */
    assert_int_equal(md.erases, bank / unit);
    assert_in_range(beats, 3U * (bank / unit) - 1U, 3U * (bank / unit) + 2U);
    assert_true(md.locked);
    assert_int_equal(md.locked_writes, 0U);
    /* a restart loads it from the array */
    tb_xfer(&bus, "601 23 02 21 00 00 00 00 00", "581 60 02 21 00 00 00 00 00");
    start_node(ops);
    tb_xfer(&bus, "601 40 02 21 00 00 00 00 00", "581 43 02 21 00 78 56 34 12");
    /* the next save: the other bank */
    tb_xfer(&bus, "601 23 02 21 00 21 43 65 87", "581 60 02 21 00 00 00 00 00");
    tb_send(&bus, SAVE_ALL);
    tb_advance(&bus, 40000U * (bank / unit));
    tb_flush(&bus);
    assert_int_equal(md.erased[bank / unit], fl.base + bank);
    /* a flash error: 0x06060000, the previous set stays */
    tb_xfer(&bus, "601 23 02 21 00 00 00 00 00", "581 60 02 21 00 00 00 00 00");
    md.fail_next = (md.family == (uint8_t)CO_FLASH_F4) ? CO_FLASH_F4_SR_WRPERR
                                                      : CO_FLASH_F1_SR_WRPRTERR;
    tb_flush(&bus);
    tb_send(&bus, SAVE_ALL);
    tb_advance(&bus, 5000U);
    expect_besides_heartbeats("581 80 10 10 01 00 00 06 06");
    start_node(ops);
    tb_xfer(&bus, "601 40 02 21 00 00 00 00 00", "581 43 02 21 00 21 43 65 87");
    /* LSS store configuration: the record's own unit, erased first */
    tb_send(&bus, "7E5 04 01 00 00 00 00 00 00");
    tb_flush(&bus);
    tb_send(&bus, "7E5 17 00 00 00 00 00 00 00");
    tb_advance(&bus, 100000U);
    expect_besides_heartbeats("7E4 17 00 00 00 00 00 00 00");
    assert_int_equal(md.erased[md.erases - 1U], fl.base + 2U * bank);
    assert_true(md.locked);
}

static void node_f1_pages(void **state)
{
    static const co_hal_ops_t ops = {.send = t_send,
                                     .nv_read = co_bxcan_flash_read,
                                     .nv_write = co_bxcan_flash_write,
                                     .nv_erase = co_bxcan_flash_erase,
                                     .nv_poll = co_bxcan_flash_poll,
                                     .nv_erase_unit = 1024U};
    uint32_t size = co_store_nv_size_unit(&generic_301_dev, 1024U);

    (void)state;
    model_reset(CO_FLASH_F1, 1024U, 0U);
    assert_int_equal(co_bxcan_flash_init(&fl, CO_FLASH_F1, 0U, &m_io, NULL, FLASH_ORG + 8192U,
                                         size, 1024U, 0U), 0);
    node_saves(&ops, 1024U);
}

static void node_f4_sectors(void **state)
{
    static const co_hal_ops_t ops = {.send = t_send,
                                     .nv_read = co_bxcan_flash_read,
                                     .nv_write = co_bxcan_flash_write,
                                     .nv_erase = co_bxcan_flash_erase,
                                     .nv_poll = co_bxcan_flash_poll,
                                     .nv_erase_unit = 16384U};
    uint32_t size = co_store_nv_size_unit(&generic_301_dev, 16384U);

    (void)state;
    model_reset(CO_FLASH_F4, 16384U, 4U); /* SNB 4 at FLASH_ORG in the model */
    assert_int_equal(co_bxcan_flash_init(&fl, CO_FLASH_F4, 0U, &m_io, NULL, FLASH_ORG,
                                         size, 16384U, 4U), 0);
    node_saves(&ops, 16384U);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(driver_f1_pages_and_half_words),
        cmocka_unit_test(driver_f4_sectors_and_words),
        cmocka_unit_test(node_f1_pages),
        cmocka_unit_test(node_f4_sectors),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
