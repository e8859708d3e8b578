/*
 * kollmorgen-s300-s700: the Kollmorgen S300/S700 servo amplifier
 * (devices/kollmorgen-s300-s700.toml) on the CiA 402 profile. Its CiA 402
 * deviations (digest D6, D8.1):
 *
 *   - statusword bit 4 only while the power stage is on (0x0240, 0x0221,
 *     0x0233, 0x0237 in §6.3.9): CO402_OPT_VOLTAGE_WHEN_ON;
 *   - device-control commands decoded with bit 7 don't care (the manual's
 *     command table prints it "X"): CO402_OPT_BIT7_DONT_CARE;
 *   - no option codes 0x605A..0x605E: quick stop brakes with 0x6085 and stays
 *     in Quick stop active (CO402_OPT_QS_STAY) and deletes the set-points
 *     (CO402_OPT_QS_CLEARS_TARGET); halt keeps them;
 *   - velocities and accelerations in position units (PUNIT/VUNIT/ACCUNIT
 *     as the manual recommends; 0x6094 reads 0, 0x6097 is derived from
 *     0x6093): CO402_OPT_UNITS_FROM_POS;
 *   - no mode-specific statusword bits in pv (bit 12 "speed = 0" not
 *     reported): CO402_OPT_PV_NO_SPEED_BIT;
 *   - homing reports 0x0237 while it runs, then 0x0637 at home and 0x1637
 *     (§6.3.7, §6.3.9): CO402_OPT_HM_TARGET_FIRST;
 *   - its 17 homing methods, manufacturer methods negative (D6.9);
 *   - every EMCY carries its error category in byte 3 (D2.8);
 *   - response monitoring (D2.4, D2.5): a node-guarding or heartbeat loss
 *     is warning n04, not a fault and no NMT change (no 0x1029): the axis
 *     brakes on the quick-stop ramp 0x6085 and holds, statusword bits 7 and
 *     11, until controlword bit 7 (fault reset) clears it
 *     (CO402_OPT_LOSS_WARN_STOP); the plug-in below shows n04 as bit 3 of
 *     the manufacturer warnings 0x2000.
 *
 * The simulated motor: 2^20 increments per revolution (PRBASE 20, as 0x6063
 * and 0x608F say), one index pulse per revolution, 100 rev/s top speed.
 */
#include "co/co402_device.h"
#include "kollmorgen_s300_s700.h"

/* 0x2000 bit 3, warning n04 "response monitoring": set while the axis
 * holds a connection loss (CO402_OPT_LOSS_WARN_STOP), i.e. from the loss
 * until the fault reset. */
#define WARN_N04 ((uint32_t)0x00000008U)

static void show_n04(co_device_run_t *r)
{
    uint32_t *warnings = (uint32_t *)co_od_value_ptr(co_device_node(r), 0x2000U, 0U);
    const co402_axis_t *ax = co402_device_axis(r, 0U);

    if ((warnings != NULL) && (ax != NULL)) {
        *warnings = co402_connection_lost(ax) ? (*warnings | WARN_N04) : (*warnings & (uint32_t)~WARN_N04);
    }
}

static co_err_t op_attach(void *inst, co_node_t *node, uint32_t now_us)
{
    (void)node;
    (void)now_us;
    show_n04((co_device_run_t *)inst);
    return CO_OK;
}

static uint32_t op_process(void *inst, uint32_t now_us)
{
    (void)now_us;
    show_n04((co_device_run_t *)inst);
    return CO_NO_DEADLINE;
}

/* the axes have taken the loss already (they come first on the host) */
static void op_error_control(void *inst, co_hb_event_t ev, uint8_t id, uint32_t now_us)
{
    (void)ev;
    (void)id;
    (void)now_us;
    show_n04((co_device_run_t *)inst);
}

static const co_profile_ops_t kollmorgen_ops = {
    .name = "kollmorgen-s300-s700",
    .attach = op_attach,
    .process = op_process,
    .error_control = op_error_control,
};

const co_device_plugin_t kollmorgen_s300_s700_plugin = {.ops = &kollmorgen_ops};
