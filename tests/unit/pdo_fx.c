#include "pdo_fx.h"

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "co/co_endian.h"

static co_err_t hook_read(void *ctx, co_od_io_t *io)
{
    pfx_t *f = (pfx_t *)ctx;
    f->hook_reads++;
    memcpy(io->value, &f->hook_value, sizeof f->hook_value);
    return CO_OK;
}

static co_err_t hook_write(void *ctx, co_od_io_t *io)
{
    pfx_t *f = (pfx_t *)ctx;
    f->hook_writes++;
    if (f->hook_veto == CO_OK) {
        f->hook_written = co_get_u32(io->buf);
    }
    return f->hook_veto;
}

void pfx_start(pfx_t *f, uint8_t id, const co_settings_t *set)
{
    co_node_config_t cfg;
    co_od_hook_t h = {hook_read, hook_write, NULL};
    char boot[16];

    memset(f, 0, sizeof *f);
    tb_init(&f->bus);
    f->dev = pdo_test_dev;
    if (set != NULL) {
        f->dev.set = *set;
    } else {
        (void)memset(&f->dev.set, 0, sizeof f->dev.set); /* CiA 301 */
    }
    pdo_test_config(&f->n, &cfg);
    cfg.dev = &f->dev;
    cfg.hal = tb_hal(&f->bus, 0);
    cfg.node_id = id;
    assert_int_equal(co_node_init(&f->n.node, &cfg, f->bus.now), CO_RESULT_OK);
    tb_attach(&f->bus, 0, &f->n.node);
    h.ctx = f;
    assert_int_equal(co_od_bind_hook(&f->n.node, 0x2020U, &h), CO_RESULT_OK);
    snprintf(boot, sizeof boot, "%03X 00", 0x700U + id);
    tb_expect(&f->bus, boot);
    tb_expect_none(&f->bus);
}

void pfx_set(pfx_t *f, uint16_t index, uint8_t sub, uint32_t value, uint32_t len)
{
    uint8_t b[4];
    co_put_u32(b, value);
    assert_int_equal(co_od_write(&f->n.node, index, sub, b, len, true), CO_OK);
}

uint32_t pfx_get(pfx_t *f, uint16_t index, uint8_t sub)
{
    uint8_t b[8] = {0};
    uint32_t len = 0;
    assert_int_equal(co_od_read(&f->n.node, index, sub, b, sizeof b, &len), CO_OK);
    return co_get_u32(b);
}
