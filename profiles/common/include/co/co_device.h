/*
 * Devices: everything needed to run a device described in devices/<name>.toml,
 * as const data, the same for every profile (CiA 402 drive, CiA 401 I/O
 * module, CiA 408 valve, a plain CiA 301 device):
 *
 *   - its generated dictionary (co_dev_t) and, where embedded, its EDS;
 *   - parts: plug-in instances of a profile kind (co_part_kind_t) with
 *     their const configuration (4 axes of a CiA 402 drive, one CiA 401
 *     module ...), each on a plant (the hardware, or the kind's simulation);
 *   - optionally a vendor plug-in for what is neither core nor profile (its
 *     instance is the co_device_run_t; state_size bytes of state);
 *   - optionally a power-on step.
 *
 * co_devices.h (generated from the descriptions in devices/) lists them by name.
 * Every device runs the same way; the memory for the instances, their
 * simulated plants and the plug-in state is one caller-provided block:
 *
 *     size_t n = co_device_mem_size(device, true);      (true: simulated plants)
 *     co_device_init(&run, device, mem, n, NULL, &app_callbacks, now);
 *     cfg.dev = device->dev; cfg.ram = ...;  (sizes from dev: with the hook table)
 *     cfg.cb = co_device_callbacks(&run);
 *     co_node_init(&node, &cfg, now);
 *     co_device_attach(&run, &node, now);
 *     loop: co_node_rx / co_node_process, co_device_process
 *
 * No allocation here: the caller owns co_device_run_t and the block.
 */
#ifndef CO_DEVICE_H
#define CO_DEVICE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "co/co_node.h"
#include "co/co_profile.h"

#ifndef CO_DEVICE_INST_MAX
#define CO_DEVICE_INST_MAX 8U /**< profile instances one device may have */
#endif

/** A kind of profile instance (one per profile: "cia402", "cia401", ...). */
typedef struct co_part_kind {
    const char *name;
    const co_profile_ops_t *ops;
    size_t inst_size;   /**< bytes of one instance */
    size_t plant_size;  /**< bytes of the plant interface the instance is given */
    size_t sim_size;    /**< bytes of one simulated plant (0: no simulation) */
    /** Set up instance @p n (0-based within its part) from @p config on
     *  @p plant (plant_size bytes: the kind's plant interface). */
    co_err_t (*init)(void *inst, const void *config, uint8_t n, const void *plant);
    /** Set up simulated plant @p n and write its plant interface into
     *  @p plant (plant_size bytes). NULL: the kind has no simulation. */
    void (*sim_init)(void *sim, const void *config, uint8_t n, uint32_t now_us, void *plant);
    /** Control interface (targets/linux, docs/linux.md): set @p value at
     *  @p index / @p sub the way the outside world would (an input of a
     *  simulated plant). CO_ERR_NO_OBJECT when the object is not the kind's
     *  to set (the caller then writes the dictionary). NULL: none. */
    co_err_t (*sim_set)(void *inst, void *sim, uint16_t index, uint8_t sub, int64_t value);
} co_part_kind_t;

/** @p count instances of @p kind with one @p config. */
typedef struct co_device_part {
    const co_part_kind_t *kind;
    const void *config;
    uint8_t count;
} co_device_part_t;

/** What a device's C file adds (devices/<cname>.c, named in the
 *  description's [profile] plugin): a vendor plug-in for what is neither
 *  core nor profile, and a power-on step. */
typedef struct co_device_plugin {
    /** The plug-in (NULL: none); its instance is the co_device_run_t. */
    const co_profile_ops_t *ops;
    size_t state_size;                   /**< bytes of plug-in state (zeroed) */
    /** After power-on, once the node and its instances have started (NULL:
     *  nothing); e.g. a device that enters Operational by itself. */
    void (*powered_on)(co_node_t *node, uint32_t now_us);
} co_device_plugin_t;

/** What a device adds to its dictionary; made by the generator from the
 *  description's [profile] tables ([profile.cia402], [profile.cia401] ...
 *  and plugin), or by a C file of devices/ ([profile] impl). */
typedef struct co_device_impl {
    const co_device_part_t *parts;
    uint8_t n_parts;
    const co_device_plugin_t *plugin;    /**< NULL: none */
} co_device_impl_t;

/** A device type (const, one per description). */
typedef struct co_device {
    const char *name;           /**< devices/<name>.toml */
    const char *summary;        /**< one line for canopen-device --list-devices */
    const co_dev_t *dev;        /**< its generated dictionary */
    const unsigned char *eds;   /**< its EDS text, NUL-terminated (NULL: not embedded) */
    const co_device_impl_t *impl; /**< NULL: the core alone */
} co_device_t;

/** The profile side of one node of a device. Fields are private. */
typedef struct co_device_run {
    const co_device_t *device;
    co_profile_host_t host;
    co_profile_t slots[CO_DEVICE_INST_MAX + 1U]; /* the instances and the plug-in */
    void *inst[CO_DEVICE_INST_MAX];
    void *sim[CO_DEVICE_INST_MAX];    /* NULL: the caller's plant */
    uint8_t part_of[CO_DEVICE_INST_MAX];
    uint8_t n_inst;
    co_node_t *node;                  /* from co_device_attach */
    void *state;                      /* the plug-in's state */
} co_device_run_t;

/** Bytes of the memory block co_device_init needs for @p device (instances,
 *  plug-in state and, with @p simulated, the simulated plants). */
size_t co_device_mem_size(const co_device_t *device, bool simulated);

/** Prepare @p run in @p mem (@p mem_size bytes, zeroed here, aligned for
 *  any type): every instance on a simulated plant (@p plants NULL), or on
 *  plants[k] for the k-th instance (counted over the parts in order; each
 *  the kind's plant interface). @p app: the application's callbacks (NULL:
 *  none), called after the instances'. CO_ERR_VALUE for a device with too
 *  many instances, a block too small, or a kind without simulation. */
co_err_t co_device_init(co_device_run_t *run, const co_device_t *device, void *mem,
                        size_t mem_size, const void *const *plants,
                        const co_node_callbacks_t *app, uint32_t now_us);

/** The node callbacks to put into co_node_config_t.cb before co_node_init. */
const co_node_callbacks_t *co_device_callbacks(co_device_run_t *run);

/** After co_node_init: attach the instances and the plug-in, then run the
 *  power-on step. */
co_err_t co_device_attach(co_device_run_t *run, co_node_t *node, uint32_t now_us);

/** Run the instances up to @p now_us; the next time they want. */
uint32_t co_device_process(co_device_run_t *run, uint32_t now_us);

/** The @p n-th instance of kind @p kind (NULL: none). */
void *co_device_instance(const co_device_run_t *run, const co_part_kind_t *kind, uint8_t n);

/** The simulated plant of the k-th instance overall (NULL: none). */
void *co_device_sim(const co_device_run_t *run, uint8_t k);

/** The node (NULL before co_device_attach). */
co_node_t *co_device_node(const co_device_run_t *run);

/** The plug-in's state (state_size bytes). */
void *co_device_state(const co_device_run_t *run);

/** Control interface: set @p index / @p sub to @p value as the outside
 *  world would: the first instance whose kind takes it (an input of a
 *  simulated plant), else a write through the dictionary as the
 *  application. */
co_err_t co_device_set(co_device_run_t *run, uint16_t index, uint8_t sub, int64_t value);

#endif /* CO_DEVICE_H */
