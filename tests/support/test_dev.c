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

/* The rows of every object, one object after the other (co_dev_t.rows):
 * object 0xXXXX has NsXXXX of them from row TsXXXX on. */
enum td_rows {
    Ts1000 = 0, Ns1000 = 1,
    Ts1001 = Ts1000 + Ns1000, Ns1001 = 1,
    Ts1002 = Ts1001 + Ns1001, Ns1002 = 1,
    Ts1003 = Ts1002 + Ns1002, Ns1003 = 2,
    Ts1005 = Ts1003 + Ns1003, Ns1005 = 1,
    Ts1006 = Ts1005 + Ns1005, Ns1006 = 1,
    Ts1007 = Ts1006 + Ns1006, Ns1007 = 1,
    Ts1012 = Ts1007 + Ns1007, Ns1012 = 1,
    Ts1019 = Ts1012 + Ns1012, Ns1019 = 1,
    Ts1029 = Ts1019 + Ns1019, Ns1029 = 4,
    Ts1008 = Ts1029 + Ns1029, Ns1008 = 1,
    Ts1009 = Ts1008 + Ns1008, Ns1009 = 1,
    Ts100A = Ts1009 + Ns1009, Ns100A = 1,
    Ts100B = Ts100A + Ns100A, Ns100B = 1,
    Ts100C = Ts100B + Ns100B, Ns100C = 1,
    Ts100D = Ts100C + Ns100C, Ns100D = 1,
    Ts1010 = Ts100D + Ns100D, Ns1010 = 4,
    Ts1011 = Ts1010 + Ns1010, Ns1011 = 7,
    Ts1014 = Ts1011 + Ns1011, Ns1014 = 1,
    Ts1015 = Ts1014 + Ns1014, Ns1015 = 1,
    Ts1016 = Ts1015 + Ns1015, Ns1016 = 2,
    Ts1017 = Ts1016 + Ns1016, Ns1017 = 1,
    Ts1018 = Ts1017 + Ns1017, Ns1018 = 5,
    Ts2000 = Ts1018 + Ns1018, Ns2000 = 1,
    Ts2001 = Ts2000 + Ns2000, Ns2001 = 1,
    Ts2002 = Ts2001 + Ns2001, Ns2002 = 1,
    Ts2003 = Ts2002 + Ns2002, Ns2003 = 1,
    Ts2004 = Ts2003 + Ns2003, Ns2004 = 1,
    Ts2005 = Ts2004 + Ns2004, Ns2005 = 1,
    Ts2006 = Ts2005 + Ns2005, Ns2006 = 1,
    Ts2007 = Ts2006 + Ns2006, Ns2007 = 1,
    Ts2008 = Ts2007 + Ns2007, Ns2008 = 1,
    Ts2009 = Ts2008 + Ns2008, Ns2009 = 1,
    Ts200A = Ts2009 + Ns2009, Ns200A = 1,
    Ts200B = Ts200A + Ns200A, Ns200B = 1,
    Ts200C = Ts200B + Ns200B, Ns200C = 1,
    Ts200D = Ts200C + Ns200C, Ns200D = 1,
    Ts200E = Ts200D + Ns200D, Ns200E = 1,
    Ts200F = Ts200E + Ns200E, Ns200F = 1,
    Ts2010 = Ts200F + Ns200F, Ns2010 = 1,
    Ts2011 = Ts2010 + Ns2010, Ns2011 = 1,
    Ts2012 = Ts2011 + Ns2011, Ns2012 = 1,
    Ts2013 = Ts2012 + Ns2012, Ns2013 = 1,
    Ts2014 = Ts2013 + Ns2013, Ns2014 = 1,
    Ts2020 = Ts2014 + Ns2014, Ns2020 = 1,
    Ts2021 = Ts2020 + Ns2020, Ns2021 = 1,
    Ts2022 = Ts2021 + Ns2021, Ns2022 = 1,
    Ts2023 = Ts2022 + Ns2022, Ns2023 = 1,
    Ts2100 = Ts2023 + Ns2023, Ns2100 = 1,
    Ts2200 = Ts2100 + Ns2100, Ns2200 = 1,
    Ts2201 = Ts2200 + Ns2200, Ns2201 = 1,
    Ts2300 = Ts2201 + Ns2201, Ns2300 = 2,
    Ts6040 = Ts2300 + Ns2300, Ns6040 = 1,
    Ts6060 = Ts6040 + Ns6040, Ns6060 = 1,
    Ts607A = Ts6060 + Ns6060, Ns607A = 1,
    Ts60FF = Ts607A + Ns607A, Ns60FF = 1,
    Ts6099 = Ts60FF + Ns60FF, Ns6099 = 2,
    TD_N_ROWS = Ts6099 + Ns6099
};

static const co_od_sub_t rows[] = {
    /* 0x1000 */ ROM(0, CO_UNSIGNED32, CO_SUB_RO, x1000),
    /* 0x1001 */ RAM(0, CO_UNSIGNED8, CO_SUB_RO | CO_SUB_MAP_T, errreg),
    /* 0x1002 */ RAM(0, CO_UNSIGNED32, CO_SUB_RO, mfr_status),
    /* 0x1003 */
    RAM(0, CO_UNSIGNED8, CO_SUB_RW, hist_n),
    /* (one row for sub 1..8: a run, CO_OD_RUN) */
    CO_OD_RUN(1, 8U, (uint8_t)CO_UNSIGNED32, CO_SUB_RO, 4U, F(hist), 0U),
    /* 0x1005 */ RAM(0, CO_UNSIGNED32, CO_SUB_RW | CO_SUB_COB16, sync_cob),
    /* 0x1006 */ RAM(0, CO_UNSIGNED32, CO_SUB_RW, sync_period),
    /* 0x1007 */ RAM(0, CO_UNSIGNED32, CO_SUB_RW, sync_window),
    /* 0x1012 */ RAM(0, CO_UNSIGNED32, CO_SUB_RW | CO_SUB_COB16, time_cob),
    /* 0x1019 */ RAM(0, CO_UNSIGNED8, CO_SUB_RW, sync_overflow),
    /* 0x1029 */
    ROM(0, CO_UNSIGNED8, CO_SUB_RO | CO_SUB_CONST, n1029),
#define B(i) CO_OD_SUB((i), (uint8_t)CO_UNSIGNED8, CO_SUB_RW, 1U, (uint16_t)(F(err_beh) + (i) - 1U), 0U)
    B(1), B(2), B(3),
#undef B
    /* 0x1008 */ ROM(0, CO_VISIBLE_STRING, CO_SUB_RO | CO_SUB_CONST, x1008),
    /* 0x1009 */ ROM(0, CO_VISIBLE_STRING, CO_SUB_RO | CO_SUB_CONST, x1009),
    /* 0x100A */ ROM(0, CO_VISIBLE_STRING, CO_SUB_RO | CO_SUB_CONST, x100A),
    /* 0x100B */ RAM(0, CO_UNSIGNED32, CO_SUB_RO | CO_SUB_NODEID, node_id),
    /* 0x100C */ RAM(0, CO_UNSIGNED16, CO_SUB_RW, guard_time),
    /* 0x100D */ RAM(0, CO_UNSIGNED8, CO_SUB_RW, life_factor),
    /* 0x1010 */
    ROM(0, CO_UNSIGNED8, CO_SUB_RO | CO_SUB_CONST, n1010),
    CO_OD_SUB(1, (uint8_t)CO_UNSIGNED32, CO_SUB_RW, 4U, F(store), 0U),
    CO_OD_SUB(2, (uint8_t)CO_UNSIGNED32, CO_SUB_RW, 4U, (uint16_t)(F(store) + 4U), 0U),
    CO_OD_SUB(3, (uint8_t)CO_UNSIGNED32, CO_SUB_RW, 4U, (uint16_t)(F(store) + 8U), 0U),
    /* 0x1011 */
    ROM(0, CO_UNSIGNED8, CO_SUB_RO | CO_SUB_CONST, n1011),
#define R(i) CO_OD_SUB((i), (uint8_t)CO_UNSIGNED32, CO_SUB_RW, 4U, (uint16_t)(F(restore) + 4U * ((i) - 1U)), 0U)
    R(1), R(2), R(3), R(4), R(5), R(6),
#undef R
    /* 0x1014 */ RAM(0, CO_UNSIGNED32, CO_SUB_RW | CO_SUB_NODEID | CO_SUB_COB16, emcy_cob),
    /* 0x1015 */ RAM(0, CO_UNSIGNED16, CO_SUB_RW, emcy_inhibit),
    /* 0x1016 */
    ROM(0, CO_UNSIGNED8, CO_SUB_RO | CO_SUB_CONST, n1016),
    CO_OD_RUN(1, 4U, (uint8_t)CO_UNSIGNED32, CO_SUB_RW, 4U, F(hb_cons), 0U),
    /* 0x1017 */ RAM(0, CO_UNSIGNED16, CO_SUB_RW, hb_prod),
    /* 0x1018 */
    ROM(0, CO_UNSIGNED8, CO_SUB_RO | CO_SUB_CONST, n1018),
#define I(i) CO_OD_SUB((i), (uint8_t)CO_UNSIGNED32, CO_SUB_RO | CO_SUB_ROM, 4U, (uint16_t)(RF(x1018) + 4U * ((i) - 1U)), 0U)
    I(1), I(2), I(3), I(4),
#undef I
    /* 0x2000 */ RAM(0, CO_UNSIGNED8, RW_MAP, u8),
    /* 0x2001 */ RAM(0, CO_INTEGER8, RW_MAP, i8),
    /* 0x2002 */ RAM(0, CO_UNSIGNED16, RW_MAP, u16),
    /* 0x2003 */ RAM(0, CO_INTEGER16, RW_MAP, i16),
    /* 0x2004 */ RAM(0, CO_UNSIGNED32, RW_MAP, u32),
    /* 0x2005 */ RAM(0, CO_INTEGER32, RW_MAP, i32),
    /* 0x2006 */ RAM(0, CO_UNSIGNED64, RW_MAP, u64),
    /* 0x2007 */ RAM(0, CO_INTEGER64, RW_MAP, i64),
    /* 0x2008 */ RAM(0, CO_REAL32, RW_MAP, r32),
    /* 0x2009 */ RAM(0, CO_REAL64, RW_MAP, r64),
    /* 0x200A */ RAM(0, CO_BOOLEAN, RW_MAP, b),
    /* 0x200B */ RAM(0, CO_UNSIGNED24, RW_MAP, u24),
    /* 0x200C */ RAM(0, CO_INTEGER24, RW_MAP, i24),
    /* 0x200D */ RAM(0, CO_UNSIGNED40, RW_MAP, u40),
    /* 0x200E */ RAM(0, CO_INTEGER48, RW_MAP, i48),
    /* 0x200F */ RAM(0, CO_UNSIGNED56, RW_MAP, u56),
    /* 0x2010 */ RAM(0, CO_TIME_OF_DAY, CO_SUB_RW, tod),
    /* 0x2011 */ RAM(0, CO_TIME_DIFFERENCE, CO_SUB_RW, tdiff),
    /* 0x2012 */ RAM(0, CO_VISIBLE_STRING, CO_SUB_RW, vstr),
    /* 0x2013 */ RAM(0, CO_OCTET_STRING, CO_SUB_RW, ostr),
    /* 0x2014 */ RAM(0, CO_UNICODE_STRING, CO_SUB_RW, ustr),
    /* 0x2020 */ CO_OD_SUB(0, (uint8_t)CO_UNSIGNED16, CO_SUB_RW | CO_SUB_LIMIT, Z(lim_u16), F(lim_u16), 0U),
    /* 0x2021 */ CO_OD_SUB(0, (uint8_t)CO_INTEGER16, CO_SUB_RW | CO_SUB_LIMIT, Z(lim_i16), F(lim_i16), 1U),
    /* 0x2022 */ RAM(0, CO_UNSIGNED32, CO_SUB_WO, wo_u32),
    /* 0x2023 */ ROM(0, CO_UNSIGNED32, CO_SUB_RO | CO_SUB_CONST, x2023),
    /* 0x2100 (hooked: its RAM offsets count from its base, its hook slot) */
    CO_OD_SUB(0, (uint8_t)CO_UNSIGNED32, CO_SUB_RW, Z(hooked), (uint16_t)(F(hooked) - TD_HOOK_2100), 0U),
    /* 0x2200 */ CO_OD_SUB(0, (uint8_t)CO_DOMAIN, CO_SUB_RW | CO_SUB_HOOKIO, 0U, 0U, 0U),
    /* 0x2201 */ CO_OD_SUB(0, (uint8_t)CO_UNSIGNED32, CO_SUB_RW | CO_SUB_HOOKIO, 4U, 0U, 0U),
    /* 0x2300 */
    RAM(0, CO_UNSIGNED32, CO_SUB_RW, rec0),
    RAM(1, CO_UNSIGNED16, CO_SUB_RW, rec1),
    /* 0x6040 */ RAM(0, CO_UNSIGNED16, RW_MAP, cw),
    /* 0x6060 */ RAM(0, CO_INTEGER8, RW_MAP, mode),
    /* 0x607A */ RAM(0, CO_INTEGER32, RW_MAP, target_pos),
    /* 0x60FF */ RAM(0, CO_INTEGER32, RW_MAP, target_vel),
    /* 0x6099 */
    ROM(0, CO_UNSIGNED8, CO_SUB_RO | CO_SUB_CONST, n6099),
    CO_OD_RUN(1, 2U, (uint8_t)CO_UNSIGNED32, CO_SUB_RW | CO_SUB_LIMIT, 4U, F(homing_speed), 2U),
};
typedef char td_rows_n[(sizeof rows / sizeof rows[0] == TD_N_ROWS) ? 1 : -1];

#define E(idx, subs, code) CO_OD_ENTRY((idx), (uint8_t)N##subs, 0U, (code), (uint16_t)T##subs)
#define EH(idx, subs, code, slot) \
    CO_OD_ENTRY((idx), (uint8_t)N##subs, (uint8_t)((slot) + 1U), (code), (uint16_t)T##subs)

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

/* Defaults (co_od.h, CO_OD_DEF_RUN): the values that are not zero and the
 * $NODEID ones (0x100B, the EMCY COB-ID: its COB-ID base), in the order of
 * their places, as wire bytes. D(at, end, n, w): a run's two bytes, of n
 * values of 1 << w bytes at @p at, the run before it ending at @p end. */
#define D(at, end, n, w) (uint8_t)((at) - (end)), CO_OD_DEF_RUN((n), (w))
#define DN(at, end, marks) (uint8_t)((at) - (end)), (uint8_t)(CO_OD_DEF_RUN(1U, 2U) | (marks))
#define DN16(at, end, marks) (uint8_t)((at) - (end)), (uint8_t)(CO_OD_DEF_RUN(1U, 1U) | (marks))
#define END(field) (F(field) + Z(field))
#define LE16(v) (uint8_t)(v), (uint8_t)((v) >> 8)
#define LE32(v) (uint8_t)(v), (uint8_t)((v) >> 8), (uint8_t)((v) >> 16), (uint8_t)((v) >> 24)
static const uint8_t defaults[] = {
    /* communication parameters */
    /* (the COB-IDs in their 16-bit forms: co_od.h CO_SUB_COB16) */
    D(F(sync_cob), 0U, 1U, 1U), LE16(0x80U),
    DN16(F(emcy_cob), END(sync_cob), CO_OD_DEF_NODEID | CO_OD_DEF_COB), LE16(0x80U),
    D(F(err_beh), END(emcy_cob), 3U, 0U), 0U, 1U, 1U,
    D(F(time_cob), END(err_beh), 1U, 1U), LE16(0x8100U), /* 0x80000100 */
    DN(F(node_id), END(time_cob), CO_OD_DEF_NODEID), LE32(0UL),
    /* application values */
    D(F(u16), END(node_id), 1U, 1U), LE16(0x1234U),
    D(F(u32), END(u16), 1U, 2U), LE32(0xDEADBEEFUL),
    D(F(vstr), END(u32), 5U, 0U), 'h', 'e', 'l', 'l', 'o',
    D(F(lim_u16), F(vstr) + 5U, 1U, 1U), LE16(100U),
    D(F(rec0), END(lim_u16), 1U, 2U), LE32(0x11223344UL),
    D(F(rec1), END(rec0), 1U, 1U), LE16(7U),
};
/* (each run after the one before it, less than 256 bytes after it) */
typedef char td_default_gaps[((F(emcy_cob) >= END(sync_cob)) && (F(err_beh) >= END(emcy_cob)) &&
                              (F(time_cob) >= END(err_beh)) && (F(node_id) >= END(time_cob)) &&
                              (F(u16) >= END(node_id)) && (F(u16) - END(node_id) <= 255U) &&
                              (F(vstr) - END(u32) <= 255U) && (F(rec0) > F(lim_u16)) &&
                              (F(lim_u16) - (F(vstr) + 5U) <= 255U) &&
                              (F(rec0) - END(lim_u16) <= 255U) && (F(rec1) == END(rec0)))
                                 ? 1
                                 : -1];

/* the core's objects at their places (co_node.h) */
typedef char td_core_at[((F(sync_cob) == CO_RAM_1005) && (F(sync_window) == CO_RAM_1007) &&
                         (F(emcy_cob) == CO_RAM_1014) && (F(emcy_inhibit) == CO_RAM_1015) &&
                         (F(hb_prod) == CO_RAM_1017) && (F(sync_overflow) == CO_RAM_1019) &&
                         (F(hb_cons) == CO_RAM_1016) &&
                         (F(errreg) == F(errreg) + CO_RAM_END_1001) &&
                         (F(hist_n) == F(errreg) + CO_RAM_END_1003) &&
                         (F(hist) == F(errreg) + CO_RAM_END_1003_1))
                            ? 1
                            : -1];

const co_dev_t td_dev = {
    .od = od,
    .rows = rows,
    .od_count = (uint16_t)(sizeof od / sizeof od[0]),
    .ram_size = (uint16_t)offsetof(td_ram_t, hooks),
    .hooks_at = (uint16_t)offsetof(td_ram_t, hooks),
    .comm_end = F(u8),
    .app_end = F(errreg),
    .defaults = defaults,
    .rom = (const uint8_t *)&rom,
    .limits = limits,
    .n_hooks = TD_N_HOOKS,
    .boot_emcy_data = NULL,
    .stage = F(stage),
    .stage_size = (uint16_t)sizeof(((td_ram_t *)0)->stage),
    .n_defaults = 11U,
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
