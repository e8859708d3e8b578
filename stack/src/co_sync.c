/*
 * SYNC consumer and producer (0x1005, 0x1006, 0x1007, 0x1019) and the TIME
 * consumer/producer (0x1012).
 */
#include "co/co_endian.h"
#include "co_priv.h"

#define COB_SYNC_GEN  0x40000000UL /* 0x1005 bit 30: this node produces SYNC */
#define COB_TIME_CONS 0x80000000UL /* 0x1012 bit 31: consume TIME */
#define COB_TIME_PROD 0x40000000UL /* 0x1012 bit 30: produce TIME */

static bool sync_allowed(const co_node_t *node)
{
    return (node->nmt == (uint8_t)CO_NMT_PRE_OPERATIONAL) ||
           (node->nmt == (uint8_t)CO_NMT_OPERATIONAL);
}

static uint8_t overflow(const co_node_t *node)
{
    return (node->sync_overflow != NULL) ? *node->sync_overflow : 0U;
}

static bool producing(const co_node_t *node)
{
#if CO_SYNC_PRODUCER
    return (node->sync_cob != NULL) && ((*node->sync_cob & COB_SYNC_GEN) != 0U) &&
           (node->sync_period != NULL) && (*node->sync_period != 0U);
#else
    (void)node;
    return false;
#endif
}

/* The communication cycle period 0x1006 in us, within the timer horizon. */
static uint32_t period_us(const co_node_t *node)
{
    return co_dict_us(*node->sync_period, 1U);
}

/* Everything a SYNC sets in motion, received or produced here. */
static void on_sync(co_node_t *node, uint8_t counter)
{
    node->sync_last = node->now;
    /* CiA 301: synchronous RPDOs received before this SYNC take effect, the
     * application runs its cycle, then synchronous TPDOs are sampled. */
    co_rpdo_sync(node);
    if (node->cb.sync != NULL) {
        node->cb.sync(node->cb.ctx, node, counter);
    }
    co_tpdo_sync(node, counter);
}

void co_sync_reset(co_node_t *node)
{
    node->sync_counter = 1U;
    node->sync_last = node->now;
    if (producing(node)) {
        node->sync_deadline = node->now + period_us(node);
    }
}

void co_sync_rx(co_node_t *node, const co_frame_t *f)
{
    uint8_t ovf = overflow(node);
    uint8_t want = (ovf > 1U) ? 1U : 0U;

    if (!sync_allowed(node) || co_frame_is_rtr(f)) {
        return;
    }
    if (f->dlc != want) {
        /* CiA 301: a SYNC whose length does not fit 0x1019 is not used */
        co_emcy_raise(node, CO_EMCY_SYNC_LENGTH, CO_ERREG_COMM, NULL);
        return;
    }
    if (co_emcy_is_active(node, CO_EMCY_SYNC_LENGTH)) {
        co_emcy_clear(node, CO_EMCY_SYNC_LENGTH);
    }
    on_sync(node, (want != 0U) ? f->data[0] : 0U);
}

uint32_t co_sync_process(co_node_t *node, uint32_t next)
{
    if (!producing(node)) {
        return next;
    }
    if (co_time_reached(node->now, node->sync_deadline)) {
        uint8_t ovf = overflow(node);
        uint8_t cnt = 0U;
        uint32_t period = period_us(node);
        if (sync_allowed(node)) {
            if (ovf > 1U) {
                cnt = node->sync_counter;
                node->sync_counter = (cnt >= ovf) ? 1U : (uint8_t)(cnt + 1U);
            }
            co_tx(node, *node->sync_cob & 0x7FFUL, &cnt, (ovf > 1U) ? 1U : 0U);
            on_sync(node, cnt);
        }
        node->sync_deadline += period;
        if (co_time_reached(node->now, node->sync_deadline)) {
            node->sync_deadline = node->now + period; /* fell behind: no burst */
        }
    }
    return co_deadline_min(node->now, next, node->sync_deadline);
}

bool co_sync_window_open(const co_node_t *node)
{
    uint32_t w = (node->sync_window != NULL) ? *node->sync_window : 0U;

    return (w == 0U) || ((uint32_t)(node->now - node->sync_last) <= w);
}

void co_time_rx(co_node_t *node, const co_frame_t *f)
{
    const uint32_t *cob = co_time_cob(node);

    if (!sync_allowed(node) || co_frame_is_rtr(f) || (f->dlc < 6U) || (cob == NULL) ||
        ((*cob & COB_TIME_CONS) == 0U)) {
        return;
    }
    if (node->cb.time != NULL) {
        node->cb.time(node->cb.ctx, node, co_get_u32(f->data) & 0x0FFFFFFFUL,
                      co_get_u16(&f->data[4]));
    }
}

co_err_t co_time_send(co_node_t *node, uint32_t ms, uint16_t days)
{
    const uint32_t *cob = co_time_cob(node);
    uint8_t d[6];

    if ((cob == NULL) || ((*cob & COB_TIME_PROD) == 0U)) {
        return CO_ERR_NO_ACCESS;
    }
    if (!sync_allowed(node)) {
        return CO_ERR_STORE_STATE;
    }
    co_put_u32(d, ms & 0x0FFFFFFFUL);
    co_put_u16(&d[4], days);
    co_tx(node, *cob & 0x7FFUL, d, 6U);
    return CO_OK;
}
