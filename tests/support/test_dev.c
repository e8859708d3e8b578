#include "test_dev.h"

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <string.h>

#include <cmocka.h>

typedef struct td_rom {
    uint32_t x1000;
    uint32_t x1018[4];
    uint32_t x2023;
    uint8_t n1016;
    uint8_t n1018;
    uint8_t n6099;
    uint8_t n1010;
    char x1008[7];
    char x1009[3];
    char x100A[5];
    uint8_t n1029;
    uint8_t n1011;
} td_rom_t;

static const td_rom_t rom = {
    .x1000 = 0x00020192UL,
    .x1018 = {0x000000A5UL, 0x00000631UL, 0x00010002UL, 0x12345678UL},
    .x2023 = 0xCAFEF00DUL,
    .n1016 = 4U,
    .n1018 = 4U,
    .n6099 = 2U,
    .n1010 = 3U,
    .x1008 = {'6', '3', '1', '_', '4', '0', '2'},
    .x1009 = {'1', '.', '0'},
    .x100A = {'0', '.', '1', '.', '0'},
    .n1029 = 3U,
    .n1011 = 6U,
};

/* The whole image as the first default runs, then the $NODEID values, each a
 * run the node-ID is added to (the EMCY COB-ID: the COB-ID base). */
typedef struct td_defaults {
    td_ram_t img;
    uint32_t node_id;
    uint32_t emcy_cob;
} td_defaults_t;

static const td_defaults_t defaults = {.img = {
    .sync_cob = 0x80UL,
    .time_cob = 0x80000100UL,
    .node_id = 0U,
    .emcy_cob = 0x80UL,
    .err_beh = {0U, 1U, 1U},
    .u16 = 0x1234U,
    .u32 = 0xDEADBEEFUL,
    .vstr = "hello",
    .lim_u16 = 100U,
    .rec0 = 0x11223344UL,
    .rec1 = 7U,
}, .node_id = 0U, .emcy_cob = 0x80UL};

static const co_od_limit_t limits[] = {
    {10, 1000},
    {-100, 100},
    {0, 60000},
};

#define F(field) ((uint16_t)offsetof(td_ram_t, field))
#define Z(field) ((uint16_t)sizeof(((td_ram_t *)0)->field))
#define RF(field) ((uint16_t)offsetof(td_rom_t, field))
#define RZ(field) ((uint16_t)sizeof(((td_rom_t *)0)->field))
#define RAM(sub, type, flags, field) CO_OD_SUB((sub), (uint8_t)(type), (flags), Z(field), F(field), 0U)
#define ROM(sub, type, flags, field) \
    CO_OD_SUB((sub), (uint8_t)(type), (uint16_t)((flags) | CO_SUB_ROM), RZ(field), RF(field), 0U)
#define RW_MAP (CO_SUB_RW | CO_SUB_MAP)

static const co_od_sub_t s1000[] = {ROM(0, CO_UNSIGNED32, CO_SUB_RO, x1000)};
static const co_od_sub_t s1001[] = {RAM(0, CO_UNSIGNED8, CO_SUB_RO | CO_SUB_MAP_T, errreg)};
static const co_od_sub_t s1002[] = {RAM(0, CO_UNSIGNED32, CO_SUB_RO, mfr_status)};
static const co_od_sub_t s1003[] = {
    RAM(0, CO_UNSIGNED8, CO_SUB_RW, hist_n),
    /* (one row for sub 1..8: a run, CO_OD_RUN) */
    CO_OD_RUN(1, 8U, (uint8_t)CO_UNSIGNED32, CO_SUB_RO, 4U, F(hist), 0U),
};
static const co_od_sub_t s1005[] = {RAM(0, CO_UNSIGNED32, CO_SUB_RW, sync_cob)};
static const co_od_sub_t s1006[] = {RAM(0, CO_UNSIGNED32, CO_SUB_RW, sync_period)};
static const co_od_sub_t s1007[] = {RAM(0, CO_UNSIGNED32, CO_SUB_RW, sync_window)};
static const co_od_sub_t s1012[] = {RAM(0, CO_UNSIGNED32, CO_SUB_RW, time_cob)};
static const co_od_sub_t s1019[] = {RAM(0, CO_UNSIGNED8, CO_SUB_RW, sync_overflow)};
static const co_od_sub_t s1029[] = {
    ROM(0, CO_UNSIGNED8, CO_SUB_RO | CO_SUB_CONST, n1029),
#define B(i) CO_OD_SUB((i), (uint8_t)CO_UNSIGNED8, CO_SUB_RW, 1U, (uint16_t)(F(err_beh) + (i) - 1U), 0U)
    B(1), B(2), B(3),
#undef B
};
static const co_od_sub_t s1008[] = {ROM(0, CO_VISIBLE_STRING, CO_SUB_RO | CO_SUB_CONST, x1008)};
static const co_od_sub_t s1009[] = {ROM(0, CO_VISIBLE_STRING, CO_SUB_RO | CO_SUB_CONST, x1009)};
static const co_od_sub_t s100A[] = {ROM(0, CO_VISIBLE_STRING, CO_SUB_RO | CO_SUB_CONST, x100A)};
static const co_od_sub_t s100B[] = {RAM(0, CO_UNSIGNED32, CO_SUB_RO | CO_SUB_NODEID, node_id)};
static const co_od_sub_t s100C[] = {RAM(0, CO_UNSIGNED16, CO_SUB_RW, guard_time)};
static const co_od_sub_t s100D[] = {RAM(0, CO_UNSIGNED8, CO_SUB_RW, life_factor)};
static const co_od_sub_t s1010[] = {
    ROM(0, CO_UNSIGNED8, CO_SUB_RO | CO_SUB_CONST, n1010),
    CO_OD_SUB(1, (uint8_t)CO_UNSIGNED32, CO_SUB_RW, 4U, F(store), 0U),
    CO_OD_SUB(2, (uint8_t)CO_UNSIGNED32, CO_SUB_RW, 4U, (uint16_t)(F(store) + 4U), 0U),
    CO_OD_SUB(3, (uint8_t)CO_UNSIGNED32, CO_SUB_RW, 4U, (uint16_t)(F(store) + 8U), 0U),
};
static const co_od_sub_t s1011[] = {
    ROM(0, CO_UNSIGNED8, CO_SUB_RO | CO_SUB_CONST, n1011),
#define R(i) CO_OD_SUB((i), (uint8_t)CO_UNSIGNED32, CO_SUB_RW, 4U, (uint16_t)(F(restore) + 4U * ((i) - 1U)), 0U)
    R(1), R(2), R(3), R(4), R(5), R(6),
#undef R
};
static const co_od_sub_t s1014[] = {RAM(0, CO_UNSIGNED32, CO_SUB_RW | CO_SUB_NODEID, emcy_cob)};
static const co_od_sub_t s1015[] = {RAM(0, CO_UNSIGNED16, CO_SUB_RW, emcy_inhibit)};
static const co_od_sub_t s1016[] = {
    ROM(0, CO_UNSIGNED8, CO_SUB_RO | CO_SUB_CONST, n1016),
    CO_OD_RUN(1, 4U, (uint8_t)CO_UNSIGNED32, CO_SUB_RW, 4U, F(hb_cons), 0U),
};
static const co_od_sub_t s1017[] = {RAM(0, CO_UNSIGNED16, CO_SUB_RW, hb_prod)};
static const co_od_sub_t s1018[] = {
    ROM(0, CO_UNSIGNED8, CO_SUB_RO | CO_SUB_CONST, n1018),
#define I(i) CO_OD_SUB((i), (uint8_t)CO_UNSIGNED32, CO_SUB_RO | CO_SUB_ROM, 4U, (uint16_t)(RF(x1018) + 4U * ((i) - 1U)), 0U)
    I(1), I(2), I(3), I(4),
#undef I
};
static const co_od_sub_t s2000[] = {RAM(0, CO_UNSIGNED8, RW_MAP, u8)};
static const co_od_sub_t s2001[] = {RAM(0, CO_INTEGER8, RW_MAP, i8)};
static const co_od_sub_t s2002[] = {RAM(0, CO_UNSIGNED16, RW_MAP, u16)};
static const co_od_sub_t s2003[] = {RAM(0, CO_INTEGER16, RW_MAP, i16)};
static const co_od_sub_t s2004[] = {RAM(0, CO_UNSIGNED32, RW_MAP, u32)};
static const co_od_sub_t s2005[] = {RAM(0, CO_INTEGER32, RW_MAP, i32)};
static const co_od_sub_t s2006[] = {RAM(0, CO_UNSIGNED64, RW_MAP, u64)};
static const co_od_sub_t s2007[] = {RAM(0, CO_INTEGER64, RW_MAP, i64)};
static const co_od_sub_t s2008[] = {RAM(0, CO_REAL32, RW_MAP, r32)};
static const co_od_sub_t s2009[] = {RAM(0, CO_REAL64, RW_MAP, r64)};
static const co_od_sub_t s200A[] = {RAM(0, CO_BOOLEAN, RW_MAP, b)};
static const co_od_sub_t s200B[] = {RAM(0, CO_UNSIGNED24, RW_MAP, u24)};
static const co_od_sub_t s200C[] = {RAM(0, CO_INTEGER24, RW_MAP, i24)};
static const co_od_sub_t s200D[] = {RAM(0, CO_UNSIGNED40, RW_MAP, u40)};
static const co_od_sub_t s200E[] = {RAM(0, CO_INTEGER48, RW_MAP, i48)};
static const co_od_sub_t s200F[] = {RAM(0, CO_UNSIGNED56, RW_MAP, u56)};
static const co_od_sub_t s2010[] = {RAM(0, CO_TIME_OF_DAY, CO_SUB_RW, tod)};
static const co_od_sub_t s2011[] = {RAM(0, CO_TIME_DIFFERENCE, CO_SUB_RW, tdiff)};
static const co_od_sub_t s2012[] = {RAM(0, CO_VISIBLE_STRING, CO_SUB_RW, vstr)};
static const co_od_sub_t s2013[] = {RAM(0, CO_OCTET_STRING, CO_SUB_RW, ostr)};
static const co_od_sub_t s2014[] = {RAM(0, CO_UNICODE_STRING, CO_SUB_RW, ustr)};
static const co_od_sub_t s2020[] = {
    CO_OD_SUB(0, (uint8_t)CO_UNSIGNED16, CO_SUB_RW | CO_SUB_LIMIT, Z(lim_u16), F(lim_u16), 0U)};
static const co_od_sub_t s2021[] = {
    CO_OD_SUB(0, (uint8_t)CO_INTEGER16, CO_SUB_RW | CO_SUB_LIMIT, Z(lim_i16), F(lim_i16), 1U)};
static const co_od_sub_t s2022[] = {RAM(0, CO_UNSIGNED32, CO_SUB_WO, wo_u32)};
static const co_od_sub_t s2023[] = {ROM(0, CO_UNSIGNED32, CO_SUB_RO | CO_SUB_CONST, x2023)};
static const co_od_sub_t s2100[] = {RAM(0, CO_UNSIGNED32, CO_SUB_RW, hooked)};
static const co_od_sub_t s2200[] = {
    CO_OD_SUB(0, (uint8_t)CO_DOMAIN, CO_SUB_RW | CO_SUB_HOOKIO, 0U, 0U, 0U)};
static const co_od_sub_t s2201[] = {
    CO_OD_SUB(0, (uint8_t)CO_UNSIGNED32, CO_SUB_RW | CO_SUB_HOOKIO, 4U, 0U, 0U)};
static const co_od_sub_t s2300[] = {
    RAM(0, CO_UNSIGNED32, CO_SUB_RW, rec0),
    RAM(1, CO_UNSIGNED16, CO_SUB_RW, rec1),
};
static const co_od_sub_t s6040[] = {RAM(0, CO_UNSIGNED16, RW_MAP, cw)};
static const co_od_sub_t s6060[] = {RAM(0, CO_INTEGER8, RW_MAP, mode)};
static const co_od_sub_t s607A[] = {RAM(0, CO_INTEGER32, RW_MAP, target_pos)};
static const co_od_sub_t s60FF[] = {RAM(0, CO_INTEGER32, RW_MAP, target_vel)};
static const co_od_sub_t s6099[] = {
    ROM(0, CO_UNSIGNED8, CO_SUB_RO | CO_SUB_CONST, n6099),
    CO_OD_RUN(1, 2U, (uint8_t)CO_UNSIGNED32, CO_SUB_RW | CO_SUB_LIMIT, 4U, F(homing_speed), 2U),
};

#define E(idx, subs, code) \
    CO_OD_ENTRY((idx), (uint8_t)(sizeof(subs) / sizeof((subs)[0])), 0U, (code), (subs))
#define EH(idx, subs, code, slot) \
    CO_OD_ENTRY((idx), (uint8_t)(sizeof(subs) / sizeof((subs)[0])), (uint8_t)((slot) + 1U), \
                (code), (subs))

static const co_od_entry_t od[] = {
    E(0x1000, s1000, CO_OBJ_VAR),    E(0x1001, s1001, CO_OBJ_VAR),
    E(0x1002, s1002, CO_OBJ_VAR),    E(0x1003, s1003, CO_OBJ_ARRAY),
    E(0x1005, s1005, CO_OBJ_VAR),    E(0x1006, s1006, CO_OBJ_VAR),
    E(0x1007, s1007, CO_OBJ_VAR),    E(0x1008, s1008, CO_OBJ_VAR),
    E(0x1009, s1009, CO_OBJ_VAR),    E(0x100A, s100A, CO_OBJ_VAR),
    E(0x100B, s100B, CO_OBJ_VAR),    E(0x100C, s100C, CO_OBJ_VAR),
    E(0x100D, s100D, CO_OBJ_VAR),    E(0x1010, s1010, CO_OBJ_ARRAY),
    E(0x1011, s1011, CO_OBJ_ARRAY),  E(0x1012, s1012, CO_OBJ_VAR),
    E(0x1014, s1014, CO_OBJ_VAR),
    E(0x1015, s1015, CO_OBJ_VAR),    E(0x1016, s1016, CO_OBJ_ARRAY),
    E(0x1017, s1017, CO_OBJ_VAR),    E(0x1018, s1018, CO_OBJ_RECORD),
    E(0x1019, s1019, CO_OBJ_VAR),    E(0x1029, s1029, CO_OBJ_ARRAY),
    E(0x2000, s2000, CO_OBJ_VAR),    E(0x2001, s2001, CO_OBJ_VAR),
    E(0x2002, s2002, CO_OBJ_VAR),    E(0x2003, s2003, CO_OBJ_VAR),
    E(0x2004, s2004, CO_OBJ_VAR),    E(0x2005, s2005, CO_OBJ_VAR),
    E(0x2006, s2006, CO_OBJ_VAR),    E(0x2007, s2007, CO_OBJ_VAR),
    E(0x2008, s2008, CO_OBJ_VAR),    E(0x2009, s2009, CO_OBJ_VAR),
    E(0x200A, s200A, CO_OBJ_VAR),    E(0x200B, s200B, CO_OBJ_VAR),
    E(0x200C, s200C, CO_OBJ_VAR),    E(0x200D, s200D, CO_OBJ_VAR),
    E(0x200E, s200E, CO_OBJ_VAR),    E(0x200F, s200F, CO_OBJ_VAR),
    E(0x2010, s2010, CO_OBJ_VAR),    E(0x2011, s2011, CO_OBJ_VAR),
    E(0x2012, s2012, CO_OBJ_VAR),    E(0x2013, s2013, CO_OBJ_VAR),
    E(0x2014, s2014, CO_OBJ_VAR),    E(0x2020, s2020, CO_OBJ_VAR),
    E(0x2021, s2021, CO_OBJ_VAR),    E(0x2022, s2022, CO_OBJ_VAR),
    E(0x2023, s2023, CO_OBJ_VAR),    EH(0x2100, s2100, CO_OBJ_VAR, TD_HOOK_2100),
    EH(0x2200, s2200, CO_OBJ_DOMAIN, TD_HOOK_DOMAIN),
    EH(0x2201, s2201, CO_OBJ_VAR, TD_HOOK_2201),
    E(0x2300, s2300, CO_OBJ_RECORD), E(0x6040, s6040, CO_OBJ_VAR),
    E(0x6060, s6060, CO_OBJ_VAR),    E(0x607A, s607A, CO_OBJ_VAR),
    E(0x6099, s6099, CO_OBJ_ARRAY),  E(0x60FF, s60FF, CO_OBJ_VAR),
};

typedef char td_defaults_runs[((sizeof(td_ram_t) <= CO_OD_DEF_SIZE) &&
                               (offsetof(td_defaults_t, node_id) == sizeof(td_ram_t)) &&
                               (offsetof(td_defaults_t, emcy_cob) == sizeof(td_ram_t) + 4U))
                                  ? 1
                                  : -1];
/* (a run never crosses comm_end or app_end: the image is three) */
static const co_od_default_t default_at[] = {
    {0U, F(u8)},
    {F(u8), (uint16_t)(F(errreg) - F(u8))},
    {F(errreg), (uint16_t)(sizeof(td_ram_t) - F(errreg))},
    {F(node_id), (uint16_t)(4U | CO_OD_DEF_NODEID)},
    {F(emcy_cob), (uint16_t)(4U | CO_OD_DEF_NODEID | CO_OD_DEF_COB)},
};

const co_dev_t td_dev = {
    .name = "test-device",
    .od = od,
    .od_count = (uint16_t)(sizeof od / sizeof od[0]),
    .ram_size = (uint16_t)sizeof(td_ram_t),
    .comm_end = F(u8),
    .app_end = F(errreg),
    .defaults = &defaults,
    .rom = (const uint8_t *)&rom,
    .limits = limits,
    .n_hooks = TD_N_HOOKS,
    .boot_emcy_data = NULL,
    .stage = F(stage),
    .stage_size = (uint16_t)sizeof(((td_ram_t *)0)->stage),
    .default_at = default_at,
    .n_defaults = (uint16_t)(sizeof default_at / sizeof default_at[0]),
};

void td_start_cb(td_node_t *n, tb_bus_t *bus, uint8_t idx, uint8_t id, const co_dev_t *dev,
                 const co_node_callbacks_t *cb)
{
    co_node_config_t cfg;

    memset(n, 0, sizeof *n);
    memset(&cfg, 0, sizeof cfg);
    cfg.dev = (dev != NULL) ? dev : &td_dev;
    cfg.hal = tb_hal(bus, idx);
    cfg.node_id = id;
    cfg.ram = &n->ram;
    cfg.hooks = n->hooks;
    if (cb != NULL) {
        n->cb = *cb;
        cfg.cb = &n->cb;
    }
    tb_attach(bus, idx, &n->node);
    assert_int_equal(co_node_init(&n->node, &cfg, bus->now), CO_RESULT_OK);
}

void td_start(td_node_t *n, tb_bus_t *bus, uint8_t idx, uint8_t id, const co_dev_t *dev)
{
    td_start_cb(n, bus, idx, id, dev, NULL);
}
