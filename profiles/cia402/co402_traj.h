/*
 * Profile generator of the CiA 402 profile (internal): an on-line
 * trapezoidal trajectory. Every control tick it moves a demand (position,
 * velocity, acceleration) one step towards a goal under velocity and
 * acceleration limits, so a goal may change at any time (change set
 * immediately, halt, quick stop) without a jump in the demand.
 *
 * Positions Q16 increments, velocities Q16 increments/s, limits in whole
 * increments/s and increments/s^2 (0 = unlimited).
 */
#ifndef CO402_TRAJ_H
#define CO402_TRAJ_H

#include <stdbool.h>
#include <stdint.h>

typedef struct co402_traj {
    int64_t p;   /**< demand position, Q16 increments */
    int64_t v;   /**< demand velocity, Q16 increments/s */
    int32_t a;   /**< acceleration of the last step, increments/s^2 */
} co402_traj_t;

/** Start from a position and velocity (bumpless take-over). */
void co402_traj_set(co402_traj_t *t, int64_t p, int64_t v);

/** One step towards @p target, to arrive at rest. Returns true when the
 *  demand is at the target at rest. */
bool co402_traj_pos(co402_traj_t *t, int64_t target, uint32_t vmax, uint32_t acc, uint32_t dec,
                    uint32_t dt_us);

/** One step of the velocity towards @p vtarget (Q16): @p acc while the
 *  speed grows, @p dec while it shrinks. Returns true once there. */
bool co402_traj_vel(co402_traj_t *t, int64_t vtarget, uint32_t acc, uint32_t dec, uint32_t dt_us);

/** The position at which a stop with @p dec from the present state ends. */
int64_t co402_traj_stop_point(const co402_traj_t *t, uint32_t dec);

/** Integer square root of a 64-bit value. */
uint64_t co402_isqrt(uint64_t x);

#endif /* CO402_TRAJ_H */
