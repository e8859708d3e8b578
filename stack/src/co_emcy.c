/*
 * EMCY producer: active errors, error register 0x1001, pre-defined error
 * field 0x1003, COB-ID 0x1014 and inhibit time 0x1015.
 */
#include <string.h>

#include "co/co_endian.h"
#include "co_priv.h"

/* 0x1001: the OR of the active errors' bits, each with the generic bit
 * (CiA 301), or with CO_OPT_ERREG_NO_GENERIC the generic bit only for an
 * error that names no other bit. */
static uint8_t errreg_now(const co_node_t *node)
{
    bool generic = !co_opt(node, CO_OPT_ERREG_NO_GENERIC);
    uint8_t r = 0U;

    for (uint8_t i = 0U; i < node->n_active; i++) {
        uint8_t bits = node->active[i].reg;
        r |= (uint8_t)(bits | (((bits == 0U) || generic) ? CO_ERREG_GENERIC : 0U));
    }
    return r;
}

static void update_errreg(co_node_t *node)
{
    if (node->errreg != NULL) {
        *node->errreg = errreg_now(node);
    }
}

static uint32_t cob_id(const co_node_t *node)
{
    return (node->emcy_cob != NULL) ? *node->emcy_cob : (0x80UL + node->node_id);
}

static uint32_t inhibit_us(const co_node_t *node)
{
    return (node->emcy_inhibit != NULL) ? co_dict_us(*node->emcy_inhibit, 100UL) : 0U;
}

/* Still within the inhibit time of the last EMCY? emcy_next is at most one
 * inhibit time (< 6.6 s) ahead of now while it runs; any other distance is a
 * time in the past, however long ago. (co_time_reached alone would take a
 * last EMCY more than 2^31 us ago for one in the future and hold the next
 * one back for up to 35 minutes.) */
static bool inhibited(const co_node_t *node)
{
    uint32_t left = node->emcy_next - node->now;

    return (left != 0U) && (left <= inhibit_us(node));
}

static void send(co_node_t *node, const uint8_t *d)
{
    uint32_t cob = cob_id(node);

    if ((node->nmt == (uint8_t)CO_NMT_STOPPED) || ((cob & 0x80000000UL) != 0U) ||
        (node->node_id == CO_NODE_ID_UNCONFIGURED)) {
        return; /* no EMCY in Stopped; not valid; nothing while unconfigured */
    }
    if ((node->n_emcy_q > 0U) || inhibited(node)) {
        if (node->n_emcy_q < CO_EMCY_QUEUE_LEN) {
            (void)memcpy(node->emcy_q[node->n_emcy_q].data, d, 8U);
            node->n_emcy_q++;
        }
        return;
    }
    co_tx(node, cob & 0x7FFUL, d, 8U);
    node->emcy_next = node->now + inhibit_us(node);
}

static void send_code(co_node_t *node, uint16_t code, const uint8_t *mfr)
{
    uint8_t d[8] = {0};

    co_put_u16(d, code);
    d[2] = (node->errreg != NULL) ? *node->errreg : errreg_now(node);
    if (mfr != NULL) {
        (void)memcpy(&d[3], mfr, 5U);
    }
    send(node, d);
}

static void history_push(co_node_t *node, uint16_t code, const uint8_t *mfr)
{
    uint8_t n;

    if ((node->hist == NULL) || (node->hist_count == NULL)) {
        return;
    }
    n = *node->hist_count;
    if (n < node->hist_depth) {
        n++;
    }
    for (uint8_t i = (uint8_t)(n - 1U); i > 0U; i--) {
        node->hist[i] = node->hist[i - 1U];
    }
    /* bits 0..15 error code, 16..31 additional information (mfr bytes 0..1;
     * none with CO_OPT_HISTORY_CODE_ONLY) */
    node->hist[0] = code;
    if ((mfr != NULL) && !co_opt(node, CO_OPT_HISTORY_CODE_ONLY)) {
        node->hist[0] |= (uint32_t)co_get_u16(mfr) << 16U;
    }
    *node->hist_count = n;
}

void co_emcy_raise(co_node_t *node, uint16_t code, uint8_t reg_bits, const uint8_t *mfr)
{
    uint8_t filled[5];
    const uint8_t *data = mfr;

    if (co_emcy_is_active(node, code) || (code == CO_EMCY_NO_ERROR)) {
        return;
    }
    if (node->n_active < CO_EMCY_ACTIVE_MAX) {
        node->active[node->n_active].code = code;
        node->active[node->n_active].reg = reg_bits;
        node->n_active++;
    }
    update_errreg(node);
    if ((data == NULL) && (node->cb.emcy_mfr != NULL)) {
        /* the device fills the manufacturer bytes of the core's own EMCYs */
        (void)memset(filled, 0, sizeof filled);
        node->cb.emcy_mfr(node->cb.ctx, node, code, filled);
        data = filled;
    }
    history_push(node, code, data);
    send_code(node, code, data);
    if (co_opt(node, CO_OPT_EMCY_STATE_PAIR)) {
        send_code(node, CO_EMCY_NO_ERROR, NULL);
    }
}

void co_emcy_clear(co_node_t *node, uint16_t code)
{
    uint8_t i = 0U;

    while ((i < node->n_active) && (node->active[i].code != code)) {
        i++;
    }
    if (i == node->n_active) {
        return;
    }
    node->n_active--;
    node->active[i] = node->active[node->n_active];
    update_errreg(node);
    if ((node->n_active == 0U) || co_opt(node, CO_OPT_EMCY_RESET_PARTIAL)) {
        send_code(node, CO_EMCY_NO_ERROR, NULL);
    }
}

bool co_emcy_is_active(const co_node_t *node, uint16_t code)
{
    for (uint8_t i = 0U; i < node->n_active; i++) {
        if (node->active[i].code == code) {
            return true;
        }
    }
    return false;
}

void co_emcy_history_clear(co_node_t *node)
{
    if (node->hist != NULL) {
        for (uint8_t i = 0U; i < node->hist_depth; i++) {
            node->hist[i] = 0U;
        }
    }
}

void co_emcy_reset(co_node_t *node)
{
    node->n_emcy_q = 0U;
    node->emcy_next = node->now;
    update_errreg(node);
}

uint32_t co_emcy_process(co_node_t *node, uint32_t next)
{
    /* more than one only when the inhibit time was lowered to 0 meanwhile */
    while ((node->n_emcy_q > 0U) && !inhibited(node)) {
        uint32_t cob = cob_id(node);
        if ((node->nmt != (uint8_t)CO_NMT_STOPPED) && ((cob & 0x80000000UL) == 0U)) {
            co_tx(node, cob & 0x7FFUL, node->emcy_q[0].data, 8U);
        }
        node->n_emcy_q--;
        for (uint8_t i = 0U; i < node->n_emcy_q; i++) {
            node->emcy_q[i] = node->emcy_q[i + 1U];
        }
        node->emcy_next = node->now + inhibit_us(node);
    }
    return (node->n_emcy_q > 0U) ? co_deadline_min(node->now, next, node->emcy_next) : next;
}
