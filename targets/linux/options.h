/*
 * Command line of canopen-device.
 *
 *   canopen-device [--iface IF] [--node-id N] [--device NAME | --eds FILE] [--storage PATH]
 *                  [--serial N] [--node [ID]:[DEVICE[:PATH[:SERIAL]]]]... [--trace FILE|-]
 *                  [--control PATH] [--log-level error|warn|info|debug]
 *   canopen-device --export-eds PATH [--device NAME]
 *   canopen-device --list-devices | --help | --version
 *
 * --eds FILE runs the device an EDS or DCF describes (as does a --device or
 * --node DEVICE ending in .eds / .dcf).
 * --node-id/--device/--storage/--serial describe one node (the default node:
 * generic-301, no storage); each --node adds one more node on the same
 * interface. With --node only, the default node is not started unless
 * --node-id is given. A device with LSS starts unconfigured (node-ID 0xFF,
 * LSS only) without a node-ID (an LSS-stored one in its --storage wins);
 * a device without LSS defaults to node-ID 1; a device whose node-ID comes
 * only through LSS (faulhaber-mc) takes none.
 */
#ifndef OPTIONS_H
#define OPTIONS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "co_lx/port.h"

#define OPT_NODES_MAX 127U
#define OPT_DEFAULT_DEVICE "generic-301" /**< --device without the option; listed first */

typedef enum opt_mode {
    OPT_RUN,
    OPT_HELP,
    OPT_VERSION,
    OPT_LIST,
    OPT_EXPORT_EDS
} opt_mode_t;

typedef struct opt_node {
    uint8_t id;           /**< 1..127; 0xFF: unconfigured (LSS devices) */
    const char *device;   /**< registry name */
    const char *storage;  /**< parameter file, NULL for none */
    const char *eds;      /**< EDS/DCF file the device is built from, or NULL */
    uint32_t serial;      /**< 0x1018 sub 4, when serial_given */
    bool id_given;
    bool serial_given;
} opt_node_t;

typedef struct options {
    opt_mode_t mode;
    const char *iface;
    const char *trace;        /**< NULL: no trace; "-": stdout */
    const char *control;      /**< --control socket path, NULL: none */
    const char *export_path;
    co_lx_level_t log_level;
    size_t n_nodes;
    opt_node_t nodes[OPT_NODES_MAX];
} options_t;

/** Parse @p argv. Returns 0, or -1 with a one-line message (no newline) in
 *  @p err: a usage error (exit status 2). Strings point into argv. */
int options_parse(options_t *o, int argc, char **argv, char *err, size_t errcap);

/** The --help text. */
extern const char options_usage[];

#endif /* OPTIONS_H */
