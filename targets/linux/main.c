/*
 * canopen-device: simulated CANopen devices on a SocketCAN interface.
 * Options in options.h, devices in co_devices.h (generated from devices/),
 * each run by the device layer (co/co_device.h) on simulated plants, the loop in
 * port/linux (co_lx/loop.h).
 */
#include <errno.h>
#include <signal.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "co/co_endian.h"
#include "co/co_node.h"
#include "co_lx/clock.h"
#include "co_lx/loop.h"
#include "co_lx/nvfile.h"
#include "co_lx/port.h"
#include "co_lx/trace.h"
#include "co/co_device.h"
#include "co_devices.h"
#include "control.h"
#include "dev_eds.h"
#include "options.h"

#ifndef CO_VERSION
#define CO_VERSION "0.0.0"
#endif

#define PROG "canopen-device"

typedef struct dnode {
    const co_device_t *dev;
    co_device_run_t run;
    co_node_t node;
    void *ram;
    void *mem;              /* the device's instances, plants and plug-in state */
    co_lx_port_t port;
    co_lx_nv_t nv;
    int has_nv;
    uint8_t id;
    dev_eds_t eds;          /* a device built from an EDS/DCF (--eds) */
    uint32_t serial;        /* 0x1018 sub 4 (--serial), when serial_given */
    bool serial_given;
    char tag[64];
} dnode_t;

/* What the control interface acts on (control.h). */
typedef struct ctl_nodes {
    dnode_t *nodes;
    size_t n;
} ctl_nodes_t;

static co_lx_level_t log_level = CO_LX_INFO;
static volatile sig_atomic_t stop_flag;

static void on_signal(int sig)
{
    (void)sig;
    stop_flag = 1;
}

static const char *level_name(co_lx_level_t l)
{
    static const char *const names[] = {"error", "warn", "info", "debug"};
    return names[(unsigned)l & 3U];
}

static void log_line(const char *tag, co_lx_level_t level, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

static void log_line(const char *tag, co_lx_level_t level, const char *fmt, ...)
{
    va_list ap;

    if (level > log_level) {
        return;
    }
    (void)fprintf(stderr, PROG ": %s: ", level_name(level));
    if (tag != NULL) {
        (void)fprintf(stderr, "%s: ", tag);
    }
    va_start(ap, fmt);
    (void)vfprintf(stderr, fmt, ap);
    va_end(ap);
    (void)fputc('\n', stderr);
}

static void port_log(void *ctx, co_lx_level_t level, const char *msg)
{
    log_line((const char *)ctx, level, "%s", msg);
}

static const char *state_name(co_nmt_state_t s)
{
    switch (s) {
    case CO_NMT_INITIALISING: return "initialising";
    case CO_NMT_STOPPED: return "stopped";
    case CO_NMT_OPERATIONAL: return "operational";
    case CO_NMT_PRE_OPERATIONAL: return "pre-operational";
    default: return "?";
    }
}

/* ---------------------------------------------------- core callbacks */

static void cb_nmt_state(void *ctx, co_node_t *node, co_nmt_state_t state)
{
    dnode_t *d = (dnode_t *)ctx;

    (void)node;
    log_line(d->tag, CO_LX_INFO, "NMT %s", state_name(state));
}

/* "node 5 (generic-301)", "node - (generic-301)" while unconfigured. */
static void set_tag(dnode_t *d, uint8_t id)
{
    if (id == CO_NODE_ID_UNCONFIGURED) {
        (void)snprintf(d->tag, sizeof d->tag, "node - (%s)", d->dev->name);
    } else {
        (void)snprintf(d->tag, sizeof d->tag, "node %u (%s)", (unsigned)id, d->dev->name);
    }
}

/* The instance's serial number (a RAM value a node reset sets back to the
 * description's default). */
static void set_serial(dnode_t *d, co_node_t *node)
{
    uint8_t b[4];

    co_put_u32(b, d->serial); /* co_od_write takes wire bytes */
    if (d->serial_given && (co_od_write(node, 0x1018U, 4U, b, 4U, true) != CO_OK)) {
        log_line(d->tag, CO_LX_WARN, "--serial: 0x1018 sub 4 of %s cannot be set",
                 d->dev->name);
    }
}

static void cb_nmt_reset(void *ctx, co_node_t *node, co_reset_t kind)
{
    dnode_t *d = (dnode_t *)ctx;

    if (co_node_id(node) != CO_NODE_ID_UNCONFIGURED) {
        set_tag(d, co_node_id(node)); /* LSS may have given it another */
    }
    if (kind == CO_RESET_NODE) {
        set_serial(d, node);
    }

    log_line(d->tag, CO_LX_INFO, "NMT reset %s",
             (kind == CO_RESET_NODE) ? "node" : "communication");
}

static void cb_hb_event(void *ctx, co_node_t *node, co_hb_event_t ev, uint8_t id,
                        co_nmt_state_t state)
{
    static const char *const names[] = {"heartbeat started", "heartbeat timeout",
                                        "heartbeat recovered", "heartbeat state",
                                        "life guarding lost", "life guarding recovered"};
    dnode_t *d = (dnode_t *)ctx;

    (void)node;
    log_line(d->tag, (ev == CO_HB_TIMEOUT || ev == CO_GUARD_LOST) ? CO_LX_WARN : CO_LX_INFO,
             "%s (producer %u, %s)", names[(unsigned)ev % 6U], (unsigned)id, state_name(state));
}

static uint32_t tick(void *ctx, co_node_t *node, uint32_t now_us)
{
    dnode_t *d = (dnode_t *)ctx;

    (void)node;
    return co_device_process(&d->run, now_us);
}

/* ---------------------------------------------------- start and stop */

static void can_failure(const char *iface, co_lx_can_fail_t why)
{
    switch (why) {
    case CO_LX_CAN_NO_IFACE:
        (void)fprintf(stderr,
                      PROG ": interface %s not found; create it with: "
                      "ip link add dev %s type vcan; ip link set up %s\n",
                      iface, iface, iface);
        break;
    case CO_LX_CAN_DOWN:
        (void)fprintf(stderr, PROG ": interface %s is down; bring it up with: ip link set up %s\n",
                      iface, iface);
        break;
    case CO_LX_CAN_NO_SUPPORT:
        (void)fprintf(stderr,
                      PROG ": cannot open %s: this kernel has no SocketCAN support "
                      "(run it where CAN is available, e.g. through tools/vcan-run)\n",
                      iface);
        break;
    case CO_LX_CAN_NOT_CAN:
        (void)fprintf(stderr, PROG ": %s is not a CAN interface\n", iface);
        break;
    default:
        (void)fprintf(stderr, PROG ": cannot open %s: %s\n", iface, strerror(errno));
        break;
    }
}

static int start_node(dnode_t *d, const opt_node_t *spec, const char *iface)
{
    co_node_config_t cfg;
    co_node_callbacks_t app;
    co_lx_can_fail_t why = CO_LX_CAN_OK;
    char err[256];
    co_result_t e;

    size_t mem_size;

    d->dev = (spec->eds != NULL) ? &d->eds.entry : co_device_find(spec->device);
    d->id = spec->id;
    d->serial = spec->serial;
    d->serial_given = spec->serial_given;
    set_tag(d, spec->id);
    mem_size = co_device_mem_size(d->dev, true);
    {
        /* the RAM image, and after it the PDO states and the hook table */
        uint32_t size = co_dev_storage_size(d->dev->dev);
        d->ram = calloc(1U, (size != 0U) ? size : 1U);
    }
    d->mem = calloc(1U, (mem_size != 0U) ? mem_size : 1U);
    if ((d->ram == NULL) || (d->mem == NULL)) {
        log_line(d->tag, CO_LX_ERROR, "out of memory");
        return -1;
    }
    if (spec->storage != NULL) {
        /* sized to what the node's storage needs (two banks) */
        if (co_lx_nv_open(&d->nv, spec->storage, co_store_nv_size(d->dev->dev), err,
                          sizeof err) != 0) {
            (void)fprintf(stderr, PROG ": %s\n", err);
            return -1;
        }
        d->has_nv = 1;
    }
    d->port.log = port_log;
    d->port.log_ctx = d->tag;
    if (co_lx_port_open(&d->port, iface, d->has_nv ? &d->nv : NULL, &why) != 0) {
        can_failure(iface, why);
        return -1;
    }
    (void)memset(&cfg, 0, sizeof cfg);
    cfg.dev = d->dev->dev;
    cfg.hal = co_lx_port_hal(&d->port);
    cfg.node_id = spec->id;
    cfg.ram = d->ram;
    (void)memset(&app, 0, sizeof app);
    app.ctx = d;
    app.nmt_state = cb_nmt_state;
    app.nmt_reset = cb_nmt_reset;
    app.hb_event = cb_hb_event;
    /* the device's instances first, then the daemon's own callbacks (logging) */
    if (co_device_init(&d->run, d->dev, d->mem, mem_size, NULL, &app, co_lx_now_us()) !=
        CO_OK) {
        log_line(d->tag, CO_LX_ERROR, "device failed to prepare");
        return -1;
    }
    cfg.cb = co_device_callbacks(&d->run);
    e = co_node_init(&d->node, &cfg, co_lx_now_us());
    if (e != CO_RESULT_OK) {
        log_line(d->tag, CO_LX_ERROR, "co_node_init failed: result %d", (int)e);
        return -1;
    }
    set_tag(d, co_node_id(&d->node)); /* an LSS-stored node-ID */
    set_serial(d, &d->node);
    co_lx_port_attach(&d->port, &d->node);
    {
        co_err_t ae = co_device_attach(&d->run, &d->node, co_lx_now_us());
        if (ae != CO_OK) {
            log_line(d->tag, CO_LX_ERROR, "device failed to start: 0x%08lX", (unsigned long)ae);
            return -1;
        }
    }
    log_line(d->tag, CO_LX_INFO, "up on %s%s%s", iface, d->has_nv ? ", parameters in " : "",
             d->has_nv ? spec->storage : "");
    if (co_node_id(&d->node) == CO_NODE_ID_UNCONFIGURED) {
        uint32_t sn = 0U;
        uint32_t len = 0U;
        (void)co_od_read(&d->node, 0x1018U, 4U, &sn, 4U, &len);
        log_line(d->tag, CO_LX_INFO, "unconfigured: waiting for LSS (serial number %lu)",
                 (unsigned long)sn);
    }
    return 0;
}

static void stop_node(dnode_t *d)
{
    co_lx_port_close(&d->port);
    if (d->has_nv) {
        co_lx_nv_close(&d->nv);
    }
    free(d->ram);
    free(d->mem);
    dev_eds_close(&d->eds);
}

/* ---------------------------------------------------- control interface */

static int is_signed(uint8_t type)
{
    return ((type >= (uint8_t)CO_INTEGER8) && (type <= (uint8_t)CO_INTEGER32)) ||
           ((type >= (uint8_t)CO_INTEGER24) && (type <= (uint8_t)CO_INTEGER64) &&
            (type != (uint8_t)CO_REAL64));
}

static void ctl_get(dnode_t *d, const ctl_cmd_t *cmd, char *reply, size_t cap)
{
    const co_dev_t *dev = d->node.dev;
    const co_od_entry_t *e = co_od_find(dev->od, dev->od_count, cmd->index);
    co_od_sub_t sub_buf;
    const co_od_sub_t *sd = (e != NULL) ? co_od_find_sub(dev, e, cmd->sub, &sub_buf) : NULL;
    uint8_t b[64];
    uint32_t len = 0U;
    co_err_t err = co_od_read(&d->node, cmd->index, cmd->sub, b, sizeof b, &len);

    if (err != CO_OK) {
        (void)snprintf(reply, cap, "error 0x%08lX", (unsigned long)err);
    } else if ((sd != NULL) && ((sd->type == (uint8_t)CO_VISIBLE_STRING) || (len > 8U))) {
        (void)snprintf(reply, cap, "ok %.*s", (int)len, (const char *)b);
    } else {
        uint64_t u = 0U;
        for (uint32_t k = 0U; k < len; k++) {
            u |= (uint64_t)b[k] << (8U * k);
        }
        if ((sd != NULL) && is_signed(sd->type) && (len > 0U) && (len < 8U) &&
            ((b[len - 1U] & 0x80U) != 0U)) {
            u |= ~(uint64_t)0U << (8U * len); /* sign-extend */
        }
        if ((sd != NULL) && is_signed(sd->type)) {
            (void)snprintf(reply, cap, "ok %lld", (long long)(int64_t)u);
        } else {
            (void)snprintf(reply, cap, "ok %llu", (unsigned long long)u);
        }
    }
}

/* Fault injection through the stack's and the port's public interfaces. */
static void ctl_fault(dnode_t *d, const ctl_cmd_t *cmd, char *reply, size_t cap)
{
    uint32_t now = co_lx_now_us();

    (void)snprintf(reply, cap, "ok");
    switch (cmd->op) {
    case CTL_EMCY_RAISE:
        co_emcy_raise(&d->node, cmd->code, cmd->reg, cmd->has_mfr ? cmd->mfr : NULL);
        log_line(d->tag, CO_LX_INFO, "control: EMCY 0x%04X raised", (unsigned)cmd->code);
        break;
    case CTL_EMCY_CLEAR:
        if (!co_emcy_is_active(&d->node, cmd->code)) {
            (void)snprintf(reply, cap, "error 0x%04X is not active", (unsigned)cmd->code);
        } else {
            co_emcy_clear(&d->node, cmd->code);
            log_line(d->tag, CO_LX_INFO, "control: EMCY 0x%04X cleared", (unsigned)cmd->code);
        }
        break;
    case CTL_HB_STOP:
    case CTL_HB_RESUME:
        co_node_hb_mute(&d->node, cmd->op == CTL_HB_STOP, now);
        log_line(d->tag, CO_LX_INFO, "control: heartbeats %s",
                 (cmd->op == CTL_HB_STOP) ? "stopped" : "resumed");
        break;
    default: /* CTL_OFFBUS */
        co_lx_port_off_bus(&d->port, cmd->ms, now);
        break;
    }
}

static void ctl_exec(void *ctx, const ctl_cmd_t *cmd, char *reply, size_t cap)
{
    const ctl_nodes_t *c = (const ctl_nodes_t *)ctx;
    dnode_t *d = NULL;

    for (size_t i = 0U; (i < c->n) && (d == NULL); i++) {
        if ((cmd->node_id < 0) || (c->nodes[i].id == (uint8_t)cmd->node_id)) {
            d = &c->nodes[i];
        }
    }
    if (cmd->op == CTL_HELP) {
        (void)snprintf(reply, cap,
                       "ok [@ID] set INDEX SUB VALUE | [@ID] get INDEX SUB | "
                       "[@ID] emcy CODE [REG [B0 B1 B2 B3 B4]] | [@ID] emcy clear CODE | "
                       "[@ID] heartbeat stop|resume | [@ID] offbus MS | nodes | help");
    } else if (cmd->op == CTL_NODES) {
        size_t at = (size_t)snprintf(reply, cap, "ok");
        for (size_t i = 0U; (i < c->n) && (at < cap); i++) {
            at += (size_t)snprintf(&reply[at], cap - at, " %u:%s", (unsigned)c->nodes[i].id,
                                   c->nodes[i].dev->name);
        }
    } else if (d == NULL) {
        (void)snprintf(reply, cap, "error no node %d", cmd->node_id);
    } else if (cmd->op == CTL_GET) {
        ctl_get(d, cmd, reply, cap);
    } else if (cmd->op != CTL_SET) {
        ctl_fault(d, cmd, reply, cap);
    } else {
        co_err_t err = co_device_set(&d->run, cmd->index, cmd->sub, cmd->value);
        if (err == CO_OK) {
            log_line(d->tag, CO_LX_DEBUG, "control: set 0x%04X %u %lld", (unsigned)cmd->index,
                     (unsigned)cmd->sub, (long long)cmd->value);
            (void)snprintf(reply, cap, "ok");
        } else {
            (void)snprintf(reply, cap, "error 0x%08lX", (unsigned long)err);
        }
    }
}

/* The nodes' EDS/DCF files, loaded before anything starts: a bad one is a
 * usage error (one line naming file, line and entry; exit status 2). */
static int load_eds(dnode_t *nodes, const options_t *o)
{
    char err[320];

    for (size_t i = 0U; i < o->n_nodes; i++) {
        if (o->nodes[i].eds == NULL) {
            continue;
        }
        if (dev_eds_open(&nodes[i].eds, o->nodes[i].eds, err, sizeof err) != 0) {
            (void)fprintf(stderr, PROG ": %s\n", err);
            return 2;
        }
        {
            const char *w = eds_warnings(nodes[i].eds.eds);
            while (*w != '\0') {
                const char *eol = strchr(w, '\n');
                int n = (eol != NULL) ? (int)(eol - w) : (int)strlen(w);
                log_line(NULL, CO_LX_WARN, "%.*s", n, w);
                w += n + ((eol != NULL) ? 1 : 0);
            }
        }
        log_line(NULL, CO_LX_INFO, "%s: %s", o->nodes[i].eds, eds_summary(nodes[i].eds.eds));
    }
    return 0;
}

static int export_eds(const options_t *o)
{
    dev_eds_t loaded;
    const co_device_t *dev;
    size_t len;
    char err[320];
    int rc = 0;

    (void)memset(&loaded, 0, sizeof loaded);
    if (o->nodes[0].eds != NULL) {
        if (dev_eds_open(&loaded, o->nodes[0].eds, err, sizeof err) != 0) {
            (void)fprintf(stderr, PROG ": %s\n", err);
            return 2;
        }
        dev = &loaded.entry;
    } else {
        dev = co_device_find(o->nodes[0].device);
    }
    len = strlen((const char *)dev->eds);
    int to_stdout = (strcmp(o->export_path, "-") == 0);
    FILE *f = to_stdout ? stdout : fopen(o->export_path, "w");

    if (f == NULL) {
        (void)fprintf(stderr, PROG ": %s: %s\n", o->export_path, strerror(errno));
        rc = 1;
    } else if ((fwrite(dev->eds, 1U, len, f) != len) | (to_stdout ? fflush(f) : fclose(f))) {
        (void)fprintf(stderr, PROG ": %s: write failed\n", o->export_path);
        rc = 1;
    } else {
        /* written */
    }
    dev_eds_close(&loaded);
    return rc;
}

static int run(const options_t *o)
{
    struct sigaction sa;
    sigset_t block;
    sigset_t old;
    co_lx_tracer_t tracer;
    co_lx_member_t *members;
    dnode_t *nodes;
    co_lx_loop_t loop;
    ctl_t ctl;
    ctl_nodes_t ctl_nodes;
    FILE *trace_out = NULL;
    size_t started = 0U;
    int rc = 0;

    (void)memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    (void)sigemptyset(&sa.sa_mask);
    (void)sigaction(SIGTERM, &sa, NULL);
    (void)sigaction(SIGINT, &sa, NULL);
    sa.sa_handler = SIG_IGN;
    (void)sigaction(SIGPIPE, &sa, NULL);
    (void)sigemptyset(&block);
    (void)sigaddset(&block, SIGTERM);
    (void)sigaddset(&block, SIGINT);
    (void)sigprocmask(SIG_BLOCK, &block, &old);

    tracer.fd = -1;
    tracer.out = NULL;
    ctl.lfd = -1;
    nodes = (dnode_t *)calloc(o->n_nodes, sizeof *nodes);
    members = (co_lx_member_t *)calloc(o->n_nodes, sizeof *members);
    if ((nodes == NULL) || (members == NULL)) {
        (void)fprintf(stderr, PROG ": out of memory\n");
        free(nodes);
        free(members);
        return 1;
    }
    rc = load_eds(nodes, o);
    if (rc != 0) {
        for (size_t i = 0U; i < o->n_nodes; i++) {
            dev_eds_close(&nodes[i].eds);
        }
        free(nodes);
        free(members);
        return rc;
    }
    if (o->trace != NULL) {
        co_lx_can_fail_t why = CO_LX_CAN_OK;
        trace_out = (strcmp(o->trace, "-") == 0) ? stdout : fopen(o->trace, "w");
        if (trace_out == NULL) {
            (void)fprintf(stderr, PROG ": %s: %s\n", o->trace, strerror(errno));
            rc = 1;
        } else if (co_lx_tracer_open(&tracer, o->iface, trace_out, &why) != 0) {
            can_failure(o->iface, why);
            rc = 1;
        } else {
            /* tracing from before the first boot-up */
        }
    }
    for (size_t i = 0U; (rc == 0) && (i < o->n_nodes); i++) {
        rc = (start_node(&nodes[i], &o->nodes[i], o->iface) == 0) ? 0 : 1;
        members[i].port = &nodes[i].port;
        members[i].node = &nodes[i].node;
        members[i].tick = tick;
        members[i].tick_ctx = &nodes[i];
        started = i + 1U;
    }
    if ((rc == 0) && (o->control != NULL)) {
        char err[160];
        ctl_nodes.nodes = nodes;
        ctl_nodes.n = o->n_nodes;
        if (ctl_open(&ctl, o->control, ctl_exec, &ctl_nodes, err, sizeof err) != 0) {
            (void)fprintf(stderr, PROG ": --control %s\n", err);
            rc = 1;
        }
    }
    if (rc == 0) {
        (void)memset(&loop, 0, sizeof loop);
        if (ctl.lfd >= 0) {
            loop.extra_fds = ctl_fds;
            loop.extra_ready = ctl_ready;
            loop.extra_ctx = &ctl;
        }
        loop.members = members;
        loop.n_members = o->n_nodes;
        loop.tracers = &tracer;
        loop.n_tracers = (tracer.fd >= 0) ? 1U : 0U;
        loop.stop = &stop_flag;
        loop.sleep_mask = &old;
        loop.log = port_log;
        loop.log_ctx = NULL;
        rc = (co_lx_loop_run(&loop) == 0) ? 0 : 1;
        log_line(NULL, CO_LX_INFO, "%s after %llu loop rounds", rc == 0 ? "stopped" : "failed",
                 (unsigned long long)loop.rounds);
    }
    if (ctl.lfd >= 0) {
        ctl_close(&ctl);
    }
    for (size_t i = 0U; i < started; i++) {
        stop_node(&nodes[i]);
    }
    co_lx_tracer_close(&tracer);
    if ((trace_out != NULL) && (trace_out != stdout)) {
        (void)fclose(trace_out);
    }
    free(nodes);
    free(members);
    return rc;
}

/* One line of --list-devices: name, LSS column (LSS, LSS-only or -), summary. */
static void list_device(const co_device_t *d)
{
    const co_lss_settings_t *ls = &d->dev->set.lss;
    const char *lss = (ls->node_id == CO_LSS_ID_ONLY) ? "LSS-only" : (ls->slave != 0U) ? "LSS" : "-";

    (void)printf("%-22s %-8s %s\n", d->name, lss, d->summary);
}

int main(int argc, char **argv)
{
    options_t *o = (options_t *)calloc(1U, sizeof *o);
    char err[256];
    int rc = 0;

    if (o == NULL) {
        return 1;
    }
    if (options_parse(o, argc, argv, err, sizeof err) != 0) {
        (void)fprintf(stderr, PROG ": %s\n", err);
        free(o);
        return 2;
    }
    log_level = o->log_level;
    switch (o->mode) {
    case OPT_HELP:
        (void)fputs(options_usage, stdout);
        break;
    case OPT_VERSION:
        (void)printf(PROG " %s\n", CO_VERSION);
        break;
    case OPT_LIST:
        /* the default device first, then the others in name order */
        list_device(co_device_find(OPT_DEFAULT_DEVICE));
        for (size_t i = 0U; i < co_device_count(); i++) {
            if (strcmp(co_device_at(i)->name, OPT_DEFAULT_DEVICE) != 0) {
                list_device(co_device_at(i));
            }
        }
        break;
    case OPT_EXPORT_EDS:
        rc = export_eds(o);
        break;
    default:
        rc = run(o);
        break;
    }
    free(o);
    return rc;
}
