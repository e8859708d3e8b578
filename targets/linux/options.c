/* Command line of canopen-device (see options.h). */
#include "options.h"

#include <errno.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "co_devices.h"
#include "dev_eds.h"

const char options_usage[] =
    "Usage: canopen-device [OPTION]...\n"
    "Run simulated CANopen devices (CiA 301 slaves) on a SocketCAN interface.\n"
    "\n"
    "  --iface IF           CAN interface (default vcan0)\n"
    "  --node-id N          node-ID 1..127 (default: unconfigured, waiting for LSS, for a\n"
    "                       device with LSS; 1 for one without; none for an LSS-only one)\n"
    "  --device NAME        device type (default generic-301; see --list-devices)\n"
    "  --storage PATH       parameter file for 0x1010/0x1011 and the LSS-stored node-ID and\n"
    "                       bit timing (default: none, store refused)\n"
    "  --serial N           serial number 0x1018 sub 4 of this node, its LSS address\n"
    "                       (default: the device description's, 1 for generic-301, cia402)\n"
    "  --node [ID]:[DEVICE[:PATH[:SERIAL]]]\n"
    "                       one more node in this process (repeatable; no ID: LSS)\n"
    "  --eds FILE           the device an EDS or DCF describes, built at start-up\n"
    "                       (also: --device FILE.eds, --node ID:FILE.eds)\n"
    "  --trace FILE|-       write every frame on the bus in candump -L format\n"
    "  --control PATH       serve line commands on a Unix socket (set/get INDEX SUB,\n"
    "                       emcy CODE, heartbeat stop|resume, offbus MS, help)\n"
    "  --log-level LEVEL    error, warn, info (default) or debug; messages go to stderr\n"
    "  --export-eds PATH    write the EDS of --device to PATH ('-': stdout) and exit\n"
    "  --list-devices       list the device types and exit\n"
    "  --help               show this help and exit\n"
    "  --version            show the version and exit\n"
    "\n"
    "SIGTERM or SIGINT stop the daemon cleanly (exit 0). Exit 1: the interface or a\n"
    "file cannot be used; exit 2: usage error or a bad EDS (file:line: [section] key).\n"
    "A virtual bus: ip link add dev vcan0 type vcan; ip link set up vcan0\n";

enum { O_NONE, O_ARG, O_FLAG };

typedef struct opt_def {
    const char *name;
    int kind;
} opt_def_t;

static const opt_def_t defs[] = {
    {"iface", O_ARG},        {"node-id", O_ARG},      {"device", O_ARG},      {"eds", O_ARG},
    {"storage", O_ARG},      {"node", O_ARG},         {"trace", O_ARG},
    {"control", O_ARG},      {"log-level", O_ARG},    {"export-eds", O_ARG},
    {"list-devices", O_FLAG}, {"help", O_FLAG},       {"version", O_FLAG},
    {"serial", O_ARG},
};

static int fail(char *err, size_t cap, const char *fmt, const char *a, const char *b)
{
    (void)snprintf(err, cap, fmt, a, b);
    return -1;
}

static int parse_id(const char *s, uint8_t *id)
{
    char *end = NULL;
    unsigned long v;

    if ((s[0] < '0') || (s[0] > '9')) {
        return -1;
    }
    errno = 0;
    v = strtoul(s, &end, 0);
    if ((errno != 0) || (end == s) || (*end != '\0') || (v < 1UL) || (v > 127UL)) {
        return -1;
    }
    *id = (uint8_t)v;
    return 0;
}

static int parse_u32(const char *s, uint32_t *v)
{
    char *end = NULL;
    unsigned long long x;

    if ((s[0] < '0') || (s[0] > '9')) {
        return -1;
    }
    errno = 0;
    x = strtoull(s, &end, 0);
    if ((errno != 0) || (end == s) || (*end != '\0') || (x > 0xFFFFFFFFULL)) {
        return -1;
    }
    *v = (uint32_t)x;
    return 0;
}

/* Cut @p s at the next ':'; the rest, or NULL. */
static char *cut(char *s)
{
    char *c = (s != NULL) ? strchr(s, ':') : NULL;

    if (c != NULL) {
        *c = '\0';
        c++;
    }
    return c;
}

/* [ID]:[DEVICE[:PATH[:SERIAL]]], split in place */
static int parse_node(char *spec, opt_node_t *n, char *err, size_t cap)
{
    char *dev = cut(spec);
    char *path = cut(dev);
    char *serial = cut(path);

    n->device = OPT_DEFAULT_DEVICE;
    n->storage = NULL;
    n->eds = NULL;
    n->id_given = (*spec != '\0');
    n->serial_given = false;
    if ((dev != NULL) && (*dev != '\0')) {
        n->device = dev;
        n->eds = dev_eds_is_file(dev) ? dev : NULL;
    }
    if ((path != NULL) && (*path != '\0')) {
        n->storage = path;
    }
    if (n->id_given && (parse_id(spec, &n->id) != 0)) {
        return fail(err, cap, "--node: node-ID must be 1..127, got '%s'%s", spec, "");
    }
    if ((serial != NULL) && (*serial != '\0')) {
        if (parse_u32(serial, &n->serial) != 0) {
            return fail(err, cap, "--node: serial number must be 0..0xFFFFFFFF, got '%s'%s",
                        serial, "");
        }
        n->serial_given = true;
    }
    return 0;
}

/* The node-ID of a node by its device's LSS: none given is unconfigured
 * with LSS, else @p def (0: a node-ID is needed); an LSS-only device takes
 * none. */
static int resolve_id(opt_node_t *n, uint8_t def, char *err, size_t cap)
{
    const co_device_t *e = (n->eds != NULL) ? NULL : co_device_find(n->device);
    bool lss = (e != NULL) && (e->dev->set.lss.slave != 0U); /* an EDS device: no LSS */
    bool lss_only = (e != NULL) && (e->dev->set.lss.node_id == CO_LSS_ID_ONLY);

    if (n->id_given && lss_only) {
        return fail(err, cap, "%s takes its node-ID only through LSS: start it without one%s",
                    n->device, "");
    }
    if (!n->id_given && !lss && (def == 0U)) {
        return fail(err, cap, "--node: node-ID must be 1..127, got ''%s%s", "", "");
    }
    if (!n->id_given) {
        n->id = lss ? CO_NODE_ID_UNCONFIGURED : def;
    }
    return 0;
}

static int set_level(options_t *o, const char *v)
{
    static const char *const names[] = {"error", "warn", "info", "debug"};

    for (unsigned i = 0U; i < 4U; i++) {
        if (strcmp(v, names[i]) == 0) {
            o->log_level = (co_lx_level_t)i;
            return 0;
        }
    }
    return -1;
}

int options_parse(options_t *o, int argc, char **argv, char *err, size_t cap)
{
    opt_node_t primary = {1U, OPT_DEFAULT_DEVICE, NULL, NULL, 0U, false, false};
    bool primary_given = false;
    bool device_given = false;
    bool want_help = false;
    bool want_version = false;
    bool want_list = false;
    size_t extra = 0U;
    opt_node_t extras[OPT_NODES_MAX];
    int i;

    (void)memset(o, 0, sizeof *o);
    o->mode = OPT_RUN;
    o->iface = "vcan0";
    o->log_level = CO_LX_INFO;

    for (i = 1; i < argc; i++) {
        char *a = argv[i];
        char *val = NULL;
        const opt_def_t *d = NULL;
        size_t len;
        char *eq;

        if ((a[0] != '-') || (a[1] != '-') || (a[2] == '\0')) {
            return fail(err, cap, "unexpected argument '%s' (try --help)%s", a, "");
        }
        eq = strchr(a, '=');
        len = (eq != NULL) ? (size_t)(eq - a - 2) : strlen(a + 2);
        for (size_t k = 0U; k < sizeof defs / sizeof defs[0]; k++) {
            if ((strlen(defs[k].name) == len) && (strncmp(defs[k].name, a + 2, len) == 0)) {
                d = &defs[k];
            }
        }
        if (d == NULL) {
            return fail(err, cap, "unknown option '%s' (try --help)%s", a, "");
        }
        if (d->kind == O_ARG) {
            if (eq != NULL) {
                val = eq + 1;
            } else if (i + 1 < argc) {
                val = argv[++i];
            } else {
                return fail(err, cap, "option --%s needs a value (try --help)%s", d->name, "");
            }
        } else if (eq != NULL) {
            return fail(err, cap, "option --%s takes no value%s", d->name, "");
        } else {
            /* a flag */
        }

        if (strcmp(d->name, "iface") == 0) {
            if ((val[0] == '\0') || (strlen(val) >= 16U)) {
                return fail(err, cap, "--iface: bad interface name '%s'%s", val, "");
            }
            o->iface = val;
        } else if (strcmp(d->name, "node-id") == 0) {
            if (parse_id(val, &primary.id) != 0) {
                return fail(err, cap, "--node-id must be 1..127, got '%s'%s", val, "");
            }
            primary.id_given = true;
            primary_given = true;
        } else if (strcmp(d->name, "serial") == 0) {
            if (parse_u32(val, &primary.serial) != 0) {
                return fail(err, cap, "--serial must be 0..0xFFFFFFFF, got '%s'%s", val, "");
            }
            primary.serial_given = true;
            primary_given = true;
        } else if ((strcmp(d->name, "device") == 0) || (strcmp(d->name, "eds") == 0)) {
            if ((d->name[0] == 'e') && !dev_eds_is_file(val) && (val[0] == '\0')) {
                return fail(err, cap, "--eds needs a file name%s%s", "", "");
            }
            primary.device = val;
            primary.eds = ((d->name[0] == 'e') || dev_eds_is_file(val)) ? val : NULL;
            device_given = true;
        } else if (strcmp(d->name, "storage") == 0) {
            if (val[0] == '\0') {
                return fail(err, cap, "--storage needs a file name%s%s", "", "");
            }
            primary.storage = val;
            primary_given = true;
        } else if (strcmp(d->name, "node") == 0) {
            if (extra >= OPT_NODES_MAX) {
                return fail(err, cap, "too many --node options%s%s", "", "");
            }
            if (parse_node(val, &extras[extra], err, cap) != 0) {
                return -1;
            }
            extra++;
        } else if (strcmp(d->name, "trace") == 0) {
            if (val[0] == '\0') {
                return fail(err, cap, "--trace needs a file name or '-'%s%s", "", "");
            }
            o->trace = val;
        } else if (strcmp(d->name, "control") == 0) {
            if (val[0] == '\0') {
                return fail(err, cap, "--control needs a socket path%s%s", "", "");
            }
            o->control = val;
        } else if (strcmp(d->name, "log-level") == 0) {
            if (set_level(o, val) != 0) {
                return fail(err, cap,
                            "--log-level must be error, warn, info or debug, got '%s'%s", val,
                            "");
            }
        } else if (strcmp(d->name, "export-eds") == 0) {
            if (val[0] == '\0') {
                return fail(err, cap, "--export-eds needs a file name or '-'%s%s", "", "");
            }
            o->export_path = val;
            o->mode = OPT_EXPORT_EDS;
        } else if (strcmp(d->name, "list-devices") == 0) {
            want_list = true;
        } else if (strcmp(d->name, "help") == 0) {
            want_help = true;
        } else {
            want_version = true;
        }
    }

    /* --help, then --version, then --list-devices win over everything else */
    if (want_help || want_version || want_list) {
        o->mode = want_help ? OPT_HELP : (want_version ? OPT_VERSION : OPT_LIST);
        return 0;
    }
    if ((primary.eds == NULL) && (co_device_find(primary.device) == NULL)) {
        return fail(err, cap, "unknown device '%s' (see --list-devices)%s", primary.device, "");
    }
    if (resolve_id(&primary, 1U, err, cap) != 0) {
        return -1;
    }
    if (o->mode == OPT_EXPORT_EDS) {
        o->nodes[0] = primary;
        o->n_nodes = 1U;
        return 0;
    }
    if (primary_given || device_given || (extra == 0U)) {
        o->nodes[o->n_nodes++] = primary;
    }
    for (size_t k = 0U; k < extra; k++) {
        if ((extras[k].eds == NULL) && (co_device_find(extras[k].device) == NULL)) {
            return fail(err, cap, "unknown device '%s' (see --list-devices)%s", extras[k].device,
                        "");
        }
        if (resolve_id(&extras[k], 0U, err, cap) != 0) {
            return -1;
        }
        for (size_t j = 0U; j < o->n_nodes; j++) {
            if ((o->nodes[j].id == extras[k].id) && (extras[k].id != CO_NODE_ID_UNCONFIGURED)) {
                char id[8];
                (void)snprintf(id, sizeof id, "%u", (unsigned)extras[k].id);
                return fail(err, cap, "node-ID %s given twice%s", id, "");
            }
        }
        if (o->n_nodes >= OPT_NODES_MAX) {
            return fail(err, cap, "too many nodes%s%s", "", "");
        }
        o->nodes[o->n_nodes++] = extras[k];
    }
    for (size_t k = 0U; k < o->n_nodes; k++) {
        for (size_t j = k + 1U; j < o->n_nodes; j++) {
            if ((o->nodes[k].storage != NULL) && (o->nodes[j].storage != NULL) &&
                (strcmp(o->nodes[k].storage, o->nodes[j].storage) == 0)) {
                return fail(err, cap, "two nodes share the parameter file '%s'%s",
                            o->nodes[k].storage, "");
            }
        }
    }
    return 0;
}
