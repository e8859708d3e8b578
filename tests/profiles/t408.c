#include "t408.h"

#include <inttypes.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "co/co_endian.h"

static const int8_t modes[] = {CO408_MODE_VPOC, CO408_MODE_VPRC_CL};

void t408_assert_range_at(int64_t v, int64_t lo, int64_t hi, const char *file, int line)
{
    if ((v < lo) || (v > hi)) {
        print_error("%s:%d: %lld is not within %lld..%lld\n", file, line, (long long)v,
                    (long long)lo, (long long)hi);
        _fail(file, line);
    }
}

void t408_start(t408_t *f, uint8_t id)
{
    co_node_config_t cfg;
    co408_config_t vc;
    co408_sim_config_t sc;
    char boot[16];

    memset(f, 0, sizeof *f);
    tb_init(&f->bus);
    co408_sim_defaults(&sc);
    co408_sim_init(&f->sim, &sc, f->bus.now);
    memset(&vc, 0, sizeof vc);
    vc.plant = co408_sim_plant(&f->sim);
    vc.modes = modes;
    vc.n_modes = (uint8_t)sizeof modes;
    co408_init(&f->v, &vc);
    co_profile_host_init(&f->host, f->slots, 2U, NULL);
    assert_int_equal(co_profile_add(&f->host, &co408_profile_ops, &f->v), CO_OK);
    cia408_config(&f->n, &cfg);
    cfg.hal = tb_hal(&f->bus, 0);
    cfg.node_id = id;
    cfg.cb = co_profile_host_callbacks(&f->host);
    tb_attach(&f->bus, 0, &f->n.node);
    assert_int_equal(co_node_init(&f->n.node, &cfg, f->bus.now), CO_RESULT_OK);
    assert_int_equal(co_profile_host_attach(&f->host, &f->n.node, f->bus.now), CO_OK);
    snprintf(boot, sizeof boot, "%03X 00", 0x700U + id);
    tb_expect(&f->bus, boot);
}

void t408_run(t408_t *f, uint32_t us)
{
    uint32_t end = f->bus.now + us;

    while ((int32_t)(end - f->bus.now) > 0) {
        uint32_t step = end - f->bus.now;
        f->bus.now += (step > 1000U) ? 1000U : step;
        (void)co_node_process(&f->n.node, f->bus.now);
        (void)co_profile_host_process(&f->host, f->bus.now);
    }
}

void t408_sdo_write(t408_t *f, uint16_t index, uint8_t sub, int64_t value, uint8_t size,
                    uint32_t abort)
{
    static const uint8_t cmd[5] = {0, 0x2F, 0x2B, 0x27, 0x23};
    char req[64];
    char resp[64];
    uint8_t id = f->n.node.node_id;
    uint64_t u = (uint64_t)value;
    uint8_t b[4] = {0, 0, 0, 0};

    for (uint8_t i = 0U; i < size; i++) {
        b[i] = (uint8_t)(u >> (8U * i));
    }
    snprintf(req, sizeof req, "%03X %02X %02X %02X %02X %02X %02X %02X %02X", 0x600U + id,
             cmd[size], index & 0xFFU, index >> 8, sub, b[0], b[1], b[2], b[3]);
    if (abort == 0U) {
        snprintf(resp, sizeof resp, "%03X 60 %02X %02X %02X 00 00 00 00", 0x580U + id,
                 index & 0xFFU, index >> 8, sub);
    } else {
        snprintf(resp, sizeof resp,
                 "%03X 80 %02X %02X %02X %02" PRIX32 " %02" PRIX32 " %02" PRIX32 " %02" PRIX32,
                 0x580U + id, index & 0xFFU, index >> 8, sub, abort & 0xFFU, (abort >> 8) & 0xFFU,
                 (abort >> 16) & 0xFFU, abort >> 24);
    }
    tb_xfer(&f->bus, req, resp);
}

void t408_sdo_expect(t408_t *f, uint16_t index, uint8_t sub, int64_t value, uint8_t size)
{
    static const uint8_t cmd[5] = {0, 0x4F, 0x4B, 0x47, 0x43};
    char req[64];
    char resp[64];
    uint8_t id = f->n.node.node_id;
    uint64_t u = (uint64_t)value;
    uint8_t b[4] = {0, 0, 0, 0};

    for (uint8_t i = 0U; i < size; i++) {
        b[i] = (uint8_t)(u >> (8U * i));
    }
    snprintf(req, sizeof req, "%03X 40 %02X %02X %02X 00 00 00 00", 0x600U + id, index & 0xFFU,
             index >> 8, sub);
    snprintf(resp, sizeof resp, "%03X %02X %02X %02X %02X %02X %02X %02X %02X", 0x580U + id,
             cmd[size], index & 0xFFU, index >> 8, sub, b[0], b[1], b[2], b[3]);
    tb_xfer(&f->bus, req, resp);
}

void t408_cw(t408_t *f, uint16_t cw)
{
    t408_sdo_write(f, 0x6040, 0, cw, 2, 0);
}

void t408_expect_sw(t408_t *f, uint16_t sw)
{
    t408_sdo_expect(f, 0x6041, 0, sw, 2);
}

int64_t t408_get(t408_t *f, uint16_t index, uint8_t sub)
{
    uint8_t b[8] = {0};
    uint32_t len = 0U;
    const co_od_entry_t *e = co_od_find(f->n.node.dev->od, f->n.node.dev->od_count, index);
    co_od_sub_t sub_buf;
    const co_od_sub_t *s = (e != NULL) ? co_od_find_sub(f->n.node.dev, e, sub, &sub_buf) : NULL;

    assert_non_null(s);
    assert_int_equal(co_od_read(&f->n.node, index, sub, b, sizeof b, &len), CO_OK);
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
