/*
 * The generic-301 device as Cortex-R5 firmware on QEMU's xlnx-zcu102:
 * CAN0 (ZynqMP CAN controller, polled), time from the PMU cycle counter,
 * parameter storage (0x1010/0x1011) in a host file through semihosting.
 *
 * Command line (semihosting, QEMU's -semihosting-config arg=...; tools/
 * run-firmware builds it):  canopen-fw --node-id N [--storage FILE]
 *   [--bitrate B] [--serial S]. --serial: 0x1018 sub 4 of this instance, its
 *   LSS address (decimal; default the description's, 1). Without --storage, 0x1010 answers 0x08000020 (no NV).
 *
 * The loop polls: no interrupt reaches QEMU's R5 (its GIC serves the A53s),
 * so the core cannot sleep in WFI until the deadline co_node_process()
 * returns; the loop calls co_node_process() only when that deadline has come
 * or a frame arrived. With an interrupt controller, WFI would go where
 * wait_for() spins.
 */
#include <stdint.h>
#include <string.h>

#include "co/co_canstate.h"
#include "co/co_endian.h"
#include "co/co_node.h"
#include "co_xcan/xcan.h"
#include "co/co_device.h"
#include "generic_301.h"
#include "generic_301_desc.h"
#include "semihost.h"

#ifndef FW_CYCLES_PER_US
#define FW_CYCLES_PER_US 1000U /* QEMU's PMU cycle counter runs at 1 GHz */
#endif
#ifndef FW_CAN_CLK_HZ
#define FW_CAN_CLK_HZ 24000000UL /* QEMU's default CAN reference clock */
#endif
#define FW_NV_MAX 4096U

void fw_main(void);

/* ------------------------------------------------------------ clock */

typedef struct fw_clock {
    uint32_t last;   /* cycle counter at the last reading */
    uint32_t frac;   /* cycles not yet counted as a microsecond */
    uint32_t us;
} fw_clock_t;

static void clock_start(fw_clock_t *c)
{
    uint32_t pmcr;

    __asm__ volatile("mrc p15, 0, %0, c9, c12, 0" : "=r"(pmcr));
    pmcr |= 0x5U; /* E: counters on, C: cycle counter reset */
    __asm__ volatile("mcr p15, 0, %0, c9, c12, 0" : : "r"(pmcr));
    __asm__ volatile("mcr p15, 0, %0, c9, c12, 1" : : "r"(0x80000000UL)); /* PMCNTENSET.C */
    c->last = 0U;
    c->frac = 0U;
    c->us = 0U;
}

/* Microseconds since clock_start; called at least every 2^32 cycles. */
static uint32_t clock_us(fw_clock_t *c)
{
    uint32_t now;
    uint32_t d;

    __asm__ volatile("mrc p15, 0, %0, c9, c13, 0" : "=r"(now));
    d = now - c->last;
    c->last = now;
    c->us += d / FW_CYCLES_PER_US;
    c->frac += d % FW_CYCLES_PER_US;
    if (c->frac >= FW_CYCLES_PER_US) {
        c->frac -= FW_CYCLES_PER_US;
        c->us++;
    }
    return c->us;
}

/* ------------------------------------------------------------ storage */

typedef struct fw_nv {
    int32_t fd;
    uint32_t size;
    uint8_t image[FW_NV_MAX]; /* the file's content, read at start */
} fw_nv_t;

static int nv_open(fw_nv_t *nv, const char *name, uint32_t size)
{
    int32_t len;

    if (size > FW_NV_MAX) {
        return -1;
    }
    nv->size = size;
    (void)memset(nv->image, 0xFF, size); /* erased */
    nv->fd = sh_open(name, 3U);          /* r+b: keep what is there */
    if (nv->fd == -1) {
        nv->fd = sh_open(name, 7U);      /* w+b: a new file */
    }
    if (nv->fd == -1) {
        return -1;
    }
    len = sh_flen(nv->fd);
    if (len > 0) {
        uint32_t n = ((uint32_t)len < size) ? (uint32_t)len : size;

        if ((sh_seek(nv->fd, 0U) != 0) || (sh_read(nv->fd, nv->image, n) != 0U)) {
            return -1;
        }
    }
    return 0;
}

static int nv_read(void *ctx, uint32_t addr, uint8_t *buf, uint32_t len)
{
    const fw_nv_t *nv = (const fw_nv_t *)ctx;

    if ((addr > nv->size) || (len > (nv->size - addr))) {
        return -1;
    }
    (void)memcpy(buf, &nv->image[addr], len);
    return 0;
}

static int nv_write(void *ctx, uint32_t addr, const uint8_t *buf, uint32_t len)
{
    fw_nv_t *nv = (fw_nv_t *)ctx;

    if ((addr > nv->size) || (len > (nv->size - addr))) {
        return -1;
    }
    (void)memcpy(&nv->image[addr], buf, len);
    if ((sh_seek(nv->fd, addr) != 0) || (sh_write(nv->fd, buf, len) != 0U)) {
        return -1;
    }
    return 0;
}

/* ------------------------------------------------------------ command line */

typedef struct fw_args {
    uint8_t node_id;
    uint32_t bitrate;
    const char *storage;
    uint32_t serial;
    int serial_given;
} fw_args_t;

static char *next_word(char **p)
{
    char *s = *p;
    char *w;

    while (*s == ' ') {
        s++;
    }
    if (*s == '\0') {
        return NULL;
    }
    w = s;
    while ((*s != ' ') && (*s != '\0')) {
        s++;
    }
    if (*s == ' ') {
        *s = '\0';
        s++;
    }
    *p = s;
    return w;
}

static int parse_u32(const char *s, uint32_t *v)
{
    uint32_t x = 0U;

    if ((s == NULL) || (*s == '\0')) {
        return -1;
    }
    for (; *s != '\0'; s++) {
        if ((*s < '0') || (*s > '9') || (x > 100000000UL)) {
            return -1;
        }
        x = (x * 10U) + (uint32_t)(*s - '0');
    }
    *v = x;
    return 0;
}

static int parse_args(char *line, fw_args_t *a)
{
    char *p = line;
    char *w;
    uint32_t v = 0U;

    a->node_id = 0U;
    a->bitrate = 500000UL;
    a->storage = NULL;
    a->serial_given = 0;
    (void)next_word(&p); /* program name */
    while ((w = next_word(&p)) != NULL) {
        if (strcmp(w, "--node-id") == 0) {
            if ((parse_u32(next_word(&p), &v) != 0) || (v < 1U) || (v > 127U)) {
                return -1;
            }
            a->node_id = (uint8_t)v;
        } else if (strcmp(w, "--bitrate") == 0) {
            if (parse_u32(next_word(&p), &a->bitrate) != 0) {
                return -1;
            }
        } else if (strcmp(w, "--serial") == 0) {
            if (parse_u32(next_word(&p), &a->serial) != 0) {
                return -1;
            }
            a->serial_given = 1;
        } else if (strcmp(w, "--storage") == 0) {
            a->storage = next_word(&p);
            if (a->storage == NULL) {
                return -1;
            }
        } else {
            return -1;
        }
    }
    return (a->node_id != 0U) ? 0 : -1;
}

/* ------------------------------------------------------------ the node */

static char cmdline[256];
static fw_clock_t clk;
static fw_nv_t nv;
static co_xcan_t can;
static generic_301_node_t g301;

/* generic-301 on the device layer: its dictionary and its plug-in
 * (devices/generic_301.c); no embedded EDS in the image. */
extern const co_device_plugin_t generic_301_plugin;
static const co_device_impl_t g301_impl = {.plugin = &generic_301_plugin};
static const co_device_t g301_device = {
    .name = "generic-301",
    .summary = "generic-301 as Cortex-R5 firmware",
    .dev = &generic_301_dev,
    .eds = NULL,
    .impl = &g301_impl,
};
static co_device_run_t run;
/* the plug-in's state (a g301_app_t, co_device_mem_size's only part) */
static union {
    g301_app_t app;
    uint64_t align;
} run_mem;

/* The hal's ctx is the CAN driver; the NV functions need the nv state:
 * one wrapper context holds both. */
typedef struct fw_hal_ctx {
    co_xcan_t *can;
    fw_nv_t *nv;
} fw_hal_ctx_t;

static int hal_send(void *ctx, const co_frame_t *f)
{
    return co_xcan_send(((fw_hal_ctx_t *)ctx)->can, f);
}
static int hal_nv_read(void *ctx, uint32_t addr, uint8_t *buf, uint32_t len)
{
    return nv_read(((fw_hal_ctx_t *)ctx)->nv, addr, buf, len);
}
static int hal_nv_write(void *ctx, uint32_t addr, const uint8_t *buf, uint32_t len)
{
    return nv_write(((fw_hal_ctx_t *)ctx)->nv, addr, buf, len);
}
static const co_hal_ops_t hal_plain = {.send = hal_send};
static const co_hal_ops_t hal_ops_nv = {.send = hal_send, .nv_read = hal_nv_read, .nv_write = hal_nv_write};
static fw_hal_ctx_t hal_ctx;

/* --serial: written again at every reset node (0x1018 sub 4 is a RAM value
 * the reset sets back to the description's default); wire bytes. */
static fw_args_t args;
static co_node_callbacks_t dev_cb; /* the device's callbacks, */
static co_node_callbacks_t fw_cb;  /* and the node's: those with fw_nmt_reset */

static void set_serial(co_node_t *node)
{
    uint8_t b[4];

    if (args.serial_given != 0) {
        co_put_u32(b, args.serial);
        (void)co_od_write(node, 0x1018U, 4U, b, 4U, true);
    }
}

static void fw_nmt_reset(void *ctx, co_node_t *node, co_reset_t kind)
{
    if (dev_cb.nmt_reset != NULL) {
        dev_cb.nmt_reset(ctx, node, kind);
    }
    if (kind == CO_RESET_NODE) {
        set_serial(node);
    }
}

static void fail(const char *msg)
{
    sh_puts("canopen-fw: ");
    sh_puts(msg);
    sh_puts("\n");
    sh_exit(0);
}

static int due(uint32_t now, uint32_t deadline)
{
    return (deadline != CO_NO_DEADLINE) && ((int32_t)(now - deadline) >= 0);
}

void fw_main(void)
{
    co_node_config_t cfg;
    uint32_t deadline;
    co_can_state_t can_state = CO_CAN_ERROR_ACTIVE;
    uint32_t overruns = 0U;

    clock_start(&clk);
    if ((sh_cmdline(cmdline, sizeof cmdline) != 0) || (parse_args(cmdline, &args) != 0)) {
        fail("usage: canopen-fw --node-id 1..127 [--storage FILE] [--bitrate B] [--serial S]");
    }
    if (co_xcan_init(&can, CO_XCAN0_BASE, NULL, NULL, FW_CAN_CLK_HZ, args.bitrate) != 0) {
        fail("CAN0 does not start (bit rate?)");
    }
    generic_301_config(&g301, &cfg);
    cfg.node_id = args.node_id;
    if (co_device_init(&run, &g301_device, &run_mem, sizeof run_mem, NULL, NULL,
                       clock_us(&clk)) != CO_OK) {
        fail("device start failed");
    }
    dev_cb = *co_device_callbacks(&run);
    fw_cb = dev_cb;
    fw_cb.nmt_reset = fw_nmt_reset;
    cfg.cb = &fw_cb;
    hal_ctx.can = &can;
    hal_ctx.nv = &nv;
    cfg.hal.ctx = &hal_ctx;
    cfg.hal.ops = &hal_plain;
    if (args.storage != NULL) {
        if (nv_open(&nv, args.storage, co_store_nv_size(cfg.dev)) != 0) {
            fail("cannot open the storage file");
        }
        cfg.hal.ops = &hal_ops_nv;
    }
    if ((co_node_init(&g301.node, &cfg, clock_us(&clk)) != CO_RESULT_OK) ||
        (co_device_attach(&run, &g301.node, clock_us(&clk)) != CO_OK)) {
        fail("node start failed");
    }
    set_serial(&g301.node);
    deadline = clock_us(&clk);
    for (;;) {
        co_frame_t f;
        uint32_t now = clock_us(&clk);
        int got = 0;
        co_can_state_t st = co_xcan_state(&can);

        if (st != can_state) { /* the core's CiA 301 policy: EMCY, 0x1029 */
            can_state = st;
            co_node_can_state(&g301.node, st, now);
            got = 1;
        }
        while (co_xcan_recv(&can, &f) != 0) {
            co_node_can_overrun(&g301.node, can.rx_overruns != overruns);
            overruns = can.rx_overruns;
            co_node_rx(&g301.node, &f, now);
            got = 1;
        }
        if ((got != 0) || due(now, deadline)) {
            uint32_t d1 = co_node_process(&g301.node, now);
            uint32_t d2 = co_device_process(&run, now);

            deadline = ((d2 != CO_NO_DEADLINE) && ((d1 == CO_NO_DEADLINE) ||
                                                   ((int32_t)(d2 - d1) < 0))) ? d2 : d1;
        }
    }
}
