/*
 * The event loop of the Linux port: one thread serves any number of nodes
 * (each with its own socket, possibly on different interfaces) and tracers.
 *
 * Each round: every node's co_node_process (and the application's tick) runs
 * and says when it wants to run again; the loop then sleeps in ppoll() until
 * a socket has a frame or the earliest of those deadlines comes. No busy
 * loop and no fixed tick: an idle node with a 1 s heartbeat wakes the
 * process once a second. A node whose TX path is full is woken by the core's
 * 1 ms retry deadline, never by the socket's writability (a SocketCAN raw
 * socket stays writable while the interface queue is full or the interface
 * is down: polling for it would spin); timers of every node keep running
 * meanwhile.
 *
 * Signals: the caller blocks SIGTERM/SIGINT and passes the mask to sleep
 * with (@c sleep_mask, normally the mask from before blocking); a handler
 * sets *stop. The loop notices it without a race (ppoll) and returns.
 */
#ifndef CO_LX_LOOP_H
#define CO_LX_LOOP_H

#include <signal.h>
#include <stddef.h>
#include <stdint.h>

#include "co/co_node.h"
#include "co_lx/port.h"
#include "co_lx/trace.h"

/** Application part of a node: runs in every round, returns the time it
 *  wants to run again (CO_NO_DEADLINE: never). */
typedef uint32_t (*co_lx_tick_fn)(void *ctx, co_node_t *node, uint32_t now_us);

typedef struct co_lx_member {
    co_lx_port_t *port;
    co_node_t *node;
    co_lx_tick_fn tick;      /**< may be NULL */
    void *tick_ctx;
} co_lx_member_t;

struct pollfd;

/** Further descriptors the loop polls (a control socket): fill @p fds (at
 *  most @p cap) and return how many; after the poll, serve what they
 *  report. Runs in the loop's thread, before the next round's timers. */
typedef size_t (*co_lx_fds_fn)(void *ctx, struct pollfd *fds, size_t cap);
typedef void (*co_lx_ready_fn)(void *ctx, const struct pollfd *fds, size_t n);

#define CO_LX_EXTRA_FDS_MAX 8U

typedef struct co_lx_loop {
    co_lx_member_t *members;
    size_t n_members;
    co_lx_tracer_t *tracers;
    size_t n_tracers;
    volatile sig_atomic_t *stop;
    const sigset_t *sleep_mask;   /**< signal mask while sleeping (NULL: unchanged) */
    co_lx_log_fn log;
    void *log_ctx;
    co_lx_fds_fn extra_fds;       /**< NULL: none */
    co_lx_ready_fn extra_ready;
    void *extra_ctx;
    uint64_t rounds;              /**< statistics: loop rounds (wake-ups) */
} co_lx_loop_t;

/** Run until *stop is set (returns 0) or a socket fails for good (returns
 *  -1, logged). */
int co_lx_loop_run(co_lx_loop_t *l);

/** How long to sleep from @p now until @p deadline in a ppoll timespec
 *  (NULL for CO_NO_DEADLINE). Exposed for the unit test. */
struct timespec;
const struct timespec *co_lx_sleep_for(uint32_t deadline, uint32_t now, struct timespec *ts);

#endif /* CO_LX_LOOP_H */
