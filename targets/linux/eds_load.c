/*
 * EDS/DCF loader: CiA 306 text -> co_dev_t in memory (eds_load.h).
 *
 * Two steps: the INI layer (sections and keys with their line numbers,
 * case-insensitive names, ';' comments, CRLF) and the builder (objects and
 * sub-entries with their types, access, values and limits; the RAM image laid
 * out communication / application / not stored, each value at its natural
 * alignment, sub-entries of one object back to back; the PDO table).
 */
#include "eds_load.h"

#include <ctype.h>
#include <errno.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#define EDS_MAX_SIZE (16UL * 1024UL * 1024UL) /* larger files are refused */
#define STR_MIN_CAP 32U                        /* writable strings hold at least this */

/* ------------------------------------------------------------ INI layer */

typedef struct kv {
    const char *key;
    const char *val;
    unsigned line;
} kv_t;

typedef struct sec {
    const char *name;
    unsigned line;
    size_t first;   /* index of the first key in ini.kv */
    size_t n;
} sec_t;

typedef struct ini {
    char *buf;
    kv_t *kv;
    size_t nkv;
    size_t capkv;
    sec_t *sec;
    size_t nsec;
    size_t capsec;
} ini_t;

/* one sub-entry while building */
typedef struct bsub {
    co_od_sub_t s;
    uint8_t *val;        /* default, native representation, s.size bytes */
    int has_limit;
    co_od_limit_t lim;
} bsub_t;

typedef struct bobj {
    uint16_t index;
    uint8_t code;
    const sec_t *sec;
    size_t first;        /* index into subs */
    size_t n;
} bobj_t;

struct eds_dev {
    co_dev_t dev;
    char *text;
    char *name;
    char summary[160];
    co_od_entry_t *entries;
    co_od_sub_t *subs;
    uint8_t *defaults;
    co_od_limit_t *limits;
    co_pdo_desc_t *pdo;
    co_od_map_t *maps;
    char *warnings;
};

typedef struct ctx {
    const char *file;
    char *err;
    size_t errcap;
    ini_t ini;
    bobj_t *obj;
    size_t nobj;
    size_t capobj;
    bsub_t *sub;
    size_t nsub;
    size_t capsub;
    char *warn;          /* warning lines, '\n'-terminated */
    size_t nwarn;
} ctx_t;

static int fail(ctx_t *c, const sec_t *s, const kv_t *k, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));

/* "FILE:LINE: [SECTION] KEY: problem" */
static int fail(ctx_t *c, const sec_t *s, const kv_t *k, const char *fmt, ...)
{
    va_list ap;
    int n;

    if (k != NULL) {
        n = snprintf(c->err, c->errcap, "%s:%u: [%s] %s: ", c->file, k->line,
                     (s != NULL) ? s->name : "", k->key);
    } else if (s != NULL) {
        n = snprintf(c->err, c->errcap, "%s:%u: [%s]: ", c->file, s->line, s->name);
    } else {
        n = snprintf(c->err, c->errcap, "%s: ", c->file);
    }
    if ((n >= 0) && ((size_t)n < c->errcap)) {
        va_start(ap, fmt);
        (void)vsnprintf(c->err + n, c->errcap - (size_t)n, fmt, ap);
        va_end(ap);
    }
    return -1;
}

static int skip(ctx_t *c, const sec_t *s, const kv_t *k, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));

/* A warning line "FILE:LINE: [SECTION] KEY: problem"; returns 1 (skip). */
static int skip(ctx_t *c, const sec_t *s, const kv_t *k, const char *fmt, ...)
{
    char line[320];
    va_list ap;
    int n;
    char *q;

    n = snprintf(line, sizeof line, "%s:%u: [%s]%s%s: ", c->file,
                 (k != NULL) ? k->line : ((s != NULL) ? s->line : 0U),
                 (s != NULL) ? s->name : "", (k != NULL) ? " " : "", (k != NULL) ? k->key : "");
    if ((n < 0) || ((size_t)n >= sizeof line)) {
        return 1;
    }
    va_start(ap, fmt);
    (void)vsnprintf(line + n, sizeof line - (size_t)n, fmt, ap);
    va_end(ap);
    q = (char *)realloc(c->warn, c->nwarn + strlen(line) + 2U);
    if (q != NULL) {
        c->warn = q;
        (void)memcpy(&c->warn[c->nwarn], line, strlen(line));
        c->nwarn += strlen(line);
        c->warn[c->nwarn++] = '\n';
        c->warn[c->nwarn] = '\0';
    }
    return 1;
}

static void *grow(void *p, size_t *cap, size_t n, size_t elem)
{
    if (n < *cap) {
        return p;
    }
    size_t nc = (*cap != 0U) ? (*cap * 2U) : 64U;
    void *q = realloc(p, nc * elem);
    if (q != NULL) {
        *cap = nc;
    }
    return q;
}

static char *trim(char *s)
{
    while ((*s != '\0') && isspace((unsigned char)*s)) {
        s++;
    }
    size_t n = strlen(s);
    while ((n > 0U) && isspace((unsigned char)s[n - 1U])) {
        s[--n] = '\0';
    }
    return s;
}

static int ini_parse(ctx_t *c, const char *text)
{
    ini_t *ini = &c->ini;
    unsigned line = 0U;
    char *p;

    ini->buf = strdup(text);
    if (ini->buf == NULL) {
        return fail(c, NULL, NULL, "out of memory");
    }
    p = ini->buf;
    while (*p != '\0') {
        char *eol = strchr(p, '\n');
        char *next = (eol != NULL) ? (eol + 1) : (p + strlen(p));
        char *l;

        if (eol != NULL) {
            *eol = '\0';
        }
        line++;
        l = trim(p);
        p = next;
        if ((*l == '\0') || (*l == ';')) {
            continue;
        }
        if (*l == '[') {
            char *end = strchr(l, ']');
            void *q = grow(ini->sec, &ini->capsec, ini->nsec, sizeof *ini->sec);
            if (q == NULL) {
                return fail(c, NULL, NULL, "out of memory");
            }
            ini->sec = (sec_t *)q;
            if (end == NULL) {
                sec_t bad = {l, line, 0U, 0U};
                return fail(c, &bad, NULL, "section name without ']'");
            }
            *end = '\0';
            ini->sec[ini->nsec].name = trim(l + 1);
            ini->sec[ini->nsec].line = line;
            ini->sec[ini->nsec].first = ini->nkv;
            ini->sec[ini->nsec].n = 0U;
            ini->nsec++;
            continue;
        }
        {
            char *eq = strchr(l, '=');
            void *q;
            if (ini->nsec == 0U) {
                kv_t bad = {l, "", line};
                return fail(c, NULL, &bad, "a key before the first section");
            }
            if (eq == NULL) {
                kv_t bad = {l, "", line};
                return fail(c, &ini->sec[ini->nsec - 1U], &bad, "a line without '='");
            }
            q = grow(ini->kv, &ini->capkv, ini->nkv, sizeof *ini->kv);
            if (q == NULL) {
                return fail(c, NULL, NULL, "out of memory");
            }
            ini->kv = (kv_t *)q;
            *eq = '\0';
            ini->kv[ini->nkv].key = trim(l);
            ini->kv[ini->nkv].val = trim(eq + 1);
            ini->kv[ini->nkv].line = line;
            ini->nkv++;
            ini->sec[ini->nsec - 1U].n++;
        }
    }
    return 0;
}

static const sec_t *find_sec(const ctx_t *c, const char *name)
{
    for (size_t i = 0U; i < c->ini.nsec; i++) {
        if (strcasecmp(c->ini.sec[i].name, name) == 0) {
            return &c->ini.sec[i];
        }
    }
    return NULL;
}

/* the last occurrence of @p key in @p s (a later line wins), NULL if absent */
static const kv_t *find_kv(const ctx_t *c, const sec_t *s, const char *key)
{
    const kv_t *found = NULL;

    if (s == NULL) {
        return NULL;
    }
    for (size_t i = 0U; i < s->n; i++) {
        const kv_t *k = &c->ini.kv[s->first + i];
        if (strcasecmp(k->key, key) == 0) {
            found = k;
        }
    }
    return found;
}

/* ------------------------------------------------------------ values */

typedef enum kind { K_UINT, K_INT, K_REAL, K_VSTR, K_USTR, K_BYTES } kind_t;

typedef struct tinfo {
    uint8_t type;
    kind_t kind;
    uint8_t len;     /* bytes of a fixed-size type, 0 for strings / DOMAIN */
} tinfo_t;

static const tinfo_t types[] = {
    {(uint8_t)CO_BOOLEAN, K_UINT, 1U},        {(uint8_t)CO_INTEGER8, K_INT, 1U},
    {(uint8_t)CO_INTEGER16, K_INT, 2U},       {(uint8_t)CO_INTEGER32, K_INT, 4U},
    {(uint8_t)CO_UNSIGNED8, K_UINT, 1U},      {(uint8_t)CO_UNSIGNED16, K_UINT, 2U},
    {(uint8_t)CO_UNSIGNED32, K_UINT, 4U},     {(uint8_t)CO_REAL32, K_REAL, 4U},
    {(uint8_t)CO_VISIBLE_STRING, K_VSTR, 0U}, {(uint8_t)CO_OCTET_STRING, K_BYTES, 0U},
    {(uint8_t)CO_UNICODE_STRING, K_USTR, 0U}, {(uint8_t)CO_TIME_OF_DAY, K_UINT, 6U},
    {(uint8_t)CO_TIME_DIFFERENCE, K_UINT, 6U}, {(uint8_t)CO_DOMAIN, K_BYTES, 0U},
    {(uint8_t)CO_INTEGER24, K_INT, 3U},       {(uint8_t)CO_REAL64, K_REAL, 8U},
    {(uint8_t)CO_INTEGER40, K_INT, 5U},       {(uint8_t)CO_INTEGER48, K_INT, 6U},
    {(uint8_t)CO_INTEGER56, K_INT, 7U},       {(uint8_t)CO_INTEGER64, K_INT, 8U},
    {(uint8_t)CO_UNSIGNED24, K_UINT, 3U},     {(uint8_t)CO_UNSIGNED40, K_UINT, 5U},
    {(uint8_t)CO_UNSIGNED48, K_UINT, 6U},     {(uint8_t)CO_UNSIGNED56, K_UINT, 7U},
    {(uint8_t)CO_UNSIGNED64, K_UINT, 8U},
};

static const tinfo_t *type_info(uint8_t t)
{
    for (size_t i = 0U; i < (sizeof types / sizeof types[0]); i++) {
        if (types[i].type == t) {
            return &types[i];
        }
    }
    return NULL;
}

/* A number as CiA 306 writes it: decimal, 0x hex or leading-0 octal, optionally
 * negative. 0: ok, -1: not a number. */
static int parse_num(const char *s, int64_t *sv, uint64_t *uv, int *neg)
{
    char *end = NULL;

    errno = 0;
    while (isspace((unsigned char)*s)) {
        s++;
    }
    if (*s == '\0') {
        return -1;
    }
    *neg = (*s == '-');
    if (*neg) {
        long long v = strtoll(s, &end, 0);
        *sv = (int64_t)v;
        *uv = (uint64_t)*sv;
    } else {
        unsigned long long v = strtoull(s, &end, 0);
        *uv = (uint64_t)v;
        *sv = (int64_t)*uv;
    }
    while ((end != NULL) && isspace((unsigned char)*end)) {
        end++;
    }
    return ((errno != 0) || (end == NULL) || (*end != '\0')) ? -1 : 0;
}

/* Strips "$NODEID" and the '+' next to it from @p in into @p out; returns 1
 * when it was there. */
static int strip_nodeid(const char *in, char *out, size_t cap)
{
    const char *p = in;
    size_t n = 0U;
    int found = 0;

    while ((*p != '\0') && (n + 1U < cap)) {
        if (strncasecmp(p, "$NODEID", 7U) == 0) {
            found = 1;
            p += 7;
            continue;
        }
        out[n++] = *p++;
    }
    out[n] = '\0';
    if (found) {
        /* "0x180+" or "+0x180" left: drop the operator */
        char *t = trim(out);
        size_t l = strlen(t);
        if ((l > 0U) && (t[l - 1U] == '+')) {
            t[l - 1U] = '\0';
        } else if (*t == '+') {
            t++;
        } else {
            /* "$NODEID" alone */
        }
        (void)memmove(out, t, strlen(t) + 1U);
        if (*trim(out) == '\0') {
            (void)strcpy(out, "0");
        }
    }
    return found;
}

/* an integer value of @p len bytes: range check, two's complement bits in *bits */
static int int_bits(const tinfo_t *ti, const char *text, uint64_t *bits, int64_t *as_limit)
{
    int64_t sv;
    uint64_t uv;
    int neg;
    unsigned w = 8U * ti->len;
    uint64_t mask = (w == 64U) ? UINT64_MAX : ((UINT64_C(1) << w) - 1U);

    if (parse_num(text, &sv, &uv, &neg) != 0) {
        return -1;
    }
    if (neg) {
        int64_t lo = (w == 64U) ? INT64_MIN : -(int64_t)(UINT64_C(1) << (w - 1U));
        if ((ti->kind != K_INT) || (sv < lo)) {
            return -1;
        }
        *bits = (uint64_t)sv & mask;
        *as_limit = sv;
        return 0;
    }
    if ((uv & ~mask) != 0U) {
        return -1;
    }
    *bits = uv;
    if ((ti->kind == K_INT) && (w < 64U) && ((uv >> (w - 1U)) != 0U)) {
        /* hex written two's complement (0xFFFF for -1 in INTEGER16) */
        *as_limit = (int64_t)(uv | ~mask);
    } else {
        *as_limit = (int64_t)uv;
    }
    return 0;
}

static int hexval(int ch)
{
    if ((ch >= '0') && (ch <= '9')) {
        return ch - '0';
    }
    ch = tolower(ch);
    return ((ch >= 'a') && (ch <= 'f')) ? (ch - 'a' + 10) : -1;
}

/* OCTET_STRING / DOMAIN: hex digits, spaces allowed; an optional 0x prefix */
static long hex_bytes(const char *text, uint8_t *out)
{
    long n = 0;
    int hi = -1;

    if ((text[0] == '0') && ((text[1] == 'x') || (text[1] == 'X'))) {
        text += 2;
    }
    for (; *text != '\0'; text++) {
        int v;
        if (isspace((unsigned char)*text)) {
            continue;
        }
        v = hexval((unsigned char)*text);
        if (v < 0) {
            return -1;
        }
        if (hi < 0) {
            hi = v;
        } else {
            if (out != NULL) {
                out[n] = (uint8_t)((hi << 4) | v);
            }
            n++;
            hi = -1;
        }
    }
    return (hi < 0) ? n : -1;
}

/* UTF-8 text -> UTF-16LE units (BMP; other code points and bad bytes
 * become U+FFFD); the number of units. @p out may be NULL. */
static size_t utf8_units(const char *text, uint8_t *out)
{
    const unsigned char *p = (const unsigned char *)text;
    size_t n = 0U;

    while (*p != '\0') {
        uint32_t cp = 0xFFFDU;
        unsigned extra = 0U;
        if (*p < 0x80U) {
            cp = *p;
        } else if ((*p & 0xE0U) == 0xC0U) {
            cp = *p & 0x1FU;
            extra = 1U;
        } else if ((*p & 0xF0U) == 0xE0U) {
            cp = *p & 0x0FU;
            extra = 2U;
        } else if ((*p & 0xF8U) == 0xF0U) {
            extra = 3U;
        } else {
            /* a stray continuation byte */
        }
        p++;
        for (unsigned k = 0U; k < extra; k++) {
            if ((*p & 0xC0U) != 0x80U) {
                cp = 0xFFFDU;
                break;
            }
            cp = (cp << 6) | (*p & 0x3FU);
            p++;
        }
        if ((extra == 3U) || (cp > 0xFFFFU)) {
            cp = 0xFFFDU;
        }
        if (out != NULL) {
            out[2U * n] = (uint8_t)(cp & 0xFFU);
            out[(2U * n) + 1U] = (uint8_t)(cp >> 8);
        }
        n++;
    }
    return n;
}

static void put_native(uint8_t *dst, uint64_t bits, uint8_t len)
{
    switch (len) {
    case 2U: {
        uint16_t v = (uint16_t)bits;
        (void)memcpy(dst, &v, 2U);
        break;
    }
    case 4U: {
        uint32_t v = (uint32_t)bits;
        (void)memcpy(dst, &v, 4U);
        break;
    }
    case 8U:
        (void)memcpy(dst, &bits, 8U);
        break;
    default: /* 1, 3, 5, 6, 7 bytes: wire order (little-endian) */
        for (uint8_t k = 0U; k < len; k++) {
            dst[k] = (uint8_t)(bits >> (8U * k));
        }
        break;
    }
}

/* ------------------------------------------------------------ objects */

typedef struct subspec {
    const sec_t *sec;      /* where the keys are */
    uint8_t sub;
    const kv_t *override;  /* [xxxxValue] entry of a compact object, or NULL */
    int compact_count;     /* >= 0: sub 0 of a compact object holding this */
} subspec_t;

static int access_flags(ctx_t *c, const sec_t *s, const kv_t *k, int mappable, uint16_t *flags)
{
    static const struct {
        const char *name;
        uint16_t flags;
        uint16_t map;
    } acc[] = {
        {"ro", CO_SUB_R, CO_SUB_MAP_T},
        {"wo", CO_SUB_W, CO_SUB_MAP_R},
        {"rw", CO_SUB_RW, CO_SUB_MAP},
        {"rwr", CO_SUB_RW, CO_SUB_MAP_T},
        {"rww", CO_SUB_RW, CO_SUB_MAP_R},
        {"const", (uint16_t)(CO_SUB_R | CO_SUB_CONST), CO_SUB_MAP_T},
    };
    if (k == NULL) {
        return fail(c, s, NULL, "AccessType missing");
    }
    for (size_t i = 0U; i < (sizeof acc / sizeof acc[0]); i++) {
        if (strcasecmp(k->val, acc[i].name) == 0) {
            *flags = (uint16_t)(acc[i].flags | (mappable ? acc[i].map : 0U));
            return 0;
        }
    }
    return fail(c, s, k, "unknown access type '%s' (ro, wo, rw, rwr, rww, const)", k->val);
}

static int limit_of(ctx_t *c, const sec_t *s, const tinfo_t *ti, const char *key, int64_t *v)
{
    const kv_t *k = find_kv(c, s, key);
    uint64_t bits;
    char num[128];

    if ((k == NULL) || (k->val[0] == '\0')) {
        return 0;
    }
    if ((ti->kind != K_INT) && (ti->kind != K_UINT)) {
        return 0; /* REAL limits are not checked by the core */
    }
    (void)strip_nodeid(k->val, num, sizeof num);
    if (int_bits(ti, num, &bits, v) != 0) {
        return fail(c, s, k, "'%s' is not a value of the object's data type", k->val);
    }
    return 1;
}

static int add_sub(ctx_t *c, const subspec_t *sp, uint16_t index)
{
    const sec_t *s = sp->sec;
    const kv_t *kt = find_kv(c, s, "DataType");
    const kv_t *kacc = find_kv(c, s, "AccessType");
    const kv_t *kmap = find_kv(c, s, "PDOMapping");
    const kv_t *kval = find_kv(c, s, "ParameterValue");
    const tinfo_t *ti;
    bsub_t *b;
    int64_t sv;
    uint64_t uv;
    int neg;
    int mappable = 0;
    const char *text;
    char num[128];
    void *q;

    q = grow(c->sub, &c->capsub, c->nsub, sizeof *c->sub);
    if (q == NULL) {
        return fail(c, NULL, NULL, "out of memory");
    }
    c->sub = (bsub_t *)q;
    b = &c->sub[c->nsub];
    (void)memset(b, 0, sizeof *b);
    c->nsub++; /* counted at once, so that ctx_free / a skip release its value */
    b->s.sub = sp->sub;
    if (sp->compact_count >= 0) {
        /* sub 0 of a CompactSubObj object: NrOfObjects, UNSIGNED8 ro */
        b->s.type = (uint8_t)CO_UNSIGNED8;
        b->s.flags = CO_SUB_R;
        b->s.size = 1U;
        b->val = (uint8_t *)calloc(1U, 1U);
        if (b->val == NULL) {
            return fail(c, NULL, NULL, "out of memory");
        }
        b->val[0] = (uint8_t)sp->compact_count;
        return 0;
    }
    if (kt == NULL) {
        return fail(c, s, NULL, "DataType missing");
    }
    if ((parse_num(kt->val, &sv, &uv, &neg) != 0) || (uv > 0xFFFFU)) {
        return fail(c, s, kt, "'%s' is not a data type index", kt->val);
    }
    ti = type_info((uint8_t)uv);
    if ((ti == NULL) || (uv > 0xFFU)) {
        return skip(c, s, kt, "object 0x%04X skipped: data type 0x%04X is not a CiA 301 basic "
                    "type", index, (unsigned)uv);
    }
    if (kmap != NULL) {
        if ((parse_num(kmap->val, &sv, &uv, &neg) != 0) || (uv > 1U)) {
            return fail(c, s, kmap, "'%s' is not 0 or 1", kmap->val);
        }
        mappable = (uv == 1U);
    }
    if (access_flags(c, s, kacc, mappable, &b->s.flags) != 0) {
        return -1;
    }
    b->s.type = ti->type;
    if (sp->override != NULL) {
        kval = sp->override;
    } else if ((kval == NULL) || (kval->val[0] == '\0')) {
        kval = find_kv(c, s, "DefaultValue");
    } else {
        /* DCF: ParameterValue wins over DefaultValue */
    }
    text = (kval != NULL) ? kval->val : "";

    switch (ti->kind) {
    case K_UINT:
    case K_INT: {
        uint64_t bits = 0U;
        int64_t dummy;
        int nodeid = strip_nodeid(text, num, sizeof num);
        if (nodeid && (ti->len != 1U) && (ti->len != 2U) && (ti->len != 4U)) {
            return fail(c, s, kval, "$NODEID in a %u-byte value (8, 16 or 32 bits only)",
                        (unsigned)ti->len);
        }
        if ((num[0] != '\0') && (int_bits(ti, num, &bits, &dummy) != 0)) {
            return fail(c, s, kval, "'%s' is not a value of data type 0x%04X", text,
                        (unsigned)ti->type);
        }
        if (nodeid) {
            b->s.flags |= CO_SUB_NODEID;
        }
        b->s.size = ti->len;
        b->val = (uint8_t *)calloc(1U, ti->len);
        if (b->val == NULL) {
            return fail(c, NULL, NULL, "out of memory");
        }
        put_native(b->val, bits, ti->len);
        {
            int64_t lo = 0;
            int64_t hi = 0;
            int has_lo = limit_of(c, s, ti, "LowLimit", &lo);
            int has_hi = limit_of(c, s, ti, "HighLimit", &hi);
            unsigned w = 8U * ti->len;
            if ((has_lo < 0) || (has_hi < 0)) {
                return -1;
            }
            if (has_lo || has_hi) {
                if (!has_lo) {
                    lo = (ti->kind == K_INT) ? ((w == 64U) ? INT64_MIN
                                                           : -(int64_t)(UINT64_C(1) << (w - 1U)))
                                             : 0;
                }
                if (!has_hi) {
                    hi = (ti->kind == K_INT)
                             ? ((w == 64U) ? INT64_MAX : (int64_t)((UINT64_C(1) << (w - 1U)) - 1U))
                             : ((w == 64U) ? -1 : (int64_t)((UINT64_C(1) << w) - 1U));
                }
                b->has_limit = 1;
                b->lim.min = lo;
                b->lim.max = hi;
            }
        }
        break;
    }
    case K_REAL: {
        char *end = NULL;
        double d = 0.0;
        if (text[0] != '\0') {
            errno = 0;
            d = strtod(text, &end);
            if ((errno != 0) || (end == text) || (*trim(end) != '\0')) {
                return fail(c, s, kval, "'%s' is not a REAL value", text);
            }
        }
        b->s.size = ti->len;
        b->val = (uint8_t *)calloc(1U, ti->len);
        if (b->val == NULL) {
            return fail(c, NULL, NULL, "out of memory");
        }
        if (ti->len == 4U) {
            float f = (float)d;
            (void)memcpy(b->val, &f, 4U);
        } else {
            (void)memcpy(b->val, &d, 8U);
        }
        break;
    }
    case K_VSTR:
    case K_USTR: {
        size_t n = (ti->kind == K_USTR) ? utf8_units(text, NULL) : strlen(text);
        size_t unit = (ti->kind == K_USTR) ? 2U : 1U;
        size_t cap = n * unit;
        if (((b->s.flags & CO_SUB_W) != 0U) && (cap < STR_MIN_CAP)) {
            cap = STR_MIN_CAP;
        }
        if (cap == 0U) {
            cap = unit;
        }
        if (cap > 0xFFFFU) {
            return fail(c, s, kval, "a string of %zu bytes (at most 65535)", cap);
        }
        b->s.size = (uint16_t)cap;
        b->val = (uint8_t *)calloc(1U, cap);
        if (b->val == NULL) {
            return fail(c, NULL, NULL, "out of memory");
        }
        if (ti->kind == K_USTR) {
            (void)utf8_units(text, b->val); /* UTF-16LE of the text */
        } else {
            (void)memcpy(b->val, text, n);
        }
        break;
    }
    default: { /* K_BYTES: OCTET_STRING, DOMAIN */
        long n = hex_bytes(text, NULL);
        int raw = (n < 0);
        size_t cap;
        if (raw && (ti->type != (uint8_t)CO_DOMAIN)) {
            return fail(c, s, kval, "'%s' is not hex bytes", text);
        }
        if (raw) {
            /* not hex (objdictgen writes DOMAIN values as text): the text's bytes */
            (void)skip(c, s, kval, "'%s' is not hex bytes: taken as the text's bytes", text);
            n = (long)strlen(text);
        }
        cap = (size_t)n;
        if ((cap == 0U) && ((b->s.flags & CO_SUB_W) != 0U)) {
            cap = STR_MIN_CAP;
        }
        if (cap > 0xFFFFU) {
            return fail(c, s, kval, "%zu bytes (at most 65535)", cap);
        }
        b->s.size = (uint16_t)cap;
        b->val = (uint8_t *)calloc(1U, (cap != 0U) ? cap : 1U);
        if (b->val == NULL) {
            return fail(c, NULL, NULL, "out of memory");
        }
        if (raw) {
            (void)memcpy(b->val, text, cap);
        } else {
            (void)hex_bytes(text, b->val);
        }
        break;
    }
    }
    return 0;
}

static int cmp_u8(const void *a, const void *b)
{
    return (int)((const subspec_t *)a)->sub - (int)((const subspec_t *)b)->sub;
}

/* "1A00" -> index; "1A00sub3" -> index, sub; else -1 */
static int parse_name(const char *name, unsigned *index, int *sub)
{
    unsigned v = 0U;

    for (int i = 0; i < 4; i++) {
        int h = hexval((unsigned char)name[i]);
        if (h < 0) {
            return -1;
        }
        v = (v << 4) | (unsigned)h;
    }
    *index = v;
    if (name[4] == '\0') {
        *sub = -1;
        return 0;
    }
    if (strncasecmp(&name[4], "sub", 3U) != 0 || name[7] == '\0') {
        return -1;
    }
    {
        unsigned s = 0U;
        for (const char *p = &name[7]; *p != '\0'; p++) {
            int h = hexval((unsigned char)*p);
            if ((h < 0) || (s > 0xFFU)) {
                return -1;
            }
            s = (s << 4) | (unsigned)h;
        }
        if (s > 0xFFU) {
            return -1;
        }
        *sub = (int)s;
    }
    return 0;
}

static int add_object(ctx_t *c, const sec_t *os, unsigned index)
{
    const kv_t *kot = find_kv(c, os, "ObjectType");
    const kv_t *kcompact = find_kv(c, os, "CompactSubObj");
    uint64_t code = CO_OBJ_VAR;
    int64_t sv;
    int neg;
    subspec_t specs[256];
    size_t n = 0U;
    bobj_t *o;
    void *q;

    if ((kot != NULL) && (kot->val[0] != '\0') &&
        ((parse_num(kot->val, &sv, &code, &neg) != 0) || (code > 0xFFU))) {
        return fail(c, os, kot, "'%s' is not an object type", kot->val);
    }
    if ((code == 5U) || (code == 6U) || (code == 0U)) {
        return 0; /* DEFTYPE / DEFSTRUCT / NULL: not a value of the device */
    }
    if ((code != CO_OBJ_VAR) && (code != CO_OBJ_DOMAIN) && (code != CO_OBJ_ARRAY) &&
        (code != CO_OBJ_RECORD)) {
        return fail(c, os, kot, "object type 0x%X (VAR 7, DOMAIN 2, ARRAY 8, RECORD 9)",
                    (unsigned)code);
    }
    if ((code == CO_OBJ_VAR) || (code == CO_OBJ_DOMAIN)) {
        specs[n].sec = os;
        specs[n].sub = 0U;
        specs[n].override = NULL;
        specs[n].compact_count = -1;
        n++;
    } else if ((kcompact != NULL) && (kcompact->val[0] != '\0') &&
               (strcmp(kcompact->val, "0") != 0)) {
        uint64_t cnt;
        char vname[16];
        const sec_t *vals;
        if ((parse_num(kcompact->val, &sv, &cnt, &neg) != 0) || (cnt < 1U) || (cnt > 254U)) {
            return fail(c, os, kcompact, "'%s' is not a number of sub-entries (1..254)",
                        kcompact->val);
        }
        (void)snprintf(vname, sizeof vname, "%04XValue", index);
        vals = find_sec(c, vname);
        specs[n].sec = os;
        specs[n].sub = 0U;
        specs[n].override = NULL;
        specs[n].compact_count = (int)cnt;
        n++;
        for (unsigned k = 1U; k <= (unsigned)cnt; k++) {
            char key[8];
            const kv_t *kv;
            (void)snprintf(key, sizeof key, "%u", k);
            kv = find_kv(c, vals, key);
            specs[n].sec = os;
            specs[n].sub = (uint8_t)k;
            specs[n].override = ((kv != NULL) && (kv->val[0] != '\0')) ? kv : NULL;
            specs[n].compact_count = -1;
            n++;
        }
    } else {
        for (size_t i = 0U; i < c->ini.nsec; i++) {
            unsigned idx;
            int sub;
            if ((parse_name(c->ini.sec[i].name, &idx, &sub) == 0) && (idx == index) && (sub >= 0)) {
                for (size_t j = 0U; j < n; j++) {
                    if (specs[j].sub == (uint8_t)sub) {
                        return fail(c, &c->ini.sec[i], NULL, "sub-index %d given twice", sub);
                    }
                }
                if (n >= 255U) {
                    return fail(c, &c->ini.sec[i], NULL, "more than 255 sub-entries");
                }
                specs[n].sec = &c->ini.sec[i];
                specs[n].sub = (uint8_t)sub;
                specs[n].override = NULL;
                specs[n].compact_count = -1;
                n++;
            }
        }
        if (n == 0U) {
            return skip(c, os, NULL, "object 0x%04X skipped: an ARRAY/RECORD without "
                        "sub-entries", index) - 1;
        }
        qsort(specs, n, sizeof specs[0], cmp_u8);
    }
    q = grow(c->obj, &c->capobj, c->nobj, sizeof *c->obj);
    if (q == NULL) {
        return fail(c, NULL, NULL, "out of memory");
    }
    c->obj = (bobj_t *)q;
    o = &c->obj[c->nobj];
    o->index = (uint16_t)index;
    o->code = (uint8_t)code;
    o->sec = os;
    o->first = c->nsub;
    o->n = n;
    for (size_t i = 0U; i < n; i++) {
        int rc = add_sub(c, &specs[i], (uint16_t)index);
        if (rc > 0) {
            /* the whole object is left out (the reason is in the warnings) */
            while (c->nsub > o->first) {
                free(c->sub[--c->nsub].val);
            }
            return 0;
        }
        if (rc != 0) {
            return -1;
        }
    }
    c->nobj++;
    return 0;
}

/* A value of the default image (co_dev_t.defaults), of object @ref index. */
typedef struct def_val {
    const bsub_t *b;
    uint16_t index;
} def_val_t;

static int cmp_def(const void *a, const void *b)
{
    return (int)((const def_val_t *)a)->b->s.off - (int)((const def_val_t *)b)->b->s.off;
}

/* 1 if any of the @p n bytes at @p p is not zero */
static int any_set(const uint8_t *p, size_t n)
{
    for (size_t k = 0U; k < n; k++) {
        if (p[k] != 0U) {
            return 1;
        }
    }
    return 0;
}

/* Append to the default runs @p out (*len bytes, *nd runs, the last ending
 * at *end in the image) the @p n bytes of @p val (native numbers of 1 << w
 * bytes) at @p pos: runs of at most 16 values as wire bytes (co_od.h). */
static void def_run(uint8_t *out, size_t *len, size_t *nd, size_t *end, size_t pos,
                    const uint8_t *val, size_t n, uint32_t w, uint8_t marks)
{
    size_t unit = (size_t)1U << w;

    while ((pos - *end) > 255U) {
        out[(*len)++] = 255U; /* a zero byte after 255 */
        out[(*len)++] = CO_OD_DEF_RUN(1U, 0U);
        out[(*len)++] = 0U;
        *end += 256U;
        (*nd)++;
    }
    for (size_t k = 0U; k < n; k += 16U * unit) {
        size_t m = ((n - k) < (16U * unit)) ? (n - k) : (16U * unit);
        out[(*len)++] = (uint8_t)((pos + k) - *end);
        out[(*len)++] = (uint8_t)(CO_OD_DEF_RUN(m / unit, w) | marks);
        for (size_t j = k; j < (k + m); j += unit) {
            uint64_t v = 0U;
            if (unit == 2U) {
                uint16_t x;
                (void)memcpy(&x, &val[j], 2U);
                v = x;
            } else if (unit == 4U) {
                uint32_t x;
                (void)memcpy(&x, &val[j], 4U);
                v = x;
            } else if (unit == 8U) {
                (void)memcpy(&v, &val[j], 8U);
            } else {
                v = val[j];
            }
            for (size_t b = 0U; b < unit; b++) {
                out[(*len)++] = (uint8_t)(v >> (8U * b)); /* wire order */
            }
        }
        *end = pos + k + m;
        (*nd)++;
    }
}

static int cmp_obj(const void *a, const void *b)
{
    return (int)((const bobj_t *)a)->index - (int)((const bobj_t *)b)->index;
}

/* ------------------------------------------------------------ layout */

static unsigned region_of(uint16_t index)
{
    if ((index == 0x1001U) || (index == 0x1003U) || (index == 0x1010U) || (index == 0x1011U)) {
        return 2U; /* not stored */
    }
    return ((index >= 0x1000U) && (index <= 0x1FFFU)) ? 0U : 1U;
}

static size_t align_of(const co_od_sub_t *s)
{
    const tinfo_t *ti = type_info(s->type);
    /* (a number's size: its type's, but a PDO mapping entry's 16-bit form) */
    size_t len = ((ti != NULL) && (ti->len != 0U)) ? s->size : 0U;

    return ((len == 2U) || (len == 4U) || (len == 8U)) ? len : 1U;
}

/* The mapping object of a PDO communication object (0x1400+n: 0x1600+n,
 * 0x1800+n: 0x1A00+n), NULL if it is none or has none. */
static const bobj_t *pdo_mapping_of(const ctx_t *c, const bobj_t *o)
{
    bobj_t key;

    if (((o->index < 0x1400U) || (o->index > 0x15FFU)) &&
        ((o->index < 0x1800U) || (o->index > 0x19FFU))) {
        return NULL;
    }
    key.index = (uint16_t)(o->index + 0x200U);
    return (const bobj_t *)bsearch(&key, c->obj, c->nobj, sizeof *c->obj, cmp_obj);
}

/* The mapping entries of mapping object @p m the core can run (sub 1..,
 * consecutive UNSIGNED32, at most 8, after a sub 0 UNSIGNED8). */
static size_t pdo_entries(const ctx_t *c, const bobj_t *m)
{
    const bsub_t *b = &c->sub[m->first];
    size_t n = 0U;

    if ((m->n == 0U) || (b[0].s.sub != 0U) || (b[0].s.type != (uint8_t)CO_UNSIGNED8)) {
        return 0U;
    }
    while ((n < 8U) && (n + 1U < m->n) && (b[n + 1U].s.sub == (uint8_t)(n + 1U)) &&
           (b[n + 1U].s.type == (uint8_t)CO_UNSIGNED32)) {
        n++;
    }
    return n;
}

/* Sub-entry @p sub of object @p index, NULL if there is none. */
static const bsub_t *bsub_of(const ctx_t *c, uint16_t index, uint8_t sub)
{
    bobj_t key;
    const bobj_t *o;

    key.index = index;
    o = (const bobj_t *)bsearch(&key, c->obj, c->nobj, sizeof *c->obj, cmp_obj);
    for (size_t k = 0U; (o != NULL) && (k < o->n); k++) {
        if (c->sub[o->first + k].s.sub == sub) {
            return &c->sub[o->first + k];
        }
    }
    return NULL;
}

/* Whether sub @p sub of @p index is absent (@p opt) or of @p type. */
static bool sub_is(const ctx_t *c, uint16_t index, uint8_t sub, co_type_t type, bool opt)
{
    const bsub_t *b = bsub_of(c, index, sub);

    return (b == NULL) ? opt : (b->s.type == (uint8_t)type);
}

/* The default of mapping entry @p b (UNSIGNED32, native), 0 for none. */
static uint32_t entry_default(const bsub_t *b)
{
    uint32_t v = 0U;

    if (b->val != NULL) {
        (void)memcpy(&v, b->val, sizeof v);
    }
    return v;
}

static int cmp_map(const void *a, const void *b)
{
    const co_od_map_t *x = (const co_od_map_t *)a;
    const co_od_map_t *y = (const co_od_map_t *)b;
    uint32_t kx = ((uint32_t)x->index << 8U) | x->sub;
    uint32_t ky = ((uint32_t)y->index << 8U) | y->sub;

    return (kx < ky) ? -1 : (kx > ky) ? 1 : 0;
}

/* The @p n rows of the mappable objects at @p rows (room for one more per
 * sub-entry), with a row of its own for every object a default mapping
 * entry names that is not one of them (absent, or not mappable: a foreign
 * EDS may have such a default; its PDO then waits for a valid mapping, as
 * the core makes of it, and the entry reads back as the EDS says), sorted.
 * Returns their number. */
static uint32_t map_rows(const ctx_t *c, co_od_map_t *rows, uint32_t n)
{
    uint32_t total = n;

    for (size_t i = 0U; i < c->nsub; i++) {
        const bsub_t *b = &c->sub[i];
        uint32_t v;
        co_od_map_t key;
        bool known = false;
        if ((b->s.type != (uint8_t)CO_UNSIGNED32) || (b->s.size != 2U) ||
            ((b->s.flags & CO_SUB_COB16) != 0U)) {
            continue; /* not a mapping entry in its 16-bit form */
        }
        v = entry_default(b);
        if ((v == 0U) || ((((v >> 8U) & 0xFFU) == 0U) && ((v >> 16U) >= 1U) && ((v >> 16U) <= 7U))) {
            continue; /* none, a dummy */
        }
        key.index = (uint16_t)(v >> 16U);
        key.sub = (uint8_t)(v >> 8U);
        key.info = 0U;
        key.off = 0U;
        for (uint32_t k = 0U; (k < total) && !known; k++) {
            known = cmp_map(&rows[k], &key) == 0;
        }
        if (!known) {
            rows[total++] = key;
        }
    }
    qsort(rows, total, sizeof *rows, cmp_map);
    return total;
}

/* Whether the core will run the PDO of communication object @p comm
 * (pdo_scan, before the layout: the types of its parameters and of every
 * PDO of its kind before it, numbered without gaps; default mapping entries
 * of 1..64 bits, which have 16-bit forms): only its mapping
 * entries take their 16-bit forms (co_od.h), which only the PDO service
 * checks. */
static bool pdo_runs(const ctx_t *c, uint16_t comm)
{
    for (uint16_t i = (comm < 0x1800U) ? 0x1400U : 0x1800U; i <= comm; i++) {
        bobj_t key;
        const bobj_t *m;
        key.index = (uint16_t)(i + 0x200U);
        m = (const bobj_t *)bsearch(&key, c->obj, c->nobj, sizeof *c->obj, cmp_obj);
        size_t n = (m != NULL) ? pdo_entries(c, m) : 0U;
        for (size_t e = 1U; e <= n; e++) {
            /* a default of 0 or more than 64 bits has no 16-bit form */
            uint32_t bits = entry_default(&c->sub[m->first + e]) & 0xFFU;
            if ((entry_default(&c->sub[m->first + e]) != 0U) && ((bits == 0U) || (bits > 64U))) {
                return false;
            }
        }
        if ((m == NULL) || (n == 0U) ||
            !sub_is(c, i, 1U, CO_UNSIGNED32, false) || !sub_is(c, i, 2U, CO_UNSIGNED8, false) ||
            !sub_is(c, i, 3U, CO_UNSIGNED16, true) || !sub_is(c, i, 5U, CO_UNSIGNED16, true) ||
            !sub_is(c, i, 6U, CO_UNSIGNED8, true)) {
            return false;
        }
    }
    return true;
}

/* Sub-entry @p b, a COB-ID the core reads, in its 16-bit form (co_od.h,
 * CO_SUB_COB16; its default below). */
static void cob_form(bsub_t *b)
{
    if (b != NULL) {
        b->s.size = 2U;
        b->s.flags |= CO_SUB_COB16;
    }
}

/* Sub-entry @p b at the next offset its alignment allows from *off. */
static void place(ctx_t *c, bsub_t *b, size_t *off, uint8_t *placed, size_t *nlim, size_t *nid)
{
    size_t al = align_of(&b->s);

    *off = (*off + al - 1U) / al * al;
    b->s.off = (uint16_t)((*off <= 0xFFFFU) ? *off : 0U);
    *off += b->s.size;
    placed[b - c->sub] = 1U;
    *nlim += (size_t)b->has_limit;
    *nid += (size_t)((b->s.flags & CO_SUB_NODEID) != 0U);
}

/* Sub-entry @p sub of object @p index if it has type @p type, else NULL. */
static bsub_t *find_sub(ctx_t *c, uint16_t index, uint8_t sub, uint8_t type)
{
    bobj_t key;
    const bobj_t *o;

    key.index = index;
    o = (const bobj_t *)bsearch(&key, c->obj, c->nobj, sizeof *c->obj, cmp_obj);
    for (size_t k = 0U; (o != NULL) && (k < o->n); k++) {
        bsub_t *b = &c->sub[o->first + k];
        if (b->s.sub == sub) {
            return (b->s.type == type) ? b : NULL;
        }
    }
    return NULL;
}

/* The core's objects at their places (co_node.h, CO_RAM_*) from @p base:
 * scalars of @p n places (index, type, offset), then the UNSIGNED32 entries
 * sub 1.. of @p array from @p array_at. An object the device lacks, or
 * has with another type, leaves zeros there (the core's "absent"; such
 * a value gets a place of its own). Returns where the places end. */
typedef struct core_place {
    uint16_t index;
    uint8_t type;
    uint8_t at;
} core_place_t;

static size_t place_core(ctx_t *c, const core_place_t *p, size_t n, uint16_t array,
                         size_t array_at, size_t base, uint8_t *placed, size_t *nlim, size_t *nid)
{
    size_t end = base;

    for (size_t k = 0U; k < n; k++) {
        bsub_t *b = find_sub(c, p[k].index, 0U, p[k].type);
        size_t at = base + p[k].at;
        if (b != NULL) {
            place(c, b, &at, placed, nlim, nid);
        }
        end = base + p[k].at + co_type_size(p[k].type);
    }
    for (uint32_t sub = 1U; sub <= 254U; sub++) {
        bsub_t *b = find_sub(c, array, (uint8_t)sub, (uint8_t)CO_UNSIGNED32);
        size_t at = base + array_at + (4U * (sub - 1U));
        if (b == NULL) {
            break;
        }
        place(c, b, &at, placed, nlim, nid);
        end = at;
    }
    return end;
}

static const co_od_sub_t *find_built(const eds_dev_t *d, uint16_t index, uint8_t sub)
{
    const co_od_entry_t *e = co_od_find(d->entries, d->dev.od_count, index);

    /* (the loader's rows are one sub-index each: no runs) */
    for (uint8_t k = 0U; (e != NULL) && (k < e->nsubs); k++) {
        if (d->subs[e->rows + k].sub == sub) {
            return &d->subs[e->rows + k];
        }
    }
    return NULL;
}

/* Where @p s is from the COB-ID @p cob (co_pdo_desc_t): 1..255, 0 when
 * there is no @p s, above 255 when it is out of reach. */
static uint32_t pdo_rel(const co_od_sub_t *cob, const co_od_sub_t *s)
{
    return (s == NULL) ? 0U : (s->off > cob->off) ? (uint32_t)(s->off - cob->off) : 0x100U;
}

/* the PDOs the core runs: pairs numbered without gaps from 0 */
static size_t pdo_scan(const eds_dev_t *d, uint16_t comm_base, uint16_t map_base,
                       co_pdo_desc_t *out)
{
    size_t n = 0U;

    for (uint16_t k = 0U; k < 0x200U; k++) {
        const co_od_sub_t *cob = find_built(d, (uint16_t)(comm_base + k), 1U);
        const co_od_sub_t *type = find_built(d, (uint16_t)(comm_base + k), 2U);
        const co_od_sub_t *inh = find_built(d, (uint16_t)(comm_base + k), 3U);
        const co_od_sub_t *ev = find_built(d, (uint16_t)(comm_base + k), 5U);
        const co_od_sub_t *start = find_built(d, (uint16_t)(comm_base + k), 6U);
        const co_od_sub_t *cnt = find_built(d, (uint16_t)(map_base + k), 0U);
        const co_od_entry_t *me = co_od_find(d->entries, d->dev.od_count,
                                             (uint16_t)(map_base + k));
        const co_od_sub_t *ms = (me != NULL) ? &d->subs[me->rows] : NULL;
        uint8_t maps = 0U;

        if ((me == NULL) || (cob == NULL) || (cob->type != (uint8_t)CO_UNSIGNED32) || (type == NULL) ||
            (type->type != (uint8_t)CO_UNSIGNED8) || (cnt == NULL) ||
            (cnt->type != (uint8_t)CO_UNSIGNED8) ||
            ((inh != NULL) && (inh->type != (uint8_t)CO_UNSIGNED16)) ||
            ((ev != NULL) && (ev->type != (uint8_t)CO_UNSIGNED16)) ||
            ((start != NULL) && (start->type != (uint8_t)CO_UNSIGNED8))) {
            break;
        }
        while ((maps < 8U) && ((size_t)maps + 1U < me->nsubs) &&
               (ms[maps + 1U].sub == (uint8_t)(maps + 1U)) &&
               (ms[maps + 1U].type == (uint8_t)CO_UNSIGNED32)) {
            maps++;
        }
        if (maps == 0U) {
            break;
        }
        /* (laid out as co_pdo_desc_t wants: build) */
        if ((ms[1].off != (uint16_t)(cnt->off - (2U * maps))) || (ms[1].size != 2U) ||
            (type->off != (uint16_t)(cnt->off + 1U)) || (pdo_rel(cob, start) > 0xFFU) ||
            (pdo_rel(cob, inh) > 0xFFU) || (pdo_rel(cob, ev) > 0xFFU)) {
            break;
        }
        if (out != NULL) {
            out[n].cob = cob->off;
            out[n].count = cnt->off;
            out[n].map_max = maps;
            out[n].start = (uint8_t)pdo_rel(cob, start);
            out[n].inhibit = (uint8_t)pdo_rel(cob, inh);
            out[n].event = (uint8_t)pdo_rel(cob, ev);
        }
        n++;
    }
    return n;
}

static eds_dev_t *build(ctx_t *c, const char *name, const char *text)
{
    eds_dev_t *d = (eds_dev_t *)calloc(1U, sizeof *d);
    size_t off = 0U;
    size_t ends[3] = {0U, 0U, 0U};
    size_t nlim = 0U;
    size_t nid = 0U;
    def_val_t *dv = NULL;
    size_t nr;
    size_t nt;
    uint32_t nmaps;
    uint8_t *placed;

    if (d == NULL) {
        (void)fail(c, NULL, NULL, "out of memory");
        return NULL;
    }
    qsort(c->obj, c->nobj, sizeof *c->obj, cmp_obj);
    for (size_t i = 1U; i < c->nobj; i++) {
        if (c->obj[i].index == c->obj[i - 1U].index) {
            (void)fail(c, c->obj[i].sec, NULL, "object 0x%04X given twice", c->obj[i].index);
            eds_free(d);
            return NULL;
        }
    }
    if (c->nsub > 0xFFFFU) {
        /* (co_od_entry_t.rows: a row number of 16 bits) */
        (void)fail(c, NULL, NULL, "more than 65535 sub-entries");
        eds_free(d);
        return NULL;
    }
    placed = (uint8_t *)calloc((c->nsub != 0U) ? c->nsub : 1U, 1U);
    if (placed == NULL) {
        (void)fail(c, NULL, NULL, "out of memory");
        eds_free(d);
        return NULL;
    }
    /* RAM image: communication, application, not stored, each of the first
     * and the last starting with the core's objects at their places
     * (co_node.h: CO_RAM_*; the last from a multiple of 4, app_end); a PDO's
     * mapping entries, their number and its transmission type one after the
     * other where its communication object is (co_pdo_desc_t) */
    /* the COB-IDs the core reads (SYNC, TIME, EMCY; the PDOs' below) */
    cob_form(find_sub(c, 0x1005U, 0U, (uint8_t)CO_UNSIGNED32));
    cob_form(find_sub(c, 0x1012U, 0U, (uint8_t)CO_UNSIGNED32));
    cob_form(find_sub(c, 0x1014U, 0U, (uint8_t)CO_UNSIGNED32));
    /* (and the SDO server's where only the application writes them) */
    for (uint8_t sub = 1U; sub <= 2U; sub++) {
        bsub_t *b = find_sub(c, 0x1200U, sub, (uint8_t)CO_UNSIGNED32);
        if ((b != NULL) && ((b->s.flags & (CO_SUB_W | CO_SUB_MAP_R)) == 0U)) {
            cob_form(b);
        }
    }
    for (unsigned r = 0U; r < 3U; r++) {
        static const core_place_t head[] = {
            {0x1005U, (uint8_t)CO_UNSIGNED32, CO_RAM_1005},
            {0x1007U, (uint8_t)CO_UNSIGNED32, CO_RAM_1007},
            {0x1014U, (uint8_t)CO_UNSIGNED32, CO_RAM_1014},
            {0x1015U, (uint8_t)CO_UNSIGNED16, CO_RAM_1015},
            {0x1017U, (uint8_t)CO_UNSIGNED16, CO_RAM_1017},
            {0x1019U, (uint8_t)CO_UNSIGNED8, CO_RAM_1019},
        };
        static const core_place_t tail[] = {
            {0x1001U, (uint8_t)CO_UNSIGNED8, CO_RAM_END_1001},
            {0x1003U, (uint8_t)CO_UNSIGNED8, CO_RAM_END_1003},
        };
        if (r == 0U) {
            off = place_core(c, head, sizeof head / sizeof head[0], 0x1016U, CO_RAM_1016, 0U,
                             placed, &nlim, &nid);
        } else if (r == 2U) {
            off = place_core(c, tail, sizeof tail / sizeof tail[0], 0x1003U, CO_RAM_END_1003_1,
                             off, placed, &nlim, &nid);
        } else {
            /* (the application values) */
        }
        for (size_t i = 0U; i < c->nobj; i++) {
            const bobj_t *o = &c->obj[i];
            const bobj_t *m = pdo_mapping_of(c, o);
            size_t n = (m != NULL) ? pdo_entries(c, m) : 0U;
            if (region_of(o->index) != r) {
                continue;
            }
            for (size_t k = 0U; (n != 0U) && (k < o->n); k++) {
                bsub_t *type = &c->sub[o->first + k];
                if ((type->s.sub == 2U) && (type->s.type == (uint8_t)CO_UNSIGNED8)) {
                    bool runs = pdo_runs(c, o->index);
                    for (size_t e = 1U; e <= n; e++) {
                        /* (the entries of a PDO the core runs in their
                         * 16-bit forms: co_od.h) */
                        if (runs) {
                            c->sub[m->first + e].s.size = 2U;
                        }
                        if (runs && (e == 1U)) {
                            cob_form(find_sub(c, o->index, 1U, (uint8_t)CO_UNSIGNED32));
                        }
                        place(c, &c->sub[m->first + e], &off, placed, &nlim, &nid);
                    }
                    place(c, &c->sub[m->first], &off, placed, &nlim, &nid);
                    place(c, type, &off, placed, &nlim, &nid);
                }
            }
            for (size_t k = 0U; k < o->n; k++) {
                if (placed[o->first + k] == 0U) {
                    place(c, &c->sub[o->first + k], &off, placed, &nlim, &nid);
                }
            }
            if (off > 0xFFF8U) {
                (void)fail(c, o->sec, NULL, "the values need more than 65535 bytes of RAM");
                free(placed);
                eds_free(d);
                return NULL;
            }
        }
        if (r == 1U) {
            off = (off + 3U) / 4U * 4U; /* (app_end) */
        }
        ends[r] = off;
    }
    free(placed);
    off = (off + 7U) / 8U * 8U;
    /* the default runs (co_od.h): at most the image's bytes, two header
     * bytes per value and per 16 bytes of one, three per 256 bytes of gap */
    d->text = strdup(text);
    d->name = strdup(name);
    d->defaults = (uint8_t *)calloc(1U, off + (2U * c->nsub) + (off / 8U) + (3U * (off / 256U)) + 16U);
    dv = (def_val_t *)calloc((c->nsub != 0U) ? c->nsub : 1U, sizeof *dv);
    d->entries = (co_od_entry_t *)calloc((c->nobj != 0U) ? c->nobj : 1U, sizeof *d->entries);
    d->subs = (co_od_sub_t *)calloc((c->nsub != 0U) ? c->nsub : 1U, sizeof *d->subs);
    d->limits = (co_od_limit_t *)calloc((nlim != 0U) ? nlim : 1U, sizeof *d->limits);
    if ((d->text == NULL) || (d->name == NULL) || (d->defaults == NULL) || (dv == NULL) ||
        (d->entries == NULL) || (d->subs == NULL) || (d->limits == NULL)) {
        (void)fail(c, NULL, NULL, "out of memory");
        free(dv);
        eds_free(d);
        return NULL;
    }
    nlim = 0U;
    {
        size_t ns = 0U;
        size_t len = 0U;
        size_t nd = 0U;
        size_t end = 0U;
        for (size_t i = 0U; i < c->nobj; i++) {
            const bobj_t *o = &c->obj[i];
            d->entries[i].index = o->index;
            d->entries[i].nsubs = (uint8_t)o->n;
            d->entries[i].tag = CO_OD_TAG(o->index, o->code, false);
            d->entries[i].rows = (uint16_t)ns;
            for (size_t k = 0U; k < o->n; k++) {
                bsub_t *b = &c->sub[o->first + k];
                if (b->has_limit) {
                    b->s.flags |= CO_SUB_LIMIT;
                    b->s.limit = (uint16_t)nlim;
                    d->limits[nlim++] = b->lim;
                }
                dv[ns].b = b;
                dv[ns].index = o->index;
                d->subs[ns++] = b->s;
            }
        }
        /* the mappable objects, which the PDO mapping entries' 16-bit
         * forms name (co_od.h; their defaults below) */
        d->dev.od = d->entries;
        d->dev.rows = d->subs;
        d->dev.od_count = (uint16_t)c->nobj;
        d->dev.ram_size = (uint16_t)off;
        nmaps = co_od_map_table(&d->dev, NULL, 0U);
        /* (room for a row per default mapping entry too: map_rows) */
        d->maps = (co_od_map_t *)calloc(nmaps + c->nsub + 1U, sizeof *d->maps);
        if (d->maps == NULL) {
            (void)fail(c, NULL, NULL, "out of memory");
            free(dv);
            eds_free(d);
            return NULL;
        }
        (void)co_od_map_table(&d->dev, d->maps, nmaps);
        nmaps = map_rows(c, d->maps, nmaps);
        if (nmaps > CO_OD_MAP_ROWS_MAX) {
            (void)fail(c, NULL, NULL, "more than %u mappable objects",
                       (unsigned)CO_OD_MAP_ROWS_MAX);
            free(dv);
            eds_free(d);
            return NULL;
        }
        d->dev.maps = d->maps;
        d->dev.n_maps = (uint16_t)nmaps;
        /* the default runs: the values that are not zero and the $NODEID
         * ones, in the order of their places */
        qsort(dv, ns, sizeof *dv, cmp_def);
        for (size_t i = 0U; i < ns; i++) {
            const bsub_t *b = dv[i].b;
            bool pdo = ((dv[i].index >= 0x1400U) && (dv[i].index <= 0x15FFU)) ||
                       ((dv[i].index >= 0x1800U) && (dv[i].index <= 0x19FFU));
            bool cob = (pdo && (b->s.sub == 1U)) || (dv[i].index == 0x1014U);
            uint8_t marks = ((b->s.flags & CO_SUB_NODEID) == 0U) ? 0U
                            : (uint8_t)(CO_OD_DEF_NODEID | (cob ? CO_OD_DEF_COB : 0U));
            size_t n = b->s.size;
            uint32_t w = 0U;
            const uint8_t *val = b->val;
            uint16_t form = 0U;
            if (((b->s.flags & CO_SUB_COB16) != 0U) && (val != NULL)) {
                /* a COB-ID: its 16-bit form (its node-ID added within bits 10..0) */
                uint32_t v;
                (void)memcpy(&v, val, sizeof v);
                if (!co_od_cob_fits(v) ||
                    ((marks != 0U) && (((v & CO_OD_COB16_CAN_ID) + 127U) > CO_OD_COB16_CAN_ID))) {
                    (void)fail(c, NULL, NULL,
                               "object 0x%04X sub-index %u: default 0x%08X is not an 11-bit COB-ID",
                               (unsigned)dv[i].index, (unsigned)b->s.sub, (unsigned)v);
                    free(dv);
                    eds_free(d);
                    return NULL;
                }
                form = co_od_cob16(v);
                val = (const uint8_t *)&form;
                w = 1U;
            } else if ((co_type_size(b->s.type) == 4U) && (n == 2U) && (val != NULL)) {
                /* a PDO mapping entry: its 16-bit form */
                uint32_t v;
                uint32_t ref;
                (void)memcpy(&v, val, sizeof v);
                ref = co_od_map_ref(&d->dev, v);
                if (ref == CO_OD_MAP_NONE) {
                    (void)fail(c, NULL, NULL,
                               "object 0x%04X sub-index %u: default 0x%08X maps no mappable object",
                               (unsigned)dv[i].index, (unsigned)b->s.sub, (unsigned)v);
                    free(dv);
                    eds_free(d);
                    return NULL;
                }
                form = (uint16_t)ref;
                val = (const uint8_t *)&form;
                w = 1U;
            } else if ((co_type_size(b->s.type) == n) && ((n == 2U) || (n == 4U) || (n == 8U))) {
                w = (n == 2U) ? 1U : (n == 4U) ? 2U : 3U; /* a native number */
            } else if (marks == 0U) {
                while ((n > 0U) && (b->val[n - 1U] == 0U)) {
                    n--; /* (bytes: without the zeros at the end) */
                }
            } else {
                /* one byte */
            }
            if ((val != NULL) && ((marks != 0U) || (any_set(val, n) != 0))) {
                def_run(d->defaults, &len, &nd, &end, b->s.off, val, n, w, marks);
            }
        }
        d->dev.n_defaults = (uint16_t)nd;
        free(dv);
    }
    d->dev.od = d->entries;
    d->dev.rows = d->subs;
    d->dev.od_count = (uint16_t)c->nobj;
    d->dev.ram_size = (uint16_t)off;
    d->dev.comm_end = (uint16_t)ends[0];
    d->dev.app_end = (uint16_t)ends[1];
    d->dev.defaults = d->defaults;
    d->dev.rom = NULL;
    d->dev.limits = (nlim != 0U) ? d->limits : NULL;
    d->dev.n_hooks = 0U;
    (void)memset(&d->dev.set, 0, sizeof d->dev.set); /* CiA 301 */
    nr = pdo_scan(d, 0x1400U, 0x1600U, NULL);
    nt = pdo_scan(d, 0x1800U, 0x1A00U, NULL);
    d->pdo = (co_pdo_desc_t *)calloc(((nr + nt) != 0U) ? (nr + nt) : 1U, sizeof *d->pdo);
    if (d->pdo == NULL) {
        (void)fail(c, NULL, NULL, "out of memory");
        eds_free(d);
        return NULL;
    }
    (void)pdo_scan(d, 0x1400U, 0x1600U, d->pdo);
    (void)pdo_scan(d, 0x1800U, 0x1A00U, &d->pdo[nr]);
    d->dev.pdo = d->pdo;
    d->dev.n_rpdo = (uint16_t)nr;
    d->dev.n_tpdo = (uint16_t)nt;
    /* the PDO states past the image, aligned (co_dev_storage_size) */
    d->dev.pdo_at = (uint16_t)((off + 7U) & ~(size_t)7U);
    {
        const kv_t *prod = find_kv(c, find_sec(c, "DeviceInfo"), "ProductName");
        (void)snprintf(d->summary, sizeof d->summary, "%.60s: %zu objects, %zu RPDOs, %zu TPDOs",
                       ((prod != NULL) && (prod->val[0] != '\0')) ? prod->val : name, c->nobj,
                       nr, nt);
    }
    return d;
}

static void ctx_free(ctx_t *c)
{
    for (size_t i = 0U; i < c->nsub; i++) {
        free(c->sub[i].val);
    }
    free(c->sub);
    free(c->obj);
    free(c->ini.kv);
    free(c->ini.sec);
    free(c->ini.buf);
    free(c->warn);
}

eds_dev_t *eds_load_text(const char *name, const char *text, char *err, size_t errcap)
{
    ctx_t c;
    eds_dev_t *d = NULL;
    int rc;

    (void)memset(&c, 0, sizeof c);
    c.file = name;
    c.err = err;
    c.errcap = errcap;
    rc = ini_parse(&c, text);
    for (size_t i = 0U; (rc == 0) && (i < c.ini.nsec); i++) {
        unsigned index;
        int sub;
        if ((parse_name(c.ini.sec[i].name, &index, &sub) == 0) && (sub < 0) &&
            (index >= 0x1000U)) {
            rc = add_object(&c, &c.ini.sec[i], index);
        }
    }
    if ((rc == 0) && (c.nobj == 0U)) {
        rc = fail(&c, NULL, NULL, "no objects (is this an EDS?)");
    }
    if (rc == 0) {
        const char *base = strrchr(name, '/');
        d = build(&c, (base != NULL) ? (base + 1) : name, text);
    }
    if (d != NULL) {
        d->warnings = c.warn;
        c.warn = NULL;
    }
    ctx_free(&c);
    return d;
}

eds_dev_t *eds_load_file(const char *path, char *err, size_t errcap)
{
    FILE *f = fopen(path, "rb");
    char *text;
    size_t n;
    eds_dev_t *d;

    if (f == NULL) {
        (void)snprintf(err, errcap, "%s: %s", path, strerror(errno));
        return NULL;
    }
    text = (char *)malloc(EDS_MAX_SIZE + 1U);
    if (text == NULL) {
        (void)fclose(f);
        (void)snprintf(err, errcap, "%s: out of memory", path);
        return NULL;
    }
    n = fread(text, 1U, EDS_MAX_SIZE + 1U, f);
    (void)fclose(f);
    if (n > EDS_MAX_SIZE) {
        free(text);
        (void)snprintf(err, errcap, "%s: larger than %lu bytes", path, EDS_MAX_SIZE);
        return NULL;
    }
    if (memchr(text, '\0', n) != NULL) {
        free(text);
        (void)snprintf(err, errcap, "%s: a NUL byte (not a text file)", path);
        return NULL;
    }
    text[n] = '\0';
    d = eds_load_text(path, text, err, errcap);
    free(text);
    return d;
}

const co_dev_t *eds_device(const eds_dev_t *d)
{
    return &d->dev;
}

const char *eds_text(const eds_dev_t *d)
{
    return d->text;
}

const char *eds_warnings(const eds_dev_t *d)
{
    return (d->warnings != NULL) ? d->warnings : "";
}

const char *eds_name(const eds_dev_t *d)
{
    return d->name;
}

const char *eds_summary(const eds_dev_t *d)
{
    return d->summary;
}

void eds_free(eds_dev_t *d)
{
    if (d == NULL) {
        return;
    }
    free(d->text);
    free(d->name);
    free(d->defaults);
    free(d->entries);
    free(d->subs);
    free(d->limits);
    free(d->pdo);
    free(d->maps);
    free(d->warnings);
    free(d);
}
