/*
 * Object dictionary: lookup, the single access path, limits, defaults.
 */
#include <string.h>

#include "co/co_endian.h"
#include "co_priv.h"

/* The largest power of two not above @p n (> 0). */
static inline uint32_t pow2_floor(uint32_t n)
{
#if defined(__GNUC__)
    return (uint32_t)1U << (31U - (uint32_t)__builtin_clz(n));
#else
    uint32_t p = 1U;
    while ((p << 1U) <= n) {
        p <<= 1U;
    }
    return p;
#endif
}

/* Binary search over the entries sorted by index, in steps of powers of
 * two: the first step leaves a range of a power of two entries, which each
 * further step halves without a branch on the comparison (a conditional
 * move); the one entry left is compared at the end. */
CO_INLINE const co_od_entry_t *find(const co_od_entry_t *od, uint32_t count, uint16_t index)
{
    const co_od_entry_t *e = od;
    uint32_t step;

    if (!CO_FAST) {
        /* (a build for size: the plain search, over the n entries from e) */
        uint32_t n = count;
        while (n != 0U) {
            const co_od_entry_t *m = &e[n >> 1U];
            if (m->index == index) {
                return m;
            }
            if (m->index < index) {
                e = &m[1];
                n = (n - 1U) >> 1U; /* (the entries after m) */
            } else {
                n >>= 1U; /* (the entries before m) */
            }
        }
        return NULL;
    }
    if (count == 0U) {
        return NULL;
    }
    step = pow2_floor(count);
    e = (e[count - step].index <= index) ? &e[count - step] : e;
    for (step >>= 1U; step != 0U; step >>= 1U) {
        e = (e[step].index <= index) ? &e[step] : e;
    }
    return (e->index == index) ? e : NULL;
}

/* The descriptor of element @p k of row @p r, sub-index @p sub (one body
 * for row_sub and scan_sub). */
static inline const co_od_sub_t *run_elem(const co_od_sub_t *r, uint8_t sub, uint32_t k,
                                          co_od_sub_t *buf)
{
    *buf = *r;
    buf->sub = sub;
    buf->flags &= CO_SUB_FLAGS;
    if ((buf->flags & CO_SUB_ROM) == 0U) {
        buf->off = (uint16_t)(buf->off + (k * buf->size)); /* (ROM: one value for the run) */
    }
    return buf;
}

/* The descriptor of element @p k of row @p r (of a run, the sub-index
 * k places after its first). */
static inline const co_od_sub_t *row_sub(const co_od_sub_t *r, uint32_t k, co_od_sub_t *buf)
{
    return run_elem(r, (uint8_t)((r->sub + 1U + k) - co_od_run_len(r)), k, buf);
}

const co_od_sub_t *co_od_row_sub(const co_od_sub_t *r, uint32_t k, co_od_sub_t *buf)
{
    return row_sub(r, k, buf);
}

/* The descriptor of @p sub of @p e, an entry of @p dev, from the row that
 * holds it (of a run, the one @p d before its last: its element n - 1 - d),
 * in @p buf. (A build for speed keeps it out of the lookup's hot path, a
 * build for size inlines it: one copy in co_od_lookup, whose calls are the
 * only ones it links.) */
#if CO_FAST
CO_NOINLINE static const co_od_sub_t *scan_sub(const co_dev_t *dev, const co_od_entry_t *e,
                                               uint8_t sub, co_od_sub_t *buf)
#else
CO_INLINE const co_od_sub_t *scan_sub(const co_dev_t *dev, const co_od_entry_t *e, uint8_t sub,
                                      co_od_sub_t *buf)
#endif
{
    const co_od_sub_t *r = co_od_rows(dev, e);

    if ((sub == 0U) && ((e->tag & CO_OD_TAG_SUB0) != 0U)) {
        /* the highest sub-index: the last row's, in the ROM image */
        buf->sub = 0U;
        buf->type = (uint8_t)CO_UNSIGNED8;
        buf->flags = CO_SUB_R | CO_SUB_CONST | CO_SUB_ROM;
        buf->size = 1U;
        ptrdiff_t at = &r[e->nsubs - 1U].sub - dev->rom;
        buf->off = (uint16_t)at;
#if CO_LIMITS
        buf->limit = 0U;
#endif
        return buf;
    }
    for (uint32_t i = e->nsubs; i > 0U; i--) {
        uint32_t d = (uint8_t)(r->sub - sub);
        uint32_t n = co_od_run_len(r);
        if (d < n) {
            return run_elem(r, sub, n - 1U - d, buf);
        }
        r++;
    }
    return NULL;
}

/* The descriptor of @p sub of @p e, an entry of @p dev (scan_sub); a build
 * for speed first looks at the row in its dense slot (arrays and most
 * records are dense; a run's row is never there: co_od.h) and gives it
 * itself, no copy. */
CO_INLINE const co_od_sub_t *find_sub(const co_dev_t *dev, const co_od_entry_t *e, uint8_t sub,
                                      co_od_sub_t *buf)
{
    if (CO_FAST && (sub < e->nsubs) && (co_od_rows(dev, e)[sub].sub == sub)) {
        return &co_od_rows(dev, e)[sub];
    }
    return scan_sub(dev, e, sub, buf);
}

const co_od_entry_t *co_od_find(const co_od_entry_t *od, uint16_t count, uint16_t index)
{
    return find(od, count, index);
}

/* (the other finds call co_od_find: in a build for size, the search is one function) */

/* The descriptor of @p sub of @p e in @p buf (a copy of a row that is
 * one, a build for speed) */
static inline const co_od_sub_t *fill(const co_od_sub_t *s, co_od_sub_t *buf)
{
    if (CO_FAST && (s != NULL) && (s != buf)) {
        *buf = *s;
    }
    return (s != NULL) ? buf : NULL;
}

const co_od_sub_t *co_od_find_sub(const co_dev_t *dev, const co_od_entry_t *e, uint8_t sub,
                                  co_od_sub_t *buf)
{
    return fill(find_sub(dev, e, sub, buf), buf);
}

/* Indexed by type 0x00..0x1F (0x1C..0x1F: no type); 0 for variable-length
 * types. */
const uint8_t co_type_sizes[CO_TYPE_SIZES] = {
    0, 1, 1, 2, 4, 1, 2, 4, 4, 0, 0, 0, 6, 6, 0, 0,
    3, 8, 5, 6, 7, 8, 3, 0, 5, 6, 7, 8, 0, 0, 0, 0
};

uint8_t co_type_size(uint8_t type)
{
    /* (any byte: the core's own co_type_len takes the dictionary's types) */
    return (type <= (uint8_t)CO_UNSIGNED64) ? co_type_len(type) : 0U;
}


bool co_type_is_signed(uint8_t type)
{
    return (type == (uint8_t)CO_INTEGER8) || (type == (uint8_t)CO_INTEGER16) ||
           (type == (uint8_t)CO_INTEGER24) || (type == (uint8_t)CO_INTEGER32) ||
           (type == (uint8_t)CO_INTEGER40) || (type == (uint8_t)CO_INTEGER48) ||
           (type == (uint8_t)CO_INTEGER56) || (type == (uint8_t)CO_INTEGER64);
}

/* @p index / @p sub: *e, and in *s its descriptor (find_sub: @p buf or a
 * row of the table). */
CO_HOT co_err_t lookup(const co_node_t *node, uint16_t index, uint8_t sub,
                       const co_od_entry_t **e, const co_od_sub_t **s, co_od_sub_t *buf)
{
    const co_dev_t *dev = node->dev;

    /* (a build for size: one copy of the search, co_od_find's) */
    *e = CO_FAST ? find(dev->od, dev->od_count, index) : co_od_find(dev->od, dev->od_count, index);
    if (*e == NULL) {
        return (CO_SET(node, sdo.unknown_object) == CO_SDO_ABORT_NO_ACCESS) ? CO_ERR_NO_ACCESS
                                                                         : CO_ERR_NO_OBJECT;
    }
    *s = find_sub(dev, *e, sub, buf);
    return (*s == NULL) ? CO_ERR_NO_SUB : CO_OK;
}

co_err_t co_od_lookup(const co_node_t *node, uint16_t index, uint8_t sub,
                      const co_od_entry_t **e, co_od_sub_t *s)
{
    const co_od_sub_t *p = NULL;
    co_err_t err = lookup(node, index, sub, e, &p, s);

    (void)fill(p, s);
    return err;
}

static co_err_t check_access(const co_node_t *node, const co_od_sub_t *s, bool write)
{
    if (write) {
        /* (a writable const, CO_SUB_ROM | CO_SUB_W, is a command a service
         * takes: 0x1010 / 0x1011 without storage, co_store_is_command) */
        if ((s->flags & (CO_SUB_W | CO_SUB_CONST)) != CO_SUB_W) {
            return (CO_SET(node, sdo.read_only) == CO_SDO_ABORT_NO_ACCESS) ? CO_ERR_NO_ACCESS
                                                                        : CO_ERR_READ_ONLY;
        }
    } else if ((s->flags & CO_SUB_R) == 0U) {
        return CO_ERR_WRITE_ONLY;
    } else {
        /* readable */
    }
    return CO_OK;
}

/* (a build for size: the descriptor always in @p buf) */
CO_HOT co_err_t lookup_for(const co_node_t *node, uint16_t index, uint8_t sub, bool write,
                           const co_od_entry_t **e, const co_od_sub_t **s, co_od_sub_t *buf)
{
    co_err_t err;

    if (CO_FAST) {
        err = lookup(node, index, sub, e, s, buf);
    } else {
        err = co_od_lookup(node, index, sub, e, buf);
        *s = buf;
    }
    return (err == CO_OK) ? check_access(node, *s, write) : err;
}

/* (one function at -Os: its callers stay small) */
CO_NOINLINE co_err_t co_od_lookup_for(const co_node_t *node, uint16_t index, uint8_t sub,
                                      bool write, const co_od_entry_t **e, co_od_sub_t *s)
{
    const co_od_sub_t *p = NULL;
    co_err_t err = lookup_for(node, index, sub, write, e, &p, s);

    (void)fill(p, s);
    return err;
}

/* The current size of the value @p v of @p s: strings up to their first
 * NUL character, other values their size. */
static uint32_t data_size(const uint8_t *v, const co_od_sub_t *s)
{
    uint32_t n = s->size;

    if ((s->type == (uint8_t)CO_VISIBLE_STRING) || (s->type == (uint8_t)CO_UNICODE_STRING)) {
        /* the text ends at the first NUL character: a zero byte, a zero
         * UTF-16 unit (a loop: memchr costs more flash) */
        uint32_t w = (s->type == (uint8_t)CO_UNICODE_STRING) ? 2U : 1U;
        uint32_t i = 0U;
        while (((i + w) <= n) && ((v[i] != 0U) || (v[i + w - 1U] != 0U))) {
            i += w;
        }
        n = i;
    }
    return n;
}

/* ------------------------------------------------------ service hooks */

/* The hook of the service that owns @p e (its slot, co_od_svc, is set with
 * the table: CO_OD_SVC_OF), or NULL. */
static inline const co_svc_hook_t *svc_hook(const co_od_entry_t *e)
{
    return (co_od_svc(e) != 0U) ? &co_svc_hooks[co_od_svc(e) - 1U] : NULL;
}

/* Before a stored value is read: the owning service's read hook. */
static inline co_err_t svc_read(co_node_t *node, const co_od_entry_t *e, const co_od_sub_t *s)
{
    const co_svc_hook_t *h = svc_hook(e);

    return ((h != NULL) && ((h->ops & CO_SVC_READ) != 0U))
               ? h->fn(node, CO_SVC_READ, e, s, NULL, 0U)
               : CO_OK;
}

/* A write of an object a service owns: that service runs at the next
 * co_node_process (its deadlines may have changed), unless its hook says
 * what changed itself (CO_SVC_SELF). */
static void touch_owner(co_node_t *node, const co_svc_hook_t *h)
{
    if ((h != NULL) && ((h->ops & CO_SVC_SELF) == 0U)) {
        co_svc_touch(node, h->row);
    }
}

/* Where the RAM value of @p index / @p sub, of @p type (0: any), is, or NULL
 * (absent, another type, not in RAM). */
uint8_t *co_od_ram_of(co_node_t *node, uint16_t index, uint8_t sub, uint8_t type)
{
    const co_od_entry_t *e;
    co_od_sub_t s;

    if ((co_od_lookup(node, index, sub, &e, &s) != CO_OK) || ((type != 0U) && (s.type != type)) ||
        ((s.flags & (CO_SUB_ROM | CO_SUB_HOOKIO)) != 0U)) {
        return NULL;
    }
    return &node->ram[(uint16_t)(e->base + s.off)]; /* (a RAM value) */
}

uint8_t co_od_array_len(co_node_t *node, uint16_t index, uint8_t type, uint8_t max)
{
    /* sub 1.. of that type, RAM values one after the other (from sub 1's) */
    const uint8_t *next = NULL;
    uint8_t n = 0U;

    while (n < max) {
        const uint8_t *at = co_od_ram_of(node, index, (uint8_t)(n + 1U), type);
        if ((at == NULL) || ((n != 0U) && (at != next))) {
            break;
        }
        next = &at[co_type_len(type)];
        n++;
    }
    return n;
}

/* ------------------------------------------------------ application hooks */

static inline co_od_hook_t *hook_of(const co_node_t *node, const co_od_entry_t *e)
{
    /* (a hooked entry's base is its slot) */
    uint32_t slot = co_od_hooked(e) ? e->base : 0xFFFFU;

    if (slot >= node->dev->n_hooks) {
        return NULL;
    }
    /* (the table in the RAM image's storage, aligned: co_dev_t.hooks_at) */
    return &((co_od_hook_t *)(void *)&node->ram[node->dev->hooks_at])[slot];
}

/* The entry's application hook, read or (@p write) write, on @p io (the
 * caller sets offset, buf, len, total and last, this the rest). Without
 * such a hook: CO_ERR_NO_ACCESS for a value without storage (CO_SUB_HOOKIO:
 * nothing else produces or takes it), else CO_OK (nothing to do). */
CO_NOINLINE static co_err_t app_io(co_node_t *node, const co_od_entry_t *e, const co_od_sub_t *s,
                                   bool write, co_od_io_t *io)
{
    co_od_hook_t *h = hook_of(node, e);
    co_err_t (*fn)(void *ctx, co_od_io_t *io) = NULL;

    if (h != NULL) {
        fn = write ? h->write : h->read;
    }
    if (fn == NULL) {
        return ((s->flags & CO_SUB_HOOKIO) != 0U) ? CO_ERR_NO_ACCESS : CO_OK;
    }
    io->node = node;
    io->entry = e;
    io->desc = s;
    io->value = co_od_loc(node, e, s);
    return fn(h->ctx, io);
}

co_err_t co_od_read_part(co_node_t *node, const co_od_entry_t *e, const co_od_sub_t *s,
                         co_od_chunk_t *c)
{
    const uint8_t *v;
    uint8_t fixed = co_type_len(s->type);
    uint32_t offset = c->offset;
    uint32_t cap = c->len;
    uint32_t size;
    uint32_t n;
    uint32_t mapped;

    if ((s->flags & CO_SUB_HOOKIO) != 0U) {
        /* the hook produces the chunk (never more than asked for) */
        co_err_t err = app_io(node, e, s, false, c);
        if (c->len > cap) {
            c->len = cap;
        }
        return err;
    }
    if (offset == 0U) {
        /* before a stored value is read: the owning service's hook, then
         * the application's (either may refresh it or veto) */
        co_err_t err = svc_read(node, e, s);
        if ((err == CO_OK) && (!CO_FAST || co_od_hooked(e))) {
            /* (on the reader's chunk: what the hook may set there is set
             * anew below; a build for size asks app_io without looking
             * first: no hook, nothing to do) */
            err = app_io(node, e, s, false, c);
        }
        if (err != CO_OK) {
            return err;
        }
    }
    v = (const uint8_t *)co_od_loc(node, e, s);
    if ((fixed != 0U) && (s->size != fixed)) {
        /* a stored form (co_od.h): a COB-ID's or a PDO mapping entry's
         * UNSIGNED32 from its 16 bits */
        uint16_t form;
        (void)memcpy(&form, v, sizeof form);
        mapped = ((s->flags & CO_SUB_COB16) != 0U) ? co_od_cob_u32(form)
                                                    : co_od_map_u32(node->dev, form);
        v = (const uint8_t *)&mapped;
    }
    size = (fixed != 0U) ? fixed : data_size(v, s);
    n = (offset < size) ? (size - offset) : 0U;
    if (n > cap) {
        n = cap;
    }
    if ((fixed != 0U) && (offset == 0U) && (n == fixed) && (CO_FAST || !CO_NATIVE_LE)) {
        co_to_wire(c->buf, v, fixed); /* the whole value (a build for size: the copy below) */
    } else if ((fixed != 0U) && !CO_NATIVE_LE) {
        /* part of a number: from its wire image (on a little-endian CPU
         * the stored bytes are the wire image: the copy below) */
        uint8_t wire[8];
        co_to_wire(wire, v, fixed);
        co_copy(c->buf, &wire[offset], n);
    } else {
        co_copy(c->buf, &v[offset], n); /* (n may be 0) */
    }
    c->len = n;
    c->total = size;
    c->last = (offset + n) >= size;
    return CO_OK;
}

#if CO_LIMITS
static uint64_t load_uint(const uint8_t *p, uint8_t n)
{
    uint64_t v = 0U;
    for (uint8_t i = n; i > 0U; i--) {
        v = (v << 8U) | p[i - 1U];
    }
    return v;
}

/* A value against its entry in the device's limit table. */
static co_err_t check_range(const co_od_limit_t *lim, uint8_t type, const uint8_t *data,
                            uint8_t n)
{
    uint64_t raw = load_uint(data, n);

    if (co_type_is_signed(type)) {
        int64_t v;
        if ((n < 8U) && ((raw >> ((8U * n) - 1U)) != 0U)) {
            raw |= ~((UINT64_C(1) << (8U * n)) - 1U); /* sign-extend */
        }
        v = (int64_t)raw;
        if (v < lim->min) {
            return CO_ERR_VALUE_LOW;
        }
        if (v > lim->max) {
            return CO_ERR_VALUE_HIGH;
        }
    } else if ((type != (uint8_t)CO_REAL32) && (type != (uint8_t)CO_REAL64)) {
        if (raw < (uint64_t)lim->min) {
            return CO_ERR_VALUE_LOW;
        }
        if (raw > (uint64_t)lim->max) {
            return CO_ERR_VALUE_HIGH;
        }
    } else {
        /* REAL limits are not checked by the core (use a hook). */
    }
    return CO_OK;
}
#endif

static co_err_t check_limits(const co_node_t *node, const co_od_sub_t *s, const uint8_t *data,
                             uint32_t len)
{
    if (s->type == (uint8_t)CO_BOOLEAN) {
        return (data[0] > 1U) ? CO_ERR_VALUE : CO_OK;
    }
#if CO_LIMITS
    if (((s->flags & CO_SUB_LIMIT) != 0U) && (node->dev->limits != NULL) && (len <= 8U)) {
        return check_range(&node->dev->limits[s->limit], s->type, data, (uint8_t)len);
    }
#else
    (void)node;
    (void)len;
#endif
    return CO_OK;
}

/* ------------------------------------------------ PDO mapping entries */

/* The key a row of the mappable-object table is sorted by. */
static inline uint32_t map_key(const co_od_map_t *m)
{
    return ((uint32_t)m->index << 8U) | m->sub;
}

uint32_t co_od_map_ref(const co_dev_t *dev, uint32_t v)
{
    /* (a write of a mapping entry, rare: the forms of its length one by
     * one, the dummy types' and the rows', until one reads as @p v) */
    for (uint32_t r = 1U; r < (CO_OD_MAP_ROW0 + dev->n_maps); r++) {
        uint32_t form = CO_OD_MAP_ENTRY(r, v & 0xFFU);
        if (co_od_map_u32(dev, form) == v) {
            return form;
        }
    }
    return (v == 0U) ? 0U : CO_OD_MAP_NONE;
}

/* UNSIGNED32 @p wire (wire bytes) of @p s into @p v in its stored form
 * (co_od.h): a COB-ID's 16 bits (write_value refused one without), or a
 * mapping entry's (an entry that has none, which the PDO service's check
 * refuses, leaves the old one). */
CO_NOINLINE static void form_put(const co_dev_t *dev, const co_od_sub_t *s, uint8_t *v,
                                 const uint8_t *wire)
{
    uint32_t x = co_get_u32(wire);
    uint32_t ref = ((s->flags & CO_SUB_COB16) != 0U) ? co_od_cob16(x) : co_od_map_ref(dev, x);

    if (ref != CO_OD_MAP_NONE) {
        uint16_t r16 = (uint16_t)ref;
        (void)memcpy(v, &r16, sizeof r16);
    }
}

uint32_t co_od_map_u32(const co_dev_t *dev, uint32_t ref)
{
    uint32_t r = (ref & 0xFFFFU) >> CO_OD_MAP_REF_SHIFT;
    uint32_t bits = (ref & CO_OD_MAP_BITS) + 1U;

    if (r >= CO_OD_MAP_ROW0) {
        r -= CO_OD_MAP_ROW0;
        /* (a form that names no row reads as the empty entry) */
        return (r < dev->n_maps) ? ((map_key(&dev->maps[r]) << 8U) | bits) : 0U;
    }
    return (r == 0U) ? 0U : ((r << 16U) | bits); /* the empty entry, a dummy type */
}

/* The engine's commit (co_od_commit): a checked value of @p s from wire
 * bytes into its RAM place. */
CO_INLINE void commit_value(co_node_t *node, const co_od_entry_t *e, const co_od_sub_t *s,
                      const uint8_t *data, uint32_t len)
{
    uint8_t fixed = co_type_len(s->type);

    if ((s->flags & (CO_SUB_ROM | CO_SUB_HOOKIO)) == 0U) {
        uint8_t *v = &node->ram[(uint16_t)(e->base + s->off)]; /* a RAM value */
        if ((fixed != 0U) && (s->size != fixed)) {
            /* a stored form: a COB-ID's, a PDO mapping entry's (the PDO
             * service's check found the object mappable: it has one) */
            form_put(node->dev, s, v, data);
        } else if ((fixed != 0U) && (CO_FAST || !CO_NATIVE_LE)) {
            co_pdo_from_wire(v, data, fixed); /* 1, 2 and 4 bytes without a call */
        } else {
            /* (a build for size on a little-endian CPU: a number's wire
             * bytes are its value, len its size) */
            if (data != v) {
                /* (a value gathered in place is its own data) */
                co_copy(v, data, len);
            }
            if (len < s->size) {
                /* a string or DOMAIN shorter than its capacity (a number
                 * comes whole: len is its type's size, which is its size,
                 * as odgen and the EDS loader lay it out) */
                (void)memset(&v[len], 0, s->size - len);
            }
        }
    }
}

void co_od_commit(co_node_t *node, const co_od_entry_t *e, const co_od_sub_t *s,
                  const uint8_t *data, uint32_t len)
{
    commit_value(node, e, s, data, len);
}

CO_HOT co_err_t write_value(co_node_t *node, const co_od_entry_t *e, const co_od_sub_t *s,
                            const uint8_t *data, uint32_t len)
{
    const co_svc_hook_t *sh;
    co_err_t err;
    uint8_t fixed = co_type_len(s->type);
    uint8_t ops;

    if (fixed != 0U) {
        if (len != fixed) {
            return CO_ERR_TYPE_MISMATCH;
        }
    } else if (len > s->size) {
        if ((s->flags & CO_SUB_HOOKIO) == 0U) {
            return CO_ERR_TYPE_TOO_LONG;
        }
    } else {
        /* fits */
    }
    err = check_limits(node, s, data, len);
    if (err != CO_OK) {
        return err;
    }
    sh = svc_hook(e);
    ops = (sh != NULL) ? sh->ops : 0U;
    if ((ops & CO_SVC_CHECK) != 0U) {
        err = sh->fn(node, CO_SVC_CHECK, e, s, data, len);
        if (err != CO_OK) {
            return err;
        }
    }
    if (!CO_FAST || co_od_hooked(e) || ((s->flags & CO_SUB_HOOKIO) != 0U)) {
        /* (a build for size asks app_io without looking first: no hook,
         * nothing to do) */
        /* the application's hook with the whole value (none for a value
         * without storage: no access) */
        co_od_io_t io = {NULL, NULL, NULL, NULL, 0U, (uint8_t *)(uintptr_t)data, len, len, true};
        err = app_io(node, e, s, true, &io);
        if (err != CO_OK) {
            return err;
        }
    }
    if (CO_FAST && ((ops & CO_SVC_COMMIT) != 0U)) {
        /* (a build for speed: the commit's result returned at once, the
         * plain write's path below without this case) */
        touch_owner(node, sh);
        return sh->fn(node, CO_SVC_COMMIT, e, s, data, len);
    }
    if ((ops & CO_SVC_COMMIT) != 0U) {
        err = sh->fn(node, CO_SVC_COMMIT, e, s, data, len); /* the service's commit */
    } else if (CO_FAST && (fixed != 0U) && ((s->flags & (CO_SUB_ROM | CO_SUB_HOOKIO)) == 0U) &&
               (s->size == fixed)) {
        co_pdo_from_wire(&node->ram[(uint16_t)(e->base + s->off)], data, fixed); /* a number: no call */
    } else if (CO_STORAGE) {
        co_od_commit(node, e, s, data, len); /* (one copy: the store service commits too) */
    } else {
        commit_value(node, e, s, data, len); /* (its only caller: inlined) */
    }
    touch_owner(node, sh);
    if ((ops & (CO_SVC_COMMIT | CO_SVC_WRITTEN)) == CO_SVC_WRITTEN) {
        (void)sh->fn(node, CO_SVC_WRITTEN, e, s, NULL, 0U); /* (a commit's result is the answer) */
    }
    return err;
}

co_err_t co_od_write_value(co_node_t *node, const co_od_entry_t *e, const co_od_sub_t *s,
                           const uint8_t *data, uint32_t len)
{
    return write_value(node, e, s, data, len);
}

co_err_t co_od_download(co_node_t *node, uint16_t index, uint8_t sub, const uint8_t *data,
                        uint32_t size)
{
    const co_od_entry_t *e;
    co_od_sub_t sd;
    const co_od_sub_t *s = &sd;
    co_err_t err = CO_FAST ? lookup_for(node, index, sub, true, &e, &s, &sd)
                           : co_od_lookup_for(node, index, sub, true, &e, &sd);
    uint8_t fixed;

    if (err != CO_OK) {
        return err;
    }
    fixed = co_type_len(s->type);
    if (fixed == 0U) {
        /* longer than the object: 0x06070012, size indicated or not */
        co_od_chunk_t c = {NULL, NULL, NULL, NULL, 0U, (uint8_t *)(uintptr_t)data,
                           (size != 0U) ? size : 4U, size, true};
        return co_od_write_part(node, e, s, &c);
    }
    if (size == 0U) {
        size = (fixed < 4U) ? fixed : 4U; /* size not indicated: what the object needs */
    }
    return CO_FAST ? write_value(node, e, s, data, size) : co_od_write_value(node, e, s, data, size);
}

co_err_t co_od_write_part(co_node_t *node, const co_od_entry_t *e, const co_od_sub_t *s,
                          co_od_chunk_t *c)
{
    uint32_t offset = c->offset;
    uint32_t len = c->len;
    const uint8_t *data = c->buf;
    bool last = c->last;

    if ((s->flags & CO_SUB_HOOKIO) != 0U) {
        return app_io(node, e, s, true, c); /* the hook takes every chunk */
    }
    if ((s->flags & CO_SUB_ROM) != 0U) {
        return CO_ERR_NO_ACCESS;
    }
    /* (a value in a stored form, co_od.h, comes whole as its UNSIGNED32) */
    uint32_t room = co_type_len(s->type);
    if (room == 0U) {
        room = s->size;
    }
    if ((offset > room) || (len > (room - offset))) {
        return CO_ERR_TYPE_TOO_LONG;
    }
    if ((offset == 0U) && last) {
        return co_od_write_value(node, e, s, data, len); /* whole: nothing to gather */
    }
    if (room != s->size) {
        return CO_ERR_TYPE_TOO_LONG; /* (a stored form: no parts gather in its place) */
    }
    {
        /* parts gather in the staging area (co_dev_t.stage) when it holds the
         * value; without one they are written in place */
        uint16_t to = (node->dev->stage_size >= s->size) ? node->dev->stage
                                                          : (uint16_t)(e->base + s->off);
        uint8_t *at = &node->ram[to];
        co_copy(&at[offset], data, len);
        /* complete: checked, hooked and committed as one value (the write
         * hook may veto it, the value is unchanged then unless it was
         * gathered in place) */
        return last ? co_od_write_value(node, e, s, at, offset + len) : CO_OK;
    }
}

/* Restore [0, to) of the RAM image: zeros, then the default runs (co_od.h)
 * that start inside it; a $NODEID run gets the node-ID (a PDO or EMCY
 * COB-ID the COB-ID base, which differs from it only with LSS) added to its
 * value. The runs come as wire bytes: a CPU that is not known to be
 * little-endian turns its numbers of 2, 4 and 8 bytes to its own order. */
void co_od_restore(co_node_t *node, uint16_t to)
{
    const co_dev_t *dev = node->dev;
    const uint8_t *d = dev->defaults;
    uint32_t at = 0U;

    (void)memset(node->ram, 0, to);
    for (uint32_t i = dev->n_defaults; i > 0U; i--) {
        uint32_t h = d[1];
        uint32_t w = (h & CO_OD_DEF_W) >> 4U;
        uint32_t n = ((h & CO_OD_DEF_N) + 1U) << w;
        uint8_t *p;
        at += d[0];
        if (at >= to) {
            break; /* (the runs are in the order of their places) */
        }
        p = &node->ram[at];
        co_copy(p, &d[2], n);
        if ((h & CO_OD_DEF_NODEID) != 0U) {
            /* added byte by byte from the least significant one, as the
             * value's own width wraps it */
            uint32_t sum = ((h & CO_OD_DEF_COB) != 0U) ? co_node_cob_base(node) : node->node_id;
            for (uint32_t k = 0U; k < n; k++) {
                sum += p[k];
                p[k] = (uint8_t)sum;
                sum >>= 8U;
            }
        }
        if (!CO_NATIVE_LE && (w != 0U)) {
            for (uint32_t k = 0U; k < n; k += (1U << w)) {
                co_from_wire(&p[k], &p[k], (uint8_t)(1U << w));
            }
        }
        at += n;
        d = &d[2U + n];
    }
}

/* ------------------------------------------------------------ public API */

co_err_t co_od_read(co_node_t *node, uint16_t index, uint8_t sub, void *buf, uint32_t cap,
                    uint32_t *len)
{
    const co_od_entry_t *e;
    co_od_sub_t sd;
    const co_od_sub_t *s = &sd;
    co_od_chunk_t c = {NULL, NULL, NULL, NULL, 0U, (uint8_t *)buf, cap, 0U, false};
    co_err_t err = co_od_lookup(node, index, sub, &e, &sd);

    if (err != CO_OK) {
        return err;
    }
    err = co_od_read_part(node, e, s, &c);
    if (err == CO_OK) {
        *len = c.len;
        if (!c.last) {
            err = CO_ERR_TYPE_TOO_LONG; /* the caller's buffer is too small */
        }
    }
    return err;
}

co_err_t co_od_write(co_node_t *node, uint16_t index, uint8_t sub, const void *data,
                     uint32_t len, bool as_app)
{
    const co_od_entry_t *e;
    co_od_sub_t sd;
    const co_od_sub_t *s = &sd;
    co_err_t err = co_od_lookup(node, index, sub, &e, &sd);

    if ((err == CO_OK) && !as_app) {
        err = check_access(node, s, true);
    }
    if ((err == CO_OK) && as_app && ((s->flags & (CO_SUB_ROM | CO_SUB_W)) == CO_SUB_ROM)) {
        err = CO_ERR_READ_ONLY; /* (a writable const is a command: check_access) */
    }
    if ((err == CO_OK) && ((s->flags & CO_SUB_COB16) != 0U) && (len == 4U) &&
        !co_od_cob_fits(co_get_u32((const uint8_t *)data))) {
        /* a COB-ID without a 16-bit form (co_od.h; the services' checks refuse
         * one over SDO, the generator gives a COB-ID no service checks its
         * form only where SDO cannot write it) */
        err = CO_ERR_VALUE;
    }
    if (err == CO_OK) {
        if (co_od_is_streamed(s) && ((s->flags & CO_SUB_HOOKIO) != 0U)) {
            co_od_chunk_t c = {NULL, NULL, NULL, NULL, 0U, (uint8_t *)(uintptr_t)data, len, len,
                               true};
            err = co_od_write_part(node, e, s, &c);
        } else {
            err = co_od_write_value(node, e, s, (const uint8_t *)data, len);
        }
    }
    return err;
}

void *co_od_value_ptr(co_node_t *node, uint16_t index, uint8_t sub)
{
    return co_od_ram_of(node, index, sub, 0U);
}

co_result_t co_od_bind_hook(co_node_t *node, uint16_t index, const co_od_hook_t *hook)
{
    const co_od_entry_t *e = co_od_find(node->dev->od, node->dev->od_count, index);
    co_od_hook_t *h;

    if (e == NULL) {
        return CO_RESULT_NO_OBJECT;
    }
    h = hook_of(node, e);
    if (h == NULL) {
        return CO_RESULT_NO_HOOK_SLOT;
    }
    if ((h->read != NULL) || (h->write != NULL)) {
        return CO_RESULT_HOOK_BOUND; /* two plug-ins on one object: the first stays */
    }
    *h = *hook;
    return CO_RESULT_OK;
}
