/*
 * A simulated drive plant for the CiA 402 profile: a motor with inertia,
 * torque and speed limits and viscous friction, a cascaded position /
 * velocity loop, limit switches, a home switch and an index pulse per
 * revolution. Integer arithmetic, driven only by the time pushed in, so the
 * same inputs at the same times give the same motion on every machine.
 *
 * It implements co402_plant.h; a real drive replaces it with its hardware.
 */
#ifndef CO402_SIM_H
#define CO402_SIM_H

#include <stdbool.h>
#include <stdint.h>

#include "co/co402_plant.h"

typedef struct co402_sim_config {
    uint32_t step_us;        /**< integration step (0: 250 us) */
    uint32_t accel_rated;    /**< increments/s^2 the rated torque gives the unloaded
                                  motor (rated torque / inertia) */
    uint16_t torque_max;     /**< per mille of rated torque */
    uint32_t speed_max;      /**< increments/s */
    uint16_t kp;             /**< position loop gain, 1/s */
    uint16_t kv;             /**< velocity loop gain, 1/s */
    uint32_t ki;             /**< velocity loop integral gain, 1/s^2 */
    uint16_t friction;       /**< viscous friction, 1/s (deceleration = friction * v) */
    uint32_t counts_per_rev; /**< an index pulse every counts_per_rev increments (0: none) */
    int32_t index_offset;    /**< position of one index pulse */
    uint32_t switches;       /**< switches fitted: CO402_IN_NEG_LIMIT | _POS_LIMIT | _HOME */
    int32_t neg_limit;       /**< negative limit switch active at p <= neg_limit */
    int32_t pos_limit;       /**< positive limit switch active at p >= pos_limit */
    int32_t home_lo;         /**< home switch active for home_lo <= p <= home_hi */
    int32_t home_hi;         /**< (INT32_MIN / INT32_MAX for a switch open on one side) */
    int32_t start_pos;       /**< position at power-on, increments */
} co402_sim_config_t;

typedef struct co402_sim {
    co402_sim_config_t cfg;
    co402_demand_t d;
    int64_t p;               /* Q16 increments */
    int64_t v;               /* Q16 increments/s */
    int64_t vi;              /* velocity loop integral, increments/s^2 */
    int64_t index_k;         /* index interval the position is in */
    int64_t edge_pos[CO402_IN_EDGES];
    int64_t index_pos;
    uint32_t edge_count[CO402_IN_EDGES];
    uint32_t index_count;
    uint32_t t;              /* simulated up to this time */
    uint32_t t_cmd;          /* time of the last command */
    uint32_t levels;         /* CO402_IN_ENABLE / _VOLTAGE as set */
    uint32_t inputs;         /* current inputs */
    int16_t torque;
    uint16_t fault;
} co402_sim_t;

/** Defaults: 4096 increments/rev, 100 rev/s top speed, 0.2 s from rest to
 *  top speed at rated torque, torque limit 300 %, kp 100/s, kv 600/s, ki 20000/s^2,
 *  no switches, enable and DC-link voltage present. */
void co402_sim_defaults(co402_sim_config_t *cfg);

void co402_sim_init(co402_sim_t *s, const co402_sim_config_t *cfg, uint32_t now_us);

/** The plant interface of @p s, for co402_config_t.plant. */
co402_plant_t co402_sim_plant(co402_sim_t *s);

/** Set or clear CO402_IN_ENABLE / CO402_IN_VOLTAGE. */
void co402_sim_set_level(co402_sim_t *s, uint32_t mask, bool on);

/** Report a plant fault (an error code such as 0x2310 over-current), 0 clears it. */
void co402_sim_set_fault(co402_sim_t *s, uint16_t code);

/** Actual position in whole increments, rounded (raw plant coordinates). */
int32_t co402_sim_position(const co402_sim_t *s);

/** Actual velocity in whole increments/s. */
int32_t co402_sim_velocity(const co402_sim_t *s);

#endif /* CO402_SIM_H */
