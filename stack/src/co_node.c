/*
 * The node: initialisation, receive dispatch by COB-ID, timers, the TX path.
 */
#include <stddef.h>
#include <string.h>

#include "co_priv.h"

/* ------------------------------------------------------------------ TX */

static uint32_t run_rows(co_node_t *node, uint16_t run, uint32_t next);

static bool hal_send(co_node_t *node, const co_frame_t *f)
{
    return node->hal.ops->send(node->hal.ctx, f) == 0;
}

#if !CO_FAST
bool co_tx_now(co_node_t *node, const co_frame_t *f)
{
    return (node->tx_hold == 0U) && hal_send(node, f);
}
#endif

bool co_tx_try(co_node_t *node, uint8_t bit, const co_frame_t *f)
{
    bool sent = ((node->tx_hold & ((uint32_t)bit - 1U)) == 0U) && hal_send(node, f);

    node->tx_hold = (uint8_t)(sent ? (node->tx_hold & ~(uint32_t)bit) : (node->tx_hold | bit));
    return sent;
}

/* The frames the node makes itself (CO_TXH_SDO and the bits above it), in
 * their order as long as the HAL takes them, none while a SYNC or an EMCY
 * waits: the held answers from their slots, the boot-up (the state
 * Initialising, 0x00), a heartbeat (the NMT state now) and a guarding reply
 * (the toggle bit and the NMT state now; the toggle changes with each reply
 * that goes out). */
static void tx_tail(co_node_t *node)
{
    uint32_t bit = CO_TXH_SDO;

    while ((bit <= CO_TXH_LAST) && ((node->tx_hold & (bit - 1U)) == 0U)) {
        if ((node->tx_hold & bit) != 0U) {
            co_frame_t f;
            f.id = 0x700UL + node->node_id;
            f.dlc = 1U;
            (void)memset(f.data, 0, sizeof f.data);
            if ((bit & CO_TXH_ANSWERS) != 0U) {
                f.id = ((CO_LSS == 0) || (bit == CO_TXH_SDO)) ? (0x580UL + node->node_id)
                                                              : CO_LSS_TX_ID;
                f.dlc = 8U;
                (void)memcpy(f.data, node->tx_answer[CO_TX_ANSWER_SLOT(bit)], 8U);
            } else if (bit != CO_TXH_BOOT) {
                f.data[0] = node->nmt;
#if CO_NODE_GUARDING
                if (bit == CO_TXH_GUARD) {
                    f.data[0] |= node->errctl.guard_toggle;
                }
#endif
            } else {
                /* the boot-up: 0x00 */
            }
            if (!hal_send(node, &f)) {
                break;
            }
            node->tx_hold &= (uint8_t)~bit;
#if CO_NODE_GUARDING
            if (bit == CO_TXH_GUARD) {
                node->errctl.guard_toggle ^= 0x80U;
            }
#endif
        }
        bit <<= 1U;
    }
}

void co_tx_hold(co_node_t *node, uint8_t bit, const uint8_t *answer)
{
    if (answer != NULL) {
        (void)memcpy(node->tx_answer[CO_TX_ANSWER_SLOT(bit)], answer, 8U);
    }
    node->tx_hold |= bit;
    tx_tail(node);
}

void co_node_tx_ready(co_node_t *node, uint32_t now_us)
{
    co_node_clock(node, now_us);
    /* the services' timers, as an extra co_node_process would: the SYNC
     * and the EMCYs that wait go out, then what the node makes itself; a
     * stream stalled on the full TX path (SDO block upload) goes on */
    tx_tail(node);
    (void)run_rows(node, CO_SVC_ALL, CO_NO_DEADLINE);
    tx_tail(node);
    co_svc_touch_all(node); /* their deadlines, taken anew by co_node_process */
}

/* A COB-ID write (CiA 301 7.5.2), for the services' checks. */
co_err_t co_check_cob(uint32_t cur, uint32_t v, uint32_t rule)
{
    uint32_t use_bits = rule & CO_COB_USE;
    uint32_t reserved = ((rule & CO_COB_RSV30) != 0U) ? 0x40000000U : 0U;
    bool always = (rule & CO_COB_ALWAYS) != 0U;
    /* in use: a bit of use_bits set, or (!CO_COB_WHEN_SET) the one bit clear */
    uint32_t flip = ((rule & CO_COB_WHEN_SET) != 0U) ? 0U : use_bits;
    bool cur_used;
    bool new_used;

    if ((v & (0x3FFFF800UL | reserved)) != 0U) {
        return CO_ERR_VALUE;
    }
    cur_used = ((cur ^ flip) & use_bits) != 0U;
    /* (bits 31 and 30 of @p v where the form of @p cur has them) */
    new_used = (((v >> 16U) ^ flip) & use_bits) != 0U;
    if (cur_used && new_used && ((v & 0x7FFUL) != (cur & 0x7FFUL))) {
        return CO_ERR_VALUE;
    }
    if ((new_used || always) && co_cob_restricted(v & 0x7FFUL)) {
        return CO_ERR_VALUE;
    }
    return CO_OK;
}

/* ------------------------------------------------------- RX dispatch */


void co_rx_add(co_node_t *node, uint16_t cob, uint8_t svc)
{
    uint8_t i = node->n_rx;

    if (i >= CO_RX_SLOTS_MAX) {
        return;
    }
    node->rx[i] = (uint16_t)(cob | ((uint16_t)svc << CO_RX_ROW_SHIFT));
    node->n_rx++;
    co_rx_accept(node, cob, (uint8_t)(i + 1U));
}

/* The rows of co_services[] that run: all, or only LSS while unconfigured. */
static uint8_t services_running(const co_node_t *node)
{
    return co_node_unconfigured(node) ? CO_SVC_UNCONFIGURED_ROWS : CO_N_SERVICES;
}

/* Event @p ev (CO_SVC_*) to the services in table order: to all of them,
 * CO_SVC_SLOTS to the running ones. A reset (CO_RESET_NODE: all of the RAM
 * image, CO_RESET_COMMUNICATION: the communication area) restores the
 * values to their defaults first (the store service then loads the stored
 * set over them). */
static void services_walk(co_node_t *node, uint8_t ev)
{
    uint32_t rows = (ev == CO_SVC_SLOTS) ? services_running(node) : CO_N_SERVICES;

    if ((ev == (uint8_t)CO_RESET_NODE) || (ev == (uint8_t)CO_RESET_COMMUNICATION)) {
        co_od_restore(node, (ev == (uint8_t)CO_RESET_NODE) ? node->dev->ram_size
                                                           : node->dev->comm_end);
    }

    for (uint32_t k = 0U; k < rows; k++) {
        void (*fn)(co_node_t *, uint8_t) = co_services[k]->event;
        if (fn != NULL) {
            fn(node, ev);
        }
    }
}

/* Until the table is rebuilt, every frame goes the way of a function code
 * with several slots and finds the table stale: the first one rebuilds it
 * (co_node_rx). */
void co_rx_invalidate(co_node_t *node)
{
    node->n_rx |= CO_RX_STALE;
    (void)memset(node->rx_at, (int)CO_RX_AT_MANY, sizeof node->rx_at);
}

/* Every running service adds its slots, in table order; then the port hears of the
 * new set (its hardware filters). */
void co_rx_rebuild(co_node_t *node)
{
    node->n_rx = 0U;
    (void)memset(node->rx_at, (int)CO_RX_AT_NONE, sizeof node->rx_at);
    services_walk(node, CO_SVC_SLOTS);
    if (CO_CB(node, rx_set) != NULL) {
        node->cb->rx_set(node->cb->ctx, node);
    }
}

/* The PDOs that may receive (co_pdo_rx_cob), none while the PDO service
 * does not run (an unconfigured node). */
static uint16_t pdo_n_rx(const co_node_t *node)
{
    return co_node_unconfigured(node) ? 0U : co_pdo_n_rx(node);
}

bool co_node_rx_cob(const co_node_t *node, uint16_t i, uint16_t *cob)
{
    uint16_t k = node->n_rx & (uint16_t)~CO_RX_STALE; /* (a stale table: as the port has it) */

    if (i < k) {
        *cob = (uint16_t)(node->rx[i] & 0x7FFU);
        return true;
    }
    /* then the PDOs that receive one */
    for (uint16_t p = 0U; p < pdo_n_rx(node); p++) {
        uint16_t id = co_pdo_rx_cob(node, p);
        if (id == CO_PDO_RX_NONE) {
            continue;
        }
        if (k == i) {
            *cob = id;
            return true;
        }
        k++;
    }
    return false;
}

/* The frame to the service of row @p kind (the row of a receive slot for
 * its COB-ID): a frame for any other service than SYNC makes it run at the
 * next co_node_process. */
CO_HOT void rx_svc(co_node_t *node, const co_frame_t *f, uint8_t kind, uint32_t now_us)
{
    /* its timers may have changed (a SYNC received changes none: the
     * producer's run from its own period) */
    node->svc_run |= (co_svc_bits_t)(((kind != CO_ROW_SYNC) ? 1U : 0U) << kind);
    co_node_clock(node, now_us);
    co_services[kind]->rx(node, 0U, f);
}

/* The frame to the PDO service, PDO @p i's (its COB-ID). */
CO_HOT void rx_pdo(co_node_t *node, const co_frame_t *f, uint16_t i, uint32_t now_us)
{
    co_node_clock(node, now_us);
    co_svc_pdo.rx(node, i, f); /* (known: called directly) */
}

/* A search of the services' slots, then the PDOs', and the frame to the
 * first one for @p cob. */
#if CO_FAST
CO_NOINLINE
#endif
static void rx_search(co_node_t *node, const co_frame_t *f, uint16_t cob, uint32_t now_us)
{
    co_rx_settle(node); /* a frame that came while the table was out of date */
    for (uint32_t k = 0U; k < node->n_rx; k++) {
        uint16_t slot = node->rx[k];
        if ((slot & 0x7FFU) == cob) {
            rx_svc(node, f, (uint8_t)(slot >> CO_RX_ROW_SHIFT), now_us);
            return;
        }
    }
    for (uint16_t i = 0U; i < pdo_n_rx(node); i++) {
        if (co_pdo_rx_cob(node, i) == cob) {
            rx_pdo(node, f, i, now_us);
            return;
        }
    }
}

/* A build for speed: the function code's only slot, if it is for the
 * frame's COB-ID, or a search where it has several (out of line: the
 * frames of a function code with one slot then save no registers for a
 * call they do not make). A build for size: a search for every function
 * code with a slot (a few comparisons more per frame, one path instead of
 * two). */
void co_node_rx(co_node_t *node, const co_frame_t *f, uint32_t now_us)
{
    uint16_t cob;
    uint16_t at;

    if ((f->id & CO_FRAME_EFF) != 0U) {
        return; /* the predefined connection set is 11-bit only */
    }
    cob = (uint16_t)(f->id & 0x7FFU);
    at = node->rx_at[cob >> 7U];
    if (at == CO_RX_AT_NONE) {
        return; /* not for this node */
    }
    if (!CO_FAST || (at == CO_RX_AT_MANY)) {
        rx_search(node, f, cob, now_us);
        return;
    }
    if (at <= CO_RX_SLOTS_MAX) {
        uint16_t slot = node->rx[at - 1U];
        if ((slot & 0x7FFU) != cob) {
            return;
        }
        rx_svc(node, f, (uint8_t)(slot >> CO_RX_ROW_SHIFT), now_us);
        return;
    }
    if (co_pdo_rx_cob(node, (uint16_t)(at - CO_RX_AT_PDO)) != cob) {
        return;
    }
    rx_pdo(node, f, (uint16_t)(at - CO_RX_AT_PDO), now_us);
}

/* ------------------------------------------------------------ timers */

/* The caller's clock jumped ahead by 2^31 us or more since the node last saw
 * it (a stopped process, a paused VM, a debugger): every armed deadline is
 * then in the past, although the wrap-safe comparison would take it for one
 * up to 35 minutes ahead. They all become due now. */
CO_NOINLINE void co_node_stalled(co_node_t *node, uint32_t now_us)
{
    uint16_t n = (uint16_t)(node->dev->n_rpdo + node->dev->n_tpdo);

    /* the next heartbeat due now (the last one long past: then the cycle
     * starts over from now) */
    node->errctl.hb_last = now_us - (uint32_t)CO_HORIZON_US;
    /* every heartbeat consumer's deadline has come (co_hb.c: hbc_advance
     * finds 2^21 units passed) */
    node->errctl.hbc_base = now_us - (uint32_t)CO_HORIZON_US;
#if CO_NODE_GUARDING
    node->errctl.guard_deadline = now_us;
#endif
#if CO_SYNC_PRODUCER
    node->sync.deadline = now_us;
#endif
    node->sync.last = now_us - (uint32_t)CO_HORIZON_US; /* the SYNC window is long closed */
    node->emcy_next = now_us;
    node->sdo.deadline = now_us;
    co_svc_touch_all(node);
#if CO_LSS
    node->lss.switch_at = now_us;
#endif
    for (uint32_t i = 0U; i < n; i++) {
        co_pdo_st(node)[i].at = now_us - (uint32_t)CO_HORIZON_US; /* every PDO time has ended */
    }
}

#if !CO_FAST
void co_node_clock(co_node_t *node, uint32_t now_us)
{
    co_node_clock_at(node, now_us);
}
#endif

/* The services that run now: every one once the earliest deadline they
 * returned has come (or the TX path holds frames back), else only those
 * with something new and, while event-driven TPDOs detect changes, the PDO
 * service. An idle call costs a comparison. */
static uint16_t services_due(co_node_t *node, uint32_t now_us)
{
    uint16_t run;

    if ((node->tx_hold != 0U) ||
        ((node->due != CO_NO_DEADLINE) && co_time_reached(now_us, node->due))) {
        co_svc_touch_all(node);
    }
    run = node->svc_run;
#if CO_TPDO_CHANGE
    if (node->pdo_poll != 0U) {
        run |= (uint16_t)(1U << CO_ROW_PDO);
    }
#endif
    return run;
}

/* The rows of @p run (and those touched meanwhile by a row before them),
 * in table order; then once more the rows touched during that pass before
 * their turn (what is touched after that runs at the next call). Returns
 * the earlier of @p next and their deadlines. */
static uint32_t run_rows(co_node_t *node, uint16_t run, uint32_t next)
{
    uint8_t rows = services_running(node);

    uint16_t todo = run;
    uint32_t due = next;

    for (uint32_t pass = 0U; (pass < 2U) && (todo != 0U); pass++) {
        node->svc_run = 0U;
        for (uint32_t k = 0U; (k < rows) && ((((uint32_t)todo | node->svc_run) >> k) != 0U); k++) {
            if (((((uint32_t)todo | node->svc_run) >> k) & 1U) != 0U) {
                node->svc_run &= (co_svc_bits_t)~(1U << k);
                if (co_services[k]->process != NULL) {
                    due = co_services[k]->process(node, due);
                }
            }
        }
        todo = node->svc_run;
    }
    return due;
}

uint32_t co_node_process(co_node_t *node, uint32_t now_us)
{
    uint32_t next;
    uint16_t run;

    co_node_clock(node, now_us);
    co_rx_settle(node); /* COB-IDs the application changed since */
    if (node->tx_hold != 0U) {
        tx_tail(node); /* what waits before what the services make now */
    }
    run = services_due(node, now_us);
    next = node->due;
    if (run != 0U) {
        /* an earlier deadline than the cached one comes from the rows that run */
        if (run == CO_SVC_ALL) {
            next = (uint32_t)CO_NO_DEADLINE;
        }
        next = run_rows(node, run, next);
        if (node->tx_hold != 0U) {
            /* the services' frames first (an EMCY before a held answer) */
            tx_tail(node);
        }
        if (node->tx_hold != 0U) {
            /* TX path still full: look again in a millisecond */
            next = co_deadline_min(now_us, next, now_us + 1000U);
        }
        node->due = next;
    }
    if ((next != CO_NO_DEADLINE) && !co_time_reached(next, now_us)) {
        next = now_us; /* never a deadline before the time given */
    }
    return next;
}

/* ------------------------------------------------------------ NMT */

void co_node_set_state(co_node_t *node, co_nmt_state_t st)
{
    uint8_t from = node->nmt;

    if (from == (uint8_t)st) {
        return;
    }
    node->nmt = (uint8_t)st;
    co_svc_touch_all(node);
    services_walk(node, (from == (uint8_t)CO_NMT_INITIALISING) ? CO_SVC_BOOTED : CO_SVC_NMT);
    if (CO_CB(node, nmt_state) != NULL) {
        node->cb->nmt_state(node->cb->ctx, node, st);
    }
}

static void services_reset(co_node_t *node, uint8_t kind)
{
    services_walk(node, kind);
}

/* Initialising: the communication services start from their reset values,
 * the boot-up frame goes out, and the node enters Pre-operational. */
static void boot(co_node_t *node)
{
    node->nmt = (uint8_t)CO_NMT_INITIALISING;
    services_walk(node, CO_SVC_START);
    co_rx_invalidate(node);
    /* the producers' frames that waited are made anew from the state they
     * start over from (a held answer still goes) */
    node->tx_hold &= (uint8_t)CO_TXH_ANSWERS;
    if (co_node_unconfigured(node)) {
        return; /* LSS init: no boot-up, no NMT until a valid node-ID */
    }
    if (CO_SET(node, nmt.bootup) == CO_BOOTUP_FRAME) {
        /* the boot-up: one byte, the state Initialising (0x00) */
        co_tx_hold(node, CO_TXH_BOOT, NULL);
    }
    co_node_set_state(node, CO_NMT_PRE_OPERATIONAL);
}

/* A device with a node-ID object (co_dev_t.nodeid_index): take the node-ID
 * from it when it holds another valid one; true if it changed. */
static bool take_nodeid(co_node_t *node)
{
    const uint8_t *v;

    /* (a manufacturer's deviation: without CO_PERSONALITY such a device is
     * refused at init) */
    if ((CO_PERSONALITY == 0) || (node->dev->nodeid_index == 0U)) {
        return false;
    }
    v = (const uint8_t *)co_od_value_ptr(node, node->dev->nodeid_index, 0U);
    if ((v == NULL) || (*v < 1U) || (*v > 127U) || (*v == node->node_id)) {
        return false;
    }
    co_node_keep_cob_base(node, co_node_cob_base_for(node, *v));
    node->node_id = *v;
    node->pending_id = *v;
    return true;
}

/* Reset communication restores the communication area, reset node all of
 * the image, each to defaults and then to the stored set (0x1010): the
 * services' reset of that kind. Where the objects live does not change, so
 * what the services' bind found at init stays valid. A device with a
 * node-ID object takes its node-ID from it first ($NODEID defaults follow
 * it); after a node reset that object has its stored value, so the image is
 * restored again if the node-ID changes. */
CO_NOINLINE static void reset(co_node_t *node, co_reset_t kind_asked)
{
    /* a new node-ID (LSS, co_node_set_id) takes effect here (CiA 305) */
    co_reset_t kind = co_node_take_id(node, kind_asked);

    if (kind == CO_RESET_COMMUNICATION) {
        (void)take_nodeid(node);
        services_reset(node, (uint8_t)kind);
    } else {
        services_reset(node, (uint8_t)kind);
        if (take_nodeid(node)) {
            services_reset(node, (uint8_t)kind);
        }
    }
    if (CO_CB(node, nmt_reset) != NULL) {
        node->cb->nmt_reset(node->cb->ctx, node, kind);
    }
    boot(node);
}

/* Execute NMT command @p cs: the application's notice first (the node still
 * in its old state; only when the command changes the state or resets),
 * then the state change or the reset. Unknown command specifiers are
 * ignored (CiA 301 defines no answer). */
void co_node_nmt_exec(co_node_t *node, uint8_t cs)
{
    uint8_t to;

    if (cs == (uint8_t)CO_NMT_CMD_START) {
        to = (uint8_t)CO_NMT_OPERATIONAL;
    } else if (cs == (uint8_t)CO_NMT_CMD_STOP) {
        to = (uint8_t)CO_NMT_STOPPED;
    } else if (cs == (uint8_t)CO_NMT_CMD_PRE_OPERATIONAL) {
        to = (uint8_t)CO_NMT_PRE_OPERATIONAL;
    } else if ((cs == (uint8_t)CO_NMT_CMD_RESET_NODE) ||
               (cs == (uint8_t)CO_NMT_CMD_RESET_COMMUNICATION)) {
        to = (uint8_t)CO_NMT_INITIALISING; /* a reset */
    } else {
        return;
    }
    if (((to == (uint8_t)CO_NMT_INITIALISING) || (node->nmt != to)) &&
        (CO_CB(node, nmt_command) != NULL)) {
        node->cb->nmt_command(node->cb->ctx, node, cs);
    }
    if (to != (uint8_t)CO_NMT_INITIALISING) {
        co_node_set_state(node, (co_nmt_state_t)to);
    } else {
        reset(node, (cs == (uint8_t)CO_NMT_CMD_RESET_NODE) ? CO_RESET_NODE
                                                           : CO_RESET_COMMUNICATION);
    }
}

void co_node_nmt_command(co_node_t *node, uint8_t cs, uint32_t now_us)
{
    co_node_clock(node, now_us);
    co_node_nmt_exec(node, cs);
    co_rx_settle(node);
}

/* -------------------------------------------------------------- init */

/* The services find their objects: the core objects of co_binds[] (their
 * hooks are const: co_svc_hooks), a device with the objects of a service
 * this build leaves out refused; then LSS its stored configuration. */
static co_result_t bind_services(co_node_t *node)
{
    for (uint32_t k = 0U; k < CO_N_BINDS; k++) {
        const co_bind_t *b = &co_binds[k];
        uint16_t index = (uint16_t)(0x1000U + b->index);
        uint8_t type = (uint8_t)(b->spec & 0x1FU);
        uint8_t kind = (uint8_t)(b->spec & CO_BIND_KIND);
        uint8_t *at = &((uint8_t *)node)[b->at];
        void *v;
        if (kind >= CO_BIND_LEN) {
            *at = co_od_array_len(node, index, type,
                                  (kind == CO_BIND_LEN) ? 254U : (uint8_t)CO_HB_CONSUMERS_MAX);
            continue;
        }
        if (kind == CO_BIND_NONE) {
            if (co_od_find(node->dev->od, node->dev->od_count, index) != NULL) {
                return CO_RESULT_DEV_INCOMPAT;
            }
            continue;
        }
        v = co_od_ram_of(node, index, ((b->spec & CO_BIND_SUB1) != 0U) ? 1U : 0U, type);
        (void)memcpy(at, &v, sizeof v);
    }
#if CO_LSS
    co_services[0]->event(node, CO_SVC_BIND); /* (its row: the first) */
#endif
#if !CO_PERSONALITY && !CO_LSS
    if (node->dev->nodeid_index != 0U) {
        return CO_RESULT_DEV_INCOMPAT; /* a deviation this build leaves out */
    }
#elif !CO_PERSONALITY
    {
        /* every setting 0 (CiA 301) but lss.slave where the build has LSS:
         * a service, not a deviation; and without block SDO (CO_SDO_BLOCK=0)
         * "no block", which such a core does anyway (odgen/build.py says the
         * same) */
        const uint8_t *b = (const uint8_t *)&node->dev->set;
        uint32_t any = node->dev->nodeid_index;
        for (size_t k = 0U; k < sizeof node->dev->set; k++) {
            bool cia = ((CO_LSS != 0) && (k == offsetof(co_settings_t, lss.slave))) ||
                       ((CO_SDO_BLOCK == 0) && (k == offsetof(co_settings_t, sdo.refused)) &&
                        (b[k] == CO_SDO_XFER_BLOCK));
            any |= cia ? 0U : b[k];
        }
        if (any != 0U) {
            return CO_RESULT_DEV_INCOMPAT; /* a deviation this build leaves out */
        }
    }
#elif !CO_LSS
    if (node->dev->set.lss.slave != 0U) {
        return CO_RESULT_DEV_INCOMPAT;
    }
#endif
#if !CO_LIMITS
    if (node->dev->limits != NULL) {
        return CO_RESULT_DEV_INCOMPAT;
    }
#endif
    return CO_RESULT_OK;
}

co_result_t co_node_init(co_node_t *node, const co_node_config_t *cfg, uint32_t now_us)
{
    co_result_t r;
    uint8_t id;

    if ((cfg == NULL) || (cfg->dev == NULL) || (cfg->ram == NULL) || (cfg->hal.ops == NULL) ||
        (cfg->hal.ops->send == NULL) || (cfg->dev->od == NULL)) {
        return CO_RESULT_BAD_CONFIG;
    }
    if (((cfg->dev->n_rpdo + cfg->dev->n_tpdo) != 0U) &&
        (cfg->dev->pdo == NULL)) {
        return CO_RESULT_BAD_CONFIG;
    }
    /* (an LSS slave: a build without LSS refuses it, CO_RESULT_DEV_INCOMPAT) */
#if CO_LSS
    id = (cfg->dev->set.lss.node_id == CO_LSS_ID_ONLY) ? CO_NODE_ID_UNCONFIGURED : cfg->node_id;
    if (((id < 1U) || (id > 127U)) &&
        ((id != CO_NODE_ID_UNCONFIGURED) || (cfg->dev->set.lss.slave == 0U))) {
        return CO_RESULT_BAD_NODE_ID;
    }
#else
    id = cfg->node_id;
    if ((id < 1U) || (id > 127U)) {
        return CO_RESULT_BAD_NODE_ID;
    }
#endif
    (void)memset(node, 0, sizeof *node);
    /* dev, hal, ram, cb: the first fields of both, in the same places
     * (test_services: test_config_head) */
    (void)memcpy(node, cfg, offsetof(co_node_config_t, node_id));
    (void)memset(&node->ram[cfg->dev->hooks_at], 0,
                 (size_t)cfg->dev->n_hooks * sizeof(co_od_hook_t));
    node->node_id = id;
    node->pending_id = id;
    co_node_keep_cob_base(node, id);
    node->sdo.timeout_ms = (cfg->sdo_timeout_ms != 0U) ? cfg->sdo_timeout_ms : 1000U;
    node->now = now_us;
    node->svc_run = CO_SVC_ALL;
    r = bind_services(node); /* LSS first: an LSS-stored node-ID replaces cfg->node_id */
    if (r != CO_RESULT_OK) {
        return r;
    }
    services_reset(node, (uint8_t)CO_RESET_NODE); /* defaults, then the stored set */
    if (take_nodeid(node)) {
        services_reset(node, (uint8_t)CO_RESET_NODE); /* the stored node-ID: its $NODEID defaults */
    }
    boot(node);
    co_rx_settle(node); /* the receive set, told to the port */
    return CO_RESULT_OK;
}

co_nmt_state_t co_node_nmt_state(const co_node_t *node)
{
    return (co_nmt_state_t)node->nmt;
}

uint32_t co_node_now(const co_node_t *node)
{
    return node->now;
}

uint8_t co_node_id(const co_node_t *node)
{
    return node->node_id;
}

uint8_t co_node_bit_timing(const co_node_t *node)
{
#if CO_LSS
    return node->lss.active_bt;
#else
    (void)node;
    return 0xFFU;
#endif
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
    if (co_node_unconfigured(node) && (id != CO_NODE_ID_UNCONFIGURED)) {
        reset(node, CO_RESET_NODE); /* out of LSS init: initialise now */
        co_rx_settle(node);
    }
    return CO_OK;
}

uint8_t co_node_cob_base_for(const co_node_t *node, uint8_t id)
{
    if ((id == CO_NODE_ID_UNCONFIGURED) || (node->node_id == CO_NODE_ID_UNCONFIGURED) ||
        (CO_SET(node, lss.cob_ids) != CO_LSS_COBS_KEEP)) {
        return id; /* CiA 305: the COB-IDs follow the node-ID */
    }
    return co_node_cob_base(node); /* valid to valid: the PDO and EMCY COB-IDs stay */
}

co_reset_t co_node_take_id(co_node_t *node, co_reset_t kind)
{
    uint8_t from = node->node_id;
    uint8_t to = node->pending_id;

    if (from == to) {
        return kind;
    }
    co_node_keep_cob_base(node, co_node_cob_base_for(node, to));
    node->node_id = to;
    if ((CO_LSS == 0) || (from != CO_NODE_ID_UNCONFIGURED) || (to == CO_NODE_ID_UNCONFIGURED)) {
        return kind;
    }
    if (CO_SET(node, lss.cob_ids) == CO_LSS_COBS_KEEP) {
        co_store_forget_comm(node); /* the communication settings start from defaults */
    }
    return CO_RESET_NODE; /* the node was never initialised with an ID */
}
