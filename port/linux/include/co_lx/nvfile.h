/*
 * File-backed non-volatile memory for the HAL's nv_read / nv_write.
 *
 * The memory is an in-memory image of @c size bytes (erased: 0xFF) loaded
 * from the file at open. nv_read reads the image. Each nv_write changes the
 * image and then persists the whole image atomically: it is written to
 * "<path>.tmp", fsync'ed, renamed over <path>, and the directory is
 * fsync'ed, so after a crash the file holds either the old or the new image.
 * When persisting fails, the image is rolled back and nv_write fails (the
 * core answers the store request with an error).
 *
 * The file is created by the first nv_write; a missing file reads as erased.
 */
#ifndef CO_LX_NVFILE_H
#define CO_LX_NVFILE_H

#include <stddef.h>
#include <stdint.h>

#define CO_LX_NV_SIZE_DEFAULT 65536U

typedef struct co_lx_nv {
    char *path;
    char *tmp;
    uint8_t *img;
    uint32_t size;
    uint32_t writes;   /**< completed nv_writes (persisted) */
} co_lx_nv_t;

/** Open the memory behind @p path with @p size bytes. Returns 0, or -1 with
 *  a message in @p err (the file cannot be read, is larger than @p size, or
 *  its directory is not writable). */
int co_lx_nv_open(co_lx_nv_t *nv, const char *path, uint32_t size, char *err, size_t errcap);

/** HAL functions; @p ctx is the co_lx_nv_t. Return 0 on success, -1 for an
 *  access outside the memory or a failed write. */
int co_lx_nv_read(void *ctx, uint32_t addr, uint8_t *buf, uint32_t len);
int co_lx_nv_write(void *ctx, uint32_t addr, const uint8_t *buf, uint32_t len);

void co_lx_nv_close(co_lx_nv_t *nv);

#endif /* CO_LX_NVFILE_H */
