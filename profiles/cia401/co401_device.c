/*
 * CiA 401 as a part of a device and its loopback simulation
 * (co/co401_device.h).
 */
#include "co/co401_device.h"

#include <string.h>

static void sim_read(void *ctx, uint8_t *din, uint8_t n_din, int16_t *ain, uint8_t n_ain)
{
    const co401_sim_t *s = (const co401_sim_t *)ctx;

    (void)memcpy(din, s->din, (n_din <= CO401_DIO_BYTES) ? n_din : CO401_DIO_BYTES);
    for (uint8_t k = 0U; (k < n_ain) && (k < CO401_AIO_MAX); k++) {
        ain[k] = s->ain[k];
    }
}

/* Loopback: an output that changes drives the input of the same number. */
static void sim_write(void *ctx, const uint8_t *dout, uint8_t n_dout, const int16_t *aout,
                      uint8_t n_aout)
{
    co401_sim_t *s = (co401_sim_t *)ctx;

    for (uint8_t b = 0U; (b < n_dout) && (b < CO401_DIO_BYTES); b++) {
        if (dout[b] != s->dout[b]) {
            s->dout[b] = dout[b];
            s->din[b] = dout[b];
        }
    }
    for (uint8_t k = 0U; (k < n_aout) && (k < CO401_AIO_MAX); k++) {
        if (aout[k] != s->aout[k]) {
            s->aout[k] = aout[k];
            s->ain[k] = aout[k];
        }
    }
    s->writes++;
}

static const co401_io_ops_t sim_ops = {
    .read = sim_read,
    .write = sim_write,
};

void co401_sim_init(co401_sim_t *s)
{
    (void)memset(s, 0, sizeof *s);
}

co401_plant_t co401_sim_plant(co401_sim_t *s)
{
    co401_plant_t p;

    p.ops = &sim_ops;
    p.ctx = s;
    return p;
}

static co_err_t part_init(void *inst, const void *config, uint8_t n, const void *plant)
{
    (void)n;
    co401_init((co401_t *)inst, (const co401_config_t *)config, *(const co401_plant_t *)plant);
    return CO_OK;
}

static void part_sim_init(void *sim, const void *config, uint8_t n, uint32_t now_us, void *plant)
{
    (void)config;
    (void)n;
    (void)now_us;
    co401_sim_init((co401_sim_t *)sim);
    *(co401_plant_t *)plant = co401_sim_plant((co401_sim_t *)sim);
}

static co_err_t part_sim_set(void *inst, void *sim, uint16_t index, uint8_t sub, int64_t value)
{
    co401_sim_t *s = (co401_sim_t *)sim;
    uint8_t byte;
    uint8_t width;
    uint8_t ain;

    if ((s == NULL) || !co401_input_of((const co401_t *)inst, index, sub, &byte, &width, &ain)) {
        return CO_ERR_NO_OBJECT;
    }
    if (ain != 0xFFU) {
        if ((value < INT16_MIN) || (value > INT16_MAX)) {
            return CO_ERR_VALUE;
        }
        s->ain[ain] = (int16_t)value;
        return CO_OK;
    }
    if ((value < 0) || ((uint64_t)value >> (8U * width)) != 0U) {
        return CO_ERR_VALUE;
    }
    for (uint8_t k = 0U; k < width; k++) {
        s->din[byte + k] = (uint8_t)((uint64_t)value >> (8U * k));
    }
    return CO_OK;
}

const co_part_kind_t co401_part = {
    .name = "cia401",
    .ops = &co401_profile_ops,
    .inst_size = sizeof(co401_t),
    .plant_size = sizeof(co401_plant_t),
    .sim_size = sizeof(co401_sim_t),
    .init = part_init,
    .sim_init = part_sim_init,
    .sim_set = part_sim_set,
};

co401_t *co401_device_module(const co_device_run_t *run, uint8_t n)
{
    return (co401_t *)co_device_instance(run, &co401_part, n);
}
