#include "tseed.h"

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "co/co_endian.h"

void tseed_assert_range_at(int64_t v, int64_t lo, int64_t hi, const char *file, int line)
{
    if ((v < lo) || (v > hi)) {
        print_error("%s:%d: %lld is not within %lld..%lld\n", file, line, (long long)v,
                    (long long)lo, (long long)hi);
        _fail(file, line);
    }
}

void tseed_init(tseed_t *f)
{
    memset(f, 0, sizeof *f);
    tb_init(&f->bus);
}

void tseed_start(tseed_t *f, unsigned k, const co_device_t *dev, co_node_config_t *cfg,
                 co_node_t *node, uint8_t id, const co402_sim_config_t *sim)
{
    tseed_node_t *n = &f->n[k];
    co402_plant_t plant;
    const void *plants[1];

    assert_true(k < TSEED_NODES);
    if (sim != NULL) {
        n->simcfg = *sim;
    } else {
        co402_params_sim_config(co402_device_params(dev), &n->simcfg);
    }
    co402_sim_init(&n->sim, &n->simcfg, f->bus.now);
    plant = co402_sim_plant(&n->sim);
    plants[0] = &plant;
    assert_int_equal(co402_device_axes(dev), 1U);
    assert_int_equal(co_device_init(&n->run, dev, n->mem, sizeof n->mem, plants, NULL, f->bus.now),
                     CO_OK);
    cfg->hal = tb_hal(&f->bus, (uint8_t)k);
    cfg->node_id = id;
    cfg->cb = co_device_callbacks(&n->run);
    n->node = node;
    tb_attach(&f->bus, (uint8_t)k, node);
    assert_int_equal(co_node_init(node, cfg, f->bus.now), CO_RESULT_OK);
    assert_int_equal(co_device_attach(&n->run, node, f->bus.now), CO_OK);
    if (f->count <= k) {
        f->count = k + 1U;
    }
}

void tseed_run(tseed_t *f, uint32_t us)
{
    uint32_t end = f->bus.now + us;

    while ((int32_t)(end - f->bus.now) > 0) {
        uint32_t step = end - f->bus.now;
        f->bus.now += (step > 1000U) ? 1000U : step;
        for (unsigned k = 0U; k < f->count; k++) {
            if (f->n[k].node != NULL) {
                (void)co_node_process(f->n[k].node, f->bus.now);
                (void)co_device_process(&f->n[k].run, f->bus.now);
            }
        }
    }
}

uint32_t tseed_run_until(tseed_t *f, unsigned k, uint16_t mask, uint16_t value, uint32_t max_us)
{
    uint32_t t = 0U;

    while ((tseed_sw(f, k) & mask) != value) {
        if (t >= max_us) {
            print_error("statusword 0x%04X: (& 0x%04X) != 0x%04X after %u us\n", tseed_sw(f, k),
                        mask, value, (unsigned)t);
            fail();
        }
        tseed_run(f, 1000U);
        t += 1000U;
    }
    return t;
}

int64_t tseed_get(tseed_t *f, unsigned k, uint16_t index, uint8_t sub)
{
    co_node_t *node = f->n[k].node;
    uint8_t b[8] = {0};
    uint32_t len = 0U;
    const co_od_entry_t *e = co_od_find(node->dev->od, node->dev->od_count, index);
    co_od_sub_t sub_buf;
    const co_od_sub_t *s = (e != NULL) ? co_od_find_sub(node->dev, e, sub, &sub_buf) : NULL;

    assert_non_null(s);
    assert_int_equal(co_od_read(node, index, sub, b, sizeof b, &len), CO_OK);
    switch (s->type) {
    case CO_INTEGER8:
        return (int8_t)b[0];
    case CO_INTEGER16:
        return (int16_t)co_get_u16(b);
    case CO_INTEGER32:
        return (int32_t)co_get_u32(b);
    case CO_UNSIGNED16:
        return co_get_u16(b);
    case CO_UNSIGNED32:
        return co_get_u32(b);
    default:
        return b[0];
    }
}

void tseed_set(tseed_t *f, unsigned k, uint16_t index, uint8_t sub, int64_t value, uint8_t size)
{
    uint8_t b[4];
    uint64_t u = (uint64_t)value;

    for (uint8_t i = 0U; i < size; i++) {
        b[i] = (uint8_t)(u >> (8U * i));
    }
    assert_int_equal(co_od_write(f->n[k].node, index, sub, b, size, true), CO_OK);
}

uint16_t tseed_sw(tseed_t *f, unsigned k)
{
    return (uint16_t)tseed_get(f, k, 0x6041, 0);
}

co402_axis_t *tseed_axis(tseed_t *f, unsigned k)
{
    return co402_device_axis(&f->n[k].run, 0U);
}

void tseed_expectf_at(tb_bus_t *bus, const char *file, int line, const char *fmt, ...)
{
    char text[128];
    va_list ap;

    va_start(ap, fmt);
    (void)vsnprintf(text, sizeof text, fmt, ap);
    va_end(ap);
    tb_expect_at(bus, text, file, line);
}

void tseed_sendf(tb_bus_t *bus, const char *fmt, ...)
{
    char text[128];
    va_list ap;

    va_start(ap, fmt);
    (void)vsnprintf(text, sizeof text, fmt, ap);
    va_end(ap);
    tb_send(bus, text);
}

const co_frame_t *tseed_frame_at(tb_bus_t *bus, uint16_t id, uint8_t dlc, const char *file,
                                 int line)
{
    const co_frame_t *fr = tb_next(bus);

    if (fr == NULL) {
        print_error("%s:%d: expected a frame %03X (%u bytes), got none\n", file, line, id, dlc);
        _fail(file, line);
    }
    if ((fr->id != id) || (fr->dlc != dlc)) {
        print_error("%s:%d: expected a frame %03X (%u bytes), got %03X (%u bytes)\n", file, line,
                    id, dlc, (unsigned)fr->id, (unsigned)fr->dlc);
        _fail(file, line);
    }
    return fr;
}

int32_t tseed_i32(const co_frame_t *f, unsigned at)
{
    return (int32_t)co_get_u32(&f->data[at]);
}

int16_t tseed_i16(const co_frame_t *f, unsigned at)
{
    return (int16_t)co_get_u16(&f->data[at]);
}
