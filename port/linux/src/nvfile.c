/* File-backed non-volatile memory (see nvfile.h). */
#include "co_lx/nvfile.h"

#include <errno.h>
#include <fcntl.h>
#include <libgen.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static int write_all(int fd, const uint8_t *data, size_t len)
{
    size_t done = 0U;

    while (done < len) {
        ssize_t w = write(fd, &data[done], len - done);
        if (w < 0) {
            if (errno != EINTR) {
                return -1;
            }
        } else {
            done += (size_t)w;
        }
    }
    return 0;
}

/* the directory of a path, for fsync after the rename */
static int open_dir_of(const char *path)
{
    char *copy = strdup(path);
    int fd;

    if (copy == NULL) {
        return -1;
    }
    fd = open(dirname(copy), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    free(copy);
    return fd;
}

static int persist(const co_lx_nv_t *nv)
{
    int fd = open(nv->tmp, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC,
                  S_IRUSR | S_IWUSR | S_IRGRP | S_IROTH);
    int dfd;
    int rc = 0;

    if (fd < 0) {
        return -1;
    }
    if ((write_all(fd, nv->img, nv->size) != 0) || (fsync(fd) != 0)) {
        rc = -1;
    }
    if (close(fd) != 0) {
        rc = -1;
    }
    if ((rc == 0) && (rename(nv->tmp, nv->path) != 0)) {
        rc = -1;
    }
    if (rc != 0) {
        (void)unlink(nv->tmp);
        return -1;
    }
    dfd = open_dir_of(nv->path);
    if (dfd >= 0) {
        if (fsync(dfd) != 0) {
            rc = -1;
        }
        (void)close(dfd);
    }
    return rc;
}

static int load(co_lx_nv_t *nv, char *err, size_t errcap)
{
    struct stat st;
    int fd = open(nv->path, O_RDONLY | O_CLOEXEC);
    uint32_t got = 0U;

    if (fd < 0) {
        if (errno == ENOENT) {
            return 0; /* not written yet: erased */
        }
        (void)snprintf(err, errcap, "%s: %s", nv->path, strerror(errno));
        return -1;
    }
    if ((fstat(fd, &st) != 0) || !S_ISREG(st.st_mode) || (st.st_size > (off_t)nv->size)) {
        (void)snprintf(err, errcap, "%s: not a parameter file of at most %lu bytes", nv->path,
                       (unsigned long)nv->size);
        (void)close(fd);
        return -1;
    }
    while (got < (uint32_t)st.st_size) {
        ssize_t r = read(fd, &nv->img[got], (size_t)st.st_size - got);
        if ((r < 0) && (errno == EINTR)) {
            continue;
        }
        if (r <= 0) {
            (void)snprintf(err, errcap, "%s: read failed", nv->path);
            (void)close(fd);
            return -1;
        }
        got += (uint32_t)r;
    }
    (void)close(fd);
    return 0;
}

int co_lx_nv_open(co_lx_nv_t *nv, const char *path, uint32_t size, char *err, size_t errcap)
{
    int dfd;

    (void)memset(nv, 0, sizeof *nv);
    nv->size = size;
    nv->path = strdup(path);
    nv->img = (uint8_t *)malloc(size);
    if ((nv->path == NULL) || (nv->img == NULL) ||
        (asprintf(&nv->tmp, "%s.tmp", path) < 0)) {
        nv->tmp = NULL;
        (void)snprintf(err, errcap, "%s: out of memory", path);
        co_lx_nv_close(nv);
        return -1;
    }
    (void)memset(nv->img, 0xFF, size);
    dfd = open_dir_of(path);
    if ((dfd < 0) || (faccessat(dfd, ".", W_OK, AT_EACCESS) != 0)) {
        (void)snprintf(err, errcap, "%s: directory not writable (%s)", path, strerror(errno));
        if (dfd >= 0) {
            (void)close(dfd);
        }
        co_lx_nv_close(nv);
        return -1;
    }
    (void)close(dfd);
    if (load(nv, err, errcap) != 0) {
        co_lx_nv_close(nv);
        return -1;
    }
    return 0;
}

int co_lx_nv_read(void *ctx, uint32_t addr, uint8_t *buf, uint32_t len)
{
    const co_lx_nv_t *nv = (const co_lx_nv_t *)ctx;

    if ((addr > nv->size) || (len > (nv->size - addr))) {
        return -1;
    }
    (void)memcpy(buf, &nv->img[addr], len);
    return 0;
}

int co_lx_nv_write(void *ctx, uint32_t addr, const uint8_t *buf, uint32_t len)
{
    co_lx_nv_t *nv = (co_lx_nv_t *)ctx;
    uint8_t *old;

    if ((addr > nv->size) || (len > (nv->size - addr))) {
        return -1;
    }
    old = (uint8_t *)malloc((len != 0U) ? len : 1U);
    if (old == NULL) {
        return -1;
    }
    (void)memcpy(old, &nv->img[addr], len);
    (void)memcpy(&nv->img[addr], buf, len);
    if (persist(nv) != 0) {
        (void)memcpy(&nv->img[addr], old, len);
        free(old);
        return -1;
    }
    free(old);
    nv->writes++;
    return 0;
}

void co_lx_nv_close(co_lx_nv_t *nv)
{
    free(nv->path);
    free(nv->tmp);
    free(nv->img);
    (void)memset(nv, 0, sizeof *nv);
}
