/*
 * sensor_demo: the example device of an outside project, run on an
 * in-memory bus. It checks what a master would see and exits 0 when all of it
 * is right (run by tools/run-tests for both examples):
 *   boot-up 0x710 00, the vendor-ID over SDO (0x1018 sub 1), a set-point
 *   write inside and outside its limits (0x6001: 0..1000), and TPDO1 with the
 *   temperature after a SYNC in Operational.
 */
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "co/co_node.h"
#include "sensor.h"

#define NODE_ID 0x10U

typedef struct bus {
    co_frame_t sent[8];
    unsigned n;
} bus_t;

static int bus_send(void *ctx, const co_frame_t *f)
{
    bus_t *b = ctx;
    if (b->n < 8U) {
        b->sent[b->n] = *f;
    }
    b->n++;
    return 0;
}

static const co_hal_ops_t bus_ops = {.send = bus_send};

static int failures;

/* the node's answer to one frame (or to nothing), compared with @p want */
static void expect(sensor_node_t *s, bus_t *b, const co_frame_t *in, uint32_t want_id,
                   const uint8_t *want, uint8_t want_len, const char *what)
{
    b->n = 0U;
    if (in != NULL) {
        co_node_rx(&s->node, in, 1000U);
    }
    (void)co_node_process(&s->node, 1000U);
    const co_frame_t *f = &b->sent[0];
    int ok = b->n == 1U && f->id == want_id && f->dlc == want_len &&
             memcmp(f->data, want, want_len) == 0;
    printf("%-44s %s", what, ok ? "ok  " : "FAIL");
    if (b->n > 0U) {
        printf("  %03X", (unsigned)f->id);
        for (uint8_t k = 0U; k < f->dlc; k++) {
            printf(" %02X", f->data[k]);
        }
    }
    printf("\n");
    failures += ok ? 0 : 1;
}

static co_frame_t frame(uint32_t id, uint8_t len, const uint8_t *data)
{
    co_frame_t f;
    memset(&f, 0, sizeof f);
    f.id = id;
    f.dlc = len;
    memcpy(f.data, data, len);
    return f;
}

int main(void)
{
    static sensor_node_t s;
    bus_t b = {0};
    co_node_config_t cfg;

    sensor_config(&s, &cfg);
    cfg.hal.ops = &bus_ops;
    cfg.hal.ctx = &b;
    cfg.node_id = NODE_ID;
    if (co_node_init(&s.node, &cfg, 0U) != CO_RESULT_OK || b.n != 1U || b.sent[0].id != 0x710U) {
        printf("boot-up                                      FAIL\n");
        return 1;
    }
    printf("boot-up 710 00                               ok\n");

    static const uint8_t up_1018[8] = {0x40, 0x18, 0x10, 0x01, 0, 0, 0, 0};
    static const uint8_t vendor[8] = {0x43, 0x18, 0x10, 0x01, 0x34, 0x12, 0x00, 0x00};
    co_frame_t f = frame(0x610U, 8U, up_1018);
    expect(&s, &b, &f, 0x590U, vendor, 8U, "SDO upload 0x1018:01 (vendor-ID)");

    static const uint8_t dn_ok[8] = {0x2B, 0x01, 0x60, 0x00, 0xE8, 0x03, 0, 0};
    static const uint8_t dn_ack[8] = {0x60, 0x01, 0x60, 0x00, 0, 0, 0, 0};
    f = frame(0x610U, 8U, dn_ok);
    expect(&s, &b, &f, 0x590U, dn_ack, 8U, "SDO download 0x6001 = 1000");

    static const uint8_t dn_high[8] = {0x2B, 0x01, 0x60, 0x00, 0xE9, 0x03, 0, 0};
    static const uint8_t abort_high[8] = {0x80, 0x01, 0x60, 0x00, 0x31, 0x00, 0x09, 0x06};
    f = frame(0x610U, 8U, dn_high);
    expect(&s, &b, &f, 0x590U, abort_high, 8U, "SDO download 0x6001 = 1001 (too high)");

    /* the application sets the temperature; Operational; SYNC: TPDO1 */
    static const uint8_t t_215[2] = {0xD7, 0x00}; /* 215 = 21.5 degC, little-endian */
    if (co_od_write(&s.node, 0x6000U, 0U, t_215, 2U, true) != CO_OK) {
        failures++;
    }
    static const uint8_t start[2] = {0x01, NODE_ID};
    f = frame(0x000U, 2U, start);
    co_node_rx(&s.node, &f, 1000U);
    f = frame(0x080U, 0U, t_215);
    expect(&s, &b, &f, 0x190U, t_215, 2U, "SYNC -> TPDO1 temperature 21.5 degC");

    printf("%s\n", failures == 0 ? "sensor_demo: all ok" : "sensor_demo: FAILED");
    return failures == 0 ? 0 : 1;
}
