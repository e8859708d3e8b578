#include "co/co_frame.h"

#include <string.h>

void co_frame_set(co_frame_t *f, uint32_t id, const uint8_t *data, uint8_t len)
{
    uint8_t n = (len > 8U) ? 8U : len;

    f->id = id;
    f->dlc = n;
    (void)memset(f->data, 0, sizeof f->data);
    if (data != NULL) {
        (void)memcpy(f->data, data, n);
    }
}

bool co_frame_equal(const co_frame_t *a, const co_frame_t *b)
{
    bool same = (a->id == b->id) && (a->dlc == b->dlc);

    if (same && (a->dlc <= 8U)) {
        same = (memcmp(a->data, b->data, a->dlc) == 0);
    }
    return same;
}
