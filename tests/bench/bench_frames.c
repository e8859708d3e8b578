/*
 * Instructions per frame: each bench_* function handles one kind of frame
 * N times on the minimal slave (targets/cortex-m/minimal-slave.toml, 4+4
 * PDOs). tools/bench-instructions runs this under callgrind and divides the
 * inclusive instruction count of each function by N.
 */
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "co/co_node.h"
#include "minimal_slave.h"

#define N 1000U

static unsigned sent;

static int bench_send(void *ctx, const co_frame_t *f)
{
    (void)ctx;
    (void)f;
    sent++;
    return 0;
}

static const co_hal_ops_t ops = {.send = bench_send};
static minimal_slave_node_t slave;
static uint32_t now = 1000U;

static co_frame_t frame(uint16_t id, uint8_t dlc, const uint8_t *data)
{
    co_frame_t f;
    memset(&f, 0, sizeof f);
    f.id = id;
    f.dlc = dlc;
    if (dlc > 0U) {
        memcpy(f.data, data, dlc);
    }
    return f;
}

/* SDO expedited upload request of 0x1000 and its answer. */
__attribute__((noinline)) static void bench_sdo(void)
{
    static const uint8_t req[8] = {0x40, 0x00, 0x10, 0x00, 0, 0, 0, 0};
    co_frame_t f = frame(0x601U, 8U, req);
    for (unsigned i = 0; i < N; i++) {
        co_node_rx(&slave.node, &f, now);
    }
}

/* RPDO1 (4 bytes, event-driven, one UNSIGNED32 mapped). */
__attribute__((noinline)) static void bench_rpdo(void)
{
    static const uint8_t d[4] = {1, 2, 3, 4};
    co_frame_t f = frame(0x201U, 4U, d);
    for (unsigned i = 0; i < N; i++) {
        co_node_rx(&slave.node, &f, now);
    }
}

/* SYNC with 4 synchronous TPDOs (each one UNSIGNED32). */
__attribute__((noinline)) static void bench_sync(void)
{
    co_frame_t f = frame(0x080U, 0U, NULL);
    for (unsigned i = 0; i < N; i++) {
        co_node_rx(&slave.node, &f, now);
    }
}

/* A frame for another node (an SDO request to node 5). */
__attribute__((noinline)) static void bench_other(void)
{
    static const uint8_t req[8] = {0x40, 0x00, 0x10, 0x00, 0, 0, 0, 0};
    co_frame_t f = frame(0x605U, 8U, req);
    for (unsigned i = 0; i < N; i++) {
        co_node_rx(&slave.node, &f, now);
    }
}

int main(void)
{
    co_node_config_t cfg;
    static const uint8_t start[2] = {0x01, 0x01};
    co_frame_t f;

    minimal_slave_config(&slave, &cfg);
    cfg.hal.ops = &ops;
    cfg.node_id = 1U;
    if (co_node_init(&slave.node, &cfg, now) != CO_RESULT_OK) {
        return 1;
    }
    f = frame(0x000U, 2U, start);
    co_node_rx(&slave.node, &f, now);
    sent = 0U;
    bench_sdo();
    bench_rpdo();
    bench_sync();
    bench_other();
    printf("frames sent: %u (expected %u)\n", sent, 5U * N);
    return (sent == 5U * N) ? 0 : 1;
}
