/*
 * CiA 408 profile internals shared by its modules. Not a public header.
 */
#ifndef CO408_PRIV_H
#define CO408_PRIV_H

#include <stdbool.h>
#include <stdint.h>

#include "co/co408.h"

/* Objects of one channel. */
enum {
    O_CW = 0, O_SW, O_DEV_MODE, O_CTRL_MODE, O_LOCAL,
    O_VPOC_SP, O_VPOC_ACT, O_VPOC_RT, O_VPOC_AU, O_VPOC_AD, O_VPOC_BU, O_VPOC_BD,
    O_VPRC_SP, O_VPRC_ACT, O_VPRC_RT, O_VPRC_AU, O_VPRC_AD, O_VPRC_BU, O_VPRC_BD,
    O_VPRC_DEV, O_VPRC_FE, O_VPRC_FED, O_VPRC_FET,
    O_DCOL_SP, O_DCOL_RT, O_DCOL_AU, O_DCOL_AD, O_DCOL_BU, O_DCOL_BD,
    O_DSC_SP, O_DSC_ACT, O_DSC_DEV, O_DSC_FE, O_DSC_FED, O_DSC_FET,
    O_DPC_SP, O_DPC_ACT, O_DPC_DEV, O_DPC_FE, O_DPC_FED, O_DPC_FET,
    O_NPT_SP, O_NPT_ACT, O_NPT_DEV, O_NPT_FE, O_NPT_FED, O_NPT_FET,
    /* manufacturer area (Wandfluh numbering) */
    O_WIN_MIN, O_WIN_MAX, O_REF_MIN, O_REF_MAX, O_AREF_MIN, O_AREF_MAX, O_DB_ON, O_DB,
    O_TW_ON, O_TW_DELAY, O_TW_THR, O_CB_SOL1, O_CB_SOL2, O_CB_SP, O_CAPABILITY,
    O_COUNT
};

#define O_NONE 0xFFU

/* How a control mode uses the objects. Ramps: type, then the times A up,
 * A down, B up, B down at ramp + 1 .. + 4; following error: type, delay,
 * threshold at fe, fe + 1, fe + 2. */
typedef struct co408_mode {
    int8_t value;
    uint8_t sp;
    uint8_t act;
    uint8_t dev;
    uint8_t ramp;
    uint8_t fe;
    uint8_t flags;
} co408_mode_t;

#define MODE_CLOSED   0x01U /* closed loop */
#define MODE_INTERNAL 0x02U /* set-point / actual in the internal resolution (vprc) */

/* ---- co408.c */
const co408_mode_t *co408_mode_of(int8_t value);
bool co408_mode_offered(const co408_valve_t *v, int8_t value);
void co408_fault_event(co408_valve_t *v, uint16_t code);

/* ---- co408_sp.c: set-point path and windows, once per tick */
void co408_sp_enter_active(co408_valve_t *v);
void co408_sp_reset(co408_valve_t *v);
/* The demand for the plant in the present state, status bits 9, 11, 12 in v->msw. */
void co408_sp_run(co408_valve_t *v, co408_demand_t *d);
/* Actual values, control deviation. */
void co408_sp_publish(co408_valve_t *v);

#endif /* CO408_PRIV_H */
