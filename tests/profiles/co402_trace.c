/*
 * co402_trace: a profile position move of the cia402 device on the
 * simulated plant, written as CSV (one row per millisecond) for
 * tools/plot-trace:
 *
 *     t_ms,position,velocity,statusword,position_demand
 *
 * The move: enable, then a set-point of 20000 increments (profile velocity
 * 10000/s, acceleration 50000/s^2), and at 1.5 s a new set-point of 4000
 * with "change set immediately", until the target is reached. Everything
 * goes through the object dictionary as a master's SDO writes would.
 *
 * Usage: co402_trace [OUT.csv]   (default: standard output)
 */
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "cia402.h"
#include "co/co402.h"
#include "co/co402_sim.h"
#include "co/co_profile.h"

typedef struct trace {
    cia402_node_t n;
    co_profile_host_t host;
    co_profile_t slot;
    co402_axis_t ax;
    co402_sim_t sim;
    uint32_t now;
    unsigned frames;
} trace_t;

static trace_t tr;

static int hal_send(void *ctx, const co_frame_t *f)
{
    (void)f;
    ((trace_t *)ctx)->frames++;
    return 0;
}

static const co_hal_ops_t hal_ops = {.send = hal_send};

static int put(uint16_t index, int64_t v, uint32_t len)
{
    uint8_t b[4];
    for (uint32_t i = 0; i < len; i++) {
        b[i] = (uint8_t)((uint64_t)v >> (8U * i));
    }
    if (co_od_write(&tr.n.node, index, 0, b, len, false) != CO_OK) {
        fprintf(stderr, "co402_trace: write 0x%04X failed\n", index);
        return -1;
    }
    return 0;
}

static int32_t get(uint16_t index)
{
    uint8_t b[4] = {0};
    uint32_t len = 0;
    (void)co_od_read(&tr.n.node, index, 0, b, sizeof b, &len);
    if (len == 2U) {
        return (int32_t)(uint16_t)(b[0] | (b[1] << 8));
    }
    return (int32_t)((uint32_t)b[0] | ((uint32_t)b[1] << 8) | ((uint32_t)b[2] << 16) |
                     ((uint32_t)b[3] << 24));
}

static void step(FILE *out)
{
    tr.now += 1000U;
    (void)co_node_process(&tr.n.node, tr.now);
    (void)co_profile_host_process(&tr.host, tr.now);
    fprintf(out, "%u,%d,%d,%d,%d\n", (unsigned)(tr.now / 1000U), (int)get(0x6064),
            (int)get(0x606C), (int)get(0x6041), (int)get(0x6062));
}

int main(int argc, char **argv)
{
    co_node_config_t cfg;
    co402_sim_config_t sc;
    co402_config_t ac;
    FILE *out = stdout;
    unsigned t;
    int err = 0;

    if (argc > 1) {
        out = fopen(argv[1], "w");
        if (out == NULL) {
            perror(argv[1]);
            return 1;
        }
    }
    memset(&tr, 0, sizeof tr);
    co402_sim_defaults(&sc);
    co402_sim_init(&tr.sim, &sc, 0);
    memset(&ac, 0, sizeof ac);
    ac.plant = co402_sim_plant(&tr.sim);
    co402_init(&tr.ax, &ac);
    co_profile_host_init(&tr.host, &tr.slot, 1, NULL);
    (void)co_profile_add(&tr.host, &co402_profile_ops, &tr.ax);
    cia402_config(&tr.n, &cfg);
    cfg.hal.ops = &hal_ops;
    cfg.hal.ctx = &tr;
    cfg.node_id = 1;
    cfg.cb = co_profile_host_callbacks(&tr.host);
    if ((co_node_init(&tr.n.node, &cfg, 0) != CO_RESULT_OK) ||
        (co_profile_host_attach(&tr.host, &tr.n.node, 0) != CO_OK)) {
        fprintf(stderr, "co402_trace: cannot start the node\n");
        return 1;
    }
    fprintf(out, "t_ms,position,velocity,statusword,position_demand\n");
    err |= put(0x6083, 50000, 4);
    err |= put(0x6084, 50000, 4);
    err |= put(0x6040, 0x0006, 2);
    step(out);
    err |= put(0x6040, 0x000F, 2);
    for (t = 0; t < 20U; t++) {
        step(out);
    }
    err |= put(0x607A, 20000, 4);
    err |= put(0x6040, 0x001F, 2);
    step(out);
    err |= put(0x6040, 0x000F, 2);
    for (t = 0; t < 1500U; t++) {
        step(out);
    }
    err |= put(0x607A, 4000, 4);
    err |= put(0x6040, 0x003F, 2);
    step(out);
    err |= put(0x6040, 0x000F, 2);
    for (t = 0; (t < 10000U) && ((get(0x6041) & 0x0400) == 0); t++) {
        step(out);
    }
    for (t = 0; t < 200U; t++) {
        step(out);
    }
    if (out != stdout) {
        (void)fclose(out);
    }
    if ((err != 0) || (get(0x6064) != 4000)) {
        fprintf(stderr, "co402_trace: the move did not end at 4000 (%d)\n", (int)get(0x6064));
        return 1;
    }
    return 0;
}
