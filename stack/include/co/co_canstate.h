/*
 * CAN controller state reported by a port, with its CiA 301 policy in the
 * core (so that every port, SocketCAN or a microcontroller's controller,
 * answers the same way):
 *
 *   CO_CAN_ERROR_PASSIVE  raise EMCY 0x8120 "CAN in error passive mode"
 *                         (0x1001 communication bit); 0x8140 is cleared.
 *   CO_CAN_BUS_OFF        raise EMCY 0x8140 "recovered from bus-off" (it
 *                         waits in the core's EMCY queue while the bus is
 *                         off and leaves once the controller is back, which
 *                         is what the code means) and, on the change into
 *                         bus-off, apply 0x1029 sub 1 (communication error:
 *                         co_node_error_behaviour).
 *   CO_CAN_ERROR_ACTIVE   clear 0x8120 and 0x8140 (EMCY 0x0000 when no
 *                         other error remains).
 *   co_node_can_overrun   lost true: raise 0x8110 "CAN overrun (objects
 *                         lost)"; false (a frame received without loss):
 *                         clear it. An overrun is an event.
 *
 * A port calls these from the node's context (the main loop; an ISR sets a
 * flag the loop turns into a call). Repeating a state changes nothing.
 */
#ifndef CO_CANSTATE_H
#define CO_CANSTATE_H

#include <stdbool.h>
#include <stdint.h>

#include "co/co_node.h"

#define CO_EMCY_CAN_OVERRUN 0x8110U /**< CAN overrun (objects lost) */
#define CO_EMCY_CAN_PASSIVE 0x8120U /**< CAN in error passive mode */
#define CO_EMCY_CAN_BUSOFF  0x8140U /**< recovered from bus-off */

typedef enum co_can_state {
    CO_CAN_ERROR_ACTIVE,  /**< error counters below 128 (warnings included) */
    CO_CAN_ERROR_PASSIVE, /**< an error counter at 128 or above */
    CO_CAN_BUS_OFF        /**< the controller left the bus */
} co_can_state_t;

/** The controller is now in @p state (see above). */
void co_node_can_state(co_node_t *node, co_can_state_t state, uint32_t now_us);

/** Frames were lost before the one just received (@p lost true), or a frame
 *  arrived without loss (false). */
void co_node_can_overrun(co_node_t *node, bool lost);

#endif /* CO_CANSTATE_H */
