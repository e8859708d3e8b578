/*
 * NMT slave: boot-up, the state machine, resets.
 */
#include <string.h>

#include "co_priv.h"

#define NMT_START      0x01U
#define NMT_STOP       0x02U
#define NMT_PRE_OP     0x80U
#define NMT_RESET_NODE 0x81U
#define NMT_RESET_COMM 0x82U

static void set_state(co_node_t *node, co_nmt_state_t st)
{
    if (node->nmt == (uint8_t)st) {
        return;
    }
    node->nmt = (uint8_t)st;
    if (st == CO_NMT_STOPPED) {
        co_sdo_reset(node); /* no SDO in Stopped: an open transfer ends silently */
    }
    co_pdo_nmt(node, st);
    if (node->cb.nmt_state != NULL) {
        node->cb.nmt_state(node->cb.ctx, node, st);
    }
}

/* Initialising: the communication services start from their reset values,
 * the boot-up frame goes out, and the node enters Pre-operational. */
void co_nmt_boot(co_node_t *node)
{
    node->nmt = (uint8_t)CO_NMT_INITIALISING;
    co_sdo_reset(node);
    co_emcy_reset(node);
    co_sync_reset(node);
    co_pdo_reset(node);
    co_lss_reset(node);
    co_hb_reset(node); /* also rebuilds the receive table */
    if (node->node_id == CO_NODE_ID_UNCONFIGURED) {
        return; /* LSS init: no boot-up, no NMT until a valid node-ID */
    }
    if (!co_opt(node, CO_OPT_NO_BOOTUP)) {
        static const uint8_t bootup = 0x00U;
        co_tx(node, 0x700UL + node->node_id, &bootup, 1U);
    }
    if (co_opt(node, CO_OPT_BOOT_EMCY) && (node->emcy_cob != NULL) &&
        ((*node->emcy_cob & 0x80000000UL) == 0U)) {
        uint8_t d[8] = {0};
        if (node->dev->boot_emcy_data != NULL) {
            (void)memcpy(&d[3], node->dev->boot_emcy_data, 5U);
        }
        co_tx(node, *node->emcy_cob & 0x7FFUL, d, 8U);
    }
    set_state(node, CO_NMT_PRE_OPERATIONAL);
    /* Heartbeat consumers and life guarding start over (co_hb_reset), so an
     * EMCY 0x8130 of a producer or master lost before the reset has nothing
     * left to clear it. CiA 301 is silent; we end it here, after the boot-up
     * (the first frame after a reset) and in Pre-operational, where EMCY may
     * be sent. No-op after a node reset (no active errors) and at init. */
    co_emcy_clear(node, CO_EMCY_HB_GUARD);
    /* the same for the RPDO errors: monitoring starts over */
    co_emcy_clear(node, CO_EMCY_PDO_SHORT);
    co_emcy_clear(node, CO_EMCY_PDO_LONG);
    co_emcy_clear(node, CO_EMCY_RPDO_TIMEOUT);
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
    const co_od_sub_t *s = ((e != NULL) && (sub != 0U)) ? co_od_find_sub(e, sub) : NULL;
    const uint8_t *v = NULL;

    if ((s != NULL) && (s->type == (uint8_t)CO_UNSIGNED8)) {
        v = (const uint8_t *)co_od_loc(node, s);
    }
    if (v == NULL) {
        return;
    }
    if ((*v == 0U) && (node->nmt == (uint8_t)CO_NMT_OPERATIONAL)) {
        set_state(node, CO_NMT_PRE_OPERATIONAL);
    } else if (*v == 2U) {
        set_state(node, CO_NMT_STOPPED);
    } else {
        /* no change */
    }
}
#endif

void co_node_error_behaviour(co_node_t *node, uint8_t sub, uint32_t now_us)
{
    co_node_clock(node, now_us);
    co_nmt_error(node, sub);
}

bool co_nmt_take_nodeid(co_node_t *node)
{
    const uint8_t *v;

    if (node->dev->nodeid_index == 0U) {
        return false;
    }
    v = (const uint8_t *)co_od_value_ptr(node, node->dev->nodeid_index, 0U);
    if ((v == NULL) || (*v < 1U) || (*v > 127U) || (*v == node->node_id)) {
        return false;
    }
    node->cob_base = co_node_cob_base_for(node, *v);
    node->node_id = *v;
    node->pending_id = *v;
    return true;
}

void co_nmt_reset(co_node_t *node, co_reset_t kind)
{
    /* Reset communication restores the communication area, reset node all
     * of the image, each to defaults and then to the stored set (0x1010).
     * Where the core's objects live does not change, so the pointers
     * co_comm_bind found at init stay valid. A new node-ID (LSS,
     * co_node_set_id) takes effect here (CiA 305). A device with a node-ID
     * object takes its node-ID from it next ($NODEID defaults follow it);
     * after a node reset that object has its stored value, so the image is
     * restored again if the node-ID changes. */
    co_reset_t k = co_node_take_id(node, kind);

    if (k == CO_RESET_COMMUNICATION) {
        (void)co_nmt_take_nodeid(node);
        co_store_reset(node, k);
    } else {
        co_store_reset(node, k);
        if (co_nmt_take_nodeid(node)) {
            co_store_reset(node, k);
        }
    }
    if (k == CO_RESET_NODE) {
        node->n_active = 0U;
    }
    if (node->cb.nmt_reset != NULL) {
        node->cb.nmt_reset(node->cb.ctx, node, k);
    }
    co_nmt_boot(node);
}

void co_node_nmt_command(co_node_t *node, uint8_t cs, uint32_t now_us)
{
    co_node_clock(node, now_us);
    switch (cs) {
    case NMT_START:
        set_state(node, CO_NMT_OPERATIONAL);
        break;
    case NMT_STOP:
        set_state(node, CO_NMT_STOPPED);
        break;
    case NMT_PRE_OP:
        set_state(node, CO_NMT_PRE_OPERATIONAL);
        break;
    case NMT_RESET_NODE:
        co_nmt_reset(node, CO_RESET_NODE);
        break;
    case NMT_RESET_COMM:
        co_nmt_reset(node, CO_RESET_COMMUNICATION);
        break;
    default:
        break; /* unknown command specifier: ignored (CiA 301 defines no answer) */
    }
}

void co_nmt_rx(co_node_t *node, const co_frame_t *f)
{
    if (co_frame_is_rtr(f) || (f->dlc != 2U)) {
        return;
    }
    if ((f->data[1] != 0U) && (f->data[1] != node->node_id)) {
        return;
    }
    co_node_nmt_command(node, f->data[0], node->now);
}
