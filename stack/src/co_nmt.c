/*
 * NMT slave service: the NMT command frame (COB-ID 0) and the error
 * behaviour 0x1029. The state machine itself (boot-up, state changes,
 * resets) is the node's: co_node.c.
 */
#include "co_priv.h"

static void nmt_event(co_node_t *node, uint8_t ev)
{
    if (ev == CO_SVC_SLOTS) {
        co_rx_add(node, 0x000U, CO_ROW_NMT);
    }
}

static void nmt_rx(co_node_t *node, uint16_t arg, const co_frame_t *f)
{
    (void)arg;
    if (co_frame_is_rtr(f) || (f->dlc != 2U)) {
        return;
    }
    if ((f->data[1] != 0U) && (f->data[1] != node->node_id)) {
        return;
    }
    /* (co_node_nmt_command without the clock: the frame's time is set) */
    co_node_nmt_exec(node, f->data[0]);
    co_rx_settle(node);
}

/* 0x1029 Error behaviour (CiA 301): what the device does on a serious
 * error of class @p sub (1: communication error, 2..: device-specific). 0:
 * Pre-operational, only from Operational; 1: no change; 2: Stopped;
 * reserved and manufacturer-specific values (3..0xFF): no change (a device
 * acts on its own values itself). Without 0x1029 (or that sub-index) the
 * state does not change. */
#if CO_ERROR_BEHAVIOUR
void co_nmt_error(co_node_t *node, uint8_t sub)
{
    const co_od_entry_t *e = co_od_find(node->dev->od, node->dev->od_count, 0x1029U);
    co_od_sub_t sd;
    const co_od_sub_t *s = ((e != NULL) && (sub != 0U)) ? co_od_find_sub(node->dev, e, sub, &sd) : NULL;
    const uint8_t *v = NULL;

    if ((s != NULL) && (s->type == (uint8_t)CO_UNSIGNED8)) {
        v = (const uint8_t *)co_od_loc(node, e, s);
    }
    if (v == NULL) {
        return;
    }
    if ((*v == 0U) && (node->nmt == (uint8_t)CO_NMT_OPERATIONAL)) {
        co_node_nmt_exec(node, (uint8_t)CO_NMT_CMD_PRE_OPERATIONAL);
    } else if (*v == 2U) {
        co_node_nmt_exec(node, (uint8_t)CO_NMT_CMD_STOP);
    } else {
        /* no change */
    }
}

/* 0..2, 0x80..0xFF manufacturer-specific; 3..0x7F reserved */
co_err_t co_errbeh_obj(co_node_t *node, uint8_t op, const co_od_entry_t *e,
                       const co_od_sub_t *s, const uint8_t *data, uint32_t len)
{
    (void)node;
    (void)op;
    (void)e;
    if ((s->sub > 0U) && (len == 1U) && (data[0] >= 3U) && (data[0] <= 0x7FU)) {
        return CO_ERR_VALUE;
    }
    return CO_OK;
}

const co_service_t co_svc_nmt = {
    nmt_event, nmt_rx, NULL,
};

#else /* !CO_ERROR_BEHAVIOUR: co_node_init refuses a device with 0x1029 */

const co_service_t co_svc_nmt = {
    nmt_event, nmt_rx, NULL,
};

#endif

void co_node_error_behaviour(co_node_t *node, uint8_t sub, uint32_t now_us)
{
    co_node_clock(node, now_us);
    if (CO_CB(node, error_class) != NULL) {
        node->cb->error_class(node->cb->ctx, node, sub);
    }
    co_nmt_error(node, sub);
}
