/*
 * The firmware tools/bench-size measures: a node of the device generated as
 * "size-dev" (tests/perf/size-seg.toml or cono-ex-feat.toml, CANopenNode's
 * example dictionary), fed from the CAN receive interrupt through a frame
 * queue and processed in the main loop, with a stand-in CAN driver. The
 * same shape as targets/cortex-m/minimal_slave.c; never run.
 */
#include <stdint.h>

#include "co/co_node.h"
#include "co/co_rxq.h"
#include "size_dev.h"

/* Stand-ins for the CAN peripheral: a TX mailbox register and the RX FIFO
 * (identifier, length, data bytes 0..3 and 4..7). */
static volatile uint32_t can_tx_reg;
static volatile uint32_t can_rx_fifo[4];
static int can_send(void *ctx, const co_frame_t *f)
{
    (void)ctx;
    can_tx_reg = f->id ^ f->data[0];
    return 0;
}
static const co_hal_ops_t hal_ops = {.send = can_send};

static size_dev_node_t node;
static co_frame_t rx_store[8];
static co_rxq_t rxq;
volatile uint32_t systick_us;

void CAN1_RX0_IRQHandler(void);
void CAN1_RX0_IRQHandler(void)
{
    co_frame_t f;
    uint32_t lo = can_rx_fifo[2];
    uint32_t hi = can_rx_fifo[3];

    f.id = can_rx_fifo[0];
    f.dlc = (uint8_t)(can_rx_fifo[1] & 0x0FU);
    for (uint8_t k = 0U; k < 4U; k++) {
        f.data[k] = (uint8_t)(lo >> (8U * k));
        f.data[4U + k] = (uint8_t)(hi >> (8U * k));
    }
    (void)co_rxq_push(&rxq, &f);
}

int main(void)
{
    co_node_config_t cfg;
    co_frame_t f;

    size_dev_config(&node, &cfg);
    cfg.hal.ops = &hal_ops;
    cfg.node_id = 5U;
    (void)co_rxq_init(&rxq, rx_store, 8U);
    (void)co_node_init(&node.node, &cfg, systick_us);
    for (;;) {
        while (co_rxq_pop(&rxq, &f)) {
            co_node_rx(&node.node, &f, systick_us);
        }
        (void)co_node_process(&node.node, systick_us);
    }
}
