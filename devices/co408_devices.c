/*
 * The CiA 408 valves: their profile settings, by name.
 */
#include "co408_devices.h"

#include <stddef.h>
#include <string.h>

#include "cia408.h"
#include "wandfluh_dsv.h"

/* cia408: vpoc and vprc closed loop; unsupported values 0x06090030. */
static const int8_t cia408_modes[] = {CO408_MODE_VPOC, CO408_MODE_VPRC_CL};

const co408_device_t co408_dev_cia408 = {
    "cia408", &cia408_dev, 1U, {cia408_modes, NULL}, {(uint8_t)sizeof cia408_modes, 0U},
    CO_OK, NULL,
};

/* Wandfluh DSV (controller variant): channel 1 every mode of digest 5.3,
 * channel 2 the open-loop spool and pressure valve; an unsupported value
 * answers 0x06040043 ("Wert ungueltig": the device's list has no
 * 0x06090030). */
static const int8_t dsv_modes_1[] = {
    CO408_MODE_VPOC, CO408_MODE_VPRC, CO408_MODE_VPRC_CL, CO408_MODE_DCOL, CO408_MODE_DSC,
    CO408_MODE_DPC, CO408_MODE_VPRC_2, CO408_MODE_NPT_1, CO408_MODE_NPT_2, CO408_MODE_NPT_3,
};
static const int8_t dsv_modes_2[] = {CO408_MODE_VPOC, CO408_MODE_VPRC};

const co408_device_t co408_dev_wandfluh_dsv = {
    "wandfluh-dsv", &wandfluh_dsv_dev, 2U, {dsv_modes_1, dsv_modes_2},
    {(uint8_t)sizeof dsv_modes_1, (uint8_t)sizeof dsv_modes_2}, CO_ERR_PARAM_INCOMPAT, NULL,
};

static const co408_device_t *const all[] = {
    &co408_dev_cia408,
    &co408_dev_wandfluh_dsv,
};

const co408_device_t *co408_device_at(unsigned k)
{
    return (k < (sizeof all / sizeof all[0])) ? all[k] : NULL;
}

const co408_device_t *co408_device_find(const char *name)
{
    for (size_t k = 0U; k < (sizeof all / sizeof all[0]); k++) {
        if (strcmp(all[k]->name, name) == 0) {
            return all[k];
        }
    }
    return NULL;
}
