/* CAN controller state to EMCY and 0x1029 (see co/co_canstate.h). */
#include "co/co_canstate.h"

void co_node_can_state(co_node_t *node, co_can_state_t state, uint32_t now_us)
{
    switch (state) {
    case CO_CAN_BUS_OFF:
        if (!co_emcy_is_active(node, CO_EMCY_CAN_BUSOFF)) {
            co_emcy_raise(node, CO_EMCY_CAN_BUSOFF, CO_ERREG_COMM, NULL);
            /* CiA 301: bus-off is a communication error (0x1029 sub 1) */
            co_node_error_behaviour(node, CO_ERRBEH_COMM, now_us);
        }
        break;
    case CO_CAN_ERROR_PASSIVE:
        /* raised first: clearing 0x8140 then leaves an error active */
        co_emcy_raise(node, CO_EMCY_CAN_PASSIVE, CO_ERREG_COMM, NULL);
        co_emcy_clear(node, CO_EMCY_CAN_BUSOFF);
        break;
    default: /* CO_CAN_ERROR_ACTIVE */
        co_emcy_clear(node, CO_EMCY_CAN_PASSIVE);
        co_emcy_clear(node, CO_EMCY_CAN_BUSOFF);
        break;
    }
}

void co_node_can_overrun(co_node_t *node, bool lost)
{
    if (lost) {
        co_emcy_raise(node, CO_EMCY_CAN_OVERRUN, CO_ERREG_COMM, NULL);
    } else {
        co_emcy_clear(node, CO_EMCY_CAN_OVERRUN);
    }
}
