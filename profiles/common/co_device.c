/*
 * Devices: a device's profile instances, their plants and its plug-in on
 * the plug-in host (co/co_device.h).
 */
#include "co/co_device.h"

#include <string.h>

#define ALIGN 8U

static size_t up(size_t n)
{
    return (n + (ALIGN - 1U)) & ~(size_t)(ALIGN - 1U);
}

size_t co_device_mem_size(const co_device_t *device, bool simulated)
{
    const co_device_impl_t *impl = device->impl;
    size_t n = 0U;

    if (impl == NULL) {
        return 0U;
    }
    for (uint8_t p = 0U; p < impl->n_parts; p++) {
        const co_part_kind_t *k = impl->parts[p].kind;
        size_t one = up(k->inst_size);
        if (simulated) {
            one += up(k->sim_size) + up(k->plant_size);
        }
        n += one * impl->parts[p].count;
    }
    return n + ((impl->plugin != NULL) ? up(impl->plugin->state_size) : 0U);
}

static void *take(uint8_t *mem, size_t *at, size_t size)
{
    void *p = &mem[*at];

    *at += up(size);
    return p;
}

co_err_t co_device_init(co_device_run_t *run, const co_device_t *device, void *mem,
                        size_t mem_size, const void *const *plants,
                        const co_node_callbacks_t *app, uint32_t now_us)
{
    const co_device_impl_t *impl = device->impl;
    uint8_t *block = (uint8_t *)mem;
    size_t at = 0U;
    co_err_t err = CO_OK;

    (void)memset(run, 0, sizeof *run);
    run->device = device;
    co_profile_host_init(&run->host, run->slots, (uint8_t)(CO_DEVICE_INST_MAX + 1U), app);
    if (impl == NULL) {
        return CO_OK;
    }
    if (mem_size < co_device_mem_size(device, plants == NULL)) {
        return CO_ERR_VALUE;
    }
    if (mem_size != 0U) {
        (void)memset(mem, 0, mem_size);
    }
    for (uint8_t p = 0U; (p < impl->n_parts) && (err == CO_OK); p++) {
        const co_device_part_t *part = &impl->parts[p];
        const co_part_kind_t *k = part->kind;
        for (uint8_t n = 0U; (n < part->count) && (err == CO_OK); n++) {
            const void *plant;
            void *inst;
            if ((run->n_inst >= CO_DEVICE_INST_MAX) ||
                ((plants == NULL) && (k->sim_init == NULL))) {
                return CO_ERR_VALUE;
            }
            inst = take(block, &at, k->inst_size);
            if (plants == NULL) {
                void *sim = take(block, &at, k->sim_size);
                void *iface = take(block, &at, k->plant_size);
                k->sim_init(sim, part->config, n, now_us, iface);
                run->sim[run->n_inst] = sim;
                plant = iface;
            } else {
                plant = plants[run->n_inst];
            }
            run->inst[run->n_inst] = inst;
            run->part_of[run->n_inst] = p;
            run->n_inst++;
            err = k->init(inst, part->config, n, plant);
            if (err == CO_OK) {
                err = co_profile_add(&run->host, k->ops, inst);
            }
        }
    }
    if ((err == CO_OK) && (impl->plugin != NULL) && (impl->plugin->ops != NULL)) {
        size_t st = impl->plugin->state_size;
        run->state = (st != 0U) ? take(block, &at, st) : NULL;
        err = co_profile_add(&run->host, impl->plugin->ops, run);
    }
    return err;
}

const co_node_callbacks_t *co_device_callbacks(co_device_run_t *run)
{
    return co_profile_host_callbacks(&run->host);
}

co_err_t co_device_attach(co_device_run_t *run, co_node_t *node, uint32_t now_us)
{
    co_err_t err;

    run->node = node;
    err = co_profile_host_attach(&run->host, node, now_us);
    if ((err == CO_OK) && (run->device->impl != NULL) && (run->device->impl->plugin != NULL) &&
        (run->device->impl->plugin->powered_on != NULL)) {
        run->device->impl->plugin->powered_on(node, now_us);
    }
    return err;
}

uint32_t co_device_process(co_device_run_t *run, uint32_t now_us)
{
    return co_profile_host_process(&run->host, now_us);
}

void *co_device_instance(const co_device_run_t *run, const co_part_kind_t *kind, uint8_t n)
{
    uint8_t seen = 0U;

    if (run->device->impl == NULL) {
        return NULL;
    }
    for (uint8_t k = 0U; k < run->n_inst; k++) {
        if (run->device->impl->parts[run->part_of[k]].kind == kind) {
            if (seen == n) {
                return run->inst[k];
            }
            seen++;
        }
    }
    return NULL;
}

void *co_device_sim(const co_device_run_t *run, uint8_t k)
{
    return (k < run->n_inst) ? run->sim[k] : NULL;
}

co_node_t *co_device_node(const co_device_run_t *run)
{
    return run->node;
}

void *co_device_state(const co_device_run_t *run)
{
    return run->state;
}

co_err_t co_device_set(co_device_run_t *run, uint16_t index, uint8_t sub, int64_t value)
{
    const co_dev_t *dev;
    const co_od_entry_t *e;
    const co_od_sub_t *d;
    co_od_sub_t sub_buf;
    uint8_t buf[8];
    uint8_t size;

    if (run->node == NULL) {
        return CO_ERR_GENERAL;
    }
    for (uint8_t k = 0U; k < run->n_inst; k++) {
        const co_part_kind_t *kind = run->device->impl->parts[run->part_of[k]].kind;
        if (kind->sim_set != NULL) {
            co_err_t err = kind->sim_set(run->inst[k], run->sim[k], index, sub, value);
            if (err != CO_ERR_NO_OBJECT) {
                return err;
            }
        }
    }
    dev = run->node->dev;
    e = co_od_find(dev->od, dev->od_count, index);
    d = (e != NULL) ? co_od_find_sub(dev, e, sub, &sub_buf) : NULL;
    if (d == NULL) {
        return (e == NULL) ? CO_ERR_NO_OBJECT : CO_ERR_NO_SUB;
    }
    size = co_type_size(d->type);
    if ((size == 0U) || (size > 8U)) {
        return CO_ERR_TYPE_MISMATCH;
    }
    for (uint8_t b = 0U; b < size; b++) {
        buf[b] = (uint8_t)((uint64_t)value >> (8U * b));
    }
    return co_od_write(run->node, index, sub, buf, size, true);
}
