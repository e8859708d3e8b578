/*
 * Explicit little-endian packing for CANopen payloads.
 *
 * CANopen puts every multi-byte value on the wire least significant byte
 * first (CiA 301, 7.1.2). These helpers never cast a buffer to a wider
 * type, so they are correct on big-endian CPUs and on unaligned buffers.
 */
#ifndef CO_ENDIAN_H
#define CO_ENDIAN_H

#include <stdint.h>
#include <string.h>

/* On a little-endian CPU the wire order is the CPU's: a value is stored as
 * one copy (on a CPU that allows unaligned stores, one store instruction
 * instead of one per byte). */
#if defined(__BYTE_ORDER__) && defined(__ORDER_LITTLE_ENDIAN__)
#if __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
#define CO_ENDIAN_LE 1
#endif
#endif

static inline uint16_t co_get_u16(const uint8_t *p)
{
    return (uint16_t)((uint16_t)p[0] | (uint16_t)((uint16_t)p[1] << 8U));
}

static inline uint32_t co_get_u24(const uint8_t *p)
{
    return (uint32_t)p[0] | ((uint32_t)p[1] << 8U) | ((uint32_t)p[2] << 16U);
}

static inline uint32_t co_get_u32(const uint8_t *p)
{
    return (uint32_t)p[0] | ((uint32_t)p[1] << 8U) | ((uint32_t)p[2] << 16U) |
           ((uint32_t)p[3] << 24U);
}

static inline uint64_t co_get_u64(const uint8_t *p)
{
    return (uint64_t)co_get_u32(p) | ((uint64_t)co_get_u32(&p[4]) << 32U);
}

static inline void co_put_u16(uint8_t *p, uint16_t v)
{
#ifdef CO_ENDIAN_LE
    (void)memcpy(p, &v, 2U);
#else
    p[0] = (uint8_t)(v & 0xFFU);
    p[1] = (uint8_t)(v >> 8U);
#endif
}

static inline void co_put_u24(uint8_t *p, uint32_t v)
{
    p[0] = (uint8_t)(v & 0xFFU);
    p[1] = (uint8_t)((v >> 8U) & 0xFFU);
    p[2] = (uint8_t)((v >> 16U) & 0xFFU);
}

static inline void co_put_u32(uint8_t *p, uint32_t v)
{
#ifdef CO_ENDIAN_LE
    (void)memcpy(p, &v, 4U);
#else
    p[0] = (uint8_t)(v & 0xFFU);
    p[1] = (uint8_t)((v >> 8U) & 0xFFU);
    p[2] = (uint8_t)((v >> 16U) & 0xFFU);
    p[3] = (uint8_t)(v >> 24U);
#endif
}

static inline void co_put_u64(uint8_t *p, uint64_t v)
{
    co_put_u32(p, (uint32_t)(v & 0xFFFFFFFFU));
    co_put_u32(&p[4], (uint32_t)(v >> 32U));
}

#endif /* CO_ENDIAN_H */
