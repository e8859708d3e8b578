/*
 * The CiA 408 valves as devices (co_devices.h): one CiA 408 part per
 * description, configured by its co408_device_t (co408_devices.c).
 */
#include "co/co408_device.h"
#include "co408_devices.h"

static const co_device_part_t cia408_parts[] = {{&co408_part, &co408_dev_cia408, 1U}};
static const co_device_part_t dsv_parts[] = {{&co408_part, &co408_dev_wandfluh_dsv, 2U}};

const co_device_impl_t cia408_impl = {.parts = cia408_parts, .n_parts = 1U};
const co_device_impl_t wandfluh_dsv_impl = {.parts = dsv_parts, .n_parts = 1U};
