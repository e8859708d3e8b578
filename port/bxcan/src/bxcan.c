/* STM32 bxCAN driver (see co_bxcan/bxcan.h). */
#include "co_bxcan/bxcan.h"

#include <stddef.h>

static uint32_t rd(const co_bxcan_t *c, uint32_t off)
{
    if (c->io != NULL) {
        return c->io->read(c->io_ctx, off);
    }
    return *(volatile const uint32_t *)(c->base + off);
}

static void wr(const co_bxcan_t *c, uint32_t off, uint32_t v)
{
    if (c->io != NULL) {
        c->io->write(c->io_ctx, off, v);
    } else {
        *(volatile uint32_t *)(c->base + off) = v;
    }
}

/* BTR = BRP (prescaler - 1) | (TS1 - 1) << 16 | (TS2 - 1) << 20 |
 * (SJW - 1) << 24; a bit is 1 + TS1 + TS2 time quanta. The entry with the
 * sample point nearest 87.5 % (then the most quanta) for each clock and
 * CiA bit rate; 800 kbit/s does not divide 42 or 45 MHz. */
static const co_bxcan_timing_t timing[] = {
    {8000000UL, 10000UL, 0x011C0031UL}, /* 50 x 16 tq, 87.5 % */
    {8000000UL, 20000UL, 0x011C0018UL}, /* 25 x 16 tq, 87.5 % */
    {8000000UL, 50000UL, 0x011C0009UL}, /* 10 x 16 tq, 87.5 % */
    {8000000UL, 125000UL, 0x011C0003UL}, /* 4 x 16 tq, 87.5 % */
    {8000000UL, 250000UL, 0x011C0001UL}, /* 2 x 16 tq, 87.5 % */
    {8000000UL, 500000UL, 0x011C0000UL}, /* 1 x 16 tq, 87.5 % */
    {8000000UL, 800000UL, 0x00070000UL}, /* 1 x 10 tq, 90.0 % */
    {8000000UL, 1000000UL, 0x00050000UL}, /* 1 x 8 tq, 87.5 % */
    {16000000UL, 10000UL, 0x011C0063UL}, /* 100 x 16 tq, 87.5 % */
    {16000000UL, 20000UL, 0x011C0031UL}, /* 50 x 16 tq, 87.5 % */
    {16000000UL, 50000UL, 0x011C0013UL}, /* 20 x 16 tq, 87.5 % */
    {16000000UL, 125000UL, 0x011C0007UL}, /* 8 x 16 tq, 87.5 % */
    {16000000UL, 250000UL, 0x011C0003UL}, /* 4 x 16 tq, 87.5 % */
    {16000000UL, 500000UL, 0x011C0001UL}, /* 2 x 16 tq, 87.5 % */
    {16000000UL, 800000UL, 0x00070001UL}, /* 2 x 10 tq, 90.0 % */
    {16000000UL, 1000000UL, 0x011C0000UL}, /* 1 x 16 tq, 87.5 % */
    {24000000UL, 10000UL, 0x011C0095UL}, /* 150 x 16 tq, 87.5 % */
    {24000000UL, 20000UL, 0x011C004AUL}, /* 75 x 16 tq, 87.5 % */
    {24000000UL, 50000UL, 0x011C001DUL}, /* 30 x 16 tq, 87.5 % */
    {24000000UL, 125000UL, 0x011C000BUL}, /* 12 x 16 tq, 87.5 % */
    {24000000UL, 250000UL, 0x011C0005UL}, /* 6 x 16 tq, 87.5 % */
    {24000000UL, 500000UL, 0x011C0002UL}, /* 3 x 16 tq, 87.5 % */
    {24000000UL, 800000UL, 0x011B0001UL}, /* 2 x 15 tq, 86.7 % */
    {24000000UL, 1000000UL, 0x00050002UL}, /* 3 x 8 tq, 87.5 % */
    {36000000UL, 10000UL, 0x011C00E0UL}, /* 225 x 16 tq, 87.5 % */
    {36000000UL, 20000UL, 0x000500E0UL}, /* 225 x 8 tq, 87.5 % */
    {36000000UL, 50000UL, 0x011C002CUL}, /* 45 x 16 tq, 87.5 % */
    {36000000UL, 125000UL, 0x011C0011UL}, /* 18 x 16 tq, 87.5 % */
    {36000000UL, 250000UL, 0x011C0008UL}, /* 9 x 16 tq, 87.5 % */
    {36000000UL, 500000UL, 0x00050008UL}, /* 9 x 8 tq, 87.5 % */
    {36000000UL, 800000UL, 0x011B0002UL}, /* 3 x 15 tq, 86.7 % */
    {36000000UL, 1000000UL, 0x011E0001UL}, /* 2 x 18 tq, 88.9 % */
    {42000000UL, 10000UL, 0x0005020CUL}, /* 525 x 8 tq, 87.5 % */
    {42000000UL, 20000UL, 0x011B008BUL}, /* 140 x 15 tq, 86.7 % */
    {42000000UL, 50000UL, 0x00050068UL}, /* 105 x 8 tq, 87.5 % */
    {42000000UL, 125000UL, 0x011C0014UL}, /* 21 x 16 tq, 87.5 % */
    {42000000UL, 250000UL, 0x00050014UL}, /* 21 x 8 tq, 87.5 % */
    {42000000UL, 500000UL, 0x011A0005UL}, /* 6 x 14 tq, 85.7 % */
    {42000000UL, 1000000UL, 0x011A0002UL}, /* 3 x 14 tq, 85.7 % */
    {45000000UL, 10000UL, 0x011B012BUL}, /* 300 x 15 tq, 86.7 % */
    {45000000UL, 20000UL, 0x011B0095UL}, /* 150 x 15 tq, 86.7 % */
    {45000000UL, 50000UL, 0x011B003BUL}, /* 60 x 15 tq, 86.7 % */
    {45000000UL, 125000UL, 0x0005002CUL}, /* 45 x 8 tq, 87.5 % */
    {45000000UL, 250000UL, 0x011B000BUL}, /* 12 x 15 tq, 86.7 % */
    {45000000UL, 500000UL, 0x011B0005UL}, /* 6 x 15 tq, 86.7 % */
    {45000000UL, 1000000UL, 0x011B0002UL}, /* 3 x 15 tq, 86.7 % */
    {48000000UL, 10000UL, 0x011C012BUL}, /* 300 x 16 tq, 87.5 % */
    {48000000UL, 20000UL, 0x011C0095UL}, /* 150 x 16 tq, 87.5 % */
    {48000000UL, 50000UL, 0x011C003BUL}, /* 60 x 16 tq, 87.5 % */
    {48000000UL, 125000UL, 0x011C0017UL}, /* 24 x 16 tq, 87.5 % */
    {48000000UL, 250000UL, 0x011C000BUL}, /* 12 x 16 tq, 87.5 % */
    {48000000UL, 500000UL, 0x011C0005UL}, /* 6 x 16 tq, 87.5 % */
    {48000000UL, 800000UL, 0x011B0003UL}, /* 4 x 15 tq, 86.7 % */
    {48000000UL, 1000000UL, 0x011C0002UL}, /* 3 x 16 tq, 87.5 % */
};

const co_bxcan_timing_t *co_bxcan_timing_table(uint32_t *n)
{
    *n = (uint32_t)((sizeof timing) / (sizeof timing[0]));
    return timing;
}

uint32_t co_bxcan_timing(uint32_t clk_hz, uint32_t bitrate)
{
    uint32_t btr = 0U;

    for (size_t k = 0U; k < ((sizeof timing) / (sizeof timing[0])); k++) {
        if ((timing[k].clk_hz == clk_hz) && (timing[k].bitrate == bitrate)) {
            btr = timing[k].btr;
            break;
        }
    }
    return btr;
}

static int wait_msr(const co_bxcan_t *c, uint32_t mask, uint32_t want)
{
    for (uint32_t k = 0U; k < 100000UL; k++) {
        if ((rd(c, CO_BXCAN_MSR) & mask) == want) {
            return 0;
        }
    }
    return -1;
}

int co_bxcan_init(co_bxcan_t *c, uintptr_t base, const co_bxcan_io_t *io, void *io_ctx,
                  co_rxq_t *rxq, uint32_t clk_hz, uint32_t bitrate)
{
    uint32_t btr = co_bxcan_timing(clk_hz, bitrate);

    c->base = base;
    c->io = io;
    c->io_ctx = io_ctx;
    c->rxq = rxq;
    c->rx_overruns = 0U;
    c->tx_ready = 0U;
    c->state = (uint8_t)CO_CAN_ERROR_ACTIVE;
    if (btr == 0U) {
        return -1;
    }
    /* out of sleep into initialisation */
    wr(c, CO_BXCAN_MCR, CO_BXCAN_MCR_INRQ);
    if (wait_msr(c, CO_BXCAN_MSR_INAK, CO_BXCAN_MSR_INAK) != 0) {
        return -1;
    }
    wr(c, CO_BXCAN_MCR, CO_BXCAN_MCR_INRQ | CO_BXCAN_MCR_TXFP | CO_BXCAN_MCR_ABOM);
    wr(c, CO_BXCAN_BTR, btr);
    (void)co_bxcan_filters(c, NULL, 0U);
    wr(c, CO_BXCAN_IER, CO_BXCAN_IER_TMEIE | CO_BXCAN_IER_FMPIE0 | CO_BXCAN_IER_FOVIE0 |
                            CO_BXCAN_IER_FMPIE1 | CO_BXCAN_IER_FOVIE1 | CO_BXCAN_IER_EPVIE |
                            CO_BXCAN_IER_BOFIE | CO_BXCAN_IER_ERRIE);
    wr(c, CO_BXCAN_MCR, CO_BXCAN_MCR_TXFP | CO_BXCAN_MCR_ABOM); /* leave initialisation */
    return wait_msr(c, CO_BXCAN_MSR_INAK, 0U);
}

/* a 16-bit list filter entry: STID at 15:5, RTR 4, IDE 3 (0), EXID 17:15 at 2:0 */
static uint32_t f16(uint16_t cob, bool rtr)
{
    return (((uint32_t)cob & 0x7FFU) << 5U) | (rtr ? 0x10U : 0U);
}

uint32_t co_bxcan_filters(co_bxcan_t *c, const uint16_t *cobs, uint32_t n)
{
    /* each identifier twice (data frame and RTR: guarding, RTR of a TPDO
     * are answered by the node); four entries per bank */
    uint32_t entries = n * 2U;
    uint32_t banks = (entries + 3U) / 4U;
    uint32_t used = 0U;

    wr(c, CO_BXCAN_FMR, CO_BXCAN_FMR_FINIT);
    wr(c, CO_BXCAN_FA1R, 0U);
    wr(c, CO_BXCAN_FFA1R, 0U); /* all into FIFO 0 */
    if ((cobs == NULL) || (n == 0U) || (banks > CO_BXCAN_BANKS)) {
        /* bank 0: 32-bit mask filter with mask 0, everything passes */
        wr(c, CO_BXCAN_FM1R, 0U);
        wr(c, CO_BXCAN_FS1R, 1U);
        wr(c, CO_BXCAN_F0R1, 0U);
        wr(c, CO_BXCAN_F0R1 + 4U, 0U);
        wr(c, CO_BXCAN_FA1R, 1U);
        used = 1U;
    } else {
        uint32_t mask = (uint32_t)((1UL << banks) - 1U);

        wr(c, CO_BXCAN_FM1R, mask); /* list mode */
        wr(c, CO_BXCAN_FS1R, 0U);   /* 16-bit scale */
        for (uint32_t b = 0U; b < banks; b++) {
            uint32_t e[4];

            for (uint32_t k = 0U; k < 4U; k++) {
                uint32_t i = (b * 4U) + k;
                /* a bank not filled up repeats the last entry */
                uint32_t j = (i < entries) ? i : (entries - 1U);
                e[k] = f16(cobs[j / 2U], (j % 2U) != 0U);
            }
            wr(c, CO_BXCAN_F0R1 + (8U * b), e[0] | (e[1] << 16U));
            wr(c, CO_BXCAN_F0R1 + (8U * b) + 4U, e[2] | (e[3] << 16U));
        }
        wr(c, CO_BXCAN_FA1R, mask);
        used = banks;
    }
    wr(c, CO_BXCAN_FMR, 0U);
    return used;
}

static uint32_t word(const uint8_t *b)
{
    return (uint32_t)b[0] | ((uint32_t)b[1] << 8U) | ((uint32_t)b[2] << 16U) |
           ((uint32_t)b[3] << 24U);
}

int co_bxcan_send(void *ctx, const co_frame_t *f)
{
    co_bxcan_t *c = (co_bxcan_t *)ctx;
    uint32_t tsr = rd(c, CO_BXCAN_TSR);
    uint32_t box = 3U;
    uint32_t tir;
    uint32_t off;
    uint8_t d[8] = {0};

    for (uint32_t m = 0U; m < 3U; m++) {
        if ((tsr & (CO_BXCAN_TSR_TME0 << m)) != 0U) {
            box = m;
            break;
        }
    }
    if (box == 3U) {
        return 1; /* all three mailboxes busy */
    }
    if ((f->id & CO_FRAME_EFF) != 0U) {
        tir = (uint32_t)((f->id & CO_FRAME_ID_MASK) << 3U) | CO_BXCAN_XIR_IDE;
    } else {
        tir = (f->id & 0x7FFU) << 21U;
    }
    if ((f->id & CO_FRAME_RTR) != 0U) {
        tir |= CO_BXCAN_XIR_RTR;
    } else {
        for (uint8_t k = 0U; (k < f->dlc) && (k < 8U); k++) {
            d[k] = f->data[k];
        }
    }
    off = CO_BXCAN_TI0R + (16U * box);
    wr(c, off, tir);
    wr(c, off + 4U, (uint32_t)f->dlc & 0x0FU);
    wr(c, off + 8U, word(&d[0]));
    wr(c, off + 12U, word(&d[4]));
    wr(c, off, tir | CO_BXCAN_TIR_TXRQ);
    return 0;
}

void co_bxcan_tx_isr(co_bxcan_t *c)
{
    uint32_t tsr = rd(c, CO_BXCAN_TSR);
    uint32_t done = tsr & CO_BXCAN_TSR_RQCP_ALL;

    if (done != 0U) {
        wr(c, CO_BXCAN_TSR, done); /* rc_w1: acknowledge those mailboxes */
        c->tx_ready = 1U;
    }
}

void co_bxcan_rx_isr(co_bxcan_t *c, uint32_t fifo)
{
    uint32_t rfr = (fifo == 0U) ? CO_BXCAN_RF0R : CO_BXCAN_RF1R;
    uint32_t box = CO_BXCAN_RI0R + (16U * fifo);
    uint32_t st = rd(c, rfr);

    if ((st & CO_BXCAN_RFR_FOVR) != 0U) {
        c->rx_overruns++;
        wr(c, rfr, CO_BXCAN_RFR_FOVR);
    }
    while ((rd(c, rfr) & CO_BXCAN_RFR_FMP) != 0U) {
        co_frame_t f;
        uint32_t rir = rd(c, box);
        uint32_t dlc = rd(c, box + 4U) & 0x0FU;
        uint32_t lo = rd(c, box + 8U);
        uint32_t hi = rd(c, box + 12U);

        if ((rir & CO_BXCAN_XIR_IDE) != 0U) {
            f.id = (uint32_t)(((rir >> 3U) & CO_FRAME_ID_MASK) | CO_FRAME_EFF);
        } else {
            f.id = rir >> 21U;
        }
        if ((rir & CO_BXCAN_XIR_RTR) != 0U) {
            f.id |= CO_FRAME_RTR;
        }
        f.dlc = (uint8_t)((dlc > 8U) ? 8U : dlc);
        for (uint32_t k = 0U; k < 4U; k++) {
            f.data[k] = (uint8_t)(lo >> (8U * k));
            f.data[4U + k] = (uint8_t)(hi >> (8U * k));
        }
        wr(c, rfr, CO_BXCAN_RFR_RFOM); /* release the mailbox */
        if ((c->rxq != NULL) && !co_rxq_push(c->rxq, &f)) {
            c->rx_overruns++; /* the queue to the loop is full */
        }
    }
}

co_can_state_t co_bxcan_state(const co_bxcan_t *c)
{
    uint32_t esr = rd(c, CO_BXCAN_ESR);
    co_can_state_t st = CO_CAN_ERROR_ACTIVE;

    if ((esr & CO_BXCAN_ESR_BOFF) != 0U) {
        st = CO_CAN_BUS_OFF;
    } else if ((esr & CO_BXCAN_ESR_EPVF) != 0U) {
        st = CO_CAN_ERROR_PASSIVE;
    } else {
        /* error active (warning level included) */
    }
    return st;
}

void co_bxcan_sce_isr(co_bxcan_t *c)
{
    c->state = (uint8_t)co_bxcan_state(c);
    wr(c, CO_BXCAN_MSR, CO_BXCAN_MSR_ERRI); /* rc_w1 */
}
