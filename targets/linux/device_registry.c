/* The device table of the daemon (see device_registry.h). */
#include "device_registry.h"

#include <string.h>

#include "anagate_motion.h"
#include "anagate_motion_400vac.h"
#include "anagate_motion_bl.h"
#include "cia402.h"
#include "cia408.h"
#include "co402_devices.h"
#include "co408_devices.h"
#include "dev_co402.h"
#include "dev_co408.h"
#include "dev_generic_301.h"
#include "faulhaber_mc.h"
#include "generic_301.h"
#include "kollmorgen_s300_s700.h"
#include "ssd_630.h"
#include "wandfluh_dsv.h"

/* EDS texts, embedded at build time (cmake/embed_text.cmake) */
extern const unsigned char codev_eds_generic_301[];
extern const unsigned char codev_eds_cia402[];
extern const unsigned char codev_eds_kollmorgen_s300_s700[];
extern const unsigned char codev_eds_ssd_630[];
extern const unsigned char codev_eds_faulhaber_mc[];
extern const unsigned char codev_eds_anagate_motion[];
extern const unsigned char codev_eds_anagate_motion_bl[];
extern const unsigned char codev_eds_anagate_motion_400vac[];
extern const unsigned char codev_eds_cia408[];
extern const unsigned char codev_eds_wandfluh_dsv[];

/* A CiA 402 drive: dictionary <c>_dev with its RAM type and hook count, the
 * profile's device description, one simulated plant per axis (dev_co402.h). */
#define DRIVE(name_, c_, hooks_, drive_, summary_)                                         \
    {                                                                                       \
        .name = (name_), .summary = (summary_), .dev = &c_##_dev,                           \
        .ram_size = sizeof(c_##_ram_t), .n_hooks = (hooks_), .eds = codev_eds_##c_,         \
        .app_size = sizeof(dco402_app_t), .profile = &(drive_), .prepare = dco402_prepare,  \
        .attach = dco402_attach, .process = dco402_process, .sync = NULL, .nmt = NULL,      \
        .reset = NULL, .detach = dco402_detach,                                             \
    }

/* A CiA 408 valve: dictionary, the profile's device description, one
 * simulated valve per channel (dev_co408.h). */
#define VALVE(name_, c_, hooks_, valve_, summary_)                                         \
    {                                                                                       \
        .name = (name_), .summary = (summary_), .dev = &c_##_dev,                           \
        .ram_size = sizeof(c_##_ram_t), .n_hooks = (hooks_), .eds = codev_eds_##c_,         \
        .app_size = sizeof(dco408_app_t), .profile = &(valve_), .prepare = dco408_prepare,  \
        .attach = dco408_attach, .process = dco408_process, .sync = NULL, .nmt = NULL,      \
        .reset = NULL, .detach = NULL,                                                      \
    }

static const device_entry_t devices[] = {
    {
        .name = "generic-301",
        .summary = "CiA 301 conformance device: every basic type, 100 kB DOMAIN 0x2300, "
                   "4 RPDO + 4 TPDO, 4 heartbeat consumers, error history of 8",
        .dev = &generic_301_dev,
        .ram_size = sizeof(generic_301_ram_t),
        .n_hooks = GENERIC_301_N_HOOKS,
        .eds = codev_eds_generic_301,
        .app_size = sizeof(g301_app_t),
        .profile = NULL,
        .prepare = NULL,
        .attach = g301_attach,
        .process = g301_process,
        .sync = NULL,
        .nmt = NULL,
        .reset = g301_reset,
        .detach = NULL,
    },
    DRIVE("cia402", cia402, CIA402_N_HOOKS, co402_dev_cia402,
          "CiA 402 servo drive on a simulated motor, strict CiA 402"),
    DRIVE("kollmorgen-s300-s700", kollmorgen_s300_s700, KOLLMORGEN_S300_S700_N_HOOKS,
          co402_dev_kollmorgen_s300_s700, "Kollmorgen S300/S700 servo amplifier (CiA 402)"),
    DRIVE("ssd-630", ssd_630, SSD_630_N_HOOKS, co402_dev_ssd_630,
          "SSD Drives 630 series drive (CiA 402)"),
    DRIVE("faulhaber-mc", faulhaber_mc, FAULHABER_MC_N_HOOKS, co402_dev_faulhaber_mc,
          "FAULHABER Motion Controller (CiA 402)"),
    DRIVE("anagate-motion", anagate_motion, ANAGATE_MOTION_N_HOOKS, co402_dev_anagate_motion,
          "AnaGate Motion BT, 4 stepper axes at 0x6000 + 0x800 n (CiA 402)"),
    DRIVE("anagate-motion-bt2", anagate_motion, ANAGATE_MOTION_N_HOOKS,
          co402_dev_anagate_motion_bt2, "AnaGate Motion BT with 2 motors (CiA 402)"),
    DRIVE("anagate-motion-bl", anagate_motion_bl, ANAGATE_MOTION_BL_N_HOOKS,
          co402_dev_anagate_motion_bl, "AnaGate Motion BL, 2 brushless axes (CiA 402)"),
    DRIVE("anagate-motion-400vac", anagate_motion_400vac, ANAGATE_MOTION_400VAC_N_HOOKS,
          co402_dev_anagate_motion_400vac, "AnaGate Motion 400 Vac, 2 axes (CiA 402)"),
    VALVE("cia408", cia408, CIA408_N_HOOKS, co408_dev_cia408,
          "CiA 408 proportional valve on a simulated valve: vpoc and vprc closed loop"),
    VALVE("wandfluh-dsv", wandfluh_dsv, WANDFLUH_DSV_N_HOOKS, co408_dev_wandfluh_dsv,
          "WANDFLUH DSV valve electronics (CiA DSP-408), 2 channels, on simulated valves"),
};

size_t device_count(void)
{
    return sizeof devices / sizeof devices[0];
}

const device_entry_t *device_at(size_t i)
{
    return (i < device_count()) ? &devices[i] : NULL;
}

const device_entry_t *device_find(const char *name)
{
    for (size_t i = 0U; i < device_count(); i++) {
        if (strcmp(devices[i].name, name) == 0) {
            return &devices[i];
        }
    }
    return NULL;
}
