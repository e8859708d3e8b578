/*
 * On-line trapezoidal profile generator.
 */
#include "co402_traj.h"

#include "co/co402_plant.h"

#define V_UNLIMITED INT64_MAX
#define TRAJ_US_PER_S 1000000LL

uint64_t co402_isqrt(uint64_t v)
{
    uint64_t x = v;
    uint64_t r = 0U;
    uint64_t bit = (uint64_t)1U << 62U;

    while (bit > x) {
        bit >>= 2U;
    }
    while (bit != 0U) {
        if (x >= (r + bit)) {
            x -= r + bit;
            r = (r >> 1U) + bit;
        } else {
            r >>= 1U;
        }
        bit >>= 2U;
    }
    return r;
}

static int64_t magnitude(int64_t v)
{
    return (v < 0) ? -v : v;
}

/* Velocity change (Q16) an acceleration allows in dt; unlimited for 0. */
static int64_t dv_of(uint32_t acc, uint32_t dt_us)
{
    if (acc == 0U) {
        return V_UNLIMITED;
    }
    return ((int64_t)acc * CO402_Q16 * (int64_t)dt_us) / TRAJ_US_PER_S;
}

/* The highest speed (Q16) from which a stop with dec ends within s (Q16):
 * sqrt(2 dec s). */
static int64_t brake_speed(uint32_t dec, int64_t s)
{
    uint64_t twice;

    if (dec == 0U) {
        return V_UNLIMITED;
    }
    twice = 2U * (uint64_t)dec;
    if ((uint64_t)s <= (UINT64_MAX / twice)) {
        /* sqrt(2 dec s_q16) = v * 2^8 */
        return (int64_t)(co402_isqrt(twice * (uint64_t)s) << 8U);
    }
    if (((uint64_t)s >> 16U) <= (UINT64_MAX / twice)) {
        uint64_t v = co402_isqrt(twice * ((uint64_t)s >> 16U));
        return (v < ((uint64_t)1U << 46U)) ? (int64_t)(v << 16U) : V_UNLIMITED;
    }
    return V_UNLIMITED;
}

void co402_traj_set(co402_traj_t *t, int64_t p, int64_t v)
{
    t->p = p;
    t->v = v;
    t->a = 0;
}

static void advance(co402_traj_t *t, int64_t v1, uint32_t dt_us)
{
    if (dt_us != 0U) {
        t->a = (int32_t)((((v1 - t->v) / CO402_Q16) * TRAJ_US_PER_S) / (int64_t)dt_us);
    }
    t->p += (((t->v + v1) / 2) * (int64_t)dt_us) / TRAJ_US_PER_S;
    t->v = v1;
}

/* The next velocity going from v towards vt: acc while speeding up, dec
 * while slowing down, never through zero in one step. */
static int64_t ramp(int64_t v, int64_t goal, uint32_t acc, uint32_t dec, uint32_t dt_us)
{
    int64_t dv;
    int64_t vt = goal;

    if (v == vt) {
        return v;
    }
    if ((v != 0) && ((v > 0) != (vt > 0)) && (vt != 0)) {
        vt = 0; /* reverse: first down to zero */
    }
    if (magnitude(vt) > magnitude(v)) {
        dv = dv_of(acc, dt_us);
    } else {
        dv = dv_of(dec, dt_us);
    }
    if (vt > v) {
        return ((vt - v) > dv) ? (v + dv) : vt; /* up */
    }
    return ((v - vt) > dv) ? (v - dv) : vt;
}

bool co402_traj_vel(co402_traj_t *t, int64_t vtarget, uint32_t acc, uint32_t dec, uint32_t dt_us)
{
    advance(t, ramp(t->v, vtarget, acc, dec, dt_us), dt_us);
    return t->v == vtarget;
}

int64_t co402_traj_stop_point(const co402_traj_t *t, uint32_t dec)
{
    int64_t v = magnitude(t->v);
    int64_t s;

    if ((dec == 0U) || (v == 0)) {
        return t->p;
    }
    /* v^2 / (2 dec) in Q16: (v_q16 / 2^8)^2 / (2 dec) */
    v /= 256;
    s = (v > 3037000499LL) ? (INT64_MAX / 4) : ((v * v) / (2 * (int64_t)dec));
    return (t->v > 0) ? (t->p + s) : (t->p - s);
}

/* A speed difference the discretisation may swallow in one step. */
static bool within(int64_t diff, int64_t dv)
{
    return (dv == V_UNLIMITED) || (diff <= (2 * dv));
}

bool co402_traj_pos(co402_traj_t *t, int64_t target, uint32_t vmax, uint32_t acc, uint32_t dec,
                    uint32_t dt_us)
{
    int64_t s = target - t->p;
    int64_t dv = dv_of(dec, dt_us);
    int64_t dir;
    int64_t vlim;
    int64_t vt;
    int64_t v1;
    int64_t p_before;

    if ((s == 0) && (t->v == 0)) {
        t->a = 0;
        return true;
    }
    if (s != 0) {
        dir = (s > 0) ? (int64_t)1 : (int64_t)-1;
    } else {
        dir = (t->v > 0) ? (int64_t)-1 : (int64_t)1;
    }
    vlim = brake_speed(dec, magnitude(s));
    if ((vmax != 0U) && (vlim > ((int64_t)vmax * CO402_Q16))) {
        vlim = (int64_t)vmax * CO402_Q16;
    }
    vt = dir * vlim;
    if ((t->v != 0) && ((t->v > 0) == (dir > 0)) && (magnitude(t->v) > vlim) &&
        within(magnitude(t->v) - vlim, dv)) {
        /* on the braking curve: follow it (the curve is what dec allows;
         * the excess is discretisation) */
        v1 = vt;
    } else {
        /* includes a target too close to stop in time: brake with dec,
         * pass it and come back */
        v1 = ramp(t->v, vt, acc, dec, dt_us);
    }
    p_before = t->p;
    advance(t, v1, dt_us);
    /* at (or within this step past) the target, slow enough to stop there */
    if ((((target - t->p) * dir) <= 0) && (((t->p - p_before) * dir) >= 0) &&
        within(magnitude(t->v), dv)) {
        t->p = target;
        t->v = 0;
        t->a = 0;
        return true;
    }
    return false;
}
