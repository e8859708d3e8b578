/*
 * The hardware abstraction: a const table of functions plus a context
 * pointer, one per node (or per bus). SocketCAN, an MCU CAN driver and the
 * in-memory test bus are all drivers of this interface.
 *
 * Threading contract
 * ------------------
 * The core is passive and not re-entrant per node: co_node_rx() and
 * co_node_process() of one node must be called from one context (a main loop
 * or one task). An MCU receive ISR does not call the core; it pushes frames
 * into a co_rxq (co_rxq.h, single producer / single consumer, lock-free) that
 * the main loop drains into co_node_rx(). send() is called only from that same
 * context. Different nodes are independent and may run in different threads.
 */
#ifndef CO_HAL_H
#define CO_HAL_H

#include <stdint.h>

#include "co/co_frame.h"

typedef struct co_hal_ops {
    /** Queue @p f for transmission. Return 0 when it was accepted, non-zero
     *  when the TX path is full: the core keeps the frame and tries again on
     *  the next co_node_process(). Required. */
    int (*send)(void *ctx, const co_frame_t *f);
    /** Read @p len bytes of non-volatile memory at @p addr. Return 0 on
     *  success. Optional (NULL, or nv_write NULL: no storage; 0x1010/0x1011
     *  read 0 and answer 0x08000020). Addresses are 0 ..
     *  co_store_nv_size(dev) - 1; a HAL shared by several nodes maps each
     *  node's range through its ctx. */
    int (*nv_read)(void *ctx, uint32_t addr, uint8_t *buf, uint32_t len);
    /** Write @p len bytes of non-volatile memory at @p addr (byte-granular,
     *  like EEPROM/FRAM or a flash emulation; erased flash with nv_erase).
     *  Return 0 on success, non-zero on a failure (the save answers
     *  0x06060000). One save writes each byte of the new bank once, data in
     *  ascending order and the 16-byte header last. Optional. */
    int (*nv_write)(void *ctx, uint32_t addr, const uint8_t *buf, uint32_t len);
    /** LSS (CiA 305): switch the CAN controller to index @p index of the
     *  CiA 305 bit-timing table (0 1000 .. 8 10 kbit/s, 9 automatic). Called
     *  at co_node_init with an LSS-stored bit timing and when LSS activate
     *  bit timing switches. Optional (NULL: the rate stays as it is). */
    int (*bit_timing)(void *ctx, uint8_t index);
    /** Asynchronous non-volatile writes. Optional: NULL means nv_write and
     *  nv_erase are complete when they return. With it they may only start
     *  the work (taking what they need of @p buf before they return) and
     *  complete in the order they were issued; the core then asks nv_poll
     *  from co_node_process until it returns 0 (everything issued so far is
     *  durable) or a value other than CO_NV_BUSY (failed: the save answers
     *  0x06060000). The node serves the bus meanwhile, and the SDO answer to
     *  the 0x1010 / 0x1011 write (the LSS answer to store configuration)
     *  comes when the set (the record) is durable. */
    int (*nv_poll)(void *ctx);
    /** Erase [@p addr, @p addr + @p len) before it is written (flash);
     *  both are multiples of nv_erase_unit. Optional (NULL: memory that is
     *  written without erasing: EEPROM, FRAM, a file). With nv_poll it may
     *  be asynchronous too: the core writes the bank when nv_poll says the
     *  erase is done, outside the SDO answer path. */
    int (*nv_erase)(void *ctx, uint32_t addr, uint32_t len);
    /** Erase granularity in bytes (a power of two; 0 or 1: none). Each of
     *  the two banks of the parameter storage starts on a multiple of it
     *  and spans whole units, so the banks never share an erase unit; each
     *  LSS record has a unit of its own behind them (co_store_nv_size_unit
     *  gives the size to provide). */
    uint32_t nv_erase_unit;
} co_hal_ops_t;

/** nv_poll: writes (or an erase) still in progress. */
#define CO_NV_BUSY 1

typedef struct co_hal {
    const co_hal_ops_t *ops;
    void *ctx;
} co_hal_t;

#endif /* CO_HAL_H */
