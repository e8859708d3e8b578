/*
 * EMCY producer: active errors, error register 0x1001, pre-defined error
 * field 0x1003, COB-ID 0x1014 and inhibit time 0x1015.
 */
#include <string.h>

#include "co/co_endian.h"
#include "co_priv.h"

/* 0x1001: the OR of the active errors' bits, each with the generic bit
 * (CiA 301), or with CO_ERREG_GENERIC_UNCLASSIFIED the generic bit only for an
 * error that names no other bit. */
static uint8_t errreg_now(const co_node_t *node)
{
    bool generic = (CO_SET(node, emcy.generic_bit) == CO_ERREG_GENERIC_ALWAYS);
    uint8_t r = 0U;

    for (uint32_t i = node->emcy.n_active; i > 0U; i--) {
        uint8_t bits = node->emcy.active_reg[i - 1U];
        r |= (uint8_t)(bits | (((bits == 0U) || generic) ? CO_ERREG_GENERIC : 0U));
    }
    return r;
}

/* 0x1001 brought up to date; its value (also without a 0x1001). */
static uint8_t update_errreg(co_node_t *node)
{
    uint8_t r = errreg_now(node);

    co_ram_end(node)[CO_RAM_END_1001] = r; /* (unused without 0x1001) */
    return r;
}

/* 0x1014 (co_node.h, CO_RAM_1014: 0 without the object) */
static uint32_t emcy_cob(const co_node_t *node)
{
    return co_ram_cob(node, CO_RAM_1014);
}

/* The CAN-ID EMCYs go out on, 0 while none may go: in Stopped, with the
 * COB-ID not valid, and while unconfigured. */
static uint32_t emcy_id(const co_node_t *node)
{
    uint32_t cob = emcy_cob(node);

    if (cob == 0U) {
        cob = 0x80UL + node->node_id; /* (no 0x1014) */
    }

    if ((node->nmt == (uint8_t)CO_NMT_STOPPED) || ((cob & CO_COB_B31) != 0U) ||
        co_node_unconfigured(node)) {
        cob = 0U;
    }
    return cob & 0x7FFUL;
}

static uint32_t inhibit_us(const co_node_t *node)
{
    return co_dict_us(co_ram_u16(node, CO_RAM_1015), 100UL); /* (0 without 0x1015) */
}

/* The waiting EMCYs go out, oldest first, as far as the inhibit time and
 * the TX path let them (more than one only when the inhibit time is 0); the
 * others wait for the service's timer, or, one the TX path refused, for its
 * next run (every co_node_process while a frame waits, co_node_tx_ready):
 * an EMCY leaves the queue when it is sent (or dropped: none may go). The
 * oldest is q[0]; the others move up when it leaves (at most
 * CO_EMCY_QUEUE_LEN - 1 copies of 8 bytes, for no index of the oldest).
 * Within the inhibit time of the last EMCY: co_node_t.emcy_next is at most one inhibit
 * time (< 6.6 s) ahead of now while it runs; any other distance is a time
 * in the past, however long ago. (co_time_reached alone would take a last
 * EMCY more than 2^31 us ago for one in the future and hold the next one
 * back for up to 35 minutes.) Returns the earlier of @p next and the time
 * the oldest waiting EMCY may go (the service's timer: without storage
 * drain is the service's process entry itself). */
static uint32_t drain(co_node_t *node, uint32_t next)
{
    co_emcy_t *m = &node->emcy;
    uint32_t inhibit = inhibit_us(node);

    while (m->n_q > 0U) {
        uint32_t left = node->emcy_next - node->now;
        co_frame_t f;
        if ((left != 0U) && (left <= inhibit)) {
            break; /* inhibited */
        }
        f.id = emcy_id(node);
        f.dlc = 8U;
        (void)memcpy(f.data, m->q[0].data, 8U);
        if (f.id == 0U) {
            node->tx_hold &= (uint8_t)~CO_TXH_EMCY; /* dropped: it waits no more */
        } else if (!co_tx_try(node, CO_TXH_EMCY, &f)) {
            return next; /* the TX path: no timer, the node runs the service again */
        } else {
            /* sent */
        }
        m->n_q--;
        for (uint32_t k = 0U; k < m->n_q; k++) {
            (void)memcpy(m->q[k].data, m->q[k + 1U].data, 8U);
        }
        node->emcy_next = node->now + inhibit;
    }
    return (m->n_q > 0U) ? co_deadline_min(node->now, next, node->emcy_next) : next;
}

/* An EMCY (@p code, 0x1001 now, the manufacturer bytes or zeros) joins the
 * queue, built in its place there (lost when the queue is full), and goes
 * out at once when nothing is ahead of it and no inhibit time runs. */
static void send_code(co_node_t *node, uint16_t code, const uint8_t *mfr)
{
    co_emcy_t *m = &node->emcy;

    if (emcy_id(node) == 0U) {
        return; /* no EMCY in Stopped; not valid; nothing while unconfigured */
    }
    if (m->n_q < CO_EMCY_QUEUE_LEN) {
        uint8_t *d = m->q[m->n_q].data;
        (void)memset(d, 0, 8U);
        if (mfr != NULL) {
            co_copy(&d[3], mfr, 5U);
        }
        co_put_u16(d, code);
        d[2] = update_errreg(node);
        m->n_q++;
    }
    (void)drain(node, 0U);
}

/* The history grows by one while 0x1003 has an entry n + 1 at its place
 * after the n recorded (its depth, looked up when an error comes: no byte
 * of RAM for it; without 0x1003 sub 1 the depth is 0: its count stays 0,
 * unused). */
static void history_push(co_node_t *node, uint16_t code, const uint8_t *mfr)
{
    uint8_t *end = co_ram_end(node);
    uint8_t n = end[CO_RAM_END_1003];
    uint32_t carry;

    if ((n < 254U) && (co_od_ram_of(node, 0x1003U, (uint8_t)(n + 1U), CO_UNSIGNED32) ==
                       &end[CO_RAM_END_1003_1 + (4U * n)])) {
        n++;
    }
    /* bits 0..15 error code, 16..31 additional information (mfr bytes 0..1;
     * none with CO_HISTORY_CODE_ONLY) */
    carry = code;
    if ((mfr != NULL) && (CO_SET(node, emcy.history) == CO_HISTORY_CODE_AND_INFO)) {
        carry |= (uint32_t)co_get_u16(mfr) << 16U;
    }
    /* newest first: the others move one down, each carried (a plain copy
     * loop becomes a call of the C library's memmove, 252 bytes of
     * newlib-nano) */
    for (uint8_t i = 0U; i < n; i++) {
        uint8_t *at = &end[CO_RAM_END_1003_1 + (4U * i)];
        uint32_t older;
        (void)memcpy(&older, at, 4U);
        (void)memcpy(at, &carry, 4U);
        carry = older;
    }
    end[CO_RAM_END_1003] = n;
}

/* The slot of active error @p code + 1, 0 when it is not active (the
 * active codes differ: searched from the last). */
CO_NOINLINE static uint32_t active_at(const co_node_t *node, uint16_t code)
{
    uint32_t i = node->emcy.n_active;

    while ((i > 0U) && (node->emcy.active_code[i - 1U] != code)) {
        i--;
    }
    return i;
}

void co_emcy_raise(co_node_t *node, uint16_t code, uint8_t reg_bits, const uint8_t *mfr)
{
    uint8_t filled[5];
    const uint8_t *data = mfr;

    if ((active_at(node, code) != 0U) || (code == CO_EMCY_NO_ERROR)) {
        return;
    }
    if (node->emcy.n_active < CO_EMCY_ACTIVE_MAX) {
        node->emcy.active_code[node->emcy.n_active] = code;
        node->emcy.active_reg[node->emcy.n_active] = reg_bits;
        node->emcy.n_active++;
    }
    (void)update_errreg(node);
    if ((data == NULL) && (CO_CB(node, emcy_mfr) != NULL)) {
        /* the device fills the manufacturer bytes of the core's own EMCYs */
        (void)memset(filled, 0, sizeof filled);
        node->cb->emcy_mfr(node->cb->ctx, node, code, filled);
        data = filled;
    }
    history_push(node, code, data);
    co_svc_touch_all(node); /* the queue, and what reacts to errors */
    send_code(node, code, data);
    if (CO_SET(node, emcy.state_pair) != 0U) {
        send_code(node, CO_EMCY_NO_ERROR, NULL);
    }
}

void co_emcy_clear(co_node_t *node, uint16_t code)
{
    co_emcy_t *m = &node->emcy;
    uint32_t i = active_at(node, code);

    if (i == 0U) {
        return;
    }
    i--;
    m->n_active--;
    m->active_code[i] = m->active_code[m->n_active];
    m->active_reg[i] = m->active_reg[m->n_active];
    (void)update_errreg(node);
    co_svc_touch_all(node);
    if ((m->n_active == 0U) || (CO_SET(node, emcy.reset) == CO_EMCY_RESET_EACH_CLEAR)) {
        send_code(node, CO_EMCY_NO_ERROR, NULL);
    }
}

bool co_emcy_is_active(const co_node_t *node, uint16_t code)
{
    return active_at(node, code) != 0U;
}

#if CO_STORAGE
static uint32_t emcy_process(co_node_t *node, uint32_t next)
{
    if ((node->emcy.store_report != 0U) && !co_store_damaged(node)) {
        /* a save or restore wrote a whole parameter set */
        node->emcy.store_report = 0U;
        co_emcy_clear(node, CO_EMCY_STORE_DAMAGED);
    }
    return drain(node, next);
}
#endif

/* ------------------------------------------------------------ service */

/* (its objects: at their places in the RAM image, co_node.h's CO_RAM_*;
 * the depth of the history: co_binds[], co_services.c) */

/* Leaving Initialising, after the boot-up frame. */
static void emcy_booted(co_node_t *node)
{
    static const uint16_t ended[4] = {CO_EMCY_HB_GUARD, CO_EMCY_PDO_SHORT, CO_EMCY_PDO_LONG,
                                      CO_EMCY_RPDO_TIMEOUT};
    uint32_t cob = emcy_cob(node);

    if ((CO_SET(node, nmt.boot_emcy) != 0U) && (cob != 0U) && ((cob & CO_COB_B31) == 0U)) {
        /* through the queue (the queue starts empty: CO_SVC_START), error
         * register 0 */
        co_emcy_t *m = &node->emcy;
        uint8_t *d = m->q[m->n_q].data;
        (void)memset(d, 0, 8U);
        if (node->dev->boot_emcy_data != NULL) {
            co_copy(&d[3], node->dev->boot_emcy_data, 5U);
        }
        m->n_q++;
        (void)drain(node, 0U);
    }
    /* Heartbeat consumers, life guarding and RPDO monitoring started over
     * (their CO_SVC_START reset), so an EMCY 0x8130 of a producer or master
     * lost before the reset, or an RPDO error, has nothing left to clear it.
     * CiA 301 is silent; we end them here, after the boot-up (the first frame
     * after a reset) and in Pre-operational, where EMCY may be sent. No-op
     * after a node reset (no active errors) and at init. */
    for (const uint16_t *c = ended; c != &ended[4]; c++) {
        co_emcy_clear(node, *c);
    }
    /* the newest parameter set was damaged: an older one or the defaults
     * were loaded (co_store.c); reported until a save writes a whole one */
#if CO_STORAGE
    if (co_store_damaged(node)) {
        node->emcy.store_report = 1U;
        co_emcy_raise(node, CO_EMCY_STORE_DAMAGED, 0U, NULL);
    }
#endif
}

/* A reset node has no active errors; the communication starts over with an
 * empty queue and no inhibit time running. */
static void emcy_event(co_node_t *node, uint8_t kind)
{
    if (kind == (uint8_t)CO_RESET_NODE) {
        node->emcy.n_active = 0U;
#if CO_STORAGE
        node->emcy.store_report = 0U;
#endif
    } else if (kind == CO_SVC_START) {
        node->emcy.n_q = 0U;
        node->emcy_next = node->now;
        (void)update_errreg(node);
    } else if (kind == CO_SVC_BOOTED) {
        emcy_booted(node);
    } else {
        /* reset communication keeps the active errors */
    }
}

/* 0x1003: entries beyond the number of recorded errors hold no data; only
 * 0 may be written to sub0, which clears the history. 0x1014: the CAN-ID is
 * fixed while the EMCY is valid (bit 31 = 0). */
co_err_t co_emcy_obj(co_node_t *node, uint8_t op, const co_od_entry_t *e,
                     const co_od_sub_t *s, const uint8_t *data, uint32_t len)
{
    co_emcy_t *m = &node->emcy;
    uint8_t sub = s->sub;
    co_err_t err = CO_OK;

    (void)len;
    if (e->index != 0x1003U) {
        /* 0x1014 / 0x1015 (CO_SVC_SELF): a new COB-ID or inhibit time
         * concerns the service's timer only for an EMCY that waits */
        if (m->n_q > 0U) {
            co_svc_touch(node, CO_ROW_EMCY);
        }
        if ((e->index == 0x1014U) && (len == 4U)) { /* (an UNSIGNED32 at its place) */
            err = co_check_cob(emcy_cob(node), co_get_u32(data), CO_COB_B31 | CO_COB_RSV30);
        }
    } else if (op == (uint8_t)CO_SVC_READ) {
        if (sub > co_ram_end(node)[CO_RAM_END_1003]) { /* (never sub0) */
            err = CO_ERR_NO_DATA;
        }
    } else if ((sub == 0U) && (data[0] != 0U)) { /* checked (an UNSIGNED8) */
        err = CO_ERR_VALUE;
    } else {
        /* 0 written to sub0: the history is empty (entries beyond the
         * number of errors hold no data; the next error is entry 1) */
    }
    return err;
}

const co_service_t co_svc_emcy = {
    emcy_event, NULL,
#if CO_STORAGE
    emcy_process,
#else
    drain, /* (nothing else at its timer) */
#endif
};
