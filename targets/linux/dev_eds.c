/* A device made from an EDS/DCF at start-up (dev_eds.h). */
#include "dev_eds.h"

#include <string.h>
#include <strings.h>

int dev_eds_open(dev_eds_t *e, const char *path, char *err, size_t errcap)
{
    (void)memset(e, 0, sizeof *e);
    e->eds = eds_load_file(path, err, errcap);
    if (e->eds == NULL) {
        return -1;
    }
    {
        const co_dev_t *dev = eds_device(e->eds);
        e->entry.name = eds_name(e->eds);
        e->entry.summary = eds_summary(e->eds);
        e->entry.dev = dev;
        e->entry.eds = (const unsigned char *)eds_text(e->eds);
    }
    return 0;
}

void dev_eds_close(dev_eds_t *e)
{
    eds_free(e->eds);
    e->eds = NULL;
}

int dev_eds_is_file(const char *name)
{
    size_t n = strlen(name);

    return (n > 4U) && ((strcasecmp(&name[n - 4U], ".eds") == 0) ||
                        (strcasecmp(&name[n - 4U], ".dcf") == 0));
}
