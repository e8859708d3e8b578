/*
 * Simulated proportional valve: solenoids, spool, controlled quantity.
 */
#include "co/co408_sim.h"

#include <stddef.h>
#include <string.h>

#define SIM_Q16 65536LL

static int64_t sim_div_floor(int64_t a, int64_t b)
{
    int64_t q = a / b;
    if (((a % b) != 0) && ((a < 0) != (b < 0))) {
        q--;
    }
    return q;
}

static int32_t round_q16(int64_t v)
{
    return (int32_t)sim_div_floor(v + (SIM_Q16 / 2), SIM_Q16);
}

void co408_sim_defaults(co408_sim_config_t *cfg)
{
    (void)memset(cfg, 0, sizeof *cfg);
    cfg->step_us = 250U;
    cfg->tau_i_us = 5000U;
    cfg->tau_y_us = 50000U;
    cfg->i_min = 2048;
    cfg->i_max = CO408_FULL;
    cfg->kp = 3000U;
}

void co408_sim_init(co408_sim_t *s, const co408_sim_config_t *cfg, uint32_t now_us)
{
    (void)memset(s, 0, sizeof *s);
    s->cfg = *cfg;
    if (s->cfg.step_us == 0U) {
        s->cfg.step_us = 250U;
    }
    if (s->cfg.i_max <= s->cfg.i_min) {
        s->cfg.i_max = s->cfg.i_min + 1;
    }
    s->t = now_us;
}

uint16_t co408_sim_fault_code(uint32_t faults)
{
    if ((faults & CO408_SIM_UNDERVOLT) != 0U) {
        return 0x3412U;
    }
    if ((faults & (CO408_SIM_SOL_A_OPEN | CO408_SIM_SOL_A_SHORT)) != 0U) {
        return 0x2311U;
    }
    if ((faults & (CO408_SIM_SOL_B_OPEN | CO408_SIM_SOL_B_SHORT)) != 0U) {
        return 0x2312U;
    }
    if ((faults & CO408_SIM_SP_CABLE) != 0U) {
        return 0x3422U;
    }
    return 0U;
}

/* Spool opening (internal) the current @p i (Q16) gives: 0 up to Imin. */
static int64_t opening(const co408_sim_t *s, int64_t i)
{
    int64_t lo = (int64_t)s->cfg.i_min * SIM_Q16;

    if (i <= lo) {
        return 0;
    }
    return ((i - lo) * CO408_FULL) / (s->cfg.i_max - s->cfg.i_min);
}

static int64_t spool_q16(const co408_sim_t *s)
{
    return opening(s, s->ia) - opening(s, s->ib);
}

/* The current (Q16) a solenoid needs for the opening @p cmd (>= 0). */
static int64_t current_for(const co408_sim_t *s, int64_t cmd)
{
    if (cmd <= 0) {
        return 0;
    }
    return ((int64_t)s->cfg.i_min * SIM_Q16) +
           ((cmd * (s->cfg.i_max - s->cfg.i_min) * SIM_Q16) / CO408_FULL);
}

static int64_t lag(int64_t x, int64_t goal, uint32_t dt, uint32_t tau)
{
    if (tau <= dt) {
        return goal;
    }
    return x + sim_div_floor((goal - x) * (int64_t)dt, (int64_t)tau);
}

static void step(co408_sim_t *s, uint32_t dt)
{
    int64_t cmd = 0;
    int64_t want_a;
    int64_t want_b;

    if (s->d.kind == (uint8_t)CO408_DEMAND_OPEN) {
        cmd = s->d.value;
    } else if (s->d.kind == (uint8_t)CO408_DEMAND_CLOSED) {
        /* feed-forward + proportional on the controlled quantity */
        int64_t e = ((int64_t)s->d.value * SIM_Q16) - s->y;
        cmd = s->d.value + sim_div_floor(e * (int64_t)s->cfg.kp, 1000LL * SIM_Q16);
    } else {
        cmd = 0;
    }
    if (cmd > CO408_FULL) {
        cmd = CO408_FULL;
    } else if (cmd < -CO408_FULL) {
        cmd = -CO408_FULL;
    } else {
        /* within range */
    }
    want_a = current_for(s, cmd);
    want_b = current_for(s, -cmd);
    if ((s->faults & (CO408_SIM_UNDERVOLT | CO408_SIM_SOL_A_OPEN | CO408_SIM_SOL_A_SHORT)) != 0U) {
        want_a = 0; /* no current flows / the driver switches off */
    }
    if ((s->faults & (CO408_SIM_UNDERVOLT | CO408_SIM_SOL_B_OPEN | CO408_SIM_SOL_B_SHORT)) != 0U) {
        want_b = 0;
    }
    s->ia = lag(s->ia, want_a, dt, s->cfg.tau_i_us);
    s->ib = lag(s->ib, want_b, dt, s->cfg.tau_i_us);
    s->y = lag(s->y, spool_q16(s), dt, s->cfg.tau_y_us);
}

static void sim_update(void *ctx, uint32_t now_us, co408_feedback_t *fb)
{
    co408_sim_t *s = (co408_sim_t *)ctx;

    while ((int32_t)(now_us - s->t) > 0) {
        uint32_t dt = now_us - s->t;
        if (dt > s->cfg.step_us) {
            dt = s->cfg.step_us;
        }
        step(s, dt);
        s->t += dt;
    }
    fb->current = round_q16(s->ia - s->ib);
    fb->spool = round_q16(spool_q16(s));
    fb->actual = round_q16(s->y);
    fb->local_sp = ((s->faults & CO408_SIM_SP_CABLE) != 0U) ? 0 : s->local_sp;
    fb->inputs = s->inputs;
    fb->fault = co408_sim_fault_code(s->faults);
}

static void sim_command(void *ctx, const co408_demand_t *d)
{
    co408_sim_t *s = (co408_sim_t *)ctx;

    s->d = *d;
}

static const co408_plant_ops_t sim_ops = {sim_update, sim_command};

co408_plant_t co408_sim_plant(co408_sim_t *s)
{
    co408_plant_t p;

    p.ops = &sim_ops;
    p.ctx = s;
    return p;
}

void co408_sim_inject(co408_sim_t *s, uint32_t faults)
{
    s->faults = faults;
}

void co408_sim_set_input(co408_sim_t *s, uint32_t mask, bool on)
{
    if (on) {
        s->inputs |= mask;
    } else {
        s->inputs &= ~mask;
    }
}

void co408_sim_set_local_sp(co408_sim_t *s, int32_t q)
{
    s->local_sp = q;
}
