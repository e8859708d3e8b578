/* The monotonic clock of the Linux port. */
#include "co_lx/clock.h"

#include <time.h>

uint32_t co_lx_now_us(void)
{
    struct timespec ts;

    (void)clock_gettime(CLOCK_MONOTONIC, &ts);
    /* modulo 2^32 by design: the core's time base wraps */
    return (uint32_t)(((uint64_t)ts.tv_sec * 1000000ULL) + ((uint64_t)ts.tv_nsec / 1000ULL));
}
