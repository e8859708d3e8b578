/*
 * The one copy of co_deadline_min in a build for size (co_priv.h): a module
 * of its own, below every service, so that a service linked without the
 * node (tests/unit/test_svc_alone) has it too.
 */
#include "co_priv.h"

#if !CO_FAST
uint32_t co_deadline_min(uint32_t now, uint32_t cur, uint32_t cand)
{
    return co_deadline_earlier(now, cur, cand);
}
#endif
