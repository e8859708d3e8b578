/* Frame trace in the candump -L log format (see trace.h). */
#include "co_lx/trace.h"

#include <errno.h>
#include <inttypes.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <unistd.h>

#include <linux/can.h>


static const char hexdig[] = "0123456789ABCDEF";

size_t co_lx_trace_format(char *buf, size_t cap, int64_t sec, uint32_t usec, const char *iface,
                          uint32_t can_id, uint8_t len, const uint8_t *data)
{
    char id[16];
    char payload[20];
    size_t p = 0U;
    uint8_t n_bytes = len;
    int n;

    if ((can_id & CAN_ERR_FLAG) != 0U) {
        (void)snprintf(id, sizeof id, "%08" PRIX32, can_id & (CAN_ERR_MASK | CAN_ERR_FLAG));
    } else if ((can_id & CAN_EFF_FLAG) != 0U) {
        (void)snprintf(id, sizeof id, "%08" PRIX32, can_id & CAN_EFF_MASK);
    } else {
        (void)snprintf(id, sizeof id, "%03" PRIX32, can_id & CAN_SFF_MASK);
    }
    if (n_bytes > 8U) {
        n_bytes = 8U;
    }
    if ((can_id & CAN_RTR_FLAG) != 0U) {
        payload[p] = 'R';
        p++;
        if (n_bytes != 0U) {
            payload[p] = hexdig[n_bytes];
            p++;
        }
    } else {
        for (uint8_t i = 0U; i < n_bytes; i++) {
            payload[p] = hexdig[data[i] >> 4];
            payload[p + 1U] = hexdig[data[i] & 0x0FU];
            p += 2U;
        }
    }
    payload[p] = '\0';
    n = snprintf(buf, cap, "(%010" PRId64 ".%06" PRIu32 ") %s %s#%s\n", sec, usec, iface, id,
                 payload);
    if ((n < 0) || ((size_t)n >= cap)) {
        return 0U;
    }
    return (size_t)n;
}

int co_lx_tracer_open(co_lx_tracer_t *t, const char *iface, FILE *out, co_lx_can_fail_t *why)
{
    int on = 1;
    int rcvbuf = 1 << 20;

    t->fd = -1;
    t->out = out;
    (void)snprintf(t->iface, sizeof t->iface, "%s", iface);
    t->fd = co_lx_can_open(iface, why);
    if (t->fd < 0) {
        return -1;
    }
    (void)setsockopt(t->fd, SOL_SOCKET, SO_TIMESTAMP, &on, (socklen_t)sizeof on);
    (void)setsockopt(t->fd, SOL_SOCKET, SO_RCVBUF, &rcvbuf, (socklen_t)sizeof rcvbuf);
    return 0;
}

int co_lx_tracer_drain(co_lx_tracer_t *t)
{
    int count = 0;

    for (;;) {
        struct can_frame cf;
        struct timeval tv;
        char line[CO_LX_TRACE_LINE_MAX];
        size_t n;
        int r = co_lx_can_recv(t->fd, &cf, &tv, NULL);

        if (r <= 0) {
            return (r < 0) ? -1 : count;
        }
        n = co_lx_trace_format(line, sizeof line, (int64_t)tv.tv_sec, (uint32_t)tv.tv_usec,
                               t->iface, cf.can_id, cf.len, cf.data);
        if (n > 0U) {
            (void)fwrite(line, 1U, n, t->out);
        }
        count++;
    }
}

void co_lx_tracer_close(co_lx_tracer_t *t)
{
    if (t->fd >= 0) {
        (void)co_lx_tracer_drain(t);
        (void)close(t->fd);
        t->fd = -1;
    }
    if (t->out != NULL) {
        (void)fflush(t->out);
    }
}
