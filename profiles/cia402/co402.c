/*
 * CiA 402 axis: objects, units, the state machine, faults, statusword, the
 * control tick and the plug-in operations.
 */
#include <stddef.h>
#include <string.h>

#include "co/co_endian.h"
#include "co/co_pobj.h"
#include "co402_priv.h"

typedef char co402_obj_count_matches[(O_COUNT == CO402_OBJ_COUNT) ? 1 : -1];

#define MIN_STANDSTILL (4LL * CO402_Q16) /* 4 increments/s */

/* ------------------------------------------------------------ objects */

typedef struct obj_ref {
    uint16_t index;
    uint8_t sub;
} obj_ref_t;

/* Indices of axis 0, in the order of the O_* enumeration. */
static const obj_ref_t obj_refs[O_COUNT] = {
    {0x6040U, 0U}, {0x6041U, 0U}, {0x603FU, 0U}, {0x6007U, 0U}, {0x605AU, 0U}, {0x605BU, 0U},
    {0x605CU, 0U}, {0x605DU, 0U}, {0x605EU, 0U}, {0x6060U, 0U}, {0x6061U, 0U}, {0x6062U, 0U},
    {0x6063U, 0U}, {0x6064U, 0U}, {0x6065U, 0U}, {0x6066U, 0U}, {0x6067U, 0U}, {0x6068U, 0U},
    {0x606BU, 0U}, {0x606CU, 0U}, {0x606DU, 0U}, {0x606EU, 0U}, {0x606FU, 0U}, {0x6070U, 0U},
    {0x6071U, 0U}, {0x6072U, 0U}, {0x6074U, 0U}, {0x6077U, 0U}, {0x607AU, 0U}, {0x607CU, 0U},
    {0x607DU, 1U}, {0x607DU, 2U}, {0x607EU, 0U}, {0x607FU, 0U}, {0x6081U, 0U}, {0x6083U, 0U},
    {0x6084U, 0U}, {0x6085U, 0U}, {0x6087U, 0U}, {0x608FU, 1U}, {0x608FU, 2U}, {0x6093U, 1U},
    {0x6093U, 2U}, {0x6094U, 1U}, {0x6094U, 2U}, {0x6097U, 1U}, {0x6097U, 2U}, {0x6098U, 0U},
    {0x6099U, 1U}, {0x6099U, 2U}, {0x609AU, 0U}, {0x60B0U, 0U}, {0x60B1U, 0U}, {0x60B2U, 0U},
    {0x60C1U, 1U}, {0x60C2U, 1U}, {0x60C2U, 2U}, {0x60F4U, 0U}, {0x60FDU, 0U}, {0x60FFU, 0U},
    {0x6502U, 0U}, {0x6042U, 0U}, {0x6043U, 0U}, {0x6044U, 0U}, {0x6046U, 1U}, {0x6046U, 2U},
    {0x6048U, 1U}, {0x6048U, 2U}, {0x6049U, 1U}, {0x6049U, 2U}, {0x604AU, 1U}, {0x604AU, 2U},
    {0x6080U, 0U},
};

#define OBJ_CONST 0x80U /* obj_type: the value is in the device's ROM image */

static uint16_t axis_index(const co402_axis_t *ax, uint16_t index)
{
    return (uint16_t)(index + (0x800U * ax->cfg.axis));
}

bool co402_has(const co402_axis_t *ax, uint8_t id)
{
    return ax->obj[id] != NULL;
}

int64_t co402_get(const co402_axis_t *ax, uint8_t id, int64_t dflt)
{
    const void *p = ax->obj[id];

    if (p == NULL) {
        return dflt;
    }
    switch (ax->obj_type[id] & (uint8_t)~OBJ_CONST) {
    case (uint8_t)CO_INTEGER8: {
        int8_t v;
        (void)memcpy(&v, p, 1U);
        return v;
    }
    case (uint8_t)CO_UNSIGNED8: {
        uint8_t v;
        (void)memcpy(&v, p, 1U);
        return v;
    }
    case (uint8_t)CO_INTEGER16: {
        int16_t v;
        (void)memcpy(&v, p, 2U);
        return v;
    }
    case (uint8_t)CO_UNSIGNED16: {
        uint16_t v;
        (void)memcpy(&v, p, 2U);
        return v;
    }
    case (uint8_t)CO_INTEGER32: {
        int32_t v;
        (void)memcpy(&v, p, 4U);
        return v;
    }
    default: {
        uint32_t v;
        (void)memcpy(&v, p, 4U);
        return v;
    }
    }
}

void co402_put(co402_axis_t *ax, uint8_t id, int64_t v)
{
    void *p = ax->obj[id];

    if ((p == NULL) || ((ax->obj_type[id] & OBJ_CONST) != 0U)) {
        return;
    }
    switch (co_pobj_int_size(ax->obj_type[id])) {
    case 1U: {
        uint8_t b = (uint8_t)((uint64_t)v & 0xFFU);
        (void)memcpy(p, &b, 1U);
        break;
    }
    case 2U: {
        uint16_t h = (uint16_t)((uint64_t)v & 0xFFFFU);
        (void)memcpy(p, &h, 2U);
        break;
    }
    default: {
        uint32_t w = (uint32_t)((uint64_t)v & 0xFFFFFFFFU);
        (void)memcpy(p, &w, 4U);
        break;
    }
    }
}

static void bind_objects(co402_axis_t *ax)
{
    const co_dev_t *dev = ax->node->dev;

    for (uint8_t i = 0U; i < (uint8_t)O_COUNT; i++) {
        uint16_t index = axis_index(ax, obj_refs[i].index);
        const co_od_entry_t *e = co_od_find(dev->od, dev->od_count, index);
        co_od_sub_t sub_buf;
        const co_od_sub_t *s = (e != NULL) ? co_od_find_sub(dev, e, obj_refs[i].sub, &sub_buf) : NULL;
        ax->obj[i] = NULL;
        ax->obj_type[i] = 0U;
        if ((s == NULL) || (co_pobj_int_size(s->type) == 0U) || ((s->flags & CO_SUB_HOOKIO) != 0U)) {
            /* absent, or not an integer the axis can keep */
        } else if ((s->flags & CO_SUB_ROM) != 0U) {
            /* a constant (0x6502 ...): read it where the device keeps it, never write */
            ax->obj[i] = (void *)(uintptr_t)&dev->rom[s->off];
            ax->obj_type[i] = (uint8_t)(s->type | OBJ_CONST);
        } else {
            ax->obj[i] = co_od_value_ptr(ax->node, index, obj_refs[i].sub);
            ax->obj_type[i] = s->type;
        }
    }
}

/* -------------------------------------------------------------- units */

static int64_t div_floor(int64_t a, int64_t b)
{
    int64_t q = a / b;
    if (((a % b) != 0) && ((a < 0) != (b < 0))) {
        q--;
    }
    return q;
}

static int64_t sat_q16(int64_t v)
{
    if (v > CO402_Q16_MAX) {
        return CO402_Q16_MAX;
    }
    return (v < -CO402_Q16_MAX) ? -CO402_Q16_MAX : v;
}

/* user * num / den as Q16, saturated to +-CO402_Q16_MAX; @p user within
 * +-2^32 (32-bit objects, times a sign): user * num fits 64 bits, and a
 * quotient beyond INT32_MAX saturates before it is shifted into Q16. */
static int64_t scale_in(int64_t user, uint32_t num, uint32_t den)
{
    int64_t x = user * (int64_t)num;
    int64_t q = x / (int64_t)den;
    int64_t r = x % (int64_t)den;
    if ((q > (int64_t)INT32_MAX) || (q < -(int64_t)INT32_MAX)) {
        return (q > 0) ? CO402_Q16_MAX : -CO402_Q16_MAX;
    }
    return sat_q16((q * CO402_Q16) + ((r * CO402_Q16) / (int64_t)den));
}

/* Q16 -> user units, rounded to the nearest */
static int64_t scale_out(int64_t q16, uint32_t num, uint32_t den)
{
    if (num == den) {
        return div_floor(q16 + (CO402_Q16 / 2), CO402_Q16);
    }
    return div_floor((div_floor(q16, 256) * (int64_t)den) + ((int64_t)num * 128), (int64_t)num * 256);
}

static void factor(const co402_axis_t *ax, uint8_t num_id, uint8_t den_id, uint32_t *num,
                   uint32_t *den)
{
    *num = (uint32_t)co402_get(ax, num_id, 1);
    *den = (uint32_t)co402_get(ax, den_id, 1);
    if ((*num == 0U) || (*den == 0U)) {
        *num = 1U;
        *den = 1U;
    }
}

static void pos_factor(const co402_axis_t *ax, uint32_t *num, uint32_t *den)
{
    factor(ax, O_POS_NUM, O_POS_DEN, num, den);
}

static void vel_factor(const co402_axis_t *ax, uint32_t *num, uint32_t *den)
{
    if ((ax->cfg.options & CO402_OPT_VEL_RPM) != 0U) {
        *num = co402_counts_per_rev(ax); /* rpm -> increments/s */
        *den = 60U;
    } else if (co402_has(ax, O_VEL_NUM) && ((ax->cfg.options & CO402_OPT_UNITS_FROM_POS) == 0U)) {
        factor(ax, O_VEL_NUM, O_VEL_DEN, num, den);
    } else if ((ax->cfg.vel_num != 0U) && (ax->cfg.vel_den != 0U)) {
        *num = ax->cfg.vel_num; /* the device's fixed velocity unit */
        *den = ax->cfg.vel_den;
    } else {
        pos_factor(ax, num, den);
    }
}

static int64_t pos_sign(const co402_axis_t *ax)
{
    return ((co402_get(ax, O_POLARITY, 0) & 0x80) != 0) ? -1 : 1;
}

static int64_t vel_sign(const co402_axis_t *ax)
{
    return ((co402_get(ax, O_POLARITY, 0) & 0x40) != 0) ? -1 : 1;
}

int64_t co402_dist_in(const co402_axis_t *ax, int64_t user)
{
    uint32_t num;
    uint32_t den;
    pos_factor(ax, &num, &den);
    return scale_in(user * pos_sign(ax), num, den);
}

int64_t co402_pos_in(const co402_axis_t *ax, int64_t user)
{
    return co402_dist_in(ax, user);
}

int64_t co402_pos_out(const co402_axis_t *ax, int64_t q16)
{
    uint32_t num;
    uint32_t den;
    pos_factor(ax, &num, &den);
    return scale_out(q16, num, den) * pos_sign(ax);
}

int64_t co402_vel_in(const co402_axis_t *ax, int64_t user)
{
    uint32_t num;
    uint32_t den;
    vel_factor(ax, &num, &den);
    return scale_in(user * vel_sign(ax), num, den);
}

int64_t co402_vel_out(const co402_axis_t *ax, int64_t q16)
{
    uint32_t num;
    uint32_t den;
    vel_factor(ax, &num, &den);
    return scale_out(q16, num, den) * vel_sign(ax);
}

static uint32_t sat32(int64_t v)
{
    if (v <= 0) {
        return 0U;
    }
    return (v > (int64_t)UINT32_MAX) ? UINT32_MAX : (uint32_t)v;
}

uint32_t co402_speed_in(const co402_axis_t *ax, uint32_t user)
{
    uint32_t num;
    uint32_t den;
    vel_factor(ax, &num, &den);
    return sat32(((int64_t)user * (int64_t)num) / (int64_t)den);
}

uint32_t co402_acc_in(const co402_axis_t *ax, uint32_t user)
{
    uint32_t num;
    uint32_t den;
    if (co402_has(ax, O_ACC_NUM) &&
        ((ax->cfg.options & (CO402_OPT_UNITS_FROM_POS | CO402_OPT_VEL_RPM)) == 0U)) {
        factor(ax, O_ACC_NUM, O_ACC_DEN, &num, &den);
    } else if ((ax->cfg.acc_num != 0U) && (ax->cfg.acc_den != 0U)) {
        num = ax->cfg.acc_num; /* the device's fixed acceleration unit */
        den = ax->cfg.acc_den;
    } else {
        vel_factor(ax, &num, &den);
    }
    return sat32(((int64_t)user * (int64_t)num) / (int64_t)den);
}

uint32_t co402_counts_per_rev(const co402_axis_t *ax)
{
    int64_t inc = co402_get(ax, O_ENC_INC, 0);
    int64_t rev = co402_get(ax, O_ENC_REV, 1);

    if ((inc > 0) && (rev > 0)) {
        /* fewer increments than revolutions (both legal): at least 1, so
         * that every division by it is defined */
        uint32_t c = sat32(inc / rev);
        return (c != 0U) ? c : 1U;
    }
    return (ax->cfg.counts_per_rev != 0U) ? ax->cfg.counts_per_rev : 4096U;
}

uint32_t co402_tick(const co402_axis_t *ax)
{
    return (ax->cfg.tick_us != 0U) ? ax->cfg.tick_us : 1000U;
}

int64_t co402_standstill(const co402_axis_t *ax)
{
    int64_t thr = co402_vel_in(ax, co402_get(ax, O_VEL_THRESHOLD, 0));
    if (thr < 0) {
        thr = -thr;
    }
    return (thr > MIN_STANDSTILL) ? thr : MIN_STANDSTILL;
}

/* Software position limits (0x607D) in internal Q16; false when off
 * (absent, or both 0, or min >= max). */
bool co402_limits(const co402_axis_t *ax, int64_t *lo, int64_t *hi)
{
    int64_t a;
    int64_t b;

    if (!co402_has(ax, O_LIMIT_MIN) || !co402_has(ax, O_LIMIT_MAX)) {
        return false;
    }
    a = co402_get(ax, O_LIMIT_MIN, 0);
    b = co402_get(ax, O_LIMIT_MAX, 0);
    if (a >= b) {
        return false;
    }
    a = co402_pos_in(ax, a);
    b = co402_pos_in(ax, b);
    *lo = (a < b) ? a : b; /* polarity may swap them */
    *hi = (a < b) ? b : a;
    return true;
}

bool co402_clamp(const co402_axis_t *ax, int64_t *p)
{
    int64_t lo;
    int64_t hi;

    if (!co402_limits(ax, &lo, &hi)) {
        return false;
    }
    if (*p < lo) {
        *p = lo;
        return true;
    }
    if (*p > hi) {
        *p = hi;
        return true;
    }
    return false;
}

/* ------------------------------------------------- profile generator */

void co402_traj_get(const co402_axis_t *ax, co402_traj_t *t)
{
    t->p = ax->tr_p;
    t->v = ax->tr_v;
    t->a = ax->tr_a;
}

void co402_traj_put(co402_axis_t *ax, const co402_traj_t *t)
{
    /* the step just made runs from (dm_p, dm_v) with t->a during the tick */
    ax->dm_p = ax->tr_p;
    ax->dm_v = ax->tr_v;
    ax->tr_p = t->p;
    ax->tr_v = t->v;
    ax->tr_a = t->a;
}

void co402_sync_traj(co402_axis_t *ax)
{
    ax->tr_p = ax->pos;
    ax->tr_v = ax->vel;
    ax->tr_a = 0;
    ax->dm_p = ax->pos;
    ax->dm_v = ax->vel;
}

void co402_demand_pos(const co402_axis_t *ax, co402_demand_t *d, const co402_traj_t *t)
{
    /* the plant follows the generator's step from its start */
    d->kind = (uint8_t)CO402_DEMAND_POSITION;
    d->pos = ax->dm_p - ax->shift;
    d->vel = ax->dm_v;
    d->acc = t->a;
}

void co402_demand_at(co402_axis_t *ax, co402_demand_t *d, int64_t p, int64_t v)
{
    ax->tr_p = p;
    ax->tr_v = v;
    ax->tr_a = 0;
    ax->dm_p = p;
    ax->dm_v = v;
    d->kind = (uint8_t)CO402_DEMAND_POSITION;
    d->pos = p - ax->shift;
    d->vel = v;
    d->acc = 0;
}

bool co402_stop_step(co402_axis_t *ax, uint8_t kind, co402_demand_t *d)
{
    int64_t still = co402_standstill(ax);
    int64_t v = (ax->vel < 0) ? -ax->vel : ax->vel;

    if (kind == (uint8_t)STOP_LIMIT) {
        /* stop on the torque (current) limit: the plant brakes */
        co402_sync_traj(ax);
        d->kind = (uint8_t)CO402_DEMAND_BRAKE;
        d->vel = 0;
        d->acc = 0;
        return v <= still;
    } else {
        co402_traj_t t;
        uint32_t dec = (kind == (uint8_t)STOP_QUICK) ? co402_quick_dec(ax) : co402_slow_dec(ax);
        co402_traj_get(ax, &t);
        (void)co402_traj_vel(&t, 0, dec, dec, co402_tick(ax));
        co402_traj_put(ax, &t);
        co402_demand_pos(ax, d, &t);
        return (t.v == 0) && (v <= still);
    }
}

/* --------------------------------------------------------- statusword */

uint16_t co402_statusword(const co402_axis_t *ax)
{
    static const uint16_t state_bits[8] = {0x0000U, 0x0040U, 0x0021U, 0x0023U,
                                           0x0027U, 0x0007U, 0x000FU, 0x0008U};
    uint32_t o = ax->cfg.options;
    uint16_t sw = state_bits[ax->state & 7U];
    bool on = (ax->state >= (uint8_t)CO402_SWITCHED_ON) && (ax->state <= (uint8_t)CO402_FAULT_REACTION);

    if ((o & CO402_OPT_NO_VOLTAGE_BIT) == 0U) {
        bool present = (ax->fb.inputs & CO402_IN_VOLTAGE) != 0U;
        bool volt = ((o & CO402_OPT_VOLTAGE_WHEN_ON) != 0U) ? on : present;
        if (volt) {
            sw |= CO402_SW_VOLTAGE;
        }
    }
    if (ax->warning || ax->loss) {
        sw |= CO402_SW_WARNING;
    }
    if (ax->loss) {
        sw |= CO402_SW_LIMIT; /* "internal limit active" in every state (Kollmorgen n04) */
    }
    if ((o & CO402_OPT_NO_REMOTE_BIT) == 0U) {
        if (((o & CO402_OPT_REMOTE_IS_ENABLE) == 0U) || ((ax->fb.inputs & CO402_IN_ENABLE) != 0U)) {
            sw |= CO402_SW_REMOTE;
        }
    }
    if ((ax->state == (uint8_t)CO402_OPERATION_ENABLED) ||
        (ax->state == (uint8_t)CO402_QUICK_STOP_ACTIVE)) {
        sw |= (uint16_t)(ax->msw & (CO402_SW_TARGET | CO402_SW_LIMIT | CO402_SW_OMS1 | CO402_SW_OMS2));
        if (((o & CO402_OPT_SW15_MIRRORS_12) != 0U) && ((sw & CO402_SW_OMS1) != 0U)) {
            sw |= 0x8000U;
        }
    }
    return sw;
}

/* CO402_OPT_TPDO_ON_SW: ask for every TPDO whose mapping holds this axis'
 * statusword (0x1A00 + n), in PDO order. */
static void request_sw_tpdos(co402_axis_t *ax)
{
    uint32_t want = (uint32_t)axis_index(ax, 0x6041U) << 16U; /* index, sub-index 0 */

    for (uint16_t n = 0U; n < ax->node->dev->n_tpdo; n++) {
        uint16_t map = (uint16_t)(0x1A00U + n);
        uint8_t count = 0U;
        uint32_t len = 0U;
        if (co_od_read(ax->node, map, 0U, &count, 1U, &len) != CO_OK) {
            continue;
        }
        for (uint8_t k = 1U; k <= count; k++) {
            uint8_t b[4] = {0U, 0U, 0U, 0U};
            if ((co_od_read(ax->node, map, k, b, 4U, &len) == CO_OK) &&
                ((co_get_u32(b) & 0xFFFFFF00UL) == want)) {
                (void)co_tpdo_request(ax->node, n); /* outside Operational: refused, fine */
                break;
            }
        }
    }
}

static void publish_sw(co402_axis_t *ax)
{
    uint16_t sw = co402_statusword(ax);
    bool changed = co402_get(ax, O_SW, sw) != (int64_t)sw;

    co402_put(ax, O_SW, sw);
    if (changed && ((ax->cfg.options & CO402_OPT_TPDO_ON_SW) != 0U) && (ax->node != NULL)) {
        request_sw_tpdos(ax);
    }
}

/* ----------------------------------------------------- state machine */

static int16_t option(const co402_axis_t *ax, uint8_t id, int16_t dflt)
{
    return (int16_t)co402_get(ax, id, dflt);
}

/* The quick stop option code (0x605A; without it 2, or 6 with CO402_OPT_QS_STAY). */
static int16_t qs_code(const co402_axis_t *ax)
{
    return option(ax, O_QS_OPT, ((ax->cfg.options & CO402_OPT_QS_STAY) != 0U) ? 6 : 2);
}

/* An option code's ramp (1..4) as a stop kind. */
static uint8_t ramp_of(int16_t code)
{
    switch (code) {
    case 1:
        return (uint8_t)STOP_SLOW;
    case 2:
        return (uint8_t)STOP_QUICK;
    case 3:
    case 4:
        return (uint8_t)STOP_LIMIT;
    default:
        return (uint8_t)STOP_COAST;
    }
}

static void power_off(co402_axis_t *ax)
{
    ax->drive = (uint8_t)DRV_OFF;
    ax->msw = 0U;
}

static void enter(co402_axis_t *ax, co402_state_t st)
{
    ax->state = (uint8_t)st;
    switch (st) {
    case CO402_OPERATION_ENABLED:
        if (ax->loss) {
            ax->drive = (uint8_t)DRV_HOLD; /* no motion until the loss is reset */
            ax->target = ax->pos;
            co402_sync_traj(ax);
        } else {
            ax->drive = (uint8_t)DRV_RUN;
            co402_mode_enter(ax);
        }
        break;
    case CO402_QUICK_STOP_ACTIVE:
    case CO402_FAULT_REACTION:
        break; /* the caller starts the stop */
    case CO402_FAULT:
        power_off(ax);
        if ((ax->cfg.options & CO402_OPT_FAULT_HOLDS_ZERO) != 0U) {
            ax->drive = (uint8_t)DRV_HOLD;
            ax->target = ax->pos;
            co402_sync_traj(ax);
        }
        break;
    default:
        power_off(ax);
        break;
    }
}

/* Start a stop of @p kind; at rest the axis goes to @p then. */
static void start_stop(co402_axis_t *ax, uint8_t kind, co402_state_t then)
{
    if (ax->drive != (uint8_t)DRV_STOP) {
        co402_sync_traj(ax);
    }
    ax->drive = (uint8_t)DRV_STOP;
    ax->stop_kind = kind;
    ax->after_stop = (uint8_t)then;
}

static bool energised(const co402_axis_t *ax)
{
    return (ax->drive != (uint8_t)DRV_OFF) && (ax->state != (uint8_t)CO402_FAULT);
}

/* Transitions 5 and 8: disable operation / shutdown from Operation enabled,
 * with their option code (0: at once; 1: slow down first, the state
 * changes when the axis is at rest). */
static void leave_operation(co402_axis_t *ax, uint8_t opt_id, co402_state_t to)
{
    int16_t code = option(ax, opt_id, (opt_id == (uint8_t)O_DO_OPT) ? 1 : 0);

    if (code == 1) {
        start_stop(ax, (uint8_t)STOP_SLOW, to);
    } else {
        enter(ax, to);
    }
}

static void quick_stop(co402_axis_t *ax)
{
    int16_t code = qs_code(ax);

    if ((ax->cfg.options & CO402_OPT_QS_CLEARS_TARGET) != 0U) {
        co402_put(ax, O_TARGET_POS, 0);
        co402_put(ax, O_TARGET_VEL, 0);
        co402_put(ax, O_TARGET_TORQUE, 0);
    }
    ax->state = (uint8_t)CO402_QUICK_STOP_ACTIVE;
    ax->msw &= (uint16_t)~(CO402_SW_TARGET | CO402_SW_OMS1);
    if ((code <= 0) || (code > 8)) {
        enter(ax, CO402_SWITCH_ON_DISABLED); /* 0: disable the drive function (then 12) */
    } else if (code <= 4) {
        start_stop(ax, ramp_of(code), CO402_SWITCH_ON_DISABLED);
    } else {
        start_stop(ax, ramp_of((int16_t)(code - 4)), CO402_QUICK_STOP_ACTIVE);
    }
}

/* Transition 13 and the fault reaction (0x605E). */
static void fault_reaction(co402_axis_t *ax)
{
    int16_t code = option(ax, O_FR_OPT, ((ax->cfg.options & CO402_OPT_FR_SLOW) != 0U) ? 1 : 2);

    ax->state = (uint8_t)CO402_FAULT_REACTION;
    ax->msw = 0U;
    if (!energised(ax) || (code <= 0) || (code > 4)) {
        enter(ax, CO402_FAULT); /* 14 at once */
    } else {
        start_stop(ax, ramp_of(code), CO402_FAULT);
    }
}

enum { CMD_NONE = 0, CMD_SHUTDOWN, CMD_SWITCH_ON, CMD_ENABLE, CMD_DISABLE_VOLTAGE, CMD_QUICK_STOP };

static uint8_t decode(const co402_axis_t *ax, uint16_t cw)
{
    uint16_t b7 = (uint16_t)(((ax->cfg.options & CO402_OPT_BIT7_DONT_CARE) != 0U) ? 0U : CO402_CW_FAULT_RESET);

    if ((cw & (b7 | 0x02U)) == 0x00U) {
        return CMD_DISABLE_VOLTAGE;
    }
    if ((cw & (b7 | 0x06U)) == 0x02U) {
        return CMD_QUICK_STOP;
    }
    if ((cw & (b7 | 0x07U)) == 0x06U) {
        return CMD_SHUTDOWN;
    }
    if ((cw & (b7 | 0x0FU)) == 0x07U) {
        return CMD_SWITCH_ON; /* also "disable operation" */
    }
    if ((cw & (b7 | 0x0FU)) == 0x0FU) {
        return CMD_ENABLE; /* also "switch on + enable operation" */
    }
    return CMD_NONE;
}

static bool enable_input(const co402_axis_t *ax)
{
    return (ax->fb.inputs & CO402_IN_ENABLE) != 0U;
}

/* One transition for @p cmd from the present state; true if one was made. */
static bool transition(co402_axis_t *ax, uint8_t cmd)
{
    switch (ax->state) {
    case (uint8_t)CO402_SWITCH_ON_DISABLED:
        if ((cmd == CMD_SHUTDOWN) &&
            (((ax->cfg.options & CO402_OPT_REMOTE_IS_ENABLE) == 0U) || enable_input(ax))) {
            enter(ax, CO402_READY); /* 2 */
            return true;
        }
        break;
    case (uint8_t)CO402_READY:
        if ((cmd == CMD_SWITCH_ON) || (cmd == CMD_ENABLE)) {
            if (enable_input(ax)) {
                enter(ax, CO402_SWITCHED_ON); /* 3 (the hardware enable gates it) */
                return true;
            }
        } else if ((cmd == CMD_DISABLE_VOLTAGE) || (cmd == CMD_QUICK_STOP)) {
            enter(ax, CO402_SWITCH_ON_DISABLED); /* 7 */
            return true;
        } else {
            /* shutdown: already there */
        }
        break;
    case (uint8_t)CO402_SWITCHED_ON:
        if (cmd == CMD_ENABLE) {
            enter(ax, CO402_OPERATION_ENABLED); /* 4 */
            return true;
        }
        if (cmd == CMD_SHUTDOWN) {
            enter(ax, CO402_READY); /* 6 */
            return true;
        }
        if ((cmd == CMD_DISABLE_VOLTAGE) || (cmd == CMD_QUICK_STOP)) {
            enter(ax, CO402_SWITCH_ON_DISABLED); /* 10 */
            return true;
        }
        break;
    case (uint8_t)CO402_OPERATION_ENABLED:
        if (cmd == CMD_ENABLE) {
            if ((ax->drive == (uint8_t)DRV_STOP) && !ax->loss) {
                ax->drive = (uint8_t)DRV_RUN; /* a pending 5 / 8 is called off */
                co402_mode_enter(ax);
            }
        } else if (cmd == CMD_SWITCH_ON) {
            leave_operation(ax, O_DO_OPT, CO402_SWITCHED_ON); /* 5 */
            return true;
        } else if (cmd == CMD_SHUTDOWN) {
            leave_operation(ax, O_SD_OPT, CO402_READY); /* 8 */
            return true;
        } else if (cmd == CMD_DISABLE_VOLTAGE) {
            enter(ax, CO402_SWITCH_ON_DISABLED); /* 9 */
            return true;
        } else if (cmd == CMD_QUICK_STOP) {
            quick_stop(ax); /* 11 */
            return true;
        } else {
            /* nothing */
        }
        break;
    case (uint8_t)CO402_QUICK_STOP_ACTIVE:
        if (cmd == CMD_DISABLE_VOLTAGE) {
            enter(ax, CO402_SWITCH_ON_DISABLED); /* 12 */
            return true;
        }
        if ((cmd == CMD_ENABLE) && (qs_code(ax) >= 5) && (qs_code(ax) <= 8)) {
            enter(ax, CO402_OPERATION_ENABLED); /* 16 */
            return true;
        }
        break;
    default:
        break;
    }
    return false;
}

static bool faults_pending(const co402_axis_t *ax)
{
    for (uint8_t i = 0U; i < CO402_FAULTS_MAX; i++) {
        if (ax->faults[i] != 0U) {
            return true;
        }
    }
    return ax->fb.fault != 0U;
}

/* Transition 15. The errors end (EMCY 0x0000) at the next tick, so that the
 * answer to the controlword write that reset them goes out first. */
static void fault_reset(co402_axis_t *ax)
{
    for (uint8_t i = 0U; i < CO402_FAULTS_MAX; i++) {
        if (ax->raised[i] != 0U) {
            ax->to_clear[i] = ax->raised[i];
            ax->raised[i] = 0U;
        }
    }
    co402_put(ax, O_ERR, 0);
    enter(ax, CO402_SWITCH_ON_DISABLED); /* 15 */
}

/* CO402_OPT_LOSS_WARN_STOP: a fault reset ends the connection-loss warning;
 * an axis held in Operation enabled by it runs its mode again. */
static void loss_reset(co402_axis_t *ax)
{
    ax->loss = false;
    if ((ax->state == (uint8_t)CO402_OPERATION_ENABLED) &&
        ((ax->drive == (uint8_t)DRV_HOLD) ||
         ((ax->drive == (uint8_t)DRV_STOP) &&
          (ax->after_stop == (uint8_t)CO402_QUICK_STOP_ACTIVE)))) {
        ax->drive = (uint8_t)DRV_RUN;
        co402_mode_enter(ax);
    }
}

static void controlword(co402_axis_t *ax, uint16_t cw)
{
    uint16_t old = ax->cw;

    ax->cw = cw;
    if (((ax->cfg.options & CO402_OPT_NMT_OPERATIONAL) != 0U) &&
        (ax->nmt != (uint8_t)CO_NMT_OPERATIONAL)) {
        publish_sw(ax);
        return;
    }
    if (ax->loss && ((cw & CO402_CW_FAULT_RESET) != 0U) && ((old & CO402_CW_FAULT_RESET) == 0U)) {
        loss_reset(ax);
    }
    if (ax->state == (uint8_t)CO402_FAULT) {
        if (((cw & CO402_CW_FAULT_RESET) != 0U) && ((old & CO402_CW_FAULT_RESET) == 0U) &&
            !faults_pending(ax)) {
            fault_reset(ax);
        }
    } else if (ax->state != (uint8_t)CO402_FAULT_REACTION) {
        uint8_t cmd = decode(ax, cw);
        if (transition(ax, cmd) && ((ax->cfg.options & CO402_OPT_ONE_TRANSITION) == 0U)) {
            /* "switch on + enable operation" from Ready: 3 then 4 */
            if ((cmd == CMD_ENABLE) && (ax->state == (uint8_t)CO402_SWITCHED_ON)) {
                (void)transition(ax, cmd);
            }
        }
        if ((ax->state == (uint8_t)CO402_OPERATION_ENABLED) && (ax->drive == (uint8_t)DRV_RUN)) {
            co402_mode_cw(ax, old, cw);
        }
    } else {
        /* Fault reaction active: no command */
    }
    publish_sw(ax);
}

/* ------------------------------------------------------------ faults */

static uint8_t reg_bits(uint16_t code)
{
    switch (code >> 12U) {
    case 0x2U:
        return CO_ERREG_CURRENT;
    case 0x3U:
        return CO_ERREG_VOLTAGE;
    case 0x4U:
        return CO_ERREG_TEMPERATURE;
    case 0x8U:
        return ((code & 0xFF00U) == 0x8100U) ? CO_ERREG_COMM : CO_ERREG_PROFILE;
    case 0xFU:
        return CO_ERREG_MANUFACTURER;
    default:
        return 0U;
    }
}

/* Raise the EMCY of @p code as the device reports it (co402_config_t.errors). */
static void emcy_raise(co402_axis_t *ax, uint16_t code)
{
    for (uint8_t i = 0U; i < ax->cfg.n_errors; i++) {
        const co402_error_t *e = &ax->cfg.errors[i];
        if (e->code == code) {
            co_emcy_raise(ax->node, code, e->reg, e->mfr);
            return;
        }
    }
    co_emcy_raise(ax->node, code, reg_bits(code), NULL);
}

static void fault_enter(co402_axis_t *ax, uint16_t code)
{
    bool known = false;

    for (uint8_t i = 0U; i < CO402_FAULTS_MAX; i++) {
        if (ax->raised[i] == code) {
            known = true;
        }
    }
    for (uint8_t i = 0U; (i < CO402_FAULTS_MAX) && !known; i++) {
        if (ax->raised[i] == 0U) {
            ax->raised[i] = code;
            known = true;
        }
    }
    if (ax->node != NULL) {
        emcy_raise(ax, code);
    }
    if ((ax->state != (uint8_t)CO402_FAULT_REACTION) && (ax->state != (uint8_t)CO402_FAULT)) {
        co402_put(ax, O_ERR, code);
        fault_reaction(ax);
    }
    publish_sw(ax);
}

void co402_fault_raise(co402_axis_t *ax, uint16_t code)
{
    bool present = false;

    for (uint8_t i = 0U; i < CO402_FAULTS_MAX; i++) {
        if (ax->faults[i] == code) {
            present = true;
        }
    }
    for (uint8_t i = 0U; (i < CO402_FAULTS_MAX) && !present; i++) {
        if (ax->faults[i] == 0U) {
            ax->faults[i] = code;
            present = true;
        }
    }
    fault_enter(ax, code);
}

void co402_fault_clear(co402_axis_t *ax, uint16_t code)
{
    for (uint8_t i = 0U; i < CO402_FAULTS_MAX; i++) {
        if (ax->faults[i] == code) {
            ax->faults[i] = 0U;
        }
    }
}

void co402_fault_event(co402_axis_t *ax, uint16_t code)
{
    fault_enter(ax, code);
}

void co402_set_warning(co402_axis_t *ax, bool on)
{
    ax->warning = on;
    publish_sw(ax);
}

bool co402_connection_lost(const co402_axis_t *ax)
{
    return ax->loss;
}

co402_state_t co402_state(const co402_axis_t *ax)
{
    return (co402_state_t)ax->state;
}

int32_t co402_position(const co402_axis_t *ax)
{
    return (int32_t)div_floor(ax->pos + (CO402_Q16 / 2), CO402_Q16);
}

int32_t co402_velocity(const co402_axis_t *ax)
{
    return (int32_t)div_floor(ax->vel + (CO402_Q16 / 2), CO402_Q16);
}

/* ------------------------------------------------------------- hooks */

static co_err_t hook_cw(void *ctx, co_od_io_t *io)
{
    co402_axis_t *ax = (co402_axis_t *)ctx;

    if (io->len != 2U) {
        return CO_ERR_TYPE_MISMATCH;
    }
    controlword(ax, co_get_u16(io->buf));
    return CO_OK;
}

static void apply_mode(co402_axis_t *ax, int8_t mode)
{
    if (mode == ax->mode) {
        return;
    }
    ax->mode = mode;
    co402_put(ax, O_MODE_DISP, mode);
    if ((ax->state == (uint8_t)CO402_OPERATION_ENABLED) && (ax->drive == (uint8_t)DRV_RUN)) {
        co402_mode_enter(ax);
    }
    publish_sw(ax);
}

static co_err_t hook_mode(void *ctx, co_od_io_t *io)
{
    co402_axis_t *ax = (co402_axis_t *)ctx;
    int8_t mode = (int8_t)io->buf[0];
    int64_t v = (ax->vel < 0) ? -ax->vel : ax->vel;

    if (!co402_mode_supported(ax, mode)) {
        return CO_ERR_VALUE;
    }
    if (((ax->cfg.options & CO402_OPT_MODE_AT_REST) != 0U) && (mode != ax->mode) &&
        (ax->state == (uint8_t)CO402_OPERATION_ENABLED) &&
        ((v > co402_standstill(ax)) || (co402_get(ax, O_TARGET_VEL, 0) != 0))) {
        return CO_ERR_STORE_STATE;
    }
    apply_mode(ax, mode);
    return CO_OK;
}

static co_err_t hook_method(void *ctx, co_od_io_t *io)
{
    return co402_hm_accepted((const co402_axis_t *)ctx, (int8_t)io->buf[0]) ? CO_OK : CO_ERR_VALUE;
}

/* --------------------------------------------------------- the tick */

static void read_plant(co402_axis_t *ax, uint32_t now)
{
    ax->cfg.plant.ops->update(ax->cfg.plant.ctx, now, &ax->fb);
    ax->pos = ax->fb.pos + ax->shift;
    ax->vel = ax->fb.vel;
}

static void publish_actuals(co402_axis_t *ax, const co402_demand_t *d)
{
    int64_t demand = (d->kind == (uint8_t)CO402_DEMAND_POSITION) ? (d->pos + ax->shift) : ax->pos;

    co402_put(ax, O_POS_INTERNAL, div_floor(ax->pos + (CO402_Q16 / 2), CO402_Q16));
    co402_put(ax, O_POS_ACTUAL, co402_pos_out(ax, ax->pos));
    co402_put(ax, O_POS_DEMAND, co402_pos_out(ax, demand));
    co402_put(ax, O_FE_ACTUAL, co402_pos_out(ax, demand) - co402_pos_out(ax, ax->pos));
    co402_put(ax, O_VEL_ACTUAL, co402_vel_out(ax, ax->vel));
    co402_put(ax, O_VEL_DEMAND, co402_vel_out(ax, (d->kind == (uint8_t)CO402_DEMAND_OFF) ? 0 : d->vel));
    co402_put(ax, O_TORQUE_ACTUAL, ax->fb.torque);
    co402_put(ax, O_TORQUE_DEMAND, (d->kind == (uint8_t)CO402_DEMAND_TORQUE) ? d->torque : ax->fb.torque);
    co402_put(ax, O_DIG_IN, ax->fb.inputs & (CO402_IN_NEG_LIMIT | CO402_IN_POS_LIMIT | CO402_IN_HOME));
    if (co402_has(ax, O_VL_ACTUAL) || co402_has(ax, O_VL_DEMAND)) {
        /* rpm, rounded: v * 60 / (increments per revolution) */
        int64_t per = (int64_t)co402_counts_per_rev(ax) * CO402_Q16;
        int64_t dv = (d->kind == (uint8_t)CO402_DEMAND_OFF) ? 0 : ax->tr_v;
        co402_put(ax, O_VL_ACTUAL, div_floor((ax->vel * 60) + (per / 2), per));
        co402_put(ax, O_VL_DEMAND, div_floor((dv * 60) + (per / 2), per));
    }
}

static void check_following(co402_axis_t *ax, const co402_demand_t *d)
{
    uint32_t window = (uint32_t)co402_get(ax, O_FE_WINDOW, 0xFFFFFFFFLL);
    /* statusword bit 13 is "following error" in pp, ip and csp only */
    bool bit13 = (ax->mode == CO402_MODE_PP) || (ax->mode == CO402_MODE_IP) ||
                 (ax->mode == CO402_MODE_CSP);
    int64_t err;

    if ((d->kind != (uint8_t)CO402_DEMAND_POSITION) || (window == 0xFFFFFFFFU) ||
        !co402_has(ax, O_FE_WINDOW) || (ax->state != (uint8_t)CO402_OPERATION_ENABLED)) {
        err = 0;
    } else {
        err = co402_pos_out(ax, d->pos + ax->shift) - co402_pos_out(ax, ax->pos);
        if (err < 0) {
            err = -err;
        }
    }
    if (err <= (int64_t)window) {
        ax->fe_on = false;
        if (bit13) {
            ax->msw &= (uint16_t)~CO402_SW_OMS2;
        }
        return;
    }
    if (!ax->fe_on) {
        ax->fe_on = true;
        ax->fe_timer = ax->now;
    }
    if ((ax->now - ax->fe_timer) >= ((uint32_t)co402_get(ax, O_FE_TIMEOUT, 0) * 1000U)) {
        if (bit13) {
            ax->msw |= CO402_SW_OMS2;
        }
        if ((ax->cfg.options & CO402_OPT_FE_WARN_ONLY) == 0U) {
            co402_fault_event(ax, CO402_ERR_FOLLOWING);
        }
    }
}

static void check_plant(co402_axis_t *ax)
{
    uint16_t f = ax->fb.fault;

    if (f != ax->plant_fault) {
        if (ax->plant_fault != 0U) {
            co402_fault_clear(ax, ax->plant_fault);
        }
        ax->plant_fault = f;
        if (f != 0U) {
            co402_fault_raise(ax, f);
        }
    }
    if (!enable_input(ax)) {
        if ((ax->state == (uint8_t)CO402_SWITCHED_ON) ||
            (ax->state == (uint8_t)CO402_OPERATION_ENABLED) ||
            (ax->state == (uint8_t)CO402_QUICK_STOP_ACTIVE)) {
            if ((ax->cfg.options & CO402_OPT_REMOTE_IS_ENABLE) != 0U) {
                enter(ax, CO402_SWITCH_ON_DISABLED);
            } else {
                power_off(ax); /* the power stage has lost its enable: no ramp */
                co402_fault_raise(ax, CO402_ERR_ENABLE);
            }
        }
    } else {
        co402_fault_clear(ax, CO402_ERR_ENABLE);
    }
}

static void run_tick(co402_axis_t *ax, uint32_t now)
{
    co402_demand_t d;

    ax->now = now;
    for (uint8_t i = 0U; i < CO402_FAULTS_MAX; i++) {
        if (ax->to_clear[i] != 0U) {
            co_emcy_clear(ax->node, ax->to_clear[i]);
            ax->to_clear[i] = 0U;
        }
    }
    read_plant(ax, now);
    check_plant(ax);
    (void)memset(&d, 0, sizeof d);
    switch (ax->drive) {
    case (uint8_t)DRV_RUN:
        co402_mode_run(ax, &d);
        break;
    case (uint8_t)DRV_STOP:
        if (co402_stop_step(ax, ax->stop_kind, &d)) {
            if (ax->after_stop == (uint8_t)CO402_QUICK_STOP_ACTIVE) {
                ax->drive = (uint8_t)DRV_HOLD;
                ax->target = ax->tr_p;
                ax->msw |= CO402_SW_TARGET;
            } else {
                enter(ax, (co402_state_t)ax->after_stop);
            }
        }
        break;
    case (uint8_t)DRV_HOLD: {
        co402_traj_t t;
        co402_traj_get(ax, &t);
        (void)co402_traj_pos(&t, ax->target, 0U, co402_quick_dec(ax), co402_quick_dec(ax),
                             co402_tick(ax));
        co402_traj_put(ax, &t);
        co402_demand_pos(ax, &d, &t);
        break;
    }
    default:
        co402_sync_traj(ax);
        d.kind = (uint8_t)CO402_DEMAND_OFF;
        break;
    }
    if ((ax->drive == (uint8_t)DRV_OFF) && (d.kind != (uint8_t)CO402_DEMAND_OFF)) {
        d.kind = (uint8_t)CO402_DEMAND_OFF; /* the state changed during this tick */
    }
    d.torque_limit = (uint16_t)co402_get(ax, O_MAX_TORQUE, 0);
    check_following(ax, &d);
    ax->cfg.plant.ops->command(ax->cfg.plant.ctx, &d);
    publish_actuals(ax, &d);
    publish_sw(ax);
}

/* ----------------------------------------------------- plug-in ops */

void co402_init(co402_axis_t *ax, const co402_config_t *cfg)
{
    (void)memset(ax, 0, sizeof *ax);
    ax->cfg = *cfg;
}

static void start_axis(co402_axis_t *ax, uint32_t now)
{
    ax->now = now;
    ax->next_tick = now;
    ax->shift = 0;
    ax->cw = (uint16_t)co402_get(ax, O_CW, 0);
    (void)memset(ax->faults, 0, sizeof ax->faults);
    (void)memset(ax->raised, 0, sizeof ax->raised);
    (void)memset(ax->to_clear, 0, sizeof ax->to_clear);
    ax->plant_fault = 0U;
    ax->loss = false;
    ax->msw = 0U;
    ax->pp_flags = 0U;
    ax->hm_phase = (uint8_t)HM_IDLE;
    read_plant(ax, now);
    co402_sync_traj(ax);
    ax->state = (uint8_t)CO402_NOT_READY; /* 0 */
    ax->drive = (uint8_t)DRV_OFF;
    ax->mode = (int8_t)co402_get(ax, O_MODE, 0);
    if ((ax->cfg.options & CO402_OPT_VELOCITY_RAMP) != 0U) {
        ax->mode = CO402_MODE_RAMP; /* the one mode; no 0x6060 */
    } else if (!co402_mode_supported(ax, ax->mode)) {
        ax->mode = CO402_MODE_NONE;
    } else {
        /* a supported mode */
    }
    co402_put(ax, O_MODE_DISP, ax->mode);
    co402_put(ax, O_ERR, 0);
    enter(ax, CO402_SWITCH_ON_DISABLED); /* 1: initialisation done */
    publish_sw(ax);
}

static co_err_t op_attach(void *inst, co_node_t *node, uint32_t now_us)
{
    co402_axis_t *ax = (co402_axis_t *)inst;
    co_od_hook_t h;

    if ((ax->cfg.plant.ops == NULL) || (ax->cfg.axis > 7U)) {
        return CO_ERR_VALUE;
    }
    ax->node = node;
    bind_objects(ax);
    if (!co402_has(ax, O_CW) || !co402_has(ax, O_SW)) {
        ax->node = NULL;
        return CO_ERR_OD_MISSING;
    }
    h.read = NULL;
    h.ctx = ax;
    h.write = hook_cw;
    if (co_od_bind_hook(node, axis_index(ax, 0x6040U), &h) != CO_RESULT_OK) {
        ax->node = NULL;
        return CO_ERR_OD_MISSING; /* the controlword must be seen as it is written */
    }
    h.write = hook_mode;
    (void)co_od_bind_hook(node, axis_index(ax, 0x6060U), &h); /* else polled each tick */
    h.write = hook_method;
    (void)co_od_bind_hook(node, axis_index(ax, 0x6098U), &h);
    ax->nmt = (uint8_t)co_node_nmt_state(node);
    start_axis(ax, now_us);
    ax->attached = true;
    return CO_OK;
}

#ifndef CO402_IDLE_US
#define CO402_IDLE_US 100000U /**< wake-up period of an axis at rest with its power stage off */
#endif

/* With the power stage off and the motor standing, nothing in the axis
 * changes with time alone: it wakes up only every CO402_IDLE_US. Whatever
 * could change that (a controlword by SDO or RPDO) arrives in a frame, and
 * the node is processed after every frame: the ticks missed until then run
 * at once, with the same results as one by one. */
static bool at_rest(const co402_axis_t *ax)
{
    return ((ax->state == (uint8_t)CO402_SWITCH_ON_DISABLED) ||
            (ax->state == (uint8_t)CO402_READY) ||
            (ax->state == (uint8_t)CO402_SWITCHED_ON)) &&
           (ax->vel == 0);
}

static uint32_t op_process(void *inst, uint32_t now_us)
{
    co402_axis_t *ax = (co402_axis_t *)inst;
    uint32_t tick = co402_tick(ax);
    unsigned n = 0U;

    if (!ax->attached) {
        return CO_NO_DEADLINE;
    }
    if ((int32_t)(ax->next_tick - now_us) > (int32_t)(CO402_IDLE_US + tick)) {
        /* the next tick is never more than a tick (or the rest period) ahead:
         * the caller's clock jumped by 2^31 us or more (a stall), which the
         * wrap-safe comparison takes for a time 35 minutes back */
        ax->next_tick = now_us;
    }
    while ((int32_t)(now_us - ax->next_tick) >= 0) {
        int8_t m = (int8_t)co402_get(ax, O_MODE, ax->mode);
        if ((m != ax->mode) && ((ax->cfg.options & CO402_OPT_VELOCITY_RAMP) == 0U) &&
            co402_mode_supported(ax, m)) {
            apply_mode(ax, m); /* a device without a hook slot on 0x6060 */
        }
        run_tick(ax, ax->next_tick);
        ax->next_tick += tick;
        if (++n >= 1000U) {
            ax->next_tick = now_us + tick; /* far behind: skip, do not run for ever */
            break;
        }
    }
    if (at_rest(ax) && ((int32_t)((now_us + CO402_IDLE_US) - ax->next_tick) > 0)) {
        return now_us + CO402_IDLE_US;
    }
    return ax->next_tick;
}

static void op_sync(void *inst, uint8_t counter, uint32_t now_us)
{
    co402_axis_t *ax = (co402_axis_t *)inst;

    (void)counter;
    if (ax->attached) {
        co402_mode_sync(ax, now_us);
    }
}

/* 0x6007 abort connection option code: 1 fault, 2 disable voltage, 3 quick stop. */
static void abort_connection(co402_axis_t *ax, uint16_t code)
{
    switch (co402_get(ax, O_ABORT, 0)) {
    case 1:
        co402_fault_event(ax, code);
        break;
    case 2:
        if ((ax->state != (uint8_t)CO402_FAULT_REACTION) && (ax->state != (uint8_t)CO402_FAULT)) {
            (void)transition(ax, CMD_DISABLE_VOLTAGE);
        }
        break;
    case 3:
        if (ax->state == (uint8_t)CO402_OPERATION_ENABLED) {
            quick_stop(ax);
        } else {
            (void)transition(ax, CMD_QUICK_STOP);
        }
        break;
    default:
        break;
    }
    publish_sw(ax);
}

static void op_nmt_state(void *inst, co_nmt_state_t state, uint32_t now_us)
{
    co402_axis_t *ax = (co402_axis_t *)inst;
    uint8_t was = ax->nmt;

    (void)now_us;
    ax->nmt = (uint8_t)state;
    if (ax->attached && (was == (uint8_t)CO_NMT_OPERATIONAL) && (state == CO_NMT_STOPPED)) {
        abort_connection(ax, CO402_ERR_COMM);
    }
}

static void op_reset(void *inst, co_reset_t kind, uint32_t now_us)
{
    co402_axis_t *ax = (co402_axis_t *)inst;

    if (ax->attached && (kind == CO_RESET_NODE)) {
        /* the application objects are back at their defaults and the core
         * has dropped its active errors: start over */
        start_axis(ax, now_us);
    }
}

/* CO402_OPT_LOSS_WARN_STOP: the warning; an axis that runs its mode stops
 * on the quick-stop ramp and holds at rest (in Operation enabled). */
static void loss_warning(co402_axis_t *ax)
{
    ax->loss = true;
    if ((ax->state == (uint8_t)CO402_OPERATION_ENABLED) && (ax->drive == (uint8_t)DRV_RUN)) {
        start_stop(ax, (uint8_t)STOP_QUICK, CO402_QUICK_STOP_ACTIVE);
    }
    publish_sw(ax);
}

static void op_error_control(void *inst, co_hb_event_t ev, uint8_t id, uint32_t now_us)
{
    co402_axis_t *ax = (co402_axis_t *)inst;

    (void)id;
    (void)now_us;
    if (ax->attached && ((ev == CO_HB_TIMEOUT) || (ev == CO_GUARD_LOST))) {
        if ((ax->cfg.options & CO402_OPT_LOSS_WARN_STOP) != 0U) {
            loss_warning(ax);
        } else {
            abort_connection(ax, CO402_ERR_HB_GUARD);
        }
    }
}

const co_profile_ops_t co402_profile_ops = {
    .name = "cia402",
    .attach = op_attach,
    .process = op_process,
    .sync = op_sync,
    .nmt_state = op_nmt_state,
    .reset = op_reset,
    .error_control = op_error_control,
};
