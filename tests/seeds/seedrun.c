#include "seedrun.h"

#include <inttypes.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "co/co_endian.h"
#include "test_frames.h"

void sr_start(seedrun_t *s, const co_device_t *d, co_node_config_t *cfg, co_node_t *node,
              const co402_sim_config_t *sim, uint8_t id)
{
    co402_plant_t plants[SR_AXES_MAX];
    const void *pl[SR_AXES_MAX];
    uint8_t axes = co402_device_axes(d);
    char boot[16];

    memset(s, 0, sizeof *s);
    tb_init(&s->bus);
    s->id = id;
    s->node = node;
    assert_true(axes <= SR_AXES_MAX);
    for (uint8_t i = 0U; i < axes; i++) {
        co402_sim_config_t sc;
        if (sim != NULL) {
            sc = *sim;
        } else {
            co402_params_sim_config(co402_device_params(d), &sc);
        }
        co402_sim_init(&s->sim[i], &sc, s->bus.now);
        plants[i] = co402_sim_plant(&s->sim[i]);
        pl[i] = &plants[i];
    }
    assert_true(co_device_mem_size(d, axes == 0U) <= sizeof s->mem);
    assert_int_equal(co_device_init(&s->run, d, s->mem, sizeof s->mem,
                                    (axes != 0U) ? pl : NULL, NULL, s->bus.now),
                     CO_OK);
    cfg->hal = tb_hal(&s->bus, 0);
    cfg->node_id = id;
    cfg->cb = co_device_callbacks(&s->run);
    /* the node memory must be attached to the bus before init sends boot-up */
    tb_attach(&s->bus, 0, node);
    assert_int_equal(co_node_init(node, cfg, s->bus.now), CO_RESULT_OK);
    assert_int_equal(co_device_attach(&s->run, node, s->bus.now), CO_OK);
    if (cfg->dev->set.lss.node_id == CO_LSS_ID_ONLY) {
        /* the node-ID only through LSS (FAULHABER quick start, digest 1.5):
         * unconfigured and silent; switch global, configure node-ID, back to
         * waiting: the node initialises at once */
        char conf[40];
        tb_expect_none(&s->bus);
        tb_send(&s->bus, "7E5 04 01 00 00 00 00 00 00");
        tb_expect_none(&s->bus);
        snprintf(conf, sizeof conf, "7E5 11 %02X 00 00 00 00 00 00", (unsigned)id);
        tb_send(&s->bus, conf);
        tb_expect(&s->bus, "7E4 11 00 00 00 00 00 00 00");
        tb_send(&s->bus, "7E5 04 00 00 00 00 00 00 00");
    }
    snprintf(boot, sizeof boot, "%03X 00", 0x700U + id);
    tb_expect(&s->bus, boot);
}

void sr_poll(seedrun_t *s)
{
    /* the axes and the plug-in first: what their tick changed goes out now */
    (void)co_device_process(&s->run, s->bus.now);
    (void)co_node_process(s->node, s->bus.now);
}

void sr_run(seedrun_t *s, uint32_t ms)
{
    for (uint32_t i = 0; i < ms; i++) {
        if (s->bus.read_pos == s->bus.n_log) {
            /* everything logged was read (one node, nothing to pump): start
             * the log afresh, so long runs fit */
            s->bus.n_log = 0;
            s->bus.read_pos = 0;
            s->bus.deliver_pos = 0;
        }
        s->bus.now += 1000U;
        sr_poll(s);
    }
}

uint32_t sr_run_until_frame(seedrun_t *s, uint32_t max_ms)
{
    uint32_t t = 0;

    while (s->bus.read_pos >= s->bus.n_log) {
        if (t >= max_ms) {
            print_error("no frame within %u ms\n", (unsigned)max_ms);
            fail();
        }
        sr_run(s, 1);
        t++;
    }
    return t;
}

void sr_sdo(seedrun_t *s, const char *req, const char *resp)
{
    char rq[64];
    char rs[64];
    int nq = snprintf(rq, sizeof rq, "%03X %s", 0x600U + s->id, req);
    int ns = snprintf(rs, sizeof rs, "%03X %s", 0x580U + s->id, resp);

    /* a frame text longer than the buffer is a mistake in the test */
    assert_true((nq > 0) && ((size_t)nq < sizeof rq));
    assert_true((ns > 0) && ((size_t)ns < sizeof rs));
    tb_send(&s->bus, rq);
    tb_expect(&s->bus, rs);
    tb_expect_none(&s->bus);
}

void sr_sdo_write(seedrun_t *s, uint16_t index, uint8_t sub, uint32_t value, uint8_t size)
{
    static const uint8_t cmd[5] = {0, 0x2F, 0x2B, 0x27, 0x23};
    char rq[64];
    char rs[64];

    snprintf(rq, sizeof rq,
             "%02X %02X %02X %02X %02" PRIX32 " %02" PRIX32 " %02" PRIX32 " %02" PRIX32,
             cmd[size], index & 0xFFU, index >> 8, sub, value & 0xFFU, (value >> 8) & 0xFFU,
             (value >> 16) & 0xFFU, value >> 24);
    snprintf(rs, sizeof rs, "60 %02X %02X %02X 00 00 00 00", index & 0xFFU, index >> 8, sub);
    sr_sdo(s, rq, rs);
}

uint32_t sr_sdo_read(seedrun_t *s, uint16_t index, uint8_t sub)
{
    char rq[64];
    const co_frame_t *f;

    snprintf(rq, sizeof rq, "%03X 40 %02X %02X %02X 00 00 00 00", 0x600U + s->id, index & 0xFFU,
             index >> 8, sub);
    tb_send(&s->bus, rq);
    f = tb_next(&s->bus);
    assert_non_null(f);
    assert_int_equal(f->id, 0x580U + s->id);
    assert_int_equal(f->data[0] & 0xF3U, 0x43U); /* expedited, size indicated */
    tb_expect_none(&s->bus);
    return co_get_u32(&f->data[4]);
}

void sr_expect_at(seedrun_t *s, const char *text, const char *file, int line)
{
    char buf[64];

    if (text[0] == '+') {
        unsigned base = 0;
        int n = 0;
        sscanf(text + 1, "%x%n", &base, &n);
        snprintf(buf, sizeof buf, "%03X%s", base + s->id, text + 1 + n);
        tb_expect_at(&s->bus, buf, file, line);
    } else {
        tb_expect_at(&s->bus, text, file, line);
    }
}

int64_t sr_get(seedrun_t *s, uint16_t index, uint8_t sub)
{
    uint8_t b[8] = {0};
    uint32_t len = 0U;
    const co_dev_t *dev = s->node->dev;
    const co_od_entry_t *e = co_od_find(dev->od, dev->od_count, index);
    co_od_sub_t sub_buf;
    const co_od_sub_t *d = (e != NULL) ? co_od_find_sub(dev, e, sub, &sub_buf) : NULL;

    assert_non_null(d);
    assert_int_equal(co_od_read(s->node, index, sub, b, sizeof b, &len), CO_OK);
    switch (d->type) {
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

void sr_set(seedrun_t *s, uint16_t index, uint8_t sub, int64_t value, uint8_t size)
{
    uint8_t b[4];
    uint64_t u = (uint64_t)value;

    for (uint8_t i = 0U; i < size; i++) {
        b[i] = (uint8_t)(u >> (8U * i));
    }
    assert_int_equal(co_od_write(s->node, index, sub, b, size, true), CO_OK);
}

void sr_assert_range_at(int64_t v, int64_t lo, int64_t hi, const char *file, int line)
{
    if ((v < lo) || (v > hi)) {
        print_error("%s:%d: %lld is not within %lld..%lld\n", file, line, (long long)v,
                    (long long)lo, (long long)hi);
        _fail(file, line);
    }
}
