/*
 * A profile's view of one integer object of its node: where the value lives
 * (the node's RAM image, or the device's const ROM image) and its type, found
 * once at attach, then read and written without a dictionary look-up. For
 * the values a plug-in keeps current every tick (status, actual values) and
 * the parameters it reads every tick; writes the master makes still go
 * through the dictionary path and the hooks.
 */
#ifndef CO_POBJ_H
#define CO_POBJ_H

#include <stdbool.h>
#include <stdint.h>

#include "co/co_node.h"

typedef struct co_pobj {
    void *p;       /**< the value, NULL when the device lacks the object */
    uint8_t type;  /**< co_type_t, | CO_POBJ_CONST for a value in ROM */
} co_pobj_t;

#define CO_POBJ_CONST 0x80U

/** Find @p index / @p sub of @p node: an integer value of 8, 16 or 32 bits
 *  stored in RAM or ROM. Anything else (absent, hook I/O, other types)
 *  leaves @p o empty. */
void co_pobj_bind(co_pobj_t *o, co_node_t *node, uint16_t index, uint8_t sub);

/** Bytes of an integer of CiA 301 data type @p type (1, 2 or 4); 0 for any
 *  other type. */
uint8_t co_pobj_int_size(uint8_t type);

/** True when the device has the object. */
bool co_pobj_has(const co_pobj_t *o);

/** The value, sign-extended by its type; @p dflt without the object. */
int64_t co_pobj_get(const co_pobj_t *o, int64_t dflt);

/** Store @p v (truncated to the type); nothing without the object or for a
 *  constant. */
void co_pobj_put(const co_pobj_t *o, int64_t v);

#endif /* CO_POBJ_H */
