/*
 * The Linux port without a CAN bus: a datagram socketpair stands in for the
 * raw CAN socket (same one-frame-per-datagram semantics), so the HAL's send,
 * the TX-full hold-back and retry, receive into the node and error frames to
 * EMCY run natively. Also: the error-frame table, the candump -L trace
 * format, the file-backed non-volatile memory and the loop's sleep time.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include <errno.h>
#include <fcntl.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include <linux/can.h>
#include <linux/can/error.h>

#include "co_lx/canerr.h"
#include "co_lx/clock.h"
#include "co_lx/loop.h"
#include "co_lx/nvfile.h"
#include "co_lx/port.h"
#include "co_lx/trace.h"
#include "test_dev.h"
#include "test_frames.h"

/* ------------------------------------------------------------ helpers */

typedef struct fx {
    int sv[2];           /* sv[0]: the port's "socket", sv[1]: the bus side */
    co_lx_port_t port;
    td_node_t n;
} fx_t;

static fx_t fx;

static void make_pair(int sndbuf)
{
    assert_int_equal(socketpair(AF_UNIX, SOCK_DGRAM | SOCK_NONBLOCK, 0, fx.sv), 0);
    if (sndbuf > 0) {
        assert_int_equal(setsockopt(fx.sv[0], SOL_SOCKET, SO_SNDBUF, &sndbuf, sizeof sndbuf), 0);
    }
}

static void start_node(uint8_t id)
{
    co_node_config_t cfg;

    memset(&fx.port, 0, sizeof fx.port);
    fx.port.fd = fx.sv[0];
    (void)snprintf(fx.port.iface, sizeof fx.port.iface, "%s", "test0");
    memset(&fx.n, 0, sizeof fx.n);
    memset(&cfg, 0, sizeof cfg);
    cfg.dev = &td_dev;
    cfg.hal = co_lx_port_hal(&fx.port);
    cfg.node_id = id;
    cfg.ram = &fx.n.ram;
    assert_int_equal(co_node_init(&fx.n.node, &cfg, 1000U), CO_RESULT_OK);
    co_lx_port_attach(&fx.port, &fx.n.node);
}

/* the next frame on the bus side, formatted; "" when none */
static const char *bus_next(char *buf, size_t cap)
{
    struct can_frame cf;
    co_frame_t f;
    ssize_t n = read(fx.sv[1], &cf, sizeof cf);

    if (n < 0) {
        assert_true((errno == EAGAIN) || (errno == EWOULDBLOCK));
        buf[0] = '\0';
        return buf;
    }
    assert_int_equal(n, sizeof cf);
    co_lx_frame_from_can(&cf, &f);
    tf_format(&f, buf, cap);
    return buf;
}

#define EXPECT_OUT(text)                                                     \
    do {                                                                     \
        char b_[64];                                                         \
        assert_string_equal(bus_next(b_, sizeof b_), (text));                \
    } while (0)

static void bus_send_raw(uint32_t can_id, const uint8_t *data, uint8_t len)
{
    struct can_frame cf;

    memset(&cf, 0, sizeof cf);
    cf.can_id = can_id;
    cf.len = len;
    if (len > 0U) {
        memcpy(cf.data, data, len);
    }
    assert_int_equal(write(fx.sv[1], &cf, sizeof cf), sizeof cf);
}

static void bus_send(const char *text)
{
    co_frame_t f = tf_parse(text);
    struct can_frame cf;

    co_lx_frame_to_can(&f, &cf);
    assert_int_equal(write(fx.sv[1], &cf, sizeof cf), sizeof cf);
}

static int teardown(void **state)
{
    (void)state;
    close(fx.sv[0]);
    close(fx.sv[1]);
    return 0;
}

/* ------------------------------------------------------------ HAL on a socket */

static void boot_up_and_sdo_over_the_socket(void **state)
{
    (void)state;
    make_pair(0);
    start_node(5);
    EXPECT_OUT("705 00");
    EXPECT_OUT("");
    bus_send("605 40 00 10 00 00 00 00 00");
    assert_int_equal(co_lx_port_rx(&fx.port, 2000U), 1);
    EXPECT_OUT("585 43 00 10 00 92 01 02 00");
    assert_int_equal(co_lx_port_rx(&fx.port, 2000U), 0); /* nothing waiting */
    /* identifier flags survive the conversion both ways */
    bus_send("705 R1");
    assert_int_equal(co_lx_port_rx(&fx.port, 2100U), 1);
    assert_int_equal(fx.port.rx_frames, 2U);
}

static void full_tx_path_holds_frames_back_and_retries(void **state)
{
    char buf[64];
    unsigned sent = 0U;
    uint32_t next;

    (void)state;
    make_pair(4096);
    start_node(5);
    EXPECT_OUT("705 00");
    /* fill the socket's send buffer until it refuses */
    {
        struct can_frame cf;
        memset(&cf, 0, sizeof cf);
        cf.can_id = 0x123U;
        while (write(fx.sv[0], &cf, sizeof cf) == (ssize_t)sizeof cf) {
            sent++;
        }
        assert_true((errno == EAGAIN) || (errno == ENOBUFS));
    }
    assert_true(sent > 0U);
    /* an SDO answer now finds the path full: refused, held back by the core */
    bus_send("605 40 18 10 01 00 00 00 00");
    assert_int_equal(co_lx_port_rx(&fx.port, 3000U), 1);
    assert_true(fx.port.tx_blocked);
    assert_true(fx.port.tx_refused >= 1U);
    /* the core asks to be called again soon (retry), timers keep their time */
    next = co_node_process(&fx.n.node, 3000U);
    assert_true(co_lx_until(next, 3000U) <= 1000);
    /* the bus drains: the held-back frame leaves on the next process */
    for (unsigned i = 0U; i < sent; i++) {
        assert_string_equal(bus_next(buf, sizeof buf), "123");
    }
    (void)co_node_process(&fx.n.node, 4000U);
    EXPECT_OUT("585 43 18 10 01 A5 00 00 00");
    assert_false(fx.port.tx_blocked);
    EXPECT_OUT("");
}

static void error_frames_become_emcy(void **state)
{
    uint8_t d[8] = {0};

    (void)state;
    make_pair(0);
    start_node(5);
    EXPECT_OUT("705 00");
    /* error passive: EMCY 0x8120, error register generic + communication */
    d[1] = CAN_ERR_CRTL_RX_PASSIVE;
    bus_send_raw(CAN_ERR_FLAG | CAN_ERR_CRTL, d, 8U);
    assert_int_equal(co_lx_port_rx(&fx.port, 5000U), 1);
    (void)co_node_process(&fx.n.node, 5000U);
    EXPECT_OUT("085 20 81 11 00 00 00 00 00");
    assert_true(co_emcy_is_active(&fx.n.node, 0x8120U));
    /* bus-off in Operational: EMCY 0x8140, and 0x1029 sub 1 = 0 (the test
     * device's default) makes it a communication error: Pre-operational */
    co_node_nmt_command(&fx.n.node, 0x01U, 5500U);
    memset(d, 0, sizeof d);
    bus_send_raw(CAN_ERR_FLAG | CAN_ERR_BUSOFF, d, 8U);
    assert_int_equal(co_lx_port_rx(&fx.port, 6000U), 1);
    (void)co_node_process(&fx.n.node, 6000U);
    EXPECT_OUT("085 40 81 11 00 00 00 00 00");
    assert_int_equal(co_node_nmt_state(&fx.n.node), CO_NMT_PRE_OPERATIONAL);
    /* restarted: both end; EMCY 0x0000 once the last one clears */
    bus_send_raw(CAN_ERR_FLAG | CAN_ERR_RESTARTED, d, 8U);
    assert_int_equal(co_lx_port_rx(&fx.port, 7000U), 1);
    (void)co_node_process(&fx.n.node, 7000U);
    EXPECT_OUT("085 00 00 00 00 00 00 00 00");
    assert_false(co_emcy_is_active(&fx.n.node, 0x8120U));
    assert_false(co_emcy_is_active(&fx.n.node, 0x8140U));
    EXPECT_OUT("");
}

/* Fault injection: off the bus for 50 ms as at bus-off. Nothing goes out
 * and nothing is received meanwhile; in Operational the node falls to
 * Pre-operational (0x1029 sub 1 = 0); back on the bus, the held frames
 * leave: EMCY 0x8140 first (lowest CAN-ID), then its EMCY 0x0000, then the
 * heartbeats that came due. */
static void off_bus_and_back_as_after_bus_off(void **state)
{
    (void)state;
    make_pair(0);
    start_node(5);
    EXPECT_OUT("705 00");
    bus_send("605 2B 17 10 00 14 00 00 00"); /* heartbeat 20 ms */
    assert_int_equal(co_lx_port_rx(&fx.port, 2000U), 1);
    EXPECT_OUT("585 60 17 10 00 00 00 00 00");
    co_node_nmt_command(&fx.n.node, 0x01U, 2000U);
    assert_int_equal(co_lx_port_process(&fx.port, 2000U), CO_NO_DEADLINE);
    co_lx_port_off_bus(&fx.port, 50U, 3000U);
    assert_true(fx.port.off_bus);
    assert_true(co_emcy_is_active(&fx.n.node, 0x8140U));
    assert_int_equal(co_node_nmt_state(&fx.n.node), CO_NMT_PRE_OPERATIONAL);
    /* an SDO request while off the bus is never seen */
    bus_send("605 40 00 10 00 00 00 00 00");
    assert_int_equal(co_lx_port_rx(&fx.port, 10000U), 1);
    assert_int_equal(fx.port.rx_frames, 1U);
    (void)co_node_process(&fx.n.node, 30000U);
    EXPECT_OUT("");
    assert_int_equal(co_lx_port_process(&fx.port, 52999U), 53000U);
    EXPECT_OUT("");
    assert_int_equal(co_lx_port_process(&fx.port, 53000U), CO_NO_DEADLINE);
    assert_false(fx.port.off_bus);
    EXPECT_OUT("085 40 81 11 00 00 00 00 00");
    EXPECT_OUT("085 00 00 00 00 00 00 00 00");
    EXPECT_OUT("705 7F");
    assert_false(co_emcy_is_active(&fx.n.node, 0x8140U));
    /* on the bus again: requests are answered (heartbeats aside) */
    bus_send("605 40 00 10 00 00 00 00 00");
    assert_int_equal(co_lx_port_rx(&fx.port, 54000U), 1);
    {
        char b[64];
        const char *f = bus_next(b, sizeof b);
        while (strcmp(f, "705 7F") == 0) {
            f = bus_next(b, sizeof b);
        }
        assert_string_equal(f, "585 43 00 10 00 92 01 02 00");
    }
}

/* ------------------------------------------------------------ error-frame table */

static void canerr_table(void **state)
{
    co_lx_canerr_t st;
    co_lx_emcy_action_t a[CO_LX_CANERR_ACTIONS_MAX];
    uint8_t d[8] = {0};

    (void)state;
    memset(&st, 0, sizeof st);
    /* not an error frame */
    assert_int_equal(co_lx_canerr_frame(&st, 0x123U, d, a), 0);
    /* controller overflow: 0x8110 once */
    d[1] = CAN_ERR_CRTL_RX_OVERFLOW;
    assert_int_equal(co_lx_canerr_frame(&st, CAN_ERR_FLAG | CAN_ERR_CRTL, d, a), 1);
    assert_int_equal(a[0].code, 0x8110U);
    assert_true(a[0].raise);
    assert_int_equal(co_lx_canerr_frame(&st, CAN_ERR_FLAG | CAN_ERR_CRTL, d, a), 0);
    /* the next frame without loss ends the overrun; a lossy one raises it */
    assert_int_equal(co_lx_canerr_rx(&st, 0U, a), 1);
    assert_int_equal(a[0].code, 0x8110U);
    assert_false(a[0].raise);
    assert_int_equal(co_lx_canerr_rx(&st, 0U, a), 0);
    assert_int_equal(co_lx_canerr_rx(&st, 3U, a), 1);
    assert_true(a[0].raise);
    /* TX passive then warning only: 0x8120 raised then cleared */
    d[1] = CAN_ERR_CRTL_TX_PASSIVE;
    assert_int_equal(co_lx_canerr_frame(&st, CAN_ERR_FLAG | CAN_ERR_CRTL, d, a), 1);
    assert_int_equal(a[0].code, 0x8120U);
    assert_true(a[0].raise);
    d[1] = CAN_ERR_CRTL_TX_WARNING;
    assert_int_equal(co_lx_canerr_frame(&st, CAN_ERR_FLAG | CAN_ERR_CRTL, d, a), 1);
    assert_int_equal(a[0].code, 0x8120U);
    assert_false(a[0].raise);
    /* bus-off, then error-active again ends it */
    d[1] = 0U;
    assert_int_equal(co_lx_canerr_frame(&st, CAN_ERR_FLAG | CAN_ERR_BUSOFF, d, a), 1);
    assert_int_equal(a[0].code, 0x8140U);
    assert_true(a[0].raise);
    d[1] = CAN_ERR_CRTL_ACTIVE;
    assert_int_equal(co_lx_canerr_frame(&st, CAN_ERR_FLAG | CAN_ERR_CRTL, d, a), 1);
    assert_int_equal(a[0].code, 0x8140U);
    assert_false(a[0].raise);
    /* passive and bus-off in one frame, then restarted clears both */
    d[1] = CAN_ERR_CRTL_RX_PASSIVE;
    assert_int_equal(co_lx_canerr_frame(&st, CAN_ERR_FLAG | CAN_ERR_CRTL | CAN_ERR_BUSOFF, d, a),
                     2);
    d[1] = 0U;
    assert_int_equal(co_lx_canerr_frame(&st, CAN_ERR_FLAG | CAN_ERR_RESTARTED, d, a), 2);
    assert_false(a[0].raise);
    assert_false(a[1].raise);
    assert_false(st.busoff || st.passive);
}

/* ------------------------------------------------------------ trace format */

static void trace_format_is_candump_log(void **state)
{
    char b[CO_LX_TRACE_LINE_MAX];
    const uint8_t sdo[8] = {0x40, 0x00, 0x10, 0x00, 0x00, 0x00, 0x00, 0x00};
    const uint8_t hb[1] = {0x7F};
    const uint8_t ab[3] = {0xAB, 0x01, 0xFF};

    (void)state;
    assert_int_not_equal(co_lx_trace_format(b, sizeof b, 1700000000, 123456U, "vcan0", 0x601U, 8U,
                                            sdo), 0U);
    assert_string_equal(b, "(1700000000.123456) vcan0 601#4000100000000000\n");
    (void)co_lx_trace_format(b, sizeof b, 5, 7U, "can1", 0x705U, 1U, hb);
    assert_string_equal(b, "(0000000005.000007) can1 705#7F\n");
    (void)co_lx_trace_format(b, sizeof b, 1, 0U, "vcan0", 0x080U, 0U, NULL);
    assert_string_equal(b, "(0000000001.000000) vcan0 080#\n");
    (void)co_lx_trace_format(b, sizeof b, 1, 0U, "vcan0", 0x705U | CAN_RTR_FLAG, 0U, NULL);
    assert_string_equal(b, "(0000000001.000000) vcan0 705#R\n");
    (void)co_lx_trace_format(b, sizeof b, 1, 0U, "vcan0", 0x705U | CAN_RTR_FLAG, 1U, NULL);
    assert_string_equal(b, "(0000000001.000000) vcan0 705#R1\n");
    (void)co_lx_trace_format(b, sizeof b, 1, 0U, "vcan0", 0x1ABCDEF0U | CAN_EFF_FLAG, 3U, ab);
    assert_string_equal(b, "(0000000001.000000) vcan0 1ABCDEF0#AB01FF\n");
    (void)co_lx_trace_format(b, sizeof b, 1, 0U, "vcan0", CAN_ERR_FLAG | CAN_ERR_BUSOFF, 8U,
                             sdo);
    assert_string_equal(b, "(0000000001.000000) vcan0 20000040#4000100000000000\n");
    /* too small a buffer: nothing */
    assert_int_equal(co_lx_trace_format(b, 10U, 1, 0U, "vcan0", 0x601U, 8U, sdo), 0U);
}

/* ------------------------------------------------------------ non-volatile memory */

static char dir[64];

static int nv_setup(void **state)
{
    (void)state;
    (void)snprintf(dir, sizeof dir, "/tmp/test_lx_nv.XXXXXX");
    assert_non_null(mkdtemp(dir));
    return 0;
}

static int nv_teardown(void **state)
{
    char cmd[128];

    (void)state;
    (void)snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    assert_int_equal(system(cmd), 0);
    return 0;
}

/* nv_poll until it is no longer busy (the writer thread's fsync and rename) */
static int nv_poll_until_done(co_lx_nv_t *nv)
{
    int r;

    for (int k = 0; k < 10000; k++) {
        r = co_lx_nv_poll(nv);
        if (r != CO_NV_BUSY) {
            return r;
        }
        (void)usleep(1000);
    }
    return r;
}

static void nv_file_round_trip(void **state)
{
    co_lx_nv_t nv;
    char path[128];
    char tmp[140];
    char err[256];
    uint8_t buf[8];
    const uint8_t data[4] = {1, 2, 3, 4};
    struct stat st;

    (void)state;
    (void)snprintf(path, sizeof path, "%s/params.bin", dir);
    (void)snprintf(tmp, sizeof tmp, "%s.tmp", path);
    assert_int_equal(co_lx_nv_open(&nv, path, 256U, err, sizeof err), 0);
    /* nothing written yet: erased, and no file */
    assert_int_equal(co_lx_nv_read(&nv, 0U, buf, 8U), 0);
    for (unsigned i = 0U; i < 8U; i++) {
        assert_int_equal(buf[i], 0xFF);
    }
    assert_int_not_equal(stat(path, &st), 0);
    /* writes change the image only; nv_poll persists it once, in the
     * background (busy until the file holds it); the temporary file is gone */
    assert_int_equal(co_lx_nv_write(&nv, 10U, data, 2U), 0);
    assert_int_equal(co_lx_nv_write(&nv, 12U, &data[2], 2U), 0);
    assert_int_not_equal(stat(path, &st), 0);
    assert_int_equal(nv_poll_until_done(&nv), 0);
    assert_int_equal(stat(path, &st), 0);
    assert_int_equal(st.st_size, 256);
    assert_int_not_equal(stat(tmp, &st), 0);
    assert_int_equal(nv.writes, 1U);
    assert_int_equal(co_lx_nv_poll(&nv), 0); /* nothing new: nothing written */
    assert_int_equal(nv.writes, 1U);
    /* outside the memory: refused */
    assert_int_equal(co_lx_nv_write(&nv, 254U, data, 4U), -1);
    assert_int_equal(co_lx_nv_read(&nv, 256U, buf, 1U), -1);
    assert_int_equal(co_lx_nv_read(&nv, 0xFFFFFFF0U, buf, 0x20U), -1);
    co_lx_nv_close(&nv);
    /* open again: the written bytes are back, the rest erased */
    assert_int_equal(co_lx_nv_open(&nv, path, 256U, err, sizeof err), 0);
    assert_int_equal(co_lx_nv_read(&nv, 9U, buf, 6U), 0);
    assert_int_equal(buf[0], 0xFF);
    assert_memory_equal(&buf[1], data, 4U);
    assert_int_equal(buf[5], 0xFF);
    co_lx_nv_close(&nv);
    /* a file larger than the memory (an older daemon's 64 KiB image): its
     * first bytes are the memory */
    assert_int_equal(co_lx_nv_open(&nv, path, 16U, err, sizeof err), 0);
    assert_int_equal(co_lx_nv_read(&nv, 10U, buf, 4U), 0);
    assert_memory_equal(buf, data, 4U);
    co_lx_nv_close(&nv);
    /* beyond 64 KiB it is no parameter file */
    assert_int_equal(truncate(path, 65537), 0);
    assert_int_equal(co_lx_nv_open(&nv, path, 16U, err, sizeof err), -1);
    assert_non_null(strstr(err, "params.bin"));
}

static void nv_write_failure_rolls_back(void **state)
{
    co_lx_nv_t nv;
    char path[128];
    char err[256];
    uint8_t buf[4];
    const uint8_t data[4] = {9, 9, 9, 9};

    (void)state;
    (void)snprintf(path, sizeof path, "%s/params.bin", dir);
    assert_int_equal(co_lx_nv_open(&nv, path, 64U, err, sizeof err), 0);
    /* the file's place is taken by a directory: the rename fails; the
     * image rolls back to what the file holds */
    assert_int_equal(mkdir(path, 0755), 0);
    assert_int_equal(co_lx_nv_write(&nv, 0U, data, 4U), 0);
    assert_int_equal(nv_poll_until_done(&nv), -1);
    assert_int_equal(co_lx_nv_read(&nv, 0U, buf, 4U), 0);
    assert_int_equal(buf[0], 0xFF);
    assert_int_equal(nv.writes, 0U);
    co_lx_nv_close(&nv);
    /* a directory that does not exist is refused at open */
    (void)snprintf(path, sizeof path, "%s/missing/params.bin", dir);
    assert_int_equal(co_lx_nv_open(&nv, path, 64U, err, sizeof err), -1);
    assert_non_null(strstr(err, "missing"));
}

/* A 0x1010 save on the port with a parameter file (issue 19 item 9): the
 * file is written once per save, sized to what the node's storage needs,
 * in the writer thread; the SDO answer comes when the file holds the set,
 * and the node is served meanwhile (co_node_process runs, frames are
 * answered). */
static void save_writes_the_file_once(void **state)
{
    co_lx_nv_t nv;
    co_node_config_t cfg;
    char path[128];
    char err[256];
    char out[64];
    struct stat st;
    uint32_t now = 2000U;
    unsigned rounds = 0U;

    (void)state;
    (void)snprintf(path, sizeof path, "%s/params.bin", dir);
    assert_int_equal(co_lx_nv_open(&nv, path, co_store_nv_size(&td_dev), err, sizeof err), 0);
    make_pair(0);
    memset(&fx.port, 0, sizeof fx.port);
    fx.port.fd = fx.sv[0];
    fx.port.nv = &nv;
    memset(&fx.n, 0, sizeof fx.n);
    memset(&cfg, 0, sizeof cfg);
    cfg.dev = &td_dev;
    cfg.hal = co_lx_port_hal(&fx.port);
    cfg.node_id = 5;
    cfg.ram = &fx.n.ram;
    assert_int_equal(co_node_init(&fx.n.node, &cfg, 1000U), CO_OK);
    co_lx_port_attach(&fx.port, &fx.n.node);
    EXPECT_OUT("705 00");
    bus_send("605 23 10 10 01 73 61 76 65");
    assert_int_equal(co_lx_port_rx(&fx.port, now), 1);
    EXPECT_OUT(""); /* not in the file yet: no answer */
    while (strcmp(bus_next(out, sizeof out), "") == 0) {
        /* the loop goes on: a request meanwhile is answered at once */
        if (rounds == 0U) {
            bus_send("605 40 00 10 00 00 00 00 00");
            assert_int_equal(co_lx_port_rx(&fx.port, now), 1);
            EXPECT_OUT("585 80 00 10 00 22 00 00 08"); /* the SDO server waits for the save */
        }
        (void)usleep(1000);
        now += 1000U;
        (void)co_node_process(&fx.n.node, now);
        rounds++;
        assert_true(rounds < 10000U);
    }
    assert_string_equal(out, "585 60 10 10 01 00 00 00 00");
    assert_int_equal(nv.writes, 1U);
    assert_int_equal(stat(path, &st), 0);
    assert_int_equal((uint32_t)st.st_size, co_store_nv_size(&td_dev));
    co_lx_nv_close(&nv);
    close(fx.sv[0]);
    close(fx.sv[1]);
}

/* ------------------------------------------------------------ time */

static void sleep_time_and_wrap(void **state)
{
    struct timespec ts;
    const struct timespec *p;
    uint32_t a;
    uint32_t b;

    (void)state;
    assert_null(co_lx_sleep_for(CO_NO_DEADLINE, 5U, &ts));
    p = co_lx_sleep_for(1500U, 500U, &ts);
    assert_non_null(p);
    assert_int_equal(ts.tv_sec, 0);
    assert_int_equal(ts.tv_nsec, 1000000L);
    /* across the 2^32 wrap */
    (void)co_lx_sleep_for(0x00000010U, 0xFFFFFFF0U, &ts);
    assert_int_equal(ts.tv_nsec, 32000L);
    (void)co_lx_sleep_for(2500000U, 0U, &ts);
    assert_int_equal(ts.tv_sec, 2);
    assert_int_equal(ts.tv_nsec, 500000000L);
    /* a deadline in the past: no sleep */
    (void)co_lx_sleep_for(100U, 200U, &ts);
    assert_int_equal(ts.tv_sec, 0);
    assert_int_equal(ts.tv_nsec, 0);
    assert_int_equal(co_lx_until(0x10U, 0xFFFFFFF0U), 32);
    assert_int_equal(co_lx_until(0xFFFFFFF0U, 0x10U), -32);
    assert_int_equal(co_lx_earlier(0x10U, 0xFFFFFFF8U, 0xFFFFFFF0U), 0xFFFFFFF8U);
    /* the clock moves forward */
    a = co_lx_now_us();
    {
        struct timespec d = {0, 2000000L};
        (void)nanosleep(&d, NULL);
    }
    b = co_lx_now_us();
    assert_true(co_lx_until(b, a) >= 2000);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_teardown(boot_up_and_sdo_over_the_socket, teardown),
        cmocka_unit_test_teardown(full_tx_path_holds_frames_back_and_retries, teardown),
        cmocka_unit_test_teardown(error_frames_become_emcy, teardown),
        cmocka_unit_test_teardown(off_bus_and_back_as_after_bus_off, teardown),
        cmocka_unit_test(canerr_table),
        cmocka_unit_test(trace_format_is_candump_log),
        cmocka_unit_test_setup_teardown(nv_file_round_trip, nv_setup, nv_teardown),
        cmocka_unit_test_setup_teardown(nv_write_failure_rolls_back, nv_setup, nv_teardown),
        cmocka_unit_test_setup_teardown(save_writes_the_file_once, nv_setup, nv_teardown),
        cmocka_unit_test(sleep_time_and_wrap),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
