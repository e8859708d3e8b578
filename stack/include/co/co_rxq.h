/*
 * Receive queue between a CAN receive ISR (single producer) and the loop that
 * calls co_node_rx (single consumer). Lock-free: the ISR only writes 'head',
 * the loop only writes 'tail'; both are read and written whole (16-bit
 * stores are atomic on every Cortex-M). On a multi-core system define
 * CO_RXQ_BARRIER() as a full memory barrier.
 *
 * The caller provides the frame storage, of any length: the queue holds as
 * many frames as it has slots (an index carries a lap bit besides its slot,
 * so a full queue differs from an empty one without a slot left free). The
 * queue keeps 11-bit frames only, the ones co_node_rx acts on, each in
 * 10 bytes (co_rxq_frame_t) instead of the 16 of a co_frame_t.
 */
#ifndef CO_RXQ_H
#define CO_RXQ_H

#include <stdbool.h>
#include <stdint.h>

#include "co/co_frame.h"

#ifndef CO_RXQ_BARRIER
#if defined(__GNUC__)
#define CO_RXQ_BARRIER() __asm__ volatile("" ::: "memory")
#else
#define CO_RXQ_BARRIER() ((void)0)
#endif
#endif

/** A frame as the queue keeps it: identifier, RTR flag and length in one
 *  16-bit word (11-bit frames only), then the data bytes. */
typedef struct co_rxq_frame {
    uint16_t id_dlc; /**< CAN-ID << 5 | RTR << 4 | length (0..15) */
    uint8_t data[8];
} co_rxq_frame_t;

typedef struct co_rxq {
    co_rxq_frame_t *buf;
    uint16_t len;             /**< frames it holds */
    volatile uint16_t head;   /**< written by the producer: the slot, bit 15 the lap */
    volatile uint16_t tail;   /**< written by the consumer (the same) */
    volatile uint16_t dropped;/**< frames lost because the queue was full */
} co_rxq_t;

/** @p len (the frames @p storage holds) must be 1..32767. Returns false otherwise. */
bool co_rxq_init(co_rxq_t *q, co_rxq_frame_t *storage, uint16_t len);

/** The queue co_rxq_init makes, as the initialiser of a static co_rxq_t
 *  (no code at start-up): @p len must be 1..32767. */
#define CO_RXQ_INIT(storage, len) {(storage), (uint16_t)(len), 0U, 0U, 0U}
/** Producer (ISR): false (and a count in 'dropped') when the queue is full.
 *  A 29-bit frame is not kept (co_node_rx ignores them): true. */
bool co_rxq_push(co_rxq_t *q, const co_frame_t *f);
/** Consumer (main loop): false when the queue is empty. */
bool co_rxq_pop(co_rxq_t *q, co_frame_t *f);

#endif /* CO_RXQ_H */
