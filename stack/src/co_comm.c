/*
 * The communication objects the core itself owns: where they live, the
 * CiA 301 rules for writing them, and what a write sets in motion.
 */
#include <string.h>

#include "co/co_endian.h"
#include "co_priv.h"

static void *ram_of(co_node_t *node, uint16_t index, uint8_t sub, uint8_t type)
{
    const co_od_entry_t *e = co_od_find(node->dev->od, node->dev->od_count, index);
    const co_od_sub_t *s = (e != NULL) ? co_od_find_sub(e, sub) : NULL;

    if ((s == NULL) || (s->type != type) || ((s->flags & (CO_SUB_ROM | CO_SUB_HOOKIO)) != 0U)) {
        return NULL;
    }
    return &node->ram[s->off];
}

/* Number of consecutive sub-entries 1..n of an array whose values are stored
 * back to back, or 0 if the layout is not usable by the core. */
static uint8_t array_len(const co_node_t *node, uint16_t index, uint8_t type, uint8_t max)
{
    const co_od_entry_t *e = co_od_find(node->dev->od, node->dev->od_count, index);
    uint8_t n = 0U;

    if (e == NULL) {
        return 0U;
    }
    for (uint8_t k = 1U; (k < e->nsubs) && (n < max); k++) {
        const co_od_sub_t *s = &e->subs[k];
        if ((s->sub != k) || (s->type != type) ||
            ((s->flags & (CO_SUB_ROM | CO_SUB_HOOKIO)) != 0U) ||
            (s->off != (uint16_t)(e->subs[1].off + ((uint16_t)(k - 1U) * co_type_len(type))))) {
            break;
        }
        n++;
    }
    return n;
}

/* A device that needs a service or option this build leaves out
 * (co_config.h) is refused. */
static co_err_t check_build(const co_node_t *node)
{
    co_err_t err = CO_OK;

#if CO_OPTIONS != 0xFFFFFFFFUL
    if ((node->dev->options & ~(uint32_t)CO_OPTIONS) != 0U) {
        err = CO_ERR_DEV_INCOMPAT;
    }
#endif
#if !CO_TIME
    if (node->time_cob != NULL) {
        err = CO_ERR_DEV_INCOMPAT;
    }
#endif
#if !CO_SYNC_PRODUCER
    if (node->sync_period != NULL) {
        err = CO_ERR_DEV_INCOMPAT;
    }
#endif
#if !CO_ERROR_BEHAVIOUR
    if (co_od_find(node->dev->od, node->dev->od_count, 0x1029U) != NULL) {
        err = CO_ERR_DEV_INCOMPAT;
    }
#endif
#if !CO_LSS
    if ((node->dev->options & CO_OPT_LSS) != 0U) {
        err = CO_ERR_DEV_INCOMPAT;
    }
#endif
#if !CO_LIMITS
    if (node->dev->limits != NULL) {
        err = CO_ERR_DEV_INCOMPAT;
    }
#endif
    (void)node;
    return err;
}

co_err_t co_comm_bind(co_node_t *node)
{
    node->errreg = (uint8_t *)ram_of(node, 0x1001U, 0U, (uint8_t)CO_UNSIGNED8);
    node->hist_count = (uint8_t *)ram_of(node, 0x1003U, 0U, (uint8_t)CO_UNSIGNED8);
    node->hist_depth = (node->hist_count != NULL)
                           ? array_len(node, 0x1003U, (uint8_t)CO_UNSIGNED32, 254U)
                           : 0U;
    node->hist = (node->hist_depth != 0U)
                     ? (uint32_t *)ram_of(node, 0x1003U, 1U, (uint8_t)CO_UNSIGNED32)
                     : NULL;
    node->sync_cob = (uint32_t *)ram_of(node, 0x1005U, 0U, (uint8_t)CO_UNSIGNED32);
    node->sync_period = (uint32_t *)ram_of(node, 0x1006U, 0U, (uint8_t)CO_UNSIGNED32);
    node->sync_window = (uint32_t *)ram_of(node, 0x1007U, 0U, (uint8_t)CO_UNSIGNED32);
    node->time_cob = (uint32_t *)ram_of(node, 0x1012U, 0U, (uint8_t)CO_UNSIGNED32);
    node->sync_overflow = (uint8_t *)ram_of(node, 0x1019U, 0U, (uint8_t)CO_UNSIGNED8);
    node->guard_time = (uint16_t *)ram_of(node, 0x100CU, 0U, (uint8_t)CO_UNSIGNED16);
    node->life_factor = (uint8_t *)ram_of(node, 0x100DU, 0U, (uint8_t)CO_UNSIGNED8);
    node->emcy_cob = (uint32_t *)ram_of(node, 0x1014U, 0U, (uint8_t)CO_UNSIGNED32);
    node->emcy_inhibit = (uint16_t *)ram_of(node, 0x1015U, 0U, (uint8_t)CO_UNSIGNED16);
    node->n_hb_cons = array_len(node, 0x1016U, (uint8_t)CO_UNSIGNED32,
                                (uint8_t)CO_HB_CONSUMERS_MAX);
    node->hb_cons = (node->n_hb_cons != 0U)
                        ? (uint32_t *)ram_of(node, 0x1016U, 1U, (uint8_t)CO_UNSIGNED32)
                        : NULL;
    node->hb_prod = (uint16_t *)ram_of(node, 0x1017U, 0U, (uint8_t)CO_UNSIGNED16);
    return check_build(node);
}

static co_err_t check_hb_consumer(const co_node_t *node, uint8_t sub, uint32_t v)
{
    uint8_t id = (uint8_t)((v >> 16U) & 0xFFU);
    uint16_t t = (uint16_t)(v & 0xFFFFU);

    if ((v & 0xFF000000UL) != 0U) {
        return CO_ERR_VALUE;
    }
    if ((t == 0U) || (id == 0U)) {
        return CO_OK; /* entry not used */
    }
    if (id > 127U) {
        return CO_ERR_VALUE;
    }
    /* CiA 301: one producer may be monitored by one entry only. */
    for (uint8_t k = 0U; k < node->n_hb_cons; k++) {
        uint32_t o = node->hb_cons[k];
        if (((uint8_t)(k + 1U) != sub) && (((o >> 16U) & 0xFFU) == id) && ((o & 0xFFFFU) != 0U)) {
            return CO_ERR_PARAM_INCOMPAT;
        }
    }
    return CO_OK;
}

/* A COB-ID write (CiA 301 7.5.2): 29-bit identifiers are not supported,
 * bits 11..28 are 0, @p reserved bits must be 0, and the CAN-ID may not change
 * while the object is in use: in use is any of @p use_bits set (@p use_when_set)
 * or all of them clear (!use_when_set, the EMCY 'valid' bit). A CAN-ID in use
 * (or @p always in use, the SYNC consumer) may not be a restricted one
 * (CiA 301 7.3.5). */
static co_err_t check_cob(uint32_t cur, uint32_t v, uint32_t use_bits, bool use_when_set,
                          uint32_t reserved, bool always)
{
    bool cur_used = use_when_set ? ((cur & use_bits) != 0U) : ((cur & use_bits) == 0U);
    bool new_used = use_when_set ? ((v & use_bits) != 0U) : ((v & use_bits) == 0U);

    if (((v & 0x20000000UL) != 0U) || ((v & 0x1FFFF800UL) != 0U) || ((v & reserved) != 0U)) {
        return CO_ERR_VALUE;
    }
    if (cur_used && new_used && ((v & 0x7FFUL) != (cur & 0x7FFUL))) {
        return CO_ERR_VALUE;
    }
    if ((new_used || always) && co_cob_restricted(v & 0x7FFUL)) {
        return CO_ERR_VALUE;
    }
    return CO_OK;
}

co_err_t co_comm_check_write(const co_node_t *node, uint16_t index, uint8_t sub,
                             const uint8_t *data, uint32_t len)
{
    if ((index < 0x1000U) || (index > 0x1FFFU)) {
        return CO_OK;
    }
    if (index >= 0x1400U) {
        return co_pdo_check_write(node, index, sub, data, len);
    }
    switch (index) {
    case 0x1003U:
        /* only 0 may be written to sub0: it clears the history */
        if ((sub == 0U) && (len == 1U) && (data[0] != 0U)) {
            return CO_ERR_VALUE;
        }
        break;
    case 0x1005U:
        /* SYNC: the CAN-ID is fixed while this node produces SYNC (bit 30) */
        if ((sub == 0U) && (len == 4U) && (node->sync_cob != NULL)) {
            return check_cob(*node->sync_cob, co_get_u32(data), 0x40000000UL, true, 0U, true);
        }
        break;
    case 0x1006U:
        /* communication cycle period: within the timer horizon (2^31 us) */
        if ((sub == 0U) && (len == 4U) && (co_get_u32(data) > CO_HORIZON_US)) {
            return CO_ERR_VALUE_HIGH;
        }
        break;
    case 0x1012U:
        /* TIME: the CAN-ID is fixed while consumed or produced (bits 31, 30) */
        if ((sub == 0U) && (len == 4U) && (co_time_cob(node) != NULL)) {
            return check_cob(*co_time_cob(node), co_get_u32(data), 0xC0000000UL, true, 0U,
                             false);
        }
        break;
    case 0x1014U:
        /* EMCY: the CAN-ID is fixed while the EMCY is valid (bit 31 = 0) */
        if ((sub == 0U) && (len == 4U) && (node->emcy_cob != NULL)) {
            return check_cob(*node->emcy_cob, co_get_u32(data), 0x80000000UL, false,
                             0x40000000UL, false);
        }
        break;
    case 0x100CU:
    case 0x100DU:
        /* guarding and heartbeat exclusive: guarding refused while heartbeat runs */
        if (co_opt(node, CO_OPT_GUARD_HB_EXCLUSIVE) && (node->hb_prod != NULL) &&
            (*node->hb_prod != 0U)) {
            return CO_ERR_RESOURCE;
        }
        break;
    case 0x1019U:
        /* counter overflow: 0 or 2..240, and only while no SYNC period is set */
        if ((sub == 0U) && (len == 1U)) {
            if ((data[0] == 1U) || (data[0] > 240U)) {
                return CO_ERR_VALUE;
            }
            if ((node->sync_period != NULL) && (*node->sync_period != 0U)) {
                return CO_ERR_STORE_STATE;
            }
        }
        break;
    case 0x1016U:
        if ((sub > 0U) && (len == 4U) && (sub <= node->n_hb_cons)) {
            return check_hb_consumer(node, sub, co_get_u32(data));
        }
        break;
#if CO_ERROR_BEHAVIOUR
    case 0x1029U:
        /* error behaviour: 0..2, 0x80..0xFF manufacturer-specific; 3..0x7F reserved */
        if ((sub > 0U) && (len == 1U) && (data[0] >= 3U) && (data[0] <= 0x7FU)) {
            return CO_ERR_VALUE;
        }
        break;
#endif
    default:
        break;
    }
    return CO_OK;
}

void co_comm_written(co_node_t *node, uint16_t index, uint8_t sub)
{
    switch (index) {
    case 0x1003U:
        if (sub == 0U) {
            co_emcy_history_clear(node);
        }
        break;
    case 0x100CU:
    case 0x100DU:
        /* Life guarding is re-armed with the new life time by the next
         * guarding request. A lost state is kept: that request must still end
         * the error (co_hb_process ends it if life guarding is now off). */
        if (node->guard_state == 1U) { /* armed */
            node->guard_state = 0U;
        }
        break;
    case 0x1016U:
        if ((sub > 0U) && (sub <= node->n_hb_cons)) {
            node->hbc[sub - 1U].state = 0U; /* this entry starts over (co_hb.c) */
            co_hb_consumers_changed(node);
        }
        break;
    case 0x1017U:
        co_hb_producer_changed(node);
        break;
    case 0x1005U:
    case 0x1006U:
    case 0x1012U:
    case 0x1019U:
        co_sync_reset(node);
        co_rx_rebuild(node);
        break;
    default:
        co_pdo_written(node, index, sub);
        break;
    }
}
