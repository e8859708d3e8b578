#include <stddef.h>
#include <string.h>

#include "co/co_rxq.h"

bool co_rxq_init(co_rxq_t *q, co_rxq_frame_t *storage, uint16_t len)
{
    if ((storage == NULL) || (len < 1U) || (len > 32767U)) {
        return false;
    }
    q->buf = storage;
    q->len = len;
    q->head = 0U;
    q->tail = 0U;
    q->dropped = 0U;
    return true;
}

/* An index is a slot (bits 0..14) and a lap bit, which flips each time the
 * index passes the last slot: the same slot is an empty queue on the same
 * lap, a full one on the other. */
#define LAP 0x8000U

/* The index after @p i of @p q. */
static inline uint16_t next_index(const co_rxq_t *q, uint32_t i)
{
    return (uint16_t)((((i & ~LAP) + 1U) == q->len) ? ((i & LAP) ^ LAP) : (i + 1U));
}

bool co_rxq_push(co_rxq_t *q, const co_frame_t *f)
{
    uint32_t head = q->head;
    co_rxq_frame_t *s;

    if ((f->id & CO_FRAME_EFF) != 0U) {
        return true; /* (not for the node) */
    }
    if ((head ^ q->tail) == LAP) { /* full: the tail's slot, a lap ahead */
        q->dropped = (uint16_t)(q->dropped + 1U);
        return false;
    }
    s = &q->buf[head & ~LAP];
    s->id_dlc = (uint16_t)(((f->id & 0x7FFU) << 5U) | ((f->id & CO_FRAME_RTR) >> 26U) |
                           (f->dlc & 0x0FU));
    (void)memcpy(s->data, f->data, sizeof s->data);
    CO_RXQ_BARRIER(); /* the frame is complete before the consumer sees it */
    q->head = next_index(q, head);
    return true;
}

bool co_rxq_pop(co_rxq_t *q, co_frame_t *f)
{
    uint32_t tail = q->tail;
    const co_rxq_frame_t *s = &q->buf[tail & ~LAP];

    if (tail == q->head) {
        return false;
    }
    CO_RXQ_BARRIER();
    f->id = ((uint32_t)s->id_dlc >> 5U) | (((uint32_t)s->id_dlc & 0x10U) << 26U);
    f->dlc = (uint8_t)(s->id_dlc & 0x0FU);
    (void)memcpy(f->data, s->data, sizeof f->data);
    CO_RXQ_BARRIER(); /* read before the slot is handed back */
    q->tail = next_index(q, tail);
    return true;
}
