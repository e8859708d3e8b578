/* The device table of the daemon (see device_registry.h). */
#include "device_registry.h"

#include <string.h>

#include "dev_generic_301.h"
#include "generic_301.h"

/* EDS texts, embedded at build time (cmake/embed_text.cmake) */
extern const unsigned char codev_eds_generic_301[];

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
        .attach = g301_attach,
        .process = g301_process,
        .sync = NULL,
        .nmt = NULL,
        .reset = g301_reset,
        .detach = NULL,
    },
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
