/*
 * SocketCAN raw sockets: open one on an interface (non-blocking, error
 * frames on), send a core frame, receive a frame with its timestamp and the
 * count of frames the socket dropped.
 */
#ifndef CO_LX_SOCKETCAN_H
#define CO_LX_SOCKETCAN_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <sys/time.h>

#include <linux/can.h>

#include "co/co_frame.h"

/** Why co_lx_can_open failed (also in errno's terms, see the message). */
typedef enum co_lx_can_fail {
    CO_LX_CAN_OK = 0,
    CO_LX_CAN_NO_SUPPORT,  /**< the kernel has no SocketCAN (no PF_CAN / CAN_RAW) */
    CO_LX_CAN_NO_IFACE,    /**< no such interface */
    CO_LX_CAN_DOWN,        /**< the interface exists but is down */
    CO_LX_CAN_NOT_CAN,     /**< the interface is not a CAN interface */
    CO_LX_CAN_OTHER
} co_lx_can_fail_t;

/** Open a raw CAN socket bound to @p iface: non-blocking, all frames, error
 *  frames (bus-off, controller problems, restarts) delivered, socket
 *  receive-queue drop counter on. Returns the descriptor, or -1 with
 *  *@p why set (when not NULL). */
int co_lx_can_open(const char *iface, co_lx_can_fail_t *why);

/** Send @p f. Returns 0 when sent, 1 when the TX path is full
 *  (ENOBUFS/EAGAIN: try again later), -1 on any other error (errno). */
int co_lx_can_send(int fd, const co_frame_t *f);

/** Receive one frame. Returns 1 with a frame, 0 when none is waiting, -1 on
 *  an error (errno). @p ts (may be NULL) gets the kernel's receive time
 *  (wall clock) when SO_TIMESTAMP is on, else the current time; @p dropped
 *  (may be NULL) the socket's total drop counter (SO_RXQ_OVFL). */
int co_lx_can_recv(int fd, struct can_frame *cf, struct timeval *ts, uint32_t *dropped);

/** Convert between SocketCAN and core frames. */
void co_lx_frame_to_can(const co_frame_t *f, struct can_frame *cf);
void co_lx_frame_from_can(const struct can_frame *cf, co_frame_t *f);

#endif /* CO_LX_SOCKETCAN_H */
