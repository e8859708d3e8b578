/*
 * A CANopen slave node: the one instance struct a caller allocates per node.
 *
 * The core is passive. The port pushes every received frame with the time
 * (co_node_rx), and calls co_node_process with the time whenever the deadline
 * it last returned has come (or earlier: extra calls are harmless). Frames go
 * out through the HAL. Times are microseconds of a monotonic clock; they may
 * wrap around 2^32 (every ~71 minutes): all comparisons are wrap-safe, and no
 * single timer is longer than 2^31 us (~35 minutes; longer life-guarding
 * times are clamped).
 */
#ifndef CO_NODE_H
#define CO_NODE_H

#include <stdbool.h>
#include <stdint.h>

#include "co/co_config.h"
#include "co/co_err.h"
#include "co/co_frame.h"
#include "co/co_hal.h"
#include "co/co_od.h"
#include "co/co_pdo.h"
#include "co/co_settings.h"

#define CO_NO_DEADLINE 0xFFFFFFFFUL /**< co_node_process: nothing is due, ever */

/** Error register 0x1001 bits. */
#define CO_ERREG_GENERIC      0x01U
#define CO_ERREG_CURRENT      0x02U
#define CO_ERREG_VOLTAGE      0x04U
#define CO_ERREG_TEMPERATURE  0x08U
#define CO_ERREG_COMM         0x10U
#define CO_ERREG_PROFILE      0x20U
#define CO_ERREG_MANUFACTURER 0x80U

/** EMCY codes the core itself raises. */
#define CO_EMCY_NO_ERROR      0x0000U
#define CO_EMCY_HB_GUARD      0x8130U /**< life guard or heartbeat error */
#define CO_EMCY_SYNC_LENGTH   0x8240U /**< unexpected SYNC data length */
#define CO_EMCY_PDO_SHORT     0x8210U /**< PDO not processed due to length error */
#define CO_EMCY_PDO_LONG      0x8220U /**< PDO length exceeded */
#define CO_EMCY_RPDO_TIMEOUT  0x8250U /**< RPDO timeout */

/** NMT states; the values are the heartbeat / guarding state codes. */
typedef enum co_nmt_state {
    CO_NMT_INITIALISING = 0x00,
    CO_NMT_STOPPED = 0x04,
    CO_NMT_OPERATIONAL = 0x05,
    CO_NMT_PRE_OPERATIONAL = 0x7F
} co_nmt_state_t;

typedef enum co_reset {
    CO_RESET_COMMUNICATION = 1,
    CO_RESET_NODE = 2
} co_reset_t;

typedef enum co_hb_event {
    CO_HB_STARTED,   /**< first heartbeat of a monitored producer */
    CO_HB_TIMEOUT,   /**< consumer time elapsed without a heartbeat */
    CO_HB_RECOVERED, /**< heartbeats resumed after a timeout */
    CO_HB_STATE,     /**< producer reported another NMT state (incl. boot-up) */
    CO_GUARD_LOST,   /**< life guarding: no guarding request within the life time */
    CO_GUARD_RECOVERED
} co_hb_event_t;

/**
 * The const description of a device type, made by the generator from the
 * device's description file. Shared by all nodes of that type.
 */
typedef struct co_dev {
    uint16_t od_count;
    uint16_t ram_size;          /**< bytes of the per-node RAM image */
    uint16_t comm_end;          /**< [0, comm_end): communication parameters */
    uint16_t app_end;           /**< [comm_end, app_end): stored application values;
                                     [app_end, ram_size): not stored */
    uint16_t n_rpdo;
    uint16_t n_tpdo;
    uint16_t n_maps;            /**< rows of @ref maps */
    /** With set.lss.slave: the bit rates the device supports, bit k for index k
     *  of the CiA 305 bit-timing table (0 1000, 1 800, 2 500, 3 250, 4 125,
     *  6 50, 7 20, 8 10 kbit/s, 9 automatic detection); the generator makes
     *  it from [device] baudrates. Configure bit timing refuses the others. */
    uint16_t lss_bit_timings;
    /** A manufacturer object (UNSIGNED8) that holds the node-ID the node takes
     *  on at each Reset Communication (and at init), when it is 1..127; 0: none,
     *  the node-ID stays the one co_node_init was given (Wandfluh DSV 0x2000). */
    uint16_t nodeid_index;
    /** RAM offset and size of the SDO download staging area (not stored):
     *  a string or DOMAIN held in RAM that arrives in parts gathers there and
     *  replaces the value only when complete and accepted, so a rejected or
     *  aborted transfer leaves the old value. The generator sizes it to the
     *  largest such writable value. 0: none (values of more than one part
     *  are then written in place as they arrive). */
    uint16_t stage;
    uint16_t stage_size;
    /** With n_hooks: where the node's hook table (n_hooks co_od_hook_t
     *  slots) is, in bytes from the start of the RAM image's storage
     *  (co_node_config_t.ram), past the image (ram_size) and aligned for a
     *  pointer; the generator places it at the end of the RAM image's struct
     *  (the node keeps no pointer to it; like the core objects' places, not
     *  checked at run time: a hand-written co_dev_t follows it). */
    uint16_t hooks_at;
    /** With PDOs: where the node's PDO states (n_rpdo + n_tpdo co_pdo_t) are,
     *  in bytes from the start of the RAM image's storage, past the image
     *  and aligned for a co_pdo_t; the generator places them at the end of
     *  the RAM image's struct (not checked at run time either). */
    uint16_t pdo_at;
    /** Default runs in @ref defaults: the generator lists the values that
     *  are not zero and each $NODEID-relative value (a run of its own, marked
     *  CO_OD_DEF_NODEID), in the order of their places, none across
     *  comm_end or app_end. */
    uint16_t n_defaults;
    uint8_t n_hooks;            /**< hook slots the node's hook table must have */
    /** The personality (co_settings.h); all zero: CiA 301. (The 16-bit
     *  fields, n_hooks and the personality first, the pointers last: their
     *  loads stay short, offsets of at most 124, where a byte's are 31.)
     *  Only in a core with CO_PERSONALITY or CO_LSS: a core with neither
     *  has nothing to read there (the generated dictionary says so with
     *  #if, and refuses to compile where it needs a deviation). */
#if CO_PERSONALITY || CO_LSS
    co_settings_t set;
#endif
    const co_od_entry_t *od;    /**< od_count entries, sorted by index */
    const co_od_sub_t *rows;    /**< the entries' rows (co_od_entry_t.rows) */
    const uint8_t *defaults;    /**< n_defaults default runs (co_od.h: CO_OD_DEF_RUN) */
    const uint8_t *rom;         /**< const values (CO_SUB_ROM) */
    const co_od_limit_t *limits;
    const uint8_t *boot_emcy_data; /**< 5 bytes, with set.nmt.boot_emcy */
    const co_pdo_desc_t *pdo;   /**< n_rpdo RPDOs, then n_tpdo TPDOs */
    /** The mappable objects (co_od_map_t, n_maps rows sorted by index and
     *  sub-index), which the PDO mapping entries in the RAM image refer to. */
    const co_od_map_t *maps;
    /** With set.tpdo.change_mask: per TPDO (n_tpdo entries) the RAM offset
     *  of its change mask, two UNSIGNED32 values (the manufacturer object the
     *  description names, sub 1 and 2): bit k of the first is bit k of PDO
     *  bytes 0..3, of the second of bytes 4..7; a change of the mapped data
     *  sends the TPDO only if it touches a set bit. NULL: no masks. */
    const uint16_t *tpdo_mask;
} co_dev_t;

/**
 * Where the core's services find their objects in a device's RAM image:
 * at places fixed here, not found at run time (the node keeps no pointers
 * to them). tools/odgen lays every generated image out so: it refuses such
 * an object of another type or storage, and its source checks the places
 * at compile time (the EDS loader of targets/linux lays its images out the
 * same way); co_node_init does not check them: a hand-written co_dev_t
 * follows them. The image starts with these communication parameters
 * (stored: [0, comm_end)):
 */
#define CO_RAM_1007 0U  /**< UNSIGNED32 synchronous window length */
#define CO_RAM_1005 4U  /**< UNSIGNED32 COB-ID SYNC, its 16-bit form (co_od.h CO_SUB_COB16) */
#define CO_RAM_1014 6U  /**< UNSIGNED32 COB-ID EMCY, its 16-bit form (CO_SUB_COB16) */
#define CO_RAM_1015 8U  /**< UNSIGNED16 inhibit time EMCY */
#define CO_RAM_1017 10U /**< UNSIGNED16 producer heartbeat time */
#define CO_RAM_1019 12U /**< UNSIGNED8 synchronous counter overflow value */
/** UNSIGNED32 consumer heartbeat times, 0x1016 sub 1.. one after the other
 *  (bytes 13..15: any values, or unused) */
#define CO_RAM_1016 16U
/** The values not stored ([app_end, ram_size)) start with these, counted
 *  from app_end (a multiple of 4): */
#define CO_RAM_END_1001 0U /**< UNSIGNED8 error register */
#define CO_RAM_END_1003 1U /**< UNSIGNED8 0x1003 sub 0, the number of errors */
/** UNSIGNED32 pre-defined error field, 0x1003 sub 1.. one after the other
 *  (bytes 2..3: any values, or unused) */
#define CO_RAM_END_1003_1 4U
/* A device without one of these objects (or with its value in ROM or
 * behind a hook) has zeros in its place, which the services read as its
 * absence: no SYNC (0x1005: CAN-ID 0 is NMT's), the window always open, no
 * counter, EMCY on 0x80 + node-ID and no boot-up EMCY (0x1014 0: a value no
 * write gives it), no inhibit time, no heartbeat; without 0x1016 or 0x1003
 * sub 1 the node monitors nothing and keeps no history (their length,
 * co_node_t, is 0). */

/** Bytes of the storage co_node_config_t.ram points to for a node of @p dev:
 *  the RAM image and, past it, the PDO states (pdo_at) and the hook table
 *  (hooks_at). */
static inline uint32_t co_dev_storage_size(const co_dev_t *dev)
{
    uint32_t n_pdo = (uint32_t)dev->n_rpdo + dev->n_tpdo;
    uint32_t end = dev->ram_size;

    if ((n_pdo != 0U) && ((dev->pdo_at + (n_pdo * (uint32_t)sizeof(co_pdo_t))) > end)) {
        end = dev->pdo_at + (n_pdo * (uint32_t)sizeof(co_pdo_t));
    }
    if ((dev->n_hooks != 0U) &&
        ((dev->hooks_at + (dev->n_hooks * (uint32_t)sizeof(co_od_hook_t))) > end)) {
        end = dev->hooks_at + (dev->n_hooks * (uint32_t)sizeof(co_od_hook_t));
    }
    return end;
}

/** The first of the rows of @p e, an entry of @p dev. */
static inline const co_od_sub_t *co_od_rows(const co_dev_t *dev, const co_od_entry_t *e)
{
    return &dev->rows[e->rows];
}

struct co_node;

/** Application callbacks; any may be NULL. */
typedef struct co_node_callbacks {
    void *ctx;
    /** The NMT state changed (after the change). */
    void (*nmt_state)(void *ctx, struct co_node *node, co_nmt_state_t state);
    /** An NMT reset is being executed: reset the application part. The core
     *  has already restored what it owns (communication or all objects). */
    void (*nmt_reset)(void *ctx, struct co_node *node, co_reset_t kind);
    /** Heartbeat consumer or life-guarding event; @p id is the producer's node-ID
     *  (0 for guarding), @p state its last NMT state. */
    void (*hb_event)(void *ctx, struct co_node *node, co_hb_event_t ev, uint8_t id,
                     co_nmt_state_t state);
    /** A SYNC was received or produced (Pre-operational and Operational);
     *  @p counter is its counter value, 0 without a counter. */
    void (*sync)(void *ctx, struct co_node *node, uint8_t counter);
    /** A TIME_OF_DAY arrived (0x1012 consumer bit set): milliseconds after
     *  midnight and days since 1 January 1984. */
    void (*time)(void *ctx, struct co_node *node, uint32_t ms, uint16_t days);
    /** An error is raised without manufacturer data (co_emcy_raise with mfr
     *  NULL): every EMCY the core raises itself (0x8130 heartbeat / life
     *  guarding, 0x8210 / 0x8220 RPDO length, 0x8240 SYNC length, 0x8250
     *  RPDO timeout) and those a port raises that way (0x81xx CAN
     *  controller). Fill the manufacturer-specific EMCY bytes 3..7 @p mfr
     *  (zero on entry); they go out in the EMCY and bytes 0..1 into 0x1003
     *  like any manufacturer data. Called with the error active and 0x1001
     *  updated, before the frame. It must not raise or clear errors. NULL:
     *  zeros (CiA 301 leaves the field to the manufacturer). */
    void (*emcy_mfr)(void *ctx, struct co_node *node, uint16_t code, uint8_t mfr[5]);
    /** RPDO @p n (0-based) was received and all the mapped objects it
     *  covers are written (asynchronous: at once; synchronous: at the SYNC
     *  that applies it). A device applies its outputs here, all at once. */
    void (*rpdo)(void *ctx, struct co_node *node, uint16_t n);
    /** The mapped data of event-driven TPDO @p n (0-based) changed from
     *  @p last (what it sent last) to @p now (8 bytes each, zero beyond the
     *  mapping; the change masks of set.tpdo.change_mask passed): true lets
     *  the change send it (asked at every co_node_process while the data
     *  differs from what was sent). Not asked for the first transmission in
     *  Operational, a request, the event timer or an RTR. NULL: every
     *  change sends. Never asked in a core built with CO_TPDO_CHANGE=0
     *  (no change detection). */
    bool (*tpdo_event)(void *ctx, struct co_node *node, uint16_t n, const uint8_t last[8],
                       const uint8_t now[8]);
    /** An NMT command @p cs (0x01 start, 0x02 stop, 0x80 pre-operational,
     *  0x81 reset node, 0x82 reset communication; a 0x1029 reaction as its
     *  command) is about to be executed: the node is still in its old state
     *  (an EMCY may still go out). Only when it changes the state or resets. */
    void (*nmt_command)(void *ctx, struct co_node *node, uint8_t cs);
    /** A serious error of class @p sub was reported by co_node_error_behaviour
     *  (CO_ERRBEH_COMM: the port's bus-off, ...), before the 0x1029 reaction.
     *  (Heartbeat and life-guarding losses arrive through hb_event.) */
    void (*error_class)(void *ctx, struct co_node *node, uint8_t sub);
    /** The set of CAN-IDs the node receives (co_node_rx_cob) was made anew:
     *  at init and whenever a COB-ID, a heartbeat consumer or a PDO's
     *  validity changed. A port with hardware filters reprograms them. */
    void (*rx_set)(void *ctx, struct co_node *node);
} co_node_callbacks_t;

/** Everything co_node_init needs. */
typedef struct co_node_config {
    /* (dev .. cb: the first fields of co_node_t, copied at once) */
    const co_dev_t *dev;
    co_hal_t hal;
    /** The RAM image: dev->ram_size bytes, suitably aligned, and in the
     *  same storage the node's PDO states at dev->pdo_at and, with
     *  dev->n_hooks, the hook table at dev->hooks_at (the generated RAM
     *  image struct has them at its end: co_dev_storage_size) */
    void *ram;
    /** The application's callbacks, NULL for none. The node keeps the
     *  pointer: they must stay where they are while the node runs (a const
     *  table in flash, or the caller's own copy). */
    const co_node_callbacks_t *cb;
    /** 1..127; on an LSS slave (set.lss.slave) also 0xFF (CO_NODE_ID_UNCONFIGURED): the node
     *  starts unconfigured. An LSS slave uses the node-ID its LSS
     *  configuration store holds instead, when the HAL's NV has one. */
    uint8_t node_id;
    /** The SDO server's timeout in ms, 0: 1 s (1..65,535 ms, the range of
     *  CANopenNode's SDOserverTimeoutTime_ms; the node keeps it in 2 bytes) */
    uint16_t sdo_timeout_ms;
} co_node_config_t;

/** Node-ID of an unconfigured node (CiA 305): it sends nothing and answers
 *  only LSS until it gets a valid node-ID. */
#define CO_NODE_ID_UNCONFIGURED 0xFFU

/* ---------------- private state (do not touch; here so callers can allocate) */

/** LSS slave state (co_lss.c). */
typedef struct co_lss {
    uint32_t switch_at;   /**< activate bit timing: time of the switch */
    uint8_t state;        /**< 0 waiting, 1 configuration */
    uint8_t sel_step;     /**< switch state selective: LSS address parts matched */
    uint8_t id_step;      /**< identify remote slave: parts matched */
    uint8_t fs_pos;       /**< fastscan: LSS number part the slave compares next */
    uint8_t bit_timing;   /**< configured (pending) bit-timing index, 0xFF none */
    uint8_t active_bt;    /**< active bit-timing index, 0xFF none (the port's rate) */
    uint8_t switching;    /**< 1: activate bit timing waits for switch_at */
    uint8_t nv_step;      /**< store configuration in progress: 0 none, 1 erasing, 2 writing */
    uint8_t nv_rec;       /**< the record it writes */
} co_lss_t;

/** Parameter storage (co_store.c): a save or restore an asynchronous HAL
 *  is still writing (co_hal_ops_t.nv_poll), and the report of a damaged set. */
typedef struct co_store {
    co_err_t result;      /**< of the last command, once done */
    uint8_t step;         /**< idle, erasing, writing, done */
    uint8_t from_ram;     /**< the pending command: groups saved from the RAM image, */
    uint8_t drop;         /**< groups the new set no longer holds, */
    uint8_t mark;         /**< held groups restored to defaults (data kept), */
    uint8_t unmark;       /**< held groups whose saved data loads again */
    uint8_t damaged;      /**< the newest set found at the last reset was damaged */
} co_store_t;

typedef struct co_sdo_srv {
    /* (state and flags first: the server's most used bytes, where a 16-bit
     * load or store reaches them) */
    uint8_t state;
    uint8_t flags;       /**< and the toggle bit of the next segment */
    uint16_t timeout_ms; /**< co_node_config_t.sdo_timeout_ms (0: 1000) */
#if CO_SDO_BLOCK
    uint8_t blksize;
    uint8_t seqno;       /**< block: last good / last sent sequence number */
    uint16_t crc;
#endif
    const co_od_entry_t *entry;
    co_od_sub_t desc;    /**< the sub-entry's descriptor (of entry) */
#if CO_SDO_BLOCK
    uint16_t crc_sent;   /**< block upload: CRC up to the last segment sent (in
                              the 2 bytes after desc that were padding) */
#endif
    uint32_t size;       /**< total size, 0 if unknown */
    uint32_t offset;     /**< bytes done (acknowledged) */
    uint32_t deadline;
    /** A value of fixed size gathered before its commit; an upload's first
     *  chunk, staged (at most 7 bytes, its length in buf[7]); a block
     *  download's last segment, held until the end request brings its
     *  length (co_sdo_server.c, held_at). */
    uint8_t buf[8];
} co_sdo_srv_t;

/** Error control (co_hb.c): heartbeat producer and consumers, node and life
 *  guarding (the consumers' count and the producer's mute flag are bytes of
 *  co_node_t: n_hb_cons, bits; 0x1016, 0x1017 at their places in the RAM
 *  image, CO_RAM_1016). */
typedef struct co_errctl {
    uint32_t hb_last;        /**< time of the last heartbeat (or boot-up) */
#if CO_NODE_GUARDING
    uint16_t *guard_time;    /**< 0x100C */
    uint8_t *life_factor;    /**< 0x100D */
    uint32_t guard_deadline;
    uint8_t guard_toggle;
    uint8_t guard_state;     /**< 0 off, 1 armed (first RTR seen), 2 lost */
#endif
    /** the heartbeat consumers' time base: their deadlines count from it */
    uint32_t hbc_base;
    /* the heartbeat consumers, one element each (two arrays: no padding;
     * an entry's state is in their values: co_hb.c) */
    /** the deadline, in units of 1024 us after hbc_base, rounded up (16 bits:
     *  a consumer time of 65,535 ms is 64,000 units), 0xFFFF while lost */
    uint16_t hbc_left[CO_HB_CONSUMERS_MAX];
    uint8_t hbc_nmt[CO_HB_CONSUMERS_MAX];   /**< producer's last state, 0x80 before the
                                                 first heartbeat */
} co_errctl_t;

typedef struct co_emcy_pending {
    uint8_t data[8];
} co_emcy_pending_t;

/** EMCY producer (co_emcy.c): 0x1001, 0x1003, 0x1014, 0x1015 (at their
 *  places in the RAM image, CO_RAM_1014). Without a word of its own (the
 *  inhibit time's end is co_node_t.emcy_next) it packs to 2 bytes, and the
 *  history's depth is looked up when an error is recorded: RAM -4 B in the
 *  SEG and BLK builds. */
typedef struct co_emcy {
    uint8_t n_active;
    uint8_t n_q;             /**< waiting EMCYs, the oldest in q[0] */
#if CO_STORAGE
    uint8_t store_report;    /**< EMCY 0x5530 raised for a damaged parameter set */
#endif
    /* the active errors (two arrays: no padding) */
    uint16_t active_code[CO_EMCY_ACTIVE_MAX];
    uint8_t active_reg[CO_EMCY_ACTIVE_MAX]; /**< the 0x1001 bits each sets */
    co_emcy_pending_t q[CO_EMCY_QUEUE_LEN];
} co_emcy_t;

/** SYNC consumer and producer (co_sync.c): 0x1005, 0x1006, 0x1007, 0x1019
 *  (but 0x1006 at their places in the RAM image, CO_RAM_1005). */
typedef struct co_sync {
    uint32_t last;           /**< time of the last SYNC (window) */
#if CO_SYNC_PRODUCER
    uint32_t *period;        /**< 0x1006 */
    uint32_t deadline;       /**< producer: next SYNC */
    uint8_t counter;         /**< counter of the SYNC produced next */
#endif
} co_sync_t;

/** TIME consumer and producer (co_time.c): 0x1012. */
typedef struct co_time {
    uint8_t *cob;            /**< 0x1012, its 16-bit form (co_od.h CO_SUB_COB16) */
} co_time_t;

struct co_svc_hook;

/** co_node_t.svc_run: a bit per row of the core's service table (six rows,
 *  and LSS, TIME and storage where the build has them: co_priv.h) */
#if (6 + CO_LSS + CO_TIME + CO_STORAGE) <= 8
typedef uint8_t co_svc_bits_t;
#define CO_SVC_BITS_BYTE 1
#else
typedef uint16_t co_svc_bits_t;
#define CO_SVC_BITS_BYTE 0
#endif

/** The answers the node holds back while the TX path is full (co_node.c):
 *  one per request/response service, which has at most one answer
 *  outstanding: the SDO server's, and with CO_LSS the LSS slave's. Every
 *  other frame the core sends is made again from its producer's state when
 *  the TX path takes it (co_priv.h, CO_TXH_*). */
#define CO_TX_ANSWERS (1U + (unsigned)(CO_LSS))

typedef struct co_node {
    const co_dev_t *dev;
    co_hal_t hal;
    uint8_t *ram;            /**< (and the PDO states and hook table: co_dev_t.pdo_at,
                                  hooks_at) */
    const co_node_callbacks_t *cb; /**< NULL: none */
    /* (the order of what follows: what the core uses most where a short
     * instruction reaches it, without padding; on a Cortex-M a 16-bit load
     * or store reaches bytes up to offset 31, halfwords up to 62, words up
     * to 124: SEG stack code -180 bytes) */
    uint8_t node_id;         /**< active node-ID, CO_NODE_ID_UNCONFIGURED while unconfigured */
    uint8_t pending_id;      /**< node-ID from the next reset communication */
    uint8_t nmt;             /**< co_nmt_state_t */
    /** the dispatcher's receive table (co_node.c): its slots in rx[], and
     *  in bit 7 (CO_RX_STALE) that it is out of date (rebuilt before the
     *  next lookup) */
    uint8_t n_rx;
    /** frames waiting for the TX path, a bit per producer in CAN priority
     *  order (co_priv.h, CO_TXH_*): a frame goes only while no bit below
     *  its own is set */
    uint8_t tx_hold;
    /* (error control's bytes, here where they fill the bytes before the
     * words: co_errctl_t 64 -> 60 bytes in the SEG and BLK builds; with a
     * two-byte svc_run 'bits' comes after rx_at, so that these bytes
     * stay 8 in any build) */
    uint8_t n_hb_cons;       /**< heartbeat consumer entries (0x1016 sub 1..) */
#if CO_SVC_BITS_BYTE
    uint8_t bits;            /**< CO_NODE_HB_MUTED, CO_NODE_PDO_BUFFERED (co_priv.h) */
#endif
    /** co_node_process: bit k: service row k has something new since it
     *  last ran (a frame, a write of its objects); CO_SVC_ALL: every row,
     *  and 'due' is stale. */
    co_svc_bits_t svc_run;
    uint32_t now;
    /** co_node_process: the earliest deadline of the services when they last
     *  ran (one that has moved later since only costs an early call). */
    uint32_t due;
    uint32_t emcy_next;      /**< EMCY (co_emcy.c): earliest time the next EMCY may
                                  go (inhibit time; here: co_emcy_t) */
    /* one part per service */
    co_sdo_srv_t sdo;
    co_sync_t sync;
    co_errctl_t errctl;
    co_emcy_t emcy;
    uint8_t rx_at[16];       /**< per function code (COB-ID >> 7): its only slot,
                                  none, or several (co_node.c) */
#if !CO_SVC_BITS_BYTE
    uint8_t bits;            /**< CO_NODE_HB_MUTED, CO_NODE_PDO_BUFFERED (co_priv.h) */
#endif
#if CO_LSS
    uint8_t cob_base;        /**< node-ID the $NODEID defaults of the PDO and EMCY
                                  COB-IDs use (CO_LSS_COBS_KEEP; else node_id) */
#endif
#if CO_TPDO_CHANGE
    uint8_t pdo_poll;        /**< PDO: 1: event-driven TPDOs compare their data at
                                  every co_node_process (change detection) */
#endif
    /** The services' receive slots: the COB-ID in bits 0..10, the row of
     *  the service in the service table above them (co_node.c). */
    uint16_t rx[CO_RX_SLOTS_MAX];
    /** the answers held back (CO_TX_ANSWERS): their data bytes (identifier
     *  and length are the service's) */
    uint8_t tx_answer[CO_TX_ANSWERS][8];
#if CO_TIME
    co_time_t time;
#endif
#if CO_STORAGE
    co_store_t store;
#endif
#if CO_LSS
    co_lss_t lss;
#endif
} co_node_t;

/* ---------------- API ---------------- */

/** Initialise @p node from @p cfg, restore all values to their defaults and
 *  then to the stored set (0x1010) if the HAL's NV holds a valid one, send
 *  the boot-up frame and enter Pre-operational. Clears the hook slots
 *  (dev->hooks_at): bind hooks after this call. Returns CO_RESULT_OK, or
 *  CO_RESULT_BAD_CONFIG / CO_RESULT_BAD_NODE_ID for a bad configuration, or
 *  CO_RESULT_DEV_INCOMPAT for a device that needs a service or option this
 *  build of the core leaves out (co_config.h); nothing is sent then. */
co_result_t co_node_init(co_node_t *node, const co_node_config_t *cfg, uint32_t now_us);

/** Bytes of non-volatile memory parameter storage (0x1010/0x1011) uses for a
 *  node of @p dev: the HAL's nv_read/nv_write see addresses 0 .. this - 1
 *  (two banks; the second starts at half of it). */
uint32_t co_store_nv_size(const co_dev_t *dev);

/** The same for a HAL whose non-volatile memory is erased in units of
 *  @p erase_unit bytes (co_hal_ops_t.nv_erase_unit): each bank spans whole
 *  units. */
uint32_t co_store_nv_size_unit(const co_dev_t *dev, uint32_t erase_unit);

/** True while a save or restore command (0x1010 / 0x1011) is being written
 *  by an asynchronous HAL (co_hal_ops_t.nv_poll); a new one is refused with
 *  0x08000022 until it is done. */
bool co_store_busy(const co_node_t *node);

/** EMCY code raised after a reset whose newest parameter set was damaged
 *  (the older set or the defaults were loaded instead); cleared by the next
 *  successful save. */
#define CO_EMCY_STORE_DAMAGED 0x5530U

/** Handle one received frame. Safe for any frame (other nodes' frames, bad
 *  lengths, RTRs): malformed requests get the CiA-defined answer. */
void co_node_rx(co_node_t *node, const co_frame_t *f, uint32_t now_us);

/** Run timers and retry held-back frames. Returns the time (absolute, us) by
 *  which it wants to be called again, or CO_NO_DEADLINE. */
uint32_t co_node_process(co_node_t *node, uint32_t now_us);

/** The active node-ID (CO_NODE_ID_UNCONFIGURED while unconfigured). */
uint8_t co_node_id(const co_node_t *node);

/** Give the node another node-ID (1..127, or CO_NODE_ID_UNCONFIGURED on an
 *  LSS slave): it takes effect at the next reset communication or reset node
 *  (CiA 305), at once for an unconfigured node, which then initialises and
 *  sends its boot-up. The $NODEID defaults follow the new ID (the PDO and
 *  EMCY COB-IDs not with CO_LSS_COBS_KEEP). CO_ERR_VALUE for an ID out
 *  of range. LSS configure node-ID does the same through the bus. */
co_err_t co_node_set_id(co_node_t *node, uint8_t id, uint32_t now_us);

/** The CiA 305 bit-timing index LSS put in force (activate bit timing, or
 *  the stored one at init: 0 1000 ... 8 10 kbit/s), 0xFF when none (the
 *  port's own rate; a device with automatic detection shows that). Always
 *  0xFF without LSS. */
uint8_t co_node_bit_timing(const co_node_t *node);

/** NMT command specifiers (CiA 301 7.2.8.3.1), for co_node_nmt_command. */
typedef enum co_nmt_cmd {
    CO_NMT_CMD_START = 0x01,
    CO_NMT_CMD_STOP = 0x02,
    CO_NMT_CMD_PRE_OPERATIONAL = 0x80,
    CO_NMT_CMD_RESET_NODE = 0x81,
    CO_NMT_CMD_RESET_COMMUNICATION = 0x82
} co_nmt_cmd_t;

/** The node's current time: the time of the frame or process call it is
 *  handling (for hooks and callbacks), else of the last one. */
uint32_t co_node_now(const co_node_t *node);
/** The port's TX-ready notice: the controller has room again (a TX mailbox
 *  or FIFO slot emptied; on an MCU the TX interrupt sets a flag the main loop
 *  turns into this call). The frames that wait for the TX path (made again
 *  from their producers' state; an SDO or LSS answer held) go out now,
 *  lowest CAN-ID first, and a block upload stalled on the full TX path
 *  resumes; without the notice both wait for co_node_process, which looks
 *  again every 1 ms while the path is full. */
void co_node_tx_ready(co_node_t *node, uint32_t now_us);

/** The @p i-th CAN-ID (11 bits, 0-based) of the frames the node acts on:
 *  LSS (0x7E5; alone while unconfigured), NMT, its SDO and guarding RTR,
 *  SYNC, TIME, heartbeats it consumes, its
 *  RPDOs, and its TPDOs (whose RTR it answers). For a controller's hardware
 *  filters; false past the last. The set changes only where the rx_set
 *  callback says so. */
bool co_node_rx_cob(const co_node_t *node, uint16_t i, uint16_t *cob);

/** The current NMT state. */
co_nmt_state_t co_node_nmt_state(const co_node_t *node);

/** Execute an NMT command locally (as if received for this node); @p cs is a
 *  co_nmt_cmd_t (other values are ignored). */
void co_node_nmt_command(co_node_t *node, uint8_t cs, uint32_t now_us);

/** 0x1029 sub-index of the communication error class. */
#define CO_ERRBEH_COMM 1U

/** A serious error of class @p sub (0x1029 sub-index: CO_ERRBEH_COMM for a
 *  communication error, 2.. device-specific classes) was detected: the NMT
 *  state changes as 0x1029 sub @p sub says (0 Pre-operational, only from
 *  Operational; 1 no change; 2 Stopped; other values no change). Without
 *  0x1029 or that sub-index nothing changes. The core applies class 1 itself
 *  to a heartbeat consumer timeout and to life guarding; a port calls it
 *  with CO_ERRBEH_COMM for bus-off, a device or profile for its own classes. */
void co_node_error_behaviour(co_node_t *node, uint8_t sub, uint32_t now_us);

/** Read a whole value (up to @p cap bytes) through the dictionary path,
 *  hooks included. *len receives the length. The value arrives as wire
 *  bytes: a number little-endian (as in an SDO upload, co_get_u32() etc.
 *  decode it), never in the CPU's native byte order. */
co_err_t co_od_read(co_node_t *node, uint16_t index, uint8_t sub, void *buf, uint32_t cap,
                    uint32_t *len);

/** Write a whole value through the dictionary path: access, size, limits,
 *  hooks and the core's own checks apply, exactly as for an SDO download.
 *  @p data holds the value as wire bytes: a number little-endian, @p len
 *  bytes long (the size of its type), exactly as the data bytes of an SDO
 *  download; encode it with co_put_u16()/co_put_u32() etc. Passing the
 *  address of a native integer works only on a little-endian CPU.
 *  @p as_app: true skips the access check (an application may set ro values). */
co_err_t co_od_write(co_node_t *node, uint16_t index, uint8_t sub, const void *data,
                     uint32_t len, bool as_app);

/** Pointer to the stored value of a sub-entry (NULL for hook-only/ROM/absent).
 *  For the application's own fast access; the core never uses this behind a
 *  hook's back. */
void *co_od_value_ptr(co_node_t *node, uint16_t index, uint8_t sub);

/** Bind hooks to the entry @p index (which must have a hook slot), after
 *  co_node_init. They run after the core's own checks of the object (a
 *  service's hook comes first). CO_RESULT_NO_OBJECT, CO_RESULT_NO_HOOK_SLOT,
 *  or CO_RESULT_HOOK_BOUND when hooks are bound there already (two plug-ins
 *  on one object): the bound ones stay. */
co_result_t co_od_bind_hook(co_node_t *node, uint16_t index, const co_od_hook_t *hook);

/** Raise an error: set it active, update 0x1001 and 0x1003 and send an EMCY
 *  with @p code, the register and @p mfr (5 bytes, NULL for zeros).
 *  @p reg_bits are the 0x1001 bits this error sets (the generic bit is added;
 *  with CO_ERREG_GENERIC_UNCLASSIFIED only when @p reg_bits is 0). With @p mfr
 *  NULL the emcy_mfr callback (if any) fills the manufacturer bytes. 
 *  Raising an active code again does nothing. */
void co_emcy_raise(co_node_t *node, uint16_t code, uint8_t reg_bits, const uint8_t *mfr);

/** Clear an active error; when it was the last, send EMCY 0x0000. */
void co_emcy_clear(co_node_t *node, uint16_t code);

/** Send a TIME_OF_DAY (0x1012 producer bit set; Pre-operational or
 *  Operational): CO_ERR_NO_ACCESS when the node is no TIME producer,
 *  CO_ERR_STORE_STATE in another NMT state, CO_ERR_RESOURCE when the TX path
 *  is full (frames wait or the HAL refused it: nothing is sent, the time it
 *  carries would be stale later; call again with the time then). */
co_err_t co_time_send(co_node_t *node, uint32_t ms, uint16_t days);

/** True while the synchronous window (0x1007) after the last SYNC is open
 *  (always, when 0x1007 is 0 or absent). */
bool co_sync_window_open(const co_node_t *node);

/** Ask for a transmission of TPDO @p n (0-based) with transmission type 0
 *  (at the next SYNC) or 254/255 (as soon as the inhibit time allows).
 *  Changes of mapped data are also found without this call: event-driven
 *  TPDOs compare their data at every co_node_process (not on a device with
 *  CO_TPDO_CHANGE_IGNORED or in a core built with CO_TPDO_CHANGE=0, whose
 *  application calls this for its events). */
co_err_t co_tpdo_request(co_node_t *node, uint16_t n);

/** Fault injection (a simulated device, a test of a master): @p muted true
 *  stops the heartbeat producer's frames while everything else goes on as
 *  before (0x1017 keeps its value, SDO, PDO, EMCY and the boot-up of a
 *  reset still go out, guarding RTRs are answered as before), so that a
 *  master's heartbeat consumer times out on a node that is still alive;
 *  false resumes them, the first heartbeat at once, then every 0x1017 ms.
 *  A reset does not end it. */
void co_node_hb_mute(co_node_t *node, bool muted, uint32_t now_us);

/** True while @p code is active. */
bool co_emcy_is_active(const co_node_t *node, uint16_t code);

#endif /* CO_NODE_H */
