/*
 * CiA 402 modes of operation: profile position, velocity (vl), profile
 * velocity, profile torque, interpolated position and the cyclic
 * synchronous modes. Homing is in co402_homing.c.
 */
#include <stddef.h>

#include "co402_priv.h"

#define MODES_US_PER_S 1000000LL

static int64_t mag(int64_t v)
{
    return (v < 0) ? -v : v;
}

bool co402_mode_supported(const co402_axis_t *ax, int8_t mode)
{
    uint32_t mask = (ax->cfg.modes != 0U) ? ax->cfg.modes : 0x25U;

    mask = (uint32_t)co402_get(ax, O_MODES, mask);
    switch (mode) {
    case CO402_MODE_NONE:
        return true;
    case CO402_MODE_PP:
    case CO402_MODE_VL:
    case CO402_MODE_PV:
    case CO402_MODE_TQ:
    case CO402_MODE_HM:
    case CO402_MODE_IP:
    case CO402_MODE_CSP:
    case CO402_MODE_CSV:
    case CO402_MODE_CST:
        return (mask & (1UL << (uint32_t)((int32_t)mode - 1))) != 0U;
    default:
        return false;
    }
}

bool co402_position_mode(const co402_axis_t *ax)
{
    return (ax->mode == CO402_MODE_PP) || (ax->mode == CO402_MODE_HM) ||
           (ax->mode == CO402_MODE_IP) || (ax->mode == CO402_MODE_CSP);
}

/* vl ramps: delta speed (rpm) per delta time (s) as increments/s^2. */
static uint32_t vl_ramp(const co402_axis_t *ax, uint8_t dv_id, uint8_t dt_id)
{
    int64_t dv = co402_get(ax, dv_id, 0);
    int64_t dt = co402_get(ax, dt_id, 0);
    int64_t a;

    if ((dv <= 0) || (dt <= 0)) {
        return 0U; /* unlimited */
    }
    a = (dv * (int64_t)co402_counts_per_rev(ax)) / (60 * dt);
    if (a < 1) {
        return 1U;
    }
    return (a > (int64_t)UINT32_MAX) ? UINT32_MAX : (uint32_t)a;
}

/* vl deceleration: 0x6049, or 0x6048 for both ways where 0x6049 is absent */
static uint32_t vl_dec(const co402_axis_t *ax)
{
    return co402_has(ax, O_VL_DEC_DV) ? vl_ramp(ax, O_VL_DEC_DV, O_VL_DEC_DT)
                                      : vl_ramp(ax, O_VL_ACC_DV, O_VL_ACC_DT);
}

/* Velocity ramp (CO402_OPT_VELOCITY_RAMP): full speed in increments/s. */
static uint32_t ramp_full(const co402_axis_t *ax)
{
    return (ax->cfg.full_speed != 0U) ? ax->cfg.full_speed : (50U * co402_counts_per_rev(ax));
}

/* A ramp time in ms per full scale (0x6083 / 0x6084) as increments/s^2
 * (0: a step, unlimited). */
static uint32_t ramp_rate(const co402_axis_t *ax, uint8_t id)
{
    uint64_t ms = (uint64_t)(uint32_t)co402_get(ax, id, 0);
    uint64_t a;

    if (ms == 0U) {
        return 0U;
    }
    a = ((uint64_t)ramp_full(ax) * 1000U) / ms;
    if (a < 1U) {
        return 1U;
    }
    return (a > (uint64_t)UINT32_MAX) ? UINT32_MAX : (uint32_t)a;
}

uint32_t co402_slow_dec(const co402_axis_t *ax)
{
    if (ax->mode == CO402_MODE_RAMP) {
        return ramp_rate(ax, O_PROFILE_DEC);
    }
    if (ax->mode == CO402_MODE_VL) {
        return vl_dec(ax);
    }
    if (ax->mode == CO402_MODE_HM) {
        return co402_acc_in(ax, (uint32_t)co402_get(ax, O_HM_ACC, 0));
    }
    return co402_acc_in(ax, (uint32_t)co402_get(ax, O_PROFILE_DEC, 0));
}

uint32_t co402_quick_dec(const co402_axis_t *ax)
{
    if (ax->mode == CO402_MODE_RAMP) {
        return 0U; /* "as fast as possible": the demand drops to 0 at once */
    }
    if ((ax->mode == CO402_MODE_VL) && co402_has(ax, O_VL_QS_DV)) {
        return vl_ramp(ax, O_VL_QS_DV, O_VL_QS_DT);
    }
    if (co402_has(ax, O_QS_DEC)) {
        return co402_acc_in(ax, (uint32_t)co402_get(ax, O_QS_DEC, 0));
    }
    return co402_slow_dec(ax);
}

/* pp: the profile velocity, limited by the max profile velocity. */
static uint32_t pp_speed(const co402_axis_t *ax)
{
    uint32_t v = (uint32_t)co402_get(ax, O_PROFILE_VEL, 0);
    uint32_t vmax = (uint32_t)co402_get(ax, O_MAX_PROFILE_VEL, 0);

    if ((vmax != 0U) && ((v > vmax) || (v == 0U))) {
        v = vmax;
    }
    return co402_speed_in(ax, v);
}

/* Window timer: true once @p cond has held for @p ms. */
static bool held_for(co402_axis_t *ax, bool cond, uint32_t ms, uint32_t *start, bool *on)
{
    if (!cond) {
        *on = false;
        return false;
    }
    if (!*on) {
        *on = true;
        *start = ax->now;
    }
    return (ax->now - *start) >= (ms * 1000U);
}

void co402_mode_enter(co402_axis_t *ax)
{
    co402_traj_t t;

    co402_sync_traj(ax);
    co402_traj_get(ax, &t);
    ax->msw = 0U;
    ax->timer_on = false;
    ax->vtimer_on = false;
    ax->fe_on = false;
    ax->pp_flags = 0U;
    ax->ip_flags = 0U;
    ax->cur_vel = pp_speed(ax);
    ax->cur_acc = co402_acc_in(ax, (uint32_t)co402_get(ax, O_PROFILE_ACC, 0));
    ax->cur_dec = co402_acc_in(ax, (uint32_t)co402_get(ax, O_PROFILE_DEC, 0));
    ax->target = co402_traj_stop_point(&t, ax->cur_dec);
    ax->ip_from = ax->pos;
    ax->ip_to = ax->pos;
    ax->ip_period = 0U;
    ax->ip_t0 = ax->now;
    ax->cs_vel = ax->vel;
    ax->cs_torque = ax->fb.torque;
    ax->tq_demand = ax->fb.torque;
    if (ax->mode == CO402_MODE_HM) {
        co402_hm_enter(ax);
    }
    if ((ax->mode == CO402_MODE_CSP) || (ax->mode == CO402_MODE_CSV) ||
        (ax->mode == CO402_MODE_CST)) {
        ax->msw |= CO402_SW_OMS1; /* the set-points are followed */
    }
}

/* pp: a new set-point (rising edge of controlword bit 4). */
static void pp_setpoint(co402_axis_t *ax, uint16_t cw)
{
    int64_t user = co402_get(ax, O_TARGET_POS, 0);
    int64_t tgt;
    bool limited;

    if ((ax->msw & CO402_SW_OMS1) != 0U) {
        return; /* the generator takes no set-point while it acknowledges one */
    }
    if ((cw & CO402_CW_RELATIVE) != 0U) {
        int64_t base;
        if ((ax->cfg.options & CO402_OPT_PP_REL_ACTUAL) != 0U) {
            base = ax->pos;
        } else {
            base = ((ax->pp_flags & PP_NEXT) != 0U) ? ax->next_target : ax->target;
        }
        tgt = base + co402_dist_in(ax, user);
    } else {
        tgt = co402_pos_in(ax, user);
    }
    limited = co402_clamp(ax, &tgt);
    if (((cw & CO402_CW_CHANGE_NOW) != 0U) || ((ax->cfg.options & CO402_OPT_PP_ALWAYS_NOW) != 0U) ||
        ((ax->pp_flags & PP_MOVING) == 0U)) {
        ax->target = tgt;
        ax->cur_vel = pp_speed(ax);
        ax->cur_acc = co402_acc_in(ax, (uint32_t)co402_get(ax, O_PROFILE_ACC, 0));
        ax->cur_dec = co402_acc_in(ax, (uint32_t)co402_get(ax, O_PROFILE_DEC, 0));
        ax->pp_flags = (uint8_t)((ax->pp_flags & (uint8_t)~(PP_NEXT | PP_LIMITED)) | PP_MOVING);
        if (limited) {
            ax->pp_flags |= PP_LIMITED;
        }
    } else {
        ax->next_target = tgt;
        ax->next_vel = pp_speed(ax);
        ax->next_acc = co402_acc_in(ax, (uint32_t)co402_get(ax, O_PROFILE_ACC, 0));
        ax->next_dec = co402_acc_in(ax, (uint32_t)co402_get(ax, O_PROFILE_DEC, 0));
        ax->pp_flags |= PP_NEXT;
    }
    ax->pp_flags |= PP_MOVED;
    ax->msw |= CO402_SW_OMS1;
    if ((ax->cfg.options & CO402_OPT_PP_TR_NEXT_TICK) == 0U) {
        ax->msw &= (uint16_t)~CO402_SW_TARGET; /* else the next tick clears it */
    }
    ax->timer_on = false;
}

void co402_mode_cw(co402_axis_t *ax, uint16_t old, uint16_t cw)
{
    bool rising = ((cw & CO402_CW_NEW_SETPOINT) != 0U) && ((old & CO402_CW_NEW_SETPOINT) == 0U);

    switch (ax->mode) {
    case CO402_MODE_PP:
        if (rising) {
            pp_setpoint(ax, cw);
        }
        if (((cw & CO402_CW_NEW_SETPOINT) == 0U) && ((ax->pp_flags & PP_NEXT) == 0U)) {
            ax->msw &= (uint16_t)~CO402_SW_OMS1;
        }
        break;
    case CO402_MODE_HM:
        co402_hm_cw(ax, old, cw);
        break;
    case CO402_MODE_IP:
        if ((cw & CO402_CW_NEW_SETPOINT) != 0U) {
            if ((ax->ip_flags & IP_ACTIVE) == 0U) {
                ax->ip_flags = IP_ACTIVE;
                ax->ip_from = ax->tr_p;
                ax->ip_to = ax->tr_p;
                ax->ip_period = 0U;
                if ((ax->cfg.options & CO402_OPT_IP_TR_AT_REST) != 0U) {
                    ax->msw &= (uint16_t)~CO402_SW_TARGET; /* it was "at rest, ip off" */
                }
            }
            ax->msw |= CO402_SW_OMS1;
        } else {
            ax->ip_flags = 0U;
            ax->msw &= (uint16_t)~CO402_SW_OMS1;
        }
        break;
    default:
        break;
    }
}

static void pp_run(co402_axis_t *ax, co402_demand_t *d)
{
    co402_traj_t t;
    uint32_t window = (uint32_t)co402_get(ax, O_POS_WINDOW, 0xFFFFFFFFLL);
    bool idle;
    bool in;

    co402_traj_get(ax, &t);
    if (co402_traj_pos(&t, ax->target, ax->cur_vel, ax->cur_acc, ax->cur_dec, co402_tick(ax)) &&
        ((ax->pp_flags & PP_MOVING) != 0U)) {
        ax->pp_flags &= (uint8_t)~(PP_MOVING | PP_LIMITED);
        if ((ax->pp_flags & PP_NEXT) != 0U) {
            /* the buffered set-point starts where this one ended */
            ax->target = ax->next_target;
            ax->cur_vel = ax->next_vel;
            ax->cur_acc = ax->next_acc;
            ax->cur_dec = ax->next_dec;
            ax->pp_flags = (uint8_t)((ax->pp_flags & (uint8_t)~PP_NEXT) | PP_MOVING);
            if ((ax->cw & CO402_CW_NEW_SETPOINT) == 0U) {
                ax->msw &= (uint16_t)~CO402_SW_OMS1;
            }
        }
    }
    co402_traj_put(ax, &t);
    co402_demand_pos(ax, d, &t);
    idle = (ax->pp_flags & (PP_MOVING | PP_NEXT)) == 0U;
    in = (window == 0xFFFFFFFFU) ||
         (mag(co402_pos_out(ax, ax->target) - co402_pos_out(ax, ax->pos)) <= (int64_t)window);
    if ((ax->cfg.options & CO402_OPT_PP_TR_AFTER_MOVE) != 0U) {
        /* set once a set-point has been reached, kept until the next one */
        if (idle && ((ax->pp_flags & PP_MOVED) != 0U) &&
            held_for(ax, in, (uint32_t)co402_get(ax, O_POS_WINDOW_TIME, 0), &ax->timer,
                     &ax->timer_on)) {
            ax->msw |= CO402_SW_TARGET;
        }
    } else if (held_for(ax, idle && in, (uint32_t)co402_get(ax, O_POS_WINDOW_TIME, 0), &ax->timer,
                        &ax->timer_on)) {
        ax->msw |= CO402_SW_TARGET;
    } else {
        ax->msw &= (uint16_t)~CO402_SW_TARGET;
    }
    if ((ax->pp_flags & PP_LIMITED) != 0U) {
        ax->msw |= CO402_SW_LIMIT;
    } else {
        ax->msw &= (uint16_t)~CO402_SW_LIMIT;
    }
}

/* pv statusword bit 12: the speed has been below 0x606F for 0x6070 ms. */
static void speed_zero(co402_axis_t *ax)
{
    int64_t actual = co402_vel_out(ax, ax->vel);

    if ((ax->cfg.options & CO402_OPT_PV_NO_SPEED_BIT) != 0U) {
        ax->msw &= (uint16_t)~CO402_SW_OMS1;
    } else if (held_for(ax, mag(actual) <= co402_get(ax, O_VEL_THRESHOLD, 0),
                 (uint32_t)co402_get(ax, O_VEL_THRESHOLD_TIME, 0), &ax->vtimer, &ax->vtimer_on)) {
        ax->msw |= CO402_SW_OMS1;
    } else {
        ax->msw &= (uint16_t)~CO402_SW_OMS1;
    }
}

static void velocity_status(co402_axis_t *ax, int64_t target_user)
{
    int64_t actual = co402_vel_out(ax, ax->vel);
    bool reached;

    if (co402_has(ax, O_VEL_WINDOW)) {
        reached = held_for(ax, mag(actual - target_user) <= co402_get(ax, O_VEL_WINDOW, 0),
                           (uint32_t)co402_get(ax, O_VEL_WINDOW_TIME, 0), &ax->timer,
                           &ax->timer_on);
    } else {
        reached = ax->tr_v == co402_vel_in(ax, target_user);
    }
    if (reached) {
        ax->msw |= CO402_SW_TARGET;
    } else {
        ax->msw &= (uint16_t)~CO402_SW_TARGET;
    }
    speed_zero(ax);
}

static void pv_run(co402_axis_t *ax, co402_demand_t *d)
{
    co402_traj_t t;
    int64_t user = co402_get(ax, O_TARGET_VEL, 0);
    int64_t vt = co402_vel_in(ax, user);
    int64_t lo;
    int64_t hi;
    uint32_t vmax = (uint32_t)co402_get(ax, O_MAX_PROFILE_VEL, 0);

    if (vmax != 0U) {
        int64_t m = (int64_t)co402_speed_in(ax, vmax) * CO402_Q16;
        vt = (vt > m) ? m : ((vt < -m) ? -m : vt);
    }
    ax->msw &= (uint16_t)~CO402_SW_LIMIT;
    if (co402_limits(ax, &lo, &hi) && (((ax->pos >= hi) && (vt > 0)) || ((ax->pos <= lo) && (vt < 0)))) {
        vt = 0;
        ax->msw |= CO402_SW_LIMIT;
    }
    co402_traj_get(ax, &t);
    (void)co402_traj_vel(&t, vt, co402_acc_in(ax, (uint32_t)co402_get(ax, O_PROFILE_ACC, 0)),
                         co402_acc_in(ax, (uint32_t)co402_get(ax, O_PROFILE_DEC, 0)),
                         co402_tick(ax));
    t.p = ax->pos;
    co402_traj_put(ax, &t);
    d->kind = (uint8_t)CO402_DEMAND_VELOCITY;
    d->vel = ax->dm_v; /* from the start of the step */
    d->acc = t.a;
    velocity_status(ax, co402_vel_out(ax, vt));
}

static void vl_run(co402_axis_t *ax, co402_demand_t *d)
{
    co402_traj_t t;
    int64_t rpm = co402_get(ax, O_VL_TARGET, 0);
    int64_t a = mag(rpm);
    int64_t vmin = co402_get(ax, O_VL_MIN, 0);
    int64_t vmax = co402_get(ax, O_VL_MAX, 0);
    int64_t vt;
    uint16_t cw = ax->cw;

    if ((a != 0) && (a < vmin)) {
        a = vmin;
    }
    if ((vmax > 0) && (a > vmax)) {
        a = vmax;
    }
    rpm = (rpm < 0) ? -a : a;
    vt = (rpm * (int64_t)co402_counts_per_rev(ax) * CO402_Q16) / 60;
    co402_traj_get(ax, &t);
    if (((cw & CO402_CW_NEW_SETPOINT) == 0U) || ((cw & CO402_CW_RELATIVE) == 0U)) {
        vt = 0; /* ramp function generator disabled / reference 0 */
    }
    if (((cw & CO402_CW_CHANGE_NOW) != 0U) || ((cw & CO402_CW_NEW_SETPOINT) == 0U)) {
        (void)co402_traj_vel(&t, vt, vl_ramp(ax, O_VL_ACC_DV, O_VL_ACC_DT), vl_dec(ax),
                             co402_tick(ax));
    } else {
        (void)co402_traj_vel(&t, t.v, 0U, 0U, co402_tick(ax)); /* ramp locked */
    }
    t.p = ax->pos;
    co402_traj_put(ax, &t);
    d->kind = (uint8_t)CO402_DEMAND_VELOCITY;
    d->vel = ax->dm_v; /* from the start of the step */
    d->acc = t.a;
    if (t.v == vt) {
        ax->msw |= CO402_SW_TARGET;
    } else {
        ax->msw &= (uint16_t)~CO402_SW_TARGET;
    }
}

/* Velocity ramp: 0x6080 per mille of full speed, 0x6083 while the speed
 * grows, 0x6084 while it shrinks (chosen against the present ramp speed),
 * 0x607E bit 6 reverses; bit 10 once the ramp is at the target. */
static void ramp_run(co402_axis_t *ax, co402_demand_t *d)
{
    co402_traj_t t;
    int64_t permille = co402_get(ax, O_RAMP_TARGET, 0);
    int64_t vt = (permille * (int64_t)ramp_full(ax) * CO402_Q16) / 1000;

    if ((co402_get(ax, O_POLARITY, 0) & 0x40) != 0) {
        vt = -vt;
    }
    co402_traj_get(ax, &t);
    (void)co402_traj_vel(&t, vt, ramp_rate(ax, O_PROFILE_ACC), ramp_rate(ax, O_PROFILE_DEC),
                         co402_tick(ax));
    t.p = ax->pos;
    co402_traj_put(ax, &t);
    d->kind = (uint8_t)CO402_DEMAND_VELOCITY;
    d->vel = ax->dm_v; /* from the start of the step */
    d->acc = t.a;
    if (t.v == vt) {
        ax->msw |= CO402_SW_TARGET;
    } else {
        ax->msw &= (uint16_t)~CO402_SW_TARGET;
    }
}

static int16_t clamp_torque(const co402_axis_t *ax, int64_t tq)
{
    int64_t m = co402_get(ax, O_MAX_TORQUE, 0x7FFF);
    int64_t v = tq;

    if (m <= 0) {
        m = 0x7FFF;
    }
    if (v > m) {
        v = m;
    }
    if (v < -m) {
        v = -m;
    }
    return (int16_t)v;
}

static void tq_run(co402_axis_t *ax, co402_demand_t *d)
{
    int16_t target = clamp_torque(ax, co402_get(ax, O_TARGET_TORQUE, 0));
    int64_t slope = co402_get(ax, O_TORQUE_SLOPE, 0);
    int64_t step = (slope * (int64_t)co402_tick(ax)) / MODES_US_PER_S;
    int64_t diff = (int64_t)target - ax->tq_demand;

    if ((slope <= 0) || (mag(diff) <= step)) {
        ax->tq_demand = target;
    } else {
        if (step < 1) {
            step = 1;
        }
        ax->tq_demand = (int16_t)(ax->tq_demand + ((diff > 0) ? step : -step));
    }
    co402_sync_traj(ax);
    d->kind = (uint8_t)CO402_DEMAND_TORQUE;
    d->torque = ax->tq_demand;
    d->vel = 0;
    if (ax->tq_demand == target) {
        ax->msw |= CO402_SW_TARGET;
    } else {
        ax->msw &= (uint16_t)~CO402_SW_TARGET;
    }
}

/* Interpolated position demand at @p t. */
static void interpolate(const co402_axis_t *ax, uint32_t when, int64_t *p, int64_t *v)
{
    int64_t delta = ax->ip_to - ax->ip_from;
    int32_t el = (int32_t)(when - ax->ip_t0);

    if ((ax->ip_period == 0U) || (el > (int32_t)ax->ip_period)) {
        *p = ax->ip_to;
        *v = 0;
    } else if (el <= 0) {
        *p = ax->ip_from;
        *v = 0;
    } else {
        int64_t per = (int64_t)ax->ip_period;
        *p = ax->ip_from + ((delta / per) * el) + (((delta % per) * el) / per);
        *v = ((delta / per) * MODES_US_PER_S) + (((delta % per) * MODES_US_PER_S) / per);
    }
}

static void ip_run(co402_axis_t *ax, co402_demand_t *d)
{
    co402_traj_t t;

    if ((ax->mode == CO402_MODE_IP) && ((ax->ip_flags & IP_ACTIVE) == 0U)) {
        int64_t v = mag(ax->vel);
        co402_traj_get(ax, &t);
        (void)co402_traj_vel(&t, 0, co402_slow_dec(ax), co402_slow_dec(ax), co402_tick(ax));
        co402_traj_put(ax, &t);
        co402_demand_pos(ax, d, &t);
        if ((ax->cfg.options & CO402_OPT_IP_TR_AT_REST) != 0U) {
            if ((t.v == 0) && (v <= co402_standstill(ax))) {
                ax->msw |= CO402_SW_TARGET;
            } else {
                ax->msw &= (uint16_t)~CO402_SW_TARGET;
            }
        }
    } else {
        int64_t p;
        int64_t v;
        interpolate(ax, ax->now, &p, &v);
        co402_demand_at(ax, d, p, v);
        if (ax->mode == CO402_MODE_CSP) {
            ax->msw |= CO402_SW_OMS1; /* target position followed */
        }
    }
}

/* The interpolation period: 0x60C2 (units * 10^index s), else the measured
 * SYNC interval, else one tick. */
static uint32_t ip_period(const co402_axis_t *ax)
{
    int64_t units = co402_get(ax, O_IP_UNITS, 0);
    int64_t index = co402_get(ax, O_IP_INDEX, -3);

    if ((units > 0) && (index >= -6) && (index <= 0)) {
        int64_t us = units;
        for (int64_t e = 6 + index; e > 0; e--) {
            us *= 10; /* units * 10^(6 + index) us */
        }
        return (us > (int64_t)UINT32_MAX) ? UINT32_MAX : (uint32_t)us;
    }
    if ((ax->sync_interval != 0U) && (ax->sync_interval < 1000000U)) {
        return ax->sync_interval;
    }
    return co402_tick(ax);
}

void co402_mode_sync(co402_axis_t *ax, uint32_t now_us)
{
    if (ax->last_sync != 0U) {
        ax->sync_interval = now_us - ax->last_sync;
    }
    ax->last_sync = now_us;
    if ((ax->state != (uint8_t)CO402_OPERATION_ENABLED) || (ax->drive != (uint8_t)DRV_RUN)) {
        return;
    }
    switch (ax->mode) {
    case CO402_MODE_IP:
    case CO402_MODE_CSP: {
        int64_t v;
        int64_t to;
        if (ax->mode == CO402_MODE_IP) {
            if ((ax->ip_flags & IP_ACTIVE) == 0U) {
                return;
            }
            to = co402_pos_in(ax, co402_get(ax, O_IP_DATA, 0));
        } else {
            to = co402_pos_in(ax, co402_get(ax, O_TARGET_POS, 0)) +
                 co402_dist_in(ax, co402_get(ax, O_POS_OFFSET, 0));
        }
        if (co402_clamp(ax, &to)) {
            ax->msw |= CO402_SW_LIMIT;
        } else {
            ax->msw &= (uint16_t)~CO402_SW_LIMIT;
        }
        interpolate(ax, now_us, &ax->ip_from, &v);
        ax->ip_to = to;
        ax->ip_t0 = now_us;
        ax->ip_period = ip_period(ax);
        ax->ip_flags |= IP_SEGMENT;
        break;
    }
    case CO402_MODE_CSV:
        ax->cs_vel = co402_vel_in(ax, co402_get(ax, O_TARGET_VEL, 0) + co402_get(ax, O_VEL_OFFSET, 0));
        break;
    case CO402_MODE_CST:
        ax->cs_torque = clamp_torque(ax, co402_get(ax, O_TARGET_TORQUE, 0) +
                                             co402_get(ax, O_TORQUE_OFFSET, 0));
        break;
    default:
        break;
    }
}

static uint8_t halt_kind(const co402_axis_t *ax)
{
    switch (co402_get(ax, O_HALT_OPT, 1)) {
    case 2:
        return (uint8_t)STOP_QUICK;
    case 3:
    case 4:
        return (uint8_t)STOP_LIMIT;
    default:
        return (uint8_t)STOP_SLOW;
    }
}

void co402_mode_run(co402_axis_t *ax, co402_demand_t *d)
{
    if (((ax->cw & CO402_CW_HALT) != 0U) && (ax->mode != CO402_MODE_NONE) &&
        (ax->mode != CO402_MODE_HM)) {
        /* halt: stop with 0x605D and stay; the set-points are kept */
        if (co402_stop_step(ax, halt_kind(ax), d)) {
            ax->msw |= CO402_SW_TARGET;
        } else {
            ax->msw &= (uint16_t)~CO402_SW_TARGET;
        }
        ax->timer_on = false;
        if (ax->mode == CO402_MODE_TQ) {
            ax->tq_demand = ax->fb.torque;
        }
        if (ax->mode == CO402_MODE_PV) {
            speed_zero(ax);
        }
        return;
    }
    switch (ax->mode) {
    case CO402_MODE_PP:
        pp_run(ax, d);
        break;
    case CO402_MODE_PV:
        pv_run(ax, d);
        break;
    case CO402_MODE_VL:
        vl_run(ax, d);
        break;
    case CO402_MODE_TQ:
        tq_run(ax, d);
        break;
    case CO402_MODE_RAMP:
        ramp_run(ax, d);
        break;
    case CO402_MODE_HM:
        co402_hm_run(ax, d);
        break;
    case CO402_MODE_IP:
    case CO402_MODE_CSP:
        ip_run(ax, d);
        break;
    case CO402_MODE_CSV:
        co402_sync_traj(ax);
        d->kind = (uint8_t)CO402_DEMAND_VELOCITY;
        d->vel = ax->cs_vel;
        ax->msw |= CO402_SW_OMS1;
        break;
    case CO402_MODE_CST:
        co402_sync_traj(ax);
        d->kind = (uint8_t)CO402_DEMAND_TORQUE;
        d->torque = ax->cs_torque;
        ax->msw |= CO402_SW_OMS1;
        break;
    default: {
        /* no mode: hold where the axis came to rest */
        co402_traj_t t;
        co402_traj_get(ax, &t);
        (void)co402_traj_pos(&t, ax->target, 0U, co402_quick_dec(ax), co402_quick_dec(ax),
                             co402_tick(ax));
        co402_traj_put(ax, &t);
        co402_demand_pos(ax, d, &t);
        break;
    }
    }
}
