/* Xilinx ZynqMP CAN controller driver (see co_xcan/xcan.h). */
#include "co_xcan/xcan.h"

#include <stddef.h>
#include <string.h>

/* Linux can_id flags, which QEMU's model keeps in the ID register */
#define LX_EFF ((uint32_t)0x80000000UL)
#define LX_RTR ((uint32_t)0x40000000UL)
/* the manual's ID register fields */
#define HW_IDH_SHIFT 21U
#define HW_SRR       ((uint32_t)0x00100000UL)
#define HW_IDE       ((uint32_t)0x00080000UL)
#define HW_IDL_SHIFT 1U
#define HW_RTR       ((uint32_t)0x00000001UL)

static uint32_t rd(const co_xcan_t *c, uint32_t off)
{
    if (c->io != NULL) {
        return c->io->read(c->io_ctx, off);
    }
    return *(volatile const uint32_t *)(c->base + off);
}

static void wr(const co_xcan_t *c, uint32_t off, uint32_t v)
{
    if (c->io != NULL) {
        c->io->write(c->io_ctx, off, v);
    } else {
        *(volatile uint32_t *)(c->base + off) = v;
    }
}

uint32_t co_xcan_id_to_reg(uint32_t id)
{
    uint32_t cob = id & CO_FRAME_ID_MASK;
    bool rtr = (id & CO_FRAME_RTR) != 0U;
#if CO_XCAN_LAYOUT == CO_XCAN_LAYOUT_QEMU
    uint32_t r = ((id & CO_FRAME_EFF) != 0U) ? (uint32_t)(cob | LX_EFF) : (uint32_t)(cob & 0x7FFU);

    return rtr ? (r | LX_RTR) : r;
#else
    uint32_t r;

    if ((id & CO_FRAME_EFF) != 0U) {
        r = ((cob >> 18U) << HW_IDH_SHIFT) | HW_SRR | HW_IDE |
            ((cob & 0x3FFFFU) << HW_IDL_SHIFT);
        if (rtr) {
            r |= HW_RTR;
        }
    } else {
        r = (cob & 0x7FFU) << HW_IDH_SHIFT;
        if (rtr) {
            r |= HW_SRR;
        }
    }
    return r;
#endif
}

uint32_t co_xcan_reg_to_id(uint32_t reg)
{
#if CO_XCAN_LAYOUT == CO_XCAN_LAYOUT_QEMU
    uint32_t id = ((reg & LX_EFF) != 0U) ? (uint32_t)((reg & CO_FRAME_ID_MASK) | CO_FRAME_EFF)
                                         : (uint32_t)(reg & 0x7FFU);

    return ((reg & LX_RTR) != 0U) ? (id | CO_FRAME_RTR) : id;
#else
    uint32_t idh = reg >> HW_IDH_SHIFT;

    if ((reg & HW_IDE) != 0U) {
        uint32_t id = (idh << 18U) | ((reg >> HW_IDL_SHIFT) & 0x3FFFFU) | CO_FRAME_EFF;
        return ((reg & HW_RTR) != 0U) ? (id | CO_FRAME_RTR) : id;
    }
    return ((reg & HW_SRR) != 0U) ? (idh | CO_FRAME_RTR) : idh;
#endif
}

/* data bytes 4k..4k+3 <-> one data register */
static uint32_t pack(const uint8_t *b)
{
#if CO_XCAN_LAYOUT == CO_XCAN_LAYOUT_QEMU
    return (uint32_t)b[0] | ((uint32_t)b[1] << 8U) | ((uint32_t)b[2] << 16U) |
           ((uint32_t)b[3] << 24U);
#else
    return ((uint32_t)b[0] << 24U) | ((uint32_t)b[1] << 16U) | ((uint32_t)b[2] << 8U) |
           (uint32_t)b[3];
#endif
}

static void unpack(uint32_t w, uint8_t *b)
{
    for (uint32_t k = 0U; k < 4U; k++) {
#if CO_XCAN_LAYOUT == CO_XCAN_LAYOUT_QEMU
        b[k] = (uint8_t)(w >> (8U * k));
#else
        b[k] = (uint8_t)(w >> (24U - (8U * k)));
#endif
    }
}

/* One pass over 25..8 time quanta per bit: the first that divides the clock
 * with TS2 = n/8 (sample point near 87.5 %); with @p relaxed, TS1 capped at
 * 16 and the rest in TS2 (an earlier sample point) when that does not fit. */
static int timing_pass(uint32_t clk_hz, uint32_t bitrate, int relaxed, uint32_t *brpr,
                       uint32_t *btr)
{
    for (uint32_t n = 25U; n >= 8U; n--) {
        uint32_t per_bit = bitrate * n;
        uint32_t ts2 = (n + 4U) / 8U;
        uint32_t ts1 = n - 1U - ts2;

        if ((relaxed != 0) && (ts1 > 16U)) {
            ts1 = 16U;
            ts2 = n - 17U;
        }
        if (((per_bit / n) == bitrate) && ((clk_hz % per_bit) == 0U) && (ts1 <= 16U) &&
            (ts2 <= 8U)) {
            uint32_t pre = clk_hz / per_bit;
            uint32_t sjw = (ts2 < 4U) ? ts2 : 4U;

            if ((pre >= 1U) && (pre <= 256U)) {
                *brpr = pre - 1U;
                *btr = (ts1 - 1U) | ((ts2 - 1U) << 4U) | ((sjw - 1U) << 7U);
                return 0;
            }
        }
    }
    return -1;
}

int co_xcan_timing(uint32_t clk_hz, uint32_t bitrate, uint32_t *brpr, uint32_t *btr)
{
    if (bitrate == 0U) {
        return -1;
    }
    if (timing_pass(clk_hz, bitrate, 0, brpr, btr) == 0) {
        return 0;
    }
    return timing_pass(clk_hz, bitrate, 1, brpr, btr);
}

int co_xcan_init(co_xcan_t *c, uintptr_t base, const co_xcan_io_t *io, void *io_ctx,
                 uint32_t clk_hz, uint32_t bitrate)
{
    uint32_t brpr = 0U;
    uint32_t btr = 0U;

    c->base = base;
    c->io = io;
    c->io_ctx = io_ctx;
    c->rx_overruns = 0U;
    c->tx_full = 0U;
    if (co_xcan_timing(clk_hz, bitrate, &brpr, &btr) != 0) {
        return -1;
    }
    wr(c, CO_XCAN_SRR, CO_XCAN_SRR_SRST); /* reset: configuration mode */
    wr(c, CO_XCAN_BRPR, brpr);
    wr(c, CO_XCAN_BTR, btr);
    wr(c, CO_XCAN_AFR, 0U);               /* no acceptance filter: every frame */
    wr(c, CO_XCAN_IER, 0U);
    wr(c, CO_XCAN_ICR, 0x7FFFU);
    wr(c, CO_XCAN_MSR, 0U);               /* normal mode */
    wr(c, CO_XCAN_SRR, CO_XCAN_SRR_CEN);
    for (uint32_t k = 0U; k < 1000U; k++) {
        if ((rd(c, CO_XCAN_SR) & CO_XCAN_SR_NORMAL) != 0U) {
            return 0;
        }
    }
    return -1;
}

int co_xcan_recv(co_xcan_t *c, co_frame_t *f)
{
    uint32_t isr = rd(c, CO_XCAN_ISR);
    uint32_t dlc;

    if ((isr & CO_XCAN_IXR_RXOFLW) != 0U) {
        c->rx_overruns++;
        wr(c, CO_XCAN_ICR, CO_XCAN_IXR_RXOFLW);
    }
    if ((isr & CO_XCAN_IXR_RXNEMP) == 0U) {
        return 0;
    }
    /* read in this order: ID, DLC, DATA1, DATA2 */
    f->id = co_xcan_reg_to_id(rd(c, CO_XCAN_RXFIFO_ID));
    dlc = rd(c, CO_XCAN_RXFIFO_ID + 4U) >> 28U;
    f->dlc = (uint8_t)((dlc > 8U) ? 8U : dlc);
    unpack(rd(c, CO_XCAN_RXFIFO_ID + 8U), &f->data[0]);
    unpack(rd(c, CO_XCAN_RXFIFO_ID + 12U), &f->data[4]);
    /* cleared; set again at once while more frames wait */
    wr(c, CO_XCAN_ICR, CO_XCAN_IXR_RXNEMP | CO_XCAN_IXR_RXOK);
    return 1;
}

int co_xcan_send(void *ctx, const co_frame_t *f)
{
    co_xcan_t *c = (co_xcan_t *)ctx;
    uint8_t d[8] = {0};

    if ((rd(c, CO_XCAN_SR) & CO_XCAN_SR_TXFLL) != 0U) {
        c->tx_full++;
        return 1;
    }
    if ((f->id & CO_FRAME_RTR) == 0U) {
        (void)memcpy(d, f->data, (f->dlc > 8U) ? 8U : f->dlc);
    }
    wr(c, CO_XCAN_TXFIFO_ID, co_xcan_id_to_reg(f->id));
    wr(c, CO_XCAN_TXFIFO_ID + 4U, (uint32_t)f->dlc << 28U);
    wr(c, CO_XCAN_TXFIFO_ID + 8U, pack(&d[0]));
    wr(c, CO_XCAN_TXFIFO_ID + 12U, pack(&d[4])); /* writing DATA2 sends */
    return 0;
}

co_can_state_t co_xcan_state(const co_xcan_t *c)
{
    uint32_t estat = (rd(c, CO_XCAN_SR) >> CO_XCAN_SR_ESTAT_SHIFT) & 3U;
    co_can_state_t st = CO_CAN_ERROR_ACTIVE;

    if (estat == 2U) {
        st = CO_CAN_BUS_OFF;
    } else if (estat == 3U) {
        st = CO_CAN_ERROR_PASSIVE;
    } else {
        /* 1: error active; 0: configuration mode */
    }
    return st;
}
