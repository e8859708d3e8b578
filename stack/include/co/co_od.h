/*
 * Object dictionary.
 *
 * A device's dictionary is a const table of entries sorted by index (flash on
 * an MCU). Each entry lists its sub-entries sorted by sub-index. A sub-entry
 * knows its data type, access, PDO-mappability, limits and where its value
 * lives: at an offset into the node's RAM image (one image per node, so the
 * same const tables serve several nodes), or at an offset into the device's
 * const ROM image, or nowhere (the value is produced and consumed by a hook:
 * DOMAINs and computed objects). The default of every RAM value is the same
 * offset in the device's const default image.
 *
 * Every access (SDO, PDO, application) goes through co_od_read()/co_od_write()
 * or the chunked calls below the SDO server uses; errors are co_err_t, whose
 * values are the SDO abort codes. Those calls take and give values as wire
 * bytes (numbers little-endian, as on the bus); the RAM and ROM images hold
 * them in the CPU's native order, converted on the way in and out.
 */
#ifndef CO_OD_H
#define CO_OD_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "co/co_config.h"
#include "co/co_err.h"

struct co_node;
struct co_dev;

/** CiA 301 data types (the values are the type indices 0x0001..0x001B). */
typedef enum co_type {
    CO_BOOLEAN = 0x01, CO_INTEGER8 = 0x02, CO_INTEGER16 = 0x03, CO_INTEGER32 = 0x04,
    CO_UNSIGNED8 = 0x05, CO_UNSIGNED16 = 0x06, CO_UNSIGNED32 = 0x07, CO_REAL32 = 0x08,
    CO_VISIBLE_STRING = 0x09, CO_OCTET_STRING = 0x0A, CO_UNICODE_STRING = 0x0B,
    CO_TIME_OF_DAY = 0x0C, CO_TIME_DIFFERENCE = 0x0D, CO_DOMAIN = 0x0F,
    CO_INTEGER24 = 0x10, CO_REAL64 = 0x11, CO_INTEGER40 = 0x12, CO_INTEGER48 = 0x13,
    CO_INTEGER56 = 0x14, CO_INTEGER64 = 0x15, CO_UNSIGNED24 = 0x16, CO_UNSIGNED40 = 0x18,
    CO_UNSIGNED48 = 0x19, CO_UNSIGNED56 = 0x1A, CO_UNSIGNED64 = 0x1B
} co_type_t;

/* Sub-entry flags. Access: ro = R, wo = W, rw = R|W, const = R|CONST,
 * rwr = R|W|MAP_T, rww = R|W|MAP_R (CiA 306 access types). */
#define CO_SUB_R       0x0001U /**< readable over SDO */
#define CO_SUB_W       0x0002U /**< writable over SDO */
#define CO_SUB_CONST   0x0004U /**< constant (read-only, never changes) */
#define CO_SUB_MAP_T   0x0008U /**< may be mapped into a TPDO */
#define CO_SUB_MAP_R   0x0010U /**< may be mapped into an RPDO */
#define CO_SUB_ROM     0x0020U /**< value lives in the device's const ROM image */
#define CO_SUB_HOOKIO  0x0040U /**< no stored value: the entry's hook reads/writes it */
#define CO_SUB_NODEID  0x0080U /**< default is relative to the node-ID ($NODEID+x) */
#define CO_SUB_LIMIT   0x0100U /**< 'limit' indexes the device's limit table */
/** An UNSIGNED32 COB-ID stored in 16 bits (size 2: co_od_cob_u32; a PDO
 *  mapping entry is an UNSIGNED32 of size 2 without it: CO_OD_MAP_ENTRY) */
#define CO_SUB_COB16   0x0200U
/** A row of a dictionary table may describe a run of sub-indices (uniform
 *  ARRAY and RECORD elements: the same type, flags, size and limit, values
 *  one after the other in RAM, or one const value for all in ROM): the
 *  run's length - 1 (up to 64) in these bits of its flags, its last sub-index in 'sub'
 *  (CO_OD_RUN). The run's k-th sub-index has its value at off + k * size,
 *  with CO_SUB_ROM at off (the same value). (A row's place in its table is never above
 *  its first sub-index, so a run's row never sits at the place of its
 *  'sub': a row found there is one sub-index.) The descriptors the lookups
 *  give (co_od_find_sub) are one sub-index each, without these bits. */
#define CO_SUB_RUN_SHIFT 10U
#define CO_SUB_FLAGS   0x03FFU /**< the CO_SUB_* flags of a row's flags */
#define CO_SUB_MAP     (CO_SUB_MAP_T | CO_SUB_MAP_R)
#define CO_SUB_RO      CO_SUB_R
#define CO_SUB_WO      CO_SUB_W
#define CO_SUB_RW      (CO_SUB_R | CO_SUB_W)

/** Object codes (CiA 306 ObjectType). */
#define CO_OBJ_VAR     0x07U
#define CO_OBJ_ARRAY   0x08U
#define CO_OBJ_RECORD  0x09U
#define CO_OBJ_DOMAIN  0x02U

/** One sub-entry (a descriptor), or in a dictionary table one row: one
 *  sub-entry, or a run of them (CO_SUB_RUN_SHIFT). */
typedef struct co_od_sub {
    uint8_t  sub;    /**< sub-index (a run's last) */
    uint8_t  type;   /**< co_type_t */
    uint16_t flags;  /**< CO_SUB_* (a row: and its run's length - 1) */
    uint16_t size;   /**< bytes; capacity for strings and DOMAINs */
    uint16_t off;    /**< offset into the RAM image, or the ROM image with CO_SUB_ROM */
#if CO_LIMITS
    uint16_t limit;  /**< with CO_SUB_LIMIT: index into co_dev_t.limits */
#endif
} co_od_sub_t;

/** Initialiser of one co_od_sub_t (the generated dictionaries use it): a
 *  core built without value limits (CO_LIMITS=0) has no 'limit' field, 2
 *  bytes less flash per sub-entry. */
#if CO_LIMITS
#define CO_OD_SUB(sub, type, flags, size, off, limit) \
    {(sub), (type), (flags), (size), (off), (limit)}
#else
#define CO_OD_SUB(sub, type, flags, size, off, limit) {(sub), (type), (flags), (size), (off)}
#endif
/** Initialiser of one row for the @p n (2..64) sub-indices sub..sub+n-1
 *  of one type, flags, size and limit, with values at off, off + size, ...
 *  (with CO_SUB_ROM: one value at off) */
#define CO_OD_RUN(sub, n, type, flags, size, off, limit) \
    CO_OD_SUB((uint8_t)((sub) + (n) - 1U), (type), \
              (uint16_t)((flags) | (((n) - 1U) << CO_SUB_RUN_SHIFT)), (size), (off), (limit))

/* Defaults (co_dev_t.defaults, co_dev_t.n_defaults runs): the values of
 * the RAM image that are not zero and the $NODEID-relative ones, as runs in
 * the order of their places in the image (the rest of the image is zero).
 * A run is two bytes, then its values as wire bytes (little-endian):
 *   [0] its gap: the bytes of zeros between the end of the run before it
 *       (the start of the image) and its place (a gap above 255: a run of
 *       a zero byte in between);
 *   [1] CO_OD_DEF_RUN(n, w): n values (1..16) of 1 << w bytes each (w 0..3:
 *       numbers of 2, 4 and 8 bytes are native integers in the image), and
 *       the marks CO_OD_DEF_NODEID / CO_OD_DEF_COB. */
#define CO_OD_DEF_RUN(n, w) ((uint8_t)((((uint32_t)(w)) << 4U) | ((uint32_t)(n) - 1U)))
#define CO_OD_DEF_N      0x0FU /**< header byte 1: the run's number of values - 1 */
#define CO_OD_DEF_W      0x30U /**< header byte 1: log2 of the size of its values */
/** The run is one $NODEID-relative value of 1, 2 or 4 bytes (CO_SUB_NODEID):
 *  the node-ID is added to it when it is restored. */
#define CO_OD_DEF_NODEID 0x80U
/** With CO_OD_DEF_NODEID: a PDO or EMCY COB-ID, whose base is the node's
 *  COB-ID base (it differs from the node-ID only with LSS). */
#define CO_OD_DEF_COB    0x40U

/** The core service that owns the object at @p index (co_od_svc, co_od_entry_t.tag):
 *  its hook's slot + 1 in the core's const service-hook table (co_svc_hooks,
 *  co_services.c), 0 for an object no service of this build owns. A constant
 *  expression: the generated tables carry it, nothing registers at run time.
 *  Slots: 1 EMCY history 0x1003, 2 EMCY 0x1014..0x1015, 3 SYNC 0x1005..0x1007
 *  and 0x1019, 4 heartbeat consumers 0x1016 (and guarding 0x100C..0x100D),
 *  5 heartbeat producer 0x1017, 6 storage 0x1010..0x1011, 7 PDO
 *  0x1400..0x1BFF, then TIME 0x1012 and error behaviour 0x1029 where the
 *  build has them (CO_SVC_N_HOOKS). */
#define CO_OD_SVC_OF(i) \
    (((i) == 0x1003U) ? 1U \
     : (((i) == 0x1014U) || ((i) == 0x1015U)) ? 2U \
     : ((((i) >= 0x1005U) && ((i) <= 0x1007U)) || ((i) == 0x1019U)) ? 3U \
     : (((i) == 0x1016U) || ((CO_NODE_GUARDING != 0) && (((i) == 0x100CU) || ((i) == 0x100DU)))) ? 4U \
     : ((i) == 0x1017U) ? 5U \
     : (((i) == 0x1010U) || ((i) == 0x1011U)) ? 6U \
     : (((i) >= 0x1400U) && ((i) <= 0x1BFFU)) ? 7U \
     : ((CO_TIME != 0) && ((i) == 0x1012U)) ? 8U \
     : ((CO_ERROR_BEHAVIOUR != 0) && ((i) == 0x1029U)) ? (8U + (unsigned)(CO_TIME)) \
     : 0U)
/** Number of slots of the core's service-hook table. */
#define CO_SVC_N_HOOKS (7U + (unsigned)(CO_TIME) + (unsigned)(CO_ERROR_BEHAVIOUR))

/** One object (8 bytes). Its rows are @ref nsubs rows of the device's one
 *  table of rows (co_dev_t.rows) from row @ref rows on (co_od_rows).
 *  Objects of the same shape (the PDOs' parameters) share their rows: the
 *  RAM offsets in them count from @ref base, where each object's values
 *  start (0 for rows of its own, whose offsets are the values' own; an
 *  object of one value that uses another's row: the distance between the
 *  two values, modulo 2^16 as base and offset are added). An
 *  object with a hook slot (CO_OD_TAG_HOOK) has rows of its own and its
 *  slot as its base: their RAM offsets count from it. */
typedef struct co_od_entry {
    uint16_t index;
    uint16_t rows;           /**< its first row in co_dev_t.rows */
    uint16_t base;           /**< added to the RAM offset of every sub-entry */
    uint8_t  nsubs;          /**< number of its rows (a row may be a run) */
    uint8_t  tag;            /**< CO_OD_TAG_*: owning service, object code, hook */
} co_od_entry_t;

/* co_od_entry_t.tag */
#define CO_OD_TAG_HOOK 0x01U /**< a hook slot, base (the rows are its own) */
#define CO_OD_TAG_CODE 0x06U /**< the object code (CO_OD_CODE_BITS) */
/** Sub-index 0 is not a row: a const UNSIGNED8, readable, whose value is
 *  the highest sub-index of the rows (the last row's 'sub', a byte of the
 *  device's ROM image, which holds the rows: a RECORD's "highest sub-index
 *  supported", an ARRAY's number of entries). */
#define CO_OD_TAG_SUB0 0x08U
#define CO_OD_TAG_SVC_SHIFT 4U /**< the top bits: CO_OD_SVC_OF(index), the owning service's hook */
/** The bits of object code @p code (CO_OBJ_*) in a tag. */
#define CO_OD_CODE_BITS(code) \
    ((((code) == CO_OBJ_VAR) ? 0U : ((code) == CO_OBJ_ARRAY) ? 1U \
      : ((code) == CO_OBJ_RECORD) ? 2U : 3U) << 1U)
/** The tag of object @p index, of code @p code (CO_OBJ_*), @p hooked or not. */
#define CO_OD_TAG(index, code, hooked) \
    ((uint8_t)((CO_OD_SVC_OF(index) << CO_OD_TAG_SVC_SHIFT) | CO_OD_CODE_BITS(code) | \
               ((hooked) ? CO_OD_TAG_HOOK : 0U)))

/** Initialisers of one co_od_entry_t (the generated dictionaries use them):
 *  rows of its own from row @p rows of co_dev_t.rows, with hook slot
 *  @p hook - 1 (0: none; its rows' RAM offsets then count from the slot),
 *  and shared ones whose RAM offsets count from @p base (no hook). */
#define CO_OD_ENTRY(index, nsubs, hook, code, rows) \
    {(index), (rows), (uint16_t)(((hook) != 0U) ? ((hook) - 1U) : 0U), (nsubs), \
     CO_OD_TAG((index), (code), ((hook) != 0U))}
#define CO_OD_ENTRY_AT(index, nsubs, code, rows, base) \
    {(index), (rows), (base), (nsubs), CO_OD_TAG((index), (code), false)}
/** An entry with its tag as it is (CO_OD_TAG, and CO_OD_TAG_SUB0). */
#define CO_OD_ENTRY_TAG(index, nsubs, rows, base, tag) {(index), (rows), (base), (nsubs), (tag)}

/** The owning service's hook slot + 1 of @p e (CO_OD_SVC_OF), 0: none. */
static inline uint32_t co_od_svc(const co_od_entry_t *e)
{
    return (uint32_t)e->tag >> CO_OD_TAG_SVC_SHIFT;
}

/** Whether @p e has a hook slot (its base). */
static inline bool co_od_hooked(const co_od_entry_t *e)
{
    return (e->tag & CO_OD_TAG_HOOK) != 0U;
}

/** The object code of @p e (CO_OBJ_*). */
static inline uint8_t co_od_code(const co_od_entry_t *e)
{
    uint32_t b = ((uint32_t)e->tag & CO_OD_TAG_CODE) >> 1U;
    return (b == 3U) ? (uint8_t)CO_OBJ_DOMAIN : (uint8_t)(CO_OBJ_VAR + b); /* (VAR, ARRAY, RECORD) */
}

/** Offset of the value of @p s (an entry of @p e) in the RAM image, or in
 *  the ROM image with CO_SUB_ROM. */
static inline uint16_t co_od_off(const co_od_entry_t *e, const co_od_sub_t *s)
{
    return ((s->flags & CO_SUB_ROM) != 0U) ? s->off : (uint16_t)(e->base + s->off);
}

/** One mappable object of a device (co_dev_t.maps, sorted by index and
 *  sub-index): every sub-entry of a fixed-size type that may be mapped into
 *  a PDO (CO_SUB_MAP_T or CO_SUB_MAP_R), with what the PDO engine needs to
 *  copy its value without a dictionary lookup. The generator makes the
 *  table (a dictionary built at run time: co_od_map_table; the daemon's
 *  EDS loader adds a row for each object a default mapping entry names
 *  that is not mappable, so that entry reads back: the PDO engine looks
 *  the object up before it uses a row). */
typedef struct co_od_map {
    uint16_t index;
    uint8_t  sub;
    uint8_t  info;   /**< CO_OD_MAP_SIZE, CO_OD_MAP_SIGNED, CO_OD_MAP_AT_END */
    uint16_t off;    /**< offset of its value in the RAM image (0: not in RAM) */
} co_od_map_t;
#define CO_OD_MAP_SIZE   0x07U /**< info: its type's size - 1 */
#define CO_OD_MAP_SIGNED 0x08U /**< info: a signed type */
#define CO_OD_MAP_AT_END 0x10U /**< info: fewer than 8 bytes of the RAM image from off on */

/** A PDO mapping entry (the UNSIGNED32 index:16 sub:8 bits:8 of CiA 301)
 *  is stored in the RAM image as 16 bits: (reference << CO_OD_MAP_REF_SHIFT)
 *  | (bits - 1), where the reference is 1..7 for the dummy types
 *  0x0001..0x0007 (sub-index 0) and CO_OD_MAP_ROW0 + k for row k of the
 *  device's mappable-object table; 0 is the entry 0x00000000. A device has
 *  at most CO_OD_MAP_ROWS_MAX mappable objects (the generator refuses
 *  more). The dictionary shows such a sub-entry (a row of type UNSIGNED32
 *  and size 2) as its UNSIGNED32 value: co_od.c converts it both ways. */
#define CO_OD_MAP_REF_SHIFT 6U
#define CO_OD_MAP_BITS      0x3FU
#define CO_OD_MAP_ROW0      8U
#define CO_OD_MAP_ROWS_MAX  (1024U - CO_OD_MAP_ROW0)
/** The 16-bit form of a mapping entry of @p bits (1..64) bits of reference
 *  @p ref (CO_OD_MAP_ROW0 + its object's row, or its dummy type). */
#define CO_OD_MAP_ENTRY(ref, bits) \
    ((uint16_t)(((uint32_t)(ref) << CO_OD_MAP_REF_SHIFT) | ((uint32_t)(bits) - 1U)))

/** Stored forms: a sub-entry of type UNSIGNED32 and a size below 4 keeps
 *  its value in the RAM image in a compact form (and its default, and a
 *  stored parameter set); the dictionary's users (SDO, the application's
 *  co_od_read / co_od_write, the EDS) see the UNSIGNED32, co_od.c converts
 *  both ways. Size 2 without CO_SUB_COB16: a PDO mapping entry
 *  (CO_OD_MAP_ENTRY). Size 2 with CO_SUB_COB16: a COB-ID (CiA 301 7.5.2)
 *  of an 11-bit CAN-ID, bits 31 and 30 in bits 15 and 14, the CAN-ID in
 *  bits 10..0 (bits 13..11 are 0); a value with any of bits 29..11 set has
 *  no such form: a write of it is refused (0x06090030) and leaves the old
 *  value. */
#define CO_OD_COB16_CAN_ID 0x07FFU
static inline uint32_t co_od_cob_u32(uint32_t form)
{
    return (form & CO_OD_COB16_CAN_ID) | ((form & 0xC000U) << 16U);
}
/** The 16-bit form of COB-ID @p v (bits 29..11: none, see co_od_cob_fits). */
static inline uint16_t co_od_cob16(uint32_t v)
{
    return (uint16_t)((v & CO_OD_COB16_CAN_ID) | ((v >> 16U) & 0xC000U));
}
static inline bool co_od_cob_fits(uint32_t v)
{
    return (v & 0x3FFFF800U) == 0U;
}

/** The rows of the mappable-object table of a dictionary built at run time
 *  (an EDS loaded by a daemon; the generator writes its own, the same):
 *  at most @p cap rows into @p out (NULL with cap 0: count only); returns
 *  the number of mappable objects (more than @p cap: not all written). */
uint32_t co_od_map_table(const struct co_dev *dev, co_od_map_t *out, uint32_t cap);
/** The 16-bit form of mapping entry @p v in @p dev, CO_OD_MAP_NONE when
 *  it has none (an object that is not in the table, a length of 0 or above
 *  64 bits). */
#define CO_OD_MAP_NONE 0xFFFFFFFFUL
uint32_t co_od_map_ref(const struct co_dev *dev, uint32_t v);
/** The UNSIGNED32 mapping entry of 16-bit form @p ref in @p dev (a form
 *  that names no object reads as 0). */
uint32_t co_od_map_u32(const struct co_dev *dev, uint32_t ref);

/** Value limits. Compared as signed or unsigned according to the type. */
typedef struct co_od_limit {
    int64_t min;
    int64_t max;
} co_od_limit_t;

/** One access as a hook sees it. */
typedef struct co_od_io {
    struct co_node *node;
    const co_od_entry_t *entry;
    const co_od_sub_t *desc;
    void *value;       /**< where the value is stored, NULL with CO_SUB_HOOKIO */
    uint32_t offset;   /**< byte offset of this chunk in the object's value */
    uint8_t *buf;      /**< read: fill it; write: the data of this chunk */
    uint32_t len;      /**< read: capacity in, bytes produced out; write: bytes */
    uint32_t total;    /**< write: announced total size (0 = unknown);
                            read (HOOKIO): set to the total size, 0 if unknown */
    bool last;         /**< write: last chunk; read (HOOKIO): set on the last chunk */
} co_od_io_t;

/**
 * Hooks of one entry.
 * read: for a stored value, called once before the value is read (it may
 *   refresh it, or veto with an error), on the reader's chunk at offset 0
 *   (buf and len: the reader's buffer and capacity, which the value fills
 *   after the hook, whatever it set there); with CO_SUB_HOOKIO called for every
 *   chunk to produce the data, at any offset (again for a retransmission) and
 *   with the capacity the reader has (an SDO block upload asks for up to 56
 *   bytes at a time); fewer bytes than asked are fine, but a chunk shorter
 *   than 7 bytes before io->last ends an SDO block upload with 0x08000000.
 * Data in io->buf is always the wire image (little-endian); io->value points
 * at the stored value (native integers for 16/32/64-bit types).
 * write: for a stored value, called with the complete new value (already
 *   checked against type, size and limits) before it is committed: any error
 *   vetoes the write. Strings and DOMAINs written in segments gather in the
 *   device's staging area (co_dev_t.stage) and the hook is called once with
 *   the whole new value in io->buf (io->value still holds the old one); the
 *   value changes only when the hook accepts it. With CO_SUB_HOOKIO called
 *   for every chunk (the hook stages them itself until io->last).
 */
typedef struct co_od_hook {
    co_err_t (*read)(void *ctx, co_od_io_t *io);
    co_err_t (*write)(void *ctx, co_od_io_t *io);
    void *ctx;
} co_od_hook_t;

/** Find an entry by index (binary search). NULL if absent. */
const co_od_entry_t *co_od_find(const co_od_entry_t *od, uint16_t count, uint16_t index);

/** Find a sub-entry of @p e (an entry of @p dev): its descriptor, written
 *  to @p buf (which the result points to), or NULL if absent. */
const co_od_sub_t *co_od_find_sub(const struct co_dev *dev, const co_od_entry_t *e, uint8_t sub,
                                  co_od_sub_t *buf);

/** Number of sub-indices row @p r of a table describes (1, or a run's). */
static inline uint32_t co_od_run_len(const co_od_sub_t *r)
{
    return ((uint32_t)r->flags >> CO_SUB_RUN_SHIFT) + 1U;
}

/** The descriptor of the @p k-th sub-index (k < co_od_run_len(r)) of row
 *  @p r (its sub-index r->sub + 1 - co_od_run_len(r) + k), written to
 *  @p buf; returns @p buf. */
const co_od_sub_t *co_od_row_sub(const co_od_sub_t *r, uint32_t k, co_od_sub_t *buf);

/** Size in bytes of a fixed-size type, 0 for strings and DOMAIN. */
uint8_t co_type_size(uint8_t type);

#endif /* CO_OD_H */
