/*
 * What the CiA 408 profile drives: the valve plant interface.
 *
 * The profile (device state machine, set-point path, windows) computes a
 * demand every control tick and hands it to a plant: the solenoid drivers,
 * the spool and, in the closed-loop modes, the controlled quantity (pressure,
 * flow, axis position) with its controller. A real valve electronics
 * implements the two calls on its hardware; co408_sim.h implements them as a
 * simulated valve.
 *
 * Units: the internal resolution of CiA 408, 16384 = 100 % (spool opening,
 * solenoid current of Imax, controlled quantity of its reference range);
 * negative values open the spool the other way (solenoid B).
 */
#ifndef CO408_PLANT_H
#define CO408_PLANT_H

#include <stdint.h>

#define CO408_FULL 16384 /**< 100 % in the internal resolution */

/** What the plant shall do until the next demand. */
typedef enum co408_demand_kind {
    CO408_DEMAND_OFF = 0, /**< solenoids off */
    CO408_DEMAND_OPEN,    /**< open loop: spool opening @p value */
    CO408_DEMAND_CLOSED   /**< closed loop: controlled quantity to @p value */
} co408_demand_kind_t;

typedef struct co408_demand {
    uint8_t kind;   /**< co408_demand_kind_t */
    int32_t value;  /**< -CO408_FULL .. CO408_FULL */
} co408_demand_t;

/* Inputs (co408_feedback_t.inputs). */
#define CO408_IN_ENABLE 0x01U /**< the enable digital input (local control, 604Fh = 1) */

typedef struct co408_feedback {
    int32_t current;    /**< solenoid current, +: solenoid A, -: solenoid B (of Imax) */
    int32_t spool;      /**< spool position (opening) */
    int32_t actual;     /**< controlled quantity (closed loop) */
    int32_t local_sp;   /**< the local (analog) set-point input (6042h = 2) */
    uint32_t inputs;    /**< CO408_IN_* */
    uint16_t fault;     /**< 0, or the EMCY code of a fault the electronics detect */
} co408_feedback_t;

typedef struct co408_plant_ops {
    /** Advance to @p now_us under the demand last given and report. */
    void (*update)(void *ctx, uint32_t now_us, co408_feedback_t *fb);
    /** The demand from now on. */
    void (*command)(void *ctx, const co408_demand_t *d);
} co408_plant_ops_t;

typedef struct co408_plant {
    const co408_plant_ops_t *ops;
    void *ctx;
} co408_plant_t;

#endif /* CO408_PLANT_H */
