/*
 * faulhaber-mc: the FAULHABER Motion Controller (devices/faulhaber-mc.toml)
 * as a CiA 402 device (co_device_faulhaber_mc in co_devices.h) and its
 * device plug-in.
 *
 * One CiA 402 axis with FAULHABER's deviations as profile options and its
 * fixed units (velocities in rpm, accelerations in 1/s^2, 3000 increments
 * per revolution: BL controller with Hall sensors), a simulated BL motor,
 * and a plug-in for what is FAULHABER's own:
 *   - the error register 0x2320 with the masks 0x2321 (emergency, fault)
 *     and the error delay 0x2322.01; its EMCYs carry 0x2320 in bytes 3-4,
 *     also the ones the core raises itself (heartbeat / guarding 0x8130,
 *     RPDO length 0x8210 / 0x8220) and the CAN port's (0x8110, 0x8120,
 *     0x8140), through the plug-in's emcy_mfr;
 *     writing the fault mask sets the same bits in the emergency mask; an
 *     error whose fault-mask bit is set puts the axis into Fault
 *     (faulhaber_mc_error() reports a drive error condition);
 *   - heartbeat and node guarding exclude each other (0x1017 > 0 clears
 *     0x100C/0x100D; a guard time while producing heartbeats: 0x08000020);
 *   - factory restore (0x1011.1-3) only in Switch on disabled, 0x2310 not
 *     while homing (0x08000022);
 *   - the position factor 0x6093 computed from 0x608F, 0x6091 and 0x6092
 *     (numerator below 2e9, else 0x06040047), 0x257A sets the target in
 *     increments, 0x2562 and 0x2361 follow the axis.
 */
#ifndef FAULHABER_MC_DESC_H
#define FAULHABER_MC_DESC_H

#include <stdbool.h>
#include <stdint.h>

#include "co/co402_device.h"
#include "faulhaber_mc.h"

/* Bits of the FAULHABER error register 0x2320 (and of the masks 0x2321). */
#define FAULHABER_ERR_OVERCURRENT  0x0001U /**< EMCY 0x2310 (after the error delay) */
#define FAULHABER_ERR_DEVIATION    0x0002U /**< EMCY 0x8400 in pp, 0x8611 in pv (after the delay) */
#define FAULHABER_ERR_OVERVOLTAGE  0x0004U /**< EMCY 0x3210 (after the delay) */
#define FAULHABER_ERR_TEMPERATURE  0x0008U /**< EMCY 0x4310 */
#define FAULHABER_ERR_FLASH        0x0010U /**< EMCY 0x5530 */
#define FAULHABER_ERR_CAN_PASSIVE  0x0040U /**< EMCY 0x8120 */
#define FAULHABER_ERR_CAN_OVERRUN  0x0080U /**< EMCY 0x8110 */
#define FAULHABER_ERR_GUARDING     0x0100U /**< EMCY 0x8130 (heartbeat / life guarding) */
#define FAULHABER_ERR_BUS_OFF      0x0200U /**< EMCY 0x8140 */
#define FAULHABER_ERR_CONVERSION   0x0800U /**< EMCY 0xFF01 */
#define FAULHABER_ERR_SOFTWARE     0x1000U /**< EMCY 0x6100 */
#define FAULHABER_ERR_PDO_LONG     0x2000U /**< EMCY 0x8220 */
#define FAULHABER_ERR_PDO_SHORT    0x4000U /**< EMCY 0x8210 */

/** State of the FAULHABER plug-in (the caller allocates it and gives it with
 *  co_device_init: the block holds it). */
typedef struct faulhaber_mc_state {
    uint32_t since[16];      /* when each present condition arose */
    uint16_t code[16];       /* EMCY code each reported error was raised with */
    uint16_t present;        /* conditions present (the delay may still run) */
    uint16_t core;           /* 0x2320 bits of errors the core raised (op_emcy_mfr) */
    uint16_t faulted;        /* ... of those, the ones whose fault-mask reaction ran */
} faulhaber_mc_state_t;

/** The plug-in (instance: the co_device_run_t), for devices of other
 *  FAULHABER variants. */
extern const co_profile_ops_t faulhaber_mc_ops;

/** A drive error condition (@p bit of 0x2320) arises (@p on) or ends. It is
 *  reported after the error delay 0x2322.01 (over-current, deviation,
 *  over-voltage) or at once, at the next co_device_process. */
void faulhaber_mc_error(co_device_run_t *r, uint16_t bit, bool on);

#endif /* FAULHABER_MC_DESC_H */
