/*
 * The core's byte copy (co_priv.h co_copy): from the last byte down, a loop
 * the compiler keeps as it is (a forward byte loop is turned back into a
 * call of the C library's memcpy at -Os).
 */
#include "co_priv.h"

void co_copy_bytes(void *dst, const void *src, size_t n)
{
    uint8_t *d = (uint8_t *)dst;
    const uint8_t *s = (const uint8_t *)src;
    size_t k = n;

    while (k != 0U) {
        k--;
        d[k] = s[k];
    }
}
