/*
 * Driver for the Xilinx ZynqMP CAN controller (CAN0 at 0xFF060000, CAN1 at
 * 0xFF070000; the "xlnx.zynqmp-can" of QEMU's xlnx-zcu102 machine).
 *
 * Polling: co_xcan_recv() takes one frame out of the RX FIFO, co_xcan_send()
 * is the HAL's send (TX FIFO, 64 frames deep). On a core whose interrupt
 * controller sees the CAN interrupt, an ISR calls co_xcan_recv() and pushes
 * into a co_rxq; on QEMU's Cortex-R5 (the GIC is wired to the A53s only) the
 * main loop calls it.
 *
 * Identifier and data layout: a build option.
 *   CO_XCAN_LAYOUT_QEMU (default): QEMU's model puts the Linux can_id into
 *     the ID register (11-bit id in bits 10:0, or 29-bit id with bit 31 set;
 *     bit 30 RTR) and data byte 0 in bits 7:0 of DATA1 (byte 4 in DATA2).
 *   CO_XCAN_LAYOUT_HW (-DCO_XCAN_LAYOUT=CO_XCAN_LAYOUT_HW): the hardware
 *     manual's layout: IDH (11 bits) at 31:21, SRR/RTR at 20, IDE at 19,
 *     IDL (18 bits) at 18:1, RTR at 0; data byte 0 in bits 31:24 of DATA1.
 * Register access is 32-bit. A test model replaces MMIO with co_xcan_io_t.
 */
#ifndef CO_XCAN_H
#define CO_XCAN_H

#include <stdint.h>

#include "co/co_canstate.h"
#include "co/co_frame.h"
#include "co/co_hal.h"

#define CO_XCAN_LAYOUT_QEMU 1
#define CO_XCAN_LAYOUT_HW   2
#ifndef CO_XCAN_LAYOUT
#define CO_XCAN_LAYOUT CO_XCAN_LAYOUT_QEMU
#endif

#define CO_XCAN0_BASE 0xFF060000UL
#define CO_XCAN1_BASE 0xFF070000UL

/* register offsets */
#define CO_XCAN_SRR   0x00U  /**< software reset: SRST bit 0, CEN bit 1 */
#define CO_XCAN_MSR   0x04U  /**< mode select: SLEEP 0, LBACK 1, SNOOP 2 */
#define CO_XCAN_BRPR  0x08U  /**< baud rate prescaler (value + 1) */
#define CO_XCAN_BTR   0x0CU  /**< TS1 3:0, TS2 6:4, SJW 8:7 (each value + 1) */
#define CO_XCAN_ECR   0x10U  /**< error counters: TEC 7:0, REC 15:8 */
#define CO_XCAN_ESR   0x14U
#define CO_XCAN_SR    0x18U  /**< status */
#define CO_XCAN_ISR   0x1CU
#define CO_XCAN_IER   0x20U
#define CO_XCAN_ICR   0x24U
#define CO_XCAN_TXFIFO_ID 0x30U /**< then DLC 0x34, DATA1 0x38, DATA2 0x3C (sends) */
#define CO_XCAN_RXFIFO_ID 0x50U /**< then DLC 0x54, DATA1 0x58, DATA2 0x5C */
#define CO_XCAN_AFR   0x60U

#define CO_XCAN_SRR_SRST  0x1U
#define CO_XCAN_SRR_CEN   0x2U
#define CO_XCAN_SR_CONFIG 0x0001U
#define CO_XCAN_SR_NORMAL 0x0008U
#define CO_XCAN_SR_ERRWRN 0x0040U
#define CO_XCAN_SR_ESTAT_SHIFT 7U  /**< 2 bits: 1 error active, 2 bus-off, 3 passive */
#define CO_XCAN_SR_TXFLL  0x0400U
#define CO_XCAN_IXR_TXOK   0x0002U
#define CO_XCAN_IXR_RXOK   0x0010U
#define CO_XCAN_IXR_RXOFLW 0x0040U
#define CO_XCAN_IXR_RXNEMP 0x0080U
#define CO_XCAN_IXR_BSOFF  0x0200U

/** Register access of a model (unit tests); NULL in co_xcan_t: MMIO. */
typedef struct co_xcan_io {
    uint32_t (*read)(void *ctx, uint32_t off);
    void (*write)(void *ctx, uint32_t off, uint32_t value);
} co_xcan_io_t;

typedef struct co_xcan {
    uintptr_t base;           /**< register base address */
    const co_xcan_io_t *io;   /**< NULL: MMIO at base */
    void *io_ctx;
    uint32_t rx_overruns;     /**< RX FIFO overflows seen */
    uint32_t tx_full;         /**< sends refused because the TX FIFO was full */
} co_xcan_t;

/** Bit timing: BRPR and BTR values for @p bitrate at the CAN reference
 *  clock @p clk_hz: 8..25 time quanta per bit, sample point near 87.5 %
 *  (earlier only where no such setting divides the clock). Returns 0, or -1
 *  when no setting divides the clock exactly (e.g. below 15.6 kbit/s at
 *  100 MHz: the prescaler has 8 bits). */
int co_xcan_timing(uint32_t clk_hz, uint32_t bitrate, uint32_t *brpr, uint32_t *btr);

/** Reset the controller, program the bit timing (co_xcan_timing), accept
 *  every identifier and enter normal mode. Returns 0, or -1 when the timing
 *  cannot be met or the controller does not leave configuration mode. */
int co_xcan_init(co_xcan_t *c, uintptr_t base, const co_xcan_io_t *io, void *io_ctx,
                 uint32_t clk_hz, uint32_t bitrate);

/** Take one received frame out of the RX FIFO into @p f. Returns 1 for a
 *  frame, 0 when the FIFO is empty. Counts RX FIFO overflows. */
int co_xcan_recv(co_xcan_t *c, co_frame_t *f);

/** The HAL's send (ctx is the co_xcan_t): 0 when the frame went into the TX
 *  FIFO, 1 when the FIFO is full (the core keeps it and retries). */
int co_xcan_send(void *ctx, const co_frame_t *f);

/** The controller's error state from SR.ESTAT (2 bus-off, 3 error passive,
 *  else error active; QEMU's model keeps its error counters at 0, so there
 *  it is always active). For co_node_can_state. */
co_can_state_t co_xcan_state(const co_xcan_t *c);

/** The identifier register value for @p id (CO_FRAME_RTR / CO_FRAME_EFF
 *  flags included) in the build's layout, and back. */
uint32_t co_xcan_id_to_reg(uint32_t id);
uint32_t co_xcan_reg_to_id(uint32_t reg);

#endif /* CO_XCAN_H */
