/* The event loop of the Linux port (see loop.h). */
#include "co_lx/loop.h"

#include <errno.h>
#include <poll.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "co_lx/clock.h"

#define RX_BATCH 64U   /* frames taken from one socket before timers run again */

static void loop_say(const co_lx_loop_t *l, co_lx_level_t level, const char *msg)
{
    if (l->log != NULL) {
        l->log(l->log_ctx, level, msg);
    }
}

const struct timespec *co_lx_sleep_for(uint32_t deadline, uint32_t now, struct timespec *ts)
{
    int32_t us;

    if (deadline == CO_NO_DEADLINE) {
        return NULL;
    }
    us = co_lx_until(deadline, now);
    if (us < 0) {
        us = 0;
    }
    ts->tv_sec = (time_t)(us / 1000000);
    ts->tv_nsec = (long)(us % 1000000) * 1000L;
    return ts;
}

/* Run every node's application and timers; the earliest deadline. The
 * application first: what its tick changed (an input, a statusword) goes
 * out in the same round. */
static uint32_t run_timers(co_lx_loop_t *l, uint32_t now)
{
    uint32_t next = CO_NO_DEADLINE;

    for (size_t i = 0U; i < l->n_members; i++) {
        co_lx_member_t *m = &l->members[i];
        uint32_t pd = co_lx_port_process(m->port, now);
        uint32_t a = (m->tick != NULL) ? m->tick(m->tick_ctx, m->node, now) : CO_NO_DEADLINE;
        uint32_t d = co_node_process(m->node, now);

        a = (pd == CO_NO_DEADLINE) ? a : ((a == CO_NO_DEADLINE) ? pd : co_lx_earlier(a, pd, now));

        d = (d == CO_NO_DEADLINE) ? a : ((a == CO_NO_DEADLINE) ? d : co_lx_earlier(a, d, now));
        if (d != CO_NO_DEADLINE) {
            next = (next == CO_NO_DEADLINE) ? d : co_lx_earlier(d, next, now);
        }
    }
    return next;
}

static int drain_member(const co_lx_loop_t *l, co_lx_member_t *m)
{
    for (unsigned k = 0U; k < RX_BATCH; k++) {
        uint32_t now = co_lx_now_us();
        int r = co_lx_port_rx(m->port, now);

        if (r < 0) {
            char msg[128];
            bool down = (errno == ENETDOWN);
            (void)snprintf(msg, sizeof msg, "%s: %s%s", m->port->iface, strerror(errno),
                           down ? " (waiting for it to come up)" : "");
            loop_say(l, down ? CO_LX_WARN : CO_LX_ERROR, msg);
            return down ? 0 : -1;
        }
        if (r == 0) {
            break;
        }
        /* the core wants co_node_process after every received frame */
        (void)co_node_process(m->node, now);
    }
    return 0;
}

int co_lx_loop_run(co_lx_loop_t *l)
{
    size_t nfds = l->n_members + l->n_tracers;
    struct pollfd *fds =
        (struct pollfd *)calloc(nfds + CO_LX_EXTRA_FDS_MAX + 1U, sizeof *fds);
    int rc = 0;

    if (fds == NULL) {
        loop_say(l, CO_LX_ERROR, "out of memory");
        return -1;
    }
    while ((rc == 0) && (*l->stop == 0)) {
        struct timespec ts;
        const struct timespec *tsp;
        uint32_t now = co_lx_now_us();
        uint32_t next = run_timers(l, now);
        bool traced = false;
        int r;

        for (size_t i = 0U; i < l->n_members; i++) {
            fds[i].fd = l->members[i].port->fd;
            /* never POLLOUT: SocketCAN keeps a raw socket writable while the
             * interface queue is full or the interface is down, so the loop
             * would spin at 100 % CPU; a held-back frame is retried at the
             * core's deadline (1 ms) instead */
            fds[i].events = (short)POLLIN;
            fds[i].revents = 0;
        }
        for (size_t i = 0U; i < l->n_tracers; i++) {
            fds[l->n_members + i].fd = l->tracers[i].fd;
            fds[l->n_members + i].events = POLLIN;
            fds[l->n_members + i].revents = 0;
        }
        size_t n_extra = (l->extra_fds != NULL)
                             ? l->extra_fds(l->extra_ctx, &fds[nfds], CO_LX_EXTRA_FDS_MAX)
                             : 0U;
        tsp = co_lx_sleep_for(next, co_lx_now_us(), &ts);
        l->rounds++;
        r = ppoll(fds, (nfds_t)(nfds + n_extra), tsp, l->sleep_mask);
        if (r < 0) {
            if (errno != EINTR) {
                loop_say(l, CO_LX_ERROR, "ppoll failed");
                rc = -1;
            }
            continue;
        }
        for (size_t i = 0U; (i < l->n_members) && (rc == 0); i++) {
            if ((fds[i].revents & (POLLIN | POLLERR | POLLHUP | POLLNVAL)) != 0) {
                rc = drain_member(l, &l->members[i]);
            }
        }
        for (size_t i = 0U; (i < l->n_tracers) && (rc == 0); i++) {
            if ((fds[l->n_members + i].revents & POLLIN) != 0) {
                traced = (co_lx_tracer_drain(&l->tracers[i]) > 0) || traced;
            }
        }
        if (traced) {
            for (size_t i = 0U; i < l->n_tracers; i++) {
                (void)fflush(l->tracers[i].out);
            }
        }
        if ((rc == 0) && (n_extra != 0U) && (l->extra_ready != NULL)) {
            l->extra_ready(l->extra_ctx, &fds[nfds], n_extra);
        }
    }
    free(fds);
    return rc;
}
