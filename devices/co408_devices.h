/*
 * The CiA 408 valves of this repository (devices/<name>.toml with the CiA 408
 * profile), for a daemon that runs one by name and for the tests.
 */
#ifndef CO408_DEVICES_H
#define CO408_DEVICES_H

#include "co/co408_device.h"

extern const co408_device_t co408_dev_cia408;       /* cia408: the standard valve */
extern const co408_device_t co408_dev_wandfluh_dsv; /* Wandfluh DSV */

/** The device named @p name (as devices/<name>.toml), NULL if none. */
const co408_device_t *co408_device_find(const char *name);

/** The @p k-th device (NULL after the last). */
const co408_device_t *co408_device_at(unsigned k);

#endif /* CO408_DEVICES_H */
