/*
 * cia402: the standard CiA 402 drive (devices/cia402.toml) on the profile
 * without deviations, on the default simulated motor.
 */
#include "cia402.h"
#include "co402_devices.h"

const co402_device_t co402_dev_cia402 = {
    .name = "cia402",
    .dev = &cia402_dev,
    .axes = 1U,
    .options = 0U,
};
