/*
 * STM32 bxCAN driver (STM32F1/F2/F4 CAN1, base 0x40006400): three TX
 * mailboxes, two 3-frame RX FIFOs, 14 filter banks, interrupt-driven.
 *
 *   send (the HAL's): an empty mailbox takes the frame, else 1 (the core
 *     holds it back in CAN-ID order). Transmit priority is request order
 *     (MCR.TXFP): frames of one COB-ID (SDO segments) never overtake.
 *   co_bxcan_tx_isr (CAN1_TX / USB_HP_CAN1_TX): acknowledges finished
 *     mailboxes and raises tx_ready; the main loop calls co_node_tx_ready.
 *   co_bxcan_rx_isr(fifo) (CAN1_RX0 / RX1): every waiting frame into the
 *     co_rxq the main loop drains; a FIFO overrun counts (rx_overruns).
 *   co_bxcan_sce_isr (CAN1_SCE): ESR's error passive / bus-off into state;
 *     the main loop hands it to co_node_can_state when it changed.
 *   co_bxcan_filters: the node's receive COB-IDs as 16-bit list filters
 *     (4 per bank) into FIFO 0; more than fit: everything is accepted.
 *
 * Bit timing comes from a const table (co_bxcan_timing) for 10 kbit/s ..
 * 1 Mbit/s at the APB1 clocks STM32 parts run CAN at (8, 16, 24, 36, 42,
 * 45, 48 MHz), sample point 87.5 % where the clock allows (CiA 301).
 * Register access is 32-bit; a test model replaces MMIO with co_bxcan_io_t.
 */
#ifndef CO_BXCAN_H
#define CO_BXCAN_H

#include <stdbool.h>
#include <stdint.h>

#include "co/co_canstate.h"
#include "co/co_frame.h"
#include "co/co_rxq.h"

#define CO_BXCAN1_BASE 0x40006400UL

/* register offsets */
#define CO_BXCAN_MCR  0x000U
#define CO_BXCAN_MSR  0x004U
#define CO_BXCAN_TSR  0x008U
#define CO_BXCAN_RF0R 0x00CU
#define CO_BXCAN_RF1R 0x010U
#define CO_BXCAN_IER  0x014U
#define CO_BXCAN_ESR  0x018U
#define CO_BXCAN_BTR  0x01CU
#define CO_BXCAN_TI0R 0x180U /**< TX mailbox n: TIR 0x180 + 16n, TDTR +4, TDLR +8, TDHR +12 */
#define CO_BXCAN_RI0R 0x1B0U /**< RX FIFO n: RIR 0x1B0 + 16n, RDTR +4, RDLR +8, RDHR +12 */
#define CO_BXCAN_FMR  0x200U
#define CO_BXCAN_FM1R 0x204U
#define CO_BXCAN_FS1R 0x20CU
#define CO_BXCAN_FFA1R 0x214U
#define CO_BXCAN_FA1R 0x21CU
#define CO_BXCAN_F0R1 0x240U /**< bank i: FiR1 0x240 + 8i, FiR2 +4 */
#define CO_BXCAN_BANKS 14U

#define CO_BXCAN_MCR_INRQ  0x00000001U
#define CO_BXCAN_MCR_SLEEP 0x00000002U
#define CO_BXCAN_MCR_TXFP  0x00000004U
#define CO_BXCAN_MCR_ABOM  0x00000040U
#define CO_BXCAN_MSR_INAK  0x00000001U
#define CO_BXCAN_MSR_ERRI  0x00000004U
#define CO_BXCAN_TSR_RQCP0 0x00000001U /**< mailbox n: << 8n */
#define CO_BXCAN_TSR_RQCP_ALL 0x00010101U /**< RQCP0..2 */
#define CO_BXCAN_TSR_TME0  0x04000000U /**< mailbox n: << n */
#define CO_BXCAN_RFR_FMP   0x00000003U
#define CO_BXCAN_RFR_FOVR  0x00000010U
#define CO_BXCAN_RFR_RFOM  0x00000020U
#define CO_BXCAN_IER_TMEIE  0x00000001U
#define CO_BXCAN_IER_FMPIE0 0x00000002U
#define CO_BXCAN_IER_FOVIE0 0x00000008U
#define CO_BXCAN_IER_FMPIE1 0x00000010U
#define CO_BXCAN_IER_FOVIE1 0x00000040U
#define CO_BXCAN_IER_EPVIE  0x00000200U
#define CO_BXCAN_IER_BOFIE  0x00000400U
#define CO_BXCAN_IER_ERRIE  0x00008000U
#define CO_BXCAN_ESR_EPVF  0x00000002U
#define CO_BXCAN_ESR_BOFF  0x00000004U
#define CO_BXCAN_TIR_TXRQ  0x00000001U
#define CO_BXCAN_XIR_RTR   0x00000002U
#define CO_BXCAN_XIR_IDE   0x00000004U
#define CO_BXCAN_FMR_FINIT 0x00000001U

/** Register access of a model (unit tests); NULL: MMIO at base. */
typedef struct co_bxcan_io {
    uint32_t (*read)(void *ctx, uint32_t off);
    void (*write)(void *ctx, uint32_t off, uint32_t value);
} co_bxcan_io_t;

typedef struct co_bxcan {
    uintptr_t base;
    const co_bxcan_io_t *io;   /**< NULL: MMIO */
    void *io_ctx;
    co_rxq_t *rxq;             /**< the RX ISRs push here */
    volatile uint32_t rx_overruns; /**< FIFO overruns (ISR), for co_node_can_overrun */
    volatile uint8_t tx_ready; /**< set by the TX ISR; the loop clears it */
    volatile uint8_t state;    /**< co_can_state_t, written by the SCE ISR */
} co_bxcan_t;

/** One bit-timing entry: APB1 clock, bit rate, BTR value (BRP, TS1, TS2, SJW). */
typedef struct co_bxcan_timing {
    uint32_t clk_hz;
    uint32_t bitrate;
    uint32_t btr;
} co_bxcan_timing_t;

/** The BTR value for @p bitrate at @p clk_hz from the table, or 0 when the
 *  table has no entry. */
uint32_t co_bxcan_timing(uint32_t clk_hz, uint32_t bitrate);

/** The whole table (for tests and documentation); *n its length. */
const co_bxcan_timing_t *co_bxcan_timing_table(uint32_t *n);

/** Leave sleep, enter initialisation, set the bit timing (table), transmit
 *  in request order, automatic bus-off recovery, accept everything into FIFO
 *  0, enable the TX/RX/error interrupts, start. Returns 0, or -1 for a bit
 *  rate the table lacks or a controller that does not answer. */
int co_bxcan_init(co_bxcan_t *c, uintptr_t base, const co_bxcan_io_t *io, void *io_ctx,
                  co_rxq_t *rxq, uint32_t clk_hz, uint32_t bitrate);

/** Program the filter banks from @p cobs (@p n 11-bit COB-IDs; RTRs of
 *  them pass too): 16-bit list mode, four per bank, into FIFO 0. With more
 *  than 4 * 14 identifiers one mask filter accepts everything. Returns the
 *  number of banks used. */
uint32_t co_bxcan_filters(co_bxcan_t *c, const uint16_t *cobs, uint32_t n);

/** The HAL's send (ctx is the co_bxcan_t). */
int co_bxcan_send(void *ctx, const co_frame_t *f);

/** The error state in ESR now. The SCE interrupt signals error passive and
 *  bus-off; the return to error active (after ABOM's recovery) has no
 *  interrupt, so the main loop reads this too. */
co_can_state_t co_bxcan_state(const co_bxcan_t *c);

void co_bxcan_tx_isr(co_bxcan_t *c);
void co_bxcan_rx_isr(co_bxcan_t *c, uint32_t fifo);
void co_bxcan_sce_isr(co_bxcan_t *c);

#endif /* CO_BXCAN_H */
