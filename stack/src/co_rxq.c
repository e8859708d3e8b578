#include <stddef.h>

#include "co/co_rxq.h"

bool co_rxq_init(co_rxq_t *q, co_frame_t *storage, uint16_t len)
{
    if ((storage == NULL) || (len < 2U) || (len > 32768U) || ((len & (len - 1U)) != 0U)) {
        return false;
    }
    q->buf = storage;
    q->mask = (uint16_t)(len - 1U);
    q->head = 0U;
    q->tail = 0U;
    q->dropped = 0U;
    return true;
}

bool co_rxq_push(co_rxq_t *q, const co_frame_t *f)
{
    uint16_t head = q->head;
    uint16_t next = (uint16_t)((head + 1U) & q->mask);

    if (next == q->tail) {
        q->dropped = (uint16_t)(q->dropped + 1U);
        return false;
    }
    q->buf[head] = *f;
    CO_RXQ_BARRIER(); /* the frame is complete before the consumer sees it */
    q->head = next;
    return true;
}

bool co_rxq_pop(co_rxq_t *q, co_frame_t *f)
{
    uint16_t tail = q->tail;

    if (tail == q->head) {
        return false;
    }
    CO_RXQ_BARRIER();
    *f = q->buf[tail];
    CO_RXQ_BARRIER(); /* read before the slot is handed back */
    q->tail = (uint16_t)((tail + 1U) & q->mask);
    return true;
}
