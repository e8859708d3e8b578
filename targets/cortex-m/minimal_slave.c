/*
 * The minimal slave measured against the size target: NMT, heartbeat
 * producer and consumer, node guarding, SDO (expedited, segmented, block),
 * 4 RPDOs + 4 TPDOs, SYNC, EMCY with an 8-deep history, on a Cortex-M3 with a
 * stub CAN driver. Its dictionary is generated from minimal-slave.toml; the
 * start-up code (startup.c, libc_min.c, cortex-m3.ld) is the project's own,
 * so the image holds nothing the firmware does not use. Built only for the
 * size report; it never runs. tools/bench-size links the same loop with its
 * own device (SLAVE_HEADER, SLAVE_NODE_T, SLAVE_CONFIG, SLAVE_NODE_ID).
 */
#include <stdint.h>
#include <string.h>

#include "co/co_node.h"
#include "co/co_rxq.h"

#ifndef SLAVE_HEADER
#define SLAVE_HEADER  "minimal_slave.h"
#define SLAVE_NODE_T  minimal_slave_node_t
#define SLAVE_CONFIG  minimal_slave_config
#define SLAVE_NODE_ID 1U
#endif
#include SLAVE_HEADER

/* Stand-ins for the CAN peripheral's registers, memory-mapped as on a real
 * MCU (not RAM): at a bxCAN's addresses (STM32 CAN1), a TX mailbox register
 * and the RX FIFO's four (identifier, length, data bytes 0..3 and 4..7). */
#define CAN_BASE    0x40006400UL
#define can_tx_reg  (*(volatile uint32_t *)(uintptr_t)(CAN_BASE + 0x180UL)) /* TI0R */
#define can_rx_fifo ((volatile const uint32_t *)(uintptr_t)(CAN_BASE + 0x1B0UL)) /* RI0R.. */
static int can_send(void *ctx, const co_frame_t *f)
{
    (void)ctx;
    can_tx_reg = f->id ^ f->data[0];
    return 0;
}
static const co_hal_ops_t hal_ops = {.send = can_send};

static SLAVE_NODE_T node;
/* Frames that wait for the main loop, which empties the queue on every
 * pass: 3 (30 B; the queue holds as many frames as it has slots). A frame
 * costs the node a few hundred instructions, a CAN frame on the bus at
 * 1 Mbit/s at least 47 us, so only a long pass lets frames pile up; one
 * that finds the queue full is counted in rxq.dropped. A firmware with
 * longer passes makes it deeper. */
#define RXQ_LEN 3U
static co_rxq_frame_t rx_store[RXQ_LEN];
static co_rxq_t rxq = CO_RXQ_INIT(rx_store, RXQ_LEN);
volatile uint32_t systick_us;

/* The CAN RX interrupt (startup.c's vector table): the frame goes into the
 * queue the main loop drains. */
void CAN1_RX0_IRQHandler(void);
void CAN1_RX0_IRQHandler(void)
{
    co_frame_t f;
    uint32_t d[2];

    f.id = can_rx_fifo[0];
    f.dlc = (uint8_t)(can_rx_fifo[1] & 0x0FU);
    /* the data registers hold bytes 0..3 and 4..7, the first in the low
     * byte: on the little-endian Cortex-M the frame's bytes as they are */
    d[0] = can_rx_fifo[2];
    d[1] = can_rx_fifo[3];
    (void)memcpy(f.data, d, sizeof f.data);
    (void)co_rxq_push(&rxq, &f);
}

int main(void)
{
    co_node_config_t cfg;
    co_frame_t f;

    SLAVE_CONFIG(&node, &cfg);
    cfg.hal.ops = &hal_ops;
    cfg.node_id = SLAVE_NODE_ID;
    (void)co_node_init(&node.node, &cfg, systick_us);
    for (;;) {
        while (co_rxq_pop(&rxq, &f)) {
            co_node_rx(&node.node, &f, systick_us);
        }
        (void)co_node_process(&node.node, systick_us);
    }
}
