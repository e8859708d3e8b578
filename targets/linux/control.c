/* The control interface of canopen-device (see control.h). */
#include "control.h"

#include <errno.h>
#include <stdbool.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

static int number(const char *s, int64_t *v)
{
    char *end = NULL;
    long long x;

    errno = 0;
    x = strtoll(s, &end, 0);
    if ((errno != 0) || (end == s) || (*end != '\0')) {
        return -1;
    }
    *v = (int64_t)x;
    return 0;
}

/* An unsigned number in [0, max] into *out, else the message. */
static int bounded(const char *w, int64_t max, const char *what, int64_t *out, char *err,
                   size_t errcap)
{
    if ((number(w, out) != 0) || (*out < 0) || (*out > max)) {
        (void)snprintf(err, errcap, "bad %s %s", what, w);
        return -1;
    }
    return 0;
}

static int parse_setget(char *const *w, size_t n, ctl_cmd_t *cmd, char *err, size_t errcap)
{
    bool set = (w[0][0] == 's');
    int64_t v;

    if (n != (set ? 4U : 3U)) {
        (void)snprintf(err, errcap, "usage: %s", set ? "set INDEX SUB VALUE" : "get INDEX SUB");
        return -1;
    }
    if (bounded(w[1], 0xFFFF, "index", &v, err, errcap) != 0) {
        return -1;
    }
    cmd->index = (uint16_t)v;
    if (bounded(w[2], 0xFF, "sub-index", &v, err, errcap) != 0) {
        return -1;
    }
    cmd->sub = (uint8_t)v;
    cmd->op = set ? CTL_SET : CTL_GET;
    if (set && (number(w[3], &cmd->value) != 0)) {
        (void)snprintf(err, errcap, "bad value %s", w[3]);
        return -1;
    }
    return 0;
}

/* emcy CODE [REG [B0 B1 B2 B3 B4]] | emcy clear CODE */
static int parse_emcy(char *const *w, size_t n, ctl_cmd_t *cmd, char *err, size_t errcap)
{
    int64_t v;

    if ((n == 3U) && (strcmp(w[1], "clear") == 0)) {
        if (bounded(w[2], 0xFFFF, "error code", &v, err, errcap) != 0) {
            return -1;
        }
        cmd->op = CTL_EMCY_CLEAR;
        cmd->code = (uint16_t)v;
        return 0;
    }
    if ((n != 2U) && (n != 3U) && (n != 8U)) {
        (void)snprintf(err, errcap, "usage: emcy CODE [REG [B0 B1 B2 B3 B4]] | emcy clear CODE");
        return -1;
    }
    if (bounded(w[1], 0xFFFF, "error code", &v, err, errcap) != 0) {
        return -1;
    }
    if (v == 0) {
        (void)snprintf(err, errcap, "error code 0 is not an error (emcy clear CODE)");
        return -1;
    }
    cmd->op = CTL_EMCY_RAISE;
    cmd->code = (uint16_t)v;
    if ((n >= 3U) && (bounded(w[2], 0xFF, "error register bits", &v, err, errcap) != 0)) {
        return -1;
    }
    cmd->reg = (n >= 3U) ? (uint8_t)v : 0U;
    cmd->has_mfr = (n == 8U);
    for (size_t k = 0U; k < 5U && cmd->has_mfr; k++) {
        if (bounded(w[3U + k], 0xFF, "manufacturer byte", &v, err, errcap) != 0) {
            return -1;
        }
        cmd->mfr[k] = (uint8_t)v;
    }
    return 0;
}

int ctl_parse(const char *line, ctl_cmd_t *cmd, char *err, size_t errcap)
{
    char copy[CTL_LINE_MAX + 1U];
    char *words[CTL_WORDS_MAX + 1U];
    size_t n = 0U;
    size_t at = 0U;
    char *save = NULL;
    int64_t v;

    if (strlen(line) > CTL_LINE_MAX) {
        (void)snprintf(err, errcap, "line too long");
        return -1;
    }
    (void)strcpy(copy, line);
    for (char *w = strtok_r(copy, " \t\r", &save); (w != NULL) && (n <= CTL_WORDS_MAX);
         w = strtok_r(NULL, " \t\r", &save)) {
        words[n++] = w;
    }
    (void)memset(cmd, 0, sizeof *cmd);
    cmd->node_id = -1;
    if ((n > 0U) && (words[0][0] == '@')) {
        if ((number(&words[0][1], &v) != 0) || (v < 1) || (v > 127)) {
            (void)snprintf(err, errcap, "bad node-ID %s", words[0]);
            return -1;
        }
        cmd->node_id = (int)v;
        at = 1U;
    }
    if (at >= n) {
        (void)snprintf(err, errcap, "empty command");
        return -1;
    }
    if (n > CTL_WORDS_MAX) {
        (void)snprintf(err, errcap, "too many words");
        return -1;
    }
    {
        char *const *w = &words[at];
        size_t k = n - at;
        if ((strcmp(w[0], "help") == 0) && (k == 1U)) {
            cmd->op = CTL_HELP;
            return 0;
        }
        if ((strcmp(w[0], "nodes") == 0) && (k == 1U)) {
            cmd->op = CTL_NODES;
            return 0;
        }
        if ((strcmp(w[0], "set") == 0) || (strcmp(w[0], "get") == 0)) {
            return parse_setget(w, k, cmd, err, errcap);
        }
        if (strcmp(w[0], "emcy") == 0) {
            return parse_emcy(w, k, cmd, err, errcap);
        }
        if (strcmp(w[0], "heartbeat") == 0) {
            if ((k == 2U) && ((strcmp(w[1], "stop") == 0) || (strcmp(w[1], "resume") == 0))) {
                cmd->op = (w[1][0] == 's') ? CTL_HB_STOP : CTL_HB_RESUME;
                return 0;
            }
            (void)snprintf(err, errcap, "usage: heartbeat stop|resume");
            return -1;
        }
        if (strcmp(w[0], "offbus") == 0) {
            if (k != 2U) {
                (void)snprintf(err, errcap, "usage: offbus MS");
                return -1;
            }
            if ((bounded(w[1], CTL_OFFBUS_MAX_MS, "time", &v, err, errcap) != 0) || (v == 0)) {
                (void)snprintf(err, errcap, "bad time %s (1..%u ms)", w[1],
                               (unsigned)CTL_OFFBUS_MAX_MS);
                return -1;
            }
            cmd->op = CTL_OFFBUS;
            cmd->ms = (uint32_t)v;
            return 0;
        }
        (void)snprintf(err, errcap, "unknown command %s (help)", w[0]);
    }
    return -1;
}

int ctl_open(ctl_t *c, const char *path, ctl_exec_fn exec, void *ctx, char *err, size_t errcap)
{
    struct sockaddr_un a;

    (void)memset(c, 0, sizeof *c);
    c->lfd = -1;
    for (size_t k = 0U; k < CTL_CLIENTS; k++) {
        c->cfd[k] = -1;
    }
    c->exec = exec;
    c->exec_ctx = ctx;
    if (strlen(path) >= sizeof a.sun_path) {
        (void)snprintf(err, errcap, "%.80s: path too long for a socket", path);
        return -1;
    }
    (void)memset(&a, 0, sizeof a);
    a.sun_family = AF_UNIX;
    (void)strcpy(a.sun_path, path);
    (void)strcpy(c->path, path);
    c->lfd = socket(AF_UNIX, SOCK_STREAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
    if (c->lfd < 0) {
        (void)snprintf(err, errcap, "%s: %s", path, strerror(errno));
        return -1;
    }
    (void)unlink(path);
    if ((bind(c->lfd, (const struct sockaddr *)&a, sizeof a) != 0) || (listen(c->lfd, 4) != 0)) {
        (void)snprintf(err, errcap, "%s: %s", path, strerror(errno));
        (void)close(c->lfd);
        c->lfd = -1;
        return -1;
    }
    return 0;
}

size_t ctl_fds(void *ctx, struct pollfd *fds, size_t cap)
{
    const ctl_t *c = (const ctl_t *)ctx;
    size_t n = 0U;

    if ((c->lfd < 0) || (cap < CTL_FDS)) {
        return 0U;
    }
    fds[n].fd = c->lfd;
    fds[n].events = POLLIN;
    fds[n].revents = 0;
    n++;
    for (size_t k = 0U; k < CTL_CLIENTS; k++) {
        fds[n].fd = c->cfd[k]; /* -1: ignored by poll */
        fds[n].events = POLLIN;
        fds[n].revents = 0;
        n++;
    }
    return n;
}

static void drop(ctl_t *c, size_t k)
{
    (void)close(c->cfd[k]);
    c->cfd[k] = -1;
    c->len[k] = 0U;
}

static void answer(ctl_t *c, size_t k, const char *line)
{
    char cmdline[CTL_LINE_MAX + 1U];
    char reply[256];
    ctl_cmd_t cmd;
    char err[128];
    size_t len;

    (void)snprintf(cmdline, sizeof cmdline, "%s", line);
    if (ctl_parse(cmdline, &cmd, err, sizeof err) != 0) {
        (void)snprintf(reply, sizeof reply, "error %s", err);
    } else {
        c->exec(c->exec_ctx, &cmd, reply, sizeof reply);
    }
    len = strlen(reply);
    if (len < sizeof reply - 1U) {
        reply[len++] = '\n';
    }
    if (send(c->cfd[k], reply, len, MSG_NOSIGNAL) != (ssize_t)len) {
        drop(c, k);
    }
}

static void serve(ctl_t *c, size_t k)
{
    char in[256];
    ssize_t r = recv(c->cfd[k], in, sizeof in, MSG_DONTWAIT);

    if (r <= 0) {
        if ((r == 0) || ((errno != EAGAIN) && (errno != EWOULDBLOCK))) {
            drop(c, k);
        }
        return;
    }
    for (ssize_t i = 0; (i < r) && (c->cfd[k] >= 0); i++) {
        if (in[i] == '\n') {
            if (c->len[k] > CTL_LINE_MAX) {
                c->len[k] = 0U;
                if (send(c->cfd[k], "error line too long\n", 20U, MSG_NOSIGNAL) != 20) {
                    drop(c, k);
                }
                continue;
            }
            c->buf[k][c->len[k]] = '\0';
            c->len[k] = 0U;
            answer(c, k, c->buf[k]);
        } else if (c->len[k] < CTL_LINE_MAX) {
            c->buf[k][c->len[k]++] = in[i];
        } else {
            c->len[k] = CTL_LINE_MAX + 1U; /* too long: answered at its end */
        }
    }
}

void ctl_ready(void *ctx, const struct pollfd *fds, size_t n)
{
    ctl_t *c = (ctl_t *)ctx;

    if (n < CTL_FDS) {
        return;
    }
    for (size_t k = 0U; k < CTL_CLIENTS; k++) {
        if ((c->cfd[k] >= 0) && ((fds[1U + k].revents & (POLLIN | POLLHUP | POLLERR)) != 0)) {
            serve(c, k);
        }
    }
    if ((fds[0].revents & POLLIN) != 0) {
        int fd = accept4(c->lfd, NULL, NULL, SOCK_NONBLOCK | SOCK_CLOEXEC);
        size_t k = 0U;
        while ((k < CTL_CLIENTS) && (c->cfd[k] >= 0)) {
            k++;
        }
        if ((fd >= 0) && (k < CTL_CLIENTS)) {
            c->cfd[k] = fd;
            c->len[k] = 0U;
        } else if (fd >= 0) {
            (void)send(fd, "error too many clients\n", 23U, MSG_NOSIGNAL);
            (void)close(fd);
        } else {
            /* nothing to accept after all */
        }
    }
}

void ctl_close(ctl_t *c)
{
    for (size_t k = 0U; k < CTL_CLIENTS; k++) {
        if (c->cfd[k] >= 0) {
            drop(c, k);
        }
    }
    if (c->lfd >= 0) {
        (void)close(c->lfd);
        c->lfd = -1;
        (void)unlink(c->path);
    }
}
