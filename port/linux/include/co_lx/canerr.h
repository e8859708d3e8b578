/*
 * SocketCAN error frames to CiA 301 EMCY codes.
 *
 * The controller state the kernel reports in error frames (CAN_ERR_FLAG) is
 * tracked per node (the flags below); each change is logged as the action
 * on the node's emergency object, and the port hands the resulting state to
 * the core (co_node_can_state / co_node_can_overrun, co/co_canstate.h),
 * whose policy gives the same codes:
 *
 *   bus-off (CAN_ERR_BUSOFF)                  raise 0x8140 "recovered from bus-off"
 *       (the EMCY is held back by the core while the bus is off and leaves
 *        once the controller is back, which is what the code means);
 *       cleared when the controller reports the restart (CAN_ERR_RESTARTED)
 *       or error-active again.
 *   error passive (CAN_ERR_CRTL_RX/TX_PASSIVE) raise 0x8120, cleared on
 *       CAN_ERR_CRTL_ACTIVE, on restart, or when only warnings remain.
 *   controller overflow (CAN_ERR_CRTL_RX/TX_OVERFLOW) or frames dropped by
 *       the socket's receive queue          raise 0x8110 "CAN overrun"; an
 *       overrun is an event, so it is cleared by the next frame received
 *       without loss.
 *
 * Pure functions of the frame and the state: unit-tested without a bus.
 */
#ifndef CO_LX_CANERR_H
#define CO_LX_CANERR_H

#include <stdbool.h>
#include <stdint.h>

#define CO_LX_EMCY_OVERRUN   0x8110U /**< CAN overrun (objects lost) */
#define CO_LX_EMCY_PASSIVE   0x8120U /**< CAN in error passive mode */
#define CO_LX_EMCY_BUSOFF    0x8140U /**< recovered from bus-off */

#define CO_LX_CANERR_ACTIONS_MAX 4U

/** Error state of one controller as the node has reported it. */
typedef struct co_lx_canerr {
    bool busoff;
    bool passive;
    bool overrun;
} co_lx_canerr_t;

/** One change to the node's emergency object. */
typedef struct co_lx_emcy_action {
    uint16_t code;
    bool raise;       /**< true: co_emcy_raise, false: co_emcy_clear */
} co_lx_emcy_action_t;

/** Update @p st from one error frame (@p can_id with CAN_ERR_FLAG, @p data
 *  its 8 data bytes); writes the actions into @p out and returns how many. */
unsigned co_lx_canerr_frame(co_lx_canerr_t *st, uint32_t can_id, const uint8_t data[8],
                            co_lx_emcy_action_t out[CO_LX_CANERR_ACTIONS_MAX]);

/** A data frame was received; @p lost frames were dropped before it (socket
 *  receive queue overflow). Returns the actions (0 or 1) in @p out. */
unsigned co_lx_canerr_rx(co_lx_canerr_t *st, uint32_t lost,
                         co_lx_emcy_action_t out[CO_LX_CANERR_ACTIONS_MAX]);

#endif /* CO_LX_CANERR_H */
