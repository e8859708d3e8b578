/*
 * anagate-motion: the AnaGate Motion motor modules (devices/anagate-motion*.toml)
 * as devices (co_devices.h, generated from the descriptions).
 *
 * Every motor is a CiA 402 axis at +0x800 * (motor - 1) whose one mode is
 * the velocity ramp (CO402_OPT_VELOCITY_RAMP: 0x6080 per mille of full
 * speed, 0x6083/0x6084 ms per full scale), with statusword bit 4 while the
 * power stage is on and bit 9 unused. Full speed (1000 per mille) is 3000
 * rpm of the simulated motor (4096 increments per revolution).
 *
 *   co_device_anagate_motion        "anagate-motion"        BT, variant B: 4 motors
 *   co_device_anagate_motion_bt2    "anagate-motion-bt2"    BT, variant A: 2 motors
 *   co_device_anagate_motion_bl     "anagate-motion-bl"     BL: 2 motors
 *   co_device_anagate_motion_400vac "anagate-motion-400vac" 400 Vac: 2 motors, on/off,
 *                                   phase currents in 0x6078 (a device plug-in)
 * A module with fewer motors keeps the objects of all four (the PDOs carry
 * four); the missing motors read 0 and ignore their controlword.
 */
#ifndef ANAGATE_MOTION_DESC_H
#define ANAGATE_MOTION_DESC_H

#include <stdint.h>

#include "co/co402_device.h"

#define ANAGATE_FULL_SPEED 204800U   /**< increments/s at 1000 per mille (3000 rpm) */
#define ANAGATE_PHASE_CURRENT 150U   /**< 400 Vac: phase current of a running motor, 0.01 A */

/** The module's sensor and encoder inputs (T-PDO4, Tabelle 35) as the
 *  simulation or the hardware reads them: @p bytes[0..7] into 0x2000.1..8
 *  (byte 1: bit 7..0 = S1, S2, E1 C, E1 B, E1 A, E2 C, E2 B, E2 A; bytes
 *  2..7 the encoder values and edge counts; byte 8 S1 count << 4 | S2
 *  count). A change sends T-PDO4. */
void anagate_motion_set_inputs(co_node_t *node, const uint8_t bytes[8]);

#endif /* ANAGATE_MOTION_DESC_H */
