/*
 * CiA 408 valve channel: objects, the device state machine, faults, NMT
 * reactions, the control tick and the plug-in operations.
 */
#include <stddef.h>
#include <string.h>

#include "co/co_endian.h"
#include "co408_priv.h"

typedef char co408_obj_count_matches[(O_COUNT == CO408_OBJ_COUNT) ? 1 : -1];

/* ------------------------------------------------------------ objects */

typedef struct obj_ref {
    uint16_t index;
    uint8_t sub;
} obj_ref_t;

/* Indices of channel 0, in the order of the O_* enumeration. */
static const obj_ref_t obj_refs[O_COUNT] = {
    {0x6040U, 0U}, {0x6041U, 0U}, {0x6042U, 0U}, {0x6043U, 0U}, {0x604FU, 0U},
    {0x6300U, 1U}, {0x6301U, 1U}, {0x6330U, 0U}, {0x6332U, 1U}, {0x6333U, 1U}, {0x6335U, 1U},
    {0x6336U, 1U},
    {0x6380U, 1U}, {0x6381U, 1U}, {0x63B0U, 0U}, {0x63B2U, 1U}, {0x63B3U, 1U}, {0x63B5U, 1U},
    {0x63B6U, 1U}, {0x63D0U, 1U}, {0x63D1U, 0U}, {0x63D2U, 1U}, {0x63D3U, 1U},
    {0x6480U, 1U}, {0x64B0U, 0U}, {0x64B2U, 1U}, {0x64B3U, 1U}, {0x64B5U, 1U}, {0x64B6U, 1U},
    {0x6500U, 1U}, {0x6501U, 1U}, {0x6550U, 1U}, {0x6551U, 0U}, {0x6552U, 1U}, {0x6553U, 1U},
    {0x6600U, 1U}, {0x6601U, 1U}, {0x6650U, 1U}, {0x6651U, 0U}, {0x6652U, 1U}, {0x6653U, 1U},
    {0x2280U, 0U}, {0x2281U, 0U}, {0x22D0U, 0U}, {0x22D1U, 0U}, {0x22D2U, 1U}, {0x22D3U, 1U},
    {0x2329U, 0U}, {0x232AU, 0U}, {0x232BU, 0U}, {0x232CU, 0U}, {0x222BU, 0U}, {0x222CU, 0U},
    {0x232DU, 0U}, {0x232EU, 0U}, {0x2402U, 0U}, {0x2403U, 0U}, {0x2404U, 0U}, {0x2505U, 0U},
    {0x2585U, 0U}, {0x2324U, 0U}, {0x605FU, 0U},
};

static const co408_mode_t modes[] = {
    {CO408_MODE_VPOC, O_VPOC_SP, O_VPOC_ACT, O_NONE, O_VPOC_RT, O_NONE, 0U},
    {CO408_MODE_VPRC, O_VPRC_SP, O_NONE, O_NONE, O_VPRC_RT, O_NONE, 0U},
    {CO408_MODE_VPRC_CL, O_VPRC_SP, O_VPRC_ACT, O_VPRC_DEV, O_NONE, O_VPRC_FE,
     MODE_CLOSED | MODE_INTERNAL},
    {CO408_MODE_VPRC_2, O_VPRC_SP, O_VPRC_ACT, O_VPRC_DEV, O_NONE, O_VPRC_FE,
     MODE_CLOSED | MODE_INTERNAL},
    {CO408_MODE_DCOL, O_DCOL_SP, O_NONE, O_NONE, O_DCOL_RT, O_NONE, 0U},
    {CO408_MODE_DSC, O_DSC_SP, O_DSC_ACT, O_DSC_DEV, O_NONE, O_DSC_FE, MODE_CLOSED},
    {CO408_MODE_DPC, O_DPC_SP, O_DPC_ACT, O_DPC_DEV, O_NONE, O_DPC_FE, MODE_CLOSED},
    {CO408_MODE_NPT_1, O_NPT_SP, O_NPT_ACT, O_NPT_DEV, O_NONE, O_NPT_FE, MODE_CLOSED},
    {CO408_MODE_NPT_2, O_NPT_SP, O_NPT_ACT, O_NPT_DEV, O_NONE, O_NPT_FE, MODE_CLOSED},
    {CO408_MODE_NPT_3, O_NPT_SP, O_NPT_ACT, O_NPT_DEV, O_NONE, O_NPT_FE, MODE_CLOSED},
};

static uint16_t chan_index(const co408_valve_t *v, uint16_t index)
{
    uint16_t step = (index >= 0x6000U) ? 0x800U : 0x700U;
    return (uint16_t)(index + (step * v->cfg.channel));
}

static void bind_objects(co408_valve_t *v)
{
    for (uint8_t i = 0U; i < (uint8_t)O_COUNT; i++) {
        co_pobj_bind(&v->obj[i], v->node, chan_index(v, obj_refs[i].index), obj_refs[i].sub);
    }
}

const co408_mode_t *co408_mode_of(int8_t value)
{
    for (size_t i = 0U; i < (sizeof modes / sizeof modes[0]); i++) {
        if (modes[i].value == value) {
            return &modes[i];
        }
    }
    return NULL;
}

bool co408_mode_offered(const co408_valve_t *v, int8_t value)
{
    const co408_mode_t *m = co408_mode_of(value);

    if ((m == NULL) || !co_pobj_has(&v->obj[m->sp])) {
        return false;
    }
    if (v->cfg.modes == NULL) {
        return true;
    }
    for (uint8_t i = 0U; i < v->cfg.n_modes; i++) {
        if (v->cfg.modes[i] == value) {
            return true;
        }
    }
    return false;
}

/* --------------------------------------------------------- status word */

uint16_t co408_statusword(const co408_valve_t *v)
{
    /* R M H D per state */
    static const uint16_t state_bits[8] = {0x0000U, 0x0008U, 0x0009U, 0x000BU,
                                           0x000FU, 0x0007U, 0x0003U, 0x0001U};
    return (uint16_t)(state_bits[v->state & 7U] | v->msw);
}

static void publish_sw(co408_valve_t *v)
{
    co_pobj_put(&v->obj[O_SW], co408_statusword(v));
}

/* ------------------------------------------------------- state machine */

static bool normal_state(const co408_valve_t *v)
{
    return (v->state == (uint8_t)CO408_INIT) || (v->state == (uint8_t)CO408_DISABLED) ||
           (v->state == (uint8_t)CO408_HOLD) || (v->state == (uint8_t)CO408_ACTIVE);
}

static bool fault_state(const co408_valve_t *v)
{
    return (v->state == (uint8_t)CO408_FAULT) || (v->state == (uint8_t)CO408_FAULT_HOLD);
}

static void enter(co408_valve_t *v, co408_state_t st)
{
    uint8_t was = v->state;

    v->state = (uint8_t)st;
    switch (st) {
    case CO408_ACTIVE:
        co408_sp_enter_active(v);
        break;
    case CO408_HOLD:
        /* the set-point of DEVICE_MODE_ACTIVE is kept; from DISABLED or a
         * fault there is none yet */
        v->held = (was == (uint8_t)CO408_ACTIVE) ? co408_output(v) : 0;
        v->msw = 0U;
        break;
    case CO408_FAULT_REACTION:
        if (was == (uint8_t)CO408_ACTIVE) {
            v->held = co408_output(v); /* for FAULT_HOLD */
        } else if (was != (uint8_t)CO408_HOLD) {
            v->held = 0;
        } else {
            /* HOLD: keep its set-point */
        }
        v->msw = 0U;
        co408_sp_reset(v);
        break;
    case CO408_FAULT_HOLD:
        v->msw = 0U;
        break;
    default:
        v->held = 0;
        v->msw = 0U;
        co408_sp_reset(v);
        break;
    }
}

/* One transition for control word @p cw from the present state; true if
 * one was made (TR_2 .. TR_7). */
static bool transition(co408_valve_t *v, uint16_t cw)
{
    uint16_t dhm = (uint16_t)(cw & (CO408_CW_D | CO408_CW_H | CO408_CW_M));

    switch (v->state) {
    case (uint8_t)CO408_INIT:
        if ((cw & CO408_CW_D) != 0U) {
            enter(v, CO408_DISABLED); /* TR_2 */
            return true;
        }
        break;
    case (uint8_t)CO408_DISABLED:
        if ((cw & (CO408_CW_D | CO408_CW_H)) == (CO408_CW_D | CO408_CW_H)) {
            enter(v, CO408_HOLD); /* TR_3 */
            return true;
        }
        if (dhm == 0U) {
            enter(v, CO408_INIT); /* TR_7 */
            return true;
        }
        break;
    case (uint8_t)CO408_HOLD:
        if (dhm == (CO408_CW_D | CO408_CW_H | CO408_CW_M)) {
            enter(v, CO408_ACTIVE); /* TR_4 */
            return true;
        }
        if ((cw & (CO408_CW_H | CO408_CW_M)) == 0U) {
            enter(v, CO408_DISABLED); /* TR_6 */
            return true;
        }
        break;
    case (uint8_t)CO408_ACTIVE:
        if ((cw & CO408_CW_M) == 0U) {
            enter(v, CO408_HOLD); /* TR_5 */
            return true;
        }
        break;
    default:
        break;
    }
    return false;
}

/* The chain: transitions until none applies (at most four: INIT .. ACTIVE). */
static void evaluate(co408_valve_t *v, uint16_t cw)
{
    for (uint8_t n = 0U; (n < 4U) && transition(v, cw); n++) {
    }
}

static bool cause_present(const co408_valve_t *v)
{
    for (uint8_t i = 0U; i < CO408_FAULTS_MAX; i++) {
        if (v->faults[i] != 0U) {
            return true;
        }
    }
    return false;
}

/* TR_10 / TR_11: the errors end (EMCY 0x0000) at the next tick, so that the
 * answer to the write that reset them goes out first. */
static void fault_reset(co408_valve_t *v, uint16_t cw)
{
    bool hold = (v->state == (uint8_t)CO408_FAULT_HOLD) && ((cw & CO408_CW_H) != 0U);

    if (cause_present(v)) {
        return; /* the cause is still there: stay */
    }
    enter(v, hold ? CO408_HOLD : CO408_DISABLED);
    evaluate(v, cw);
}

static void control(co408_valve_t *v, uint16_t cw)
{
    uint16_t old = v->cw;

    v->cw = cw;
    if (fault_state(v)) {
        if (((cw & CO408_CW_R) != 0U) && ((old & CO408_CW_R) == 0U)) {
            fault_reset(v, cw);
        }
    } else if (normal_state(v)) {
        evaluate(v, cw);
    } else {
        /* NOT_READY, FAULT_REACTION: no command */
    }
    publish_sw(v);
}

/* -------------------------------------------------------------- faults */

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
    default:
        return 0U;
    }
}

static void remember(uint16_t *list, uint16_t code)
{
    for (uint8_t i = 0U; i < CO408_FAULTS_MAX; i++) {
        if (list[i] == code) {
            return;
        }
    }
    for (uint8_t i = 0U; i < CO408_FAULTS_MAX; i++) {
        if (list[i] == 0U) {
            list[i] = code;
            return;
        }
    }
}

static void forget(uint16_t *list, uint16_t code)
{
    for (uint8_t i = 0U; i < CO408_FAULTS_MAX; i++) {
        if (list[i] == code) {
            list[i] = 0U;
        }
    }
}

/* TR_8 (without the EMCY): outputs off, the reaction ends at the next tick. */
static void fault_reaction(co408_valve_t *v)
{
    if (normal_state(v)) {
        v->fr_hold = (v->state == (uint8_t)CO408_HOLD) || (v->state == (uint8_t)CO408_ACTIVE);
        enter(v, CO408_FAULT_REACTION);
    }
    publish_sw(v);
}

void co408_fault_event(co408_valve_t *v, uint16_t code)
{
    remember(v->raised, code);
    if (v->node != NULL) {
        co_emcy_raise(v->node, code, reg_bits(code), NULL);
    }
    fault_reaction(v);
}

void co408_fault_raise(co408_valve_t *v, uint16_t code)
{
    remember(v->faults, code);
    co408_fault_event(v, code);
}

void co408_fault_clear(co408_valve_t *v, uint16_t code)
{
    forget(v->faults, code);
}

/* NMT Stop / Reset Communication: TR_8 now, the 0x8100 error as soon as an
 * EMCY may go out (op_nmt_state). */
static void comm_fault(co408_valve_t *v)
{
    remember(v->raised, CO408_ERR_COMM);
    v->pending_comm = true;
    fault_reaction(v);
}

/* --------------------------------------------------------------- hooks */

static bool configurable(const co408_valve_t *v)
{
    return (v->state == (uint8_t)CO408_INIT) || (v->state == (uint8_t)CO408_DISABLED);
}

static co_err_t bad_value(const co408_valve_t *v)
{
    return (v->cfg.bad_value != CO_OK) ? v->cfg.bad_value : CO_ERR_VALUE;
}

static co_err_t hook_cw(void *ctx, co_od_io_t *io)
{
    co408_valve_t *v = (co408_valve_t *)ctx;

    if (io->len != 2U) {
        return CO_ERR_TYPE_MISMATCH;
    }
    if (co_pobj_get(&v->obj[O_LOCAL], 0) == 1) {
        return CO_ERR_STORE_LOCAL; /* the control word is local */
    }
    control(v, co_get_u16(io->buf));
    return CO_OK;
}

static co_err_t hook_dev_mode(void *ctx, co_od_io_t *io)
{
    const co408_valve_t *v = (const co408_valve_t *)ctx;

    if (!configurable(v)) {
        return CO_ERR_STORE_STATE;
    }
    return ((io->buf[0] == 1U) || (io->buf[0] == 2U)) ? CO_OK : bad_value(v);
}

static co_err_t hook_ctrl_mode(void *ctx, co_od_io_t *io)
{
    co408_valve_t *v = (co408_valve_t *)ctx;
    int8_t m = (int8_t)io->buf[0];

    if (!configurable(v)) {
        return CO_ERR_STORE_STATE;
    }
    if (!co408_mode_offered(v, m)) {
        return bad_value(v);
    }
    v->mode = m;
    return CO_OK;
}

static co_err_t hook_local(void *ctx, co_od_io_t *io)
{
    const co408_valve_t *v = (const co408_valve_t *)ctx;

    if (io->buf[0] > 1U) {
        return bad_value(v);
    }
    return configurable(v) ? CO_OK : CO_ERR_STORE_STATE;
}

static co_err_t hook_setpoint(void *ctx, co_od_io_t *io)
{
    const co408_valve_t *v = (const co408_valve_t *)ctx;

    (void)io;
    return (co_pobj_get(&v->obj[O_DEV_MODE], 1) == 2) ? CO_ERR_STORE_LOCAL : CO_OK;
}

/* ------------------------------------------------------------ the tick */

static uint32_t tick_us(const co408_valve_t *v)
{
    return (v->cfg.tick_us != 0U) ? v->cfg.tick_us : 1000U;
}

/* A plant fault the electronics watch: solenoid cable break / short
 * (0x2505 / 0x2585 monitoring), set-point cable break (0x2324). */
static uint16_t watched(const co408_valve_t *v, uint16_t code)
{
    uint8_t gate = O_NONE;

    if (code == CO408_ERR_SOLENOID1) {
        gate = O_CB_SOL1;
    } else if (code == CO408_ERR_SOLENOID2) {
        gate = O_CB_SOL2;
    } else if (code == CO408_ERR_SP_CABLE) {
        gate = O_CB_SP;
    } else {
        /* not gated */
    }
    return ((gate != O_NONE) && (co_pobj_get(&v->obj[gate], 1) == 0)) ? 0U : code;
}

static void check_plant(co408_valve_t *v)
{
    uint16_t f = watched(v, v->fb.fault);
    bool en = (v->fb.inputs & CO408_IN_ENABLE) != 0U;

    if (f != v->plant_fault) {
        if (v->plant_fault != 0U) {
            co408_fault_clear(v, v->plant_fault);
        }
        v->plant_fault = f;
        if (f != 0U) {
            co408_fault_raise(v, f);
        }
    }
    if ((co_pobj_get(&v->obj[O_LOCAL], 0) == 1) && (en != v->enable_in) && normal_state(v)) {
        /* local control: the enable input is the control word (D, H, M) */
        v->cw = en ? (uint16_t)(CO408_CW_D | CO408_CW_H | CO408_CW_M) : 0U;
        evaluate(v, v->cw);
    }
    v->enable_in = en;
}

static void run_tick(co408_valve_t *v, uint32_t now)
{
    co408_demand_t d;

    v->now = now;
    v->cfg.plant.ops->update(v->cfg.plant.ctx, now, &v->fb);
    if (v->state == (uint8_t)CO408_FAULT_REACTION) {
        /* TR_9 / TR_12: the outputs are off since the last tick, the
         * reaction is over */
        enter(v, (v->fr_hold && ((v->cw & CO408_CW_H) != 0U)) ? CO408_FAULT_HOLD : CO408_FAULT);
    }
    check_plant(v);
    if (!fault_state(v) && !cause_present(v)) {
        for (uint8_t i = 0U; i < CO408_FAULTS_MAX; i++) {
            if ((v->raised[i] != 0U) && !(v->pending_comm && (v->raised[i] == CO408_ERR_COMM))) {
                co_emcy_clear(v->node, v->raised[i]); /* reset by TR_10 / TR_11 */
                v->raised[i] = 0U;
            }
        }
    }
    (void)memset(&d, 0, sizeof d);
    co408_sp_run(v, &d);
    v->cfg.plant.ops->command(v->cfg.plant.ctx, &d);
    co408_sp_publish(v);
    publish_sw(v);
}

/* ---------------------------------------------------- plug-in operations */

void co408_init(co408_valve_t *v, const co408_config_t *cfg)
{
    (void)memset(v, 0, sizeof *v);
    v->cfg = *cfg;
}

static void start(co408_valve_t *v, uint32_t now)
{
    int8_t m = (int8_t)co_pobj_get(&v->obj[O_CTRL_MODE], CO408_MODE_VPOC);

    v->now = now;
    v->next_tick = now + tick_us(v);
    (void)memset(v->faults, 0, sizeof v->faults);
    (void)memset(v->raised, 0, sizeof v->raised);
    v->plant_fault = 0U;
    v->pending_comm = false;
    v->cw = (uint16_t)co_pobj_get(&v->obj[O_CW], 0);
    v->cfg.plant.ops->update(v->cfg.plant.ctx, now, &v->fb);
    v->enable_in = (v->fb.inputs & CO408_IN_ENABLE) != 0U;
    v->mode = co408_mode_offered(v, m) ? m : 0;
    v->state = (uint8_t)CO408_NOT_READY; /* TR_0 */
    enter(v, CO408_INIT);                /* TR_1: initialisation done */
    publish_sw(v);
}

static co_err_t op_attach(void *inst, co_node_t *node, uint32_t now_us)
{
    co408_valve_t *v = (co408_valve_t *)inst;
    co_od_hook_t h;
    static const struct {
        uint16_t index;
        co_err_t (*write)(void *ctx, co_od_io_t *io);
    } hooks[] = {
        {0x6042U, hook_dev_mode}, {0x6043U, hook_ctrl_mode}, {0x604FU, hook_local},
        {0x6300U, hook_setpoint}, {0x6380U, hook_setpoint}, {0x6480U, hook_setpoint},
        {0x6500U, hook_setpoint}, {0x6600U, hook_setpoint}, {0x2280U, hook_setpoint},
    };

    if ((v->cfg.plant.ops == NULL) || (v->cfg.channel > 1U)) {
        return CO_ERR_VALUE;
    }
    v->node = node;
    bind_objects(v);
    h.read = NULL;
    h.ctx = v;
    h.write = hook_cw;
    if (!co_pobj_has(&v->obj[O_SW]) ||
        (co_od_bind_hook(node, chan_index(v, 0x6040U), &h) != CO_RESULT_OK)) {
        v->node = NULL;
        return CO_ERR_OD_MISSING; /* the control word must be seen as it is written */
    }
    for (size_t i = 0U; i < (sizeof hooks / sizeof hooks[0]); i++) {
        h.write = hooks[i].write;
        (void)co_od_bind_hook(node, chan_index(v, hooks[i].index), &h); /* where it has a slot */
    }
    v->nmt = (uint8_t)co_node_nmt_state(node);
    start(v, now_us);
    v->attached = true;
    return CO_OK;
}

static uint32_t op_process(void *inst, uint32_t now_us)
{
    co408_valve_t *v = (co408_valve_t *)inst;
    uint32_t tick = tick_us(v);
    unsigned n = 0U;

    if (!v->attached) {
        return CO_NO_DEADLINE;
    }
    while ((int32_t)(now_us - v->next_tick) >= 0) {
        run_tick(v, v->next_tick);
        v->next_tick += tick;
        if (++n >= 1000U) {
            v->next_tick = now_us + tick; /* far behind: skip, do not run for ever */
            break;
        }
    }
    return v->next_tick;
}

static void op_nmt_state(void *inst, co_nmt_state_t state, uint32_t now_us)
{
    co408_valve_t *v = (co408_valve_t *)inst;

    (void)now_us;
    v->nmt = (uint8_t)state;
    if (!v->attached) {
        return;
    }
    if (state == CO_NMT_STOPPED) {
        comm_fault(v); /* C5 / C8 */
    } else if (v->pending_comm) {
        /* out of Stopped, or the boot-up after Reset Communication is out:
         * the EMCY may go now */
        v->pending_comm = false;
        co_emcy_raise(v->node, CO408_ERR_COMM, reg_bits(CO408_ERR_COMM), NULL);
    } else {
        /* Pre-operational / Operational leave the state machine alone */
    }
}

static void op_reset(void *inst, co_reset_t kind, uint32_t now_us)
{
    co408_valve_t *v = (co408_valve_t *)inst;

    if (!v->attached) {
        return;
    }
    if (kind == CO_RESET_NODE) {
        start(v, now_us); /* TR_567: the core has dropped its errors, objects are reset */
    } else {
        comm_fault(v);    /* C12 .. C14 */
    }
}

co408_state_t co408_state(const co408_valve_t *v)
{
    return (co408_state_t)v->state;
}

const co_profile_ops_t co408_profile_ops = {
    .name = "cia408",
    .attach = op_attach,
    .process = op_process,
    .nmt_state = op_nmt_state,
    .reset = op_reset,
};
