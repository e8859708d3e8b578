/*
 * The CAN frame as the core sees it: an 11-bit (or, for ports that need it,
 * 29-bit) identifier, a remote-request flag, a length and up to 8 bytes.
 */
#ifndef CO_FRAME_H
#define CO_FRAME_H

#include <stdbool.h>
#include <stdint.h>
#include <string.h>

#define CO_FRAME_RTR   0x40000000UL /**< id flag: remote transmission request */
#define CO_FRAME_EFF   0x20000000UL /**< id flag: 29-bit extended identifier   */
#define CO_FRAME_ID_MASK 0x1FFFFFFFUL

typedef struct co_frame {
    uint32_t id;      /**< identifier in bits 0..28, plus CO_FRAME_RTR / CO_FRAME_EFF */
    uint8_t  dlc;     /**< 0..8 */
    uint8_t  data[8];
} co_frame_t;

/** Fill @p f with identifier @p id and @p len bytes of @p data (rest zeroed).
 *  @p len above 8 is clamped to 8. */
static inline void co_frame_set(co_frame_t *f, uint32_t id, const uint8_t *data, uint8_t len)
{
    uint8_t n = (len > 8U) ? 8U : len;

    f->id = id;
    f->dlc = n;
    (void)memset(f->data, 0, sizeof f->data);
    if (data != NULL) {
        (void)memcpy(f->data, data, n);
    }
}

/** True when the frames carry the same identifier, flags, length and payload
 *  bytes (bytes beyond the length are not compared). */
bool co_frame_equal(const co_frame_t *a, const co_frame_t *b);

/** True for a remote transmission request. */
static inline bool co_frame_is_rtr(const co_frame_t *f)
{
    return (f->id & CO_FRAME_RTR) != 0U;
}

/** The identifier without flags. */
static inline uint32_t co_frame_cob(const co_frame_t *f)
{
    return f->id & CO_FRAME_ID_MASK;
}

#endif /* CO_FRAME_H */
