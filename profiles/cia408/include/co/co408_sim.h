/*
 * A simulated proportional valve for the CiA 408 profile: two solenoid
 * drivers whose currents follow their demand with a first-order lag, a spool
 * that opens in proportion to the current beyond Imin (solenoid A one way,
 * B the other), and a controlled quantity (pressure, flow or axis) that
 * follows the spool opening with a first-order lag; in the closed-loop
 * modes a proportional controller with feed-forward drives the spool so
 * that it reaches the target. Integer arithmetic, driven only by the time
 * pushed in: the same inputs at the same times give the same response on
 * every machine.
 *
 * Fault injection: solenoid cable break or short (EMCY 0x2311 / 0x2312),
 * supply under-voltage (0x3412), set-point cable break (0x3422); the plant
 * reports the code, the profile raises it.
 *
 * It implements co408_plant.h; a real valve electronics replaces it.
 */
#ifndef CO408_SIM_H
#define CO408_SIM_H

#include <stdbool.h>
#include <stdint.h>

#include "co/co408_plant.h"

typedef struct co408_sim_config {
    uint32_t step_us;     /**< integration step (0: 250 us) */
    uint32_t tau_i_us;    /**< solenoid current time constant */
    uint32_t tau_y_us;    /**< controlled quantity time constant */
    int32_t i_min;        /**< Imin: current where the spool starts to open (of Imax) */
    int32_t i_max;        /**< Imax (CO408_FULL = the driver's full current) */
    uint32_t kp;          /**< closed loop: proportional gain, 1/1000 */
} co408_sim_config_t;

/* Faults (co408_sim_inject). */
#define CO408_SIM_SOL_A_OPEN  0x01U /**< solenoid A cable break */
#define CO408_SIM_SOL_A_SHORT 0x02U /**< solenoid A short circuit */
#define CO408_SIM_SOL_B_OPEN  0x04U
#define CO408_SIM_SOL_B_SHORT 0x08U
#define CO408_SIM_UNDERVOLT   0x10U /**< supply voltage too low */
#define CO408_SIM_SP_CABLE    0x20U /**< set-point input cable break */

typedef struct co408_sim {
    co408_sim_config_t cfg;
    co408_demand_t d;
    int64_t ia;           /* solenoid A current, Q16 */
    int64_t ib;
    int64_t y;            /* controlled quantity, Q16 */
    uint32_t t;           /* simulated up to this time */
    uint32_t faults;      /* CO408_SIM_* */
    uint32_t inputs;      /* CO408_IN_* */
    int32_t local_sp;
} co408_sim_t;

/** Defaults: 250 us step, current lag 5 ms, controlled quantity lag 50 ms,
 *  Imin 12.5 % (2048), Imax 100 %, kp 3.0, enable input off. */
void co408_sim_defaults(co408_sim_config_t *cfg);

void co408_sim_init(co408_sim_t *s, const co408_sim_config_t *cfg, uint32_t now_us);

/** The plant interface of @p s (co408_config_t.plant). */
co408_plant_t co408_sim_plant(co408_sim_t *s);

/** Set the injected faults (CO408_SIM_*; 0: none). */
void co408_sim_inject(co408_sim_t *s, uint32_t faults);

/** Set or clear inputs (CO408_IN_ENABLE). */
void co408_sim_set_input(co408_sim_t *s, uint32_t mask, bool on);

/** The local set-point input (internal resolution). */
void co408_sim_set_local_sp(co408_sim_t *s, int32_t q);

/** The EMCY code the electronics detect for @p faults (0: none). */
uint16_t co408_sim_fault_code(uint32_t faults);

#endif /* CO408_SIM_H */
