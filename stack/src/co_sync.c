/*
 * SYNC consumer and producer (0x1005, 0x1006, 0x1007, 0x1019).
 */
#include "co/co_endian.h"
#include "co_priv.h"

#define COB_SYNC_GEN  CO_COB_B30 /* 0x1005 bit 30: this node produces SYNC (co_cob_at) */

static bool sync_allowed(const co_node_t *node)
{
    return (node->nmt == (uint8_t)CO_NMT_PRE_OPERATIONAL) ||
           (node->nmt == (uint8_t)CO_NMT_OPERATIONAL);
}

/* 0x1005 (co_node.h, CO_RAM_1005: 0 without the object) */
static uint32_t sync_cob(const co_node_t *node)
{
    return co_ram_cob(node, CO_RAM_1005);
}

/* 0x1019 (0 without the object) */
static uint8_t overflow(const co_node_t *node)
{
    return co_ram_u8(node, CO_RAM_1019);
}

/* A SYNC period is set (0x1006 non-zero; never without the producer). */
static bool producing_period(const co_node_t *node)
{
#if CO_SYNC_PRODUCER
    return (node->sync.period != NULL) && (*node->sync.period != 0U);
#else
    (void)node;
    return false;
#endif
}

#if CO_SYNC_PRODUCER
static bool producing(const co_node_t *node)
{
    return ((sync_cob(node) & COB_SYNC_GEN) != 0U) && producing_period(node);
}
#endif

#if CO_SYNC_PRODUCER
/* The communication cycle period 0x1006 in us, within the timer horizon. */
static uint32_t period_us(const co_node_t *node)
{
    return co_dict_us(*node->sync.period, 1U);
}
#endif

/* Everything a SYNC sets in motion, received or produced here. */
static void on_sync(co_node_t *node, uint8_t counter)
{
    node->sync.last = node->now;
    /* CiA 301: synchronous RPDOs received before this SYNC take effect, the
     * application runs its cycle, then synchronous TPDOs are sampled. */
    if ((node->bits & CO_NODE_PDO_BUFFERED) != 0U) {
        co_rpdo_sync(node);
    }
    if (CO_CB(node, sync) != NULL) {
        node->cb->sync(node->cb->ctx, node, counter);
    }
    co_tpdo_sync(node, counter);
}

static void sync_reset(co_node_t *node)
{
    node->sync.last = node->now;
#if CO_SYNC_PRODUCER
    node->sync.counter = 1U;
    node->tx_hold &= (uint8_t)~CO_TXH_SYNC; /* SYNC starts over */
    if (producing(node)) {
        node->sync.deadline = node->now + period_us(node);
    }
#endif
}

static void sync_rx(co_node_t *node, const co_frame_t *f)
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
    if (node->emcy.n_active != 0U) {
        co_emcy_clear(node, CO_EMCY_SYNC_LENGTH); /* (nothing if it is not active) */
    }
    on_sync(node, (want != 0U) ? f->data[0] : 0U);
}

#if CO_SYNC_PRODUCER
/* The SYNC due now, or one the TX path refused before: made from the
 * producer's state and sent if the TX path takes it (a refused one waits
 * for the next run: co_tx_try); what a SYNC sets in motion here (counter,
 * window, RPDOs, TPDOs) starts when it is sent. The period keeps its
 * times: a SYNC that waits when the next is due is that one. */
static uint32_t sync_process(co_node_t *node, uint32_t next)
{
    bool send = (node->tx_hold & CO_TXH_SYNC) != 0U;

    node->tx_hold &= (uint8_t)~CO_TXH_SYNC; /* (sent, or set again by co_tx_try) */
    if (!producing(node)) {
        return next; /* (one that waits is dropped) */
    }
    if (co_time_reached(node->now, node->sync.deadline)) {
        uint32_t period = period_us(node);
        send = true;
        node->sync.deadline += period;
        if (co_time_reached(node->now, node->sync.deadline)) {
            node->sync.deadline = node->now + period; /* fell behind: no burst */
        }
    }
    if (send && sync_allowed(node)) {
        uint8_t ovf = overflow(node);
        uint8_t cnt = (ovf > 1U) ? node->sync.counter : 0U;
        co_frame_t f;
        f.id = sync_cob(node) & 0x7FFUL;
        f.dlc = (ovf > 1U) ? 1U : 0U;
        (void)memset(f.data, 0, sizeof f.data);
        f.data[0] = cnt;
        if (co_tx_try(node, CO_TXH_SYNC, &f)) {
            if (ovf > 1U) {
                node->sync.counter = (cnt >= ovf) ? 1U : (uint8_t)(cnt + 1U);
            }
            on_sync(node, cnt);
            if ((node->tx_hold & CO_TXH_EMCY) != 0U) {
                /* an EMCY waited behind it: its row (before this one in
                 * the table) runs once more */
                co_svc_touch(node, CO_ROW_EMCY);
            }
        }
    }
    return co_deadline_min(node->now, next, node->sync.deadline);
}
#endif

bool co_sync_window_open(const co_node_t *node)
{
    return co_sync_window(node);
}

/* ------------------------------------------------------------ service */

/* (its objects: 0x1005, 0x1007, 0x1019 at their places in the RAM image,
 * co_node.h's CO_RAM_*; 0x1006: co_binds[], co_services.c; without the
 * producer a device with a 0x1006 is refused) */

static void sync_event(co_node_t *node, uint8_t ev)
{
    uint32_t cob = sync_cob(node);

    if (ev == CO_SVC_START) {
        sync_reset(node);
    } else if ((ev == CO_SVC_SLOTS) && ((cob & COB_SYNC_GEN) == 0U) && ((cob & 0x7FFU) != 0U)) {
        /* (CAN-ID 0: no 0x1005) */
        co_rx_add(node, (uint16_t)(cob & 0x7FFU), CO_ROW_SYNC);
    } else {
        /* nothing to do */
    }
}

static void sync_rx_frame(co_node_t *node, uint16_t arg, const co_frame_t *f)
{
    (void)arg;
    sync_rx(node, f);
}

/* 0x1005: the CAN-ID is fixed while this node produces SYNC (bit 30);
 * 0x1006 within the timer horizon (2^31 us); 0x1019 counter overflow 0 or
 * 2..240, and only while no SYNC period is set. A change of 0x1005, 0x1006
 * or 0x1019 starts SYNC over. */
co_err_t co_sync_obj(co_node_t *node, uint8_t op, const co_od_entry_t *e,
                     const co_od_sub_t *s, const uint8_t *data, uint32_t len)
{
    uint16_t index = e->index;
    co_err_t err = CO_OK;

    if (op == (uint8_t)CO_SVC_WRITTEN) {
        if (index != 0x1007U) {
            sync_reset(node);
            co_rx_invalidate(node);
        }
    } else if (s->sub != 0U) {
        /* not a SYNC parameter */
    } else if ((index == 0x1005U) && (len == 4U)) { /* (an UNSIGNED32 at its place) */
        err = co_check_cob(sync_cob(node), co_get_u32(data),
                           COB_SYNC_GEN | CO_COB_WHEN_SET | CO_COB_ALWAYS);
#if CO_SYNC_PRODUCER /* (without, a device has no 0x1006: co_binds) */
    } else if ((index == 0x1006U) && (len == 4U) && (co_get_u32(data) > CO_HORIZON_US)) {
        err = CO_ERR_VALUE_HIGH;
#endif
    } else if (index == 0x1019U) { /* (at least one byte: the engine's type check) */
        if ((data[0] == 1U) || (data[0] > 240U)) {
            err = CO_ERR_VALUE;
        } else if (producing_period(node)) {
            err = CO_ERR_STORE_STATE;
        } else {
            /* allowed */
        }
    } else {
        /* no rule */
    }
    return err;
}

const co_service_t co_svc_sync = {
    sync_event, sync_rx_frame,
#if CO_SYNC_PRODUCER
    sync_process,
#else
    NULL, /* the consumer has no timer */
#endif
};
