/*
 * The CiA 402 devices of this repository (devices/<name>.toml with the CiA 402
 * profile), for a daemon that runs one by name (canopen-device --device NAME)
 * and for the tests. Each is described in its devices/<name>.c: options,
 * homing methods, error reporting, simulated plant, power-on behaviour,
 * device plug-in (faulhaber_mc_desc.c, anagate_motion_desc.c).
 */
#ifndef CO402_DEVICES_H
#define CO402_DEVICES_H

#include "co/co402_device.h"

extern const co402_device_t co402_dev_cia402;               /* cia402: the standard drive */
extern const co402_device_t co402_dev_kollmorgen_s300_s700; /* Kollmorgen S300/S700 */
extern const co402_device_t co402_dev_ssd_630;              /* SSD Drives 630 series */
extern const co402_device_t co402_dev_faulhaber_mc;          /* FAULHABER Motion Controller */
extern const co402_device_t co402_dev_anagate_motion;        /* AnaGate Motion BT, 4 motors */
extern const co402_device_t co402_dev_anagate_motion_bt2;    /* AnaGate Motion BT, 2 motors */
extern const co402_device_t co402_dev_anagate_motion_bl;     /* AnaGate Motion BL */
extern const co402_device_t co402_dev_anagate_motion_400vac; /* AnaGate Motion 400 Vac */

/** The device named @p name (as devices/<name>.toml), NULL if none. */
const co402_device_t *co402_device_find(const char *name);

/** The @p k-th device (NULL after the last). */
const co402_device_t *co402_device_at(unsigned k);

#endif /* CO402_DEVICES_H */
