/*
 * STM32 bxCAN driver (port/bxcan) against a register-level model of the
 * controller: three TX mailboxes (TME/RQCP in TSR, TXRQ starts one, the
 * model "transmits" it), two 3-deep RX FIFOs (FMP, FOVR, RFOM pops), the
 * filter banks (16-bit list and 32-bit mask mode, evaluated by the model
 * for every frame the bus delivers), ESR and the initialisation handshake.
 * Then a generic-301 node on it: the TX-empty interrupt feeds the core
 * through co_node_tx_ready, the RX interrupt feeds co_rxq.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "co/co_node.h"
#include "co_bxcan/bxcan.h"
#include "generic_301.h"
#include "test_frames.h"

typedef struct model {
    uint32_t regs[0x400 / 4];
    uint32_t fifo[2][3][4]; /* RIR, RDTR, RDLR, RDHR */
    uint32_t n_fifo[2];
    uint32_t ovr[2];
    uint32_t tx_log[16][4];
    uint32_t n_tx;
    uint32_t seq[3];        /* request order of the pending mailboxes */
    uint32_t next_seq;
} model_t;

#define R(m, off) ((m)->regs[(off) / 4U])

static uint32_t m_read(void *ctx, uint32_t off)
{
    model_t *m = (model_t *)ctx;

    if ((off == CO_BXCAN_RF0R) || (off == CO_BXCAN_RF1R)) {
        uint32_t f = (off == CO_BXCAN_RF0R) ? 0U : 1U;
        return m->n_fifo[f] | ((m->n_fifo[f] == 3U) ? 0x8U : 0U) |
               (m->ovr[f] ? CO_BXCAN_RFR_FOVR : 0U);
    }
    if ((off >= CO_BXCAN_RI0R) && (off < CO_BXCAN_RI0R + 32U)) {
        uint32_t f = (off - CO_BXCAN_RI0R) / 16U;
        assert_true(m->n_fifo[f] > 0U);
        return m->fifo[f][0][(off % 16U) / 4U];
    }
    return m->regs[off / 4U];
}

static void m_write(void *ctx, uint32_t off, uint32_t v)
{
    model_t *m = (model_t *)ctx;

    if (off == CO_BXCAN_MCR) {
        R(m, CO_BXCAN_MCR) = v;
        R(m, CO_BXCAN_MSR) = (v & CO_BXCAN_MCR_INRQ) ? CO_BXCAN_MSR_INAK : 0U;
    } else if (off == CO_BXCAN_MSR) {
        R(m, CO_BXCAN_MSR) &= ~(v & 0x1CU);          /* rc_w1 */
    } else if (off == CO_BXCAN_TSR) {
        /* RQCPx rc_w1; clearing it clears the mailbox's TXOK, ALST, TERR */
        for (uint32_t b = 0; b < 3U; b++) {
            if (v & (CO_BXCAN_TSR_RQCP0 << (8U * b))) {
                R(m, CO_BXCAN_TSR) &= ~(0xFU << (8U * b));
            }
        }
    } else if ((off == CO_BXCAN_RF0R) || (off == CO_BXCAN_RF1R)) {
        uint32_t f = (off == CO_BXCAN_RF0R) ? 0U : 1U;
        if (v & CO_BXCAN_RFR_FOVR) {
            m->ovr[f] = 0U;
        }
        if ((v & CO_BXCAN_RFR_RFOM) && (m->n_fifo[f] > 0U)) {
            memmove(m->fifo[f][0], m->fifo[f][1], sizeof m->fifo[f][0] * 2U);
            m->n_fifo[f]--;
        }
    } else if ((off >= CO_BXCAN_F0R1) && (off < CO_BXCAN_F0R1 + 8U * CO_BXCAN_BANKS)) {
        /* filter registers are written only in initialisation mode */
        assert_true(R(m, CO_BXCAN_FMR) & CO_BXCAN_FMR_FINIT);
        m->regs[off / 4U] = v;
    } else if ((off >= CO_BXCAN_TI0R) && (off < CO_BXCAN_TI0R + 48U)) {
        uint32_t box = (off - CO_BXCAN_TI0R) / 16U;
        m->regs[off / 4U] = v;
        if (((off % 16U) == 0U) && (v & CO_BXCAN_TIR_TXRQ)) {
            assert_true(R(m, CO_BXCAN_TSR) & (CO_BXCAN_TSR_TME0 << box)); /* was empty */
            R(m, CO_BXCAN_TSR) &= ~(CO_BXCAN_TSR_TME0 << box);
            m->seq[box] = ++m->next_seq;
        }
    } else {
        m->regs[off / 4U] = v;
    }
}

static const co_bxcan_io_t model_io = {m_read, m_write};

static void model_reset(model_t *m)
{
    memset(m, 0, sizeof *m);
    R(m, CO_BXCAN_TSR) = 7UL << 26U; /* TME0..2 */
    R(m, CO_BXCAN_MSR) = 0x2U;       /* SLAK: sleep after reset */
}

/* The model puts mailbox @p box on the bus: logged, RQCP|TXOK, empty again. */
static void m_transmit(model_t *m, uint32_t box)
{
    uint32_t off = CO_BXCAN_TI0R + 16U * box;
    assert_false(R(m, CO_BXCAN_TSR) & (CO_BXCAN_TSR_TME0 << box));
    for (uint32_t k = 0; k < 4U; k++) {
        m->tx_log[m->n_tx][k] = m->regs[off / 4U + k];
    }
    m->n_tx++;
    R(m, CO_BXCAN_TI0R + 16U * box) &= ~CO_BXCAN_TIR_TXRQ;
    R(m, CO_BXCAN_TSR) |= (3U << (8U * box)) | (CO_BXCAN_TSR_TME0 << box);
}

/* Transmit every pending mailbox in request order (MCR.TXFP); how many. */
static uint32_t m_flush(model_t *m)
{
    uint32_t n = 0U;
    for (;;) {
        uint32_t best = 3U;
        for (uint32_t b = 0; b < 3U; b++) {
            if (!(R(m, CO_BXCAN_TSR) & (CO_BXCAN_TSR_TME0 << b)) &&
                ((best == 3U) || (m->seq[b] < m->seq[best]))) {
                best = b;
            }
        }
        if (best == 3U) {
            return n;
        }
        m_transmit(m, best);
        n++;
    }
}

/* Does a frame (RIR layout) pass the active filter banks? Its FIFO, or -1. */
static int m_accept(const model_t *m, uint32_t rir)
{
    for (uint32_t b = 0; b < CO_BXCAN_BANKS; b++) {
        uint32_t r1 = m->regs[(CO_BXCAN_F0R1 + 8U * b) / 4U];
        uint32_t r2 = m->regs[(CO_BXCAN_F0R1 + 8U * b + 4U) / 4U];
        bool list = (R(m, CO_BXCAN_FM1R) >> b) & 1U;
        bool scale32 = (R(m, CO_BXCAN_FS1R) >> b) & 1U;
        int fifo = (int)((R(m, CO_BXCAN_FFA1R) >> b) & 1U);
        if (!((R(m, CO_BXCAN_FA1R) >> b) & 1U)) {
            continue;
        }
        if (scale32) {
            uint32_t id32 = rir & ~1U;
            if (list ? ((id32 == (r1 & ~1U)) || (id32 == (r2 & ~1U)))
                     : (((id32 ^ r1) & r2 & ~1U) == 0U)) {
                return fifo;
            }
        } else {
            /* 16-bit: STID 15:5, RTR 4, IDE 3, EXID[17:15] 2:0 */
            uint32_t id16 = ((rir >> 21U) << 5U) | (((rir >> 1U) & 1U) << 4U) |
                            (((rir >> 2U) & 1U) << 3U) | ((rir >> 18U) & 7U);
            uint32_t e[4] = {r1 & 0xFFFFU, r1 >> 16U, r2 & 0xFFFFU, r2 >> 16U};
            if (list) {
                for (int k = 0; k < 4; k++) {
                    if (id16 == e[k]) {
                        return fifo;
                    }
                }
            } else if ((((id16 ^ e[0]) & e[1]) == 0U) || (((id16 ^ e[2]) & e[3]) == 0U)) {
                return fifo;
            }
        }
    }
    return -1;
}

/* The bus delivers a frame written like "605 40 00 10 ..." or "705 R". */
static bool m_deliver(model_t *m, const char *text)
{
    co_frame_t f = tf_parse(text);
    uint32_t rir = ((f.id & 0x7FFU) << 21U) | (co_frame_is_rtr(&f) ? 2U : 0U);
    int fifo = m_accept(m, rir);
    if (fifo < 0) {
        return false;
    }
    if (m->n_fifo[fifo] == 3U) {
        m->ovr[fifo] = 1U;
        return true;
    }
    uint32_t *w = m->fifo[fifo][m->n_fifo[fifo]++];
    w[0] = rir;
    w[1] = f.dlc;
    w[2] = (uint32_t)f.data[0] | ((uint32_t)f.data[1] << 8) | ((uint32_t)f.data[2] << 16) |
           ((uint32_t)f.data[3] << 24);
    w[3] = (uint32_t)f.data[4] | ((uint32_t)f.data[5] << 8) | ((uint32_t)f.data[6] << 16) |
           ((uint32_t)f.data[7] << 24);
    return true;
}

typedef struct fx {
    model_t m;
    co_bxcan_t c;
    co_rxq_frame_t store[8];
    co_rxq_t q;
} fx_t;

static int setup(void **state)
{
    static fx_t fx;
    model_reset(&fx.m);
    assert_true(co_rxq_init(&fx.q, fx.store, 8));
    assert_int_equal(co_bxcan_init(&fx.c, 0U, &model_io, &fx.m, &fx.q, 36000000UL, 500000UL), 0);
    *state = &fx;
    return 0;
}

#define FX ((fx_t *)*state)
#define M (&FX->m)
#define C (&FX->c)

static void timing_table_entries_are_exact(void **state)
{
    uint32_t n = 0U;
    const co_bxcan_timing_t *t = co_bxcan_timing_table(&n);
    (void)state;
    assert_true(n >= 50U);
    for (uint32_t k = 0; k < n; k++) {
        uint32_t brp = (t[k].btr & 0x3FFU) + 1U;
        uint32_t ts1 = ((t[k].btr >> 16U) & 0xFU) + 1U;
        uint32_t ts2 = ((t[k].btr >> 20U) & 0x7U) + 1U;
        uint32_t sjw = ((t[k].btr >> 24U) & 0x3U) + 1U;
        uint32_t tq = 1U + ts1 + ts2;
        assert_int_equal(t[k].clk_hz % (brp * tq), 0U);
        assert_int_equal(t[k].clk_hz / (brp * tq), t[k].bitrate);      /* exact bit rate */
        assert_in_range((1000U * (1U + ts1)) / tq, 850U, 900U);         /* sample point */
        assert_true((tq >= 8U) && (tq <= 25U) && (sjw <= ts2));
        assert_int_equal(co_bxcan_timing(t[k].clk_hz, t[k].bitrate), t[k].btr);
    }
    /* every CiA bit rate at 8, 16, 24, 36 and 48 MHz */
    static const uint32_t clks[] = {8000000, 16000000, 24000000, 36000000, 48000000};
    static const uint32_t rates[] = {10000, 20000, 50000, 125000, 250000, 500000, 800000,
                                     1000000};
    for (size_t i = 0; i < 5; i++) {
        for (size_t j = 0; j < 8; j++) {
            assert_true(co_bxcan_timing(clks[i], rates[j]) != 0U);
        }
    }
    assert_int_equal(co_bxcan_timing(42000000UL, 800000UL), 0U); /* does not divide */
    assert_int_equal(co_bxcan_timing(36000000UL, 500000UL), 0x00050008UL);
}

static void init_configures_the_controller(void **state)
{
    model_t m;
    co_bxcan_t c;
    assert_int_equal(R(M, CO_BXCAN_BTR), 0x00050008UL);
    assert_int_equal(R(M, CO_BXCAN_MCR), CO_BXCAN_MCR_TXFP | CO_BXCAN_MCR_ABOM);
    assert_int_equal(R(M, CO_BXCAN_MSR) & CO_BXCAN_MSR_INAK, 0U);
    assert_true(R(M, CO_BXCAN_IER) & CO_BXCAN_IER_TMEIE);
    assert_true(R(M, CO_BXCAN_IER) & CO_BXCAN_IER_FMPIE0);
    assert_true(R(M, CO_BXCAN_IER) & CO_BXCAN_IER_BOFIE);
    assert_true(m_deliver(M, "123 01"));                 /* everything accepted */
    model_reset(&m);
    assert_int_equal(co_bxcan_init(&c, 0U, &model_io, &m, NULL, 42000000UL, 800000UL), -1);
}

static void three_mailboxes_then_full(void **state)
{
    co_frame_t f = tf_parse("585 43 00 10 00 92 01 02 00");
    assert_int_equal(co_bxcan_send(C, &f), 0);
    f = tf_parse("705 R");
    assert_int_equal(co_bxcan_send(C, &f), 0);
    f.id = 0x1ABCDEFUL | CO_FRAME_EFF;
    f.dlc = 1U;
    f.data[0] = 0x55U;
    assert_int_equal(co_bxcan_send(C, &f), 0);
    assert_int_equal(co_bxcan_send(C, &f), 1);           /* no mailbox empty */
    for (uint32_t b = 0; b < 3U; b++) {
        m_transmit(M, b);
    }
    assert_int_equal(M->tx_log[0][0], (0x585U << 21U) | 1U);
    assert_int_equal(M->tx_log[0][1], 8U);
    assert_int_equal(M->tx_log[0][2], 0x00100043UL);
    assert_int_equal(M->tx_log[0][3], 0x00020192UL);
    assert_int_equal(M->tx_log[1][0], (0x705U << 21U) | 2U | 1U);
    assert_int_equal(M->tx_log[1][1], 0U);
    assert_int_equal(M->tx_log[2][0], (0x1ABCDEFU << 3U) | 4U | 1U);
    assert_int_equal(M->tx_log[2][2], 0x55U);
    assert_int_equal(C->tx_ready, 0U);
    co_bxcan_tx_isr(C);
    assert_int_equal(C->tx_ready, 1U);
    assert_int_equal(R(M, CO_BXCAN_TSR) & 0x00FFFFFFUL, 0U); /* RQCP acknowledged */
}

static void rx_fifo_into_the_queue(void **state)
{
    co_frame_t f;
    assert_true(m_deliver(M, "605 40 18 10 01 00 00 00 00"));
    assert_true(m_deliver(M, "705 R"));
    assert_true(m_deliver(M, "000 01 05"));
    assert_true(m_deliver(M, "080"));                    /* fourth: overrun */
    co_bxcan_rx_isr(C, 0U);
    assert_int_equal(C->rx_overruns, 1U);
    assert_int_equal(M->n_fifo[0], 0U);
    assert_true(co_rxq_pop(&FX->q, &f));
    TF_ASSERT_FRAME(&f, "605 40 18 10 01 00 00 00 00");
    assert_true(co_rxq_pop(&FX->q, &f));
    TF_ASSERT_FRAME(&f, "705 R");
    assert_true(co_rxq_pop(&FX->q, &f));
    TF_ASSERT_FRAME(&f, "000 01 05");
    assert_false(co_rxq_pop(&FX->q, &f));
}

static void filters_from_the_cob_set(void **state)
{
    static const uint16_t cobs[] = {0x000, 0x080, 0x605, 0x705, 0x205};
    uint16_t many[60];
    assert_int_equal(co_bxcan_filters(C, cobs, 5U), 3U); /* 10 entries, 4 per bank */
    assert_int_equal(R(M, CO_BXCAN_FMR), 0U);            /* filters active again */
    assert_true(m_deliver(M, "605 40 00 10 00 00 00 00 00"));
    assert_true(m_deliver(M, "705 R"));                  /* guarding RTR */
    assert_true(m_deliver(M, "205 01 02"));
    assert_false(m_deliver(M, "606 40 00 10 00 00 00 00 00"));
    assert_false(m_deliver(M, "185 00"));
    assert_false(m_deliver(M, "7FF"));
    /* more than 14 banks hold: everything passes */
    for (uint16_t k = 0; k < 60U; k++) {
        many[k] = (uint16_t)(0x200U + k);
    }
    assert_int_equal(co_bxcan_filters(C, many, 60U), 1U);
    co_bxcan_rx_isr(C, 0U);
    assert_true(m_deliver(M, "7FF"));
}

static void error_states_from_esr(void **state)
{
    R(M, CO_BXCAN_MSR) |= CO_BXCAN_MSR_ERRI;
    R(M, CO_BXCAN_ESR) = CO_BXCAN_ESR_EPVF | (128U << 16U);
    co_bxcan_sce_isr(C);
    assert_int_equal(C->state, CO_CAN_ERROR_PASSIVE);
    assert_int_equal(R(M, CO_BXCAN_MSR) & CO_BXCAN_MSR_ERRI, 0U);
    R(M, CO_BXCAN_ESR) = CO_BXCAN_ESR_BOFF | CO_BXCAN_ESR_EPVF | (255U << 16U);
    co_bxcan_sce_isr(C);
    assert_int_equal(C->state, CO_CAN_BUS_OFF);
    R(M, CO_BXCAN_ESR) = 0U;                             /* recovered: no interrupt */
    assert_int_equal(co_bxcan_state(C), CO_CAN_ERROR_ACTIVE);
}

/* A generic-301 node on the model: boot-up, an SDO answer, and a block upload
 * of five segments through three mailboxes: each TX-empty interrupt lets the
 * core go on at once (co_node_tx_ready, no co_node_process in between). */
static void node_fed_by_the_interrupts(void **state)
{
    static generic_301_node_t node;
    static const char text[] = "written in seven-byte segments!"; /* 31 bytes */
    co_node_config_t cfg;
    co_hal_ops_t ops = {.send = co_bxcan_send};
    co_frame_t f;

    generic_301_config(&node, &cfg);
    cfg.hal.ops = &ops;
    cfg.hal.ctx = C;
    cfg.node_id = 5U;
    assert_int_equal(co_node_init(&node.node, &cfg, 0U), CO_RESULT_OK);
    assert_int_equal(co_od_write(&node.node, 0x2013U, 0U, text, 31U, true), CO_OK);
    assert_int_equal(m_flush(M), 1U);
    assert_int_equal(M->tx_log[0][0], (0x705U << 21U) | 1U); /* boot-up */
    co_bxcan_tx_isr(C);
    C->tx_ready = 0U;
    assert_true(m_deliver(M, "605 A4 13 20 00 7F 00 00 00"));
    assert_true(m_deliver(M, "605 A3 00 00 00 00 00 00 00"));
    co_bxcan_rx_isr(C, 0U);
    while (co_rxq_pop(&FX->q, &f)) {
        co_node_rx(&node.node, &f, 10U);
    }
    /* the answer and two segments fill the mailboxes; the rest waits */
    for (uint32_t round = 0; round < 5U; round++) {
        (void)m_flush(M);
        co_bxcan_tx_isr(C);
        if (C->tx_ready) {
            C->tx_ready = 0U;
            co_node_tx_ready(&node.node, 10U);
        }
    }
    assert_int_equal(M->n_tx, 7U);
    assert_int_equal(M->tx_log[1][2], 0x002013C6UL);
    for (uint32_t k = 0; k < 5U; k++) {                  /* sequence numbers, last 0x85 */
        assert_int_equal(M->tx_log[2U + k][2] & 0xFFU, (k == 4U) ? 0x85U : k + 1U);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(timing_table_entries_are_exact),
        cmocka_unit_test_setup(init_configures_the_controller, setup),
        cmocka_unit_test_setup(three_mailboxes_then_full, setup),
        cmocka_unit_test_setup(rx_fifo_into_the_queue, setup),
        cmocka_unit_test_setup(filters_from_the_cob_set, setup),
        cmocka_unit_test_setup(error_states_from_esr, setup),
        cmocka_unit_test_setup(node_fed_by_the_interrupts, setup),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
