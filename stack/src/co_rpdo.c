/*
 * Receive PDOs: length checks, synchronous buffering, deadline monitoring,
 * and writing the mapped objects through the dictionary's write path.
 */
#include "co_priv.h"

static bool any_rpdo(const co_node_t *node, uint16_t flag)
{
    for (uint32_t i = 0U; i < node->dev->n_rpdo; i++) {
        if ((co_pdo_st(node)[i].flags & flag) != 0U) {
            return true;
        }
    }
    return false;
}

/* The RPDO error states with their EMCYs (CiA 301), in the order their
 * EMCYs go. */
static const struct {
    uint16_t flag;
    uint16_t code;
} rpdo_errs[] = {
    {CO_PDO_F_SHORT, CO_EMCY_PDO_SHORT},
    {CO_PDO_F_LONG, CO_EMCY_PDO_LONG},
    {CO_PDO_F_TIMEOUT, CO_EMCY_RPDO_TIMEOUT},
};

/* Set the error states of RPDO i in @p on, clear the others of @p mask (any
 * other flag of @p mask as well, without EMCY: CO_PDO_F_TIMER); the EMCY
 * goes with the first PDO in a state and ends with the last one leaving it. */
void co_rpdo_error(co_node_t *node, uint16_t i, uint16_t mask, uint16_t on)
{
    co_pdo_t *p = &co_pdo_st(node)[i];
    uint16_t chg = (uint16_t)(mask & (p->flags ^ on)); /* asked, and a change */

    p->flags ^= chg;
    for (uint8_t k = 0U; k < (uint8_t)(sizeof rpdo_errs / sizeof rpdo_errs[0]); k++) {
        uint16_t flag = rpdo_errs[k].flag;
        if ((chg & flag) == 0U) {
            continue;
        }
        if ((on & flag) != 0U) {
            co_emcy_raise(node, rpdo_errs[k].code, CO_ERREG_COMM, NULL);
        } else if (!any_rpdo(node, flag)) {
            co_emcy_clear(node, rpdo_errs[k].code);
        } else {
            /* another RPDO is still in the state */
        }
    }
}

/* Write the mapped objects of RPDO i (@p p, its state) from @p data (@p dlc
 * bytes). */
static void apply(co_node_t *node, uint16_t i, const co_pdo_t *p, const uint8_t *data,
                  uint8_t dlc)
{
#if CO_FAST
    if ((p->flags & CO_PDO_F_DIRECT) != 0U) {
        co_pdo_store_direct(node, i, data, dlc);
    } else {
        co_pdo_store(node, i, data, dlc);
    }
#else
    (void)p;
    co_pdo_store(node, i, data, dlc); /* one path for every PDO */
#endif
    if (CO_CB(node, rpdo) != NULL) {
        node->cb->rpdo(node->cb->ctx, node, i);
    }
    if ((CO_SET(node, pdo.tpdo_after_rpdo) != 0U) && (i < node->dev->n_tpdo)) {
        /* TPDO i of type 255 is requested, with the data the RPDO has just
         * changed (co_tpdo_raise: this module calls none of co_tpdo.c,
         * whose pass over the PDOs checks the RPDOs' deadlines) */
        uint16_t t = (uint16_t)(node->dev->n_rpdo + i);
        if ((co_pdo_type(node, t) == 255U) && co_pdo_usable(node, t)) {
            co_tpdo_raise(node, t);
        }
    }
}

/* The length checks of a received RPDO with their EMCYs (CiA 301): false
 * when the frame is not processed. A frame that comes ends a timeout. */
static bool length_ok(co_node_t *node, uint16_t i, uint8_t dlc)
{
    uint8_t len = co_pdo_st(node)[i].len;
    /* CiA 301: a short one is not processed; one longer than mapped is (the
     * first bytes), and reported */
    bool too_short = (dlc < len) && (CO_SET(node, pdo.short_rpdo) == CO_RPDO_SHORT_EMCY);

    co_rpdo_error(node, i,
                  too_short ? CO_PDO_F_SHORT
                            : (uint16_t)(CO_PDO_F_SHORT | CO_PDO_F_LONG | CO_PDO_F_TIMEOUT),
                  too_short ? CO_PDO_F_SHORT : ((dlc > len) ? CO_PDO_F_LONG : 0U));
    return !too_short;
}

/* A frame on the COB-ID of RPDO i, which the node's dispatch found valid
 * (co_pdo_rx_cob). */
void co_rpdo_rx(co_node_t *node, uint16_t i, const co_frame_t *f)
{
    co_pdo_t *p = &co_pdo_st(node)[i];

    if ((node->nmt != (uint8_t)CO_NMT_OPERATIONAL) || co_frame_is_rtr(f) ||
        (p->len == 0U)) {
        return;
    }
    /* the usual case, the expected length and no error to end, costs one test */
    if (((f->dlc != p->len) ||
         ((p->flags & (CO_PDO_F_SHORT | CO_PDO_F_LONG | CO_PDO_F_TIMEOUT)) != 0U)) &&
        !length_ok(node, i, f->dlc)) {
        return;
    }
    if ((p->flags & CO_PDO_F_TIMER) == 0U) {
        /* deadline monitoring starts (a later deadline only costs
         * co_node_process an early look; an event timer of 0 is none) */
        co_svc_touch(node, CO_ROW_PDO);
    }
    p->at = node->now; /* the deadline runs from the last reception */
    p->flags |= CO_PDO_F_TIMER;
    if (co_pdo_type(node, i) <= 240U) {
        /* synchronous: takes effect at the next SYNC, if it came in time */
        if (co_sync_window(node)) {
            (void)memcpy(p->data, f->data, 8U);
            p->count = f->dlc; /* the buffered frame's length */
            p->flags |= CO_PDO_F_RXBUF;
            node->bits |= CO_NODE_PDO_BUFFERED;
        }
        return;
    }
    apply(node, i, p, f->data, f->dlc);
}

/* At a SYNC (co_sync.c, when CO_NODE_PDO_BUFFERED says an RPDO may hold data):
 * the buffered synchronous RPDOs take effect. Only in Operational does an
 * RPDO buffer its data, and every NMT state change drops them (restart). */
void co_rpdo_sync(co_node_t *node)
{
    node->bits &= (uint8_t)~CO_NODE_PDO_BUFFERED;
    for (uint32_t i = 0U; i < node->dev->n_rpdo; i++) {
        co_pdo_t *p = &co_pdo_st(node)[i];
        if ((p->flags & CO_PDO_F_RXBUF) != 0U) {
            p->flags &= (uint16_t)~CO_PDO_F_RXBUF;
            apply(node, (uint16_t)i, p, p->data, p->count);
        }
    }
}
