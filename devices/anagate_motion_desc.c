/*
 * anagate-motion: the AnaGate Motion modules as CiA 402 devices and the
 * 400 Vac module's plug-in (anagate_motion_desc.h).
 */
#include "anagate_motion_desc.h"

#include <stddef.h>

#include "anagate_motion.h"
#include "anagate_motion_400vac.h"
#include "anagate_motion_bl.h"

void anagate_motion_set_inputs(co_node_t *node, const uint8_t bytes[8])
{
    for (uint8_t k = 0U; k < 8U; k++) {
        (void)co_od_write(node, 0x2000U, (uint8_t)(k + 1U), &bytes[k], 1U, true);
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
    co_device_run_t *drv = (co_device_run_t *)inst;
    co_node_t *node = co_device_node(drv);
    const co402_axis_t *ax;

    (void)now_us;
    for (uint8_t i = 0U; (ax = co402_device_axis(drv, i)) != NULL; i++) {
        uint16_t *cur = (uint16_t *)co_od_value_ptr(node, (uint16_t)(0x6078U + (0x800U * i)), 0U);
        bool on = (co402_state(ax) == CO402_OPERATION_ENABLED) && (co402_velocity(ax) != 0);
        if (cur != NULL) {
            *cur = on ? (uint16_t)((ANAGATE_PHASE_CURRENT << 8U) | ANAGATE_PHASE_CURRENT) : 0U;
        }
    }
    return CO_NO_DEADLINE;
}

static const co_profile_ops_t vac_ops = {
    .name = "anagate-motion-400vac",
    .attach = vac_attach,
    .process = vac_process,
};

const co_device_plugin_t anagate_motion_400vac_plugin = {.ops = &vac_ops};
