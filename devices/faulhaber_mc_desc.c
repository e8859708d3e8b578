/*
 * faulhaber-mc: the device and its plug-in (faulhaber_mc_desc.h).
 */
#include "faulhaber_mc_desc.h"


#include <string.h>

#include "co/co_endian.h"

#define NUMERATOR_MAX 2000000000ULL /* factor group: numerator below 2e9 */

typedef struct fh_error {
    uint16_t bit;
    uint16_t code;     /* EMCY code (deviation: the pp one; pv uses 0x8611) */
    uint8_t reg;       /* 0x1001 bits besides generic */
    uint8_t flags;     /* FH_* */
} fh_error_t;

#define FH_DELAYED 0x01U /* reported after the error delay 0x2322.01 */
#define FH_CORE    0x02U /* also raised by the core or the CAN port (their EMCY, with
                            0x2320 filled in by emcy_mfr) */
#define FH_STICKY  0x04U /* never withdrawn: the 0x2320 bit stays (CAN overrun, bus-off) */

static const fh_error_t errors[] = {
    {FAULHABER_ERR_OVERCURRENT, 0x2310U, CO_ERREG_CURRENT, FH_DELAYED},
    {FAULHABER_ERR_DEVIATION, 0x8400U, CO_ERREG_PROFILE, FH_DELAYED},
    {FAULHABER_ERR_OVERVOLTAGE, 0x3210U, CO_ERREG_VOLTAGE, FH_DELAYED},
    {FAULHABER_ERR_TEMPERATURE, 0x4310U, CO_ERREG_TEMPERATURE, 0U},
    {FAULHABER_ERR_FLASH, 0x5530U, CO_ERREG_PROFILE, 0U},
    {FAULHABER_ERR_CAN_PASSIVE, 0x8120U, CO_ERREG_COMM, FH_CORE},
    {FAULHABER_ERR_CAN_OVERRUN, 0x8110U, CO_ERREG_COMM, FH_CORE | FH_STICKY},
    {FAULHABER_ERR_GUARDING, 0x8130U, CO_ERREG_COMM, FH_CORE},
    {FAULHABER_ERR_BUS_OFF, 0x8140U, CO_ERREG_COMM, FH_CORE | FH_STICKY},
    {FAULHABER_ERR_CONVERSION, 0xFF01U, 0U, 0U},
    {FAULHABER_ERR_SOFTWARE, 0x6100U, CO_ERREG_PROFILE, 0U},
    {FAULHABER_ERR_PDO_LONG, 0x8220U, CO_ERREG_COMM, FH_CORE},
    {FAULHABER_ERR_PDO_SHORT, 0x8210U, CO_ERREG_COMM, FH_CORE},
};

#define N_ERRORS (sizeof errors / sizeof errors[0])

/* ------------------------------------------------------------ helpers */

static faulhaber_mc_state_t *state(const co_device_run_t *r)
{
    return (faulhaber_mc_state_t *)co_device_state(r);
}

static uint16_t u16_at(co_node_t *node, uint16_t index, uint8_t sub)
{
    const uint16_t *p = (const uint16_t *)co_od_value_ptr(node, index, sub);
    return (p != NULL) ? *p : 0U;
}

static void set_u16(co_node_t *node, uint16_t index, uint8_t sub, uint16_t v)
{
    uint16_t *p = (uint16_t *)co_od_value_ptr(node, index, sub);
    if (p != NULL) {
        *p = v;
    }
}

static uint32_t u32_at(co_node_t *node, uint16_t index, uint8_t sub)
{
    const uint32_t *p = (const uint32_t *)co_od_value_ptr(node, index, sub);
    return (p != NULL) ? *p : 0U;
}

static uint8_t bit_no(uint16_t bit)
{
    uint8_t n = 0U;
    while ((n < 15U) && ((bit >> n) != 1U)) {
        n++;
    }
    return n;
}

/* ------------------------------------------------------------- errors */

/* Report error @p e: 0x2320, EMCY with 0x2320 in bytes 3-4 (emergency
 * mask), Fault (fault mask). */
static void report(co_device_run_t *r, const fh_error_t *e)
{
    faulhaber_mc_state_t *st = state(r);
    uint16_t reg = (uint16_t)(u16_at(co_device_node(r), 0x2320U, 0U) | e->bit);
    uint16_t code = e->code;
    uint8_t mfr[5] = {(uint8_t)(reg & 0xFFU), (uint8_t)(reg >> 8U), 0U, 0U, 0U};
    const int8_t *mode = (const int8_t *)co_od_value_ptr(co_device_node(r), 0x6061U, 0U);

    if ((e->bit == FAULHABER_ERR_DEVIATION) && (mode != NULL) && (*mode == CO402_MODE_PV)) {
        code = 0x8611U; /* as printed: 0x8611 in pv, 0x8400 in pp */
    }
    st->code[bit_no(e->bit)] = code;
    set_u16(co_device_node(r), 0x2320U, 0U, reg);
    if ((u16_at(co_device_node(r), 0x2321U, 1U) & e->bit) != 0U) {
        co_emcy_raise(co_device_node(r), code, e->reg, mfr);
    }
    if (((u16_at(co_device_node(r), 0x2321U, 2U) & e->bit) != 0U) && (co402_device_axis(r, 0U) != NULL)) {
        co402_fault_raise(co402_device_axis(r, 0U), code);
    }
}

static void withdraw(co_device_run_t *r, const fh_error_t *e)
{
    faulhaber_mc_state_t *st = state(r);
    uint16_t code = st->code[bit_no(e->bit)];

    set_u16(co_device_node(r), 0x2320U, 0U, (uint16_t)(u16_at(co_device_node(r), 0x2320U, 0U) & ~e->bit));
    co_emcy_clear(co_device_node(r), code);
    if (co402_device_axis(r, 0U) != NULL) {
        co402_fault_clear(co402_device_axis(r, 0U), code);
    }
}

/* The errors the core raised: when the core has ended one, its 0x2320 bit
 * goes (not the sticky ones) and the fault condition with it; with @p react,
 * the fault mask puts the axis into Fault once for each that lasts (not
 * inside the core's call: the fault raises an EMCY). */
static void core_errors(co_device_run_t *r, bool react)
{
    faulhaber_mc_state_t *st = state(r);
    co_node_t *node = co_device_node(r);
    co402_axis_t *ax = co402_device_axis(r, 0U);

    for (size_t i = 0U; i < N_ERRORS; i++) {
        const fh_error_t *e = &errors[i];
        if ((st->core & e->bit) == 0U) {
            continue;
        }
        if (!co_emcy_is_active(node, e->code)) {
            st->core &= (uint16_t)~e->bit;
            st->faulted &= (uint16_t)~e->bit;
            if ((e->flags & FH_STICKY) == 0U) {
                set_u16(node, 0x2320U, 0U, (uint16_t)(u16_at(node, 0x2320U, 0U) & ~e->bit));
            }
            if (ax != NULL) {
                co402_fault_clear(ax, e->code);
            }
        } else if (react && ((st->faulted & e->bit) == 0U) &&
                   ((u16_at(node, 0x2321U, 2U) & e->bit) != 0U) && (ax != NULL)) {
            st->faulted |= e->bit;
            co402_fault_raise(ax, e->code);
        } else {
            /* reported, or no fault reaction */
        }
    }
}

/* An EMCY the core (or the CAN port) raises without manufacturer data: its
 * 0x2320 bit is set and the EMCY carries 0x2320 in bytes 3-4, like the
 * FAULHABER's own (errors the core ended meanwhile are out of 0x2320
 * first). Its fault-mask reaction follows in op_process. */
static void op_emcy_mfr(void *inst, uint16_t code, uint8_t mfr[5])
{
    co_device_run_t *r = (co_device_run_t *)inst;
    co_node_t *node = co_device_node(r);
    uint16_t reg;

    core_errors(r, false);
    for (size_t i = 0U; i < N_ERRORS; i++) {
        if (((errors[i].flags & FH_CORE) != 0U) && (errors[i].code == code)) {
            set_u16(node, 0x2320U, 0U, (uint16_t)(u16_at(node, 0x2320U, 0U) | errors[i].bit));
            state(r)->core |= errors[i].bit;
        }
    }
    reg = u16_at(node, 0x2320U, 0U);
    mfr[0] = (uint8_t)(reg & 0xFFU);
    mfr[1] = (uint8_t)(reg >> 8U);
}

void faulhaber_mc_error(co_device_run_t *r, uint16_t bit, bool on)
{
    faulhaber_mc_state_t *st = state(r);

    for (size_t i = 0U; i < N_ERRORS; i++) {
        if (errors[i].bit != bit) {
            continue;
        }
        if (on && ((st->present & bit) == 0U)) {
            st->present |= bit;
            st->since[bit_no(bit)] = co_device_node(r)->now;
        } else if (!on && ((st->present & bit) != 0U)) {
            st->present &= (uint16_t)~bit;
            if ((u16_at(co_device_node(r), 0x2320U, 0U) & bit) != 0U) {
                withdraw(r, &errors[i]);
            }
        } else {
            /* no change */
        }
    }
}

/* ------------------------------------------------------- factor group */

static uint64_t gcd64(uint64_t a, uint64_t b)
{
    while (b != 0U) {
        uint64_t t = a % b;
        a = b;
        b = t;
    }
    return a;
}

/* 0x6093 = encoder resolution x gear ratio / feed constant, with one value
 * replaced by the one being written (@p index, @p sub, @p v). */
static co_err_t factor(co_device_run_t *r, uint16_t index, uint8_t sub, uint32_t v, bool commit)
{
    uint64_t inc = u32_at(co_device_node(r), 0x608FU, 1U);
    uint64_t mrev = u32_at(co_device_node(r), 0x608FU, 2U);
    uint64_t gm = (index == 0x6091U && sub == 1U) ? v : u32_at(co_device_node(r), 0x6091U, 1U);
    uint64_t gs = (index == 0x6091U && sub == 2U) ? v : u32_at(co_device_node(r), 0x6091U, 2U);
    uint64_t feed = (index == 0x6092U && sub == 1U) ? v : u32_at(co_device_node(r), 0x6092U, 1U);
    uint64_t fs = (index == 0x6092U && sub == 2U) ? v : u32_at(co_device_node(r), 0x6092U, 2U);
    uint64_t num;
    uint64_t den;
    uint64_t g;
    uint32_t *p;

    if ((inc == 0U) || (mrev == 0U) || (gm == 0U) || (gs == 0U) || (feed == 0U) || (fs == 0U)) {
        return CO_ERR_VALUE;
    }
    if ((inc > 0xFFFFFFFFULL) || (gm * fs > 0xFFFFFFFFULL) || (mrev * gs > 0xFFFFFFFFULL)) {
        return CO_ERR_DEV_INCOMPAT;
    }
    num = inc * gm * fs;
    den = mrev * gs * feed;
    if ((num >= NUMERATOR_MAX) || (den >= NUMERATOR_MAX)) {
        return CO_ERR_DEV_INCOMPAT; /* 0x06040047: the product, before reducing */
    }
    g = gcd64(num, den);
    num /= g;
    den /= g;
    if (commit) {
        p = (uint32_t *)co_od_value_ptr(co_device_node(r), 0x6093U, 1U);
        if (p != NULL) {
            *p = (uint32_t)num;
        }
        p = (uint32_t *)co_od_value_ptr(co_device_node(r), 0x6093U, 2U);
        if (p != NULL) {
            *p = (uint32_t)den;
        }
    }
    return CO_OK;
}

/* -------------------------------------------------------------- hooks */

static co_err_t hook_guard_time(void *ctx, co_od_io_t *io)
{
    co_device_run_t *r = (co_device_run_t *)ctx;

    if ((co_get_u16(io->buf) != 0U) && (u16_at(co_device_node(r), 0x1017U, 0U) != 0U)) {
        return CO_ERR_STORE; /* guarding and heartbeat exclude each other */
    }
    return CO_OK;
}

static co_err_t hook_heartbeat(void *ctx, co_od_io_t *io)
{
    co_device_run_t *r = (co_device_run_t *)ctx;

    if (co_get_u16(io->buf) != 0U) {
        uint8_t *life = (uint8_t *)co_od_value_ptr(co_device_node(r), 0x100DU, 0U);
        set_u16(co_device_node(r), 0x100CU, 0U, 0U);
        if (life != NULL) {
            *life = 0U;
        }
    }
    return CO_OK;
}

static co_err_t hook_restore(void *ctx, co_od_io_t *io)
{
    co_device_run_t *r = (co_device_run_t *)ctx;

    if ((io->desc->sub >= 1U) && (io->desc->sub <= 3U) && (co402_device_axis(r, 0U) != NULL) &&
        (co402_state(co402_device_axis(r, 0U)) != CO402_SWITCH_ON_DISABLED)) {
        return CO_ERR_STORE_STATE; /* factory values only while disabled */
    }
    return CO_OK;
}

static co_err_t hook_inputs(void *ctx, co_od_io_t *io)
{
    co_device_run_t *r = (co_device_run_t *)ctx;
    const int8_t *mode = (const int8_t *)co_od_value_ptr(co_device_node(r), 0x6061U, 0U);

    (void)io;
    if ((mode != NULL) && (*mode == CO402_MODE_HM)) {
        return CO_ERR_STORE_STATE; /* not while in homing mode */
    }
    return CO_OK;
}

static co_err_t hook_masks(void *ctx, co_od_io_t *io)
{
    co_device_run_t *r = (co_device_run_t *)ctx;

    if (io->desc->sub == 2U) {
        /* the fault mask's bits are set in the emergency mask too */
        set_u16(co_device_node(r), 0x2321U, 1U, (uint16_t)(u16_at(co_device_node(r), 0x2321U, 1U) | co_get_u16(io->buf)));
    }
    return CO_OK;
}

static co_err_t hook_target_internal(void *ctx, co_od_io_t *io)
{
    co_device_run_t *r = (co_device_run_t *)ctx;
    int64_t inc = (int64_t)(int32_t)co_get_u32(io->buf);
    int64_t num = (int64_t)u32_at(co_device_node(r), 0x6093U, 1U);
    int64_t den = (int64_t)u32_at(co_device_node(r), 0x6093U, 2U);
    int32_t *target = (int32_t *)co_od_value_ptr(co_device_node(r), 0x607AU, 0U);

    if ((num == 0) || (den == 0) || (target == NULL)) {
        return CO_ERR_DEV_INCOMPAT;
    }
    *target = (int32_t)((inc * den) / num); /* internal = user * num / den */
    return CO_OK;
}

static co_err_t hook_factor(void *ctx, co_od_io_t *io)
{
    co_device_run_t *r = (co_device_run_t *)ctx;

    return factor(r, io->entry->index, io->desc->sub, co_get_u32(io->buf), true);
}

/* 0x2400 "Baudrate set": the bit-timing index in force, 0xFF automatic
 * detection (the factory state, seed-001 §1.4, §7.9) */
static co_err_t hook_baudrate(void *ctx, co_od_io_t *io)
{
    co_device_run_t *r = (co_device_run_t *)ctx;
    uint8_t *v = (uint8_t *)io->value;

    if (v != NULL) {
        *v = co_node_bit_timing(co_device_node(r));
    }
    return CO_OK;
}

/* ------------------------------------------------------------ plug-in */

static co_err_t op_attach(void *inst, co_node_t *node, uint32_t now_us)
{
    co_device_run_t *r = (co_device_run_t *)inst;
    static const struct {
        uint16_t index;
        co_err_t (*write)(void *ctx, co_od_io_t *io);
    } hooks[] = {
        {0x100CU, hook_guard_time}, {0x1017U, hook_heartbeat}, {0x1011U, hook_restore},
        {0x2310U, hook_inputs},     {0x2321U, hook_masks},     {0x257AU, hook_target_internal},
        {0x6091U, hook_factor},     {0x6092U, hook_factor},
    };

    (void)now_us;
    if (co_device_state(r) == NULL) {
        return CO_ERR_VALUE;
    }
    for (size_t i = 0U; i < (sizeof hooks / sizeof hooks[0]); i++) {
        co_od_hook_t h = {NULL, hooks[i].write, r};
        if (co_od_bind_hook(node, hooks[i].index, &h) != CO_RESULT_OK) {
            return CO_ERR_OD_MISSING;
        }
    }
    {
        co_od_hook_t h = {hook_baudrate, NULL, r};
        if (co_od_bind_hook(node, 0x2400U, &h) != CO_RESULT_OK) {
            return CO_ERR_OD_MISSING;
        }
    }
    (void)factor(r, 0U, 0U, 0U, true);
    return CO_OK;
}

static uint32_t op_process(void *inst, uint32_t now_us)
{
    co_device_run_t *r = (co_device_run_t *)inst;
    faulhaber_mc_state_t *st = state(r);
    uint32_t delay = (uint32_t)u16_at(co_device_node(r), 0x2322U, 1U) * 10000U; /* 1/100 s */
    uint32_t next = CO_NO_DEADLINE;
    uint16_t reg = u16_at(co_device_node(r), 0x2320U, 0U);

    for (size_t i = 0U; i < N_ERRORS; i++) {
        const fh_error_t *e = &errors[i];
        uint32_t due = st->since[bit_no(e->bit)] + (((e->flags & FH_DELAYED) != 0U) ? delay : 0U);
        if (((st->present & e->bit) == 0U) || ((reg & e->bit) != 0U)) {
            continue;
        }
        if ((int32_t)(now_us - due) >= 0) {
            report(r, e);
            reg = u16_at(co_device_node(r), 0x2320U, 0U);
        } else if ((next == CO_NO_DEADLINE) || ((int32_t)(due - next) < 0)) {
            next = due;
        } else {
            /* a later one */
        }
    }
    core_errors(r, true);
    if (co402_device_axis(r, 0U) != NULL) {
        /* 0x2562: last demand in increments; 0x2361: speed, unfiltered */
        int32_t *demand = (int32_t *)co_od_value_ptr(co_device_node(r), 0x2562U, 0U);
        int16_t *raw = (int16_t *)co_od_value_ptr(co_device_node(r), 0x2361U, 0U);
        const int32_t *user = (const int32_t *)co_od_value_ptr(co_device_node(r), 0x6062U, 0U);
        const int32_t *rpm = (const int32_t *)co_od_value_ptr(co_device_node(r), 0x606CU, 0U);
        int64_t num = (int64_t)u32_at(co_device_node(r), 0x6093U, 1U);
        int64_t den = (int64_t)u32_at(co_device_node(r), 0x6093U, 2U);
        if ((demand != NULL) && (user != NULL) && (num != 0) && (den != 0)) {
            *demand = (int32_t)(((int64_t)*user * num) / den);
        }
        if ((raw != NULL) && (rpm != NULL)) {
            *raw = (int16_t)((*rpm > 32767) ? 32767 : ((*rpm < -32768) ? -32768 : *rpm));
        }
    }
    return next;
}

static void op_reset(void *inst, co_reset_t kind, uint32_t now_us)
{
    co_device_run_t *r = (co_device_run_t *)inst;

    (void)now_us;
    if (kind == CO_RESET_NODE) {
        (void)memset(co_device_state(r), 0, sizeof(faulhaber_mc_state_t)); /* 0x2320 is back at 0 */
    }
    (void)factor(r, 0U, 0U, 0U, true);
}

const co_profile_ops_t faulhaber_mc_ops = {
    .name = "faulhaber-mc",
    .attach = op_attach,
    .process = op_process,
    .reset = op_reset,
    .emcy_mfr = op_emcy_mfr,
};

/* ---------------------------------------------------------------- device */

const co_device_plugin_t faulhaber_mc_plugin = {
    .ops = &faulhaber_mc_ops,
    .state_size = sizeof(faulhaber_mc_state_t),
};
