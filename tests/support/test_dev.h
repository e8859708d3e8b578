/*
 * A hand-written test device: the CiA 301 communication objects the core
 * owns, an object of every basic type, limits, write-only/const objects,
 * hooked objects and a hook-backed DOMAIN. (Generated devices replace this
 * once the description generator exists; the layout is the same.)
 */
#ifndef TEST_DEV_H
#define TEST_DEV_H

#include <stdint.h>

#include "co/co_node.h"
#include "test_bus.h"

/* Hook slots of td_dev */
#define TD_HOOK_2100 0U
#define TD_HOOK_DOMAIN 1U
#define TD_HOOK_2201 2U
#define TD_N_HOOKS 3U

typedef struct td_ram {
    /* communication parameters (stored); the core's objects at their places
     * (co_node.h, CO_RAM_*) */
    uint32_t sync_window;  /* 0x1007 */
    uint16_t sync_cob;     /* 0x1005 (the COB-IDs in their 16-bit forms: co_od.h CO_SUB_COB16) */
    uint16_t emcy_cob;     /* 0x1014, $NODEID+0x80 */
    uint16_t emcy_inhibit; /* 0x1015 */
    uint16_t hb_prod;      /* 0x1017 */
    uint8_t sync_overflow; /* 0x1019 */
    uint8_t err_beh[3];    /* 0x1029 sub1..3: communication error (default 0, CiA 301),
                              two device-specific classes (default 1) */
    uint32_t hb_cons[4];   /* 0x1016 sub1..4 */
    uint32_t sync_period;  /* 0x1006 */
    uint16_t time_cob;     /* 0x1012, default 0x80000100 (consumer) */
    uint16_t pad3;
    uint32_t node_id;      /* 0x100B, $NODEID */
    uint16_t guard_time;   /* 0x100C */
    uint8_t life_factor;   /* 0x100D */
    uint8_t pad0;
    /* application values (stored) */
    uint8_t u8;
    int8_t i8;
    uint16_t u16;
    int16_t i16;
    uint16_t cw;           /* 0x6040 */
    uint32_t u32;
    int32_t i32;
    uint64_t u64;
    int64_t i64;
    uint32_t r32;          /* REAL32 bit pattern */
    uint64_t r64;          /* REAL64 bit pattern */
    uint8_t b;             /* BOOLEAN */
    uint8_t u24[3];
    uint8_t i24[3];
    uint8_t u40[5];
    uint8_t i48[6];
    uint8_t u56[7];
    uint8_t tod[6];
    uint8_t tdiff[6];
    char vstr[32];
    uint8_t ostr[10];
    uint8_t ustr[8];
    uint16_t lim_u16;      /* 0x2020: 10..1000 */
    int16_t lim_i16;       /* 0x2021: -100..100 */
    uint32_t wo_u32;       /* 0x2022: write-only */
    uint32_t hooked;       /* 0x2100 */
    uint32_t rec0;         /* 0x2300 sub0 (data in sub-index 0) */
    uint16_t rec1;         /* 0x2300 sub1 */
    int8_t mode;           /* 0x6060 */
    uint8_t pad2[3];
    int32_t target_pos;    /* 0x607A */
    int32_t target_vel;    /* 0x60FF */
    uint32_t homing_speed[2]; /* 0x6099 sub1..2, limit 0..60000 */
    /* not stored (from app_end: the core's objects at their places) */
    uint8_t errreg;        /* 0x1001 */
    uint8_t hist_n;        /* 0x1003 sub0 */
    uint16_t pad1;
    uint32_t hist[8];      /* 0x1003 sub1..8 */
    uint32_t mfr_status;   /* 0x1002 */
    uint32_t store[3];     /* 0x1010 sub1..3 (core: capability) */
    uint32_t restore[6];   /* 0x1011 sub1..6 (core: capability; 4..6 only with
                              CO_RESTORE_SAVED, else 0) */
    uint8_t stage[32];     /* SDO download staging (co_dev_t.stage): vstr is the largest */
    /* the node's hook table (not an object: co_dev_t.hooks_at) */
    co_od_hook_t hooks[TD_N_HOOKS];
} td_ram_t;

extern const co_dev_t td_dev;

/** A node of the test device on @p bus slot @p idx; its storage lives in
 *  the struct. */
typedef struct td_node {
    co_node_t node;
    td_ram_t ram;
    co_node_callbacks_t cb; /**< td_start_cb's callbacks (the node keeps a pointer) */
} td_node_t;

/** Initialise @p n as node @p id on @p bus (slot @p idx) with device @p dev
 *  (NULL: td_dev). Its boot-up frame stays in the bus log. */
void td_start(td_node_t *n, tb_bus_t *bus, uint8_t idx, uint8_t id, const co_dev_t *dev);

/** td_start with application callbacks (@p cb may be NULL). */
void td_start_cb(td_node_t *n, tb_bus_t *bus, uint8_t idx, uint8_t id, const co_dev_t *dev,
                 const co_node_callbacks_t *cb);

#endif
