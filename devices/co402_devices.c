/*
 * The CiA 402 devices by name.
 */
#include "co402_devices.h"

#include <stddef.h>
#include <string.h>

static const co402_device_t *const all[] = {
    &co402_dev_cia402,
    &co402_dev_kollmorgen_s300_s700,
    &co402_dev_ssd_630,
    &co402_dev_faulhaber_mc,
    &co402_dev_anagate_motion,
    &co402_dev_anagate_motion_bt2,
    &co402_dev_anagate_motion_bl,
    &co402_dev_anagate_motion_400vac,
};

const co402_device_t *co402_device_at(unsigned k)
{
    return (k < (sizeof all / sizeof all[0])) ? all[k] : NULL;
}

const co402_device_t *co402_device_find(const char *name)
{
    for (size_t k = 0U; k < (sizeof all / sizeof all[0]); k++) {
        if (strcmp(all[k]->name, name) == 0) {
            return all[k];
        }
    }
    return NULL;
}
