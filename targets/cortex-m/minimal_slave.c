/*
 * The minimal slave measured against the size target: NMT, heartbeat
 * producer and consumer, node guarding, SDO (expedited, segmented, block),
 * EMCY with an 8-deep history, on a Cortex-M3 with a stub CAN driver.
 * (PDO and SYNC join when the core has them.) Built only for the size
 * report; it never runs.
 */
#include <stddef.h>
#include <stdint.h>

#include "co/co_node.h"
#include "co/co_rxq.h"

typedef struct ms_ram {
    uint32_t sync_cob;
    uint16_t guard_time;
    uint8_t life_factor;
    uint8_t pad0;
    uint32_t emcy_cob;
    uint16_t emcy_inhibit;
    uint16_t hb_prod;
    uint32_t hb_cons[4];
    uint8_t errreg;
    uint8_t hist_n;
    uint16_t pad1;
    uint32_t hist[8];
} ms_ram_t;

typedef struct ms_rom {
    uint32_t x1000;
    uint32_t x1018[4];
    uint8_t n1016;
    uint8_t n1018;
} ms_rom_t;

static const ms_rom_t rom = {0x00000000UL, {0x1UL, 0x2UL, 0x3UL, 0x4UL}, 4U, 4U};
static const ms_ram_t defaults = {.sync_cob = 0x80UL, .emcy_cob = 0x80UL};

#define F(field) ((uint16_t)offsetof(ms_ram_t, field))
#define RF(field) ((uint16_t)offsetof(ms_rom_t, field))
#define V(t, fl, sz, off) {0U, (uint8_t)(t), (fl), (sz), (off), 0U}

static const co_od_sub_t s1000[] = {V(CO_UNSIGNED32, CO_SUB_RO | CO_SUB_ROM, 4U, RF(x1000))};
static const co_od_sub_t s1001[] = {V(CO_UNSIGNED8, CO_SUB_RO, 1U, F(errreg))};
static const co_od_sub_t s1003[] = {
    V(CO_UNSIGNED8, CO_SUB_RW, 1U, F(hist_n)),
#define H(i) {(i), (uint8_t)CO_UNSIGNED32, CO_SUB_RO, 4U, (uint16_t)(F(hist) + 4U * ((i) - 1U)), 0U}
    H(1), H(2), H(3), H(4), H(5), H(6), H(7), H(8),
};
static const co_od_sub_t s1005[] = {V(CO_UNSIGNED32, CO_SUB_RW, 4U, F(sync_cob))};
static const co_od_sub_t s100C[] = {V(CO_UNSIGNED16, CO_SUB_RW, 2U, F(guard_time))};
static const co_od_sub_t s100D[] = {V(CO_UNSIGNED8, CO_SUB_RW, 1U, F(life_factor))};
static const co_od_sub_t s1014[] = {V(CO_UNSIGNED32, CO_SUB_RW | CO_SUB_NODEID, 4U, F(emcy_cob))};
static const co_od_sub_t s1015[] = {V(CO_UNSIGNED16, CO_SUB_RW, 2U, F(emcy_inhibit))};
static const co_od_sub_t s1016[] = {
    V(CO_UNSIGNED8, CO_SUB_RO | CO_SUB_ROM, 1U, RF(n1016)),
#define C(i) {(i), (uint8_t)CO_UNSIGNED32, CO_SUB_RW, 4U, (uint16_t)(F(hb_cons) + 4U * ((i) - 1U)), 0U}
    C(1), C(2), C(3), C(4),
};
static const co_od_sub_t s1017[] = {V(CO_UNSIGNED16, CO_SUB_RW, 2U, F(hb_prod))};
static const co_od_sub_t s1018[] = {
    V(CO_UNSIGNED8, CO_SUB_RO | CO_SUB_ROM, 1U, RF(n1018)),
#define I(i) {(i), (uint8_t)CO_UNSIGNED32, CO_SUB_RO | CO_SUB_ROM, 4U, (uint16_t)(RF(x1018) + 4U * ((i) - 1U)), 0U}
    I(1), I(2), I(3), I(4),
};

#define E(idx, subs) {(idx), (uint8_t)(sizeof(subs) / sizeof((subs)[0])), 0U, CO_OBJ_VAR, (subs)}
static const co_od_entry_t od[] = {
    E(0x1000, s1000), E(0x1001, s1001), E(0x1003, s1003), E(0x1005, s1005),
    E(0x100C, s100C), E(0x100D, s100D), E(0x1014, s1014), E(0x1015, s1015),
    E(0x1016, s1016), E(0x1017, s1017), E(0x1018, s1018),
};

static const co_dev_t dev = {
    .name = "minimal",
    .od = od,
    .od_count = (uint16_t)(sizeof od / sizeof od[0]),
    .ram_size = (uint16_t)sizeof(ms_ram_t),
    .comm_end = F(errreg),
    .app_end = F(errreg),
    .defaults = &defaults,
    .rom = (const uint8_t *)&rom,
};

/* A stand-in for the CAN peripheral: a TX mailbox register. */
static volatile uint32_t can_tx_reg;
static int can_send(void *ctx, const co_frame_t *f)
{
    (void)ctx;
    can_tx_reg = f->id ^ f->data[0];
    return 0;
}
static const co_hal_ops_t hal_ops = {can_send, NULL, NULL};

static co_node_t node;
static ms_ram_t ram;
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
    co_node_config_t cfg = {0};
    co_frame_t f;

    cfg.dev = &dev;
    cfg.hal.ops = &hal_ops;
    cfg.node_id = 1U;
    cfg.ram = &ram;
    (void)co_rxq_init(&rxq, rx_store, 8U);
    (void)co_node_init(&node, &cfg, systick_us);
    for (;;) {
        while (co_rxq_pop(&rxq, &f)) {
            co_node_rx(&node, &f, systick_us);
        }
        (void)co_node_process(&node, systick_us);
    }
}
