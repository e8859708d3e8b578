/*
 * A profile's direct view of an integer object (co/co_pobj.h).
 */
#include "co/co_pobj.h"

#include <stddef.h>
#include <string.h>

uint8_t co_pobj_int_size(uint8_t type)
{
    switch (type) {
    case (uint8_t)CO_INTEGER8:
    case (uint8_t)CO_UNSIGNED8:
        return 1U;
    case (uint8_t)CO_INTEGER16:
    case (uint8_t)CO_UNSIGNED16:
        return 2U;
    case (uint8_t)CO_INTEGER32:
    case (uint8_t)CO_UNSIGNED32:
        return 4U;
    default:
        return 0U;
    }
}

void co_pobj_bind(co_pobj_t *o, co_node_t *node, uint16_t index, uint8_t sub)
{
    const co_dev_t *dev = node->dev;
    const co_od_entry_t *e = co_od_find(dev->od, dev->od_count, index);
    co_od_sub_t sub_buf;
    const co_od_sub_t *s = (e != NULL) ? co_od_find_sub(dev, e, sub, &sub_buf) : NULL;

    o->p = NULL;
    o->type = 0U;
    if ((s == NULL) || (co_pobj_int_size(s->type) == 0U) || ((s->flags & CO_SUB_HOOKIO) != 0U)) {
        return;
    }
    if ((s->flags & CO_SUB_ROM) != 0U) {
        o->p = (void *)(uintptr_t)&dev->rom[s->off];
        o->type = (uint8_t)(s->type | CO_POBJ_CONST);
    } else {
        o->p = co_od_value_ptr(node, index, sub);
        o->type = (o->p != NULL) ? s->type : 0U;
    }
}

bool co_pobj_has(const co_pobj_t *o)
{
    return o->p != NULL;
}

int64_t co_pobj_get(const co_pobj_t *o, int64_t dflt)
{
    if (o->p == NULL) {
        return dflt;
    }
    switch (o->type & (uint8_t)~CO_POBJ_CONST) {
    case (uint8_t)CO_INTEGER8: {
        int8_t v;
        (void)memcpy(&v, o->p, 1U);
        return v;
    }
    case (uint8_t)CO_UNSIGNED8: {
        uint8_t v;
        (void)memcpy(&v, o->p, 1U);
        return v;
    }
    case (uint8_t)CO_INTEGER16: {
        int16_t v;
        (void)memcpy(&v, o->p, 2U);
        return v;
    }
    case (uint8_t)CO_UNSIGNED16: {
        uint16_t v;
        (void)memcpy(&v, o->p, 2U);
        return v;
    }
    case (uint8_t)CO_INTEGER32: {
        int32_t v;
        (void)memcpy(&v, o->p, 4U);
        return v;
    }
    default: {
        uint32_t v;
        (void)memcpy(&v, o->p, 4U);
        return v;
    }
    }
}

void co_pobj_put(const co_pobj_t *o, int64_t v)
{
    if ((o->p == NULL) || ((o->type & CO_POBJ_CONST) != 0U)) {
        return;
    }
    switch (co_pobj_int_size(o->type)) {
    case 1U: {
        uint8_t b = (uint8_t)((uint64_t)v & 0xFFU);
        (void)memcpy(o->p, &b, 1U);
        break;
    }
    case 2U: {
        uint16_t h = (uint16_t)((uint64_t)v & 0xFFFFU);
        (void)memcpy(o->p, &h, 2U);
        break;
    }
    default: {
        uint32_t w = (uint32_t)((uint64_t)v & 0xFFFFFFFFU);
        (void)memcpy(o->p, &w, 4U);
        break;
    }
    }
}
