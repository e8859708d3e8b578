/*
 * A CiA 402 device as one descriptor: what the daemon (canopen-device
 * --device NAME) and the seed tests need to run a device description with
 * its profile instances, its options and a simulated plant per axis.
 *
 *   - the generated dictionary (codev_<name>) and how to lay out a node of it;
 *   - the axes (0..n-1 at +0x800) with the profile options and fixed units
 *     of the device (co402_config_t; the runner fills in axis and plant);
 *   - the simulated plant of each axis;
 *   - optionally a device plug-in for what is neither core nor profile
 *     (manufacturer objects, vendor error handling). Its instance is the
 *     co402_device_run_t, so it reaches the node, the axes and its own
 *     state (ctx, desc->ctx_size bytes the caller provides).
 *
 * Typical use (the node memory is the generated <cname>_node_t):
 *
 *     static faulhaber_mc_node_t n;
 *     static faulhaber_mc_state_t st;
 *     co402_device_run_t run;
 *     co402_device_start(&run, &faulhaber_mc_device, &n, &st, hal, 2, NULL, now);
 *     loop: co_node_rx(run.node, ...); next = co402_device_process(&run, now);
 */
#ifndef CO402_DEVICE_H
#define CO402_DEVICE_H

#include <stddef.h>
#include <stdint.h>

#include "co/co402.h"
#include "co/co402_sim.h"
#include "co/co_node.h"
#include "co/co_profile.h"

#define CO402_DEVICE_AXES_MAX 4U

typedef struct co402_device co402_device_t;

/** A running device: node, plug-in host, axes, plants. Caller-allocated. */
typedef struct co402_device_run {
    const co402_device_t *desc;
    co_node_t *node;                              /**< inside the caller's node memory */
    void *ctx;                                    /**< the device plug-in's state */
    co_profile_host_t host;
    co_profile_t slots[CO402_DEVICE_AXES_MAX + 1U];
    co402_axis_t axis[CO402_DEVICE_AXES_MAX];
    co402_sim_t sim[CO402_DEVICE_AXES_MAX];
} co402_device_run_t;

struct co402_device {
    const char *name;        /**< device name (canopen-device --device NAME) */
    const co_dev_t *dev;     /**< the generated dictionary */
    size_t node_size;        /**< sizeof the generated <cname>_node_t */
    /** The generated <cname>_config for node memory of node_size bytes. */
    void (*config)(void *node_mem, co_node_config_t *cfg);
    uint8_t n_axes;          /**< axes 0..n_axes-1 (objects at +0x800 * axis) */
    /** Profile configuration of every axis: options (CO402_OPT_*), units,
     *  modes, tick; axis and plant are set by the runner. */
    co402_config_t axis;
    /** Plant parameters of simulated axis @p axis (NULL: co402_sim_defaults). */
    void (*sim)(uint8_t axis, co402_sim_config_t *c);
    /** The device plug-in (NULL: none); its instance is the run struct. */
    const co_profile_ops_t *ops;
    size_t ctx_size;         /**< bytes of plug-in state the caller provides (ctx) */
};

/** Start @p d as node @p node_id: lay out the node in @p node_mem
 *  (d->node_size bytes, suitably aligned), add one axis per d->n_axes on a
 *  simulated plant each and the device plug-in (state in @p ctx, d->ctx_size
 *  bytes, zeroed here), init the node (boot-up) and attach everything.
 *  @p app: the application's own node callbacks (may be NULL). */
co_err_t co402_device_start(co402_device_run_t *r, const co402_device_t *d, void *node_mem,
                            void *ctx, co_hal_t hal, uint8_t node_id,
                            const co_node_callbacks_t *app, uint32_t now_us);

/** Run node and plug-ins up to @p now_us; the earliest next deadline. */
uint32_t co402_device_process(co402_device_run_t *r, uint32_t now_us);

#endif /* CO402_DEVICE_H */
