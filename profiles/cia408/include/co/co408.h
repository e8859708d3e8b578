/*
 * CiA 408 fluid-power valve profile (DSP-408): one valve channel as a
 * co_profile plug-in.
 *
 * A channel finds its objects at the DSP-408 indices plus 0x800 * channel
 * (manufacturer objects plus 0x700 * channel), binds write hooks to the
 * control word 0x6040, device mode 0x6042, control mode 0x6043 and device
 * local 0x604F (and to the set-point objects where the description gives
 * them a hook slot), and keeps the status word and the actual values current
 * every control tick (1 ms). What the description leaves out is not
 * supported (no 0x6380: no vprc), except the control and status words.
 *
 * Device state machine (states and status word bits 3..0 = R M H D):
 *   NOT_READY 0x0000, INIT 0x0008, DISABLED 0x0009, HOLD 0x000B,
 *   DEVICE_MODE_ACTIVE 0x000F, FAULT_REACTION 0x0007, FAULT_HOLD 0x0003,
 *   FAULT 0x0001.
 * The control word (D bit 0, H bit 1, M bit 2, R bit 3) is evaluated in a
 * chain until no transition applies: TR_2 INIT->DISABLED (D), TR_3
 * DISABLED->HOLD (D, H), TR_4 HOLD->ACTIVE (D, H, M), TR_5 ACTIVE->HOLD (M = 0),
 * TR_6 HOLD->DISABLED (H = M = 0), TR_7 DISABLED->INIT (D = H = M = 0); 0x0007
 * in INIT ends in DEVICE_MODE_ACTIVE, 0x0000 in DEVICE_MODE_ACTIVE in INIT.
 * TR_8: an error (EMCY raised) in INIT, DISABLED, HOLD or ACTIVE leads to
 * FAULT_REACTION; the reaction ends at the next tick in FAULT_HOLD when the
 * control word's H bit is set then (TR_9), else in FAULT (TR_12). A rising
 * edge of R in a fault state resets the errors once their causes are gone:
 * TR_11 FAULT_HOLD->HOLD with H set, else TR_10 ->DISABLED; the chain then
 * goes on with the same control word. A reset while a cause is still present
 * is ignored. Status bit 9: the set-point ramp runs; bit 11: following error
 * (closed loop); bit 12: target window reached (closed loop).
 *
 * NMT: Stop and Reset Communication force TR_8 with error 0x8100. CiA 301
 * sends no EMCY in Stopped, so the profile raises the 0x8100 error (0x1001,
 * 0x1003, the EMCY frame) when the node leaves Stopped, i.e. as soon as an
 * EMCY may go out; after Reset Communication it is raised after the boot-up,
 * in Pre-operational. The device state machine enters FAULT at once either
 * way. Reset Node: the state machine starts again (TR_567 to INIT, all
 * errors gone with the core's). Pre-operational and Start leave it alone.
 *
 * Mode objects: 0x6042 (1 bus set-point, 2 local set-point) and 0x6043
 * (control mode, co408_config_t.modes) are written in INIT or DISABLED only,
 * else 0x08000022; an unsupported value gets co408_config_t.bad_value.
 * 0x604F (0 bus, 1 local control word) likewise only in INIT or DISABLED.
 * Source arbitration: a control word written over the bus while 0x604F = 1,
 * and a set-point written while 0x6042 = 2, are refused with 0x08000021.
 *
 * Set-point path (docs/profiles.md, CiA 408): the set-point object of the
 * active mode (INT16 vpoc / vprc, INT32 dcol / dsc / dpc / n-point) is mapped
 * from the bus window 0x2329..0x232A to the internal resolution (+-16384),
 * then for the open-loop modes the dead band (0x232D on, 0x232E width) and
 * the ramp (type 0 off / 3 on, four times in ms per 100 %: A up, A down, B
 * up, B down; A = positive, "up" = growing magnitude) apply. Closed loop:
 * the actual value, control deviation, following-error window (type 0 off /
 * 2 on / -2 on with fault 0x1000, delay ms, threshold) and target window
 * (0x2402 = 2 on, 0x2403 delay ms, 0x2404 threshold).
 */
#ifndef CO408_H
#define CO408_H

#include <stdbool.h>
#include <stdint.h>

#include "co/co408_plant.h"
#include "co/co_node.h"
#include "co/co_pobj.h"
#include "co/co_profile.h"

typedef enum co408_state {
    CO408_NOT_READY = 0,
    CO408_INIT,
    CO408_DISABLED,
    CO408_HOLD,
    CO408_ACTIVE,          /**< DEVICE_MODE_ACTIVE */
    CO408_FAULT_REACTION,
    CO408_FAULT_HOLD,
    CO408_FAULT
} co408_state_t;

/* Control word bits. */
#define CO408_CW_D 0x0001U /**< disable (device command) */
#define CO408_CW_H 0x0002U /**< hold enable */
#define CO408_CW_M 0x0004U /**< device mode active enable */
#define CO408_CW_R 0x0008U /**< reset fault (rising edge) */

/* Status word bits. */
#define CO408_SW_RAMP   0x0200U /**< bit 9: ramp running */
#define CO408_SW_FE     0x0800U /**< bit 11: following error */
#define CO408_SW_TARGET 0x1000U /**< bit 12: target window reached */

/* Control modes (0x6043 values). */
#define CO408_MODE_VPOC    1   /**< spool valve, open loop */
#define CO408_MODE_VPRC    3   /**< pressure valve, open loop */
#define CO408_MODE_VPRC_CL 4   /**< pressure valve, closed loop */
#define CO408_MODE_DCOL    6   /**< axis position, open loop */
#define CO408_MODE_DSC     7   /**< velocity / flow, closed loop */
#define CO408_MODE_DPC     9   /**< axis position, closed loop */
#define CO408_MODE_VPRC_2  (-5) /**< pressure closed loop with 2 solenoids (Wandfluh) */
#define CO408_MODE_NPT_1   (-6) /**< 2-point controller, 1 solenoid (Wandfluh) */
#define CO408_MODE_NPT_2   (-7) /**< 2-point controller, 2 solenoids (Wandfluh) */
#define CO408_MODE_NPT_3   (-8) /**< 3-point controller, 2 solenoids (Wandfluh) */

/* Error codes (EMCY) the profile raises. */
#define CO408_ERR_GENERAL   0x1000U /**< following error with window type -2 */
#define CO408_ERR_SOLENOID1 0x2311U
#define CO408_ERR_SOLENOID2 0x2312U
#define CO408_ERR_SUPPLY    0x3412U /**< supply voltage too low */
#define CO408_ERR_SP_CABLE  0x3422U /**< set-point input cable break */
#define CO408_ERR_COMM      0x8100U /**< NMT Stop / Reset Communication */

typedef struct co408_config {
    uint8_t channel;           /**< 0..1: objects at +0x800 (profile) / +0x700 (manufacturer) */
    uint32_t tick_us;          /**< control period (0: 1000 us) */
    co408_plant_t plant;       /**< what the channel drives */
    const int8_t *modes;       /**< control modes the device offers (NULL: every mode whose
                                    set-point object it has) */
    uint8_t n_modes;
    co_err_t bad_value;        /**< answer to an unsupported 0x6042 / 0x6043 value
                                    (CO_OK: 0x06090030) */
} co408_config_t;

#define CO408_OBJ_COUNT 62U
#define CO408_FAULTS_MAX 4U

/** One valve channel. Caller-allocated; the fields are private. */
typedef struct co408_valve {
    co408_config_t cfg;
    co_node_t *node;
    co_pobj_t obj[CO408_OBJ_COUNT];
    co408_feedback_t fb;
    uint32_t now;
    uint32_t next_tick;
    uint32_t fe_since;         /* following error window exceeded since */
    uint32_t tw_since;         /* target window entered since */
    int64_t out;               /* ramped internal set-point, Q16 (open loop) / target (closed) */
    int32_t held;              /* HOLD / FAULT_HOLD: the demand kept */
    int32_t sp;                /* set-point of the mode in its own units (closed loop) */
    uint16_t faults[CO408_FAULTS_MAX]; /* conditions present (plant or application) */
    uint16_t raised[CO408_FAULTS_MAX]; /* errors raised since the last fault reset */
    uint16_t plant_fault;
    uint16_t cw;               /* last control word */
    uint16_t msw;              /* status bits 9, 11, 12 */
    uint8_t state;             /* co408_state_t */
    uint8_t nmt;
    int8_t mode;               /* control mode in use */
    bool fr_hold;              /* the fault struck in HOLD or ACTIVE */
    bool pending_comm;         /* 0x8100 waits until an EMCY may go out */
    bool fe_on;
    bool tw_on;
    bool enable_in;            /* local enable input seen last */
    bool attached;
} co408_valve_t;

/** The plug-in operations (co_profile_add(&host, &co408_profile_ops, &valve)). */
extern const co_profile_ops_t co408_profile_ops;

/** Prepare @p v with @p cfg (before co_profile_add / attach). */
void co408_init(co408_valve_t *v, const co408_config_t *cfg);

co408_state_t co408_state(const co408_valve_t *v);

/** The status word as the channel reports it. */
uint16_t co408_statusword(const co408_valve_t *v);

/** A fault condition arises (EMCY @p code, TR_8); a fault reset succeeds
 *  only after co408_fault_clear(). */
void co408_fault_raise(co408_valve_t *v, uint16_t code);

/** A fault condition has gone. */
void co408_fault_clear(co408_valve_t *v, uint16_t code);

/** The internal set-point after scaling, dead band and ramp (what the plant
 *  is given in the open-loop modes; the target in the closed-loop ones). */
int32_t co408_output(const co408_valve_t *v);

#endif /* CO408_H */
