#include "co/co_frame.h"

#include <string.h>

bool co_frame_equal(const co_frame_t *a, const co_frame_t *b)
{
    bool same = (a->id == b->id) && (a->dlc == b->dlc);

    if (same && (a->dlc <= 8U)) {
        same = (memcmp(a->data, b->data, a->dlc) == 0);
    }
    return same;
}
