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

/* 0 is "no homing"; mode m (0..23) is written as m - 24. Only mode 0 (-24,
 * the next encoder zero pulse in positive direction at homing speed 1,
 * §14.10) is described; the other modes are accepted and end in a homing
 * error (statusword bit 13), their descriptions are missing from the manual. */
static const co402_hm_method_t hm_methods[] = {
    {0, 0, 0U},    {-24, 34, CO402_HM_FAST_ONLY}, {-23, 0, 0U}, {-22, 0, 0U}, {-21, 0, 0U},
    {-20, 0, 0U},  {-19, 0, 0U}, {-18, 0, 0U}, {-17, 0, 0U}, {-16, 0, 0U}, {-15, 0, 0U},
    {-14, 0, 0U},  {-13, 0, 0U}, {-12, 0, 0U}, {-11, 0, 0U}, {-10, 0, 0U}, {-9, 0, 0U},
    {-8, 0, 0U},   {-7, 0, 0U},  {-6, 0, 0U},  {-5, 0, 0U},  {-4, 0, 0U},  {-3, 0, 0U},
    {-2, 0, 0U},   {-1, 0, 0U},
};

#define ZERO {0U, 0U, 0U, 0U, 0U}

/* §9, table 1: the error register each code reports (bit 0 included). */
static const co402_error_t errors[] = {
    {0x2230U, 0x03U, ZERO}, {0x2311U, 0x03U, ZERO}, {0x2312U, 0x03U, ZERO},
    {0x3210U, 0x05U, ZERO}, {0x3220U, 0x05U, ZERO}, {0x4210U, 0x09U, ZERO},
    {0x4310U, 0x09U, ZERO}, {0x5110U, 0x05U, ZERO}, {0x5441U, 0x81U, ZERO},
    {0x5442U, 0x81U, ZERO}, {0x5443U, 0x81U, ZERO}, {0x5530U, 0x81U, ZERO},
    {0x6010U, 0x81U, ZERO}, {0x6100U, 0x81U, ZERO}, {0x6200U, 0x81U, ZERO},
    {0x7113U, 0x09U, ZERO}, {0x7300U, 0x81U, ZERO}, {0x8400U, 0x21U, ZERO},
    {0x8611U, 0x21U, ZERO}, {0x8612U, 0x21U, ZERO}, {0x8700U, 0x21U, ZERO},
};

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

static const co402_params_t params_ssd_630_impl = {
    .options = CO402_OPT_NO_VOLTAGE_BIT | CO402_OPT_REMOTE_IS_ENABLE | CO402_OPT_SW15_MIRRORS_12 |
               CO402_OPT_MODE_AT_REST | CO402_OPT_VEL_RPM | CO402_OPT_PP_TR_NEXT_TICK |
               CO402_OPT_IP_TR_AT_REST,
    .counts_per_rev = 4096U,
    .hm_methods = hm_methods,
    .n_hm_methods = (uint8_t)(sizeof hm_methods / sizeof hm_methods[0]),
    .errors = errors,
    .n_errors = (uint8_t)(sizeof errors / sizeof errors[0]),
    .sim_config = NULL,
};

static const co_device_part_t parts_ssd_630_impl[] = {{&co402_part, &params_ssd_630_impl, 1U}};

const co_device_impl_t ssd_630_impl = {
    .parts = parts_ssd_630_impl,
    .n_parts = 1U,
    .powered_on = powered_on,
};
