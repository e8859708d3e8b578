#include "test_bus.h"

#include <setjmp.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "test_frames.h"

static int tb_hal_send(void *ctx, const co_frame_t *f)
{
    tb_port_t *p = (tb_port_t *)ctx;
    tb_bus_t *bus = p->bus;

    if ((bus->refuse > 0U) && (bus->refuse_after > 0U)) {
        bus->refuse_after--;
    } else if (bus->refuse > 0U) {
        bus->refuse--;
        bus->refused++;
        return 1;
    }
    assert_true(bus->n_log < TB_LOG_MAX);
    bus->log[bus->n_log] = *f;
    bus->from[bus->n_log] = p->idx;
    bus->n_log++;
    return 0;
}

static uint8_t *nv_of(const tb_port_t *p)
{
    return (p->idx == 0U) ? p->bus->nv : p->bus->nv_port[p->idx - 1U];
}

static int tb_nv_read(void *ctx, uint32_t addr, uint8_t *buf, uint32_t len)
{
    tb_bus_t *bus = ((tb_port_t *)ctx)->bus;
    const uint8_t *nv = nv_of((tb_port_t *)ctx);
    if ((addr > TB_NV_SIZE) || (len > TB_NV_SIZE - addr) || bus->nv_fail_read) {
        return -1;
    }
    memcpy(buf, &nv[addr], len);
    return 0;
}

static int tb_nv_write(void *ctx, uint32_t addr, const uint8_t *buf, uint32_t len)
{
    tb_bus_t *bus = ((tb_port_t *)ctx)->bus;
    uint8_t *nv = nv_of((tb_port_t *)ctx);
    if ((addr > TB_NV_SIZE) || (len > TB_NV_SIZE - addr) || bus->nv_fail_write) {
        return -1;
    }
    /* byte by byte, in address order, so a power cut can fall between any two */
    for (uint32_t i = 0U; i < len; i++) {
        if (bus->nv_cut) {
            return -1;
        }
        if (bus->nv_cut_armed && (bus->nv_budget == 0U)) {
            bus->nv_cut = true;
            if (bus->nv_tear) {
                nv[addr + i] = (uint8_t)((buf[i] & 0xF0U) | (nv[addr + i] & 0x0FU));
            }
            return -1;
        }
        if (bus->nv_cut_armed) {
            bus->nv_budget--;
        }
        nv[addr + i] = buf[i];
        bus->nv_written++;
    }
    return 0;
}

static int tb_bit_timing(void *ctx, uint8_t index)
{
    tb_port_t *p = (tb_port_t *)ctx;

    p->bus->bit_timing[p->idx] = index;
    p->bus->bit_timing_calls++;
    p->bus->bit_timing_at = p->bus->now;
    return 0;
}

static int tb_nv_write_flash(void *ctx, uint32_t addr, const uint8_t *buf, uint32_t len)
{
    tb_bus_t *bus = ((tb_port_t *)ctx)->bus;

    const uint8_t *nv = nv_of((tb_port_t *)ctx);

    for (uint32_t i = 0U; (i < len) && ((addr + i) < TB_NV_SIZE); i++) {
        if (nv[addr + i] != 0xFFU) {
            bus->nv_unerased++;
        }
    }
    bus->nv_busy = bus->nv_busy_each;
    return tb_nv_write(ctx, addr, buf, len);
}

static int tb_nv_erase(void *ctx, uint32_t addr, uint32_t len)
{
    tb_bus_t *bus = ((tb_port_t *)ctx)->bus;

    if (((addr % TB_NV_ERASE_UNIT) != 0U) || ((len % TB_NV_ERASE_UNIT) != 0U) ||
        (addr > TB_NV_SIZE) || (len > TB_NV_SIZE - addr)) {
        return -1;
    }
    bus->nv_erases++;
    bus->nv_erase_addr = addr;
    bus->nv_erase_len = len;
    memset(&nv_of((tb_port_t *)ctx)[addr], 0xFF, len);
    bus->nv_busy = bus->nv_busy_each;
    return 0;
}

static int tb_nv_poll(void *ctx)
{
    tb_bus_t *bus = ((tb_port_t *)ctx)->bus;

    bus->nv_polls++;
    if (bus->nv_busy > 0U) {
        bus->nv_busy--;
        return CO_NV_BUSY;
    }
    return bus->nv_fail_poll ? -1 : 0;
}

const co_hal_ops_t tb_hal_ops_async = {.send = tb_hal_send,
                                       .nv_read = tb_nv_read,
                                       .nv_write = tb_nv_write_flash,
                                       .nv_poll = tb_nv_poll,
                                       .nv_erase = tb_nv_erase,
                                       .nv_erase_unit = TB_NV_ERASE_UNIT,
                                       .bit_timing = tb_bit_timing};

const co_hal_ops_t tb_hal_ops = {.send = tb_hal_send,
                                 .nv_read = tb_nv_read,
                                 .nv_write = tb_nv_write,
                                 .bit_timing = tb_bit_timing};
const co_hal_ops_t tb_hal_ops_no_nv = {.send = tb_hal_send, .bit_timing = tb_bit_timing};

void tb_nv_cut(tb_bus_t *bus, uint32_t n, bool tear)
{
    bus->nv_budget = n;
    bus->nv_cut_armed = true;
    bus->nv_cut = false;
    bus->nv_tear = tear;
}

void tb_nv_power_on(tb_bus_t *bus)
{
    bus->nv_cut_armed = false;
    bus->nv_cut = false;
}

void tb_init(tb_bus_t *bus)
{
    memset(bus, 0, sizeof *bus);
    memset(bus->nv, 0xFF, sizeof bus->nv);
    memset(bus->nv_port, 0xFF, sizeof bus->nv_port);
    memset(bus->bit_timing, 0xFF, sizeof bus->bit_timing);
    bus->now = 1000U;
}

co_hal_t tb_hal(tb_bus_t *bus, uint8_t idx)
{
    co_hal_t h;
    bus->ports[idx].bus = bus;
    bus->ports[idx].idx = idx;
    h.ops = bus->nv_async ? &tb_hal_ops_async : &tb_hal_ops;
    h.ctx = &bus->ports[idx];
    return h;
}

void tb_attach(tb_bus_t *bus, uint8_t idx, co_node_t *node)
{
    bus->nodes[idx] = node;
    if (bus->n_nodes <= idx) {
        bus->n_nodes = (size_t)idx + 1U;
    }
}

void tb_send_frame(tb_bus_t *bus, const co_frame_t *f)
{
    for (size_t i = 0; i < bus->n_nodes; i++) {
        if (bus->nodes[i] != NULL) {
            co_node_rx(bus->nodes[i], f, bus->now);
        }
    }
}

void tb_send(tb_bus_t *bus, const char *text)
{
    co_frame_t f = tf_parse(text);
    tb_send_frame(bus, &f);
}

void tb_pump(tb_bus_t *bus)
{
    while (bus->deliver_pos < bus->n_log) {
        size_t i = bus->deliver_pos++;
        for (size_t k = 0; k < bus->n_nodes; k++) {
            if ((bus->nodes[k] != NULL) && (k != bus->from[i])) {
                co_node_rx(bus->nodes[k], &bus->log[i], bus->now);
            }
        }
    }
}

void tb_advance(tb_bus_t *bus, uint32_t us)
{
    uint32_t end = bus->now + us;

    for (;;) {
        uint32_t next = end;
        for (size_t i = 0; i < bus->n_nodes; i++) {
            if (bus->nodes[i] != NULL) {
                uint32_t d = co_node_process(bus->nodes[i], bus->now);
                if ((d != CO_NO_DEADLINE) && ((int32_t)(d - bus->now) > 0) &&
                    ((int32_t)(d - next) < 0)) {
                    next = d;
                }
            }
        }
        if (bus->now == end) {
            break;
        }
        bus->now = next;
    }
}

const co_frame_t *tb_next(tb_bus_t *bus)
{
    if (bus->read_pos >= bus->n_log) {
        return NULL;
    }
    return &bus->log[bus->read_pos++];
}

void tb_expect_at(tb_bus_t *bus, const char *text, const char *file, int line)
{
    const co_frame_t *f = tb_next(bus);
    if (f == NULL) {
        print_error("%s:%d: expected frame %s, but nothing was sent\n", file, line, text);
        _fail(file, line);
        return;
    }
    tf_assert_frame(f, text, file, line);
}

void tb_expect_none_at(tb_bus_t *bus, const char *file, int line)
{
    const co_frame_t *f = tb_next(bus);
    if (f != NULL) {
        char txt[64];
        tf_format(f, txt, sizeof txt);
        print_error("%s:%d: expected no frame, got %s\n", file, line, txt);
        _fail(file, line);
    }
}

void tb_flush(tb_bus_t *bus)
{
    bus->read_pos = bus->n_log;
}
