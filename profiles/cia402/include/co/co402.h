/*
 * CiA 402 drive profile: one axis of a drive as a co_profile plug-in.
 *
 * An axis finds its objects at the CiA 402 indices plus 0x800 * axis (up to
 * eight logical devices per node, CiA 301), binds write hooks to the
 * controlword (0x6040), modes of operation (0x6060) and homing method
 * (0x6098) where the device gives them a hook slot, and keeps statusword,
 * mode display and actual values current every control tick. What the
 * device description leaves out is not supported (no 0x6098: no homing),
 * except the few objects the axis cannot work without (controlword,
 * statusword).
 *
 * Implemented: the state machine (transitions 0..16, fault reset on the
 * rising edge of bit 7), statusword bits 0..15, option codes 0x605A..0x605E
 * and 0x6007, error code 0x603F with EMCY, modes pp, vl, pv, tq, hm (methods
 * 1..14, 17..30, 33..35, 37), ip, csp, csv, cst, software position limits,
 * following error, position/velocity windows, polarity, factor group
 * (0x6093/0x6094/0x6097 numerator/divisor). A plant (co402_plant.h) runs
 * below: co402_sim.h, or real hardware.
 *
 * Device deviations are data: CO402_OPT_* in co402_config_t.options.
 */
#ifndef CO402_H
#define CO402_H

#include <stdbool.h>
#include <stdint.h>

#include "co/co402_plant.h"
#include "co/co_node.h"
#include "co/co_profile.h"

/* ---- States (the values are our own; the statusword encodes them). */
typedef enum co402_state {
    CO402_NOT_READY = 0,        /**< Not ready to switch on */
    CO402_SWITCH_ON_DISABLED,   /**< Switch on disabled */
    CO402_READY,                /**< Ready to switch on */
    CO402_SWITCHED_ON,          /**< Switched on */
    CO402_OPERATION_ENABLED,    /**< Operation enabled */
    CO402_QUICK_STOP_ACTIVE,    /**< Quick stop active */
    CO402_FAULT_REACTION,       /**< Fault reaction active */
    CO402_FAULT                 /**< Fault */
} co402_state_t;

/* ---- Modes of operation (0x6060 values). */
#define CO402_MODE_NONE 0
#define CO402_MODE_PP   1  /**< profile position */
#define CO402_MODE_VL   2  /**< velocity */
#define CO402_MODE_PV   3  /**< profile velocity */
#define CO402_MODE_TQ   4  /**< profile torque */
#define CO402_MODE_HM   6  /**< homing */
#define CO402_MODE_IP   7  /**< interpolated position */
#define CO402_MODE_CSP  8  /**< cyclic synchronous position */
#define CO402_MODE_CSV  9  /**< cyclic synchronous velocity */
#define CO402_MODE_CST  10 /**< cyclic synchronous torque */
#define CO402_MODE_RAMP (-1) /**< manufacturer-specific: velocity ramp (CO402_OPT_VELOCITY_RAMP) */

/* ---- Controlword bits. */
#define CO402_CW_SWITCH_ON     0x0001U
#define CO402_CW_ENABLE_VOLT   0x0002U
#define CO402_CW_QUICK_STOP    0x0004U /**< 0 = quick stop */
#define CO402_CW_ENABLE_OP     0x0008U
#define CO402_CW_NEW_SETPOINT  0x0010U /**< pp; hm: start; ip: enable; vl: rfg enable */
#define CO402_CW_CHANGE_NOW    0x0020U /**< pp; vl: rfg unlock */
#define CO402_CW_RELATIVE      0x0040U /**< pp; vl: use reference */
#define CO402_CW_FAULT_RESET   0x0080U
#define CO402_CW_HALT          0x0100U

/* ---- Statusword bits. */
#define CO402_SW_READY         0x0001U
#define CO402_SW_SWITCHED_ON   0x0002U
#define CO402_SW_OP_ENABLED    0x0004U
#define CO402_SW_FAULT         0x0008U
#define CO402_SW_VOLTAGE       0x0010U
#define CO402_SW_QUICK_STOP    0x0020U /**< 1 = no quick stop */
#define CO402_SW_SO_DISABLED   0x0040U
#define CO402_SW_WARNING       0x0080U
#define CO402_SW_REMOTE        0x0200U
#define CO402_SW_TARGET        0x0400U /**< target reached */
#define CO402_SW_LIMIT         0x0800U /**< internal limit active */
#define CO402_SW_OMS1          0x1000U /**< mode-specific (set-point ack, homing attained, ...) */
#define CO402_SW_OMS2          0x2000U /**< mode-specific (following error, homing error, ...) */

/* ---- Error codes the profile raises itself (0x603F and EMCY). */
#define CO402_ERR_FOLLOWING   0x8611U /**< following error */
#define CO402_ERR_COMM        0x8100U /**< abort connection (0x6007 = 1) after NMT stop */
#define CO402_ERR_HB_GUARD    0x8130U /**< abort connection after a heartbeat / guarding loss */
#define CO402_ERR_ENABLE      0x5441U /**< hardware enable input lost while energised */

/* ---- Device deviations (co402_config_t.options). */
#define CO402_OPT_ONE_TRANSITION    0x00000001UL /**< one transition per controlword write: no
                                                      3+4 on 0x000F in Ready (FAULHABER) */
#define CO402_OPT_NMT_OPERATIONAL   0x00000002UL /**< controlword acts only in NMT Operational
                                                      (FAULHABER) */
#define CO402_OPT_NO_VOLTAGE_BIT    0x00000004UL /**< statusword bit 4 always 0 (FAULHABER, SSD) */
#define CO402_OPT_VOLTAGE_WHEN_ON   0x00000008UL /**< bit 4 only while the power stage is on */
#define CO402_OPT_NO_REMOTE_BIT     0x00000010UL /**< statusword bit 9 always 0 (FAULHABER) */
#define CO402_OPT_REMOTE_IS_ENABLE  0x00000020UL /**< bit 9 = hardware enable input; Shutdown
                                                      needs it; its loss ends in Switch on
                                                      disabled (SSD 630) */
#define CO402_OPT_SW15_MIRRORS_12   0x00000040UL /**< statusword bit 15 = bit 12 (SSD 630) */
#define CO402_OPT_PP_ALWAYS_NOW     0x00000080UL /**< pp: every set-point acts at once, bit 5
                                                      ignored (FAULHABER) */
#define CO402_OPT_PP_REL_ACTUAL     0x00000100UL /**< pp: relative to the actual position, not
                                                      to the last target */
#define CO402_OPT_PP_TR_AFTER_MOVE  0x00000200UL /**< pp: target reached only after a set-point,
                                                      cleared by the next (FAULHABER) */
#define CO402_OPT_HM_BIT4_CLEARS    0x00000400UL /**< hm: clearing bit 4 clears homing attained
                                                      (FAULHABER) */
#define CO402_OPT_BIT7_DONT_CARE    0x00000800UL /**< commands decoded with bit 7 don't care
                                                      (Kollmorgen) */
#define CO402_OPT_FE_WARN_ONLY      0x00001000UL /**< following error: statusword bit 13 only,
                                                      no fault */
#define CO402_OPT_MODE_AT_REST      0x00002000UL /**< 0x6060 refused (0x08000022) while the axis
                                                      moves in Operation enabled (SSD 630) */
#define CO402_OPT_FAULT_HOLDS_ZERO  0x00004000UL /**< Fault keeps the power stage on at speed
                                                      zero (FAULHABER) */
#define CO402_OPT_QS_CLEARS_TARGET  0x00008000UL /**< quick stop deletes the set-points (target
                                                      position / velocity / torque := 0)
                                                      (Kollmorgen) */
#define CO402_OPT_UNITS_FROM_POS    0x00010000UL /**< velocities and accelerations in position
                                                      units per s and per s^2: 0x6094/0x6097 are
                                                      not used (Kollmorgen: 6097h is derived
                                                      from 6093h) */
#define CO402_OPT_VEL_RPM           0x00020000UL /**< velocities in motor rpm, accelerations in
                                                      rpm/s (counts_per_rev; SSD 630, no factor
                                                      group) */
#define CO402_OPT_QS_STAY           0x00040000UL /**< without 0x605A, quick stop acts as code 6:
                                                      quick-stop ramp, stay in Quick stop active
                                                      (Kollmorgen) */
#define CO402_OPT_HM_TARGET_FIRST   0x00080000UL /**< hm: bit 10 is 0 until a homing ends; at home
                                                      and at rest bit 10 comes first, bit 12 one
                                                      tick later (Kollmorgen: 0x0237, 0x0637,
                                                      0x1637) */
#define CO402_OPT_PP_TR_NEXT_TICK   0x00100000UL /**< pp: a new set-point clears bit 10 at the next
                                                      tick, so the acknowledgement is seen with
                                                      bit 10 still set (SSD 630: 0x9627, 0x9227) */
#define CO402_OPT_IP_TR_AT_REST     0x00200000UL /**< ip: bit 10 = 1 while ip is not enabled and the
                                                      axis is at rest (SSD 630: 0x0627 in ip) */
#define CO402_OPT_PV_NO_SPEED_BIT   0x00400000UL /**< pv: no mode-specific statusword bits (bit 12
                                                      "speed = 0" stays 0; Kollmorgen) */
#define CO402_OPT_TPDO_ON_SW        0x00800000UL /**< every statusword change requests the TPDOs
                                                      that map the statusword (FAULHABER: the
                                                      only event of its event-driven TPDOs) */
#define CO402_OPT_VELOCITY_RAMP     0x01000000UL /**< the axis' one mode is a velocity ramp: target
                                                      0x6080 in per mille of full speed, ramps
                                                      0x6083 / 0x6084 in ms per full scale (0: a
                                                      step), direction 0x607E bit 6; quick stop
                                                      as fast as possible (AnaGate Motion) */
#define CO402_OPT_FR_SLOW           0x02000000UL /**< without 0x605E: fault reaction as option
                                                      code 1 (0x6084 ramp), not 2 (FAULHABER) */
#define CO402_OPT_LOSS_WARN_STOP    0x04000000UL /**< a heartbeat / guarding loss is a warning
                                                      (statusword bits 7 and 11; not 0x6007's
                                                      reaction) that stops the axis on the
                                                      quick-stop ramp (0x6085) and holds it, in
                                                      its state, until a fault reset (controlword
                                                      bit 7 rising) (Kollmorgen: warning n04) */

/** A homing method a device accepts in 0x6098 and how the axis runs it
 *  (co402_config_t.hm_methods; without a table the CiA 402 methods the
 *  profile implements are accepted and run as themselves). */
typedef struct co402_hm_method {
    int8_t value;              /**< the 0x6098 value (manufacturer methods are negative) */
    int8_t runs_as;            /**< the CiA 402 method it runs as (0: none, a homing error) */
    uint8_t flags;             /**< CO402_HM_FAST_ONLY */
} co402_hm_method_t;

#define CO402_HM_FAST_ONLY 0x01U /**< every phase at 0x6099 sub 1 (sub 2 is not used) */

/** How a device reports an error code the axis raises (co402_config_t.errors;
 *  without an entry: the error register bit of the code's class, no
 *  manufacturer bytes). */
typedef struct co402_error {
    uint16_t code;             /**< EMCY error code (0x603F) */
    uint8_t reg;               /**< 0x1001 bits it sets (the core adds bit 0, see
                                    co_emcy_raise) */
    uint8_t mfr[5];            /**< EMCY bytes 3..7 */
} co402_error_t;

typedef struct co402_config {
    uint8_t axis;              /**< 0..7: objects at 0x6000 + 0x800 * axis */
    uint32_t options;          /**< CO402_OPT_* */
    uint32_t tick_us;          /**< control period (0: 1000 us) */
    co402_plant_t plant;       /**< what the axis drives */
    uint32_t counts_per_rev;   /**< increments per motor revolution, for the vl mode's rpm
                                    (0: 4096; 0x608F overrides when the device has it) */
    uint32_t modes;            /**< supported modes as 0x6502 bits when the device lacks
                                    0x6502 (0: pp, pv, hm) */
    uint32_t vel_num;          /**< velocity factor (internal increments/s per user unit =
                                    vel_num / vel_den) where the device lacks 0x6094
                                    (0: the position factor); FAULHABER: rpm */
    uint32_t vel_den;
    uint32_t acc_num;          /**< acceleration factor where the device lacks 0x6097
                                    (0: the velocity factor); FAULHABER: 1/s^2 */
    uint32_t acc_den;
    uint32_t full_speed;       /**< CO402_OPT_VELOCITY_RAMP: increments/s at 1000 per mille
                                    (0: 50 revolutions/s) */
    const co402_hm_method_t *hm_methods; /**< homing methods of the device (NULL: CiA 402's) */
    uint8_t n_hm_methods;
    const co402_error_t *errors; /**< how the device reports error codes (NULL: none) */
    uint8_t n_errors;
} co402_config_t;

#define CO402_FAULTS_MAX 4U
#define CO402_OBJ_COUNT 73U

/** One axis. Caller-allocated; the fields are private (here for allocation). */
typedef struct co402_axis {
    co402_config_t cfg;
    co_node_t *node;
    void *obj[CO402_OBJ_COUNT];      /* value pointers into the RAM image, NULL where absent */
    uint8_t obj_type[CO402_OBJ_COUNT];
    co402_feedback_t fb;             /* plant feedback of the last tick */
    int64_t tr_p;                    /* profile generator: demand position (Q16) */
    int64_t tr_v;                    /* ... demand velocity (Q16/s) */
    int64_t dm_p;                    /* demand at the start of the present tick (Q16) */
    int64_t dm_v;
    int64_t shift;                   /* internal position = raw + shift (Q16; homing) */
    int64_t pos;                     /* actual position, internal, Q16 */
    int64_t vel;                     /* actual velocity, Q16 */
    int64_t target;                  /* pp: target; hold position elsewhere (internal Q16) */
    int64_t next_target;             /* pp: buffered set-point */
    int64_t hm_home;                 /* homing: raw position of the home event */
    int64_t hm_edge;                 /* homing: raw position of the switch edge */
    int64_t ip_from;                 /* ip / csp: interpolation segment (internal Q16) */
    int64_t ip_to;
    int64_t cs_vel;                  /* csv: velocity set-point (Q16) */
    uint32_t now;                    /* time of the last tick */
    uint32_t next_tick;
    uint32_t ip_t0;                  /* segment start */
    uint32_t ip_period;              /* segment length, us */
    uint32_t last_sync;
    uint32_t sync_interval;
    uint32_t timer;                  /* position / velocity window timer start */
    uint32_t vtimer;                 /* speed-zero timer start */
    uint32_t fe_timer;               /* following-error timer start */
    uint32_t hm_edges[CO402_IN_EDGES];
    uint32_t hm_index;
    uint32_t next_vel;               /* pp: buffered profile (inc/s, inc/s^2) */
    uint32_t next_acc;
    uint32_t next_dec;
    uint32_t cur_vel;                /* pp: active profile */
    uint32_t cur_acc;
    uint32_t cur_dec;
    int32_t tr_a;                    /* profile generator: acceleration */
    uint16_t faults[CO402_FAULTS_MAX]; /* fault conditions present */
    uint16_t raised[CO402_FAULTS_MAX]; /* EMCY codes raised since the last fault reset */
    uint16_t to_clear[CO402_FAULTS_MAX]; /* EMCY codes a fault reset ends at the next tick */
    uint16_t plant_fault;            /* fault the plant reports */
    uint16_t cw;                     /* last controlword */
    uint16_t msw;                    /* mode-dependent statusword bits (10..13) */
    int16_t cs_torque;               /* cst: torque set-point */
    int16_t tq_demand;               /* tq: ramped torque */
    uint8_t state;                   /* co402_state_t */
    uint8_t drive;                   /* where the demand comes from */
    uint8_t after_stop;              /* state entered when the running stop ends */
    uint8_t stop_kind;               /* ramp of the running stop */
    int8_t mode;                     /* active mode (0x6061) */
    uint8_t nmt;                     /* NMT state seen last */
    uint8_t pp_flags;
    uint8_t hm_phase;
    int8_t hm_dir;
    int8_t hm_method;
    uint8_t hm_flags;
    uint8_t ip_flags;
    bool timer_on;
    bool vtimer_on;
    bool fe_on;
    bool warning;
    bool loss;                       /* CO402_OPT_LOSS_WARN_STOP: connection lost, not reset */
    bool attached;
} co402_axis_t;

/** The plug-in operations (co_profile_add(&host, &co402_profile_ops, &axis)). */
extern const co_profile_ops_t co402_profile_ops;

/** Prepare @p ax with @p cfg (before co_profile_add / attach). */
void co402_init(co402_axis_t *ax, const co402_config_t *cfg);

/** The present state. */
co402_state_t co402_state(const co402_axis_t *ax);

/** A fault condition arises (transition 13) with error @p code (0x603F, EMCY).
 *  Fault reset succeeds only after co402_fault_clear() for every raised code. */
void co402_fault_raise(co402_axis_t *ax, uint16_t code);

/** A fault condition has gone (a fault reset may now succeed). */
void co402_fault_clear(co402_axis_t *ax, uint16_t code);

/** A fault event: a fault whose cause is over at once (fault reset clears it). */
void co402_fault_event(co402_axis_t *ax, uint16_t code);

/** Set or clear the warning (statusword bit 7). */
void co402_set_warning(co402_axis_t *ax, bool on);

/** CO402_OPT_LOSS_WARN_STOP: true from a heartbeat / guarding loss until the
 *  fault reset that ends its warning. */
bool co402_connection_lost(const co402_axis_t *ax);

/** The statusword as the axis reports it. */
uint16_t co402_statusword(const co402_axis_t *ax);

/** Actual position in internal increments (after homing). */
int32_t co402_position(const co402_axis_t *ax);

/** Actual velocity in internal increments/s (plant feedback of the last tick). */
int32_t co402_velocity(const co402_axis_t *ax);

#endif /* CO402_H */
