/*
 * Device-profile plug-ins: CiA 402 drives, CiA 401 I/O modules, CiA 408
 * valves ... on top of the core.
 *
 * A plug-in instance is a caller-allocated struct (one per axis, module or
 * valve; several per node) driven through a const operation table. The core
 * never includes a profile. An instance
 *   - finds its objects in the node's dictionary (co_od_value_ptr) and binds
 *     hooks to the ones it must see written or read (co_od_bind_hook), so SDO,
 *     PDO and application accesses all reach it through the one OD path;
 *   - keeps its read-only objects (status, actual values) up to date in
 *     process(), so TPDOs and SDO uploads read current values;
 *   - gets SYNC, NMT state changes, NMT resets and error-control events,
 *     and may fill the manufacturer bytes of the EMCYs the core raises.
 *
 * The host below fans the node's callbacks out to every instance (then to
 * the application's own callbacks) and collects the instances' deadlines.
 * Typical use:
 *
 *     co_profile_host_init(&host, slots, 4, &app_cb);
 *     co_profile_add(&host, &co402_profile_ops, &axis0);
 *     cfg.cb = co_profile_host_callbacks(&host);
 *     co_node_init(&node, &cfg, now);
 *     co_profile_host_attach(&host, &node, now);
 *     loop: co_node_rx(...); next = min(co_node_process(&node, now),
 *                                       co_profile_host_process(&host, now));
 */
#ifndef CO_PROFILE_H
#define CO_PROFILE_H

#include <stdint.h>

#include "co/co_err.h"
#include "co/co_node.h"

/** The operations of one kind of plug-in. Every pointer but attach may be NULL;
 *  tables are written with designated initialisers (.attach = ...). */
typedef struct co_profile_ops {
    const char *name;
    /** Bind to @p node (after co_node_init): find the objects, bind the
     *  hooks, bring the instance to its initial state. An error leaves the
     *  instance detached (a device description that lacks a mandatory
     *  object, for example). */
    co_err_t (*attach)(void *inst, co_node_t *node, uint32_t now_us);
    /** Time has come to @p now_us: run state machines, plants, timers.
     *  Returns the absolute time of the next call it wants, or
     *  CO_NO_DEADLINE. Extra calls are harmless. */
    uint32_t (*process)(void *inst, uint32_t now_us);
    /** A SYNC was received or produced (counter 0 without a counter). */
    void (*sync)(void *inst, uint8_t counter, uint32_t now_us);
    /** The node's NMT state changed. */
    void (*nmt_state)(void *inst, co_nmt_state_t state, uint32_t now_us);
    /** An NMT reset is executed: the core has already restored the part of
     *  the image it owns (communication area, or all objects for a node
     *  reset). The instance resets its own state accordingly. */
    void (*reset)(void *inst, co_reset_t kind, uint32_t now_us);
    /** Heartbeat consumer / life-guarding event (a lost master, ...). */
    void (*error_control)(void *inst, co_hb_event_t ev, uint8_t id, uint32_t now_us);
    /** An EMCY is raised without manufacturer data (the core's own EMCYs,
     *  co_node_callbacks_t.emcy_mfr): fill or change @p mfr (EMCY bytes
     *  3..7). The instances are asked in turn, then the application. Must
     *  not raise or clear errors. */
    void (*emcy_mfr)(void *inst, uint16_t code, uint8_t mfr[5]);
    /** RPDO @p n (0-based) was received and its objects written (all it
     *  covers, through the dictionary): apply them at once. */
    void (*rpdo)(void *inst, uint16_t n, uint32_t now_us);
    /** May this change send event-driven TPDO @p n (0-based)? @p last is
     *  what it sent last, @p now its data now; @p changed (last ^ now on the
     *  first call) comes with the bits of the instance's own objects whose
     *  change is no event (masked, under a delta) cleared; an instance may
     *  set a bit of its own objects for an event whose value is back where
     *  it was sent. The TPDO goes out when some bit remains set after every
     *  instance. */
    void (*tpdo_event)(void *inst, uint16_t n, const uint8_t last[8], const uint8_t now[8],
                       uint8_t changed[8]);
    /** NMT command @p cs (co_node_callbacks_t.nmt_command) is about to be
     *  executed; the node is still in its old state (an EMCY still goes out). */
    void (*nmt_command)(void *inst, uint8_t cs, uint32_t now_us);
    /** A serious error of class @p sub (CO_ERRBEH_COMM: bus-off, ...) was
     *  reported through co_node_error_behaviour. */
    void (*error_class)(void *inst, uint8_t sub, uint32_t now_us);
} co_profile_ops_t;

/** One instance: its operations and its context. */
typedef struct co_profile {
    const co_profile_ops_t *ops;
    void *inst;
} co_profile_t;

/** The plug-ins of one node (caller-allocated, like the node). */
typedef struct co_profile_host {
    co_node_t *node;         /**< NULL until co_profile_host_attach */
    co_profile_t *slots;
    uint8_t n;
    uint8_t cap;
    co_node_callbacks_t app; /**< the application's callbacks, called after the plug-ins */
    co_node_callbacks_t node_cb; /**< the node's callbacks (co_profile_host_callbacks) */
} co_profile_host_t;

/** Empty host with room for @p cap instances in @p slots; @p app (may be
 *  NULL) are the application's own node callbacks. */
void co_profile_host_init(co_profile_host_t *h, co_profile_t *slots, uint8_t cap,
                          const co_node_callbacks_t *app);

/** Add an instance (before attach). CO_ERR_NO_MEMORY when full. */
co_err_t co_profile_add(co_profile_host_t *h, const co_profile_ops_t *ops, void *inst);

/** The node callbacks that feed the instances (kept in @p h): put them into
 *  co_node_config_t.cb before co_node_init. */
const co_node_callbacks_t *co_profile_host_callbacks(co_profile_host_t *h);

/** Attach every instance to @p node (after co_node_init). Stops at the first
 *  error and returns it. */
co_err_t co_profile_host_attach(co_profile_host_t *h, co_node_t *node, uint32_t now_us);

/** Run every instance; returns the earliest deadline (CO_NO_DEADLINE if none). */
uint32_t co_profile_host_process(co_profile_host_t *h, uint32_t now_us);

#endif /* CO_PROFILE_H */
