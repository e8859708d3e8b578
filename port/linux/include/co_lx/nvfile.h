/*
 * File-backed non-volatile memory for the HAL's nv_read / nv_write.
 *
 * The memory is an in-memory image of @c size bytes (erased: 0xFF) loaded
 * from the file at open; size is what the node's storage needs
 * (co_store_nv_size). nv_read reads the image and nv_write changes it, no
 * file I/O in either. nv_poll (the HAL's asynchronous completion) persists
 * the image once for all the writes of a save, in a writer thread (started
 * at open, one for the file's life), so the
 * event loop keeps serving the bus meanwhile: the image is written to
 * "<path>.tmp", fsync'ed, renamed over <path>, and the directory is
 * fsync'ed, so after a crash the file holds either the old or the new image.
 * nv_poll answers CO_NV_BUSY until the file holds it, then 0; when
 * persisting fails, the image is rolled back to what the file holds and
 * nv_poll answers -1 (the core answers the store request with 0x06060000).
 *
 * The file is created by the first save; a missing file reads as erased; a
 * file longer than size (an older daemon's 64 KiB) gives its first size
 * bytes.
 */
#ifndef CO_LX_NVFILE_H
#define CO_LX_NVFILE_H

#include <pthread.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "co/co_hal.h"

#define CO_LX_NV_SIZE_MAX 65536U /**< the largest file taken at open */

typedef struct co_lx_nv {
    char *path;
    char *tmp;
    uint8_t *img;      /**< the memory as the node sees it */
    uint8_t *disk;     /**< what the file holds */
    uint8_t *snap;     /**< what the writer thread writes */
    uint32_t size;
    uint32_t writes;   /**< times the file was written (persisted) */
    bool dirty;        /**< img differs from what is written or being written */
    bool running;      /**< a write was handed to the writer thread */
    bool has_thread;   /**< the writer thread exists (else writes are synchronous) */
    pthread_t thread;
    pthread_mutex_t lock;
    pthread_cond_t cond;
    bool job;          /**< snap is to be written (under lock) */
    bool done;         /**< the last job is finished (under lock) */
    bool quit;         /**< the thread ends (under lock) */
    int result;        /**< the last job's result (under lock) */
} co_lx_nv_t;

/** Open the memory behind @p path with @p size bytes. Returns 0, or -1 with
 *  a message in @p err (the file cannot be read, is larger than @p size, or
 *  its directory is not writable). */
int co_lx_nv_open(co_lx_nv_t *nv, const char *path, uint32_t size, char *err, size_t errcap);

/** HAL functions; @p ctx is the co_lx_nv_t. Return 0 on success, -1 for an
 *  access outside the memory or a failed write. */
int co_lx_nv_read(void *ctx, uint32_t addr, uint8_t *buf, uint32_t len);
int co_lx_nv_write(void *ctx, uint32_t addr, const uint8_t *buf, uint32_t len);
/** HAL nv_poll: 0 when the file holds every write, CO_NV_BUSY while the
 *  writer thread is at it (it is started here), -1 when it failed. */
int co_lx_nv_poll(void *ctx);

/** Wait until the file holds every write (0), or it failed (-1). */
int co_lx_nv_flush(co_lx_nv_t *nv);

void co_lx_nv_close(co_lx_nv_t *nv);

#endif /* CO_LX_NVFILE_H */
