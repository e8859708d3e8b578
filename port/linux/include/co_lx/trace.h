/*
 * Frame trace in the candump -L log format, one frame per line:
 *
 *   (1700000000.123456) vcan0 601#4000100000000000
 *   (1700000000.123789) vcan0 701#R          remote request, DLC 0
 *   (1700000000.124000) vcan0 12345678#00    29-bit identifier
 *   (1700000000.125000) vcan0 20000040#0000000000000000   error frame
 *
 * Time is wall-clock (seconds.microseconds since the epoch, as candump
 * writes it). The identifier is 3 hex digits (11-bit), 8 digits (29-bit or
 * error frame); data bytes are upper-case hex without separators; a remote
 * request is 'R' followed by its DLC when that is not 0.
 *
 * A tracer is a raw socket of its own on the interface: it sees every frame
 * on the bus, those of this process's nodes included (CAN_RAW loopback),
 * with the kernel's receive timestamp.
 */
#ifndef CO_LX_TRACE_H
#define CO_LX_TRACE_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "co_lx/socketcan.h"

#define CO_LX_TRACE_LINE_MAX 80U

/** Format one frame (@p can_id in SocketCAN form: CAN_EFF_FLAG, CAN_RTR_FLAG,
 *  CAN_ERR_FLAG) into @p buf, with a trailing newline. Returns the length,
 *  or 0 when @p cap is too small. */
size_t co_lx_trace_format(char *buf, size_t cap, int64_t sec, uint32_t usec, const char *iface,
                          uint32_t can_id, uint8_t len, const uint8_t *data);

typedef struct co_lx_tracer {
    int fd;            /**< raw CAN socket, -1 when closed */
    char iface[16];
    FILE *out;
} co_lx_tracer_t;

/** Open a tracer on @p iface writing to @p out. Returns 0, or -1 with
 *  *@p why (may be NULL) and errno. */
int co_lx_tracer_open(co_lx_tracer_t *t, const char *iface, FILE *out, co_lx_can_fail_t *why);

/** Write every frame waiting on the tracer's socket. Returns the number of
 *  frames written, or -1 on a socket error. */
int co_lx_tracer_drain(co_lx_tracer_t *t);

void co_lx_tracer_close(co_lx_tracer_t *t);

#endif /* CO_LX_TRACE_H */
