/*
 * CiA 408 set-point path: bus-window scaling, dead band, ramps, the demand
 * per state, actual values, control deviation, following-error and target
 * windows.
 */
#include <stddef.h>
#include <string.h>

#include "co408_priv.h"

#define Q16 65536LL

static int64_t get(const co408_valve_t *v, uint8_t id, int64_t dflt)
{
    return (id == O_NONE) ? dflt : co_pobj_get(&v->obj[id], dflt);
}

static bool has(const co408_valve_t *v, uint8_t id)
{
    return (id != O_NONE) && co_pobj_has(&v->obj[id]);
}

static int64_t div_floor(int64_t a, int64_t b)
{
    int64_t q = a / b;
    if (((a % b) != 0) && ((a < 0) != (b < 0))) {
        q--;
    }
    return q;
}

static int64_t clamp(int64_t x, int64_t lo, int64_t hi)
{
    return (x < lo) ? lo : ((x > hi) ? hi : x);
}

/* x on [x0, x1] mapped linearly onto [y0, y1]; x itself when x1 <= x0. */
static int64_t lin(int64_t x, int64_t x0, int64_t x1, int64_t y0, int64_t y1)
{
    if (x1 <= x0) {
        return x;
    }
    return y0 + div_floor((x - x0) * (y1 - y0), x1 - x0);
}

static bool window(const co408_valve_t *v, int64_t *lo, int64_t *hi)
{
    if (!has(v, O_WIN_MIN) || !has(v, O_WIN_MAX)) {
        return false;
    }
    *lo = get(v, O_WIN_MIN, 0);
    *hi = get(v, O_WIN_MAX, 0);
    return *hi > *lo;
}

/* A raw bus set-point in the internal resolution: the window onto
 * -100..100 % (a window that starts below 0) or 0..100 %. */
static int32_t to_internal(const co408_valve_t *v, int64_t raw)
{
    int64_t lo;
    int64_t hi;
    int64_t q = raw;

    if (window(v, &lo, &hi)) {
        q = lin(raw, lo, hi, (lo < 0) ? -(int64_t)CO408_FULL : 0, CO408_FULL);
    }
    return (int32_t)clamp(q, -(int64_t)CO408_FULL, CO408_FULL);
}

/* A raw bus set-point in the scaled unit (0x232B..0x232C, closed loop). */
static int64_t to_scaled(const co408_valve_t *v, int64_t raw)
{
    int64_t lo;
    int64_t hi;

    if (window(v, &lo, &hi) && has(v, O_REF_MIN) && has(v, O_REF_MAX)) {
        return lin(raw, lo, hi, get(v, O_REF_MIN, 0), get(v, O_REF_MAX, 0));
    }
    return raw;
}

/* The actual-value reference range 0x222B..0x222C <-> the internal 0..100 %. */
static bool aref(const co408_valve_t *v, int64_t *lo, int64_t *hi)
{
    if (!has(v, O_AREF_MIN) || !has(v, O_AREF_MAX)) {
        return false;
    }
    *lo = get(v, O_AREF_MIN, 0);
    *hi = get(v, O_AREF_MAX, 0);
    return *hi > *lo;
}

static int32_t scaled_to_internal(const co408_valve_t *v, int64_t s)
{
    int64_t lo;
    int64_t hi;
    int64_t q = s;

    if (aref(v, &lo, &hi)) {
        q = lin(s, lo, hi, 0, CO408_FULL);
    }
    return (int32_t)clamp(q, -(int64_t)CO408_FULL, CO408_FULL);
}

static int64_t internal_to_scaled(const co408_valve_t *v, int64_t q)
{
    int64_t lo;
    int64_t hi;

    return aref(v, &lo, &hi) ? lin(q, 0, CO408_FULL, lo, hi) : q;
}

/* Dead-band compensation (0x232D on, 0x232E width): a set-point other than
 * 0 jumps past the valve's overlap, the rest of the range is compressed. */
static int32_t dead_band(const co408_valve_t *v, int32_t t)
{
    int64_t db = get(v, O_DB, 0);
    int64_t a = (t < 0) ? -(int64_t)t : t;

    if ((get(v, O_DB_ON, 0) != 1) || (db <= 0) || (t == 0)) {
        return t;
    }
    db = clamp(db, 0, CO408_FULL);
    a = db + ((a * (CO408_FULL - db)) / CO408_FULL);
    return (int32_t)((t < 0) ? -a : a);
}

int32_t co408_output(const co408_valve_t *v)
{
    return (int32_t)div_floor(v->out + (Q16 / 2), Q16);
}

void co408_sp_reset(co408_valve_t *v)
{
    v->out = 0;
    v->sp = 0;
    v->fe_on = false;
    v->tw_on = false;
}

void co408_sp_enter_active(co408_valve_t *v)
{
    v->out = (int64_t)v->held * Q16; /* the ramp starts from the value held */
    v->fe_on = false;
    v->tw_on = false;
    v->msw = 0U;
}

/* Per-tick step (Q16) for a full-scale time of @p ms; 0 ms: a jump. */
static int64_t ramp_step(const co408_valve_t *v, int64_t ms)
{
    uint32_t tick = (v->cfg.tick_us != 0U) ? v->cfg.tick_us : 1000U;

    if (ms <= 0) {
        return (int64_t)CO408_FULL * Q16 * 2;
    }
    return ((int64_t)CO408_FULL * Q16 * (int64_t)tick) / (ms * 1000);
}

/* One ramp step of v->out towards @p target (internal) with ramp objects
 * from @p rt (type, A up, A down, B up, B down). */
static void ramp(co408_valve_t *v, uint8_t rt, int32_t target)
{
    int64_t t = (int64_t)target * Q16;
    int64_t o = v->out;
    bool side_a = (o > 0) || ((o == 0) && (t > 0));
    int64_t step;
    int64_t goal;

    if ((rt == O_NONE) || (get(v, rt, 0) != 3)) {
        v->out = t; /* ramp off (0; -1 needs a digital input the model lacks) */
        return;
    }
    if (o == t) {
        return;
    }
    if (side_a) {
        step = ramp_step(v, get(v, (uint8_t)(rt + ((t > o) ? 1U : 2U)), 0));
        goal = (t < 0) ? 0 : t; /* down to 0 first when crossing */
    } else {
        step = ramp_step(v, get(v, (uint8_t)(rt + ((t < o) ? 3U : 4U)), 0));
        goal = (t > 0) ? 0 : t;
    }
    if (goal > o) {
        o = ((goal - o) > step) ? (o + step) : goal;
    } else {
        o = ((o - goal) > step) ? (o - step) : goal;
    }
    v->out = o;
    if (o != t) {
        v->msw |= CO408_SW_RAMP;
    }
}

/* The actual value of mode @p m in its own units. */
static int64_t actual_of(const co408_valve_t *v, const co408_mode_t *m)
{
    if ((m->flags & MODE_CLOSED) == 0U) {
        return v->fb.spool;
    }
    if ((m->flags & MODE_INTERNAL) != 0U) {
        return v->fb.actual;
    }
    return internal_to_scaled(v, v->fb.actual);
}

/* Following-error window (bit 11, fault 0x1000 with type -2) and target
 * window (bit 12) on the control deviation @p dev. */
static void windows(co408_valve_t *v, const co408_mode_t *m, int64_t dev)
{
    int64_t a = (dev < 0) ? -dev : dev;
    int64_t type = get(v, m->fe, 0);

    if (((type == 2) || (type == -2)) && (a > get(v, (uint8_t)(m->fe + 2U), 0))) {
        if (!v->fe_on) {
            v->fe_on = true;
            v->fe_since = v->now;
        }
        if ((v->now - v->fe_since) >= ((uint32_t)get(v, (uint8_t)(m->fe + 1U), 0) * 1000U)) {
            v->msw |= CO408_SW_FE;
            if (type == -2) {
                co408_fault_event(v, CO408_ERR_GENERAL);
            }
        }
    } else {
        v->fe_on = false;
    }
    if ((get(v, O_TW_ON, 0) == 2) && (a <= get(v, O_TW_THR, 0))) {
        if (!v->tw_on) {
            v->tw_on = true;
            v->tw_since = v->now;
        }
        if ((v->now - v->tw_since) >= ((uint32_t)get(v, O_TW_DELAY, 0) * 1000U)) {
            v->msw |= CO408_SW_TARGET;
        }
    } else {
        v->tw_on = false;
    }
}

static void run_active(co408_valve_t *v, const co408_mode_t *m)
{
    bool local = get(v, O_DEV_MODE, 1) == 2;
    int64_t raw = get(v, m->sp, 0);

    if ((m->flags & MODE_CLOSED) == 0U) {
        int32_t t = local ? v->fb.local_sp : to_internal(v, raw);
        ramp(v, m->ramp, dead_band(v, t));
        return;
    }
    if (local) {
        v->sp = (int32_t)(((m->flags & MODE_INTERNAL) != 0U) ? v->fb.local_sp
                                                              : internal_to_scaled(v, v->fb.local_sp));
    } else {
        v->sp = (int32_t)(((m->flags & MODE_INTERNAL) != 0U) ? to_internal(v, raw)
                                                              : to_scaled(v, raw));
    }
    v->out = (int64_t)(((m->flags & MODE_INTERNAL) != 0U) ? v->sp : scaled_to_internal(v, v->sp)) * Q16;
    windows(v, m, (int64_t)v->sp - actual_of(v, m));
}

void co408_sp_run(co408_valve_t *v, co408_demand_t *d)
{
    const co408_mode_t *m = co408_mode_of(v->mode);
    uint8_t closed = ((m != NULL) && ((m->flags & MODE_CLOSED) != 0U)) ? 1U : 0U;

    d->kind = (uint8_t)CO408_DEMAND_OFF;
    d->value = 0;
    v->msw = 0U;
    if (m == NULL) {
        return;
    }
    if (v->state == (uint8_t)CO408_ACTIVE) {
        run_active(v, m);
    }
    switch (v->state) { /* (a following error may have ended ACTIVE just now) */
    case (uint8_t)CO408_ACTIVE:
        d->value = co408_output(v);
        break;
    case (uint8_t)CO408_HOLD:
    case (uint8_t)CO408_FAULT_HOLD:
        d->value = v->held;
        break;
    default:
        return;
    }
    d->kind = (uint8_t)((closed != 0U) ? CO408_DEMAND_CLOSED : CO408_DEMAND_OPEN);
}

void co408_sp_publish(co408_valve_t *v)
{
    const co408_mode_t *m = co408_mode_of(v->mode);
    int64_t act;

    if (m == NULL) {
        return;
    }
    act = actual_of(v, m);
    if (m->act != O_NONE) {
        co_pobj_put(&v->obj[m->act], act);
    }
    if (m->dev != O_NONE) {
        co_pobj_put(&v->obj[m->dev], (v->state == (uint8_t)CO408_ACTIVE) ? ((int64_t)v->sp - act) : 0);
    }
}
