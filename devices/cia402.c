/*
 * cia402: the standard CiA 402 drive (devices/cia402.toml) on the profile
 * without deviations, on the default simulated motor.
 */
#include "co/co402_device.h"

static const co402_params_t params_cia402_impl = {
    .options = 0U,
};

static const co_device_part_t parts_cia402_impl[] = {{&co402_part, &params_cia402_impl, 1U}};

const co_device_impl_t cia402_impl = {
    .parts = parts_cia402_impl,
    .n_parts = 1U,
};
