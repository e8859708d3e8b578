/*
 * ssd-630: the SSD Drives 630 series servo drive (devices/ssd-630.toml) on
 * the CiA 402 profile. Its CiA 402 deviations (digest D§6, D§8.1):
 *
 *   - statusword bit 4 (voltage enabled) is 0 in every value the manual
 *     shows: CO402_OPT_NO_VOLTAGE_BIT;
 *   - bit 9 (remote) is set once the drive-enable input has 24 V; Shutdown
 *     needs it; losing the input ends in Switch on disabled (0x2019 = 0):
 *     CO402_OPT_REMOTE_IS_ENABLE;
 *   - bit 15 is set together with bit 12 (0x9227, 0x9627):
 *     CO402_OPT_SW15_MIRRORS_12;
 *   - 0x60FF must be 0 (and the axis at rest) to change the mode:
 *     CO402_OPT_MODE_AT_REST;
 *   - velocities in rpm, positions in increments, no factor group:
 *     CO402_OPT_VEL_RPM;
 *   - a new pp set-point is acknowledged with bit 10 still set (0x9627, then
 *     0x9227 while moving, §14.11): CO402_OPT_PP_TR_NEXT_TICK;
 *   - in ip mode the axis at rest reports target reached before ip is
 *     enabled (0x0627, §14.14): CO402_OPT_IP_TR_AT_REST;
 *   - homing methods 0 and -24..-1 (the drive's homing modes 0..23);
 *   - the error register of each EMCY code as §9's table gives it;
 *   - 0x2018 = 1: Operational straight after power-on.
 *
 * The simulated motor: 4096 increments per revolution (the manual gives no
 * encoder resolution), the default motor of co402_sim.
 */
#include <stddef.h>
#include <string.h>

#include "co/co402_device.h"
#include "ssd_630.h"

/* 0x2018 "NMT operational state" = 1: Operational after power-on. */
static void powered_on(co_node_t *node, uint32_t now_us)
{
    const void *p = co_od_value_ptr(node, 0x2018U, 0U);
    uint16_t autostart = 0U;

    if (p != NULL) {
        (void)memcpy(&autostart, p, sizeof autostart);
    }
    if (autostart == 1U) {
        co_node_nmt_command(node, 0x01U, now_us);
    }
}

const co_device_plugin_t ssd_630_plugin = {.powered_on = powered_on};
