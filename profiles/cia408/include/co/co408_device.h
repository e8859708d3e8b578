/*
 * CiA 408 devices: everything needed to run a valve described in
 * devices/<name>.toml with the CiA 408 profile, as data: its generated
 * dictionary, its channels, the control modes each offers, how it answers
 * an unsupported mode value, and the valve its simulation starts from.
 *
 *     co408_unit_init(&u, device, plants, &app_callbacks);
 *     cfg.dev = device->dev; ...  cfg.cb = co408_unit_callbacks(&u);
 *     co_node_init(&node, &cfg, now);
 *     co408_unit_attach(&u, &node, now);
 *     loop: co_node_rx / co_node_process, co408_unit_process
 *
 * No allocation: the caller owns the co408_unit_t.
 */
#ifndef CO408_DEVICE_H
#define CO408_DEVICE_H

#include <stdint.h>

#include "co/co408.h"
#include "co/co408_sim.h"
#include "co/co_node.h"
#include "co/co_device.h"
#include "co/co_profile.h"

#define CO408_UNIT_CHANNELS_MAX 2U

/** A CiA 408 device type (const, one per description). */
typedef struct co408_device {
    const char *name;                     /**< the description's name */
    const co_dev_t *dev;                  /**< its generated dictionary */
    uint8_t channels;                     /**< 1..CO408_UNIT_CHANNELS_MAX */
    const int8_t *modes[CO408_UNIT_CHANNELS_MAX]; /**< co408_config_t.modes per channel */
    uint8_t n_modes[CO408_UNIT_CHANNELS_MAX];
    co_err_t bad_value;                   /**< co408_config_t.bad_value */
    /** The simulated valve of channel @p ch: changes co408_sim_defaults()
     *  where the device differs (NULL: the defaults). */
    void (*sim_config)(uint8_t ch, co408_sim_config_t *c);
} co408_device_t;

/** The profile side of one node of a CiA 408 device. Fields are private. */
typedef struct co408_unit {
    const co408_device_t *device;
    co_profile_host_t host;
    co_profile_t slots[CO408_UNIT_CHANNELS_MAX];
    co408_valve_t valve[CO408_UNIT_CHANNELS_MAX];
} co408_unit_t;

/** The simulation parameters of channel @p ch of @p device. */
void co408_device_sim_config(const co408_device_t *device, uint8_t ch, co408_sim_config_t *c);

/** Prepare @p u: plants[n] drives channel n; @p app (NULL: none) are the
 *  application's node callbacks, called after the channels'. CO_ERR_VALUE
 *  for a device with no or too many channels. */
co_err_t co408_unit_init(co408_unit_t *u, const co408_device_t *device,
                         const co408_plant_t *plants, const co_node_callbacks_t *app);

/** The node callbacks for co_node_config_t.cb. */
const co_node_callbacks_t *co408_unit_callbacks(co408_unit_t *u);

/** After co_node_init: attach the channels (they start in INIT). */
co_err_t co408_unit_attach(co408_unit_t *u, co_node_t *node, uint32_t now_us);

/** Run the channels up to @p now_us; the next time they want. */
uint32_t co408_unit_process(co408_unit_t *u, uint32_t now_us);

/** Channel @p n (NULL beyond the device's channels). */
co408_valve_t *co408_unit_valve(co408_unit_t *u, uint8_t n);

/** The control interface's way into the simulated valve (co_device_set,
 *  `canopen-device --control`: `set INDEX SUB VALUE`):
 *    - faults by their EMCY code as the index, the channel as the sub-index
 *      (0 or 1: channel 1, 2: channel 2): 0x2311 / 0x2312 solenoid 1 / 2
 *      (1 cable break, 2 short circuit, 0 repaired), 0x3412 supply
 *      under-voltage, 0x3422 set-point cable break (1 / 0);
 *    - inputs at CO408_SIM_INPUTS + channel (0-based): sub 1 the enable
 *      digital input (0 / 1), sub 2 the local set-point input (internal
 *      resolution, +-CO408_FULL).
 *  Other values answer 0x06090030 (value range). These indexes are not
 *  objects of the dictionary; another index goes to the dictionary. */
#define CO408_SIM_INPUTS      0x5F00U
#define CO408_SIM_IN_ENABLE   1U
#define CO408_SIM_IN_LOCAL_SP 2U

/** CiA 408 as a part of a device (co/co_device.h): config a co408_device_t,
 *  one co408_valve_t per channel on its simulated valve (co408_sim). */
extern const co_part_kind_t co408_part;

#endif /* CO408_DEVICE_H */
