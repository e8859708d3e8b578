/*
 * CiA 401 as a part of a device (co/co_device.h): the part kind co401_part
 * (one co401_t per module, configured by co401_config_t, on a
 * co401_plant_t) and its simulation co401_sim_t: every output wired to the
 * input of the same number (loopback: the digital output bytes to the input
 * bytes, analog output k to analog input k) until the control interface
 * sets an input (co_device_set: the input object's index and sub-index, the
 * physical value before polarity); the last of the two wins.
 */
#ifndef CO401_DEVICE_H
#define CO401_DEVICE_H

#include <stdint.h>

#include "co/co401.h"
#include "co/co_device.h"

/** A simulated I/O module. */
typedef struct co401_sim {
    uint8_t din[CO401_DIO_BYTES];
    uint8_t dout[CO401_DIO_BYTES];
    int16_t ain[CO401_AIO_MAX];
    int16_t aout[CO401_AIO_MAX];
    uint32_t writes; /**< output writes seen */
} co401_sim_t;

/** The CiA 401 part kind: instance co401_t, plant co401_plant_t,
 *  simulation co401_sim_t. */
extern const co_part_kind_t co401_part;

/** The loopback simulation (all zero) and its plant interface. */
void co401_sim_init(co401_sim_t *s);
co401_plant_t co401_sim_plant(co401_sim_t *s);

/** The CiA 401 module @p n of a device (NULL: none). */
co401_t *co401_device_module(const co_device_run_t *run, uint8_t n);

#endif /* CO401_DEVICE_H */
