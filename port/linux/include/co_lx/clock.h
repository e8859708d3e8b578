/*
 * Time for the Linux port: the monotonic clock the core runs on, in
 * microseconds truncated to 32 bits (the core compares times wrap-safe),
 * and wrap-safe helpers for the loop.
 */
#ifndef CO_LX_CLOCK_H
#define CO_LX_CLOCK_H

#include <stdbool.h>
#include <stdint.h>

/** CLOCK_MONOTONIC in microseconds, modulo 2^32 (wraps every ~71 minutes). */
uint32_t co_lx_now_us(void);

/** Signed distance from @p now to @p t in microseconds (negative: past). */
static inline int32_t co_lx_until(uint32_t t, uint32_t now)
{
    uint32_t d = t - now;
    return (d <= 0x7FFFFFFFUL) ? (int32_t)d : -(int32_t)(0xFFFFFFFFUL - d) - 1;
}

/** The earlier of two deadlines seen from @p now (wrap-safe). */
static inline uint32_t co_lx_earlier(uint32_t a, uint32_t b, uint32_t now)
{
    return (co_lx_until(a, now) <= co_lx_until(b, now)) ? a : b;
}

#endif /* CO_LX_CLOCK_H */
