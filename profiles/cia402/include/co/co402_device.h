/*
 * CiA 402 as a part of a device (co/co_device.h): the part kind co402_part
 * (one instance per axis, at 0x6000 + 0x800 * n, each on a co402_plant_t;
 * simulated: co402_sim) and its configuration co402_params_t, the profile
 * options and tables that make a drive's deviations from CiA 402.
 *
 *     static const co402_params_t params = { .options = ..., .hm_methods = ... };
 *     static const co_device_part_t parts[] = { { &co402_part, &params, 2 } };
 *
 * A vendor plug-in reaches the axes with co402_device_axis(run, n).
 */
#ifndef CO402_DEVICE_H
#define CO402_DEVICE_H

#include <stddef.h>
#include <stdint.h>

#include "co/co402.h"
#include "co/co402_sim.h"
#include "co/co_device.h"

/** The profile settings of every axis of a CiA 402 part. */
typedef struct co402_params {
    uint32_t options;                    /**< CO402_OPT_* */
    uint32_t modes;                      /**< co402_config_t.modes (devices without 0x6502) */
    uint32_t counts_per_rev;             /**< co402_config_t.counts_per_rev */
    const co402_hm_method_t *hm_methods; /**< co402_config_t.hm_methods */
    uint8_t n_hm_methods;
    const co402_error_t *errors;         /**< co402_config_t.errors */
    uint8_t n_errors;
    uint32_t vel_num;                    /**< co402_config_t.vel_num .. acc_den: fixed */
    uint32_t vel_den;                    /**< velocity / acceleration units where the */
    uint32_t acc_num;                    /**< device lacks 0x6094 / 0x6097 (0: none) */
    uint32_t acc_den;
    uint32_t full_speed;                 /**< co402_config_t.full_speed (VELOCITY_RAMP) */
    /** The simulated plant: changes co402_sim_defaults() (motor, encoder)
     *  where the device differs (NULL: the defaults). */
    void (*sim_config)(co402_sim_config_t *c);
} co402_params_t;

/** The CiA 402 part kind: instance co402_axis_t, plant co402_plant_t,
 *  simulation co402_sim_t. */
extern const co_part_kind_t co402_part;

/** The profile configuration of axis @p axis with @p params on @p plant. */
void co402_params_axis_config(const co402_params_t *params, uint8_t axis, co402_plant_t plant,
                              co402_config_t *cfg);

/** The simulation parameters (co402_sim_defaults + sim_config). */
void co402_params_sim_config(const co402_params_t *params, co402_sim_config_t *c);

/** The first CiA 402 part's settings of @p device (NULL: none). */
const co402_params_t *co402_device_params(const co_device_t *device);

/** Axis @p n of a device's CiA 402 parts (NULL beyond its axes). */
co402_axis_t *co402_device_axis(const co_device_run_t *run, uint8_t n);

/** Number of CiA 402 axes of @p device. */
uint8_t co402_device_axes(const co_device_t *device);

#endif /* CO402_DEVICE_H */
