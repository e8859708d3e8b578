/*
 * LSS slave, CiA 305: node-ID and bit timing over the bus.
 *
 * Requests arrive on 0x7E5, answers go out on 0x7E4, always 8 bytes (other
 * lengths and remote frames are not LSS requests and are ignored; CiA 305
 * defines no answer to them, nor to unknown command specifiers).
 *
 * States: waiting (after power-on and reset) and configuration. Switch state
 * global (0x04) sets either for every slave; switch state selective
 * (0x40..0x43, answered by 0x44) and a complete fastscan (0x51) put one slave
 * into configuration. Which request is served where:
 *
 *   both states      0x04 switch global, 0x46..0x4B identify remote slave,
 *                    0x4C identify non-configured remote slave
 *   waiting only     0x40..0x43 switch selective, 0x51 fastscan (unconfigured
 *                    slaves only)
 *   configuration    0x11 configure node-ID, 0x13 configure bit timing,
 *                    0x15 activate bit timing, 0x17 store configuration,
 *                    0x5A..0x5E inquire identity and node-ID
 *
 * A configured node-ID is pending: it becomes active at the next reset
 * communication (co_nmt.c), or, for an unconfigured node, when the master
 * switches the slave back to waiting; the node then initialises and sends
 * its boot-up (co_node.c, co_node_set_id).
 *
 * The stored configuration (node-ID, bit timing, the $NODEID base of the PDO
 * and EMCY COB-IDs) lives behind the parameter banks in the HAL's NV
 * (co_store.c): two records of LSS_REC bytes, each
 *
 *   0 magic "coLS" (u32)   4 sequence number (u32)   8 node-ID
 *   9 COB-ID base         10 bit timing (0xFF none)  11 format (1)
 *  12 reserved (0, u16)   14 CRC-16 over bytes 0..13
 *
 * The valid record with the higher sequence number holds the configuration;
 * a store writes the other one, so a power cut keeps the previous one.
 */
#include <string.h>

#include "co/co_endian.h"
#include "co_crc16.h"
#include "co_priv.h"

#if CO_LSS

#define LSS_RX 0x7E5U
/* (answers on CO_LSS_TX_ID, co_priv.h) */

#define CS_SWITCH_GLOBAL  0x04U
#define CS_CONF_NODE_ID   0x11U
#define CS_CONF_BIT       0x13U
#define CS_ACTIVATE_BIT   0x15U
#define CS_STORE          0x17U
#define CS_SEL_VENDOR     0x40U
#define CS_SEL_SERIAL     0x43U
#define CS_SEL_ANSWER     0x44U
#define CS_IDENT_VENDOR   0x46U
#define CS_IDENT_SER_HIGH 0x4BU
#define CS_IDENT_NONCONF  0x4CU
#define CS_IDENT_SLAVE    0x4FU
#define CS_NONCONF_SLAVE  0x50U
#define CS_FASTSCAN       0x51U
#define CS_INQ_VENDOR     0x5AU
#define CS_INQ_SERIAL     0x5DU
#define CS_INQ_NODE_ID    0x5EU

#define ST_WAITING 0U
#define ST_CONFIG  1U

#define ERR_OK          0U
#define ERR_RANGE       1U /* configure: node-ID out of range / bit timing not supported */
#define ERR_STORE_NONE  1U /* store configuration not supported */
#define ERR_STORE_MEDIA 2U /* storage media access error */

#define FASTSCAN_CONFIRM 0x80U
#define BT_NONE          0xFFU
#define BT_TABLE_SIZE    10U

#define LSS_MAGIC  0x534C6F63UL /* "coLS" */
#define LSS_FORMAT 1U

static void answer(co_node_t *node, uint8_t cs, uint8_t b1, uint8_t b2)
{
    uint8_t d[8] = {0};

    d[0] = cs;
    d[1] = b1;
    d[2] = b2;
    co_tx_hold(node, CO_TXH_LSS, d); /* (on CO_LSS_TX_ID) */
}

static void answer_u32(co_node_t *node, uint8_t cs, uint32_t v)
{
    uint8_t d[8] = {0};

    d[0] = cs;
    co_put_u32(&d[1], v);
    co_tx_hold(node, CO_TXH_LSS, d); /* (on CO_LSS_TX_ID) */
}

/* LSS address part @p k (0 vendor-ID, 1 product code, 2 revision, 3 serial):
 * 0x1018 sub k+1 through the dictionary (a hook or the application may
 * provide it); 0 when the device lacks it. */
static uint32_t address(co_node_t *node, uint8_t k)
{
    uint8_t b[4] = {0};
    uint32_t len = 0U;

    if ((co_od_read(node, 0x1018U, (uint8_t)(k + 1U), b, 4U, &len) != CO_OK) || (len != 4U)) {
        return 0U;
    }
    return co_get_u32(b);
}

/* ------------------------------------------------------ NV records */

static uint32_t rec_addr(const co_node_t *node, uint8_t i)
{
    return co_store_lss_addr(node, i);
}

static bool lss_has_nv(const co_node_t *node)
{
    return (node->hal.ops->nv_read != NULL) && (node->hal.ops->nv_write != NULL);
}

/* Read record @p i: true when valid; *seq and the 3 data bytes are set. */
static bool rec_read(co_node_t *node, uint8_t i, uint32_t *seq, uint8_t data[3])
{
    uint8_t r[CO_LSS_REC];

    if ((node->hal.ops->nv_read(node->hal.ctx, rec_addr(node, i), r, CO_LSS_REC) != 0) ||
        (co_get_u32(&r[0]) != LSS_MAGIC) || (r[11] != LSS_FORMAT) ||
        (co_crc16(0xFFFFU, r, 14U) != co_get_u16(&r[14]))) {
        return false;
    }
    *seq = co_get_u32(&r[4]);
    co_copy(data, &r[8], 3U);
    return true;
}

/* The newest valid record: its index (2: none), sequence number and data. */
static uint8_t rec_newest(co_node_t *node, uint32_t *seq, uint8_t data[3])
{
    uint8_t best = 2U;

    for (uint8_t i = 0U; i < 2U; i++) {
        uint32_t s = 0U;
        uint8_t d[3];
        if (rec_read(node, i, &s, d) && ((best == 2U) || ((int32_t)(s - *seq) > 0))) {
            best = i;
            *seq = s;
            co_copy(data, d, 3U);
        }
    }
    return best;
}

/* Write the configuration as it is now into record node->lss.nv_rec. */
static bool rec_write(co_node_t *node, uint32_t seq)
{
    uint8_t r[CO_LSS_REC] = {0};

    co_put_u32(&r[0], LSS_MAGIC);
    co_put_u32(&r[4], seq);
    r[8] = node->pending_id;
    r[9] = co_node_cob_base_for(node, node->pending_id);
    r[10] = (node->lss.bit_timing != BT_NONE) ? node->lss.bit_timing : node->lss.active_bt;
    r[11] = LSS_FORMAT;
    co_put_u16(&r[14], co_crc16(0xFFFFU, r, 14U));
    return node->hal.ops->nv_write(node->hal.ctx, rec_addr(node, node->lss.nv_rec), r,
                                   CO_LSS_REC) == 0;
}

/* Store configuration: the other record than the newest. On flash
 * (nv_erase) its erase unit is erased first; with an asynchronous HAL
 * (nv_poll) the erase and the write run in the background (lss_process)
 * and the answer comes when the record is durable: ERR_PENDING. */
#define ERR_PENDING 0xFFU
static uint8_t lss_store(co_node_t *node)
{
    const co_hal_ops_t *ops = node->hal.ops;
    uint8_t old[3];
    uint32_t seq = 0U;

    if (!lss_has_nv(node)) {
        return ERR_STORE_NONE;
    }
    if ((node->lss.nv_step != 0U) || co_store_busy(node)) {
        return ERR_STORE_MEDIA; /* the NV is being written (a store or a 0x1010 save) */
    }
    node->lss.nv_rec = (rec_newest(node, &seq, old) == 0U) ? 1U : 0U;
    if ((ops->nv_erase != NULL) &&
        (ops->nv_erase(node->hal.ctx, rec_addr(node, node->lss.nv_rec),
                       co_store_lss_unit(node)) != 0)) {
        return ERR_STORE_MEDIA;
    }
    if ((ops->nv_erase != NULL) && (ops->nv_poll != NULL)) {
        node->lss.nv_step = 1U; /* written when the erase is done */
        return ERR_PENDING;
    }
    if (!rec_write(node, seq + 1U)) {
        return ERR_STORE_MEDIA;
    }
    if (ops->nv_poll != NULL) {
        node->lss.nv_step = 2U;
        return ERR_PENDING;
    }
    return ERR_OK;
}

/* Store configuration on an asynchronous HAL: erase done -> write the
 * record; written -> answer. */
static uint32_t lss_store_process(co_node_t *node, uint32_t next)
{
    int r = node->hal.ops->nv_poll(node->hal.ctx);
    uint8_t err = ERR_OK;

    if (r == CO_NV_BUSY) {
        return co_deadline_min(node->now, next, node->now + 1000U);
    }
    if (r != 0) {
        err = ERR_STORE_MEDIA;
    } else if (node->lss.nv_step == 1U) {
        uint8_t old[3];
        uint32_t seq = 0U;
        (void)rec_newest(node, &seq, old);
        if (rec_write(node, seq + 1U)) {
            node->lss.nv_step = 2U;
            return co_deadline_min(node->now, next, node->now + 1000U);
        }
        err = ERR_STORE_MEDIA;
    } else {
        /* durable */
    }
    node->lss.nv_step = 0U;
    answer(node, CS_STORE, err, 0U);
    return next;
}

/* bind (co_node_init, before any reset): the stored configuration (node-ID,
 * COB-ID base, bit timing); an LSS-stored node-ID replaces the configured one */
static void lss_bind(co_node_t *node)
{
    uint8_t d[3];
    uint32_t seq = 0U;

    (void)memset(&node->lss, 0, sizeof node->lss);
    node->lss.bit_timing = BT_NONE;
    node->lss.active_bt = BT_NONE;
    if (!co_lss_enabled(node) || !lss_has_nv(node) || (rec_newest(node, &seq, d) == 2U)) {
        return;
    }
    if (((d[0] >= 1U) && (d[0] <= 127U)) || (d[0] == CO_NODE_ID_UNCONFIGURED)) {
        node->node_id = d[0];
        node->pending_id = d[0];
        node->cob_base = ((d[1] >= 1U) && (d[1] <= 127U)) ? d[1] : d[0];
    }
    if ((d[2] < BT_TABLE_SIZE) && (node->hal.ops->bit_timing != NULL) &&
        (node->hal.ops->bit_timing(node->hal.ctx, d[2]) == 0)) {
        node->lss.active_bt = d[2];
    }
}

static void lss_reset(co_node_t *node, uint8_t kind)
{
    if (kind == CO_SVC_BIND) {
        lss_bind(node);
        return;
    }
    if (kind == CO_SVC_SLOTS) {
        if (co_lss_enabled(node)) {
            co_rx_add(node, LSS_RX, 0U); /* (its row: the first) */
        }
        return;
    }
    if (kind != CO_SVC_START) {
        return;
    }
    /* every boot leaves LSS in waiting (CiA 305) */
    node->lss.state = ST_WAITING;
    node->lss.sel_step = 0U;
    node->lss.id_step = 0U;
    node->lss.fs_pos = 0U;
}

/* ------------------------------------------------------ requests */

static void switch_global(co_node_t *node, uint8_t mode, uint32_t now)
{
    if (mode == ST_CONFIG) {
        node->lss.state = ST_CONFIG;
    } else if (mode == ST_WAITING) {
        bool was_config = (node->lss.state == ST_CONFIG);
        node->lss.state = ST_WAITING;
        node->lss.sel_step = 0U;
        if (was_config && (node->node_id == CO_NODE_ID_UNCONFIGURED) &&
            (node->pending_id != CO_NODE_ID_UNCONFIGURED)) {
            (void)co_node_set_id(node, node->pending_id, now); /* initialises now */
        }
    } else {
        /* reserved mode: ignored */
    }
}

static void switch_selective(co_node_t *node, uint8_t cs, uint32_t v)
{
    uint8_t k = (uint8_t)(cs - CS_SEL_VENDOR);
    bool match = (v == address(node, k)) ||
                 ((k == 2U) && (CO_SET(node, lss.selective) == CO_LSS_IGNORE_REVISION));

    if (cs == CS_SEL_VENDOR) {
        node->lss.sel_step = 0U; /* a new sequence */
    }
    if (!match || (node->lss.sel_step != k)) {
        node->lss.sel_step = 0U;
        return;
    }
    node->lss.sel_step++;
    if (cs == CS_SEL_SERIAL) {
        node->lss.sel_step = 0U;
        node->lss.state = ST_CONFIG;
        answer(node, CS_SEL_ANSWER, 0U, 0U);
    }
}

/* 0x46 vendor, 0x47 product, 0x48 / 0x49 revision low / high,
 * 0x4A / 0x4B serial low / high: 0x4F when the address is in the ranges. */
static void identify(co_node_t *node, uint8_t cs, uint32_t v)
{
    static const uint8_t part[6] = {0U, 1U, 2U, 2U, 3U, 3U};
    uint8_t step = (uint8_t)(cs - CS_IDENT_VENDOR);
    uint32_t a = address(node, part[step]);
    bool ok;

    if (step < 2U) {
        ok = (a == v);
    } else if ((step & 1U) == 0U) {
        ok = (a >= v); /* low bound */
    } else {
        ok = (a <= v); /* high bound */
    }
    if (cs == CS_IDENT_VENDOR) {
        node->lss.id_step = 0U;
    }
    if (!ok || (node->lss.id_step != step)) {
        node->lss.id_step = 0U;
        return;
    }
    node->lss.id_step++;
    if (cs == CS_IDENT_SER_HIGH) {
        node->lss.id_step = 0U;
        answer(node, CS_IDENT_SLAVE, 0U, 0U);
    }
}

/* Fastscan: IDNumber in bytes 1..4, BitChecked 5, LSSSub 6, LSSNext 7. */
static void fastscan(co_node_t *node, const uint8_t *d)
{
    uint32_t id = co_get_u32(&d[1]);
    uint8_t bit = d[5];
    uint8_t sub = d[6];
    uint8_t next = d[7];

    if ((node->node_id != CO_NODE_ID_UNCONFIGURED) || (node->lss.state != ST_WAITING)) {
        return; /* only unconfigured slaves in waiting take part */
    }
    if (bit == FASTSCAN_CONFIRM) {
        node->lss.fs_pos = 0U;
        answer(node, CS_IDENT_SLAVE, 0U, 0U);
        return;
    }
    if ((bit > 31U) || (sub > 3U) || (next > 3U) || (sub != node->lss.fs_pos)) {
        return;
    }
    if (((id ^ address(node, sub)) & (uint32_t)(0xFFFFFFFFUL << bit)) != 0U) {
        return; /* another slave's number */
    }
    answer(node, CS_IDENT_SLAVE, 0U, 0U);
    if (bit == 0U) {
        /* this part is complete: the next one, or, after the last, configuration */
        if (next < sub) {
            node->lss.state = ST_CONFIG;
        }
        node->lss.fs_pos = next;
    }
}

static void configure_node_id(co_node_t *node, uint8_t id)
{
    if (((id >= 1U) && (id <= 127U)) || (id == CO_NODE_ID_UNCONFIGURED)) {
        node->pending_id = id;
        answer(node, CS_CONF_NODE_ID, ERR_OK, 0U);
    } else {
        answer(node, CS_CONF_NODE_ID, ERR_RANGE, 0U);
    }
}

static void configure_bit_timing(co_node_t *node, uint8_t table, uint8_t index)
{
    uint16_t supported = node->dev->lss_bit_timings;

    if ((table == 0U) && (index < 16U) && (((uint32_t)supported >> index) & 1U) != 0U) {
        node->lss.bit_timing = index;
        answer(node, CS_CONF_BIT, ERR_OK, 0U);
    } else {
        answer(node, CS_CONF_BIT, ERR_RANGE, 0U);
    }
}

static void activate_bit_timing(co_node_t *node, uint16_t delay_ms)
{
    if (node->lss.bit_timing == BT_NONE) {
        return; /* nothing configured to switch to */
    }
    /* CiA 305: wait the switch delay, switch, and send nothing for another
     * switch delay (the port's bus is quiet meanwhile: the master's job) */
    node->lss.switch_at = node->now + ((uint32_t)delay_ms * 1000U);
    node->lss.switching = 1U;
}

static void inquire(co_node_t *node, uint8_t cs)
{
    if (cs == CS_INQ_NODE_ID) {
        answer(node, CS_INQ_NODE_ID, node->node_id, 0U);
    } else {
        answer_u32(node, cs, address(node, (uint8_t)(cs - CS_INQ_VENDOR)));
    }
}

/* Requests served in the configuration state only. */
static void rx_config(co_node_t *node, const uint8_t *d)
{
    uint8_t cs = d[0];

    if (cs == CS_CONF_NODE_ID) {
        configure_node_id(node, d[1]);
    } else if (cs == CS_CONF_BIT) {
        configure_bit_timing(node, d[1], d[2]);
    } else if (cs == CS_ACTIVATE_BIT) {
        activate_bit_timing(node, co_get_u16(&d[1]));
    } else if (cs == CS_STORE) {
        uint8_t err = lss_store(node);
        if (err != ERR_PENDING) {
            answer(node, CS_STORE, err, 0U);
        }
    } else if ((cs >= CS_INQ_VENDOR) && (cs <= CS_INQ_NODE_ID)) {
        inquire(node, cs);
    } else {
        /* not a configuration request */
    }
}

static void lss_rx(co_node_t *node, uint16_t arg, const co_frame_t *f)
{
    const uint8_t *d = f->data;
    uint8_t cs = d[0];

    (void)arg;
    if (co_frame_is_rtr(f) || (f->dlc != 8U)) {
        return;
    }
    if (cs == CS_SWITCH_GLOBAL) {
        switch_global(node, d[1], node->now);
    } else if ((cs >= CS_IDENT_VENDOR) && (cs <= CS_IDENT_SER_HIGH)) {
        identify(node, cs, co_get_u32(&d[1]));
    } else if (cs == CS_IDENT_NONCONF) {
        if ((node->node_id == CO_NODE_ID_UNCONFIGURED) &&
            (node->pending_id == CO_NODE_ID_UNCONFIGURED)) {
            answer(node, CS_NONCONF_SLAVE, 0U, 0U);
        }
    } else if (node->lss.state == ST_WAITING) {
        if ((cs >= CS_SEL_VENDOR) && (cs <= CS_SEL_SERIAL)) {
            switch_selective(node, cs, co_get_u32(&d[1]));
        } else if (cs == CS_FASTSCAN) {
            fastscan(node, d);
        } else {
            /* configuration requests are not served in waiting */
        }
    } else {
        rx_config(node, d);
    }
}

static uint32_t lss_process(co_node_t *node, uint32_t next_in)
{
    uint32_t next = next_in;

    if (node->lss.nv_step != 0U) {
        next = lss_store_process(node, next);
    }
    if (node->lss.switching == 0U) {
        return next;
    }
    if (!co_time_reached(node->now, node->lss.switch_at)) {
        return co_deadline_min(node->now, next, node->lss.switch_at);
    }
    node->lss.switching = 0U;
    if ((node->hal.ops->bit_timing != NULL) &&
        (node->hal.ops->bit_timing(node->hal.ctx, node->lss.bit_timing) == 0)) {
        node->lss.active_bt = node->lss.bit_timing;
    }
    return next;
}

/* The first row of co_services[]: it alone runs while unconfigured. */
const co_service_t co_svc_lss = {lss_reset, lss_rx, lss_process};

#endif /* CO_LSS */
