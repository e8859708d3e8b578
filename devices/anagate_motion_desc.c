/*
 * anagate-motion: attach descriptors and the 400 Vac module's plug-in
 * (anagate_motion_desc.h).
 */
#include "anagate_motion_desc.h"

#include <stddef.h>

#include "anagate_motion.h"
#include "anagate_motion_400vac.h"
#include "anagate_motion_bl.h"

#define ANAGATE_OPTIONS (CO402_OPT_VELOCITY_RAMP | CO402_OPT_VOLTAGE_WHEN_ON | CO402_OPT_NO_REMOTE_BIT)

void anagate_motion_sim(uint8_t axis, co402_sim_config_t *c)
{
    (void)axis;
    co402_sim_defaults(c);
}

void anagate_motion_set_inputs(co402_device_run_t *r, const uint8_t bytes[8])
{
    for (uint8_t k = 0U; k < 8U; k++) {
        (void)co_od_write(r->node, 0x2000U, (uint8_t)(k + 1U), &bytes[k], 1U, true);
    }
}

/* 400 Vac: a motor is switched on while it turns in Operation enabled; the
 * two phase currents (0.01 A each, U low byte, W high byte) in 0x6078. */
static co_err_t vac_attach(void *inst, co_node_t *node, uint32_t now_us)
{
    (void)inst;
    (void)node;
    (void)now_us;
    return CO_OK;
}

static uint32_t vac_process(void *inst, uint32_t now_us)
{
    co402_device_run_t *r = (co402_device_run_t *)inst;

    (void)now_us;
    for (uint8_t i = 0U; i < r->desc->n_axes; i++) {
        uint16_t *cur = (uint16_t *)co_od_value_ptr(r->node, (uint16_t)(0x6078U + (0x800U * i)), 0U);
        int32_t v = co402_sim_velocity(&r->sim[i]);
        bool on = (co402_state(&r->axis[i]) == CO402_OPERATION_ENABLED) && (v != 0);
        if (cur != NULL) {
            *cur = on ? (uint16_t)((ANAGATE_PHASE_CURRENT << 8U) | ANAGATE_PHASE_CURRENT) : 0U;
        }
    }
    return CO_NO_DEADLINE;
}

static const co_profile_ops_t vac_ops = {
    "anagate-motion-400vac", vac_attach, vac_process, NULL, NULL, NULL, NULL,
};

static void config_bt(void *node_mem, co_node_config_t *cfg)
{
    anagate_motion_config((anagate_motion_node_t *)node_mem, cfg);
}

static void config_bl(void *node_mem, co_node_config_t *cfg)
{
    anagate_motion_bl_config((anagate_motion_bl_node_t *)node_mem, cfg);
}

static void config_400vac(void *node_mem, co_node_config_t *cfg)
{
    anagate_motion_400vac_config((anagate_motion_400vac_node_t *)node_mem, cfg);
}

const co402_device_t anagate_motion_bt4_device = {
    "anagate-motion", &anagate_motion_dev, sizeof(anagate_motion_node_t), config_bt, 4U,
    {.options = ANAGATE_OPTIONS, .full_speed = ANAGATE_FULL_SPEED},
    anagate_motion_sim, NULL, 0U,
};

const co402_device_t anagate_motion_bt2_device = {
    "anagate-motion-bt2", &anagate_motion_dev, sizeof(anagate_motion_node_t), config_bt, 2U,
    {.options = ANAGATE_OPTIONS, .full_speed = ANAGATE_FULL_SPEED},
    anagate_motion_sim, NULL, 0U,
};

const co402_device_t anagate_motion_bl_device = {
    "anagate-motion-bl", &anagate_motion_bl_dev, sizeof(anagate_motion_bl_node_t), config_bl, 2U,
    {.options = ANAGATE_OPTIONS, .full_speed = ANAGATE_FULL_SPEED},
    anagate_motion_sim, NULL, 0U,
};

const co402_device_t anagate_motion_400vac_device = {
    "anagate-motion-400vac", &anagate_motion_400vac_dev, sizeof(anagate_motion_400vac_node_t),
    config_400vac, 2U,
    {.options = ANAGATE_OPTIONS, .full_speed = ANAGATE_FULL_SPEED},
    anagate_motion_sim, &vac_ops, 0U,
};
