/*
 * CiA 401: generic I/O modules (digital and analog inputs and outputs) as a
 * plug-in of the profile interface (co/co_profile.h). Portable C99, no OS.
 *
 * One co401_t per module. It finds its objects in the node's dictionary at
 * attach; what the description lacks is not offered (the defaults below
 * apply instead of an absent parameter object):
 *
 *   digital inputs   one width of 0x6000 (8-bit) / 0x6100 (16) / 0x6120 (32),
 *                    sub 1..n (ro, mappable), with at +2 polarity (0x6002,
 *                    default 0: a set bit inverts), +3 filter constant (0: a
 *                    set bit takes a change only after it was stable for
 *                    co401_config_t.filter_us), +6 / +7 / +8 interrupt masks
 *                    any change (default all set) / low-to-high / high-to-low
 *                    (default 0), and 0x6005 global interrupt enable
 *                    (default TRUE);
 *   digital outputs  one width of 0x6200 / 0x6300 / 0x6320, sub 1..n, with at
 *                    +2 polarity, +6 error mode (default all set: the bit
 *                    takes its error value), +7 error value (default 0) and
 *                    +8 filter mask (default all set: 0 keeps the output at
 *                    its present value);
 *   analog inputs    0x6401 (INTEGER16) sub 1..n, with per channel 0x6421
 *                    trigger selection (bit 0 upper limit exceeded, 1 below
 *                    lower limit, 2 changed by more than delta, 3 reduced by
 *                    more than the negative delta, 4 increased by more than
 *                    the positive delta; default 0x07), 0x6423 global
 *                    interrupt enable (default FALSE), 0x6424 / 0x6425
 *                    upper / lower limit (INTEGER32), 0x6426 delta, 0x6427 /
 *                    0x6428 negative / positive delta (UNSIGNED32);
 *   analog outputs   0x6411 (INTEGER16) sub 1..n, with 0x6443 error mode
 *                    (default 1) and 0x6444 error value (INTEGER32, default 0).
 *
 * Inputs: every process reads the plant (physical level -> filter ->
 * polarity -> object). A change of an input sends an event-driven TPDO that
 * maps it only when it is an interrupt: tpdo_event clears the changed bits
 * of these objects unless a transition of the block since the TPDO last
 * went out was enabled by the masks (and 0x6005), and of an analog input
 * unless its change from the value sent last crosses a limit or exceeds a
 * delta the trigger selection enables (and 0x6423). A masked transition
 * goes out with the next interrupt.
 *
 * Outputs: applied to the plant (object -> filter mask -> polarity ->
 * physical level) when an RPDO was received (all at once) and when an
 * output object changed (SDO, application). On a communication error
 * (heartbeat consumer timeout, life-guarding loss, a class-1 error such as
 * bus-off) and before NMT Stopped the outputs whose error mode bit is set
 * take their error value (then polarity); the next output change or RPDO
 * ends it. Reset node: the objects are back at their defaults and applied.
 *
 * A vendor layout is a setting: co401_config_t names other input / output
 * objects and the sub-index of the first block (AnaGate: 0x8000 / 0x8001,
 * data in sub 0 and 1).
 */
#ifndef CO401_H
#define CO401_H

#include <stdbool.h>
#include <stdint.h>

#include "co/co_node.h"
#include "co/co_profile.h"

#define CO401_DIO_BYTES 8U /**< digital inputs / outputs of one module: 64 each */
#define CO401_AIO_MAX 8U   /**< analog channels of one module, each way */

/** What the module drives and reads: the hardware or a simulation. */
typedef struct co401_io_ops {
    /** The physical inputs now: @p din (n_din bytes, bit k of byte b is
     *  input 8b + k + 1), @p ain (n_ain channels). */
    void (*read)(void *ctx, uint8_t *din, uint8_t n_din, int16_t *ain, uint8_t n_ain);
    /** Drive the physical outputs (n_dout bytes, n_aout channels). */
    void (*write)(void *ctx, const uint8_t *dout, uint8_t n_dout, const int16_t *aout,
                  uint8_t n_aout);
} co401_io_ops_t;

typedef struct co401_plant {
    const co401_io_ops_t *ops;
    void *ctx;
} co401_plant_t;

/** Settings of a module (const; from the description's [profile.cia401]). */
typedef struct co401_config {
    uint16_t di;        /**< digital input object (0: 0x6000, 0x6100 or 0x6120, whichever exists) */
    uint16_t dout;      /**< digital output object (0: 0x6200, 0x6300 or 0x6320) */
    uint8_t first_sub;  /**< sub-index of the first block (CiA 401: 1; 0: data in sub 0 on) */
    uint8_t n_di;       /**< blocks of di (0: as many as the object has) */
    uint8_t n_do;       /**< blocks of dout (0: as many as the object has) */
    uint32_t filter_us; /**< input filter time (0: 3 ms) */
    uint32_t poll_us;   /**< inputs read at least this often (0: 10 ms) */
} co401_config_t;

/** One module. Fields are private. */
typedef struct co401 {
    co401_config_t cfg;
    co401_plant_t plant;
    co_node_t *node;
    uint16_t di;                /* objects found (0: none) */
    uint16_t dout;
    uint8_t di_size;            /* bytes per block: 1, 2 or 4 */
    uint8_t do_size;
    uint8_t n_di;               /* blocks */
    uint8_t n_do;
    uint8_t n_ai;               /* analog channels */
    uint8_t n_ao;
    uint8_t raw[CO401_DIO_BYTES];      /* physical inputs last read */
    uint8_t stable[CO401_DIO_BYTES];   /* filtered physical inputs */
    uint32_t since[CO401_DIO_BYTES * 8U]; /* filter: time a pending change was first seen */
    uint8_t pending[CO401_DIO_BYTES];  /* filter: bits whose change waits */
    uint8_t dobj[CO401_DIO_BYTES];     /* input objects as last written */
    uint32_t irq[CO401_DIO_BYTES];     /* per block: interrupt-enabled transitions not yet sent */
    uint8_t applied[CO401_DIO_BYTES];  /* output objects as last applied */
    uint8_t dlog[CO401_DIO_BYTES];     /* logical outputs (after the filter mask) */
    uint8_t dphys[CO401_DIO_BYTES];    /* physical outputs */
    int16_t ain[CO401_AIO_MAX];
    int16_t aapplied[CO401_AIO_MAX];
    int16_t aphys[CO401_AIO_MAX];
    uint32_t next_poll;
    bool error;                 /* outputs at their error values */
    bool started;
} co401_t;

/** The plug-in operations (instance: co401_t). */
extern const co_profile_ops_t co401_profile_ops;

/** Prepare @p m with @p cfg on @p plant (before attach). */
void co401_init(co401_t *m, const co401_config_t *cfg, co401_plant_t plant);

/** The physical digital outputs now (n bytes; NULL: none). */
const uint8_t *co401_outputs(const co401_t *m, uint8_t *n);

/** True while the outputs hold their error values. */
bool co401_in_error(const co401_t *m);

/** Input channel of @p index / @p sub: *byte (digital: the first byte of
 *  its block, *width bytes) or *ain (analog channel); false when the object
 *  is none of the module's inputs. For the simulation's control interface. */
bool co401_input_of(const co401_t *m, uint16_t index, uint8_t sub, uint8_t *byte,
                    uint8_t *width, uint8_t *ain);

#endif /* CO401_H */
