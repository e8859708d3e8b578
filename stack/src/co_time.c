/*
 * TIME consumer and producer (0x1012). Without CO_TIME only the refusal of
 * a device with 0x1012 is left.
 */
#include "co/co_endian.h"
#include "co_priv.h"

#if CO_TIME

#define COB_TIME_CONS CO_COB_B31 /* 0x1012 bit 31: consume TIME (co_cob_at) */
#define COB_TIME_PROD CO_COB_B30 /* 0x1012 bit 30: produce TIME */

/* 0x1012 (0 without the object) */
static uint32_t time_cob(const co_node_t *node)
{
    return (node->time.cob != NULL) ? co_cob_at(node->time.cob) : 0U;
}

static bool time_allowed(const co_node_t *node)
{
    return (node->nmt == (uint8_t)CO_NMT_PRE_OPERATIONAL) ||
           (node->nmt == (uint8_t)CO_NMT_OPERATIONAL);
}

static void time_rx(co_node_t *node, uint16_t arg, const co_frame_t *f)
{
    (void)arg;
    if (!time_allowed(node) || co_frame_is_rtr(f) || (f->dlc < 6U) ||
        ((time_cob(node) & COB_TIME_CONS) == 0U)) {
        return;
    }
    if (CO_CB(node, time) != NULL) {
        node->cb->time(node->cb->ctx, node, co_get_u32(f->data) & 0x0FFFFFFFUL,
                      co_get_u16(&f->data[4]));
    }
}

co_err_t co_time_send(co_node_t *node, uint32_t ms, uint16_t days)
{
    uint32_t cob = time_cob(node);
    co_frame_t f;

    if ((cob & COB_TIME_PROD) == 0U) {
        return CO_ERR_NO_ACCESS;
    }
    if (!time_allowed(node)) {
        return CO_ERR_STORE_STATE;
    }
    f.id = cob & 0x7FFUL;
    f.dlc = 6U;
    (void)memset(f.data, 0, sizeof f.data);
    co_put_u32(f.data, ms & 0x0FFFFFFFUL);
    co_put_u16(&f.data[4], days);
    /* the time of the call, or none: a later frame would carry a stale
     * time (the application sends a new one) */
    return co_tx_now(node, &f) ? CO_OK : CO_ERR_RESOURCE;
}

/* (its object: co_binds[], co_services.c) */

static void time_event(co_node_t *node, uint8_t ev)
{
    uint32_t cob = time_cob(node);

    if ((ev == CO_SVC_SLOTS) && ((cob & COB_TIME_CONS) != 0U)) {
        co_rx_add(node, (uint16_t)(cob & 0x7FFU), CO_ROW_TIME);
    }
}

/* The CAN-ID is fixed while consumed or produced (bits 31, 30); a new one
 * is received from the next frame on. */
co_err_t co_time_obj(co_node_t *node, uint8_t op, const co_od_entry_t *e,
                     const co_od_sub_t *s, const uint8_t *data, uint32_t len)
{
    (void)e;
    if (op == (uint8_t)CO_SVC_WRITTEN) {
        co_rx_invalidate(node);
    } else if ((s->sub == 0U) && (len == 4U) && (node->time.cob != NULL)) {
        return co_check_cob(time_cob(node), co_get_u32(data),
                            COB_TIME_CONS | COB_TIME_PROD | CO_COB_WHEN_SET);
    } else {
        /* no rule */
    }
    return CO_OK;
}

const co_service_t co_svc_time = {
    time_event, time_rx, NULL,
};

#else /* !CO_TIME */

co_err_t co_time_send(co_node_t *node, uint32_t ms, uint16_t days)
{
    (void)node;
    (void)ms;
    (void)days;
    return CO_ERR_NO_ACCESS;
}

/* (no row in co_services[]: co_node_init refuses a device with 0x1012) */

#endif
