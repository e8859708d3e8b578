#include <stddef.h>
#include <string.h>

#include "co/co_rxq.h"

bool co_rxq_init(co_rxq_t *q, co_rxq_frame_t *storage, uint16_t len)
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
    co_rxq_frame_t *s = &q->buf[head];

    if ((f->id & CO_FRAME_EFF) != 0U) {
        return true; /* (not for the node) */
    }
    if (next == q->tail) {
        q->dropped = (uint16_t)(q->dropped + 1U);
        return false;
    }
    s->id_dlc = (uint16_t)(((f->id & 0x7FFU) << 5U) | ((f->id & CO_FRAME_RTR) >> 26U) |
                           (f->dlc & 0x0FU));
    (void)memcpy(s->data, f->data, sizeof s->data);
    CO_RXQ_BARRIER(); /* the frame is complete before the consumer sees it */
    q->head = next;
    return true;
}

bool co_rxq_pop(co_rxq_t *q, co_frame_t *f)
{
    uint16_t tail = q->tail;
    const co_rxq_frame_t *s = &q->buf[tail];

    if (tail == q->head) {
        return false;
    }
    CO_RXQ_BARRIER();
    f->id = ((uint32_t)s->id_dlc >> 5U) | (((uint32_t)s->id_dlc & 0x10U) << 26U);
    f->dlc = (uint8_t)(s->id_dlc & 0x0FU);
    (void)memcpy(f->data, s->data, sizeof f->data);
    CO_RXQ_BARRIER(); /* read before the slot is handed back */
    q->tail = (uint16_t)((tail + 1U) & q->mask);
    return true;
}
