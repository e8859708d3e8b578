/*
 * Internals shared by the core's modules. Not a public header.
 */
#ifndef CO_PRIV_H
#define CO_PRIV_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "co/co_endian.h"
#include "co/co_node.h"

/* Small helpers of the per-frame paths: inlined even at -Os, where the
 * compiler would otherwise call them (a call costs more than their body). */
#ifndef CO_INLINE
#if defined(__GNUC__)
#define CO_INLINE static inline __attribute__((always_inline))
#else
#define CO_INLINE static inline
#endif
#endif
/* Per-frame paths with several callers: inlined where the build asks for
 * speed; at -Os the compiler decides (one copy instead of one per caller):
 * the instructions per frame (tools/bench-instructions, -O2) and the flash
 * (tools/bench-size, -Os) both stay low. CO_FAST is 1 in a build for speed
 * (a second, inlined path is worth its bytes there). */
#if defined(__GNUC__) && !defined(__OPTIMIZE_SIZE__)
#define CO_FAST 1
#define CO_HOT static inline __attribute__((always_inline))
#else
#define CO_FAST 0
#define CO_HOT static inline
#endif
/* Copies of a length known only at run time. At -Os one byte loop of the
 * core's own (co_copy.c, about 20 bytes on a Cortex-M3) instead of the C
 * library's memcpy (236 bytes in newlib-nano's); a build for speed calls
 * memcpy. Lengths the compiler knows (2, 4, 8) stay memcpy: it emits them
 * as loads and stores. */
void co_copy_bytes(void *dst, const void *src, size_t n);
static inline void co_copy(void *dst, const void *src, size_t n)
{
#if CO_FAST
    (void)memcpy(dst, src, n);
#else
    co_copy_bytes(dst, src, n);
#endif
}
/* Rare paths kept out of the per-frame functions they would otherwise be
 * inlined into (their stack frame and saved registers would be paid on
 * every frame). */
#if defined(__GNUC__)
#define CO_NOINLINE __attribute__((noinline))
#else
#define CO_NOINLINE
#endif

/* A setting of the node's device (co_settings.h, e.g. CO_SET(node,
 * pdo.granularity)); with CO_PERSONALITY 0 every setting is its CiA 301
 * value 0, so the code of the deviations is not built. */
#if CO_PERSONALITY
#define CO_SET(node, field) ((uint32_t)(node)->dev->set.field)
#else
#define CO_SET(node, field) ((void)(node), 0U)
#endif

/* The application's callback @p fn of co_node_callbacks_t, NULL when it has
 * none (or no callbacks at all: co_node_t.cb NULL). */
#define CO_CB(node, fn) (((node)->cb != NULL) ? (node)->cb->fn : NULL)

/* Wrap-safe "a is at or after b". */
static inline bool co_time_reached(uint32_t now, uint32_t when)
{
    return (int32_t)(now - when) >= 0;
}

/* The horizon of every timer: no deadline is set more than 2^31 - 1 us
 * ahead of the time it is set at, so co_time_reached can tell it from a time
 * in the past. Every time value that enters the core from the dictionary
 * (0x1006, 0x1015, 0x1016, 0x1017, 0x100C x 0x100D, PDO inhibit times and
 * event timers) goes through co_dict_us, which clamps it to the horizon. */
#define CO_HORIZON_US 0x7FFFFFFFUL

/* @p v units of @p unit_us microseconds, clamped to CO_HORIZON_US. */
static inline uint32_t co_dict_us(uint32_t v, uint32_t unit_us)
{
    return (v > (CO_HORIZON_US / unit_us)) ? CO_HORIZON_US : (v * unit_us);
}

/* Restricted CAN-IDs (CiA 301 7.3.5): no configurable COB-ID (PDO, SYNC,
 * TIME, EMCY) may use them: 0x000..0x07F, 0x101..0x180, 0x581..0x5FF,
 * 0x601..0x67F, 0x6E0..0x6FF, 0x701..0x7FF (@p id: 11 bits). The last four
 * are 0x581..0x67F and 0x6E0..0x7FF without the one multiple of 0x100 in
 * each (0x600, 0x700). */
static inline bool co_cob_restricted(uint32_t id)
{
    return (id <= 0x07FU) || ((id - 0x101U) <= 0x7FU) ||
           (((id & 0xFFU) != 0U) && (((id - 0x581U) <= 0xFEU) || (id >= 0x6E0U)));
}

/* Earliest of a deadline set and another candidate. */
CO_INLINE uint32_t co_deadline_earlier(uint32_t now, uint32_t cur, uint32_t cand)
{
    if (cur == CO_NO_DEADLINE) {
        return cand;
    }
    return ((int32_t)(cand - now) < (int32_t)(cur - now)) ? cand : cur;
}
/* The same, in a build for size one copy (co_deadline.c: the services'
 * timers call it in many places), inlined in a build for speed. */
#if CO_FAST
CO_INLINE uint32_t co_deadline_min(uint32_t now, uint32_t cur, uint32_t cand)
{
    return co_deadline_earlier(now, cur, cand);
}
#else
uint32_t co_deadline_min(uint32_t now, uint32_t cur, uint32_t cand);
#endif

/* The node's PDO states, in the RAM image's storage (co_dev_t.pdo_at,
 * aligned: the generator places them). */
CO_INLINE co_pdo_t *co_pdo_st(const co_node_t *node)
{
    return (co_pdo_t *)(void *)&node->ram[node->dev->pdo_at];
}

/* Native values in the RAM image, by offset (any alignment). */
static inline uint32_t co_ram_u32(const co_node_t *node, uint16_t off)
{
    uint32_t v;
    (void)memcpy(&v, &node->ram[off], sizeof v);
    return v;
}

static inline uint16_t co_ram_u16(const co_node_t *node, uint16_t off)
{
    uint16_t v;
    (void)memcpy(&v, &node->ram[off], sizeof v);
    return v;
}

static inline uint8_t co_ram_u8(const co_node_t *node, uint16_t off)
{
    return node->ram[off];
}

/* The COB-ID at @p p in the RAM image, in its 16-bit form there (co_od.h,
 * CO_SUB_COB16): bit 31 of its UNSIGNED32 in CO_COB_B31, bit 30 in
 * CO_COB_B30, the CAN-ID in bits 10..0 (and 0 for the UNSIGNED32 0). Every
 * reader of a COB-ID the core checks (PDO, SYNC, EMCY, TIME) reads it
 * through this and works on the form (co_check_cob takes it too). */
#define CO_COB_B31 0x8000U
#define CO_COB_B30 0x4000U
CO_INLINE uint32_t co_cob_at(const uint8_t *p)
{
    uint16_t v;
    (void)memcpy(&v, p, sizeof v);
    return v;
}
CO_INLINE uint32_t co_ram_cob(const co_node_t *node, uint16_t off)
{
    return co_cob_at(&node->ram[off]);
}

/* The values not stored of the RAM image (co_node.h: CO_RAM_END_*). */
static inline uint8_t *co_ram_end(const co_node_t *node)
{
    return &node->ram[node->dev->app_end];
}

/* The CPU stores integers little-endian, like the wire (the compiler says
 * so: co_endian.h's CO_ENDIAN_LE; without that knowledge the portable
 * conversion is used). */
#ifdef CO_ENDIAN_LE
#define CO_NATIVE_LE true
#else
#define CO_NATIVE_LE false
#endif

/* Values of 16, 32 and 64 bits live in RAM/ROM as native integers (so the
 * application and the core use them as plain variables); every other type is
 * stored as its wire bytes. These two convert @p n bytes at the dictionary
 * boundary, so the wire image is little-endian on any CPU (on a
 * little-endian CPU both are copies). */
static inline void co_to_wire(uint8_t *dst, const uint8_t *src, uint8_t n)
{
    if ((n == 4U) && CO_NATIVE_LE) {
        (void)memcpy(dst, src, 4U);
    } else if (n == 4U) {
        uint32_t v;
        (void)memcpy(&v, src, 4U);
        co_put_u32(dst, v);
    } else if ((n == 2U) && !CO_NATIVE_LE) {
        uint16_t v;
        (void)memcpy(&v, src, 2U);
        co_put_u16(dst, v);
    } else if ((n == 8U) && !CO_NATIVE_LE) {
        uint64_t v;
        (void)memcpy(&v, src, 8U);
        co_put_u64(dst, v);
    } else {
        co_copy(dst, src, n);
    }
}

static inline void co_from_wire(uint8_t *dst, const uint8_t *src, uint8_t n)
{
    if ((n == 4U) && CO_NATIVE_LE) {
        (void)memcpy(dst, src, 4U);
    } else if (n == 4U) {
        uint32_t v = co_get_u32(src);
        (void)memcpy(dst, &v, 4U);
    } else if ((n == 2U) && !CO_NATIVE_LE) {
        uint16_t v = co_get_u16(src);
        (void)memcpy(dst, &v, 2U);
    } else if ((n == 8U) && !CO_NATIVE_LE) {
        uint64_t v = co_get_u64(src);
        (void)memcpy(dst, &v, 8U);
    } else {
        co_copy(dst, src, n);
    }
}

/* ---- time (co_node.c) */
void co_node_stalled(co_node_t *node, uint32_t now_us);
/* Every entry point that brings a time sets node->now through this: a jump
 * ahead of 2^31 us or more (but not a small step back, as receive time
 * stamps taken before the last co_node_process may make) is a stall. */
#define CO_STEP_BACK_MAX 0x04000000UL /* 67 s */
CO_INLINE void co_node_clock_at(co_node_t *node, uint32_t now_us)
{
    uint32_t d = now_us - node->now;

    if ((d > CO_HORIZON_US) && (d < (0xFFFFFFFFUL - CO_STEP_BACK_MAX))) {
        co_node_stalled(node, now_us);
    }
    node->now = now_us;
}
#if CO_FAST
CO_INLINE void co_node_clock(co_node_t *node, uint32_t now_us)
{
    co_node_clock_at(node, now_us);
}
#else
/* (a build for size: one copy, called from every entry point) */
void co_node_clock(co_node_t *node, uint32_t now_us);
#endif

/* co_node_t.bits */
#define CO_NODE_HB_MUTED     0x01U /* heartbeats held back (co_node_hb_mute) */
#define CO_NODE_PDO_BUFFERED 0x02U /* PDO: some RPDO may hold data for the next SYNC */

/* ---- transmit (co_node.c) */
/* No frame waits in a queue of frames: a producer whose frame the HAL
 * refuses keeps what it needs to make it again and it goes when the TX path
 * takes it (co_node_process looks again every 1 ms while any waits,
 * co_node_tx_ready at once). co_node_t.tx_hold has a bit per producer, in
 * the CAN priority of its frame (the CAN-IDs of the predefined connection
 * set: SYNC 0x080, EMCY 0x080 + node-ID, SDO 0x580 + node-ID, error control
 * 0x700 + node-ID, LSS 0x7E4), and a frame goes only while no bit below its
 * own is set: of what waits, the frame that would win arbitration goes
 * first. Only the request/response services' answers are kept as frames
 * (co_node_t.tx_answer: one each, a service has at most one outstanding). */
#define CO_TXH_SYNC    0x01U /* the SYNC producer's SYNC (co_sync.c) */
#define CO_TXH_EMCY    0x02U /* the oldest EMCY of the EMCY queue (co_emcy.c) */
#define CO_TXH_SDO     0x04U /* the SDO server's answer, tx_answer[0] */
#define CO_TXH_BOOT    0x08U /* the boot-up */
#define CO_TXH_HB      0x10U /* a heartbeat (co_hb.c): the NMT state when it goes */
#define CO_TXH_GUARD   0x20U /* a node-guarding reply (co_hb.c) */
#define CO_TXH_LSS     0x40U /* the LSS slave's answer, tx_answer[CO_TX_ANSWERS - 1] */
/* (the last bit a build has: its frames' loop ends there) */
#define CO_TXH_LAST    (CO_LSS ? CO_TXH_LSS : (CO_NODE_GUARDING ? CO_TXH_GUARD : CO_TXH_HB))
#define CO_TXH_ANSWERS (CO_TXH_SDO | CO_TXH_LSS)
#define CO_TX_ANSWER_SLOT(bit) (((bit) == CO_TXH_LSS) ? (CO_TX_ANSWERS - 1U) : 0U)
#define CO_LSS_TX_ID   0x7E4UL /* the LSS slave's answers (CiA 305) */
/* Send @p f now or not at all: false while any frame waits (tx_hold) or the
 * HAL refuses it (the TPDOs, an SDO block upload's segments, TIME). */
#if CO_FAST
static inline bool co_tx_now(co_node_t *node, const co_frame_t *f)
{
    return (node->tx_hold == 0U) && (node->hal.ops->send(node->hal.ctx, f) == 0);
}
#else
bool co_tx_now(co_node_t *node, const co_frame_t *f); /* (one copy: co_node.c) */
#endif
/* The frame of producer @p bit (CO_TXH_SYNC, CO_TXH_EMCY) now, unless a
 * frame of a higher priority waits or the HAL refuses it: then its bit is
 * set and the producer makes it again at its next run (every run while
 * tx_hold is not 0); sent, its bit is cleared. */
bool co_tx_try(co_node_t *node, uint8_t bit, const co_frame_t *f);
/* The frame of @p bit (CO_TXH_SDO and above) waits, and what waits of those
 * goes now as far as the HAL takes it: an answer's 8 data bytes @p answer
 * (replacing an answer still held: the service's state is that of its
 * newest), NULL for the frames the node makes from its state (boot-up,
 * heartbeat, guarding reply). */
void co_tx_hold(co_node_t *node, uint8_t bit, const uint8_t *answer);
/* The receive table is out of date (a COB-ID changed): the node rebuilds it
 * from the services' CO_SVC_SLOTS events before it looks up the next frame. */
void co_rx_invalidate(co_node_t *node);
void co_rx_rebuild(co_node_t *node);
/* Rebuild a stale receive table now (the node's entry points, the SDO
 * server after a request: a port with hardware filters must hear of a new
 * COB-ID before frames on it can arrive). */
#define CO_RX_STALE 0x80U /* co_node_t.n_rx: the table is out of date */
static inline void co_rx_settle(co_node_t *node)
{
    if ((node->n_rx & CO_RX_STALE) != 0U) {
        co_rx_rebuild(node);
    }
}
/* From a service's CO_SVC_SLOTS event: frames on @p cob go to the rx of
 * the service of row @p svc. */
void co_rx_add(co_node_t *node, uint16_t cob, uint8_t svc);
/* co_node_t.rx: the service's row above the COB-ID */
#define CO_RX_ROW_SHIFT 11U
/* co_node_t.rx_at, per function code (COB-ID >> 7): no slot, the only
 * slot (the node's rx[k]: 1 + k, at most CO_RX_SLOTS_MAX; PDO i, which
 * receives co_pdo_rx_cob: CO_RX_AT_PDO + i), or several (CO_RX_AT_MANY: a
 * search of the node's slots and the PDOs, also for a PDO whose index does
 * not fit). */
#define CO_RX_AT_NONE 0x00U
#define CO_RX_AT_PDO  0x80U
#define CO_RX_AT_MANY 0xFFU
/* Frames on @p cob go to slot @p at (a CO_RX_AT_* code) of the tables (a
 * build for size searches for the slot of every frame it accepts:
 * CO_RX_AT_MANY, the caller's slot computed for nothing). */
static inline void co_rx_accept(co_node_t *node, uint16_t cob, uint8_t at)
{
    uint8_t *fc = &node->rx_at[cob >> 7U];

    *fc = (CO_FAST && (*fc == CO_RX_AT_NONE)) ? at : CO_RX_AT_MANY;
}
/* Change the NMT state: the services' nmt entries in table order, then the
 * application's callback. */
void co_node_set_state(co_node_t *node, co_nmt_state_t st);
/* Execute NMT command @p cs (co_nmt_cmd_t), the application's notice first. */
void co_node_nmt_exec(co_node_t *node, uint8_t cs);

/* ---- what co_node_process runs: only the services with something new
 * (co_node_t.svc_run) until the earliest deadline they returned has come */
#define CO_SVC_ALL ((co_svc_bits_t)~0U) /* every row, and the cached deadline is stale */
/* Service row @p k has something new (a frame for it, a write of one of
 * its objects): it runs at the next co_node_process. */
static inline void co_svc_touch(co_node_t *node, uint8_t k)
{
    node->svc_run |= (co_svc_bits_t)(1U << k);
}
/* Service row @p k has nothing to do for what touched it (a frame answered
 * completely, no timer running): it need not run at the next
 * co_node_process for it (when every row runs, it runs too). */
static inline void co_svc_untouch(co_node_t *node, uint8_t k)
{
    uint32_t run = node->svc_run;

    if (run != CO_SVC_ALL) {
        run &= ~((uint32_t)1U << k);
        node->svc_run = (co_svc_bits_t)run;
    }
}
/* A service's deadline that moved to @p when without the service running
 * (a hook with CO_SVC_SELF): co_node_process comes back no later. */
static inline void co_svc_due(co_node_t *node, uint32_t when)
{
    node->due = co_deadline_min(node->now, node->due, when);
}
/* Something that may concern any service (an NMT state change, an error,
 * the TX path): they all run and their deadlines are taken anew. */
static inline void co_svc_touch_all(co_node_t *node)
{
    node->svc_run = CO_SVC_ALL;
}

/* ---- the services (co_services.c): the node's dispatch table */

/* What the dictionary engine asks of a service's hook (co_svc_hook_t.fn),
 * for an access to an object the service owns; the hook's ops bits say
 * which it wants to be asked. */
#define CO_SVC_READ    0x01U /* before a stored value is read (offset 0): an error vetoes it */
#define CO_SVC_CHECK   0x02U /* a complete new value (type, size and limits checked), before
                                the application's hook: an error vetoes the write */
#define CO_SVC_COMMIT  0x04U /* after the application's hook, instead of the engine's commit:
                                the service stores or acts on the value (co_od_commit stores
                                it); its result is the answer, CO_SVC_WRITTEN does not follow */
#define CO_SVC_WRITTEN 0x08U /* after the value was stored (the result is ignored) */
#define CO_SVC_SELF    0x10U /* the hook tells the node itself what a write changes
                                (co_svc_touch, co_svc_due): a write alone does not make
                                the service run at the next co_node_process */

/* A service's hook on the objects it owns (the entries whose svc,
 * CO_OD_SVC_OF(index), names its slot in co_svc_hooks). The dictionary
 * engine (co_od.c) calls fn for the accesses @p ops names, before the
 * application's hook of the entry (data/len: the value in wire bytes for
 * CO_SVC_CHECK and CO_SVC_COMMIT, NULL/0 otherwise). */
typedef struct co_svc_hook {
    uint8_t ops;
    uint8_t row;  /* the owning service's row in co_services[] (CO_ROW_*): a write
                     of its objects makes it run at the next co_node_process */
    co_err_t (*fn)(co_node_t *node, uint8_t op, const co_od_entry_t *e, const co_od_sub_t *s,
                   const uint8_t *data, uint32_t len);
} co_svc_hook_t;
/* The services' hooks, slot k - 1 for the entries whose svc is k
 * (co_services.c; CO_OD_SVC_OF says which objects each slot owns). */
extern const co_svc_hook_t co_svc_hooks[CO_SVC_N_HOOKS];
/* The hooks (each service's file). */
co_err_t co_emcy_obj(co_node_t *node, uint8_t op, const co_od_entry_t *e, const co_od_sub_t *s,
                     const uint8_t *data, uint32_t len);
co_err_t co_sync_obj(co_node_t *node, uint8_t op, const co_od_entry_t *e, const co_od_sub_t *s,
                     const uint8_t *data, uint32_t len);
co_err_t co_errctl_obj(co_node_t *node, uint8_t op, const co_od_entry_t *e, const co_od_sub_t *s,
                       const uint8_t *data, uint32_t len);
co_err_t co_hb_prod_obj(co_node_t *node, uint8_t op, const co_od_entry_t *e,
                        const co_od_sub_t *s, const uint8_t *data, uint32_t len);
co_err_t co_store_obj(co_node_t *node, uint8_t op, const co_od_entry_t *e, const co_od_sub_t *s,
                      const uint8_t *data, uint32_t len);
co_err_t co_pdo_obj(co_node_t *node, uint8_t op, const co_od_entry_t *e, const co_od_sub_t *s,
                    const uint8_t *data, uint32_t len);
#if CO_TIME
co_err_t co_time_obj(co_node_t *node, uint8_t op, const co_od_entry_t *e, const co_od_sub_t *s,
                     const uint8_t *data, uint32_t len);
#endif
#if CO_ERROR_BEHAVIOUR
co_err_t co_errbeh_obj(co_node_t *node, uint8_t op, const co_od_entry_t *e,
                       const co_od_sub_t *s, const uint8_t *data, uint32_t len);
#endif

/* The core objects the services use, bound once at co_node_init (where
 * they live does not change): one table for all (co_services.c), one loop
 * (co_node.c) instead of a bind function per service (the objects with
 * places in the RAM image, co_node.h's CO_RAM_*, need no row). A row names
 * object 0x1000 + index, the type its value must have and what the node
 * stores at byte 'at' of co_node_t: CO_BIND_PTR a pointer to the value of
 * the sub-index the row names (0 or CO_BIND_SUB1) in the RAM image
 * (co_od_ram_of: NULL without one); CO_BIND_LEN a uint8_t count of the
 * array's entries 1..n of that type stored back to back (co_od_array_len,
 * at most 254; CO_BIND_LEN_HB at most CO_HB_CONSUMERS_MAX); CO_BIND_NONE
 * nothing: a device with that object needs a service this build leaves
 * out (co_config.h; co_node_init refuses it: CO_RESULT_DEV_INCOMPAT). */
typedef struct co_bind {
    uint8_t index;
    uint8_t spec; /* the type (below 0x20) | CO_BIND_SUB1 | CO_BIND_* kind */
    uint16_t at;
} co_bind_t;
#define CO_BIND_SUB1   0x20U
#define CO_BIND_PTR    0x00U
#define CO_BIND_NONE   0x40U
#define CO_BIND_LEN    0x80U
#define CO_BIND_LEN_HB 0xC0U
#define CO_BIND_KIND   0xC0U
/* Its rows: a constant the node's loop compares with (the table's
 * definition has this size; an initialiser too long does not compile, a
 * row left out would be all zeros: test_services checks for one). */
#define CO_N_BINDS ((uint8_t)(6U - (unsigned)(CO_ERROR_BEHAVIOUR)))
extern const co_bind_t co_binds[CO_N_BINDS];

/* What the node tells a service (co_service_t.event), in table order to
 * every service: CO_RESET_NODE and CO_RESET_COMMUNICATION once the node has
 * restored the values of the reset's area to defaults (co_od_restore; the
 * store service loads the stored set over them), before the application's
 * nmt_reset callback, then
 * CO_SVC_START before the boot-up frame: the service's state starts over.
 * CO_SVC_BIND: co_node_init, before anything else, to the LSS service alone
 * (its stored configuration: an LSS-stored node-ID replaces the configured
 * one). CO_SVC_SLOTS: the receive table is rebuilt (to the running services
 * only): co_rx_add(node, cob, its row CO_ROW_*) for each COB-ID it receives.
 * CO_SVC_NMT: the NMT state changed to node->nmt; CO_SVC_BOOTED: the same,
 * from Initialising (after the boot-up frame). A service ignores the others. */
#define CO_SVC_START  0U
#define CO_SVC_BIND   3U
#define CO_SVC_SLOTS  4U
#define CO_SVC_NMT    5U
#define CO_SVC_BOOTED 6U

/* One service: the same entry points for all, any may be NULL. The node
 * walks co_services[] in its order for each (docs/core.md). */
typedef struct co_service {
    /* (co_node_init finds the objects a service uses: co_binds[]) */
    /* Resets, receive slots, NMT state changes: @p ev is a CO_SVC_* above. */
    void (*event)(co_node_t *node, uint8_t ev);
    /* A frame for it: @p arg is 0 (a service tells its COB-IDs apart by the
     * frame's identifier); for the
     * PDO service, the PDO whose COB-ID it is (the node's PDO table). */
    void (*rx)(co_node_t *node, uint16_t arg, const co_frame_t *f);
    /* Timers: returns the earlier of @p next and its own deadline. */
    uint32_t (*process)(co_node_t *node, uint32_t next);
} co_service_t;

/* The rows of co_services[] (co_services.c places each service at its row). */
#define CO_ROW_NMT    ((uint8_t)(CO_LSS))
#define CO_ROW_SDO    ((uint8_t)(CO_ROW_NMT + 1U))
#define CO_ROW_ERRCTL ((uint8_t)(CO_ROW_NMT + 2U))
#define CO_ROW_EMCY   ((uint8_t)(CO_ROW_NMT + 3U))
#define CO_ROW_SYNC   ((uint8_t)(CO_ROW_NMT + 4U))
#define CO_ROW_TIME   ((uint8_t)(CO_ROW_NMT + 5U)) /* only with CO_TIME */
#define CO_ROW_PDO    ((uint8_t)(CO_ROW_SYNC + 1U + (unsigned)(CO_TIME)))
#define CO_ROW_STORE  ((uint8_t)(CO_ROW_PDO + 1U))
/* Its rows, the last one's + 1 (the table's size: the node's walks compare
 * with a constant). */
#define CO_N_SERVICES ((uint8_t)(CO_ROW_PDO + 1U + (unsigned)(CO_STORAGE)))
extern const co_service_t *const co_services[CO_N_SERVICES];
/* The services (one per file; co_services.c puts them in order). */
extern const co_service_t co_svc_nmt;
extern const co_service_t co_svc_sdo;
extern const co_service_t co_svc_errctl;
extern const co_service_t co_svc_emcy;
extern const co_service_t co_svc_sync;
#if CO_TIME
extern const co_service_t co_svc_time;
#endif
extern const co_service_t co_svc_pdo;
#if CO_STORAGE
extern const co_service_t co_svc_store; /* (a row only with storage) */
#endif
#if CO_LSS
extern const co_service_t co_svc_lss;
#endif

/* ---- object dictionary internals (co_od.c) */
/* co_type_sizes[] has an entry for every value of the type's low five
 * bits (the types are 0x01..0x1B: co_type_t), so a size is one load
 * without a range check. */
#define CO_TYPE_SIZES 0x20U
extern const uint8_t co_type_sizes[CO_TYPE_SIZES];

/* Size in bytes of a fixed-size type, 0 for strings and DOMAIN. */
static inline uint8_t co_type_len(uint8_t type)
{
    return co_type_sizes[type & (CO_TYPE_SIZES - 1U)];
}

/* Strings and DOMAINs: values of variable length, read and written in parts. */
static inline bool co_od_is_streamed(const co_od_sub_t *s)
{
    return co_type_len(s->type) == 0U;
}

/* Where the value of @p s lives: RAM image, ROM image, or NULL (HOOKIO). */
CO_INLINE void *co_od_loc(const co_node_t *node, const co_od_entry_t *e, const co_od_sub_t *s)
{
    if ((s->flags & CO_SUB_HOOKIO) != 0U) {
        return NULL;
    }
    if ((s->flags & CO_SUB_ROM) != 0U) {
        /* ROM values are only ever read through this pointer. */
        return (void *)(uintptr_t)&node->dev->rom[s->off];
    }
    return &node->ram[(uint16_t)(e->base + s->off)];
}

/* @p index / @p sub: its entry in *@p e, its descriptor in *@p s (the
 * caller's). */
co_err_t co_od_lookup(const co_node_t *node, uint16_t index, uint8_t sub,
                      const co_od_entry_t **e, co_od_sub_t *s);
/* co_od_lookup, then the access check of an SDO client: readable or
 * (@p write) writable (0x06010001 / 0x06010002). */
co_err_t co_od_lookup_for(const co_node_t *node, uint16_t index, uint8_t sub, bool write,
                          const co_od_entry_t **e, co_od_sub_t *s);
bool co_type_is_signed(uint8_t type);
/* One chunk of a value being read, as a read hook sees it (a value without
 * storage: the hook reads it into the same structure): the caller sets
 * offset, buf, len (the capacity), total 0 and last false; co_od_read_part
 * sets len, total (0 if a hook does not know it) and last. */
typedef co_od_io_t co_od_chunk_t;
/* Read a chunk; at offset 0 the read hook runs first. */
co_err_t co_od_read_part(co_node_t *node, const co_od_entry_t *e, const co_od_sub_t *s,
                         co_od_chunk_t *c);
/* Write a complete value (checks, hook, commit, notification). */
co_err_t co_od_write_value(co_node_t *node, const co_od_entry_t *e, const co_od_sub_t *s,
                           const uint8_t *data, uint32_t len);
/* An expedited SDO download of @p index / @p sub: lookup, access check
 * (writable), then the whole value from @p data, @p size bytes as the
 * request indicates them (0: not indicated, then four bytes, or the
 * object's own size when it is smaller). */
co_err_t co_od_download(co_node_t *node, uint16_t index, uint8_t sub, const uint8_t *data,
                        uint32_t size);
/* Write one chunk of a streamed value (strings, DOMAIN), as a write hook
 * sees it: the caller sets offset, buf, len, total and last of @p c. */
co_err_t co_od_write_part(co_node_t *node, const co_od_entry_t *e, const co_od_sub_t *s,
                          co_od_chunk_t *c);
/* Restore [0, to) of the RAM image to defaults and apply $NODEID. */
void co_od_restore(co_node_t *node, uint16_t to);

/* The CO_SVC_* operations the service owning @p e hooks (0: none). */
static inline uint8_t co_od_svc_ops(const co_od_entry_t *e)
{
    return (co_od_svc(e) != 0U) ? co_svc_hooks[co_od_svc(e) - 1U].ops : 0U;
}
/* Store a checked value of @p s from wire bytes (the engine's commit). */
void co_od_commit(co_node_t *node, const co_od_entry_t *e, const co_od_sub_t *s,
                  const uint8_t *data, uint32_t len);

/* Where a core object lives in the RAM image: the value of @p index sub
 * @p sub if it has type @p type (0: any) and a stored RAM value, else NULL. */
uint8_t *co_od_ram_of(co_node_t *node, uint16_t index, uint8_t sub, uint8_t type);
/* Number of consecutive sub-entries 1..n (at most @p max) of an array whose
 * values of @p type are stored back to back, 0 if there are none. */
uint8_t co_od_array_len(co_node_t *node, uint16_t index, uint8_t type, uint8_t max);
/* Every sub-entry of @p dev, entry by entry and row by row (a run's
 * sub-indices one by one), to @p visit with its entry (the descriptor
 * valid for the call only). */
typedef void (*co_od_visit_t)(void *ctx, const co_od_entry_t *e, const co_od_sub_t *s);
void co_od_each_sub(const co_dev_t *dev, co_od_visit_t visit, void *ctx);

/* A COB-ID write (CiA 301 7.5.2) of @p v (UNSIGNED32) over @p cur (its
 * 16-bit form, co_cob_at): 29-bit identifiers
 * are not supported, bits 11..28 are 0 (and bit 30 with CO_COB_RSV30), and
 * the CAN-ID may not change while the object is in use: in use is any of
 * the use bits of @p rule set (CO_COB_WHEN_SET) or its one bit clear (a
 * single bit, the 'valid' bit of EMCY and PDO). A CAN-ID in use (or always,
 * CO_COB_ALWAYS: the SYNC consumer) may not be a restricted one (CiA 301
 * 7.3.5). One word for the rule: the callers pass three arguments, all in
 * registers. */
co_err_t co_check_cob(uint32_t cur, uint32_t v, uint32_t rule);
/* co_check_cob's @p rule: the object's use bits (bits 31 and 30 of its
 * COB-ID: CO_COB_B31, CO_COB_B30) and the flags below */
#define CO_COB_USE      (CO_COB_B31 | CO_COB_B30)
#define CO_COB_WHEN_SET 0x01U /* in use while a use bit is set (else: while clear) */
#define CO_COB_ALWAYS   0x02U /* the CAN-ID counts as in use whatever the bits say */
#define CO_COB_RSV30    0x04U /* bit 30 is reserved: must be 0 */

/* True while the synchronous window (0x1007) after the last SYNC is open. */
static inline bool co_sync_window(const co_node_t *node)
{
    uint32_t w = co_ram_u32(node, CO_RAM_1007); /* (0: none) */

    return (w == 0U) || ((uint32_t)(node->now - node->sync.last) <= w);
}

/* ---- node-ID (co_node.c) */
/* The $NODEID base the PDO and EMCY COB-IDs would have with node-ID @p id. */
uint8_t co_node_cob_base_for(const co_node_t *node, uint8_t id);
/* The node's $NODEID base of the PDO and EMCY COB-IDs, and setting it: only
 * an LSS slave keeps one apart from the node-ID (co_node_t.cob_base). */
static inline uint8_t co_node_cob_base(const co_node_t *node)
{
#if CO_LSS
    return node->cob_base;
#else
    return node->node_id;
#endif
}
static inline void co_node_keep_cob_base(co_node_t *node, uint8_t base)
{
#if CO_LSS
    node->cob_base = base;
#else
    (void)node;
    (void)base;
#endif
}
/* At a reset: make the pending node-ID the active one; returns the reset
 * to do (a node leaving the unconfigured state initialises completely). */
co_reset_t co_node_take_id(co_node_t *node, co_reset_t kind);

/* ---- LSS slave (co_lss.c) */
#define CO_LSS_REC     16U               /* bytes of one stored LSS record */
#define CO_LSS_NV_SIZE (2U * CO_LSS_REC) /* NV behind the parameter banks */
/* NV address of LSS record @p rec (0, 1) behind the parameter banks, and
 * the records' spacing: an erase unit of its own each on flash (co_store.c). */
uint32_t co_store_lss_addr(const co_node_t *node, uint8_t rec);
uint32_t co_store_lss_unit(const co_node_t *node);
/* Rows at the head of co_services[] that run while the node is unconfigured
 * (the LSS service); the others wait for a valid node-ID. */
#define CO_SVC_UNCONFIGURED_ROWS ((uint8_t)(CO_LSS))
/* The node waits for a node-ID (LSS); never in a build without LSS, whose
 * co_node_init refuses a device that would. */
static inline bool co_node_unconfigured(const co_node_t *node)
{
    return (CO_LSS != 0) && (node->node_id == CO_NODE_ID_UNCONFIGURED);
}
/* The device is an LSS slave (and the build has LSS). LSS is a service
 * (CO_LSS), not a deviation: read past CO_PERSONALITY, as co_node_init does. */
static inline bool co_lss_enabled(const co_node_t *node)
{
#if CO_LSS
    return node->dev->set.lss.slave != 0U;
#else
    (void)node;
    return false;
#endif
}

/* Drop the communication group of the stored set (a node leaving the
 * unconfigured state with CO_LSS_COBS_KEEP; co_store.c). */
void co_store_forget_comm(co_node_t *node);
/* True for a sub-entry of 0x1010 / 0x1011 the core acts on (sub >= 1,
 * UNSIGNED32 in RAM, or a writable const: CO_SUB_ROM | CO_SUB_W): a write
 * saves or restores, the value is never stored. */
bool co_store_is_command(const co_od_entry_t *e, const co_od_sub_t *s);
/* co_store_result: the result of the last command, once co_store_busy() is
 * false (an asynchronous HAL: the SDO server answers with it).
 * co_store_damaged: the newest parameter set found at the last reset was
 * damaged (an older one or the defaults were loaded), and no save has
 * written a whole one since: the EMCY service reports it (EMCY 0x5530). */
#if CO_STORAGE
co_err_t co_store_result(const co_node_t *node);
bool co_store_damaged(const co_node_t *node);
#else
/* without storage no command is ever written and no set ever loaded: the
 * callers' code for them is not built */
static inline co_err_t co_store_result(const co_node_t *node)
{
    (void)node;
    return CO_OK;
}
static inline bool co_store_damaged(const co_node_t *node)
{
    (void)node;
    return false;
}
#endif

/* ---- what one service asks of another (no cycles: tools/core-callgraph) */
/* A serious error of 0x1029 class @p sub: the NMT reaction it configures
 * (co_nmt.c; nothing without CO_ERROR_BEHAVIOUR). */
#if CO_ERROR_BEHAVIOUR
void co_nmt_error(co_node_t *node, uint8_t sub);
#else
static inline void co_nmt_error(co_node_t *node, uint8_t sub)
{
    (void)node;
    (void)sub;
}
#endif

/* ---- PDO (co_pdo_config.c, co_rpdo.c, co_tpdo.c) */
/* (0x0001 unused; a PDO's mapping is enabled and valid while its len is not 0) */
#define CO_PDO_F_EVENT     0x0002U /* TPDO: transmission requested / due */
#define CO_PDO_F_SENT      0x0004U /* TPDO: sent (with CO_TPDO_CHANGE: data[] holds what) */
#define CO_PDO_F_TIMER     0x0008U /* timer armed (TPDO event timer, RPDO deadline) */
#define CO_PDO_F_INHIBIT   0x0010U /* TPDO: inhibit time running until 'inhibit' */
#define CO_PDO_F_RXBUF     0x0020U /* RPDO: data[] waits for the next SYNC */
#define CO_PDO_F_TIMEOUT   0x0040U /* RPDO: deadline missed (EMCY 0x8250 raised) */
#define CO_PDO_F_SHORT     0x0080U /* RPDO: last frame too short (EMCY 0x8210) */
#define CO_PDO_F_LONG      0x0100U /* RPDO: last frame too long (EMCY 0x8220) */
#define CO_PDO_F_SYNC_PEND 0x0200U /* TPDO: synchronous data[] waits for the TX path */
#define CO_PDO_F_STARTED   0x0400U /* TPDO: SYNC start value reached */
#define CO_PDO_F_SAMPLED   0x0800U /* TPDO 252: data[] sampled at the last SYNC */
#define CO_PDO_F_RTR       0x1000U /* TPDO: a remote request waits for an answer */
#define CO_PDO_F_DIRECT    0x2000U /* every mapping entry copied directly (co_pdo_config.c) */
#define CO_PDO_F_AT_END    0x4000U /* a build for speed, CO_PDO_F_DIRECT: an entry's row has
                                      CO_OD_MAP_AT_END (only such a PDO looks at it) */

/* PDO i's mapping entries in the RAM image: 16 bits each (co_od.h,
 * CO_OD_MAP_ENTRY), a reference to a dummy type or to a row of the
 * device's mappable-object table (co_od_map_t), with the bits it maps - 1.
 * When the mapping is enabled, a PDO whose every entry is a plain RAM value
 * the engine may copy directly between frame and RAM image, with the
 * dictionary path's result, gets CO_PDO_F_DIRECT: its entries are then
 * copied from the table's rows (offset, size, sign, at the end of the
 * image), with no lookup. A PDO with any other entry goes through the
 * dictionary for every entry (a per-entry choice would cost RAM per PDO). */
CO_INLINE uint16_t co_pdo_ref(const uint8_t *map, uint32_t k)
{
    uint16_t v;
    (void)memcpy(&v, &map[2U * k], sizeof v);
    return v;
}
/* The bits entry @p ref maps; its table row (a reference of a row) */
CO_INLINE uint32_t co_pdo_ref_bits(uint32_t ref)
{
    return (ref & CO_OD_MAP_BITS) + 1U;
}
CO_INLINE const co_od_map_t *co_pdo_row(const co_dev_t *dev, uint32_t ref)
{
    return &dev->maps[(ref >> CO_OD_MAP_REF_SHIFT) - CO_OD_MAP_ROW0];
}
/* A dummy entry (an RPDO's gap): its reference is a type's */
CO_INLINE bool co_pdo_ref_dummy(uint32_t ref)
{
    return ref < (CO_OD_MAP_ROW0 << CO_OD_MAP_REF_SHIFT);
}

/* (of the COB-ID's 16-bit form, co_pdo_cob) */
#define CO_PDO_COB_INVALID CO_COB_B31
#define CO_PDO_COB_NO_RTR  CO_COB_B30

/* PDO i's parameters in the RAM image (co_pdo_desc_t): the optional ones
 * by their distance from the COB-ID, the mapping entries before their
 * number, the transmission type after it. */
CO_INLINE const uint8_t *co_pdo_at(const co_node_t *node, uint16_t i, uint32_t rel)
{
    return &(&node->ram[node->dev->pdo[i].cob])[rel];
}

CO_INLINE uint16_t co_pdo_u16(const co_node_t *node, uint16_t i, uint32_t rel)
{
    uint16_t v;
    (void)memcpy(&v, co_pdo_at(node, i, rel), sizeof v);
    return v;
}

CO_INLINE uint32_t co_pdo_cob(const co_node_t *node, uint16_t i)
{
    return co_ram_cob(node, node->dev->pdo[i].cob);
}

CO_INLINE const uint8_t *co_pdo_map(const co_node_t *node, const co_pdo_desc_t *d)
{
    return &node->ram[d->count - (2U * d->map_max)];
}

CO_INLINE uint8_t co_pdo_count(const co_node_t *node, uint16_t i)
{
    return co_ram_u8(node, node->dev->pdo[i].count);
}

CO_INLINE uint8_t co_pdo_type(const co_node_t *node, uint16_t i)
{
    return (&node->ram[node->dev->pdo[i].count])[1];
}

/* The PDOs the receive table covers: the RPDOs, and with CO_PDO_RTR the
 * TPDOs (their remote requests). */
CO_INLINE uint16_t co_pdo_n_rx(const co_node_t *node)
{
    return (uint16_t)(node->dev->n_rpdo + (CO_PDO_RTR ? node->dev->n_tpdo : 0U));
}

/* The CAN-ID PDO i receives (of those co_pdo_n_rx covers), CO_PDO_RX_NONE
 * when it receives none: invalid, or a TPDO that answers no RTR. */
#define CO_PDO_RX_NONE 0xFFFFU
CO_INLINE uint16_t co_pdo_rx_cob(const co_node_t *node, uint16_t i)
{
    uint32_t cob = co_pdo_cob(node, i);

    if (((cob & CO_PDO_COB_INVALID) != 0U) ||
        (CO_PDO_RTR && (i >= node->dev->n_rpdo) && ((cob & CO_PDO_COB_NO_RTR) != 0U))) {
        return CO_PDO_RX_NONE;
    }
    return (uint16_t)(cob & 0x7FFU);
}

/* Valid COB-ID and an enabled, valid mapping (len: the bytes it covers). */
CO_INLINE bool co_pdo_usable(const co_node_t *node, uint16_t i)
{
    return ((co_pdo_cob(node, i) & CO_PDO_COB_INVALID) == 0U) &&
           (co_pdo_st(node)[i].len != 0U);
}

/* An event-driven transmission of usable TPDO i, due at the next pass of
 * the PDO service (co_tpdo_request; an RPDO with set.pdo.tpdo_after_rpdo). */
CO_INLINE void co_tpdo_raise(co_node_t *node, uint16_t i)
{
    co_pdo_st(node)[i].flags |= CO_PDO_F_EVENT;
    co_svc_touch(node, CO_ROW_PDO);
}

/* @p n bytes of a value between the RAM image (native) and the wire, for
 * the sizes a direct entry has (1..8): the usual ones without a call. */
CO_INLINE void co_pdo_to_wire(uint8_t *dst, const uint8_t *src, uint8_t n)
{
    if (n == 1U) {
        dst[0] = src[0];
    } else if (n == 2U) {
        co_to_wire(dst, src, 2U);
    } else if (n == 4U) {
        co_to_wire(dst, src, 4U);
    } else {
        co_to_wire(dst, src, n);
    }
}

CO_INLINE void co_pdo_from_wire(uint8_t *dst, const uint8_t *src, uint8_t n)
{
    if (n == 1U) {
        dst[0] = src[0];
    } else if (n == 2U) {
        co_from_wire(dst, src, 2U);
    } else if (n == 4U) {
        co_from_wire(dst, src, 4U);
    } else {
        co_from_wire(dst, src, n);
    }
}

/* @p n (1..8) bytes, the usual lengths without a call. */
CO_INLINE void co_copy_small(uint8_t *dst, const uint8_t *src, uint8_t n)
{
    if (n == 1U) {
        dst[0] = src[0];
    } else if (n == 2U) {
        (void)memcpy(dst, src, 2U);
    } else if (n == 4U) {
        (void)memcpy(dst, src, 4U);
    } else {
        co_copy(dst, src, n);
    }
}

/* A direct TPDO entry, @p n bytes of the value at @p m into the frame at
 * @p at (8 bytes of room): the low bytes of the value's wire image (on a
 * little-endian CPU the first bytes of the native value; on a big-endian
 * CPU the entry maps the whole value). On a little-endian CPU 8 bytes are
 * read at once, the ones past the entry's for the next entry or the
 * padding to overwrite (a value at the end of the RAM image: the 8 bytes
 * that end with the mapped ones, CO_OD_MAP_AT_END). */
CO_INLINE void co_pdo_get_direct(const co_node_t *node, const co_od_map_t *m, uint32_t n,
                                 uint8_t *at, bool may_end)
{
    uint32_t off = m->off;

    if (CO_NATIVE_LE) {
        uint64_t x;
        if (!may_end || ((m->info & CO_OD_MAP_AT_END) == 0U)) {
            (void)memcpy(&x, &node->ram[off], 8U);
        } else {
            uint32_t shift = 8U * (8U - n);
            (void)memcpy(&x, &node->ram[(off + n) - 8U], 8U);
            x >>= shift;
        }
        (void)memcpy(at, &x, 8U);
    } else {
        co_pdo_to_wire(at, &node->ram[off], (uint8_t)n);
    }
}

/* A direct RPDO entry: @p n bytes at @p at into the value at @p m. */
CO_INLINE void co_pdo_put_direct(co_node_t *node, const co_od_map_t *m, const uint8_t *at,
                                 uint8_t n)
{
    uint8_t *v = &node->ram[m->off];
    uint8_t size = (uint8_t)((m->info & CO_OD_MAP_SIZE) + 1U);

    if (n == size) {
        if (CO_NATIVE_LE) {
            co_copy_small(v, at, n);
        } else {
            co_pdo_from_wire(v, at, size);
        }
    } else {
        /* the low bytes, extended by the sign for signed types */
        uint8_t wire[8];
        bool neg = ((m->info & CO_OD_MAP_SIGNED) != 0U) && ((at[n - 1U] & 0x80U) != 0U);
        (void)memset(wire, neg ? 0xFF : 0x00, sizeof wire);
        co_copy(wire, at, n);
        co_from_wire(v, wire, size);
    }
}

/* PDO i has CO_PDO_F_DIRECT (every entry copied directly, in whole bytes):
 * its mapped objects straight into @p out (8 bytes, zero past the
 * mapping), or from @p data (@p dlc bytes, the entries the frame covers;
 * dummies are gaps), without a call. */
CO_INLINE uint8_t *co_pdo_sample_entries(const co_node_t *node, const uint8_t *map,
                                         uint32_t count, uint8_t *at, bool may_end)
{
    /* (at most 8 entries of a byte or more: only the compiler needs to know) */
    uint32_t n_ent = (count <= 8U) ? count : 0U;
    uint8_t *out = at;
    for (uint32_t k = 0U; k < n_ent; k++) {
        uint32_t ref = co_pdo_ref(map, k);
        uint32_t n = co_pdo_ref_bits(ref) >> 3U; /* (a TPDO has no dummy entry) */
        co_pdo_get_direct(node, co_pdo_row(node->dev, ref), n, out, may_end);
        out = &out[n];
    }
    return out;
}

CO_INLINE void co_pdo_sample_direct(const co_node_t *node, uint16_t i, uint8_t *out)
{
    uint8_t buf[16]; /* room for the 8 bytes written at the last entry */
    uint8_t *at = buf;
    const uint8_t *map = co_pdo_map(node, &node->dev->pdo[i]);
    uint32_t count = co_pdo_count(node, i);

    /* (the entries' rows looked at for CO_OD_MAP_AT_END only where one has it) */
    if ((co_pdo_st(node)[i].flags & CO_PDO_F_AT_END) == 0U) {
        at = co_pdo_sample_entries(node, map, count, at, false);
    } else {
        at = co_pdo_sample_entries(node, map, count, at, true);
    }
    (void)memset(at, 0, 8U);
    (void)memcpy(out, buf, 8U);
}

CO_INLINE void co_pdo_store_direct(co_node_t *node, uint16_t i, const uint8_t *data, uint8_t dlc)
{
    const co_dev_t *dev = node->dev;
    const uint8_t *map = co_pdo_map(node, &dev->pdo[i]);
    uint8_t count = co_pdo_count(node, i);
    uint8_t avail = (dlc > 8U) ? 8U : dlc;
    uint8_t at = 0U;

    for (uint8_t k = 0U; k < count; k++) {
        uint32_t ref = co_pdo_ref(map, k);
        uint8_t n = (uint8_t)(co_pdo_ref_bits(ref) >> 3U);
        if ((uint8_t)(at + n) > avail) {
            break;
        }
        if (!co_pdo_ref_dummy(ref)) {
            co_pdo_put_direct(node, co_pdo_row(dev, ref), &data[at], n);
        }
        at = (uint8_t)(at + n);
    }
}

/* Event timer of PDO i in us (0: off), inhibit time of TPDO i in us (0:
 * none): in a build for size one function for both (co_pdo_map.c,
 * co_pdo_time_us: @p inhibit selects). */
#if CO_FAST
CO_INLINE uint32_t co_pdo_event_us(const co_node_t *node, uint16_t i)
{
    uint32_t rel = node->dev->pdo[i].event;
    uint32_t unit = (CO_SET(node, pdo.event_timer_unit) == CO_PDO_TIMER_100US) ? 100UL : 1000UL;

    return (rel == 0U) ? 0U : co_dict_us(co_pdo_u16(node, i, rel), unit);
}
CO_INLINE uint32_t co_pdo_inhibit_us(const co_node_t *node, uint16_t i)
{
    uint32_t rel = node->dev->pdo[i].inhibit;

    return (rel == 0U) ? 0U : co_dict_us(co_pdo_u16(node, i, rel), 100UL);
}
#else
uint32_t co_pdo_time_us(const co_node_t *node, uint16_t i, bool inhibit);
CO_INLINE uint32_t co_pdo_event_us(const co_node_t *node, uint16_t i)
{
    return co_pdo_time_us(node, i, false);
}
CO_INLINE uint32_t co_pdo_inhibit_us(const co_node_t *node, uint16_t i)
{
    return co_pdo_time_us(node, i, true);
}
#endif
/* The mapped objects of PDO i (co_pdo_map.c, one entry point for both
 * directions), a CO_PDO_F_DIRECT PDO's entries directly, the others through the
 * dictionary: sample them into @p out (8 bytes, zero past the mapping; an
 * object that cannot be read is sent as zeros), or write them from @p data
 * (@p dlc bytes; entries the frame does not cover are skipped, a refused
 * value is dropped). */
#define CO_PDO_SAMPLE 0xFFU
void co_pdo_io(co_node_t *node, uint16_t i, uint8_t *buf, uint8_t dlc);
CO_INLINE void co_pdo_sample(co_node_t *node, uint16_t i, uint8_t *out)
{
    co_pdo_io(node, i, out, CO_PDO_SAMPLE);
}
CO_INLINE void co_pdo_store(co_node_t *node, uint16_t i, const uint8_t *data, uint8_t dlc)
{
    /* (data only read: a frame's bytes, or an RPDO's buffered ones) */
    co_pdo_io(node, i, (uint8_t *)(uintptr_t)data, (dlc > 8U) ? 8U : dlc);
}
void co_rpdo_rx(co_node_t *node, uint16_t i, const co_frame_t *f);
void co_rpdo_sync(co_node_t *node);
/* Set the error states of RPDO i in @p on (CO_PDO_F_SHORT, _LONG, _TIMEOUT),
 * clear the others of @p mask, with their EMCYs (co_rpdo.c). */
void co_rpdo_error(co_node_t *node, uint16_t i, uint16_t mask, uint16_t on);
#if CO_PDO_RTR
void co_tpdo_rtr(co_node_t *node, uint16_t i);
#endif
void co_tpdo_sync(co_node_t *node, uint8_t counter);
uint32_t co_tpdo_process(co_node_t *node, uint32_t next);

#endif /* CO_PRIV_H */
