/*
 * In-memory CAN bus for tests: a real driver of the HAL interface.
 * Frames sent by any node are logged in order; tests read them back with
 * tb_expect(), and tb_pump() delivers them to the other nodes on the bus.
 * The bus can refuse frames (TX full) and provides non-volatile memory.
 */
#ifndef TEST_BUS_H
#define TEST_BUS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "co/co_node.h"

/* Sizes: every frame of a test is logged (TB_LOG_MAX frames, about 17 bytes
 * each) and the NV memory is TB_NV_SIZE bytes. A build for a target with
 * little RAM may define smaller ones (-DTB_LOG_MAX=...); a test that logs
 * more frames than that fails at the frame that does not fit. */
#ifndef TB_LOG_MAX
#define TB_LOG_MAX 4096U
#endif
#define TB_NODES_MAX 4U
#ifndef TB_NV_SIZE
#define TB_NV_SIZE 4096U
#endif

typedef struct tb_bus tb_bus_t;

typedef struct tb_port {
    tb_bus_t *bus;
    uint8_t idx;
} tb_port_t;

struct tb_bus {
    co_frame_t log[TB_LOG_MAX];
    uint8_t from[TB_LOG_MAX];  /**< port that sent it (0xFF: the test) */
    size_t n_log;
    size_t read_pos;           /**< next frame tb_expect() looks at */
    size_t deliver_pos;        /**< next frame tb_pump() delivers */
    co_node_t *nodes[TB_NODES_MAX];
    tb_port_t ports[TB_NODES_MAX];
    size_t n_nodes;
    uint32_t now;
    unsigned refuse;           /**< refuse this many send() calls (TX full) */
    unsigned refuse_after;     /**< ... after this many more are taken */
    unsigned refused;          /**< how many were refused */
    uint8_t nv[TB_NV_SIZE];        /**< NV of port 0 */
    uint8_t nv_port[TB_NODES_MAX - 1U][TB_NV_SIZE]; /**< NV of ports 1.. */
    /* LSS bit timing (HAL bit_timing): last index per port, calls, time */
    uint8_t bit_timing[TB_NODES_MAX];
    unsigned bit_timing_calls;
    uint32_t bit_timing_at;
    /* NV fault injection (see tb_nv_cut) */
    uint32_t nv_written;       /**< bytes written to NV so far (all writes) */
    uint32_t nv_budget;        /**< bytes still written before the power cut */
    bool nv_cut_armed;         /**< a power cut is armed */
    bool nv_cut;               /**< the power cut has happened: NV is frozen */
    bool nv_tear;              /**< the byte at the cut is torn, not lost */
    bool nv_fail_write;        /**< nv_write fails (nothing written) */
    bool nv_fail_read;         /**< nv_read fails */
    /* asynchronous NV with erase (tb_hal_ops_async; set nv_async before tb_hal) */
    bool nv_async;             /**< tb_hal gives the asynchronous flash-like HAL */
    unsigned nv_busy_each;     /**< nv_poll answers busy this often after each erase/write */
    unsigned nv_busy;          /**< busy answers still to give */
    unsigned nv_polls;         /**< nv_poll calls */
    unsigned nv_erases;        /**< nv_erase calls */
    uint32_t nv_erase_addr;    /**< of the last one */
    uint32_t nv_erase_len;
    unsigned nv_unerased;      /**< bytes written that were not erased (flash would not hold them) */
    bool nv_fail_poll;         /**< nv_poll reports a failure */
};

/** Erase unit of tb_hal_ops_async. */
#define TB_NV_ERASE_UNIT 256U

/** Every port has NV of its own (port 0: bus->nv) and records the LSS
 *  bit-timing switches. */
extern const co_hal_ops_t tb_hal_ops;
/** The same bus without non-volatile memory (nv_read/nv_write NULL). */
extern const co_hal_ops_t tb_hal_ops_no_nv;
/** Flash-like NV: erase in TB_NV_ERASE_UNIT units, writes and erases
 *  complete asynchronously (nv_poll busy nv_busy_each times after each). */
extern const co_hal_ops_t tb_hal_ops_async;

void tb_init(tb_bus_t *bus);
/** A HAL for node slot @p idx on @p bus (attach the node afterwards). */
co_hal_t tb_hal(tb_bus_t *bus, uint8_t idx);
void tb_attach(tb_bus_t *bus, uint8_t idx, co_node_t *node);

/** Arm a power cut: the next @p n bytes written to NV arrive, everything
 *  after is lost (writes fail) until tb_nv_power_on(). With @p tear the byte
 *  after the @p n is torn: its high nibble new, its low nibble old. */
void tb_nv_cut(tb_bus_t *bus, uint32_t n, bool tear);
/** Power is back: NV accepts writes again (its content stays as the cut left it). */
void tb_nv_power_on(tb_bus_t *bus);

/** The test sends @p text ("601 40 00 10 ...") to every node at bus->now. */
void tb_send(tb_bus_t *bus, const char *text);
void tb_send_frame(tb_bus_t *bus, const co_frame_t *f);
/** Deliver frames the nodes sent to the other nodes, until quiet. */
void tb_pump(tb_bus_t *bus);
/** Advance time by @p us in steps no larger than @p step (0: jump at once),
 *  calling co_node_process on every node at each step and whenever a
 *  deadline falls inside the step. */
void tb_advance(tb_bus_t *bus, uint32_t us);

/** Next frame a node sent, NULL if none. */
const co_frame_t *tb_next(tb_bus_t *bus);
void tb_expect_at(tb_bus_t *bus, const char *text, const char *file, int line);
void tb_expect_none_at(tb_bus_t *bus, const char *file, int line);
#define tb_expect(bus, text) tb_expect_at((bus), (text), __FILE__, __LINE__)
#define tb_expect_none(bus) tb_expect_none_at((bus), __FILE__, __LINE__)
/** Skip everything logged so far. */
void tb_flush(tb_bus_t *bus);

/** Send @p req and expect exactly @p resp in answer (and nothing else). */
#define tb_xfer(bus, req, resp)                                                                  \
    do {                                                                                         \
        tb_send((bus), (req));                                                                   \
        tb_expect((bus), (resp));                                                                \
        tb_expect_none(bus);                                                                     \
    } while (0)

#endif
