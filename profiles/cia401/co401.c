/*
 * CiA 401 generic I/O module (co/co401.h).
 */
#include "co/co401.h"

#include <string.h>

#define GLOBAL_DI      0x6005U /* global interrupt enable digital, BOOLEAN */
#define AI_OBJ         0x6401U /* read analog input 16-bit */
#define AO_OBJ         0x6411U /* write analog output 16-bit */
#define AI_TRIGGER     0x6421U
#define GLOBAL_AI      0x6423U
#define AI_UPPER       0x6424U
#define AI_LOWER       0x6425U
#define AI_DELTA       0x6426U
#define AI_NDELTA      0x6427U
#define AI_PDELTA      0x6428U
#define AO_ERR_MODE    0x6443U
#define AO_ERR_VALUE   0x6444U
/* offsets from the digital input / output object */
#define DI_POLARITY    2U
#define DI_FILTER      3U
#define DI_ANY         6U
#define DI_LOW_HIGH    7U
#define DI_HIGH_LOW    8U
#define DO_POLARITY    2U
#define DO_ERR_MODE    6U
#define DO_ERR_VALUE   7U
#define DO_FILTER      8U

#define TRIG_UPPER  0x01U
#define TRIG_LOWER  0x02U
#define TRIG_DELTA  0x04U
#define TRIG_NDELTA 0x08U
#define TRIG_PDELTA 0x10U

#define NMT_STOP 0x02U

/* ------------------------------------------------------------ objects */

/* A value through the dictionary (wire bytes, up to 4), @p dflt when the
 * device lacks the object. */
static uint32_t param(const co401_t *m, uint16_t index, uint8_t sub, uint32_t dflt)
{
    uint8_t b[4] = {0U, 0U, 0U, 0U};
    uint32_t len = 0U;

    if (co_od_read(m->node, index, sub, b, sizeof b, &len) != CO_OK) {
        return dflt;
    }
    return (uint32_t)b[0] | ((uint32_t)b[1] << 8U) | ((uint32_t)b[2] << 16U) |
           ((uint32_t)b[3] << 24U);
}

static void put(uint8_t *b, uint32_t v, uint8_t size)
{
    for (uint8_t k = 0U; k < size; k++) {
        b[k] = (uint8_t)(v >> (8U * k));
    }
}

static uint32_t get(const uint8_t *b, uint8_t size)
{
    uint32_t v = 0U;

    for (uint8_t k = 0U; k < size; k++) {
        v |= (uint32_t)b[k] << (8U * k);
    }
    return v;
}

static uint32_t ones(uint8_t size)
{
    return (size >= 4U) ? 0xFFFFFFFFU : (((uint32_t)1U << (8U * size)) - 1U);
}

/* The digital object in use of @p base (8-bit), +0x100 (16), +0x120 (32),
 * or @p given; its block size and number of blocks. */
static uint16_t find_digital(const co401_t *m, uint16_t given, uint16_t base, uint8_t want,
                             uint8_t *size, uint8_t *blocks)
{
    static const uint16_t off[3] = {0x000U, 0x100U, 0x120U};
    const co_dev_t *dev = m->node->dev;

    for (uint8_t k = 0U; k < 3U; k++) {
        uint16_t index = (given != 0U) ? given : (uint16_t)(base + off[k]);
        const co_od_entry_t *e = co_od_find(dev->od, dev->od_count, index);
        if (e != NULL) {
            uint8_t n = 0U;
            co_od_sub_t sub_buf;
            const co_od_sub_t *first = co_od_find_sub(dev, e, m->cfg.first_sub, &sub_buf);
            uint8_t sz = (first != NULL) ? co_type_size(first->type) : 0U;
            if ((sz != 1U) && (sz != 2U) && (sz != 4U)) {
                return 0U;
            }
            while ((co_od_find_sub(dev, e, (uint8_t)(m->cfg.first_sub + n), &sub_buf) != NULL) &&
                   ((uint32_t)(n + 1U) * sz <= CO401_DIO_BYTES)) {
                n++;
            }
            if ((want != 0U) && (want < n)) {
                n = want;
            }
            *size = sz;
            *blocks = n;
            return index;
        }
        if (given != 0U) {
            break;
        }
    }
    return 0U;
}

static uint8_t count_subs(const co401_t *m, uint16_t index)
{
    const co_dev_t *dev = m->node->dev;
    const co_od_entry_t *e = co_od_find(dev->od, dev->od_count, index);
    uint8_t n = 0U;
    co_od_sub_t sub_buf;

    while ((e != NULL) && (n < CO401_AIO_MAX) &&
           (co_od_find_sub(dev, e, (uint8_t)(n + 1U), &sub_buf) != NULL)) {
        n++;
    }
    return n;
}

/* ------------------------------------------------------------ outputs */

/* Drive the plant from the logical outputs (or their error values): with
 * @p force always, else when the physical outputs change (a polarity or
 * error parameter written). */
static void drive(co401_t *m, bool force)
{
    uint8_t nb = (uint8_t)(m->n_do * m->do_size);
    uint8_t before[CO401_DIO_BYTES];
    int16_t abefore[CO401_AIO_MAX];

    (void)memcpy(before, m->dphys, sizeof before);
    (void)memcpy(abefore, m->aphys, sizeof abefore);

    for (uint8_t b = 0U; b < m->n_do; b++) {
        uint8_t sub = (uint8_t)(m->cfg.first_sub + b);
        uint32_t pol = param(m, (uint16_t)(m->dout + DO_POLARITY), sub, 0U);
        uint32_t v = get(&m->dlog[b * m->do_size], m->do_size);
        if (m->error) {
            uint32_t mode = param(m, (uint16_t)(m->dout + DO_ERR_MODE), sub, ones(m->do_size));
            uint32_t ev = param(m, (uint16_t)(m->dout + DO_ERR_VALUE), sub, 0U);
            v = (v & ~mode) | (ev & mode);
        }
        put(&m->dphys[b * m->do_size], v ^ pol, m->do_size);
    }
    for (uint8_t k = 0U; k < m->n_ao; k++) {
        int16_t v = m->aapplied[k];
        if (m->error && (param(m, AO_ERR_MODE, (uint8_t)(k + 1U), 1U) != 0U)) {
            v = (int16_t)(int32_t)param(m, AO_ERR_VALUE, (uint8_t)(k + 1U), 0U);
        }
        m->aphys[k] = v;
    }
    if (!force && (memcmp(before, m->dphys, sizeof before) == 0) &&
        (memcmp(abefore, m->aphys, sizeof abefore) == 0)) {
        return;
    }
    if ((m->plant.ops != NULL) && (m->plant.ops->write != NULL)) {
        m->plant.ops->write(m->plant.ctx, m->dphys, nb, m->aphys, m->n_ao);
    }
}

/* Take the output objects: with @p force (an RPDO) always, else when one
 * changed. Ends the error state. */
static void take_outputs(co401_t *m, bool force)
{
    uint8_t obj[CO401_DIO_BYTES] = {0U};
    int16_t aobj[CO401_AIO_MAX] = {0};
    bool changed = force;

    for (uint8_t b = 0U; b < m->n_do; b++) {
        put(&obj[b * m->do_size], param(m, m->dout, (uint8_t)(m->cfg.first_sub + b), 0U),
            m->do_size);
    }
    for (uint8_t k = 0U; k < m->n_ao; k++) {
        aobj[k] = (int16_t)(uint16_t)param(m, AO_OBJ, (uint8_t)(k + 1U), 0U);
    }
    if ((memcmp(obj, m->applied, (size_t)m->n_do * m->do_size) != 0) ||
        (memcmp(aobj, m->aapplied, (size_t)m->n_ao * sizeof aobj[0]) != 0)) {
        changed = true;
    }
    if (!changed) {
        drive(m, false);
        return;
    }
    for (uint8_t b = 0U; b < m->n_do; b++) {
        uint8_t sub = (uint8_t)(m->cfg.first_sub + b);
        uint32_t fm = param(m, (uint16_t)(m->dout + DO_FILTER), sub, ones(m->do_size));
        uint32_t v = get(&obj[b * m->do_size], m->do_size);
        uint32_t prev = get(&m->dlog[b * m->do_size], m->do_size);
        put(&m->dlog[b * m->do_size], (v & fm) | (prev & ~fm), m->do_size);
    }
    (void)memcpy(m->applied, obj, (size_t)m->n_do * m->do_size);
    (void)memcpy(m->aapplied, aobj, (size_t)m->n_ao * sizeof aobj[0]);
    m->error = false;
    drive(m, true);
}

static void comm_error(co401_t *m)
{
    m->error = true;
    drive(m, true);
}

/* ------------------------------------------------------------ inputs */

/* Read the plant and update the input objects. Returns the earliest time
 * a filtered change is due (or CO_NO_DEADLINE). */
static uint32_t read_inputs(co401_t *m, uint32_t now)
{
    uint8_t nb = (uint8_t)(m->n_di * m->di_size);
    uint32_t due = CO_NO_DEADLINE;
    uint32_t ft = (m->cfg.filter_us != 0U) ? m->cfg.filter_us : 3000U;

    if ((m->plant.ops != NULL) && (m->plant.ops->read != NULL)) {
        m->plant.ops->read(m->plant.ctx, m->raw, nb, m->ain, m->n_ai);
    }
    for (uint8_t b = 0U; b < m->n_di; b++) {
        uint8_t sub = (uint8_t)(m->cfg.first_sub + b);
        uint32_t filt = param(m, (uint16_t)(m->di + DI_FILTER), sub, 0U);
        uint32_t pol = param(m, (uint16_t)(m->di + DI_POLARITY), sub, 0U);
        for (uint8_t k = 0U; k < m->di_size; k++) {
            uint8_t at = (uint8_t)(b * m->di_size + k);
            uint8_t fbits = (uint8_t)(filt >> (8U * k));
            uint8_t diff = (uint8_t)(m->raw[at] ^ m->stable[at]);
            /* unfiltered bits follow at once */
            m->stable[at] = (uint8_t)((m->stable[at] & fbits) | (m->raw[at] & ~fbits));
            for (uint8_t bit = 0U; bit < 8U; bit++) {
                uint8_t mask = (uint8_t)(1U << bit);
                uint32_t *since = &m->since[(at * 8U) + bit];
                if (((fbits & mask) == 0U) || ((diff & mask) == 0U)) {
                    m->pending[at] &= (uint8_t)~mask;
                } else if ((m->pending[at] & mask) == 0U) {
                    m->pending[at] |= mask;
                    *since = now;
                } else {
                    /* waiting */
                }
                if ((m->pending[at] & mask) != 0U) {
                    if ((int32_t)(now - (*since + ft)) >= 0) {
                        m->stable[at] ^= mask;
                        m->pending[at] &= (uint8_t)~mask;
                    } else if ((due == CO_NO_DEADLINE) || ((int32_t)(*since + ft - due) < 0)) {
                        due = *since + ft;
                    } else {
                        /* a later one is due */
                    }
                }
            }
        }
        {
            uint32_t v = get(&m->stable[b * m->di_size], m->di_size) ^ pol;
            uint32_t o = get(&m->dobj[b * m->di_size], m->di_size);
            if (m->started && (v != o) && (param(m, GLOBAL_DI, 0U, 1U) != 0U)) {
                uint32_t any = param(m, (uint16_t)(m->di + DI_ANY), sub, ones(m->di_size));
                uint32_t lh = param(m, (uint16_t)(m->di + DI_LOW_HIGH), sub, 0U);
                uint32_t hl = param(m, (uint16_t)(m->di + DI_HIGH_LOW), sub, 0U);
                m->irq[b] |= ((o ^ v) & any) | (~o & v & lh) | (o & ~v & hl);
            }
            if (!m->started || (v != o)) {
                uint8_t w[4];
                put(w, v, m->di_size);
                (void)co_od_write(m->node, m->di, sub, w, m->di_size, true);
                (void)memcpy(&m->dobj[b * m->di_size], w, m->di_size);
            }
        }
    }
    for (uint8_t k = 0U; k < m->n_ai; k++) {
        uint8_t w[2];
        put(w, (uint16_t)m->ain[k], 2U);
        (void)co_od_write(m->node, AI_OBJ, (uint8_t)(k + 1U), w, 2U, true);
    }
    return due;
}

/* ------------------------------------------------------------ TPDO events */

static uint32_t bits_of(const uint8_t *data, uint16_t off, uint8_t len)
{
    uint32_t v = 0U;

    for (uint8_t j = 0U; j < len; j++) {
        uint16_t p = (uint16_t)(off + j);
        if ((((uint32_t)data[p >> 3U] >> (p & 7U)) & 1U) != 0U) {
            v |= (uint32_t)1U << j;
        }
    }
    return v;
}

/* Clear the bits of @p changed at [off, off + len) not set in @p keep. */
static void clear_bits(uint8_t *changed, uint16_t off, uint8_t len, uint32_t keep)
{
    for (uint8_t j = 0U; j < len; j++) {
        uint16_t p = (uint16_t)(off + j);
        if (((keep >> j) & 1U) == 0U) {
            changed[p >> 3U] &= (uint8_t)~(1U << (p & 7U));
        }
    }
}

/* Is the change of analog input @p ch (1-based) from @p old to @p now an
 * interrupt? */
static bool analog_event(const co401_t *m, uint8_t ch, int32_t old, int32_t now)
{
    uint32_t trig = param(m, AI_TRIGGER, ch, 0x07U);
    int32_t upper = (int32_t)param(m, AI_UPPER, ch, 0U);
    int32_t lower = (int32_t)param(m, AI_LOWER, ch, 0U);
    int32_t diff = now - old;
    uint32_t mag = (uint32_t)((diff < 0) ? -diff : diff);

    if (param(m, GLOBAL_AI, 0U, 0U) == 0U) {
        return false;
    }
    return (((trig & TRIG_UPPER) != 0U) && (now > upper) && (old <= upper)) ||
           (((trig & TRIG_LOWER) != 0U) && (now < lower) && (old >= lower)) ||
           (((trig & TRIG_DELTA) != 0U) && (mag > param(m, AI_DELTA, ch, 0U))) ||
           (((trig & TRIG_NDELTA) != 0U) && (diff < 0) && (mag > param(m, AI_NDELTA, ch, 0U))) ||
           (((trig & TRIG_PDELTA) != 0U) && (diff > 0) && (mag > param(m, AI_PDELTA, ch, 0U)));
}

static void op_tpdo_event(void *inst, uint16_t n, const uint8_t last[8], const uint8_t now[8],
                          uint8_t changed[8])
{
    co401_t *m = (co401_t *)inst;
    uint16_t map = (uint16_t)(0x1A00U + n);
    uint8_t count = (uint8_t)param(m, map, 0U, 0U);
    uint16_t off = 0U;

    for (uint8_t k = 1U; (k <= count) && (k <= 8U); k++) {
        uint32_t e = param(m, map, k, 0U);
        uint16_t index = (uint16_t)(e >> 16U);
        uint8_t sub = (uint8_t)(e >> 8U);
        uint8_t len = (uint8_t)e;
        if ((len == 0U) || ((uint16_t)(off + len) > 64U)) {
            break;
        }
        if ((m->di != 0U) && (index == m->di) && (sub >= m->cfg.first_sub) &&
            (sub < (uint8_t)(m->cfg.first_sub + m->n_di)) && (len <= 32U)) {
            uint8_t blk = (uint8_t)(sub - m->cfg.first_sub);
            if ((m->irq[blk] != 0U) && (param(m, GLOBAL_DI, 0U, 1U) != 0U)) {
                /* an interrupt: it goes out now (or when the inhibit time
                 * ends), also when the block is back at the value sent */
                m->irq[blk] = 0U;
                changed[off >> 3U] |= (uint8_t)(1U << (off & 7U));
            } else {
                clear_bits(changed, off, len, 0U);
            }
        } else if ((index == AI_OBJ) && (sub >= 1U) && (sub <= m->n_ai) && (len == 16U)) {
            int32_t o = (int16_t)(uint16_t)bits_of(last, off, len);
            int32_t v = (int16_t)(uint16_t)bits_of(now, off, len);
            if (!analog_event(m, sub, o, v)) {
                clear_bits(changed, off, len, 0U);
            }
        } else {
            /* not the module's */
        }
        off = (uint16_t)(off + len);
    }
}

/* ------------------------------------------------------------ operations */

void co401_init(co401_t *m, const co401_config_t *cfg, co401_plant_t plant)
{
    (void)memset(m, 0, sizeof *m);
    m->cfg = *cfg;
    m->plant = plant;
}

static co_err_t op_attach(void *inst, co_node_t *node, uint32_t now_us)
{
    co401_t *m = (co401_t *)inst;

    m->node = node;
    m->di = find_digital(m, m->cfg.di, 0x6000U, m->cfg.n_di, &m->di_size, &m->n_di);
    m->dout = find_digital(m, m->cfg.dout, 0x6200U, m->cfg.n_do, &m->do_size, &m->n_do);
    if (m->di == 0U) {
        m->n_di = 0U;
    }
    if (m->dout == 0U) {
        m->n_do = 0U;
    }
    m->n_ai = count_subs(m, AI_OBJ);
    m->n_ao = count_subs(m, AO_OBJ);
    if ((m->n_di == 0U) && (m->n_do == 0U) && (m->n_ai == 0U) && (m->n_ao == 0U)) {
        return CO_ERR_OD_MISSING; /* no I/O object at all */
    }
    m->started = false;
    m->next_poll = now_us;
    return CO_OK;
}

static uint32_t op_process(void *inst, uint32_t now_us)
{
    co401_t *m = (co401_t *)inst;
    uint32_t poll = (m->cfg.poll_us != 0U) ? m->cfg.poll_us : 10000U;
    uint32_t due;

    if (!m->started) {
        take_outputs(m, true);
    } else {
        take_outputs(m, false);
    }
    due = read_inputs(m, now_us);
    m->started = true;
    if ((int32_t)(now_us - m->next_poll) >= 0) {
        m->next_poll = now_us + poll;
    }
    if ((due == CO_NO_DEADLINE) || ((int32_t)(m->next_poll - due) < 0)) {
        due = m->next_poll;
    }
    return due;
}

static void op_rpdo(void *inst, uint16_t n, uint32_t now_us)
{
    (void)n;
    (void)now_us;
    take_outputs((co401_t *)inst, true);
}

static void op_reset(void *inst, co_reset_t kind, uint32_t now_us)
{
    co401_t *m = (co401_t *)inst;

    (void)now_us;
    if (kind == CO_RESET_NODE) {
        m->started = false; /* objects at their defaults: applied and rewritten */
    }
}

static void op_error_control(void *inst, co_hb_event_t ev, uint8_t id, uint32_t now_us)
{
    (void)id;
    (void)now_us;
    if ((ev == CO_HB_TIMEOUT) || (ev == CO_GUARD_LOST)) {
        comm_error((co401_t *)inst);
    }
}

static void op_error_class(void *inst, uint8_t sub, uint32_t now_us)
{
    (void)now_us;
    if (sub == CO_ERRBEH_COMM) {
        comm_error((co401_t *)inst);
    }
}

static void op_nmt_command(void *inst, uint8_t cs, uint32_t now_us)
{
    (void)now_us;
    if (cs == NMT_STOP) {
        comm_error((co401_t *)inst);
    }
}

const co_profile_ops_t co401_profile_ops = {
    .name = "cia401",
    .attach = op_attach,
    .process = op_process,
    .reset = op_reset,
    .error_control = op_error_control,
    .rpdo = op_rpdo,
    .tpdo_event = op_tpdo_event,
    .nmt_command = op_nmt_command,
    .error_class = op_error_class,
};

const uint8_t *co401_outputs(const co401_t *m, uint8_t *n)
{
    *n = (uint8_t)(m->n_do * m->do_size);
    return m->dphys;
}

bool co401_in_error(const co401_t *m)
{
    return m->error;
}

bool co401_input_of(const co401_t *m, uint16_t index, uint8_t sub, uint8_t *byte,
                    uint8_t *width, uint8_t *ain)
{
    if ((m->di != 0U) && (index == m->di) && (sub >= m->cfg.first_sub) &&
        (sub < (uint8_t)(m->cfg.first_sub + m->n_di))) {
        *byte = (uint8_t)((sub - m->cfg.first_sub) * m->di_size);
        *width = m->di_size;
        *ain = 0xFFU;
        return true;
    }
    if ((index == AI_OBJ) && (sub >= 1U) && (sub <= m->n_ai)) {
        *ain = (uint8_t)(sub - 1U);
        *width = 2U;
        *byte = 0xFFU;
        return true;
    }
    return false;
}
