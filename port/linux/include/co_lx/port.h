/*
 * One node's connection to Linux: its raw CAN socket (the HAL's send), its
 * file-backed non-volatile memory (the HAL's nv_read/nv_write, optional),
 * and the controller error state its error frames are turned into EMCYs by.
 *
 * Each node has a socket of its own: nodes of one process see each other's
 * frames through the kernel's CAN_RAW loopback exactly as nodes on a real
 * bus do, and never their own.
 *
 * Order of use: co_lx_port_open, co_node_init with co_lx_port_hal() (the
 * boot-up frame goes out through the socket), co_lx_port_attach, then the
 * loop (loop.h).
 */
#ifndef CO_LX_PORT_H
#define CO_LX_PORT_H

#include <stdbool.h>
#include <stdint.h>

#include "co/co_hal.h"
#include "co/co_node.h"
#include "co_lx/canerr.h"
#include "co_lx/nvfile.h"
#include "co_lx/socketcan.h"

/** Log levels of the port and the daemon. */
typedef enum co_lx_level {
    CO_LX_ERROR = 0,
    CO_LX_WARN = 1,
    CO_LX_INFO = 2,
    CO_LX_DEBUG = 3
} co_lx_level_t;

/** Where the port reports what it sees (may be NULL). */
typedef void (*co_lx_log_fn)(void *ctx, co_lx_level_t level, const char *msg);

typedef struct co_lx_port {
    int fd;                  /**< raw CAN socket, -1 when closed */
    char iface[16];
    co_node_t *node;         /**< set by co_lx_port_attach */
    co_lx_nv_t *nv;          /**< NULL: no non-volatile memory */
    co_lx_canerr_t err;
    uint32_t dropped;        /**< the socket's drop counter as last seen */
    uint32_t tx_refused;     /**< frames the TX path did not accept (full) */
    uint32_t tx_failed;      /**< frames lost to other send errors */
    uint32_t rx_frames;
    bool tx_blocked;         /**< the last send was not accepted */
    uint8_t bit_timing;      /**< last LSS bit-timing index (0xFF: none) */
    bool off_bus;            /**< co_lx_port_off_bus: no frames in or out */
    uint32_t back_at;        /**< ... until this time (us) */
    uint32_t rx_ignored;     /**< frames that arrived while off the bus */
    co_lx_log_fn log;
    void *log_ctx;
} co_lx_port_t;

/** Open the node's socket on @p iface; @p nv (may be NULL) backs nv_read /
 *  nv_write. Returns 0, or -1 with *@p why (see socketcan.h) and errno. */
int co_lx_port_open(co_lx_port_t *p, const char *iface, co_lx_nv_t *nv, co_lx_can_fail_t *why);

/** The HAL for co_node_config_t.hal: send on the socket, and nv_read /
 *  nv_write when the port has non-volatile memory. */
co_hal_t co_lx_port_hal(co_lx_port_t *p);

/** Tell the port which node it serves (after co_node_init). */
void co_lx_port_attach(co_lx_port_t *p, co_node_t *node);

/** Receive one frame into the node at @p now_us (error frames become EMCY
 *  actions). Returns 1 when a frame was handled, 0 when none was waiting,
 *  -1 when the socket failed (interface gone). */
int co_lx_port_rx(co_lx_port_t *p, uint32_t now_us);

/** Fault injection: the controller leaves the bus for @p ms milliseconds
 *  (1 .. 3600000) the way it does at bus-off, and comes back by itself as
 *  after a bus-off recovery. Meanwhile no frame goes out (the core holds
 *  its frames back, the lowest CAN-ID first, as for a full TX path) and
 *  every frame that arrives is dropped unseen. The core is told through its
 *  CAN-state policy (co/co_canstate.h): at the start CO_CAN_BUS_OFF (EMCY
 *  0x8140 raised and held back; 0x1029 sub 1, the communication error
 *  behaviour, applies), at the end CO_CAN_ERROR_ACTIVE, so that the held
 *  frames go out (EMCY 0x8140 "recovered from bus-off" first, then its
 *  EMCY 0x0000 when no other error remains). A second call while off the
 *  bus moves the end to @p ms from now. */
void co_lx_port_off_bus(co_lx_port_t *p, uint32_t ms, uint32_t now_us);

/** The port's own timer (the loop calls it every round): brings an off-bus
 *  controller back when its time has come. Returns the time it wants to be
 *  called again (CO_NO_DEADLINE when on the bus). */
uint32_t co_lx_port_process(co_lx_port_t *p, uint32_t now_us);

void co_lx_port_close(co_lx_port_t *p);

#endif /* CO_LX_PORT_H */
