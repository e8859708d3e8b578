/*
 * CiA 402 homing mode: methods 1..14 and 17..30 (limit switches and home
 * switches, with and without the index pulse), 33/34 (index pulse only),
 * 35/37 (the actual position).
 *
 * One sequencer serves every switch method. A method names the switch, the
 * edge of it that defines home (its lower or upper end), the direction of
 * the final approach D and the start direction for either switch level.
 * The axis moves at the switch search speed (0x6099.1); crossing the home
 * edge against D turns it round at the zero search speed (0x6099.2);
 * crossing it along D finds home (methods 17..30), or starts the search for
 * the next index pulse along D (methods 1..14). Methods 7..14 turn round
 * once at a limit switch; hitting a limit switch otherwise is a homing
 * error. At home the axis stops with 0x609A and the position becomes the
 * home offset 0x607C.
 */
#include <stddef.h>

#include "co402_priv.h"

#define SW_NEG  0U /* edge latch numbers = CO402_IN_* bit numbers */
#define SW_POS  1U
#define SW_HOME 2U
#define SW_NONE 3U /* index pulse only */
#define SW_HERE 4U /* the actual position */

#define EDGE_LOWER 0U
#define EDGE_UPPER 1U

#define HMS_INDEX   0x01U /* home is the next index pulse after the edge */
#define HMS_REVERSE 0x02U /* a limit switch turns the search round (once) */

#define HMF_SLOW     0x01U
#define HMF_REVERSED 0x02U
#define HMF_FAST     0x04U /* CO402_HM_FAST_ONLY: 0x6099 sub 1 throughout */
#define HMF_REPORTED 0x08U /* CO402_OPT_HM_TARGET_FIRST: bit 10 has been shown alone */

typedef struct hm_spec {
    int8_t method;
    uint8_t sw;
    uint8_t edge;
    int8_t dir;         /* final approach */
    int8_t if_active;   /* start direction with the switch active */
    int8_t if_inactive; /* ... inactive */
    uint8_t flags;
} hm_spec_t;

static const hm_spec_t specs[] = {
    {1, SW_NEG, EDGE_UPPER, 1, 1, -1, HMS_INDEX},
    {2, SW_POS, EDGE_LOWER, -1, -1, 1, HMS_INDEX},
    {3, SW_HOME, EDGE_LOWER, -1, -1, 1, HMS_INDEX},
    {4, SW_HOME, EDGE_LOWER, 1, -1, 1, HMS_INDEX},
    {5, SW_HOME, EDGE_UPPER, 1, 1, -1, HMS_INDEX},
    {6, SW_HOME, EDGE_UPPER, -1, 1, -1, HMS_INDEX},
    {7, SW_HOME, EDGE_LOWER, -1, -1, 1, HMS_INDEX | HMS_REVERSE},
    {8, SW_HOME, EDGE_LOWER, 1, -1, 1, HMS_INDEX | HMS_REVERSE},
    {9, SW_HOME, EDGE_UPPER, -1, 1, 1, HMS_INDEX | HMS_REVERSE},
    {10, SW_HOME, EDGE_UPPER, 1, 1, 1, HMS_INDEX | HMS_REVERSE},
    {11, SW_HOME, EDGE_UPPER, 1, 1, -1, HMS_INDEX | HMS_REVERSE},
    {12, SW_HOME, EDGE_UPPER, -1, 1, -1, HMS_INDEX | HMS_REVERSE},
    {13, SW_HOME, EDGE_LOWER, 1, -1, -1, HMS_INDEX | HMS_REVERSE},
    {14, SW_HOME, EDGE_LOWER, -1, -1, -1, HMS_INDEX | HMS_REVERSE},
    {33, SW_NONE, EDGE_LOWER, -1, -1, -1, HMS_INDEX},
    {34, SW_NONE, EDGE_LOWER, 1, 1, 1, HMS_INDEX},
    {35, SW_HERE, EDGE_LOWER, 1, 1, 1, 0U},
    {37, SW_HERE, EDGE_LOWER, 1, 1, 1, 0U},
};

static bool find_spec(int8_t method, hm_spec_t *out)
{
    int8_t m = method;
    bool plain = false;

    if ((method >= 17) && (method <= 30)) {
        m = (int8_t)(method - 16); /* as 1..14, without the index pulse */
        plain = true;
    }
    for (size_t i = 0U; i < (sizeof(specs) / sizeof(specs[0])); i++) {
        if (specs[i].method == m) {
            *out = specs[i];
            if (plain) {
                out->method = method;
                out->flags &= (uint8_t)~HMS_INDEX;
            }
            return true;
        }
    }
    return false;
}

bool co402_hm_supported(int8_t method)
{
    hm_spec_t s;
    return find_spec(method, &s);
}

/* The device's entry for the 0x6098 value @p value (NULL: not in its table). */
static const co402_hm_method_t *device_method(const co402_axis_t *ax, int8_t value)
{
    for (uint8_t i = 0U; i < ax->cfg.n_hm_methods; i++) {
        if (ax->cfg.hm_methods[i].value == value) {
            return &ax->cfg.hm_methods[i];
        }
    }
    return NULL;
}

bool co402_hm_accepted(const co402_axis_t *ax, int8_t value)
{
    if (ax->cfg.hm_methods == NULL) {
        return co402_hm_supported(value);
    }
    return device_method(ax, value) != NULL;
}

static uint32_t hm_acc(const co402_axis_t *ax)
{
    return co402_acc_in(ax, (uint32_t)co402_get(ax, O_HM_ACC, 0));
}

static void set_status(co402_axis_t *ax)
{
    uint16_t b;
    static const uint16_t bits[] = {
        CO402_SW_TARGET,                 /* idle: not started or interrupted */
        0U,                              /* search: in progress */
        0U,                              /* index */
        CO402_SW_OMS1,                   /* stopping: attained, target not reached */
        CO402_SW_OMS1 | CO402_SW_TARGET, /* done */
        CO402_SW_OMS2,                   /* error, still moving */
        CO402_SW_OMS2 | CO402_SW_TARGET, /* error, at rest */
        0U,                              /* aborting */
    };

    b = bits[ax->hm_phase];
    if ((ax->cfg.options & CO402_OPT_HM_TARGET_FIRST) != 0U) {
        if (ax->hm_phase == (uint8_t)HM_DONE) {
            /* at home and at rest: bit 10 alone for one tick, then with bit 12 */
            if ((ax->hm_flags & HMF_REPORTED) == 0U) {
                b = CO402_SW_TARGET;
                ax->hm_flags |= HMF_REPORTED;
            }
        } else if ((ax->hm_phase == (uint8_t)HM_IDLE) || (ax->hm_phase == (uint8_t)HM_STOPPING)) {
            b = 0U; /* no "target reached" before a homing has ended */
        } else {
            /* search, index, errors, aborting: as CiA 402 */
        }
    }
    ax->msw = (uint16_t)((ax->msw & (uint16_t)~(CO402_SW_TARGET | CO402_SW_OMS1 | CO402_SW_OMS2)) | b);
}

void co402_hm_enter(co402_axis_t *ax)
{
    ax->hm_phase = (uint8_t)HM_IDLE;
    ax->hm_flags = 0U;
    set_status(ax);
}

/* Home found and the axis at rest: the home position becomes the home offset. */
static void finish(co402_axis_t *ax)
{
    int64_t shift = co402_pos_in(ax, co402_get(ax, O_HOME_OFFSET, 0)) - ax->hm_home;
    int64_t delta = shift - ax->shift;

    ax->shift = shift;
    ax->pos += delta;
    ax->tr_p += delta;
    ax->dm_p += delta;
    ax->target += delta;
    ax->ip_from += delta;
    ax->ip_to += delta;
    ax->hm_phase = (uint8_t)HM_DONE;
}

static void hm_start(co402_axis_t *ax)
{
    hm_spec_t s;
    int8_t method = (int8_t)co402_get(ax, O_HM_METHOD, 0);

    ax->hm_flags = 0U;
    if (ax->cfg.hm_methods != NULL) {
        /* the device's value runs as a CiA 402 method (none: a homing error) */
        const co402_hm_method_t *m = device_method(ax, method);
        method = (m != NULL) ? m->runs_as : 0;
        if ((m != NULL) && ((m->flags & CO402_HM_FAST_ONLY) != 0U)) {
            ax->hm_flags = HMF_FAST;
        }
    }
    ax->hm_method = method;
    for (uint8_t k = 0U; k < CO402_IN_EDGES; k++) {
        ax->hm_edges[k] = ax->fb.edge_count[k];
    }
    ax->hm_index = ax->fb.index_count;
    if (!find_spec(method, &s)) {
        ax->hm_phase = (uint8_t)HM_ERROR;
    } else if (s.sw == SW_HERE) {
        ax->hm_home = ax->fb.pos; /* at rest: done at the next tick */
        ax->hm_phase = (uint8_t)HM_STOPPING;
    } else if (s.sw == SW_NONE) {
        ax->hm_edge = ax->fb.pos;
        ax->hm_dir = s.dir;
        ax->hm_flags |= HMF_SLOW;
        ax->hm_phase = (uint8_t)HM_INDEX;
    } else {
        bool active = (ax->fb.inputs & (1UL << s.sw)) != 0U;
        ax->hm_dir = active ? s.if_active : s.if_inactive;
        ax->hm_phase = (uint8_t)HM_SEARCH;
    }
    set_status(ax);
}

void co402_hm_cw(co402_axis_t *ax, uint16_t old, uint16_t cw)
{
    bool now_set = (cw & CO402_CW_NEW_SETPOINT) != 0U;
    bool was_set = (old & CO402_CW_NEW_SETPOINT) != 0U;

    if (now_set && !was_set) {
        hm_start(ax);
    } else if (!now_set && was_set) {
        if ((ax->hm_phase == (uint8_t)HM_SEARCH) || (ax->hm_phase == (uint8_t)HM_INDEX)) {
            ax->hm_phase = (uint8_t)HM_ABORTING; /* interrupted */
        } else if ((ax->hm_phase == (uint8_t)HM_DONE) &&
                   ((ax->cfg.options & CO402_OPT_HM_BIT4_CLEARS) != 0U)) {
            ax->hm_phase = (uint8_t)HM_IDLE;
        } else {
            /* nothing to interrupt */
        }
        set_status(ax);
    } else {
        /* level unchanged */
    }
}

static int8_t motion_dir(const co402_axis_t *ax)
{
    if (ax->fb.vel != 0) {
        return (ax->fb.vel > 0) ? 1 : -1;
    }
    if (ax->tr_v != 0) {
        return (ax->tr_v > 0) ? 1 : -1;
    }
    return ax->hm_dir;
}

static void events(co402_axis_t *ax)
{
    hm_spec_t s;
    const co402_feedback_t *fb = &ax->fb;

    if (!find_spec(ax->hm_method, &s)) {
        ax->hm_phase = (uint8_t)HM_ERR_STOPPING;
        return;
    }
    /* limit switches other than the method's own */
    for (uint8_t k = SW_NEG; k <= SW_POS; k++) {
        bool toward = (k == SW_NEG) ? (ax->hm_dir < 0) : (ax->hm_dir > 0);
        if ((k != s.sw) && toward && ((fb->inputs & (1UL << k)) != 0U)) {
            if ((ax->hm_phase == (uint8_t)HM_SEARCH) && ((s.flags & HMS_REVERSE) != 0U) &&
                ((ax->hm_flags & HMF_REVERSED) == 0U)) {
                ax->hm_dir = (int8_t)-ax->hm_dir;
                ax->hm_flags |= HMF_REVERSED;
            } else {
                ax->hm_phase = (uint8_t)HM_ERR_STOPPING;
                return;
            }
        }
    }
    if ((ax->hm_phase == (uint8_t)HM_SEARCH) && (fb->edge_count[s.sw] != ax->hm_edges[s.sw])) {
        bool active = (fb->inputs & (1UL << s.sw)) != 0U;
        int8_t m = motion_dir(ax);
        uint8_t edge = (uint8_t)(((m > 0) == active) ? EDGE_LOWER : EDGE_UPPER);
        if (edge == s.edge) {
            if (m == s.dir) {
                ax->hm_edge = fb->edge_pos[s.sw];
                if ((s.flags & HMS_INDEX) != 0U) {
                    ax->hm_phase = (uint8_t)HM_INDEX;
                    ax->hm_dir = s.dir;
                    ax->hm_flags |= HMF_SLOW;
                    ax->hm_index = fb->index_count;
                } else {
                    ax->hm_home = ax->hm_edge;
                    ax->hm_phase = (uint8_t)HM_STOPPING;
                }
            } else {
                ax->hm_dir = s.dir; /* passed it the wrong way: turn round, slowly */
                ax->hm_flags |= HMF_SLOW;
            }
        }
    } else if ((ax->hm_phase == (uint8_t)HM_INDEX) && (fb->index_count != ax->hm_index)) {
        ax->hm_index = fb->index_count;
        if (((fb->index_pos - ax->hm_edge) * s.dir) > 0) {
            ax->hm_home = fb->index_pos;
            ax->hm_phase = (uint8_t)HM_STOPPING;
        }
    } else {
        /* no event */
    }
    for (uint8_t k = 0U; k < CO402_IN_EDGES; k++) {
        ax->hm_edges[k] = fb->edge_count[k];
    }
}

void co402_hm_run(co402_axis_t *ax, co402_demand_t *d)
{
    co402_traj_t t;
    uint32_t acc = hm_acc(ax);
    int64_t still = co402_standstill(ax);
    int64_t v = (ax->vel < 0) ? -ax->vel : ax->vel;

    if (((ax->cw & CO402_CW_HALT) != 0U) &&
        ((ax->hm_phase == (uint8_t)HM_SEARCH) || (ax->hm_phase == (uint8_t)HM_INDEX))) {
        ax->hm_phase = (uint8_t)HM_ABORTING; /* halt interrupts homing */
    }
    co402_traj_get(ax, &t);
    if ((ax->hm_phase == (uint8_t)HM_SEARCH) || (ax->hm_phase == (uint8_t)HM_INDEX)) {
        bool slow = ((ax->hm_flags & HMF_SLOW) != 0U) && ((ax->hm_flags & HMF_FAST) == 0U);
        uint32_t speed = (uint32_t)co402_get(ax, slow ? O_HM_SLOW : O_HM_FAST, 0);
        int64_t vt = (int64_t)co402_speed_in(ax, speed) * CO402_Q16 * ax->hm_dir;
        (void)co402_traj_vel(&t, vt, acc, acc, co402_tick(ax));
        co402_traj_put(ax, &t);
        events(ax);
    } else {
        (void)co402_traj_vel(&t, 0, acc, acc, co402_tick(ax));
        co402_traj_put(ax, &t);
        if ((t.v == 0) && (v <= still)) {
            if (ax->hm_phase == (uint8_t)HM_STOPPING) {
                finish(ax);
                co402_traj_get(ax, &t);
            } else if (ax->hm_phase == (uint8_t)HM_ERR_STOPPING) {
                ax->hm_phase = (uint8_t)HM_ERROR;
            } else if (ax->hm_phase == (uint8_t)HM_ABORTING) {
                ax->hm_phase = (uint8_t)HM_IDLE;
            } else {
                /* at rest */
            }
        }
    }
    co402_demand_pos(ax, d, &t);
    set_status(ax);
}
