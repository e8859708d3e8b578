/*
 * od_dump: initialise one node of a generated device and print its whole
 * dictionary as JSON, every value read through co_od_read (the path SDO and
 * the application use). tests/gen/test_eds_matches_c.py compares this with
 * the device's EDS.
 *
 * Usage: od_dump_<device> [node-id]   (default 5)
 * Built once per device with -DCODEV_NAME=<cname>: it uses the generated
 * header, the node bundle <cname>_node_t and <cname>_config() as an
 * application would.
 */
#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "co/co_node.h"

#ifndef CODEV_NAME
#error "build with -DCODEV_NAME=<cname>"
#endif
#define STR(x) #x
#define XSTR(x) STR(x)
#define CAT(a, b) a##b
#define XCAT(a, b) CAT(a, b)

#include XSTR(CODEV_NAME.h)

typedef XCAT(CODEV_NAME, _node_t) dump_node_t;

/* The core finds object @p index (sub 0) at @p off of the RAM image, its
 * place (co_node.h: CO_RAM_*). */
static int at_place(co_node_t *node, uint16_t index, uint32_t off)
{
    const uint8_t *v = (const uint8_t *)co_od_value_ptr(node, index, 0U);
    return (v != NULL) && (v == &node->ram[off]);
}

static unsigned frames_sent;
static uint32_t first_id;

static int count_send(void *ctx, const co_frame_t *f)
{
    (void)ctx;
    if (frames_sent == 0U) {
        first_id = f->id;
    }
    frames_sent++;
    return 0;
}

/* Erased NV memory, so 0x1010/0x1011 read what a device with storage reads
 * (the EDS describes that device) and nothing stored changes a default. */
static uint8_t nv[8192];

static int nv_read(void *ctx, uint32_t addr, uint8_t *buf, uint32_t len)
{
    (void)ctx;
    if ((addr > sizeof nv) || (len > sizeof nv - addr)) {
        return -1;
    }
    memcpy(buf, &nv[addr], len);
    return 0;
}

static int nv_write(void *ctx, uint32_t addr, const uint8_t *buf, uint32_t len)
{
    (void)ctx;
    if ((addr > sizeof nv) || (len > sizeof nv - addr)) {
        return -1;
    }
    memcpy(&nv[addr], buf, len);
    return 0;
}

static const co_hal_ops_t ops = {.send = count_send, .nv_read = nv_read, .nv_write = nv_write};

static void hex(const uint8_t *p, uint32_t n)
{
    putchar('"');
    for (uint32_t i = 0U; i < n; i++) {
        printf("%02x", p[i]);
    }
    putchar('"');
}

/* The depth of 0x1003 (the EMCY service looks it up when an error comes):
 * its entries 1.. as far as they go. */
static unsigned hist_depth(const co_dev_t *dev)
{
    const co_od_entry_t *e = co_od_find(dev->od, dev->od_count, 0x1003U);
    co_od_sub_t buf;
    unsigned n = 0U;

    while ((e != NULL) && (n < 254U) && (co_od_find_sub(dev, e, (uint8_t)(n + 1U), &buf) != NULL)) {
        n++;
    }
    return n;
}

int main(int argc, char **argv)
{
    static uint8_t buf[70000];
    static dump_node_t n;
    const co_dev_t *dev = &XCAT(CODEV_NAME, _dev);
    co_node_t *node = &n.node;
    co_node_config_t cfg;
    unsigned long id = (argc > 1) ? strtoul(argv[1], NULL, 0) : 5UL;
    co_result_t res;
    int guard_time = 0;
    int life_factor = 0;
    co_err_t err;

    if ((id < 1UL) || (id > 127UL)) {
        fprintf(stderr, "od_dump: bad node-id\n");
        return 2;
    }
    /* (the image, then the PDO states and the hook table) */
    if (sizeof n.ram < co_dev_storage_size(dev)) {
        fprintf(stderr, "od_dump: node bundle does not fit the device\n");
        return 1;
    }
    if (co_store_nv_size(dev) > sizeof nv) {
        fprintf(stderr, "od_dump: NV too small\n");
        return 1;
    }
    memset(nv, 0xFF, sizeof nv);
    XCAT(CODEV_NAME, _config)(&n, &cfg);
    if ((cfg.dev != dev) || (cfg.ram != (void *)&n.ram)) {
        fprintf(stderr, "od_dump: config helper\n");
        return 1;
    }
    cfg.hal.ops = &ops;
    cfg.node_id = (uint8_t)id;
    res = co_node_init(node, &cfg, 0U);
    if (res != CO_RESULT_OK) {
        fprintf(stderr, "od_dump: co_node_init: %d\n", (int)res);
        return 1;
    }
    if ((co_node_id(node) == CO_NODE_ID_UNCONFIGURED) &&
        (co_node_set_id(node, (uint8_t)id, 0U) != CO_OK)) {
        /* an LSS-only device (FAULHABER) starts unconfigured: give it the ID */
        fprintf(stderr, "od_dump: co_node_set_id\n");
        return 1;
    }
    printf("{\"name\": \"%s\", \"node_id\": %lu, \"ram_size\": %u, \"comm_end\": %u, "
           "\"app_end\": %u, \"n_hooks\": %u,\n",
           XSTR(CODEV_NAME), id, (unsigned)dev->ram_size, (unsigned)dev->comm_end,
           (unsigned)dev->app_end, (unsigned)dev->n_hooks);
    /* (a core without guarding refuses a device with 0x100C / 0x100D) */
#if CO_NODE_GUARDING
    guard_time = node->errctl.guard_time != NULL;
    life_factor = node->errctl.life_factor != NULL;
#endif
    /* the personality (co_settings.h), one part per service */
    printf(" \"set\": {\"nmt\": {\"bootup\": %u, \"boot_emcy\": %u, \"guarding_with_hb\": %u, "
           "\"guarding_hb_exclusive\": %u}, \"sdo\": {\"refused\": %u, \"unknown_object\": %u, "
           "\"read_only\": %u}, \"emcy\": {\"reset\": %u, \"state_pair\": %u, "
           "\"generic_bit\": %u, \"history\": %u}, \"lss\": {\"slave\": %u}},\n",
           dev->set.nmt.bootup, dev->set.nmt.boot_emcy, dev->set.nmt.guarding_with_hb,
           dev->set.nmt.guarding_hb_exclusive, dev->set.sdo.refused, dev->set.sdo.unknown_object,
           dev->set.sdo.read_only, dev->set.emcy.reset, dev->set.emcy.state_pair,
           dev->set.emcy.generic_bit, dev->set.emcy.history, dev->set.lss.slave);
    printf(" \"core\": {\"errreg\": %d, \"hist_depth\": %u, \"n_hb_cons\": %u, "
           "\"emcy_cob\": %d, \"hb_prod\": %d, \"guard_time\": %d, \"life_factor\": %d, "
           "\"emcy_inhibit\": %d, \"frames\": %u, \"first_id\": %lu, \"nmt\": %u},\n",
           at_place(node, 0x1001U, (uint32_t)dev->app_end + CO_RAM_END_1001),
           hist_depth(dev), (unsigned)node->n_hb_cons,
           at_place(node, 0x1014U, CO_RAM_1014), at_place(node, 0x1017U, CO_RAM_1017), guard_time,
           life_factor, at_place(node, 0x1015U, CO_RAM_1015), frames_sent,
           (unsigned long)first_id, (unsigned)co_node_nmt_state(node));
    printf(" \"entries\": [\n");
    for (uint16_t i = 0U; i < dev->od_count; i++) {
        const co_od_entry_t *e = &dev->od[i];
        printf("  {\"index\": %u, \"code\": %u, \"hook\": %u, \"subs\": [\n", (unsigned)e->index,
               (unsigned)co_od_code(e), co_od_hooked(e) ? (unsigned)e->base + 1U : 0U);
        uint32_t n_subs = 0U;
        uint32_t done = 0U;
        for (uint32_t k = 0U; k < 256U; k++) {
            co_od_sub_t sd;
            n_subs += (co_od_find_sub(dev, e, (uint8_t)k, &sd) != NULL) ? 1U : 0U;
        }
        /* every sub-index the entry has (its rows, a row may be a run of
         * them, and an implicit sub-index 0) */
        for (uint32_t k = 0U; k < 256U; k++) {
          {
            co_od_sub_t sd;
            const co_od_sub_t *s = co_od_find_sub(dev, e, (uint8_t)k, &sd);
            if (s == NULL) {
                continue;
            }
            uint32_t len = 0U;
            done++;
            void *p = co_od_value_ptr(node, e->index, s->sub);
            err = co_od_read(node, e->index, s->sub, buf, (uint32_t)sizeof buf, &len);
            printf("   {\"sub\": %u, \"type\": %u, \"flags\": %u, \"size\": %u, \"abort\": %lu, "
                   "\"value\": ",
                   (unsigned)s->sub, (unsigned)s->type, (unsigned)s->flags, (unsigned)s->size,
                   (unsigned long)err);
            if (err == CO_OK) {
                hex(buf, len);
            } else {
                printf("null");
            }
            /* the stored bytes (native order), also where a read is refused */
            printf(", \"ram\": ");
            if (p != NULL) {
                hex((const uint8_t *)p, s->size);
            } else {
                printf("null");
            }
#if CO_LIMITS
            if ((s->flags & CO_SUB_LIMIT) != 0U) {
                printf(", \"limit\": [%" PRId64 ", %" PRId64 "]", dev->limits[s->limit].min,
                       dev->limits[s->limit].max);
            }
#endif
            printf("}%s\n", (done < n_subs) ? "," : "");
          }
        }
        printf("  ]}%s\n", (i + 1U < dev->od_count) ? "," : "");
    }
    printf(" ]}\n");
    return 0;
}
