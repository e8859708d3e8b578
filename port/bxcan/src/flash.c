/*
 * Parameter storage in the STM32's own flash (see co_bxcan/flash.h).
 */
#include "co_bxcan/flash.h"

#include <string.h>

#include "co/co_hal.h"
#include "co_bxcan/bxcan.h"

/* BSY polls of one program operation before it counts as failed (a word
 * takes at most about 100 us; a poll is a few cycles) */
#define PROGRAM_POLLS 200000UL

static uint32_t flash_rd(const co_bxcan_flash_t *fl, uint32_t off)
{
    if (fl->io != NULL) {
        return fl->io->reg_read(fl->io_ctx, off);
    }
    return *(volatile const uint32_t *)(fl->regs + off);
}

static void flash_wr(const co_bxcan_flash_t *fl, uint32_t off, uint32_t v)
{
    if (fl->io != NULL) {
        fl->io->reg_write(fl->io_ctx, off, v);
    } else {
        *(volatile uint32_t *)(fl->regs + off) = v;
    }
}

static void mem16(const co_bxcan_flash_t *fl, uint32_t addr, uint16_t v)
{
    if (fl->io != NULL) {
        fl->io->mem_write16(fl->io_ctx, addr, v);
    } else {
        *(volatile uint16_t *)(uintptr_t)addr = v;
    }
}

static void mem32(const co_bxcan_flash_t *fl, uint32_t addr, uint32_t v)
{
    if (fl->io != NULL) {
        fl->io->mem_write32(fl->io_ctx, addr, v);
    } else {
        *(volatile uint32_t *)(uintptr_t)addr = v;
    }
}

static bool f4(const co_bxcan_flash_t *fl)
{
    return fl->family == (uint8_t)CO_FLASH_F4;
}

static uint32_t bsy(const co_bxcan_flash_t *fl)
{
    return f4(fl) ? CO_FLASH_F4_SR_BSY : CO_FLASH_F1_SR_BSY;
}

static uint32_t errors(const co_bxcan_flash_t *fl)
{
    return f4(fl) ? (CO_FLASH_F4_SR_OPERR | CO_FLASH_F4_SR_WRPERR | CO_FLASH_F4_SR_PGAERR |
                     CO_FLASH_F4_SR_PGPERR | CO_FLASH_F4_SR_PGSERR)
                  : (CO_FLASH_F1_SR_PGERR | CO_FLASH_F1_SR_WRPRTERR);
}

static uint32_t lock_bit(const co_bxcan_flash_t *fl)
{
    return f4(fl) ? CO_FLASH_F4_CR_LOCK : CO_FLASH_F1_CR_LOCK;
}

static void unlock(const co_bxcan_flash_t *fl)
{
    if ((flash_rd(fl, CO_FLASH_CR) & lock_bit(fl)) != 0U) {
        flash_wr(fl, CO_FLASH_KEYR, CO_FLASH_KEY1);
        flash_wr(fl, CO_FLASH_KEYR, CO_FLASH_KEY2);
    }
}

static void lock(const co_bxcan_flash_t *fl)
{
    flash_wr(fl, CO_FLASH_CR, lock_bit(fl));
}

/* Clear EOP and the error flags (write 1 to clear) and report whether an
 * error was set. */
static bool take_errors(const co_bxcan_flash_t *fl)
{
    uint32_t sr = flash_rd(fl, CO_FLASH_SR);
    uint32_t eop = f4(fl) ? CO_FLASH_F4_SR_EOP : CO_FLASH_F1_SR_EOP;

    flash_wr(fl, CO_FLASH_SR, sr & (errors(fl) | eop));
    return (sr & errors(fl)) != 0U;
}

/* Wait until the controller is idle (a program operation, or an erase
 * another request overlaps). False if it stays busy. */
static bool wait_idle(const co_bxcan_flash_t *fl, uint32_t polls)
{
    for (uint32_t k = 0U; k < polls; k++) {
        if ((flash_rd(fl, CO_FLASH_SR) & bsy(fl)) == 0U) {
            return true;
        }
    }
    return false;
}

int co_bxcan_flash_init(co_bxcan_flash_t *fl, co_flash_family_t family, uintptr_t regs,
                        const co_bxcan_flash_io_t *io, void *io_ctx, uint32_t base,
                        uint32_t size, uint32_t unit, uint8_t first_sector)
{
    (void)memset(fl, 0, sizeof *fl);
    if ((unit < 4U) || ((unit & (unit - 1U)) != 0U) || ((base % unit) != 0U) ||
        (size == 0U) || ((size % unit) != 0U)) {
        return -1;
    }
    fl->family = (uint8_t)family;
    fl->regs = regs;
    fl->io = io;
    fl->io_ctx = io_ctx;
    fl->base = base;
    fl->size = size;
    fl->unit = unit;
    fl->first_sector = first_sector;
    return 0;
}

int co_bxcan_flash_read(void *ctx, uint32_t addr, uint8_t *buf, uint32_t len)
{
    const co_bxcan_flash_t *fl = (const co_bxcan_flash_t *)ctx;

    if ((addr > fl->size) || (len > (fl->size - addr))) {
        return -1;
    }
    if (fl->io != NULL) {
        fl->io->mem_read(fl->io_ctx, fl->base + addr, buf, len);
    } else {
        (void)memcpy(buf, (const uint8_t *)(uintptr_t)(fl->base + addr), len);
    }
    return 0;
}

/* Start the erase of the unit at NV address @p addr. */
static void start_erase(const co_bxcan_flash_t *fl, uint32_t addr)
{
    unlock(fl);
    if (f4(fl)) {
        uint32_t snb = (uint32_t)fl->first_sector + (addr / fl->unit);
        flash_wr(fl, CO_FLASH_CR, CO_FLASH_F4_CR_SER | (snb << CO_FLASH_F4_CR_SNB_SHIFT));
        flash_wr(fl, CO_FLASH_CR,
           CO_FLASH_F4_CR_SER | (snb << CO_FLASH_F4_CR_SNB_SHIFT) | CO_FLASH_F4_CR_STRT);
    } else {
        flash_wr(fl, CO_FLASH_CR, CO_FLASH_F1_CR_PER);
        flash_wr(fl, CO_FLASH_AR, fl->base + addr);
        flash_wr(fl, CO_FLASH_CR, CO_FLASH_F1_CR_PER | CO_FLASH_F1_CR_STRT);
    }
}

int co_bxcan_flash_erase(void *ctx, uint32_t addr, uint32_t len)
{
    co_bxcan_flash_t *fl = (co_bxcan_flash_t *)ctx;

    if (((addr % fl->unit) != 0U) || ((len % fl->unit) != 0U) || (addr > fl->size) ||
        (len > (fl->size - addr))) {
        return -1;
    }
    if (len == 0U) {
        return 0;
    }
    if ((fl->erasing != 0U) || !wait_idle(fl, PROGRAM_POLLS)) {
        return -1; /* one erase at a time (the core never overlaps them) */
    }
    (void)take_errors(fl);
    fl->erase_next = addr + fl->unit;
    fl->erase_end = addr + len;
    fl->erasing = 1U;
    start_erase(fl, addr);
    return 0;
}

int co_bxcan_flash_poll(void *ctx)
{
    co_bxcan_flash_t *fl = (co_bxcan_flash_t *)ctx;

    if (fl->erasing == 0U) {
        return 0; /* writes are complete when nv_write returns */
    }
    if ((flash_rd(fl, CO_FLASH_SR) & bsy(fl)) != 0U) {
        return CO_NV_BUSY;
    }
    if (take_errors(fl)) {
        fl->erasing = 0U;
        lock(fl);
        return -1;
    }
    if (fl->erase_next < fl->erase_end) {
        start_erase(fl, fl->erase_next);
        fl->erase_next += fl->unit;
        return CO_NV_BUSY;
    }
    fl->erasing = 0U;
    lock(fl);
    return 0;
}

/* Program one half-word or word at absolute @p at and wait for it. */
static bool program(const co_bxcan_flash_t *fl, uint32_t at, uint32_t v, bool word)
{
    if (f4(fl)) {
        uint32_t cr = CO_FLASH_F4_CR_PG;
        cr |= word ? CO_FLASH_F4_CR_PSIZE32 : CO_FLASH_F4_CR_PSIZE16;
        flash_wr(fl, CO_FLASH_CR, cr);
    } else {
        flash_wr(fl, CO_FLASH_CR, CO_FLASH_F1_CR_PG);
    }
    if (word) {
        mem32(fl, at, v);
    } else {
        mem16(fl, at, (uint16_t)v);
    }
    return wait_idle(fl, PROGRAM_POLLS) && !take_errors(fl);
}

/* The byte to write at NV address @p a: from @p buf inside [@p addr,
 * + @p len), 0xFF (erased) outside it. */
static uint32_t byte_at(const uint8_t *buf, uint32_t addr, uint32_t len, uint32_t a)
{
    return ((a >= addr) && ((a - addr) < len)) ? buf[a - addr] : 0xFFU;
}

int co_bxcan_flash_write(void *ctx, uint32_t addr, const uint8_t *buf, uint32_t len)
{
    const co_bxcan_flash_t *fl = (const co_bxcan_flash_t *)ctx;
    uint32_t a;
    bool ok = true;

    if ((addr > fl->size) || (len > (fl->size - addr)) || (fl->erasing != 0U)) {
        return -1; /* outside, or before the erase nv_poll reports done */
    }
    if (len == 0U) {
        return 0;
    }
    if (!wait_idle(fl, PROGRAM_POLLS)) {
        return -1;
    }
    (void)take_errors(fl);
    unlock(fl);
    a = addr & ~(uint32_t)1U; /* an odd first byte: its half-word, the other byte 0xFF */
    while (ok && (a < (addr + len))) {
        bool word = f4(fl) && ((a & 3U) == 0U) && ((a + 4U) <= (addr + len)) && (a >= addr);
        uint32_t v = byte_at(buf, addr, len, a) | (byte_at(buf, addr, len, a + 1U) << 8U);
        if (word) {
            v |= (byte_at(buf, addr, len, a + 2U) << 16U) | (byte_at(buf, addr, len, a + 3U) << 24U);
        }
        ok = program(fl, fl->base + a, v, word);
        a += word ? 4U : 2U;
    }
    lock(fl);
    return ok ? 0 : -1;
}

/* ------------------------------------------------ one HAL context */

int co_bxcan_port_send(void *ctx, const co_frame_t *f)
{
    return co_bxcan_send(((const co_bxcan_port_t *)ctx)->can, f);
}

int co_bxcan_port_nv_read(void *ctx, uint32_t addr, uint8_t *buf, uint32_t len)
{
    return co_bxcan_flash_read(((const co_bxcan_port_t *)ctx)->flash, addr, buf, len);
}

int co_bxcan_port_nv_write(void *ctx, uint32_t addr, const uint8_t *buf, uint32_t len)
{
    return co_bxcan_flash_write(((const co_bxcan_port_t *)ctx)->flash, addr, buf, len);
}

int co_bxcan_port_nv_erase(void *ctx, uint32_t addr, uint32_t len)
{
    return co_bxcan_flash_erase(((const co_bxcan_port_t *)ctx)->flash, addr, len);
}

int co_bxcan_port_nv_poll(void *ctx)
{
    return co_bxcan_flash_poll(((const co_bxcan_port_t *)ctx)->flash);
}
