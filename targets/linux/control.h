/*
 * The control interface of canopen-device (--control PATH): a Unix stream
 * socket through which tests and tools act on the running devices the way
 * the outside world would (docs/linux.md, "Control interface"). Each line
 * is one command, answered by one line:
 *
 *   [@ID] set INDEX SUB VALUE   set an input of the device's simulated plant
 *                               (a CiA 401 input object: the physical level),
 *                               else write the object as the application
 *                               (access not checked; limits and hooks are)
 *                               -> "ok" | "error 0xAAAAAAAA"
 *   [@ID] get INDEX SUB         read the object -> "ok VALUE" | "error 0x..."
 *   [@ID] emcy CODE [REG [B0 B1 B2 B3 B4]]
 *                               raise error CODE (EMCY, 0x1001 bits REG, the
 *                               manufacturer bytes B0..B4) -> "ok"
 *   [@ID] emcy clear CODE       clear it (EMCY 0x0000 after the last) -> "ok"
 *   [@ID] heartbeat stop|resume stop / resume the heartbeat producer's
 *                               frames (the node stays alive) -> "ok"
 *   [@ID] offbus MS             off the bus for MS ms, back as after a
 *                               bus-off (EMCY 0x8140) -> "ok"
 *   nodes                       -> "ok ID:DEVICE ..." (the nodes of the process)
 *   help                        -> "ok ..." (the commands)
 *
 * Numbers are C literals (0x55, 85, -3); @ID picks the node by its
 * node-ID (default: the first node). Up to CTL_CLIENTS clients at once;
 * a line longer than CTL_LINE_MAX is answered "error line too long".
 */
#ifndef CONTROL_H
#define CONTROL_H

#include <poll.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#define CTL_CLIENTS 4U
#define CTL_LINE_MAX 200U
#define CTL_FDS (1U + CTL_CLIENTS)
#define CTL_WORDS_MAX 9U /**< words of a command line, @ID included */

/** One parsed command. */
typedef enum ctl_op {
    CTL_SET,
    CTL_GET,
    CTL_NODES,
    CTL_HELP,
    CTL_EMCY_RAISE,
    CTL_EMCY_CLEAR,
    CTL_HB_STOP,
    CTL_HB_RESUME,
    CTL_OFFBUS
} ctl_op_t;

#define CTL_OFFBUS_MAX_MS 3600000U /**< offbus: at most an hour */

typedef struct ctl_cmd {
    ctl_op_t op;
    int node_id;      /**< -1: the first node */
    uint16_t index;
    uint8_t sub;
    int64_t value;
    uint16_t code;    /**< emcy: the error code */
    uint8_t reg;      /**< emcy: 0x1001 bits */
    bool has_mfr;     /**< emcy: manufacturer bytes given */
    uint8_t mfr[5];
    uint32_t ms;      /**< offbus */
} ctl_cmd_t;

/** Parse @p line (no newline). 0, or -1 with a reason in @p err. */
int ctl_parse(const char *line, ctl_cmd_t *cmd, char *err, size_t errcap);

/** Executes a command; writes the answer line (no newline) into @p reply. */
typedef void (*ctl_exec_fn)(void *ctx, const ctl_cmd_t *cmd, char *reply, size_t cap);

typedef struct ctl {
    int lfd;                          /**< listening socket (-1: none) */
    int cfd[CTL_CLIENTS];
    char buf[CTL_CLIENTS][CTL_LINE_MAX + 1U];
    size_t len[CTL_CLIENTS];
    char path[108];
    ctl_exec_fn exec;
    void *exec_ctx;
} ctl_t;

/** Listen on @p path (an existing socket file is replaced). 0, or -1 with
 *  a message in @p err. */
int ctl_open(ctl_t *c, const char *path, ctl_exec_fn exec, void *ctx, char *err, size_t errcap);

/** The descriptors to poll (at most CTL_FDS); returns how many. */
size_t ctl_fds(void *c, struct pollfd *fds, size_t cap);

/** Serve what @p fds (as ctl_fds filled them, with revents) report. */
void ctl_ready(void *c, const struct pollfd *fds, size_t n);

/** Close the socket and remove its file. */
void ctl_close(ctl_t *c);

#endif /* CONTROL_H */
