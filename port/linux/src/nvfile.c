/* File-backed non-volatile memory (see nvfile.h). */
#include "co_lx/nvfile.h"

#include <errno.h>
#include <fcntl.h>
#include <libgen.h>
#include <pthread.h>
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

/* Write @p img to the file atomically (temporary file, fsync, rename,
 * fsync of the directory). Runs in the writer thread. */
static int persist(const co_lx_nv_t *nv, const uint8_t *img)
{
    int fd = open(nv->tmp, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC,
                  S_IRUSR | S_IWUSR | S_IRGRP | S_IROTH);
    int dfd;
    int rc = 0;

    if (fd < 0) {
        return -1;
    }
    if ((write_all(fd, img, nv->size) != 0) || (fsync(fd) != 0)) {
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

static void *writer(void *arg);

static int load(co_lx_nv_t *nv, char *err, size_t errcap)
{
    struct stat st;
    int fd = open(nv->path, O_RDONLY | O_CLOEXEC);
    uint32_t got = 0U;
    uint32_t want;

    if (fd < 0) {
        if (errno == ENOENT) {
            return 0; /* not written yet: erased */
        }
        (void)snprintf(err, errcap, "%s: %s", nv->path, strerror(errno));
        return -1;
    }
    if ((fstat(fd, &st) != 0) || !S_ISREG(st.st_mode) || (st.st_size > (off_t)CO_LX_NV_SIZE_MAX)) {
        (void)snprintf(err, errcap, "%s: not a parameter file of at most %lu bytes", nv->path,
                       (unsigned long)CO_LX_NV_SIZE_MAX);
        (void)close(fd);
        return -1;
    }
    /* a larger file (an older daemon's 64 KiB image) holds the banks at the
     * same addresses: its first size bytes are the memory */
    want = ((uint32_t)st.st_size < nv->size) ? (uint32_t)st.st_size : nv->size;
    while (got < want) {
        ssize_t r = read(fd, &nv->img[got], (size_t)want - got);
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
    (void)memcpy(nv->disk, nv->img, nv->size);
    return 0;
}

int co_lx_nv_open(co_lx_nv_t *nv, const char *path, uint32_t size, char *err, size_t errcap)
{
    int dfd;

    (void)memset(nv, 0, sizeof *nv);
    (void)pthread_mutex_init(&nv->lock, NULL);
    (void)pthread_cond_init(&nv->cond, NULL);
    nv->size = size;
    nv->path = strdup(path);
    nv->img = (uint8_t *)malloc(size);
    nv->disk = (uint8_t *)malloc(size);
    nv->snap = (uint8_t *)malloc(size);
    if ((nv->path == NULL) || (nv->img == NULL) || (nv->disk == NULL) || (nv->snap == NULL) ||
        (asprintf(&nv->tmp, "%s.tmp", path) < 0)) {
        nv->tmp = NULL;
        (void)snprintf(err, errcap, "%s: out of memory", path);
        co_lx_nv_close(nv);
        return -1;
    }
    (void)memset(nv->img, 0xFF, size);
    (void)memset(nv->disk, 0xFF, size);
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
    /* without a thread the file is written in the caller's time */
    nv->has_thread = (pthread_create(&nv->thread, NULL, writer, nv) == 0);
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

    if ((addr > nv->size) || (len > (nv->size - addr))) {
        return -1;
    }
    (void)memcpy(&nv->img[addr], buf, len);
    nv->dirty = true;
    return 0;
}

/* The writer thread: started at open, it writes each snapshot it is given
 * (job) and reports the result (done). One thread for the file's life: no
 * thread start in the event loop's time. */
static void *writer(void *arg)
{
    co_lx_nv_t *nv = (co_lx_nv_t *)arg;

    (void)pthread_mutex_lock(&nv->lock);
    for (;;) {
        int rc;
        while (!nv->job && !nv->quit) {
            (void)pthread_cond_wait(&nv->cond, &nv->lock);
        }
        if (!nv->job) {
            break; /* quit, nothing left to write */
        }
        (void)pthread_mutex_unlock(&nv->lock);
        rc = persist(nv, nv->snap);
        (void)pthread_mutex_lock(&nv->lock);
        nv->result = rc;
        nv->job = false;
        nv->done = true;
        (void)pthread_cond_broadcast(&nv->cond);
    }
    (void)pthread_mutex_unlock(&nv->lock);
    return NULL;
}

/* A write has finished (done): take its result. */
static int take_result(co_lx_nv_t *nv, int rc)
{
    nv->running = false;
    if (rc == 0) {
        (void)memcpy(nv->disk, nv->snap, nv->size);
        nv->writes++;
    } else {
        /* the file keeps the previous image: so does the memory (a later
         * write must not carry this one's bytes along) */
        (void)memcpy(nv->img, nv->disk, nv->size);
        nv->dirty = false;
    }
    return rc;
}

/* Wait for the running write (co_lx_nv_flush). */
static int wait_writer(co_lx_nv_t *nv)
{
    int rc;

    (void)pthread_mutex_lock(&nv->lock);
    while (!nv->done) {
        (void)pthread_cond_wait(&nv->cond, &nv->lock);
    }
    rc = nv->result;
    (void)pthread_mutex_unlock(&nv->lock);
    return take_result(nv, rc);
}

static int start_writer(co_lx_nv_t *nv)
{
    (void)memcpy(nv->snap, nv->img, nv->size);
    nv->dirty = false;
    if (!nv->has_thread) {
        /* no thread: write in the caller's time */
        return take_result(nv, persist(nv, nv->snap));
    }
    (void)pthread_mutex_lock(&nv->lock);
    nv->done = false;
    nv->job = true;
    (void)pthread_cond_broadcast(&nv->cond);
    (void)pthread_mutex_unlock(&nv->lock);
    nv->running = true;
    return CO_NV_BUSY;
}

int co_lx_nv_poll(void *ctx)
{
    co_lx_nv_t *nv = (co_lx_nv_t *)ctx;

    if (nv->running) {
        int rc;
        bool done;
        (void)pthread_mutex_lock(&nv->lock);
        done = nv->done;
        rc = nv->result;
        (void)pthread_mutex_unlock(&nv->lock);
        if (!done) {
            return CO_NV_BUSY;
        }
        rc = take_result(nv, rc);
        if ((rc != 0) || !nv->dirty) {
            return rc;
        }
    }
    return nv->dirty ? start_writer(nv) : 0;
}

int co_lx_nv_flush(co_lx_nv_t *nv)
{
    int rc = 0;

    if (nv->running) {
        rc = wait_writer(nv);
    }
    if ((rc == 0) && nv->dirty) {
        rc = start_writer(nv);
        if (rc == CO_NV_BUSY) {
            rc = wait_writer(nv);
        }
    }
    return rc;
}

void co_lx_nv_close(co_lx_nv_t *nv)
{
    if (nv->img != NULL) {
        (void)co_lx_nv_flush(nv);
    }
    if (nv->has_thread) {
        (void)pthread_mutex_lock(&nv->lock);
        nv->quit = true;
        (void)pthread_cond_broadcast(&nv->cond);
        (void)pthread_mutex_unlock(&nv->lock);
        (void)pthread_join(nv->thread, NULL);
    }
    (void)pthread_cond_destroy(&nv->cond);
    free(nv->path);
    free(nv->tmp);
    free(nv->img);
    free(nv->disk);
    free(nv->snap);
    (void)pthread_mutex_destroy(&nv->lock);
    (void)memset(nv, 0, sizeof *nv);
}
