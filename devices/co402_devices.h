/*
 * The CiA 402 devices of this repository (devices/<name>.toml with the CiA 402
 * profile), for a daemon that runs one by name (canopen-device --device NAME)
 * and for the tests. Each is described in its devices/<name>.c: options,
 * homing methods, error reporting, simulated plant, power-on behaviour.
 */
#ifndef CO402_DEVICES_H
#define CO402_DEVICES_H

#include "co/co402_device.h"

extern const co402_device_t co402_dev_cia402;               /* cia402: the standard drive */
extern const co402_device_t co402_dev_kollmorgen_s300_s700; /* Kollmorgen S300/S700 */
extern const co402_device_t co402_dev_ssd_630;              /* SSD Drives 630 series */

/** The device named @p name (as devices/<name>.toml), NULL if none. */
const co402_device_t *co402_device_find(const char *name);

/** The @p k-th device (NULL after the last). */
const co402_device_t *co402_device_at(unsigned k);

#endif /* CO402_DEVICES_H */
