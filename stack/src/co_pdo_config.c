/*
 * PDO configuration: the CiA 301 rules for writing the communication
 * (0x1400+/0x1800+) and mapping (0x1600+/0x1A00+) parameters, mapping
 * validation, the PDO receive table, and what NMT and resets do to PDOs.
 */
#include "co/co_endian.h"
#include "co_priv.h"

#define IDX_RPDO_COMM 0x1400U
#define IDX_RPDO_MAP  0x1600U
#define IDX_TPDO_COMM 0x1800U
#define IDX_TPDO_MAP  0x1A00U
#define PDO_RANGE     0x0200U /* up to 512 PDOs of each kind */

/* Which PDO an index of the PDO parameter area belongs to (0x1400+n RPDO
 * communication, 0x1600+n RPDO mapping, 0x1800+n and 0x1A00+n the TPDO's).
 * Returns false if the index is not a PDO parameter of this device. */
static bool pdo_of(const co_node_t *node, uint16_t index, uint16_t *i, bool *is_map)
{
    const co_dev_t *dev = node->dev;
    uint16_t rel = (uint16_t)(index - IDX_RPDO_COMM);
    uint16_t n = rel & (PDO_RANGE - 1U);
    bool tx = (rel & (IDX_TPDO_COMM - IDX_RPDO_COMM)) != 0U;

    if ((rel >= (4U * PDO_RANGE)) || (n >= (tx ? dev->n_tpdo : dev->n_rpdo))) {
        return false;
    }
    *i = (uint16_t)(tx ? (n + dev->n_rpdo) : n);
    *is_map = (rel & PDO_RANGE) != 0U;
    return true;
}

static bool is_tpdo(const co_node_t *node, uint16_t i)
{
    return i >= node->dev->n_rpdo;
}

/* Whether the PDO engine may copy the mapped object @p s of @p e (row @p m
 * of the mappable-object table) directly between the RAM image and the
 * frame, with the same result as the dictionary's path: a RAM value of its
 * type's size (not ROM, not CO_SUB_HOOKIO; the table has its place), of an
 * entry without a hook slot (a hook bound later finds the PDO going through
 * the dictionary already), mapped in whole bytes (@p bits) at a byte
 * boundary (@p pos; the low bytes of a longer value: a TPDO sends them, an
 * RPDO extends them to the value's size, by the sign for signed types). A
 * TPDO reads it directly when no service reads the object first
 * (CO_SVC_READ) (on a big-endian CPU only when it maps the whole value); an
 * RPDO writes it directly when no service hooks the object at all, the
 * value has no limits and is not a BOOLEAN (the dictionary refuses values
 * above 1). */
static bool direct_ok(const co_od_entry_t *e, const co_od_sub_t *s, const co_od_map_t *m,
                      bool tx, uint32_t bits, uint32_t pos)
{
    uint8_t size = co_type_len(s->type);
    uint8_t svc = co_od_svc_ops(e);
    uint32_t n = bits >> 3U; /* the bytes mapped */

    /* (a COB-ID's 16-bit form, co_od.h CO_SUB_COB16, begins with the low
     * byte of its UNSIGNED32: a TPDO may copy that byte directly) */
    if (co_od_hooked(e) || ((s->flags & (CO_SUB_ROM | CO_SUB_HOOKIO)) != 0U) ||
        ((s->size != size) &&
         !(tx && (n == 1U) && CO_NATIVE_LE && ((s->flags & CO_SUB_COB16) != 0U))) ||
        (CO_PDO_BITWISE && (((pos | bits) & 7U) != 0U)) ||
        (tx ? (((svc & CO_SVC_READ) != 0U) || (!CO_NATIVE_LE && (n != size)))
            : ((svc != 0U) || ((s->flags & CO_SUB_LIMIT) != 0U) ||
               (s->type == (uint8_t)CO_BOOLEAN)))) {
        return false;
    }
    /* a build for speed on a little-endian CPU reads 8 bytes at once
     * (co_pdo_get_direct), which a RAM image of fewer than 16 bytes may
     * not have */
    return !(tx && CO_FAST && CO_NATIVE_LE && ((m->info & CO_OD_MAP_AT_END) != 0U) &&
             ((m->off + n) < 8U));
}

/* Validate the mapping entries of PDO i: the @p n entries at @p map (the
 * mapping as the RAM image holds it, their 16-bit forms), or with @p map
 * NULL the one entry @p n being written (UNSIGNED32). Each entry
 * (index:16 sub:8 bits:8) is a dummy entry (a gap in an RPDO: types
 * BOOLEAN .. UNSIGNED32) or a mappable sub-entry, of any length up to its
 * size (the low bits). They become the state @p p: len, the bytes they
 * cover (0 while the mapping is disabled or invalid), and, for the entries
 * of @p map, CO_PDO_F_DIRECT when there are some and every one may be
 * copied directly (direct_ok; a dummy entry of whole bytes). A PDO with
 * any other entry goes through the dictionary for all of them (a choice per
 * entry would cost RAM in every PDO's state). */
static co_err_t map_state(const co_node_t *node, uint16_t i, const uint8_t *map, uint32_t n,
                          co_pdo_t *p)
{
    const co_dev_t *dev = node->dev;
    bool tx = is_tpdo(node, i);
    uint32_t count = (map != NULL) ? n : 1U;
    uint32_t total = 0U;
    bool direct = map != NULL;
    uint32_t end = 0U;

    p->len = 0U;
    p->flags &= (uint16_t)~(CO_PDO_F_DIRECT | CO_PDO_F_AT_END);
    if (count > dev->pdo[i].map_max) {
        return CO_ERR_MAP_LEN;
    }
    for (uint32_t k = 0U; k < count; k++) {
        uint32_t ref = (map != NULL) ? co_pdo_ref(map, k) : 0U;
        uint32_t v = (map != NULL) ? co_od_map_u32(dev, ref) : n;
        uint16_t index = (uint16_t)(v >> 16U);
        uint8_t sub = (uint8_t)((v >> 8U) & 0xFFU);
        uint32_t bits = v & 0xFFU;
        uint32_t size;

        if ((index >= 0x0001U) && (index <= 0x0007U) && (sub == 0U)) {
            if (tx) {
                return CO_ERR_NO_MAP; /* a TPDO has no gaps */
            }
            size = co_type_len((uint8_t)index);
            direct = direct && ((bits & 7U) == 0U);
        } else {
            const co_od_entry_t *e = NULL;
            co_od_sub_t s;
            co_err_t err = co_od_lookup(node, index, sub, &e, &s);
            if (err != CO_OK) {
                return (err == CO_ERR_NO_SUB) ? CO_ERR_NO_MAP : CO_ERR_NO_OBJECT;
            }
            size = co_type_len(s.type);
            if ((size == 0U) || ((s.flags & (tx ? CO_SUB_MAP_T : CO_SUB_MAP_R)) == 0U)) {
                return CO_ERR_NO_MAP;
            }
            if (direct) {
                const co_od_map_t *m = co_pdo_row(dev, ref);
                direct = direct_ok(e, &s, m, tx, bits, total);
                end |= CO_FAST ? (m->info & CO_OD_MAP_AT_END) : 0U;
            }
        }
        if ((bits == 0U) || (bits > (size * 8U))) {
            return CO_ERR_PARAM_INCOMPAT;
        }
        if (((bits & 7U) != 0U) &&
            ((CO_PDO_BITWISE == 0) || (CO_SET(node, pdo.granularity) == CO_PDO_MAP_BYTES))) {
            return CO_ERR_NO_MAP; /* granularity 8 (or a build without bit mapping): whole bytes */
        }
        total += bits;
    }
    if (total > 64U) {
        return CO_ERR_MAP_LEN;
    }
    p->len = (uint8_t)((total + 7U) / 8U); /* (0 for no entries: disabled) */
    p->flags |= (uint16_t)((direct && (total != 0U))
                               ? (CO_PDO_F_DIRECT | ((end != 0U) ? CO_PDO_F_AT_END : 0U))
                               : 0U);
    return CO_OK;
}

/* PDO i's state from its mapping as the RAM image holds it (map_state). */
static void remap(co_node_t *node, uint16_t i)
{
    (void)map_state(node, i, co_pdo_map(node, &node->dev->pdo[i]), co_pdo_count(node, i),
                    &co_pdo_st(node)[i]);
}

/* A write of sub @p sub of PDO i's mapping (@p is_map) or communication
 * record, value @p data (its size already checked by the dictionary: the
 * PDO parameters have their CiA 301 types, co_pdo_desc_t). */
static co_err_t check_write(const co_node_t *node, uint16_t i, bool is_map, uint8_t sub,
                            const uint8_t *data)
{
    const co_pdo_desc_t *d = &node->dev->pdo[i];
    bool tx = is_tpdo(node, i);
    uint32_t cob = co_pdo_cob(node, i);
    bool valid = (cob & CO_PDO_COB_INVALID) == 0U;
    uint32_t v;
    co_pdo_t tmp; /* (a state of its own: the PDO's changes only once written) */

    tmp.flags = 0U;
    if ((CO_SET(node, pdo.parameter_writes) == CO_PDO_WRITES_PREOP) &&
        (node->nmt != (uint8_t)CO_NMT_PRE_OPERATIONAL)) {
        return CO_ERR_STORE_STATE; /* the device configures PDOs in Pre-operational only */
    }
    if (is_map) {
        if (sub > d->map_max) {
            return CO_OK; /* not a mapping entry */
        }
        /* CiA 301 wants the PDO invalid first; some devices only want the
         * node out of Operational (set.pdo.mapping_while_valid) */
        if (valid && ((CO_SET(node, pdo.mapping_while_valid) == 0U) ||
                      (node->nmt == (uint8_t)CO_NMT_OPERATIONAL))) {
            return CO_ERR_STORE_STATE;
        }
        if (sub == 0U) {
            /* a new count is checked against the entries as they stand */
            return map_state(node, i, co_pdo_map(node, d), data[0], &tmp);
        }
        if (co_pdo_count(node, i) != 0U) {
            return CO_ERR_NO_ACCESS; /* entries are fixed while the mapping is enabled */
        }
        /* (the dictionary stores an accepted entry in its 16-bit form) */
        v = co_get_u32(data);
        return (v == 0U) ? CO_OK : map_state(node, i, NULL, v, &tmp);
    }
    if (sub == 1U) {
        /* 29-bit identifiers are not supported; the CAN-ID changes only while
         * invalid (on a device with set.pdo.cob_id_while_valid also while
         * valid: the current one counts as not in use); a valid one is not
         * a restricted one */
        if (CO_SET(node, pdo.cob_id_while_valid) != 0U) {
            cob |= (uint32_t)CO_PDO_COB_INVALID;
        }
        return co_check_cob(cob, co_get_u32(data), CO_PDO_COB_INVALID);
    }
    v = (sub == 3U) ? co_get_u16(data) : data[0];
    if ((sub == 2U) && (v > 240U) && (v < ((tx && CO_PDO_RTR) ? 252U : 254U))) {
        return CO_ERR_VALUE; /* reserved transmission types */
    }
    if (!tx || ((sub != 3U) && (sub != 6U))) {
        return CO_OK; /* event timer, reserved entries: any value */
    }
    if ((sub == 6U) && (v > 240U)) {
        return CO_ERR_VALUE; /* SYNC start value */
    }
    /* inhibit time and SYNC start value change only while invalid */
    return (valid && (v != ((sub == 3U) ? (uint32_t)co_pdo_u16(node, i, d->inhibit)
                                        : (uint32_t)*co_pdo_at(node, i, d->start))))
               ? CO_ERR_VALUE
               : CO_OK;
}

/* Forget what a PDO was doing (errors stay until correct PDOs resume, all
 * go with @p reset), its state anew from its mapping (remap). */
static void restart(co_node_t *node, uint16_t i, bool reset)
{
    co_pdo_t *p = &co_pdo_st(node)[i];

    if (reset) {
        p->flags = 0U;
    }
    remap(node, i);
    p->flags &= (uint16_t)(CO_PDO_F_DIRECT | CO_PDO_F_AT_END | CO_PDO_F_TIMEOUT | CO_PDO_F_SHORT |
                           CO_PDO_F_LONG);
    p->count = 0U;
}

/* After a write: the mapping's number of entries, the COB-ID (the receive
 * table changes), the transmission type or the event timer restart the PDO. */
static void pdo_written(co_node_t *node, uint16_t i, bool is_map, uint8_t sub)
{
    if ((is_map && (sub == 0U)) || (!is_map && ((sub == 1U) || (sub == 2U) || (sub == 5U)))) {
        if (!is_map && (sub == 1U)) {
            co_rx_invalidate(node);
        }
        restart(node, i, false);
    }
}

/* An NMT state change: every PDO starts over (restart: buffered synchronous
 * data and pending transmissions are dropped, the state from the mapping
 * anew), event-driven TPDOs send their current data once on entering
 * Operational. Leaving Initialising (a reset: co_node.c's boot, the only
 * change from that state), the PDOs also lose their error states (no reset
 * entry of their own: the PDOs do nothing before). */
static void pdo_nmt(co_node_t *node, bool booted)
{
    uint32_t n = (uint32_t)node->dev->n_rpdo + node->dev->n_tpdo;

    for (uint32_t i = 0U; i < n; i++) {
        restart(node, (uint16_t)i, booted);
    }
    if (node->nmt == (uint8_t)CO_NMT_OPERATIONAL) {
        (void)co_tpdo_process(node, CO_NO_DEADLINE);
    }
}

static void pdo_rx_slots(co_node_t *node)
{
    /* (PDO frames go to the PDO service directly: co_node_rx) */
    for (uint32_t i = 0U; i < co_pdo_n_rx(node); i++) {
        uint16_t id = co_pdo_rx_cob(node, (uint16_t)i);
        if (id != CO_PDO_RX_NONE) {
            co_rx_accept(node, id,
                         (i < (CO_RX_AT_MANY - CO_RX_AT_PDO)) ? (uint8_t)(CO_RX_AT_PDO + i)
                                                              : CO_RX_AT_MANY);
        }
    }
}

#if CO_PDO_RTR
/* A frame on the COB-ID of PDO @p i (co_node_rx); without CO_PDO_RTR only
 * RPDOs receive, and their frames go to co_rpdo_rx directly. */
static void pdo_rx(co_node_t *node, uint16_t i, const co_frame_t *f)
{
    if (i < node->dev->n_rpdo) {
        co_rpdo_rx(node, i, f);
    } else if (co_frame_is_rtr(f)) {
        co_tpdo_rtr(node, i);
    } else {
        /* another node's data frame on this TPDO's identifier */
    }
}
#endif

co_err_t co_pdo_obj(co_node_t *node, uint8_t op, const co_od_entry_t *e,
                    const co_od_sub_t *s, const uint8_t *data, uint32_t len)
{
    uint16_t i;
    bool is_map;

    (void)len;
    if (!pdo_of(node, e->index, &i, &is_map)) {
        return CO_OK; /* not a PDO the core runs */
    }
    if (op == (uint8_t)CO_SVC_CHECK) {
        return check_write(node, i, is_map, s->sub, data);
    }
    pdo_written(node, i, is_map, s->sub);
    return CO_OK;
}

static void pdo_event(co_node_t *node, uint8_t ev)
{
    if (ev == CO_SVC_SLOTS) {
        pdo_rx_slots(node);
    } else if (ev >= CO_SVC_NMT) {
        pdo_nmt(node, ev == CO_SVC_BOOTED);
    } else {
        /* nothing to do */
    }
}

const co_service_t co_svc_pdo = {
    pdo_event,
#if CO_PDO_RTR
    pdo_rx,
#else
    co_rpdo_rx, /* only RPDOs receive */
#endif
    co_tpdo_process,
};
