/*
 * Simulated drive plant: motor, loops, switches, index pulse.
 */
#include "co/co402_sim.h"

#include <stddef.h>
#include <string.h>

#define SIM_US_PER_S 1000000LL
#define SIM_E_MAX (INT64_C(1) << 40) /* Q16 increments/s: 2^24 increments/s */
#define SIM_CATCHUP_US 1000000UL     /* at most this much simulated time per update */
#define SIM_STEP_BACK_US 1000000UL   /* a time this much before the plant's: a step back */

static int64_t sim_floor_div(int64_t a, int64_t b)
{
    int64_t q = a / b;
    if (((a % b) != 0) && ((a < 0) != (b < 0))) {
        q--;
    }
    return q;
}

static int64_t q16(int32_t v)
{
    return (int64_t)v * CO402_Q16;
}

static int64_t clamp64(int64_t v, int64_t lim)
{
    if (v > lim) {
        return lim;
    }
    if (v < -lim) {
        return -lim;
    }
    return v;
}

void co402_sim_defaults(co402_sim_config_t *cfg)
{
    (void)memset(cfg, 0, sizeof *cfg);
    cfg->step_us = 250U;
    cfg->counts_per_rev = 4096U;
    cfg->speed_max = 409600U;      /* 100 rev/s */
    cfg->accel_rated = 2048000U;   /* 409600 inc/s reached in 0.2 s at rated torque */
    cfg->torque_max = 3000U;
    cfg->kp = 100U;
    cfg->kv = 600U;
    cfg->ki = 20000U;
    cfg->friction = 1U;
    cfg->neg_limit = INT32_MIN;
    cfg->pos_limit = INT32_MAX;
    cfg->home_lo = INT32_MIN;
    cfg->home_hi = INT32_MAX;
}

/* Zone of the home switch: 0 below, 1 on it, 2 above. */
static int home_zone(const co402_sim_t *s, int64_t p)
{
    if (p < q16(s->cfg.home_lo)) {
        return 0;
    }
    return (p > q16(s->cfg.home_hi)) ? 2 : 1;
}

static uint32_t switch_levels(const co402_sim_t *s, int64_t p)
{
    uint32_t in = 0U;

    if (((s->cfg.switches & CO402_IN_NEG_LIMIT) != 0U) && (p <= q16(s->cfg.neg_limit))) {
        in |= CO402_IN_NEG_LIMIT;
    }
    if (((s->cfg.switches & CO402_IN_POS_LIMIT) != 0U) && (p >= q16(s->cfg.pos_limit))) {
        in |= CO402_IN_POS_LIMIT;
    }
    if (((s->cfg.switches & CO402_IN_HOME) != 0U) && (home_zone(s, p) == 1)) {
        in |= CO402_IN_HOME;
    }
    return in;
}

static int64_t index_interval(const co402_sim_t *s, int64_t p)
{
    if (s->cfg.counts_per_rev == 0U) {
        return 0;
    }
    return sim_floor_div(p - q16(s->cfg.index_offset), (int64_t)s->cfg.counts_per_rev * CO402_Q16);
}

/* Latches for a move from p0 to p1 within one step. */
static void latch(co402_sim_t *s, int64_t p0, int64_t p1)
{
    uint32_t old_in = switch_levels(s, p0);
    uint32_t new_in = switch_levels(s, p1);
    int64_t k;

    if (((old_in ^ new_in) & CO402_IN_NEG_LIMIT) != 0U) {
        s->edge_count[0]++;
        s->edge_pos[0] = q16(s->cfg.neg_limit);
    }
    if (((old_in ^ new_in) & CO402_IN_POS_LIMIT) != 0U) {
        s->edge_count[1]++;
        s->edge_pos[1] = q16(s->cfg.pos_limit);
    }
    if ((s->cfg.switches & CO402_IN_HOME) != 0U) {
        int z0 = home_zone(s, p0);
        int z1 = home_zone(s, p1);
        if (z0 != z1) {
            /* from below or from above, one or both edges were crossed */
            s->edge_count[2] += ((z0 - z1) == 2) || ((z1 - z0) == 2) ? 2U : 1U;
            if (z1 > z0) {
                s->edge_pos[2] = q16((z1 == 2) ? s->cfg.home_hi : s->cfg.home_lo);
            } else {
                s->edge_pos[2] = q16((z1 == 0) ? s->cfg.home_lo : s->cfg.home_hi);
            }
        }
    }
    k = index_interval(s, p1);
    if (k != s->index_k) {
        int64_t passed = (k > s->index_k) ? (k - s->index_k) : (s->index_k - k);
        int64_t last = (k > s->index_k) ? k : (k + 1);
        s->index_count += (uint32_t)passed;
        s->index_pos = q16(s->cfg.index_offset) + (last * (int64_t)s->cfg.counts_per_rev * CO402_Q16);
        s->index_k = k;
    }
    s->inputs = (s->inputs & ~(CO402_IN_NEG_LIMIT | CO402_IN_POS_LIMIT | CO402_IN_HOME)) | new_in;
}

static void step(co402_sim_t *s, uint32_t dt)
{
    uint32_t since = (s->t + dt) - s->t_cmd;
    const co402_sim_config_t *c = &s->cfg;
    int64_t a_lim;
    int64_t acc = 0;
    int64_t v1;
    int64_t p1;
    uint32_t lim = c->torque_max;

    if ((s->d.torque_limit != 0U) && (s->d.torque_limit < lim)) {
        lim = s->d.torque_limit;
    }
    a_lim = ((int64_t)c->accel_rated * (int64_t)lim) / 1000;
    switch (s->d.kind) {
    case CO402_DEMAND_POSITION:
    case CO402_DEMAND_VELOCITY: {
        /* cascade: P position loop, PI velocity loop, with feed-forward */
        /* the demand moves on with its velocity and acceleration between
         * two commands */
        int64_t tau = (since > 10000U) ? 10000 : (int64_t)since;
        int64_t dv = ((int64_t)s->d.acc * CO402_Q16 * tau) / SIM_US_PER_S;
        int64_t vcmd = s->d.vel + dv;
        int64_t e;
        if (s->d.kind == (uint8_t)CO402_DEMAND_POSITION) {
            int64_t pd = s->d.pos + (((s->d.vel + (dv / 2)) * tau) / SIM_US_PER_S);
            /* a position error beyond the 32-bit range saturates */
            vcmd += (int64_t)c->kp * clamp64(pd - s->p, CO402_Q16_MAX);
        }
        /* the velocity loop's error saturates at SIM_E_MAX (far beyond any
         * speed), so that the gains' products stay within 64 bits */
        e = clamp64(vcmd - s->v, SIM_E_MAX);
        acc = (int64_t)s->d.acc + (((int64_t)c->kv * e) / CO402_Q16) + s->vi;
        if (((acc < a_lim) || (e < 0)) && ((acc > -a_lim) || (e > 0))) {
            /* integrate only while the torque is not at its limit (no wind-up) */
            s->vi += ((((int64_t)c->ki * e) / CO402_Q16) * (int64_t)dt) / SIM_US_PER_S;
            s->vi = clamp64(s->vi, a_lim);
        }
        break;
    }
    case CO402_DEMAND_TORQUE:
        s->vi = 0;
        acc = ((int64_t)c->accel_rated * s->d.torque) / 1000;
        break;
    case CO402_DEMAND_BRAKE: {
        /* full torque against the motion, never through zero */
        int64_t dv = ((a_lim * CO402_Q16) * (int64_t)dt) / SIM_US_PER_S;
        s->vi = 0;
        if (s->v > 0) {
            acc = (s->v > dv) ? -a_lim : -((s->v * SIM_US_PER_S) / ((int64_t)dt * CO402_Q16));
        } else if (s->v < 0) {
            acc = (-s->v > dv) ? a_lim : ((-s->v * SIM_US_PER_S) / ((int64_t)dt * CO402_Q16));
        } else {
            acc = 0;
        }
        break;
    }
    default:
        s->vi = 0;
        break; /* off: no torque */
    }
    if (s->fault != 0U) {
        acc = 0; /* a faulty power stage produces no torque */
    }
    acc = clamp64(acc, a_lim);
    s->torque = (int16_t)((c->accel_rated != 0U) ? ((acc * 1000) / (int64_t)c->accel_rated) : 0);
    acc -= ((int64_t)c->friction * s->v) / CO402_Q16;
    v1 = s->v + ((acc * CO402_Q16 * (int64_t)dt) / SIM_US_PER_S);
    v1 = clamp64(v1, (int64_t)c->speed_max * CO402_Q16);
    p1 = s->p + (((s->v + v1) / 2) * (int64_t)dt) / SIM_US_PER_S;
    latch(s, s->p, p1);
    s->p = p1;
    s->v = v1;
}

static void sim_update(void *ctx, uint32_t now_us, co402_feedback_t *fb)
{
    co402_sim_t *s = (co402_sim_t *)ctx;
    uint32_t h = (s->cfg.step_us != 0U) ? s->cfg.step_us : 250U;

    uint32_t gap = now_us - s->t;

    if ((gap > SIM_CATCHUP_US) && (gap < (0xFFFFFFFFUL - SIM_STEP_BACK_US))) {
        /* the caller was stopped (a stall, perhaps beyond 2^31 us, where the
         * wrap-safe comparison would freeze the plant for up to 35
         * minutes): the plant catches up on the last second only */
        s->t = now_us - (uint32_t)SIM_CATCHUP_US;
    }
    while ((int32_t)(now_us - s->t) > 0) {
        uint32_t dt = now_us - s->t;
        step(s, (dt < h) ? dt : h);
        s->t += (dt < h) ? dt : h;
    }
    fb->pos = s->p;
    fb->vel = s->v;
    fb->torque = s->torque;
    fb->inputs = s->inputs | s->levels;
    fb->fault = s->fault;
    for (uint8_t i = 0U; i < CO402_IN_EDGES; i++) {
        fb->edge_count[i] = s->edge_count[i];
        fb->edge_pos[i] = s->edge_pos[i];
    }
    fb->index_count = s->index_count;
    fb->index_pos = s->index_pos;
}

static void sim_command(void *ctx, const co402_demand_t *d)
{
    co402_sim_t *s = (co402_sim_t *)ctx;
    s->d = *d;
    /* a demand beyond the 32-bit range (in Q16) saturates, so that the
     * loops' products stay within 64 bits */
    s->d.pos = clamp64(d->pos, CO402_Q16_MAX);
    s->d.vel = clamp64(d->vel, CO402_Q16_MAX);
    s->t_cmd = s->t;
}

static const co402_plant_ops_t sim_ops = {sim_update, sim_command};

void co402_sim_init(co402_sim_t *s, const co402_sim_config_t *cfg, uint32_t now_us)
{
    (void)memset(s, 0, sizeof *s);
    s->cfg = *cfg;
    s->t = now_us;
    s->p = q16(cfg->start_pos);
    s->index_k = index_interval(s, s->p);
    s->levels = CO402_IN_ENABLE | CO402_IN_VOLTAGE;
    s->inputs = switch_levels(s, s->p);
}

co402_plant_t co402_sim_plant(co402_sim_t *s)
{
    co402_plant_t p;
    p.ops = &sim_ops;
    p.ctx = s;
    return p;
}

void co402_sim_set_level(co402_sim_t *s, uint32_t mask, bool on)
{
    uint32_t m = mask & (CO402_IN_ENABLE | CO402_IN_VOLTAGE);
    s->levels = on ? (s->levels | m) : (s->levels & ~m);
}

void co402_sim_set_fault(co402_sim_t *s, uint16_t code)
{
    s->fault = code;
}

int32_t co402_sim_position(const co402_sim_t *s)
{
    return (int32_t)sim_floor_div(s->p + (CO402_Q16 / 2), CO402_Q16);
}

int32_t co402_sim_velocity(const co402_sim_t *s)
{
    return (int32_t)(s->v / CO402_Q16);
}
