/*
 * ZynqMP CAN driver (port/xlnx-can) against a register-level model of the
 * controller: the RX FIFO pops four words per frame, ISR.RXNEMP is set while
 * frames wait (and again after ICR while more do), SR.TXFLL when the TX FIFO
 * is full, writing DATA2 sends. Built twice: QEMU's ID/data layout and the
 * hardware manual's (CO_XCAN_LAYOUT); the register values below are the
 * layout's exact words.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "co_xcan/xcan.h"
#include "test_frames.h"

#define QEMU (CO_XCAN_LAYOUT == CO_XCAN_LAYOUT_QEMU)

typedef struct model {
    uint32_t regs[64];
    uint32_t rx[16][4];   /* frames waiting, 4 words each */
    uint32_t n_rx;
    uint32_t rx_latch[4]; /* the frame the ID read popped */
    uint32_t tx[16][4];
    uint32_t n_tx;
    uint32_t tx_words;    /* words of the frame being written */
    uint32_t tx_cap;      /* TX FIFO depth */
    uint32_t isr;
    uint32_t estat;       /* SR bits 8:7 */
} model_t;

static uint32_t m_read(void *ctx, uint32_t off)
{
    model_t *m = (model_t *)ctx;

    switch (off) {
    case CO_XCAN_ISR:
        return m->isr | ((m->n_rx > 0U) ? CO_XCAN_IXR_RXNEMP : 0U);
    case CO_XCAN_SR:
        return (((m->regs[0] & CO_XCAN_SRR_CEN) != 0U) ? CO_XCAN_SR_NORMAL : CO_XCAN_SR_CONFIG) |
               ((m->n_tx >= m->tx_cap) ? CO_XCAN_SR_TXFLL : 0U) |
               (m->estat << CO_XCAN_SR_ESTAT_SHIFT);
    case CO_XCAN_RXFIFO_ID:
        assert_true(m->n_rx > 0U);
        (void)memcpy(m->rx_latch, m->rx[0], sizeof m->rx_latch);
        (void)memmove(m->rx[0], m->rx[1], sizeof m->rx[0] * (m->n_rx - 1U));
        m->n_rx--;
        return m->rx_latch[0];
    case CO_XCAN_RXFIFO_ID + 4U:
    case CO_XCAN_RXFIFO_ID + 8U:
    case CO_XCAN_RXFIFO_ID + 12U:
        return m->rx_latch[(off - CO_XCAN_RXFIFO_ID) / 4U];
    default:
        return m->regs[off / 4U];
    }
}

static void m_write(void *ctx, uint32_t off, uint32_t v)
{
    model_t *m = (model_t *)ctx;

    if (off == CO_XCAN_ICR) {
        m->isr &= ~v;
    } else if ((off >= CO_XCAN_TXFIFO_ID) && (off <= CO_XCAN_TXFIFO_ID + 12U)) {
        uint32_t k = (off - CO_XCAN_TXFIFO_ID) / 4U;

        assert_int_equal(k, m->tx_words); /* ID, DLC, DATA1, DATA2 in order */
        assert_true(m->n_tx < m->tx_cap);
        m->tx[m->n_tx][k] = v;
        m->tx_words = (k + 1U) % 4U;
        if (k == 3U) {
            m->n_tx++;
        }
    } else {
        m->regs[off / 4U] = v;
    }
}

static const co_xcan_io_t model_io = {m_read, m_write};

static void push_rx(model_t *m, uint32_t id, uint32_t dlc, uint32_t d1, uint32_t d2)
{
    uint32_t *w = m->rx[m->n_rx++];

    w[0] = id;
    w[1] = dlc << 28U;
    w[2] = d1;
    w[3] = d2;
}

static void start(model_t *m, co_xcan_t *c)
{
    (void)memset(m, 0, sizeof *m);
    m->tx_cap = 16U;
    assert_int_equal(co_xcan_init(c, 0U, &model_io, m, 24000000UL, 500000UL), 0);
}

static void identifiers_in_the_layout(void **state)
{
    static const struct {
        uint32_t id;
        uint32_t reg;
    } cases[] = {
#if QEMU
        {0x605U, 0x00000605UL},
        {0x705U | CO_FRAME_RTR, 0x40000705UL},
        {0x1234567UL | CO_FRAME_EFF, 0x81234567UL},
        {0x1234567UL | CO_FRAME_EFF | CO_FRAME_RTR, 0xC1234567UL},
#else
        {0x605U, 0xC0A00000UL},
        {0x705U | CO_FRAME_RTR, 0xE0B00000UL},
        {0x1234567UL | CO_FRAME_EFF, 0x091E8ACEUL},
        {0x1234567UL | CO_FRAME_EFF | CO_FRAME_RTR, 0x091E8ACFUL},
#endif
    };
    (void)state;
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        assert_int_equal(co_xcan_id_to_reg(cases[k].id), cases[k].reg);
        assert_int_equal(co_xcan_reg_to_id(cases[k].reg), cases[k].id);
    }
}

static void bit_timing_table(void **state)
{
    uint32_t brpr = 0U;
    uint32_t btr = 0U;
    (void)state;
    /* 24 MHz, 500 kbit/s: prescaler 3, 16 tq = 1 + 13 + 2 (87.5 %), SJW 2 */
    assert_int_equal(co_xcan_timing(24000000UL, 500000UL, &brpr, &btr), 0);
    assert_int_equal(brpr, 2U);
    assert_int_equal(btr, 12U | (1U << 4U) | (1U << 7U));
    /* 100 MHz, 1 Mbit/s: prescaler 5, 20 tq = 1 + 16 + 3 (TS1 at most 16), SJW 3 */
    assert_int_equal(co_xcan_timing(100000000UL, 1000000UL, &brpr, &btr), 0);
    assert_int_equal(brpr, 4U);
    assert_int_equal(btr, 15U | (2U << 4U) | (2U << 7U));
    /* every CiA bit rate at 24 MHz; at 100 MHz the 8-bit prescaler stops at
     * 100e6 / 256 / 25 = 15.6 kbit/s */
    static const uint32_t rates[] = {10000, 20000, 50000, 125000, 250000, 500000, 800000,
                                     1000000};
    for (size_t k = 0; k < sizeof rates / sizeof rates[0]; k++) {
        assert_int_equal(co_xcan_timing(24000000UL, rates[k], &brpr, &btr), 0);
        assert_int_equal(co_xcan_timing(100000000UL, rates[k], &brpr, &btr),
                         (rates[k] < 15625U) ? -1 : 0);
    }
    /* 800 kbit/s at 100 MHz: only 25 tq divide; TS1 16, TS2 8 (68 %) */
    assert_int_equal(co_xcan_timing(100000000UL, 800000UL, &brpr, &btr), 0);
    assert_int_equal(brpr, 4U);
    assert_int_equal(btr, 15U | (7U << 4U) | (3U << 7U));
    assert_int_equal(co_xcan_timing(24000000UL, 0U, &brpr, &btr), -1);
    assert_int_equal(co_xcan_timing(24000000UL, 777777UL, &brpr, &btr), -1);
}

static void init_programs_the_controller(void **state)
{
    model_t m;
    co_xcan_t c;
    (void)state;
    start(&m, &c);
    assert_int_equal(m.regs[CO_XCAN_SRR / 4U], CO_XCAN_SRR_CEN);
    assert_int_equal(m.regs[CO_XCAN_BRPR / 4U], 2U);
    assert_int_equal(m.regs[CO_XCAN_AFR / 4U], 0U);
    assert_int_equal(m.regs[CO_XCAN_MSR / 4U], 0U);
    /* a bit rate the clock cannot make: no start */
    assert_int_equal(co_xcan_init(&c, 0U, &model_io, &m, 24000000UL, 777777UL), -1);
}

static void send_writes_the_four_words(void **state)
{
    model_t m;
    co_xcan_t c;
    co_frame_t f = tf_parse("585 43 00 10 00 92 01 02 00");
    (void)state;
    start(&m, &c);
    assert_int_equal(co_xcan_send(&c, &f), 0);
    f = tf_parse("705 R");
    assert_int_equal(co_xcan_send(&c, &f), 0);
    assert_int_equal(m.n_tx, 2U);
    assert_int_equal(m.tx[0][1], 8UL << 28U);
#if QEMU
    assert_int_equal(m.tx[0][0], 0x585U);
    assert_int_equal(m.tx[0][2], 0x00100043UL);
    assert_int_equal(m.tx[0][3], 0x00020192UL);
    assert_int_equal(m.tx[1][0], 0x40000705UL);
#else
    assert_int_equal(m.tx[0][0], 0x585UL << 21U);
    assert_int_equal(m.tx[0][2], 0x43001000UL);
    assert_int_equal(m.tx[0][3], 0x92010200UL);
    assert_int_equal(m.tx[1][0], (0x705UL << 21U) | 0x00100000UL);
#endif
    assert_int_equal(m.tx[1][1], 0U);
    assert_int_equal(m.tx[1][2], 0U);
}

static void send_refused_while_the_fifo_is_full(void **state)
{
    model_t m;
    co_xcan_t c;
    co_frame_t f = tf_parse("185 01");
    (void)state;
    start(&m, &c);
    m.tx_cap = 2U;
    assert_int_equal(co_xcan_send(&c, &f), 0);
    assert_int_equal(co_xcan_send(&c, &f), 0);
    assert_int_equal(co_xcan_send(&c, &f), 1); /* the core keeps it */
    assert_int_equal(m.n_tx, 2U);
    assert_int_equal(c.tx_full, 1U);
}

static void receive_in_order_until_empty(void **state)
{
    model_t m;
    co_xcan_t c;
    co_frame_t f;
    (void)state;
    start(&m, &c);
#if QEMU
    push_rx(&m, 0x605U, 8U, 0x01101840UL, 0x00000000UL);
    push_rx(&m, 0x40000705UL, 0U, 0U, 0U);
    push_rx(&m, 0x000U, 2U, 0x00000501UL, 0U);
#else
    push_rx(&m, 0x605UL << 21U, 8U, 0x40181001UL, 0x00000000UL);
    push_rx(&m, (0x705UL << 21U) | 0x00100000UL, 0U, 0U, 0U);
    push_rx(&m, 0x000U, 2U, 0x01050000UL, 0U);
#endif
    m.isr = CO_XCAN_IXR_RXOFLW;
    assert_int_equal(co_xcan_recv(&c, &f), 1);
    TF_ASSERT_FRAME(&f, "605 40 18 10 01 00 00 00 00");
    assert_int_equal(c.rx_overruns, 1U);
    assert_int_equal(m.isr & CO_XCAN_IXR_RXOFLW, 0U); /* acknowledged */
    assert_int_equal(co_xcan_recv(&c, &f), 1);
    TF_ASSERT_FRAME(&f, "705 R");
    assert_int_equal(co_xcan_recv(&c, &f), 1);
    TF_ASSERT_FRAME(&f, "000 01 05");
    assert_int_equal(co_xcan_recv(&c, &f), 0);
    assert_int_equal(c.rx_overruns, 1U);
}

static void long_dlc_is_clamped(void **state)
{
    model_t m;
    co_xcan_t c;
    co_frame_t f;
    (void)state;
    start(&m, &c);
    push_rx(&m, co_xcan_id_to_reg(0x181U), 15U, 0U, 0U);
    assert_int_equal(co_xcan_recv(&c, &f), 1);
    assert_int_equal(f.dlc, 8U);
}

static void controller_state_from_estat(void **state)
{
    model_t m;
    co_xcan_t c;
    (void)state;
    start(&m, &c);
    m.estat = 1U;
    assert_int_equal(co_xcan_state(&c), CO_CAN_ERROR_ACTIVE);
    m.estat = 3U;
    assert_int_equal(co_xcan_state(&c), CO_CAN_ERROR_PASSIVE);
    m.estat = 2U;
    assert_int_equal(co_xcan_state(&c), CO_CAN_BUS_OFF);
    m.estat = 0U;
    assert_int_equal(co_xcan_state(&c), CO_CAN_ERROR_ACTIVE);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(identifiers_in_the_layout),
        cmocka_unit_test(bit_timing_table),
        cmocka_unit_test(init_programs_the_controller),
        cmocka_unit_test(send_writes_the_four_words),
        cmocka_unit_test(send_refused_while_the_fifo_is_full),
        cmocka_unit_test(receive_in_order_until_empty),
        cmocka_unit_test(long_dlc_is_clamped),
        cmocka_unit_test(controller_state_from_estat),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
