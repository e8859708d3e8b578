/*
 * CiA 402 devices: everything needed to run a drive described in
 * devices/<name>.toml with the CiA 402 profile, as data: its generated
 * dictionary, its axes, the profile options and tables that make its
 * deviations from CiA 402, the plant its simulation starts from and what it
 * does after power-on. A daemon picks a device by name (devices/
 * co402_devices.h) and runs it the same way for every drive:
 *
 *     co402_drive_init(&drv, device, plants, &app_callbacks);
 *     cfg.dev = device->dev; cfg.ram = ...; cfg.hooks = ...;  (sizes from dev)
 *     cfg.cb = co402_drive_callbacks(&drv);
 *     co_node_init(&node, &cfg, now);
 *     co402_drive_attach(&drv, &node, now);
 *     loop: co_node_rx / co_node_process, co402_drive_process
 *
 * A device whose behaviour is neither core nor profile (manufacturer
 * objects, vendor error handling) names a device plug-in (plugin): it runs
 * on the same host after the axes, its instance is the co402_drive_t (so it
 * reaches the node, the axes and its own state, co402_drive_node/_axis/
 * _state), its state (state_size bytes) is the caller's, given by
 * co402_drive_set_state() before co402_drive_attach.
 *
 * No allocation: the caller owns the co402_drive_t.
 */
#ifndef CO402_DEVICE_H
#define CO402_DEVICE_H

#include <stddef.h>
#include <stdint.h>

#include "co/co402.h"
#include "co/co402_sim.h"
#include "co/co_node.h"
#include "co/co_profile.h"

#ifndef CO402_DRIVE_AXES_MAX
#define CO402_DRIVE_AXES_MAX 4U /**< axes one co402_drive_t can hold */
#endif

/** A CiA 402 device type (const, one per description). */
typedef struct co402_device {
    const char *name;                    /**< the description's name (devices/<name>.toml) */
    const co_dev_t *dev;                 /**< its generated dictionary */
    uint8_t axes;                        /**< axes at 0x6000 + 0x800 * n, 1..CO402_DRIVE_AXES_MAX */
    uint32_t options;                    /**< CO402_OPT_* of every axis */
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
    /** The simulated plant of this drive: changes co402_sim_defaults() (motor,
     *  encoder) where the device differs (NULL: the defaults). */
    void (*sim_config)(co402_sim_config_t *c);
    /** After power-on, once the node and its axes have started (NULL: nothing);
     *  e.g. a device that enters Operational by itself. */
    void (*powered_on)(co_node_t *node, uint32_t now_us);
    /** The device plug-in (NULL: none); its instance is the co402_drive_t. */
    const co_profile_ops_t *plugin;
    size_t state_size;                   /**< bytes of plug-in state the caller provides */
} co402_device_t;

/** The profile side of one node of a CiA 402 device. Fields are private. */
typedef struct co402_drive {
    const co402_device_t *device;
    co_profile_host_t host;
    co_profile_t slots[CO402_DRIVE_AXES_MAX + 1U]; /* the axes and the device plug-in */
    co402_axis_t axis[CO402_DRIVE_AXES_MAX];
    co_node_t *node;                     /* from co402_drive_attach */
    void *state;                         /* the device plug-in's state */
} co402_drive_t;

/** The profile configuration of axis @p axis of @p device on @p plant. */
void co402_device_axis_config(const co402_device_t *device, uint8_t axis, co402_plant_t plant,
                              co402_config_t *cfg);

/** The simulation parameters of @p device (co402_sim_defaults + sim_config). */
void co402_device_sim_config(const co402_device_t *device, co402_sim_config_t *c);

/** Prepare @p drv: one axis per plant (plants[n] drives axis n), the
 *  application's callbacks @p app (NULL: none) called after the axes'.
 *  Returns CO_ERR_VALUE for a device with no or too many axes. */
co_err_t co402_drive_init(co402_drive_t *drv, const co402_device_t *device,
                          const co402_plant_t *plants, const co_node_callbacks_t *app);

/** The node callbacks to put into co_node_config_t.cb before co_node_init. */
co_node_callbacks_t co402_drive_callbacks(co402_drive_t *drv);

/** The device plug-in's state (device->state_size bytes, zeroed here); call
 *  before co402_drive_attach. */
void co402_drive_set_state(co402_drive_t *drv, void *state);

/** After co_node_init: attach the axes (they start in Switch on disabled) and
 *  the device plug-in, and run the device's power-on step. CO_ERR_VALUE for a
 *  device whose plug-in wants state that was not given. */
co_err_t co402_drive_attach(co402_drive_t *drv, co_node_t *node, uint32_t now_us);

/** Run the axes up to @p now_us; the next time they want (CO_NO_DEADLINE: never). */
uint32_t co402_drive_process(co402_drive_t *drv, uint32_t now_us);

/** Axis @p n (NULL beyond the device's axes). */
co402_axis_t *co402_drive_axis(co402_drive_t *drv, uint8_t n);

/** The node (NULL before co402_drive_attach). */
co_node_t *co402_drive_node(const co402_drive_t *drv);

/** The device plug-in's state (co402_drive_set_state). */
void *co402_drive_state(const co402_drive_t *drv);

#endif /* CO402_DEVICE_H */
