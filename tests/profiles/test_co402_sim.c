/*
 * The profile generator (trapezoidal, on-line) and the simulated plant:
 * exact arrival, limits respected, target changes, velocity ramps through
 * zero; the plant's inertia and limits, switch and index latches, braking,
 * torque, faults and determinism.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "co/co402_sim.h"
#include "co402_traj.h"
#include "t402.h"

#define Q CO402_Q16

static int64_t abs64(int64_t v)
{
    return (v < 0) ? -v : v;
}

/* Runs a position move; returns the steps it took and checks the limits
 * on the way: speed, acceleration (deceleration may exceed dec by the
 * discretisation at the very end), no overshoot. */
static unsigned move(co402_traj_t *t, int64_t target, uint32_t vmax, uint32_t acc, uint32_t dec)
{
    unsigned n = 0;
    int64_t start = t->p;
    int64_t v0 = t->v;

    while (!co402_traj_pos(t, target, vmax, acc, dec, 1000U)) {
        int64_t dv = abs64(t->v - v0);
        assert_true(abs64(t->v) <= ((int64_t)vmax * Q));
        assert_true(dv <= ((int64_t)((acc > dec) ? acc : dec) * Q / 1000 * 3 / 2 + 1));
        if (target > start) {
            assert_true(t->p <= target);
        }
        v0 = t->v;
        n++;
        assert_true(n < 100000U);
    }
    assert_int_equal(t->p, target);
    assert_int_equal(t->v, 0);
    return n;
}

static void traj_trapezoid(void **state)
{
    co402_traj_t t;
    unsigned n;
    (void)state;
    co402_traj_set(&t, 0, 0);
    /* 0.4 s up, 4.6 s at 20000/s, 0.4 s down: 5.4 s */
    n = move(&t, 100000LL * Q, 20000U, 50000U, 50000U);
    assert_in_range(n, 5385U, 5405U);
    /* back, with a faster deceleration */
    n = move(&t, 0, 20000U, 50000U, 200000U);
    assert_in_range(n, 5235U, 5260U);
}

static void traj_triangle(void **state)
{
    co402_traj_t t;
    int64_t top = 0;
    unsigned n = 0;
    (void)state;
    co402_traj_set(&t, 0, 0);
    /* 1000 increments never reach 20000/s: peak sqrt(1000 * 50000) = 7071/s */
    while (!co402_traj_pos(&t, 1000LL * Q, 20000U, 50000U, 50000U, 1000U)) {
        if (t.v > top) {
            top = t.v;
        }
        n++;
    }
    assert_in_range((unsigned)(top / Q), 6950U, 7100U);
    assert_in_range(n, 275U, 290U);
}

static void traj_unlimited(void **state)
{
    co402_traj_t t;
    (void)state;
    co402_traj_set(&t, 0, 0);
    /* no acceleration limit: at speed in one step; no deceleration limit: stops dead */
    assert_false(co402_traj_pos(&t, 100LL * Q, 10000U, 0U, 0U, 1000U));
    assert_int_equal(t.v, 10000LL * Q);
    assert_int_equal(t.p, 5LL * Q); /* average of 0 and 10000 over 1 ms */
    for (int i = 0; i < 9; i++) {
        assert_false(co402_traj_pos(&t, 100LL * Q, 10000U, 0U, 0U, 1000U));
    }
    assert_true(co402_traj_pos(&t, 100LL * Q, 10000U, 0U, 0U, 1000U));
    assert_int_equal(t.p, 100LL * Q);
}

static void traj_target_behind(void **state)
{
    co402_traj_t t;
    int64_t top = 0;
    (void)state;
    co402_traj_set(&t, 0, 0);
    for (int i = 0; i < 1000; i++) {
        (void)co402_traj_pos(&t, 100000LL * Q, 20000U, 50000U, 50000U, 1000U);
    }
    assert_int_equal(t.v, 20000LL * Q);
    /* the target jumps behind: brake with dec (0.4 s, 4000 increments), come back */
    for (int i = 0; i < 20000; i++) {
        int64_t v = t.v;
        if (co402_traj_pos(&t, 10000LL * Q, 20000U, 50000U, 50000U, 1000U)) {
            break;
        }
        assert_true(abs64(t.v - v) <= (50LL * Q * 3 / 2));
        if (t.p > top) {
            top = t.p;
        }
    }
    assert_int_equal(t.p, 10000LL * Q);
    assert_in_range((uint64_t)(top / Q), 19900U, 20100U); /* 16000 + 4000 of braking */
}

static void traj_velocity_through_zero(void **state)
{
    co402_traj_t t;
    unsigned n = 0;
    (void)state;
    co402_traj_set(&t, 0, 10000LL * Q);
    /* down at dec (0.1 s), then up the other way at acc (0.01 s) */
    while (!co402_traj_vel(&t, -10000LL * Q, 1000000U, 100000U, 1000U)) {
        n++;
        if (n == 100U) {
            assert_int_equal(t.v, 0);
        }
    }
    assert_int_equal(n + 1U, 110U);
    assert_int_equal(t.a, -1000000);
    assert_int_equal(co402_traj_stop_point(&t, 100000U), t.p - 500LL * Q);
    co402_traj_set(&t, 7LL * Q, 20000LL * Q);
    assert_int_equal(co402_traj_stop_point(&t, 100000U), (7LL + 2000LL) * Q);
    assert_int_equal(co402_traj_stop_point(&t, 0U), 7LL * Q);
}

static void isqrt(void **state)
{
    (void)state;
    assert_int_equal(co402_isqrt(0), 0);
    assert_int_equal(co402_isqrt(1), 1);
    assert_int_equal(co402_isqrt(3), 1);
    assert_int_equal(co402_isqrt(4), 2);
    assert_int_equal(co402_isqrt(99999999), 9999);
    assert_int_equal(co402_isqrt(100000000), 10000);
    assert_int_equal(co402_isqrt(UINT64_MAX), 0xFFFFFFFFULL);
}

/* ------------------------------------------------------------ the plant */

static co402_sim_t sim;
static co402_feedback_t fb;

static void sim_start(const co402_sim_config_t *c)
{
    co402_sim_init(&sim, c, 0);
}

static void cmd(uint8_t kind, int64_t p, int64_t v, int16_t tq)
{
    co402_plant_t pl = co402_sim_plant(&sim);
    co402_demand_t d;
    memset(&d, 0, sizeof d);
    d.kind = kind;
    d.pos = p;
    d.vel = v;
    d.torque = tq;
    pl.ops->command(pl.ctx, &d);
}

static void upd(uint32_t t)
{
    co402_plant_t pl = co402_sim_plant(&sim);
    pl.ops->update(pl.ctx, t, &fb);
}

static void sim_index_and_switches(void **state)
{
    co402_sim_config_t c;
    (void)state;
    co402_sim_defaults(&c);
    c.index_offset = 100;
    c.switches = CO402_IN_HOME | CO402_IN_POS_LIMIT | CO402_IN_NEG_LIMIT;
    c.home_lo = 1000;
    c.home_hi = 2000;
    c.pos_limit = 9000;
    c.neg_limit = -9000;
    sim_start(&c);
    upd(0);
    assert_int_equal(fb.inputs, CO402_IN_ENABLE | CO402_IN_VOLTAGE);
    cmd(CO402_DEMAND_VELOCITY, 0, 10000LL * Q, 0);
    upd(150000);
    assert_int_equal(fb.index_count, 1U); /* at about 1500 after 0.15 s: the pulse at 100 */
    assert_int_equal(fb.index_pos, 100LL * Q);
    assert_int_equal(fb.edge_count[2], 1U); /* home switch entered at its lower end */
    assert_int_equal(fb.edge_pos[2], 1000LL * Q);
    assert_int_equal(fb.inputs & CO402_IN_HOME, CO402_IN_HOME);
    upd(500000);
    assert_int_equal(fb.index_count, 2U);
    assert_int_equal(fb.index_pos, 4196LL * Q);
    assert_int_equal(fb.edge_count[2], 2U);
    assert_int_equal(fb.edge_pos[2], 2000LL * Q);
    assert_int_equal(fb.inputs & CO402_IN_HOME, 0);
    upd(1000000);
    assert_int_equal(fb.inputs & CO402_IN_POS_LIMIT, CO402_IN_POS_LIMIT);
    assert_int_equal(fb.edge_count[1], 1U);
    assert_int_equal(fb.edge_pos[1], 9000LL * Q);
    assert_int_equal(fb.index_pos, 8292LL * Q);
    /* and back: the pulses passed backwards count too */
    cmd(CO402_DEMAND_VELOCITY, 0, -10000LL * Q, 0);
    upd(2000000);
    assert_int_equal(fb.inputs & CO402_IN_POS_LIMIT, 0);
    assert_int_equal(fb.edge_count[1], 2U);
    assert_int_equal(fb.index_count, 6U); /* 100, 4196, 8292 up; 8292, 4196, 100 down */
    assert_int_equal(fb.index_pos, 100LL * Q);
    /* the whole home switch in one step: two edges, the last at its lower end */
    c.speed_max = 20000000U;
    c.start_pos = 2500;
    co402_sim_init(&sim, &c, 0);
    sim.v = -8000000LL * Q; /* 2000 increments in one step of 250 us */
    upd(250);
    assert_int_equal(sim.edge_count[2], 2U);
    assert_int_equal(sim.edge_pos[2], 1000LL * Q);
}

static void sim_inertia_and_limits(void **state)
{
    co402_sim_config_t c;
    (void)state;
    co402_sim_defaults(&c);
    c.friction = 0;
    sim_start(&c);
    /* rated torque: 2048000 increments/s^2 */
    cmd(CO402_DEMAND_TORQUE, 0, 0, 1000);
    upd(10000);
    assert_in_range((uint64_t)co402_sim_velocity(&sim), 20470U, 20490U);
    assert_int_equal(fb.torque, 1000);
    /* the speed limit */
    cmd(CO402_DEMAND_TORQUE, 0, 0, 3000);
    upd(200000);
    assert_int_equal(co402_sim_velocity(&sim), 409600);
    /* the torque limit of the demand and of the motor */
    cmd(CO402_DEMAND_VELOCITY, 0, 0, 0);
    upd(200250);
    assert_int_equal(fb.torque, -3000);
    /* brake: full torque against the motion, stops at zero and stays */
    cmd(CO402_DEMAND_BRAKE, 0, 0, 0);
    upd(300000);
    assert_int_equal(co402_sim_velocity(&sim), 0);
    upd(400000);
    assert_int_equal(co402_sim_velocity(&sim), 0);
    /* a plant fault removes the torque */
    co402_sim_set_fault(&sim, 0x2310);
    cmd(CO402_DEMAND_TORQUE, 0, 0, 1000);
    upd(500000);
    assert_int_equal(co402_sim_velocity(&sim), 0);
    assert_int_equal(fb.fault, 0x2310);
    co402_sim_set_level(&sim, CO402_IN_ENABLE, false);
    upd(500000);
    assert_int_equal(fb.inputs & (CO402_IN_ENABLE | CO402_IN_VOLTAGE), CO402_IN_VOLTAGE);
}

static void sim_friction_coasts(void **state)
{
    co402_sim_config_t c;
    (void)state;
    co402_sim_defaults(&c);
    c.friction = 2;
    sim_start(&c);
    sim.v = 10000LL * Q;
    cmd(CO402_DEMAND_OFF, 0, 0, 0);
    upd(500000); /* e^-1 */
    assert_in_range((uint64_t)co402_sim_velocity(&sim), 3670U, 3690U);
}

static void sim_position_loop(void **state)
{
    co402_sim_config_t c;
    (void)state;
    co402_sim_defaults(&c);
    sim_start(&c);
    cmd(CO402_DEMAND_POSITION, 300LL * Q, 0, 0);
    upd(200000);
    assert_int_equal(co402_sim_position(&sim), 300);
    assert_in_range((uint64_t)(co402_sim_velocity(&sim) + 2), 0U, 4U);
}

static void sim_is_deterministic(void **state)
{
    co402_sim_config_t c;
    co402_sim_t a, b;
    co402_plant_t pa, pb;
    co402_feedback_t fa, fbb;
    co402_demand_t d;
    (void)state;
    co402_sim_defaults(&c);
    co402_sim_init(&a, &c, 0);
    co402_sim_init(&b, &c, 0);
    pa = co402_sim_plant(&a);
    pb = co402_sim_plant(&b);
    memset(&d, 0, sizeof d);
    d.kind = CO402_DEMAND_POSITION;
    d.pos = 5000LL * Q;
    d.vel = 1000LL * Q;
    d.acc = 20000;
    pa.ops->command(pa.ctx, &d);
    pb.ops->command(pb.ctx, &d);
    /* the same inputs at the same times, pushed in steps of 1 ms or all at once */
    for (uint32_t t = 1000; t <= 20000U; t += 1000U) {
        pa.ops->update(pa.ctx, t, &fa);
    }
    pb.ops->update(pb.ctx, 20000U, &fbb);
    assert_int_equal(fa.pos, fbb.pos);
    assert_int_equal(fa.vel, fbb.vel);
    assert_memory_equal(&a, &b, sizeof a);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(traj_trapezoid),
        cmocka_unit_test(traj_triangle),
        cmocka_unit_test(traj_unlimited),
        cmocka_unit_test(traj_target_behind),
        cmocka_unit_test(traj_velocity_through_zero),
        cmocka_unit_test(isqrt),
        cmocka_unit_test(sim_index_and_switches),
        cmocka_unit_test(sim_inertia_and_limits),
        cmocka_unit_test(sim_friction_coasts),
        cmocka_unit_test(sim_position_loop),
        cmocka_unit_test(sim_is_deterministic),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
