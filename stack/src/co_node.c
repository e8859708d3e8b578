/*
 * The node: initialisation, receive dispatch by COB-ID, timers, TX hold-back.
 */
#include <string.h>

#include "co_priv.h"

/* ------------------------------------------------------------------ TX */

static bool hal_send(co_node_t *node, const co_frame_t *f)
{
    return node->hal.ops->send(node->hal.ctx, f) == 0;
}

/* The hold-back queue is kept in CAN priority order (lowest identifier
 * first; frames of one identifier in the order they were made), so that a
 * controller that frees a mailbox gets the frame that would win arbitration. */
static void tx_drain(co_node_t *node)
{
    uint8_t sent = 0U;

    while ((sent < node->txq_len) && hal_send(node, &node->txq[sent])) {
        sent++;
    }
    if (sent > 0U) {
        node->txq_len = (uint8_t)(node->txq_len - sent);
        (void)memmove(&node->txq[0], &node->txq[sent], (size_t)node->txq_len * sizeof node->txq[0]);
    }
}

void co_tx_frame(co_node_t *node, const co_frame_t *f)
{
    uint32_t cob = co_frame_cob(f);
    uint8_t at = node->txq_len;

    if ((node->txq_len == 0U) && hal_send(node, f)) {
        return;
    }
    while ((at > 0U) && (co_frame_cob(&node->txq[at - 1U]) > cob)) {
        at--;
    }
    if (node->txq_len == CO_TXQ_LEN) {
        /* full: the frame of lowest priority is lost (the new one, when
         * nothing waiting ranks below it) */
        if (at == CO_TXQ_LEN) {
            return;
        }
        node->txq_len--;
    }
    (void)memmove(&node->txq[at + 1U], &node->txq[at],
                  (size_t)(node->txq_len - at) * sizeof node->txq[0]);
    node->txq[at] = *f;
    node->txq_len++;
    tx_drain(node); /* the controller may have room again */
}

void co_node_tx_ready(co_node_t *node, uint32_t now_us)
{
    co_node_clock(node, now_us);
    tx_drain(node);
    if (node->txq_len == 0U) {
        (void)co_sdo_process(node, CO_NO_DEADLINE); /* a stalled block upload goes on */
    }
}

void co_tx(co_node_t *node, uint32_t id, const uint8_t *data, uint8_t len)
{
    co_frame_t f;

    co_frame_set(&f, id, data, len);
    co_tx_frame(node, &f);
}

bool co_tx_try(co_node_t *node, uint32_t id, const uint8_t *data, uint8_t len)
{
    co_frame_t f;

    co_frame_set(&f, id, data, len);
    return co_tx_now(node, &f);
}

/* ------------------------------------------------------- RX dispatch */

static void rx_add(co_node_t *node, uint16_t cob, uint8_t kind, uint8_t arg)
{
    uint8_t i = node->n_rx;

    if (i >= CO_RX_SLOTS_MAX) {
        return;
    }
    /* insertion keeps the table sorted by COB-ID */
    while ((i > 0U) && (node->rx[i - 1U].cob > cob)) {
        node->rx[i] = node->rx[i - 1U];
        i--;
    }
    node->rx[i].cob = cob;
    node->rx[i].kind = kind;
    node->rx[i].arg = arg;
    node->n_rx++;
    node->rx_filter[(cob & 0x7FU) >> 3U] |= (uint8_t)(1U << (cob & 7U));
    node->rx_fc |= (uint16_t)(1U << (cob >> 7U));
}

/* The services of a configured node (NMT, SDO, ...), then its PDOs. */
static void rx_add_services(co_node_t *node)
{
    rx_add(node, 0x000U, CO_RX_NMT, 0U);
    rx_add(node, (uint16_t)(0x600U + node->node_id), CO_RX_SDO, 0U);
    rx_add(node, (uint16_t)(0x700U + node->node_id), CO_RX_GUARD, 0U);
    if ((node->sync_cob != NULL) && ((*node->sync_cob & 0x40000000UL) == 0U)) {
        rx_add(node, (uint16_t)(*node->sync_cob & 0x7FFU), CO_RX_SYNC, 0U);
    }
    if ((co_time_cob(node) != NULL) && ((*co_time_cob(node) & 0x80000000UL) != 0U)) {
        rx_add(node, (uint16_t)(*co_time_cob(node) & 0x7FFU), CO_RX_TIME, 0U);
    }
    for (uint8_t k = 0U; k < node->n_hb_cons; k++) {
        uint32_t v = node->hb_cons[k];
        uint8_t id = (uint8_t)((v >> 16U) & 0x7FU);
        if (((v & 0xFFFFU) != 0U) && (id != 0U) && (id != node->node_id)) {
            rx_add(node, (uint16_t)(0x700U + id), CO_RX_HB, k);
        }
    }
    co_pdo_rx_rebuild(node);
}

void co_rx_rebuild(co_node_t *node)
{
    node->n_rx = 0U;
    node->rx_fc = 0U;
    (void)memset(node->rx_filter, 0, sizeof node->rx_filter);
    if (co_lss_enabled(node)) {
        rx_add(node, 0x7E5U, CO_RX_LSS, 0U);
    }
    if (node->node_id == CO_NODE_ID_UNCONFIGURED) {
        node->pdo_fc = 0U; /* LSS only */
        node->n_pdo_rx = 0U;
    } else {
        rx_add_services(node);
    }
    if (node->cb.rx_set != NULL) {
        node->cb.rx_set(node->cb.ctx, node);
    }
}

bool co_node_rx_cob(const co_node_t *node, uint16_t i, uint16_t *cob)
{
    bool found = false;

    if (i < node->n_rx) {
        *cob = node->rx[i].cob;
        found = true;
    } else if ((uint16_t)(i - node->n_rx) < node->n_pdo_rx) {
        *cob = node->pdo_rx[i - node->n_rx].cob;
        found = true;
    } else {
        /* past the last */
    }
    return found;
}

static const co_rx_slot_t *rx_find(const co_node_t *node, uint16_t cob)
{
    uint32_t lo = 0U;
    uint32_t hi = node->n_rx;

    while (lo < hi) {
        uint32_t mid = (lo + hi) >> 1U;
        uint16_t at = node->rx[mid].cob;
        if (at == cob) {
            return &node->rx[mid];
        }
        if (at < cob) {
            lo = mid + 1U;
        } else {
            hi = mid;
        }
    }
    return NULL;
}

static const co_pdo_slot_t *pdo_find(const co_node_t *node, uint16_t cob)
{
    uint32_t lo = 0U;
    uint32_t hi = node->n_pdo_rx;

    while (lo < hi) {
        uint32_t mid = (lo + hi) >> 1U;
        uint16_t at = node->pdo_rx[mid].cob;
        if (at == cob) {
            return &node->pdo_rx[mid];
        }
        if (at < cob) {
            lo = mid + 1U;
        } else {
            hi = mid;
        }
    }
    return NULL;
}

/* A frame that may be on a PDO's COB-ID. */
static void pdo_rx(co_node_t *node, uint16_t cob, const co_frame_t *f, uint32_t now_us)
{
    const co_pdo_slot_t *ps = pdo_find(node, cob);

    if (ps == NULL) {
        return;
    }
    co_node_clock(node, now_us);
    if (ps->pdo < node->dev->n_rpdo) {
        co_rpdo_rx(node, ps->pdo, f);
    } else if (co_frame_is_rtr(f)) {
        co_tpdo_rtr(node, ps->pdo);
    } else {
        /* another node's data frame on this TPDO's identifier */
    }
}

/* A frame the filter let through: find what it is for. (Not static, so
 * that the filter's reject path stays a leaf.) */
void co_rx_dispatch(co_node_t *node, const co_frame_t *f, uint16_t cob, uint32_t now_us)
{
    const co_rx_slot_t *slot = NULL;
    /* the function code tells which table can hold the COB-ID */
    uint16_t fc = (uint16_t)(1U << (cob >> 7U));

    if ((node->rx_fc & fc) != 0U) {
        slot = rx_find(node, cob);
    }
    if (slot == NULL) {
        if ((node->pdo_fc & fc) != 0U) {
            pdo_rx(node, cob, f, now_us);
        }
        return;
    }
    co_node_clock(node, now_us);
    switch (slot->kind) {
    case CO_RX_NMT:
        co_nmt_rx(node, f);
        break;
    case CO_RX_SDO:
        co_sdo_rx(node, f);
        break;
    case CO_RX_GUARD:
        co_guard_rx(node, f);
        break;
    case CO_RX_HB:
        co_hb_rx(node, slot->arg, f);
        break;
    case CO_RX_SYNC:
        co_sync_rx(node, f);
        break;
    case CO_RX_TIME:
        co_time_rx(node, f);
        break;
    case CO_RX_LSS:
        co_lss_rx(node, f);
        break;
    default:
        break;
    }
}

void co_node_rx(co_node_t *node, const co_frame_t *f, uint32_t now_us)
{
    uint16_t cob;

    if ((f->id & CO_FRAME_EFF) != 0U) {
        return; /* the predefined connection set is 11-bit only */
    }
    cob = (uint16_t)(f->id & 0x7FFU);
    if ((node->rx_filter[(cob & 0x7FU) >> 3U] & (uint8_t)(1U << (cob & 7U))) != 0U) {
        co_rx_dispatch(node, f, cob, now_us);
    }
}

/* ------------------------------------------------------------ timers */

/* The caller's clock jumped ahead by 2^31 us or more since the node last saw
 * it (a stopped process, a paused VM, a debugger): every armed deadline is
 * then in the past, although the wrap-safe comparison would take it for one
 * up to 35 minutes ahead. They all become due now. */
CO_NOINLINE void co_node_stalled(co_node_t *node, uint32_t now_us)
{
    uint16_t n = (uint16_t)(node->dev->n_rpdo + node->dev->n_tpdo);

    node->hb_deadline = now_us;
    node->guard_deadline = now_us;
    node->sync_deadline = now_us;
    node->sync_last = now_us - (uint32_t)CO_HORIZON_US; /* the SYNC window is long closed */
    node->emcy_next = now_us;
    node->sdo.deadline = now_us;
#if CO_LSS
    node->lss.switch_at = now_us;
#endif
    for (uint8_t k = 0U; k < node->n_hb_cons; k++) {
        node->hbc[k].deadline = now_us;
    }
    for (uint16_t i = 0U; i < n; i++) {
        node->pdo[i].timer = now_us;
        node->pdo[i].inhibit = now_us;
    }
}

uint32_t co_node_process(co_node_t *node, uint32_t now_us)
{
    uint32_t next = CO_NO_DEADLINE;

    co_node_clock(node, now_us);
    tx_drain(node);
    next = co_lss_process(node, next);
    if (node->node_id == CO_NODE_ID_UNCONFIGURED) {
        return next; /* LSS init: no other service runs */
    }
    next = co_sdo_process(node, next);
    next = co_hb_process(node, next);
    next = co_emcy_process(node, next);
    next = co_sync_process(node, next);
    next = co_rpdo_process(node, next);
    next = co_tpdo_process(node, next);
    if (node->txq_len > 0U) {
        /* TX path still full: look again in a millisecond */
        next = co_deadline_min(now_us, next, now_us + 1000U);
    }
    if ((next != CO_NO_DEADLINE) && !co_time_reached(next, now_us)) {
        next = now_us; /* never a deadline before the time given */
    }
    return next;
}

/* -------------------------------------------------------------- init */

co_err_t co_node_init(co_node_t *node, const co_node_config_t *cfg, uint32_t now_us)
{
    uint8_t id;

    if ((cfg == NULL) || (cfg->dev == NULL) || (cfg->ram == NULL) || (cfg->hal.ops == NULL) ||
        (cfg->hal.ops->send == NULL) || (cfg->dev->od == NULL)) {
        return CO_ERR_OD_MISSING;
    }
    if (((cfg->dev->n_rpdo + cfg->dev->n_tpdo) != 0U) &&
        ((cfg->dev->pdo == NULL) || (cfg->pdo == NULL) || (cfg->pdo_rx == NULL))) {
        return CO_ERR_OD_MISSING;
    }
    id = ((cfg->dev->options & CO_OPT_LSS_ONLY) != 0U) ? CO_NODE_ID_UNCONFIGURED : cfg->node_id;
    if (((id < 1U) || (id > 127U)) &&
        ((id != CO_NODE_ID_UNCONFIGURED) || ((cfg->dev->options & CO_OPT_LSS) == 0U))) {
        return CO_ERR_VALUE;
    }
    (void)memset(node, 0, sizeof *node);
    node->dev = cfg->dev;
    node->hal = cfg->hal;
    node->ram = (uint8_t *)cfg->ram;
    node->hooks = cfg->hooks;
    node->cb = cfg->cb;
    node->node_id = id;
    node->pending_id = id;
    node->cob_base = id;
    node->sdo_timeout_us = (cfg->sdo_timeout_us != 0U) ? cfg->sdo_timeout_us : 1000000UL;
    node->pdo = cfg->pdo;
    node->pdo_rx = cfg->pdo_rx;
    node->now = now_us;
    co_lss_init(node); /* an LSS-stored node-ID replaces cfg->node_id */
    co_store_reset(node, CO_RESET_NODE); /* defaults, then the stored set */
    if (co_nmt_take_nodeid(node)) {
        co_store_reset(node, CO_RESET_NODE); /* the stored node-ID: its $NODEID defaults */
    }
    if (co_comm_bind(node) != CO_OK) {
        return CO_ERR_DEV_INCOMPAT;
    }
    co_nmt_boot(node);
    return CO_OK;
}

co_nmt_state_t co_node_nmt_state(const co_node_t *node)
{
    return (co_nmt_state_t)node->nmt;
}

uint8_t co_node_id(const co_node_t *node)
{
    return node->node_id;
}

static bool id_valid(const co_node_t *node, uint8_t id)
{
    return ((id >= 1U) && (id <= 127U)) ||
           ((id == CO_NODE_ID_UNCONFIGURED) && co_lss_enabled(node));
}

co_err_t co_node_set_id(co_node_t *node, uint8_t id, uint32_t now_us)
{
    if (!id_valid(node, id)) {
        return CO_ERR_VALUE;
    }
    co_node_clock(node, now_us);
    node->pending_id = id;
    if ((node->node_id == CO_NODE_ID_UNCONFIGURED) && (id != CO_NODE_ID_UNCONFIGURED)) {
        co_nmt_reset(node, CO_RESET_NODE); /* out of LSS init: initialise now */
    }
    return CO_OK;
}

uint8_t co_node_cob_base_for(const co_node_t *node, uint8_t id)
{
    if ((id == CO_NODE_ID_UNCONFIGURED) || (node->node_id == CO_NODE_ID_UNCONFIGURED) ||
        !co_opt(node, CO_OPT_LSS_KEEP_COBS)) {
        return id; /* CiA 305: the COB-IDs follow the node-ID */
    }
    return node->cob_base; /* valid to valid: the PDO and EMCY COB-IDs stay */
}

co_reset_t co_node_take_id(co_node_t *node, co_reset_t kind)
{
    uint8_t from = node->node_id;
    uint8_t to = node->pending_id;

    if (from == to) {
        return kind;
    }
    node->cob_base = co_node_cob_base_for(node, to);
    node->node_id = to;
    if ((from != CO_NODE_ID_UNCONFIGURED) || (to == CO_NODE_ID_UNCONFIGURED)) {
        return kind;
    }
    if (co_opt(node, CO_OPT_LSS_KEEP_COBS)) {
        co_store_forget_comm(node); /* the communication settings start from defaults */
    }
    return CO_RESET_NODE; /* the node was never initialised with an ID */
}
