/*
 * What the CiA 402 profile drives: the plant interface.
 *
 * The profile (state machine, modes, profile generator, homing) computes a
 * demand every control tick and hands it to a plant; the plant runs the
 * servo loops and the power stage and reports back. A real drive implements
 * these two calls on its hardware (encoder counter with latches, PWM stage,
 * limit/home inputs); co402_sim.h implements them as a simulated motor.
 *
 * Units: positions in increments as Q16 fixed point (1 increment = 65536),
 * velocities in increments per second as Q16, accelerations in increments
 * per second squared, torques in per mille of the rated torque.
 */
#ifndef CO402_PLANT_H
#define CO402_PLANT_H

#include <stdbool.h>
#include <stdint.h>

#define CO402_Q16 65536
/** Largest magnitude of a position (Q16 increments) or velocity (Q16
 *  increments/s) the profile hands on: the range of a 32-bit object in Q16.
 *  Unit scaling saturates to it, so no later product overflows 64 bits. */
#define CO402_Q16_MAX ((int64_t)INT32_MAX * CO402_Q16)

/** What the plant shall do until the next demand. */
typedef enum co402_demand_kind {
    CO402_DEMAND_OFF = 0,    /**< power stage off: no torque, the motor coasts */
    CO402_DEMAND_POSITION,   /**< follow pos (with vel / acc feed-forward) */
    CO402_DEMAND_VELOCITY,   /**< follow vel (with acc feed-forward) */
    CO402_DEMAND_TORQUE,     /**< produce torque */
    CO402_DEMAND_BRAKE       /**< brake at the torque limit to standstill, then hold
                                  velocity 0 ("slow down on current limit") */
} co402_demand_kind_t;

typedef struct co402_demand {
    uint8_t kind;            /**< co402_demand_kind_t */
    int64_t pos;             /**< Q16 increments (raw plant coordinates) */
    int64_t vel;             /**< Q16 increments/s */
    int32_t acc;             /**< increments/s^2 (feed-forward) */
    int16_t torque;          /**< per mille of rated torque (TORQUE) */
    uint16_t torque_limit;   /**< per mille; 0: the plant's own maximum */
} co402_demand_t;

/* Digital inputs (co402_feedback_t.inputs); bits 0..2 as in 0x60FD. */
#define CO402_IN_NEG_LIMIT 0x01U /**< negative limit switch active */
#define CO402_IN_POS_LIMIT 0x02U /**< positive limit switch active */
#define CO402_IN_HOME      0x04U /**< home switch active */
#define CO402_IN_ENABLE    0x08U /**< hardware enable (interlock) present */
#define CO402_IN_VOLTAGE   0x10U /**< DC-link (high) voltage present */
#define CO402_IN_EDGES     3U    /**< inputs with edge latches: limits and home */

typedef struct co402_feedback {
    int64_t pos;             /**< Q16 increments (raw plant coordinates) */
    int64_t vel;             /**< Q16 increments/s */
    int16_t torque;          /**< per mille of rated torque */
    uint32_t inputs;         /**< CO402_IN_* */
    uint16_t fault;          /**< 0, or an error code (CiA 402 / EMCY) the plant reports */
    /** Edge latches of the switches (index = bit number of CO402_IN_*): the
     *  count advances on every change, pos holds where the last one was. */
    uint32_t edge_count[CO402_IN_EDGES];
    int64_t edge_pos[CO402_IN_EDGES];
    /** Index (zero) pulse latch: count of pulses passed, where the last was. */
    uint32_t index_count;
    int64_t index_pos;
} co402_feedback_t;

typedef struct co402_plant_ops {
    /** Advance to @p now_us under the demand last given and report. */
    void (*update)(void *ctx, uint32_t now_us, co402_feedback_t *fb);
    /** The demand from now on. */
    void (*command)(void *ctx, const co402_demand_t *d);
} co402_plant_ops_t;

typedef struct co402_plant {
    const co402_plant_ops_t *ops;
    void *ctx;
} co402_plant_t;

#endif /* CO402_PLANT_H */
