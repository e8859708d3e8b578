/*
 * The minimal slave measured against the size target: NMT, heartbeat
 * producer and consumer, node guarding, SDO (expedited, segmented, block),
 * 4 RPDOs + 4 TPDOs, SYNC, EMCY with an 8-deep history, on a Cortex-M3 with a
 * stub CAN driver. Its dictionary is generated from minimal-slave.toml. Built
 * only for the size report; it never runs.
 */
#include <stdint.h>

#include "co/co_node.h"
#include "co/co_rxq.h"
#include "minimal_slave.h"

/* A stand-in for the CAN peripheral: a TX mailbox register. */
static volatile uint32_t can_tx_reg;
static int can_send(void *ctx, const co_frame_t *f)
{
    (void)ctx;
    can_tx_reg = f->id ^ f->data[0];
    return 0;
}
static const co_hal_ops_t hal_ops = {can_send, NULL, NULL};

static minimal_slave_node_t slave;
static co_frame_t rx_store[8];
static co_rxq_t rxq;
volatile uint32_t systick_us;

/* The CAN RX interrupt would call co_rxq_push(&rxq, &frame). */
void can_rx_isr(const co_frame_t *f);
void can_rx_isr(const co_frame_t *f)
{
    (void)co_rxq_push(&rxq, f);
}

int main(void)
{
    co_node_config_t cfg;
    co_frame_t f;

    minimal_slave_config(&slave, &cfg);
    cfg.hal.ops = &hal_ops;
    cfg.node_id = 1U;
    (void)co_rxq_init(&rxq, rx_store, 8U);
    (void)co_node_init(&slave.node, &cfg, systick_us);
    for (;;) {
        while (co_rxq_pop(&rxq, &f)) {
            co_node_rx(&slave.node, &f, systick_us);
        }
        (void)co_node_process(&slave.node, systick_us);
    }
}
