/*
 * CiA 402 profile internals shared by its modules. Not a public header.
 */
#ifndef CO402_PRIV_H
#define CO402_PRIV_H

#include <stdbool.h>
#include <stdint.h>

#include "co/co402.h"
#include "co402_traj.h"

/* Objects of one axis (index + 0x800 * axis). */
enum {
    O_CW = 0, O_SW, O_ERR, O_ABORT, O_QS_OPT, O_SD_OPT, O_DO_OPT, O_HALT_OPT, O_FR_OPT,
    O_MODE, O_MODE_DISP, O_POS_DEMAND, O_POS_INTERNAL, O_POS_ACTUAL, O_FE_WINDOW,
    O_FE_TIMEOUT, O_POS_WINDOW, O_POS_WINDOW_TIME, O_VEL_DEMAND, O_VEL_ACTUAL, O_VEL_WINDOW,
    O_VEL_WINDOW_TIME, O_VEL_THRESHOLD, O_VEL_THRESHOLD_TIME, O_TARGET_TORQUE, O_MAX_TORQUE,
    O_TORQUE_DEMAND, O_TORQUE_ACTUAL, O_TARGET_POS, O_HOME_OFFSET, O_LIMIT_MIN, O_LIMIT_MAX,
    O_POLARITY, O_MAX_PROFILE_VEL, O_PROFILE_VEL, O_PROFILE_ACC, O_PROFILE_DEC, O_QS_DEC,
    O_TORQUE_SLOPE, O_ENC_INC, O_ENC_REV, O_POS_NUM, O_POS_DEN, O_VEL_NUM, O_VEL_DEN, O_ACC_NUM,
    O_ACC_DEN, O_HM_METHOD, O_HM_FAST, O_HM_SLOW, O_HM_ACC, O_POS_OFFSET, O_VEL_OFFSET,
    O_TORQUE_OFFSET, O_IP_DATA, O_IP_UNITS, O_IP_INDEX, O_FE_ACTUAL, O_DIG_IN, O_TARGET_VEL,
    O_MODES, O_VL_TARGET, O_VL_DEMAND, O_VL_ACTUAL, O_VL_MIN, O_VL_MAX, O_VL_ACC_DV, O_VL_ACC_DT,
    O_VL_DEC_DV, O_VL_DEC_DT, O_VL_QS_DV, O_VL_QS_DT, O_RAMP_TARGET,
    O_COUNT
};

/* Where the demand comes from (co402_axis_t.drive). */
enum { DRV_OFF = 0, DRV_RUN, DRV_STOP, DRV_HOLD };

/* Stop ramps (option code values 1..4 of 0x605A/0x605D/0x605E). */
enum { STOP_COAST = 0, STOP_SLOW = 1, STOP_QUICK = 2, STOP_LIMIT = 3 };

/* pp flags */
#define PP_MOVING  0x01U /* a set-point is being executed */
#define PP_NEXT    0x02U /* a set-point is buffered */
#define PP_LIMITED 0x04U /* the active target was clamped to a software limit */
#define PP_MOVED   0x08U /* a set-point was accepted since Operation enabled */

/* ip / cs flags */
#define IP_ACTIVE  0x01U /* ip: enabled by controlword bit 4 */
#define IP_SEGMENT 0x02U /* a segment has been latched */

/* homing phases */
enum { HM_IDLE = 0, HM_SEARCH, HM_INDEX, HM_STOPPING, HM_DONE, HM_ERR_STOPPING, HM_ERROR,
       HM_ABORTING };

/* ---- co402.c: objects, units, shared helpers */
bool co402_has(const co402_axis_t *ax, uint8_t id);
int64_t co402_get(const co402_axis_t *ax, uint8_t id, int64_t dflt);
void co402_put(co402_axis_t *ax, uint8_t id, int64_t v);
int64_t co402_pos_in(const co402_axis_t *ax, int64_t user);      /* -> Q16 internal */
int64_t co402_dist_in(const co402_axis_t *ax, int64_t user);     /* relative, -> Q16 */
int64_t co402_pos_out(const co402_axis_t *ax, int64_t q16);      /* -> user */
int64_t co402_vel_in(const co402_axis_t *ax, int64_t user);      /* -> Q16 inc/s */
int64_t co402_vel_out(const co402_axis_t *ax, int64_t q16);      /* -> user */
uint32_t co402_speed_in(const co402_axis_t *ax, uint32_t user);  /* -> inc/s */
uint32_t co402_acc_in(const co402_axis_t *ax, uint32_t user);    /* -> inc/s^2 */
uint32_t co402_counts_per_rev(const co402_axis_t *ax);
uint32_t co402_tick(const co402_axis_t *ax);
int64_t co402_standstill(const co402_axis_t *ax);                /* Q16 inc/s */
bool co402_limits(const co402_axis_t *ax, int64_t *lo, int64_t *hi);
bool co402_clamp(const co402_axis_t *ax, int64_t *p);
void co402_traj_get(const co402_axis_t *ax, co402_traj_t *t);
void co402_traj_put(co402_axis_t *ax, const co402_traj_t *t);
void co402_sync_traj(co402_axis_t *ax);                          /* demand := actual */
void co402_demand_pos(const co402_axis_t *ax, co402_demand_t *d, const co402_traj_t *t);
/* A demand at @p p moving with @p v now (the generator follows it). */
void co402_demand_at(co402_axis_t *ax, co402_demand_t *d, int64_t p, int64_t v);
/* One step of a stop with @p kind; true once at rest. */
bool co402_stop_step(co402_axis_t *ax, uint8_t kind, co402_demand_t *d);

/* ---- co402_modes.c */
bool co402_mode_supported(const co402_axis_t *ax, int8_t mode);
void co402_mode_enter(co402_axis_t *ax);
void co402_mode_cw(co402_axis_t *ax, uint16_t old, uint16_t cw);
void co402_mode_run(co402_axis_t *ax, co402_demand_t *d);
void co402_mode_sync(co402_axis_t *ax, uint32_t now_us);
uint32_t co402_slow_dec(const co402_axis_t *ax);
uint32_t co402_quick_dec(const co402_axis_t *ax);
bool co402_position_mode(const co402_axis_t *ax);

/* ---- co402_homing.c */
bool co402_hm_supported(int8_t method);
bool co402_hm_accepted(const co402_axis_t *ax, int8_t value); /* 0x6098 value of the device */
void co402_hm_enter(co402_axis_t *ax);
void co402_hm_cw(co402_axis_t *ax, uint16_t old, uint16_t cw);
void co402_hm_run(co402_axis_t *ax, co402_demand_t *d);

#endif /* CO402_PRIV_H */
