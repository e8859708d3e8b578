/* SocketCAN error frames to EMCY raise/clear actions (see canerr.h). */
#include "co_lx/canerr.h"

#include <linux/can.h>
#include <linux/can/error.h>

static unsigned put(co_lx_emcy_action_t *out, unsigned n, uint16_t code, bool raise)
{
    unsigned count = n;

    if (count < CO_LX_CANERR_ACTIONS_MAX) {
        out[count].code = code;
        out[count].raise = raise;
        count++;
    }
    return count;
}

/* flag := on; an action when it changed */
static unsigned set(bool *flag, bool on, uint16_t code, co_lx_emcy_action_t *out, unsigned n)
{
    unsigned count = n;

    if (*flag != on) {
        *flag = on;
        count = put(out, count, code, on);
    }
    return count;
}

unsigned co_lx_canerr_frame(co_lx_canerr_t *st, uint32_t can_id, const uint8_t data[8],
                            co_lx_emcy_action_t out[CO_LX_CANERR_ACTIONS_MAX])
{
    unsigned n = 0U;
    uint8_t ctrl = data[1];

    if ((can_id & CAN_ERR_FLAG) == 0U) {
        return 0U;
    }
    if ((can_id & CAN_ERR_CRTL) != 0U) {
        if ((ctrl & (CAN_ERR_CRTL_RX_OVERFLOW | CAN_ERR_CRTL_TX_OVERFLOW)) != 0U) {
            n = set(&st->overrun, true, CO_LX_EMCY_OVERRUN, out, n);
        }
        if ((ctrl & (CAN_ERR_CRTL_RX_PASSIVE | CAN_ERR_CRTL_TX_PASSIVE)) != 0U) {
            n = set(&st->passive, true, CO_LX_EMCY_PASSIVE, out, n);
        } else if ((ctrl & (CAN_ERR_CRTL_ACTIVE | CAN_ERR_CRTL_RX_WARNING |
                            CAN_ERR_CRTL_TX_WARNING)) != 0U) {
            /* back below the passive limit */
            n = set(&st->passive, false, CO_LX_EMCY_PASSIVE, out, n);
        } else {
            /* other controller problems: nothing CiA 301 names */
        }
    }
    if ((can_id & CAN_ERR_BUSOFF) != 0U) {
        n = set(&st->busoff, true, CO_LX_EMCY_BUSOFF, out, n);
    }
    if ((can_id & CAN_ERR_RESTARTED) != 0U) {
        n = set(&st->passive, false, CO_LX_EMCY_PASSIVE, out, n);
        n = set(&st->busoff, false, CO_LX_EMCY_BUSOFF, out, n);
    }
    if (((can_id & CAN_ERR_CRTL) != 0U) && ((ctrl & CAN_ERR_CRTL_ACTIVE) != 0U)) {
        n = set(&st->busoff, false, CO_LX_EMCY_BUSOFF, out, n);
    }
    return n;
}

unsigned co_lx_canerr_rx(co_lx_canerr_t *st, uint32_t lost,
                         co_lx_emcy_action_t out[CO_LX_CANERR_ACTIONS_MAX])
{
    return set(&st->overrun, lost != 0U, CO_LX_EMCY_OVERRUN, out, 0U);
}
