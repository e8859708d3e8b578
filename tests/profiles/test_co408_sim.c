/*
 * The simulated valve: solenoid current lag, spool from the current beyond
 * Imin, closed-loop response, fault codes, determinism in simulated time.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "co/co408_sim.h"

static co408_feedback_t run(co408_sim_t *s, const co408_demand_t *d, uint32_t t_us)
{
    co408_plant_t p = co408_sim_plant(s);
    co408_feedback_t fb;

    p.ops->command(p.ctx, d);
    p.ops->update(p.ctx, t_us, &fb);
    return fb;
}

static void current_lag_and_imin(void **state)
{
    co408_sim_config_t c;
    co408_sim_t s;
    co408_demand_t d = {CO408_DEMAND_OPEN, CO408_FULL};
    co408_feedback_t fb;

    (void)state;
    co408_sim_defaults(&c);
    co408_sim_init(&s, &c, 0U);
    fb = run(&s, &d, 500U); /* the current rises, still below Imin (12.5 %) */
    assert_in_range(fb.current, 1, 2047);
    assert_int_equal(fb.spool, 0);
    fb = run(&s, &d, 5000U); /* one time constant: about 63 % of the current */
    assert_in_range(fb.current, 9900, 10700);
    {
        /* the spool: the current beyond Imin over Imax - Imin (rounding apart) */
        int32_t want = ((fb.current - 2048) * CO408_FULL) / (CO408_FULL - 2048);
        assert_in_range(fb.spool, want - 2, want + 2);
    }
    fb = run(&s, &d, 50000U);
    assert_in_range(fb.current, 16380, 16384);
    /* solenoid B the other way */
    d.value = -CO408_FULL / 2;
    fb = run(&s, &d, 150000U);
    assert_in_range(fb.spool, -8200, -8180);
    assert_true(fb.current < -2048);
    d.kind = CO408_DEMAND_OFF;
    fb = run(&s, &d, 250000U);
    assert_int_equal(fb.current, 0);
    assert_int_equal(fb.spool, 0);
}

static void closed_loop_reaches_target(void **state)
{
    co408_sim_config_t c;
    co408_sim_t s;
    co408_demand_t d = {CO408_DEMAND_CLOSED, 6000};
    co408_feedback_t fb;

    (void)state;
    co408_sim_defaults(&c);
    co408_sim_init(&s, &c, 0U);
    fb = run(&s, &d, 20000U);
    assert_in_range(fb.actual, 1000, 5990);
    fb = run(&s, &d, 400000U);
    assert_in_range(fb.actual, 5990, 6010);
}

static void faults(void **state)
{
    co408_sim_config_t c;
    co408_sim_t s;
    co408_demand_t d = {CO408_DEMAND_OPEN, CO408_FULL};
    co408_feedback_t fb;

    (void)state;
    assert_int_equal(co408_sim_fault_code(0U), 0);
    assert_int_equal(co408_sim_fault_code(CO408_SIM_SOL_A_OPEN), 0x2311);
    assert_int_equal(co408_sim_fault_code(CO408_SIM_SOL_A_SHORT), 0x2311);
    assert_int_equal(co408_sim_fault_code(CO408_SIM_SOL_B_OPEN), 0x2312);
    assert_int_equal(co408_sim_fault_code(CO408_SIM_SOL_B_SHORT), 0x2312);
    assert_int_equal(co408_sim_fault_code(CO408_SIM_UNDERVOLT), 0x3412);
    assert_int_equal(co408_sim_fault_code(CO408_SIM_SP_CABLE), 0x3422);
    assert_int_equal(co408_sim_fault_code(CO408_SIM_SP_CABLE | CO408_SIM_UNDERVOLT), 0x3412);
    co408_sim_defaults(&c);
    co408_sim_init(&s, &c, 0U);
    co408_sim_set_local_sp(&s, 4000);
    fb = run(&s, &d, 100000U);
    assert_int_equal(fb.local_sp, 4000);
    co408_sim_inject(&s, CO408_SIM_SOL_A_OPEN | CO408_SIM_SP_CABLE);
    fb = run(&s, &d, 200000U); /* no current flows: the spool closes */
    assert_int_equal(fb.fault, 0x2311);
    assert_int_equal(fb.current, 0);
    assert_int_equal(fb.spool, 0);
    assert_int_equal(fb.local_sp, 0);
}

/* The same demands at the same times: the same response, whatever the
 * update calls in between. */
static void deterministic(void **state)
{
    co408_sim_config_t c;
    co408_sim_t a;
    co408_sim_t b;
    co408_demand_t d = {CO408_DEMAND_CLOSED, 9000};
    co408_feedback_t fa;
    co408_feedback_t fb;

    (void)state;
    co408_sim_defaults(&c);
    co408_sim_init(&a, &c, 1000U);
    co408_sim_init(&b, &c, 1000U);
    fa = run(&a, &d, 1000U);
    fb = run(&b, &d, 1000U);
    for (uint32_t t = 2000U; t <= 61000U; t += 1000U) {
        fa = run(&a, &d, t);
    }
    fb = run(&b, &d, 61000U);
    assert_memory_equal(&fa, &fb, sizeof fa);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(current_lag_and_imin),
        cmocka_unit_test(closed_loop_reaches_target),
        cmocka_unit_test(faults),
        cmocka_unit_test(deterministic),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
