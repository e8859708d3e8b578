/*
 * The minimal slave on an STM32F103's bxCAN (CAN1, PA11/PA12, reset clocks:
 * HSI 8 MHz, APB1 8 MHz, 500 kbit/s): the driver's interrupts feed the core
 * (RX FIFOs into co_rxq, TX-empty into co_node_tx_ready, error state into
 * co_node_can_state), the hardware filters hold the node's COB-ID set
 * (co_node_rx_cob) and are reprogrammed when the core says it changed, and
 * the core sleeps in WFI until a CAN interrupt or the 1 ms SysTick.
 * Parameters (0x1010 / 0x1011) live in the last 4 KiB of the flash, four
 * 1 KiB pages (an STM32F103x8's), two banks of two pages: a save erases its
 * bank's pages through the asynchronous NV HAL (co_bxcan/flash.h) and the
 * SDO answer comes when the set is programmed. Built in CI (tools/run-tests,
 * Cortex-M3 cross-build); it has not run on a board here.
 */
#include <stdint.h>

#include "co/co_canstate.h"
#include "co/co_node.h"
#include "co/co_rxq.h"
#include "bxcan_slave.h"
#include "co_bxcan/bxcan.h"
#include "co_bxcan/flash.h"

#define REG(a) (*(volatile uint32_t *)(uintptr_t)(a))
#define RCC_APB2ENR  0x40021018UL
#define RCC_APB1ENR  0x4002101CUL
#define GPIOA_CRH    0x40010804UL
#define NVIC_ISER0   0xE000E100UL
#define SYST_CSR     0xE000E010UL
#define SYST_RVR     0xE000E014UL
#define SYST_CVR     0xE000E018UL
#define CPU_HZ       8000000UL
#define NODE_ID      1U
#define NV_PAGE      1024U                   /* STM32F103x8: 1 KiB pages */
#define NV_SIZE      4096U                   /* = _nv_reserve (CMakeLists.txt) */
#define NV_BASE      (0x08000000UL + 65536UL - NV_SIZE)

static co_bxcan_t can;
static co_rxq_t rxq;
static co_rxq_frame_t rx_store[16];
static co_bxcan_flash_t flash;
static co_bxcan_port_t port = {&can, &flash};
static bxcan_slave_node_t slave;
static volatile uint32_t ms_ticks;
static volatile uint8_t filters_stale;

void SysTick_Handler(void);
void USB_HP_CAN1_TX_IRQHandler(void);
void CAN1_RX0_IRQHandler(void);
void CAN1_RX1_IRQHandler(void);
void CAN1_SCE_IRQHandler(void);

void SysTick_Handler(void)
{
    ms_ticks++;
}
void USB_HP_CAN1_TX_IRQHandler(void)
{
    co_bxcan_tx_isr(&can);
}
void CAN1_RX0_IRQHandler(void)
{
    co_bxcan_rx_isr(&can, 0U);
}
void CAN1_RX1_IRQHandler(void)
{
    co_bxcan_rx_isr(&can, 1U);
}
void CAN1_SCE_IRQHandler(void)
{
    co_bxcan_sce_isr(&can);
}

/* microseconds: SysTick milliseconds plus the counted-down part */
static uint32_t now_us(void)
{
    uint32_t ms;
    uint32_t cvr;

    do {
        ms = ms_ticks;
        cvr = REG(SYST_CVR);
    } while (ms != ms_ticks);
    return (ms * 1000U) + (((CPU_HZ / 1000U) - 1U - cvr) / (CPU_HZ / 1000000U));
}

static void on_rx_set(void *ctx, co_node_t *node)
{
    (void)ctx;
    (void)node;
    filters_stale = 1U;
}

/* the node's callbacks: a const table (flash) */
static const co_node_callbacks_t node_cb = {.rx_set = on_rx_set};

static void program_filters(co_node_t *node)
{
    uint16_t cobs[28]; /* 14 banks x 4 entries / (data + RTR) */
    uint16_t n = 0U;

    while ((n < 28U) && co_node_rx_cob(node, n, &cobs[n])) {
        n++;
    }
    if ((n == 28U) && co_node_rx_cob(node, n, &cobs[0])) {
        n = 0U; /* more than the banks hold: accept everything */
    }
    (void)co_bxcan_filters(&can, cobs, n);
}

static int due(uint32_t now, uint32_t deadline)
{
    return (deadline != CO_NO_DEADLINE) && ((int32_t)(now - deadline) >= 0);
}

int main(void)
{
    static const co_hal_ops_t hal_ops = {.send = co_bxcan_port_send,
                                         .nv_read = co_bxcan_port_nv_read,
                                         .nv_write = co_bxcan_port_nv_write,
                                         .nv_erase = co_bxcan_port_nv_erase,
                                         .nv_poll = co_bxcan_port_nv_poll,
                                         .nv_erase_unit = NV_PAGE};
    co_node_config_t cfg;
    uint32_t deadline;
    co_can_state_t state = CO_CAN_ERROR_ACTIVE;
    uint32_t overruns = 0U;

    REG(RCC_APB2ENR) |= 0x5U;                 /* AFIO, GPIOA */
    REG(RCC_APB1ENR) |= 1UL << 25U;           /* CAN1 */
    REG(GPIOA_CRH) = (REG(GPIOA_CRH) & ~0x000FF000UL) | 0x000B8000UL; /* PA11 in, PA12 AF PP */
    REG(SYST_RVR) = (CPU_HZ / 1000U) - 1U;
    REG(SYST_CVR) = 0U;
    REG(SYST_CSR) = 7U;                       /* core clock, interrupt, on */
    (void)co_rxq_init(&rxq, rx_store, 16U);
    if (co_bxcan_init(&can, CO_BXCAN1_BASE, NULL, NULL, &rxq, CPU_HZ, 500000UL) != 0) {
        for (;;) {
        }
    }
    REG(NVIC_ISER0) = 0xFUL << 19U;           /* CAN1 TX, RX0, RX1, SCE */
    if ((co_store_nv_size_unit(&bxcan_slave_dev, NV_PAGE) > NV_SIZE) ||
        (co_bxcan_flash_init(&flash, CO_FLASH_F1, CO_FLASH_R_BASE_F1, NULL, NULL, NV_BASE,
                             NV_SIZE, NV_PAGE, 0U) != 0)) {
        for (;;) {
        }
    }
    bxcan_slave_config(&slave, &cfg);
    cfg.hal.ops = &hal_ops;
    cfg.hal.ctx = &port;
    cfg.node_id = NODE_ID;
    cfg.cb = &node_cb;
    (void)co_node_init(&slave.node, &cfg, now_us());
    deadline = now_us();
    for (;;) {
        co_frame_t f;
        uint32_t now = now_us();
        int work = 0;

        if (filters_stale != 0U) {
            filters_stale = 0U;
            program_filters(&slave.node);
        }
        if ((co_can_state_t)can.state != state) {
            state = (co_can_state_t)can.state;
            co_node_can_state(&slave.node, state, now);
            work = 1;
        } else if ((state != CO_CAN_ERROR_ACTIVE) && (co_bxcan_state(&can) == CO_CAN_ERROR_ACTIVE)) {
            can.state = (uint8_t)CO_CAN_ERROR_ACTIVE; /* recovered: no interrupt says so */
        } else {
            /* unchanged */
        }
        while (co_rxq_pop(&rxq, &f)) {
            co_node_can_overrun(&slave.node, can.rx_overruns != overruns);
            overruns = can.rx_overruns;
            co_node_rx(&slave.node, &f, now);
            work = 1;
        }
        if (can.tx_ready != 0U) {
            can.tx_ready = 0U;
            co_node_tx_ready(&slave.node, now);
        }
        if ((work != 0) || due(now, deadline)) {
            deadline = co_node_process(&slave.node, now);
        } else {
            __asm__ volatile("wfi"); /* a CAN interrupt or the next millisecond */
        }
    }
}
