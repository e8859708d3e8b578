/* One node's socket, storage and error state (see port.h). */
#include "co_lx/port.h"
#include "co/co_canstate.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

static void port_say(const co_lx_port_t *p, co_lx_level_t level, const char *msg)
{
    if (p->log != NULL) {
        p->log(p->log_ctx, level, msg);
    }
}

static int port_send(void *ctx, const co_frame_t *f)
{
    co_lx_port_t *p = (co_lx_port_t *)ctx;
    int r;

    if (p->off_bus) {
        return 1; /* held back by the core until the controller is back */
    }
    r = co_lx_can_send(p->fd, f);
    if (r == 0) {
        if (p->tx_blocked) {
            p->tx_blocked = false;
            port_say(p, CO_LX_DEBUG, "TX path accepts frames again");
        }
        return 0;
    }
    if ((r > 0) || (errno == ENETDOWN)) {
        /* full (or the interface is down for a moment): the core holds the
         * frame back and retries it from co_node_process */
        if (!p->tx_blocked) {
            p->tx_blocked = true;
            port_say(p, CO_LX_DEBUG, "TX path full: frames held back");
        }
        p->tx_refused++;
        return 1;
    }
    if (p->tx_failed == 0U) {
        char msg[96];
        (void)snprintf(msg, sizeof msg, "send on %s failed: %s (frame dropped)", p->iface,
                       strerror(errno));
        port_say(p, CO_LX_WARN, msg);
    }
    p->tx_failed++;
    return 0;
}

static int port_nv_read(void *ctx, uint32_t addr, uint8_t *buf, uint32_t len)
{
    const co_lx_port_t *p = (const co_lx_port_t *)ctx;
    return co_lx_nv_read(p->nv, addr, buf, len);
}

static int port_nv_write(void *ctx, uint32_t addr, const uint8_t *buf, uint32_t len)
{
    const co_lx_port_t *p = (const co_lx_port_t *)ctx;
    return co_lx_nv_write(p->nv, addr, buf, len);
}

/* The file is written once per save, in the background (nvfile.h). */
static int port_nv_poll(void *ctx)
{
    const co_lx_port_t *p = (const co_lx_port_t *)ctx;
    int r = co_lx_nv_poll(p->nv);

    if ((r != 0) && (r != CO_NV_BUSY)) {
        char msg[160];
        (void)snprintf(msg, sizeof msg, "%s: writing the parameter file failed", p->nv->path);
        port_say(p, CO_LX_ERROR, msg);
    }
    return r;
}

/* LSS switched the bit timing (CiA 305 table index): a SocketCAN
 * interface's rate is set outside the daemon (ip link), so it is only
 * reported. */
static int port_bit_timing(void *ctx, uint8_t index)
{
    static const uint16_t kbit[10] = {1000U, 800U, 500U, 250U, 125U, 0U, 50U, 20U, 10U, 0U};
    co_lx_port_t *p = (co_lx_port_t *)ctx;
    char msg[128];

    p->bit_timing = index;
    if ((index < 10U) && (kbit[index] != 0U)) {
        (void)snprintf(msg, sizeof msg, "LSS bit timing %u (%u kbit/s) on %s", (unsigned)index,
                       (unsigned)kbit[index], p->iface);
    } else {
        (void)snprintf(msg, sizeof msg, "LSS bit timing %u (automatic) on %s", (unsigned)index,
                       p->iface);
    }
    port_say(p, CO_LX_INFO, msg);
    return 0;
}

static const co_hal_ops_t ops_nv = {.send = port_send,
                                    .nv_read = port_nv_read,
                                    .nv_write = port_nv_write,
                                    .nv_poll = port_nv_poll,
                                    .bit_timing = port_bit_timing};
static const co_hal_ops_t ops_plain = {.send = port_send, .bit_timing = port_bit_timing};

int co_lx_port_open(co_lx_port_t *p, const char *iface, co_lx_nv_t *nv, co_lx_can_fail_t *why)
{
    co_lx_log_fn log = p->log;
    void *log_ctx = p->log_ctx;

    (void)memset(p, 0, sizeof *p);
    p->log = log;
    p->log_ctx = log_ctx;
    p->bit_timing = 0xFFU;
    p->nv = nv;
    (void)snprintf(p->iface, sizeof p->iface, "%s", iface);
    p->fd = co_lx_can_open(iface, why);
    return (p->fd < 0) ? -1 : 0;
}

co_hal_t co_lx_port_hal(co_lx_port_t *p)
{
    co_hal_t h;

    h.ops = (p->nv != NULL) ? &ops_nv : &ops_plain;
    h.ctx = p;
    return h;
}

void co_lx_port_attach(co_lx_port_t *p, co_node_t *node)
{
    p->node = node;
}

static void apply(co_lx_port_t *p, const co_lx_emcy_action_t *a, unsigned n, uint32_t now_us)
{
    for (unsigned i = 0U; i < n; i++) {
        char msg[96];
        (void)snprintf(msg, sizeof msg, "%s: CAN controller %s: EMCY 0x%04X %s", p->iface,
                       (a[i].code == CO_LX_EMCY_BUSOFF) ? "bus-off"
                       : (a[i].code == CO_LX_EMCY_PASSIVE) ? "error passive" : "overrun",
                       (unsigned)a[i].code, a[i].raise ? "raised" : "cleared");
        port_say(p, a[i].raise ? CO_LX_WARN : CO_LX_INFO, msg);
    }
    /* the CiA 301 policy (EMCY codes, 0x1029 on bus-off) is the core's */
    if ((p->node != NULL) && (n > 0U)) {
        co_node_can_state(p->node,
                          p->err.busoff ? CO_CAN_BUS_OFF
                          : p->err.passive ? CO_CAN_ERROR_PASSIVE : CO_CAN_ERROR_ACTIVE,
                          now_us);
        co_node_can_overrun(p->node, p->err.overrun);
    }
}

int co_lx_port_rx(co_lx_port_t *p, uint32_t now_us)
{
    struct can_frame cf;
    co_lx_emcy_action_t act[CO_LX_CANERR_ACTIONS_MAX];
    uint32_t dropped = p->dropped;
    unsigned n;
    co_frame_t f;
    int r = co_lx_can_recv(p->fd, &cf, NULL, &dropped);

    if (r <= 0) {
        return r;
    }
    if (p->off_bus) {
        p->dropped = dropped;
        p->rx_ignored++;
        return 1; /* off the bus: the controller sees nothing */
    }
    if ((cf.can_id & CAN_ERR_FLAG) != 0U) {
        n = co_lx_canerr_frame(&p->err, cf.can_id, cf.data, act);
        apply(p, act, n, now_us);
        return 1;
    }
    n = co_lx_canerr_rx(&p->err, dropped - p->dropped, act);
    p->dropped = dropped;
    apply(p, act, n, now_us);
    p->rx_frames++;
    if (p->node != NULL) {
        co_lx_frame_from_can(&cf, &f);
        co_node_rx(p->node, &f, now_us);
    }
    return 1;
}

void co_lx_port_off_bus(co_lx_port_t *p, uint32_t ms, uint32_t now_us)
{
    bool was = p->off_bus;
    char msg[96];

    if (ms < 1U) {
        ms = 1U;
    } else if (ms > 3600000U) {
        ms = 3600000U;
    } else {
        /* in range */
    }
    p->off_bus = true;
    p->back_at = now_us + (ms * 1000U);
    (void)snprintf(msg, sizeof msg, "%s: off the bus for %lu ms (as at bus-off)", p->iface,
                   (unsigned long)ms);
    port_say(p, CO_LX_WARN, msg);
    if (!was && (p->node != NULL)) {
        co_node_can_state(p->node, CO_CAN_BUS_OFF, now_us);
    }
}

uint32_t co_lx_port_process(co_lx_port_t *p, uint32_t now_us)
{
    if (!p->off_bus) {
        return CO_NO_DEADLINE;
    }
    if ((int32_t)(now_us - p->back_at) < 0) {
        return p->back_at;
    }
    {
        char msg[96];
        (void)snprintf(msg, sizeof msg, "%s: back on the bus (%lu frames not seen)", p->iface,
                       (unsigned long)p->rx_ignored);
        port_say(p, CO_LX_INFO, msg);
    }
    p->rx_ignored = 0U;
    if (p->node != NULL) {
        /* error-active again: the EMCY 0x0000 joins the held frames behind
         * 0x8140 (same CAN-ID, in order), then all leave, lowest CAN-ID first */
        co_node_can_state(p->node, CO_CAN_ERROR_ACTIVE, now_us);
        p->off_bus = false;
        co_node_tx_ready(p->node, now_us);
    }
    p->off_bus = false;
    return CO_NO_DEADLINE;
}

void co_lx_port_close(co_lx_port_t *p)
{
    if (p->fd >= 0) {
        (void)close(p->fd);
        p->fd = -1;
    }
}
