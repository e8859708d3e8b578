/*
 * Internals shared by the core's modules. Not a public header.
 */
#ifndef CO_PRIV_H
#define CO_PRIV_H

#include <stdbool.h>
#include <stdint.h>

#include "co/co_node.h"

/* Receive-slot kinds (co_rx_slot_t.kind), in dispatch order of likelihood. */
enum {
    CO_RX_NMT = 1,
    CO_RX_SDO,
    CO_RX_GUARD,
    CO_RX_HB,
    CO_RX_SYNC,
    CO_RX_TIME
};

/* Wrap-safe "a is at or after b". */
static inline bool co_time_reached(uint32_t now, uint32_t when)
{
    return (int32_t)(now - when) >= 0;
}

/* Earliest of a deadline set and another candidate. */
static inline uint32_t co_deadline_min(uint32_t now, uint32_t cur, uint32_t cand)
{
    if (cur == CO_NO_DEADLINE) {
        return cand;
    }
    return ((int32_t)(cand - now) < (int32_t)(cur - now)) ? cand : cur;
}

/* ---- transmit (co_node.c) */
void co_tx(co_node_t *node, uint32_t id, const uint8_t *data, uint8_t len);
/* Send now or not at all (nothing held back): for streams that resume later. */
bool co_tx_try(co_node_t *node, uint32_t id, const uint8_t *data, uint8_t len);
void co_rx_rebuild(co_node_t *node);

/* ---- object dictionary internals (co_od.c) */
co_err_t co_od_lookup(const co_node_t *node, uint16_t index, uint8_t sub,
                      const co_od_entry_t **e, const co_od_sub_t **s);
void *co_od_loc(const co_node_t *node, const co_od_sub_t *s);
co_err_t co_od_check_access(const co_node_t *node, const co_od_sub_t *s, bool write);
/* Current size of the value (strings: up to the first NUL); 0 for HOOKIO. */
uint32_t co_od_data_size(const co_node_t *node, const co_od_sub_t *s);
bool co_od_is_streamed(const co_od_sub_t *s);
/* Read a chunk; at offset 0 the read hook runs first. *total gets the total
 * size (0 if a hook does not know it); *last is set on the final chunk. */
co_err_t co_od_read_part(co_node_t *node, const co_od_entry_t *e, const co_od_sub_t *s,
                         uint32_t offset, uint8_t *buf, uint32_t cap, uint32_t *len,
                         uint32_t *total, bool *last);
/* Write a complete value (checks, hook, commit, notification). */
co_err_t co_od_write_value(co_node_t *node, const co_od_entry_t *e, const co_od_sub_t *s,
                           const uint8_t *data, uint32_t len);
/* Write one chunk of a streamed value (strings, DOMAIN). */
co_err_t co_od_write_part(co_node_t *node, const co_od_entry_t *e, const co_od_sub_t *s,
                          uint32_t offset, const uint8_t *data, uint32_t len, uint32_t total,
                          bool last);
/* Restore [from, to) of the RAM image to defaults and apply $NODEID. */
void co_od_restore(co_node_t *node, uint16_t from, uint16_t to);

/* ---- communication objects owned by the core (co_comm.c) */
co_err_t co_comm_check_read(const co_node_t *node, uint16_t index, uint8_t sub);
co_err_t co_comm_check_write(const co_node_t *node, uint16_t index, uint8_t sub,
                             const uint8_t *data, uint32_t len);
void co_comm_written(co_node_t *node, uint16_t index, uint8_t sub);
void co_comm_bind(co_node_t *node);

/* ---- services */
void co_nmt_rx(co_node_t *node, const co_frame_t *f);
void co_nmt_boot(co_node_t *node);
void co_sdo_rx(co_node_t *node, const co_frame_t *f);
uint32_t co_sdo_process(co_node_t *node, uint32_t next);
void co_sdo_reset(co_node_t *node);
void co_hb_rx(co_node_t *node, uint8_t slot, const co_frame_t *f);
void co_guard_rx(co_node_t *node, const co_frame_t *f);
uint32_t co_hb_process(co_node_t *node, uint32_t next);
void co_hb_reset(co_node_t *node);
void co_hb_consumers_changed(co_node_t *node);
void co_hb_producer_changed(co_node_t *node);
uint32_t co_emcy_process(co_node_t *node, uint32_t next);
void co_sync_rx(co_node_t *node, const co_frame_t *f);
void co_time_rx(co_node_t *node, const co_frame_t *f);
uint32_t co_sync_process(co_node_t *node, uint32_t next);
void co_sync_reset(co_node_t *node);
void co_emcy_reset(co_node_t *node);
void co_emcy_history_clear(co_node_t *node);

/* ---- parameter storage, 0x1010 / 0x1011 (co_store.c) */
/* Restore the area a reset covers (node: the image, communication: [0, comm_end))
 * to defaults, load the stored values of that area if a valid set exists, and
 * set what 0x1010 / 0x1011 read. */
void co_store_reset(co_node_t *node, co_reset_t kind);
/* True for a sub-entry of 0x1010 / 0x1011 the core acts on (sub >= 1, UNSIGNED32 in RAM). */
bool co_store_is_command(const co_od_entry_t *e, const co_od_sub_t *s);
/* A checked write to such a sub-entry: save or restore; the value is never stored. */
co_err_t co_store_command(co_node_t *node, uint16_t index, uint8_t sub, const uint8_t *data);

#endif /* CO_PRIV_H */
