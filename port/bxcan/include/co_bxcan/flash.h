/*
 * Parameter storage (0x1010 / 0x1011, LSS records) in the STM32's own flash,
 * through the core's asynchronous NV HAL (co_hal.h: nv_read, nv_write,
 * nv_erase, nv_poll, nv_erase_unit).
 *
 * The NV area is a run of erase units of one size at the end of the flash
 * the image leaves free: STM32F1 pages (1 or 2 KiB, erased by address:
 * FLASH_CR.PER, FLASH_AR, STRT; programmed by half-words), or STM32F2/F4
 * sectors of equal size (e.g. sectors 1-2 of 16 KiB, or 6-7 of 128 KiB:
 * FLASH_CR.SER, SNB, STRT; programmed by words where 4-aligned, by
 * half-words otherwise). The core keeps two banks, each in units of its
 * own, so a power cut never tears a set: the bank being written is not the
 * one holding the newest set (co_store.c).
 *
 *   nv_erase  starts the erase of the first unit and returns; nv_poll starts
 *             the next unit whenever the controller is idle (FLASH_SR.BSY
 *             clear) and answers CO_NV_BUSY until the last one is done:
 *             the core serves the bus between polls during an erase of
 *             16 KiB..128 KiB (0.2-2 s on an F4; see the stall below), and
 *             the erase never sits in the SDO answer path.
 *   nv_write  programs at once (about 16-70 us a half-word or word, BSY
 *             polled; the core writes a bank of a few hundred bytes in one
 *             go after the erase), padding an odd first or last byte with
 *             0xFF (erased: the core never writes the other byte of that
 *             half-word afterwards).
 *   nv_read   reads the memory-mapped flash.
 *
 * Errors (F1 PGERR, WRPRTERR; F4 WRPERR, PGAERR, PGPERR, PGSERR, OPERR) make
 * the operation fail: the core answers the save with 0x06060000 and keeps
 * the previous set. The controller is locked again (FLASH_CR.LOCK) after
 * every operation. Register and memory access go through co_bxcan_flash_io_t
 * in the unit tests (a model of the controller and the array), MMIO on the
 * part.
 *
 * A limit of the silicon, not of this driver: a read of a flash bank while
 * it is being erased or programmed stalls the bus until the operation ends
 * (RM0008, RM0090). On a single-bank part whose loop executes from that
 * flash the CPU therefore stalls during an erase however it is started;
 * the node keeps serving the bus during the erase only where the loop runs
 * from RAM or from the other bank of a dual-bank part (F1 XL-density,
 * F42x/F43x with DB1M) holding the NV area. Small F1 pages (1 KiB: about
 * 20-40 ms) keep the stall short.
 */
#ifndef CO_BXCAN_FLASH_H
#define CO_BXCAN_FLASH_H

#include <stdint.h>

#include "co/co_frame.h"

#define CO_FLASH_R_BASE_F1 0x40022000UL /**< STM32F1 flash interface */
#define CO_FLASH_R_BASE_F4 0x40023C00UL /**< STM32F2/F4 flash interface */

/* register offsets (both families) */
#define CO_FLASH_KEYR 0x04U
#define CO_FLASH_SR   0x0CU
#define CO_FLASH_CR   0x10U
#define CO_FLASH_AR   0x14U /**< F1 only */

#define CO_FLASH_KEY1 0x45670123U
#define CO_FLASH_KEY2 0xCDEF89ABU

/* STM32F1 */
#define CO_FLASH_F1_SR_BSY      0x00000001U
#define CO_FLASH_F1_SR_PGERR    0x00000004U
#define CO_FLASH_F1_SR_WRPRTERR 0x00000010U
#define CO_FLASH_F1_SR_EOP      0x00000020U
#define CO_FLASH_F1_CR_PG       0x00000001U
#define CO_FLASH_F1_CR_PER      0x00000002U
#define CO_FLASH_F1_CR_STRT     0x00000040U
#define CO_FLASH_F1_CR_LOCK     0x00000080U

/* STM32F2/F4 */
#define CO_FLASH_F4_SR_EOP    0x00000001U
#define CO_FLASH_F4_SR_OPERR  0x00000002U
#define CO_FLASH_F4_SR_WRPERR 0x00000010U
#define CO_FLASH_F4_SR_PGAERR 0x00000020U
#define CO_FLASH_F4_SR_PGPERR 0x00000040U
#define CO_FLASH_F4_SR_PGSERR 0x00000080U
#define CO_FLASH_F4_SR_BSY    0x00010000U
#define CO_FLASH_F4_CR_PG     0x00000001U
#define CO_FLASH_F4_CR_SER    0x00000002U
#define CO_FLASH_F4_CR_SNB_SHIFT 3U
#define CO_FLASH_F4_CR_PSIZE16 0x00000100U
#define CO_FLASH_F4_CR_PSIZE32 0x00000200U
#define CO_FLASH_F4_CR_STRT   0x00010000U
#define CO_FLASH_F4_CR_LOCK   0x80000000U

typedef enum co_flash_family {
    CO_FLASH_F1 = 0, /**< pages erased by address, half-word programming */
    CO_FLASH_F4 = 1  /**< sectors erased by number, word / half-word programming */
} co_flash_family_t;

/** Register and array access of a model (unit tests); NULL: MMIO. Array
 *  addresses are absolute (0x08000000 ...). */
typedef struct co_bxcan_flash_io {
    uint32_t (*reg_read)(void *ctx, uint32_t off);
    void (*reg_write)(void *ctx, uint32_t off, uint32_t value);
    void (*mem_read)(void *ctx, uint32_t addr, uint8_t *buf, uint32_t len);
    void (*mem_write16)(void *ctx, uint32_t addr, uint16_t value);
    void (*mem_write32)(void *ctx, uint32_t addr, uint32_t value);
} co_bxcan_flash_io_t;

typedef struct co_bxcan_flash {
    uintptr_t regs;                 /**< CO_FLASH_R_BASE_F1 / _F4 */
    const co_bxcan_flash_io_t *io;  /**< NULL: MMIO */
    void *io_ctx;
    uint32_t base;                  /**< absolute address of the NV area (unit-aligned) */
    uint32_t size;                  /**< bytes of it: whole units, at least co_store_nv_size_unit */
    uint32_t unit;                  /**< erase unit: page or sector size (a power of two) */
    uint32_t erase_next;            /**< erase in progress: next unit's NV address */
    uint32_t erase_end;             /**< ... and the end of the range */
    uint8_t family;                 /**< co_flash_family_t */
    uint8_t first_sector;           /**< F4: FLASH_CR.SNB of the sector at base (a
                                         dual-bank part's sector 12 is 16) */
    uint8_t erasing;                /**< an erase is in progress */
} co_bxcan_flash_t;

/** Describe the NV area: @p size bytes at @p base in units of @p unit
 *  (F4: sector @p first_sector is at @p base, the following ones are of the
 *  same size). Returns 0, or -1 for an area not made of whole aligned units. */
int co_bxcan_flash_init(co_bxcan_flash_t *fl, co_flash_family_t family, uintptr_t regs,
                        const co_bxcan_flash_io_t *io, void *io_ctx, uint32_t base,
                        uint32_t size, uint32_t unit, uint8_t first_sector);

/** The HAL's NV functions; ctx is the co_bxcan_flash_t. */
int co_bxcan_flash_read(void *ctx, uint32_t addr, uint8_t *buf, uint32_t len);
int co_bxcan_flash_write(void *ctx, uint32_t addr, const uint8_t *buf, uint32_t len);
int co_bxcan_flash_erase(void *ctx, uint32_t addr, uint32_t len);
int co_bxcan_flash_poll(void *ctx);

/** One HAL context for a node on bxCAN with its parameters in flash: the
 *  HAL's ctx, for co_bxcan_port_send and co_bxcan_port_nv_* (which pass
 *  on to co_bxcan_send and co_bxcan_flash_*). The table, with the erase
 *  unit of the part as a constant:
 *
 *    static const co_hal_ops_t ops = {
 *        .send = co_bxcan_port_send, .nv_read = co_bxcan_port_nv_read,
 *        .nv_write = co_bxcan_port_nv_write, .nv_erase = co_bxcan_port_nv_erase,
 *        .nv_poll = co_bxcan_port_nv_poll, .nv_erase_unit = 1024U};
 */
typedef struct co_bxcan_port {
    void *can;                  /**< the co_bxcan_t (bxcan.h) */
    co_bxcan_flash_t *flash;
} co_bxcan_port_t;

int co_bxcan_port_send(void *ctx, const co_frame_t *f);
int co_bxcan_port_nv_read(void *ctx, uint32_t addr, uint8_t *buf, uint32_t len);
int co_bxcan_port_nv_write(void *ctx, uint32_t addr, const uint8_t *buf, uint32_t len);
int co_bxcan_port_nv_erase(void *ctx, uint32_t addr, uint32_t len);
int co_bxcan_port_nv_poll(void *ctx);

#endif /* CO_BXCAN_FLASH_H */
