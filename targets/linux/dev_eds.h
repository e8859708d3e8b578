/*
 * A device of the daemon made from an EDS/DCF at start-up (--eds FILE): the
 * dictionary eds_load builds, as a registry entry without application part
 * (objects the core gives no behaviour simply hold their values).
 */
#ifndef DEV_EDS_H
#define DEV_EDS_H

#include <stddef.h>

#include "co/co_device.h"
#include "eds_load.h"

typedef struct dev_eds {
    co_device_t entry;
    eds_dev_t *eds;
} dev_eds_t;

/** Load @p path into @p e. 0, or -1 with one line in @p err (exit status 2). */
int dev_eds_open(dev_eds_t *e, const char *path, char *err, size_t errcap);

/** Release what dev_eds_open took (harmless on a zeroed or closed @p e). */
void dev_eds_close(dev_eds_t *e);

/** 1 if the --device / --node name @p name is an EDS or DCF file name. */
int dev_eds_is_file(const char *name);

#endif /* DEV_EDS_H */
