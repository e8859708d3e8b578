#include "t402.h"

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "co/co_endian.h"

void t402_assert_range_at(int64_t v, int64_t lo, int64_t hi, const char *file, int line)
{
    if ((v < lo) || (v > hi)) {
        print_error("%s:%d: %lld is not within %lld..%lld\n", file, line, (long long)v,
                    (long long)lo, (long long)hi);
        _fail(file, line);
    }
}

void t402_sim_defaults(co402_sim_config_t *c)
{
    co402_sim_defaults(c);
}

void t402_start(t402_t *f, uint8_t id, uint32_t options, const co402_sim_config_t *sim)
{
    co_node_config_t cfg;
    co402_config_t ac;

    memset(f, 0, sizeof *f);
    tb_init(&f->bus);
    if (sim != NULL) {
        f->simcfg = *sim;
    } else {
        t402_sim_defaults(&f->simcfg);
    }
    co402_sim_init(&f->sim, &f->simcfg, f->bus.now);
    memset(&ac, 0, sizeof ac);
    ac.options = options;
    ac.plant = co402_sim_plant(&f->sim);
    co402_init(&f->ax, &ac);
    co_profile_host_init(&f->host, f->slots, 2U, NULL);
    assert_int_equal(co_profile_add(&f->host, &co402_profile_ops, &f->ax), CO_OK);
    cia402_config(&f->n, &cfg);
    cfg.hal = tb_hal(&f->bus, 0);
    cfg.node_id = id;
    cfg.cb = co_profile_host_callbacks(&f->host);
    tb_attach(&f->bus, 0, &f->n.node);
    assert_int_equal(co_node_init(&f->n.node, &cfg, f->bus.now), CO_RESULT_OK);
    assert_int_equal(co_profile_host_attach(&f->host, &f->n.node, f->bus.now), CO_OK);
    {
        char boot[16];
        snprintf(boot, sizeof boot, "%03X 00", 0x700U + id);
        tb_expect(&f->bus, boot);
    }
}

void t402_run(t402_t *f, uint32_t us)
{
    uint32_t end = f->bus.now + us;

    while ((int32_t)(end - f->bus.now) > 0) {
        uint32_t step = end - f->bus.now;
        f->bus.now += (step > 1000U) ? 1000U : step;
        (void)co_node_process(&f->n.node, f->bus.now);
        (void)co_profile_host_process(&f->host, f->bus.now);
    }
}

uint32_t t402_run_until(t402_t *f, uint16_t mask, uint16_t value, uint32_t max_us)
{
    uint32_t t = 0U;

    while ((t402_sw(f) & mask) != value) {
        if (t >= max_us) {
            print_error("statusword 0x%04X: (& 0x%04X) != 0x%04X after %u us\n", t402_sw(f), mask,
                        value, (unsigned)t);
            fail();
        }
        t402_run(f, 1000U);
        t += 1000U;
    }
    return t;
}

void t402_set(t402_t *f, uint16_t index, uint8_t sub, int64_t value, uint8_t size)
{
    uint8_t b[4];
    uint64_t u = (uint64_t)value;
    co_err_t err;

    for (uint8_t i = 0U; i < size; i++) {
        b[i] = (uint8_t)(u >> (8U * i));
    }
    err = co_od_write(&f->n.node, index, sub, b, size, false);
    if (err != CO_OK) {
        print_error("write 0x%04X:%u = %lld: 0x%08X\n", index, sub, (long long)value, (unsigned)err);
        fail();
    }
}

int64_t t402_get(t402_t *f, uint16_t index, uint8_t sub)
{
    uint8_t b[8] = {0};
    uint32_t len = 0U;
    const co_od_entry_t *e = co_od_find(f->n.node.dev->od, f->n.node.dev->od_count, index);
    co_od_sub_t sub_buf;
    const co_od_sub_t *s = (e != NULL) ? co_od_find_sub(f->n.node.dev, e, sub, &sub_buf) : NULL;
    int64_t v;

    assert_non_null(s);
    assert_int_equal(co_od_read(&f->n.node, index, sub, b, sizeof b, &len), CO_OK);
    switch (s->type) {
    case CO_INTEGER8:
        v = (int8_t)b[0];
        break;
    case CO_INTEGER16:
        v = (int16_t)co_get_u16(b);
        break;
    case CO_INTEGER32:
        v = (int32_t)co_get_u32(b);
        break;
    case CO_UNSIGNED16:
        v = co_get_u16(b);
        break;
    case CO_UNSIGNED32:
        v = co_get_u32(b);
        break;
    default:
        v = b[0];
        break;
    }
    return v;
}

void t402_cw(t402_t *f, uint16_t cw)
{
    t402_set(f, 0x6040, 0, cw, 2);
}

uint16_t t402_sw(t402_t *f)
{
    return (uint16_t)t402_get(f, 0x6041, 0);
}

void t402_enable(t402_t *f)
{
    char req[64];
    char resp[64];
    uint8_t id = f->n.node.node_id;
    static const uint16_t cws[] = {0x0006, 0x0007, 0x000F};

    for (unsigned i = 0; i < 3U; i++) {
        snprintf(req, sizeof req, "%03X 2B 40 60 00 %02X 00 00 00", 0x600U + id, cws[i]);
        snprintf(resp, sizeof resp, "%03X 60 40 60 00 00 00 00 00", 0x580U + id);
        tb_xfer(&f->bus, req, resp);
    }
    assert_int_equal(co402_state(&f->ax), CO402_OPERATION_ENABLED);
}
