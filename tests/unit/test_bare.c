/*
 * The core built with the minimal slave's options and also without block SDO,
 * node guarding, TPDO remote requests and bit-granular PDO mapping
 * and TPDO change detection (CO_SDO_BLOCK=0, CO_NODE_GUARDING=0,
 * CO_PDO_RTR=0, CO_PDO_BITWISE=0, CO_TPDO_CHANGE=0) on the lean-test device:
 * block requests answer 0x05040001 like an unknown command, a guarding RTR
 * gets no answer, a TPDO's RTR gets none and types 252/253 answer 0x06090030
 * (and the generated node's PDO receive table has room for the RPDOs only), a
 * mapping entry of a length that is not whole bytes answers 0x06040041, an
 * event-driven or acyclic TPDO does not go out when its data change (only
 * once on entering Operational, on a request and at its event timer), the
 * expedited and segmented SDO, the heartbeat, the synchronous TPDO and
 * mappings of some of an object's bytes keep working, a full TX path sends
 * what waits in CAN priority order, and a device with 0x100C/0x100D is
 * refused.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "co/co_canstate.h"
#include "lean_test.h"
#include "test_bus.h"
#include "test_dev.h"

#if CO_SDO_BLOCK || CO_NODE_GUARDING || CO_PDO_RTR || CO_PDO_BITWISE || CO_TPDO_CHANGE
#error "test_bare: a core without block SDO, guarding, TPDO RTRs, bit mapping, change detection"
#endif

static tb_bus_t bus;
static lean_test_node_t lean;
#define BUS (&bus)

static int setup(void **state)
{
    co_node_config_t cfg;

    (void)state;
    memset(&lean, 0, sizeof lean);
    tb_init(&bus);
    lean_test_config(&lean, &cfg);
    cfg.hal = tb_hal(&bus, 0);
    cfg.node_id = 1;
    assert_int_equal(co_node_init(&lean.node, &cfg, bus.now), CO_RESULT_OK);
    tb_attach(&bus, 0, &lean.node);
    tb_expect(BUS, "701 00");
    return 0;
}

static void block_sdo_left_out(void **state)
{
    (void)state;
    /* block upload and block download initiate: unknown command */
    tb_xfer(BUS, "601 A4 08 10 00 7F 00 00 00", "581 80 08 10 00 01 00 04 05");
    tb_xfer(BUS, "601 C6 00 22 00 04 00 00 00", "581 80 00 22 00 01 00 04 05");
    /* expedited and segmented stay */
    tb_xfer(BUS, "601 40 08 10 00 00 00 00 00", "581 47 08 10 00 6D 69 6E 00");
    tb_xfer(BUS, "601 21 00 22 00 04 00 00 00", "581 60 00 22 00 00 00 00 00");
    tb_xfer(BUS, "601 07 44 33 22 11 00 00 00", "581 20 00 00 00 00 00 00 00");
}

static void guarding_left_out(void **state)
{
    (void)state;
    tb_send(BUS, "701 R1");
    tb_expect_none(BUS);
    /* the heartbeat producer stays */
    tb_xfer(BUS, "601 2B 17 10 00 64 00 00 00", "581 60 17 10 00 00 00 00 00");
    tb_advance(BUS, 100000);
    tb_expect(BUS, "701 7F");
}

/* The TX path of a core without LSS and guarding (the heartbeat is the last
 * frame the node makes itself): what waits goes in CAN priority order. */
static void full_tx_path(void **state)
{
    (void)state;
    tb_xfer(BUS, "601 2B 17 10 00 0A 00 00 00", "581 60 17 10 00 00 00 00 00");
    BUS->refuse = 1000U;
    tb_send(BUS, "000 81 01");                            /* reset node: the boot-up */
    tb_send(BUS, "601 40 08 10 00 00 00 00 00");          /* an SDO answer */
    tb_advance(BUS, 30000U);                              /* no heartbeat (0x1017 reset) */
    assert_int_equal(co_od_write(&lean.node, 0x1017U, 0U, "\x0A\x00", 2U, true), CO_OK);
    tb_advance(BUS, 10000U);                              /* a heartbeat due */
    co_node_can_overrun(&lean.node, true);                /* an EMCY */
    tb_expect_none(BUS);
    BUS->refuse = 0U;
    co_node_tx_ready(&lean.node, BUS->now);
    tb_expect(BUS, "081 10 81 11 00 00 00 00 00");
    tb_expect(BUS, "581 47 08 10 00 6D 69 6E 00");
    tb_expect(BUS, "701 00");
    tb_expect(BUS, "701 7F");
    tb_expect_none(BUS);
}

static void tpdo_rtr_left_out(void **state)
{
    uint8_t v[4] = {0x44, 0x33, 0x22, 0x11};

    (void)state;
    assert_int_equal(co_od_write(&lean.node, 0x2200, 0, v, 4, true), CO_OK);
    tb_send(BUS, "000 01 01");
    /* TPDO1 (type 1, COB-ID 0x181, bit 30 clear): no answer to an RTR */
    tb_send(BUS, "181 R4");
    tb_expect_none(BUS);
    /* it still goes out at SYNC */
    tb_send(BUS, "080");
    tb_expect(BUS, "181 44 33 22 11");
    /* the RTR-only types are refused like 241..251 */
    tb_xfer(BUS, "601 2F 00 18 02 FC 00 00 00", "581 80 00 18 02 30 00 09 06");
    tb_xfer(BUS, "601 2F 00 18 02 FD 00 00 00", "581 80 00 18 02 30 00 09 06");
    tb_xfer(BUS, "601 40 00 18 02 00 00 00 00", "581 4F 00 18 02 01 00 00 00");
    tb_xfer(BUS, "601 2F 00 18 02 F1 00 00 00", "581 80 00 18 02 30 00 09 06");
    tb_expect_none(BUS);
}

static void pdo_bitwise_left_out(void **state)
{
    uint8_t v[4] = {0x44, 0x33, 0x22, 0x11};

    (void)state;
    assert_int_equal(co_od_write(&lean.node, 0x2200, 0, v, 4, true), CO_OK);
    /* TPDO1 invalid, its mapping disabled */
    tb_xfer(BUS, "601 23 00 18 01 81 01 00 80", "581 60 00 18 01 00 00 00 00");
    tb_xfer(BUS, "601 2F 00 1A 00 00 00 00 00", "581 60 00 1A 00 00 00 00 00");
    /* 12 bits of 0x2200: refused as by a device that maps whole bytes, the
     * entry keeps its value */
    tb_xfer(BUS, "601 23 00 1A 01 0C 00 00 22", "581 80 00 1A 01 41 00 04 06");
    tb_xfer(BUS, "601 40 00 1A 01 00 00 00 00", "581 43 00 1A 01 20 00 00 22");
    /* 16 of its 32 bits: the low two bytes */
    tb_xfer(BUS, "601 23 00 1A 01 10 00 00 22", "581 60 00 1A 01 00 00 00 00");
    tb_xfer(BUS, "601 2F 00 1A 00 01 00 00 00", "581 60 00 1A 00 00 00 00 00");
    tb_xfer(BUS, "601 23 00 18 01 81 01 00 00", "581 60 00 18 01 00 00 00 00");
    /* RPDO1 the same way: 16 bits of 0x2100 */
    tb_xfer(BUS, "601 23 00 14 01 01 02 00 80", "581 60 00 14 01 00 00 00 00");
    tb_xfer(BUS, "601 2F 00 16 00 00 00 00 00", "581 60 00 16 00 00 00 00 00");
    tb_xfer(BUS, "601 23 00 16 01 0C 00 00 21", "581 80 00 16 01 41 00 04 06");
    tb_xfer(BUS, "601 23 00 16 01 10 00 00 21", "581 60 00 16 01 00 00 00 00");
    tb_xfer(BUS, "601 2F 00 16 00 01 00 00 00", "581 60 00 16 00 00 00 00 00");
    tb_xfer(BUS, "601 23 00 14 01 01 02 00 00", "581 60 00 14 01 00 00 00 00");
    tb_send(BUS, "000 01 01");
    tb_send(BUS, "080");
    tb_expect(BUS, "181 44 33");
    tb_xfer(BUS, "601 23 00 21 00 11 22 33 44", "581 60 00 21 00 00 00 00 00");
    tb_send(BUS, "201 AA BB");
    tb_expect_none(BUS);
    /* the low bytes written, extended to the value's size */
    tb_xfer(BUS, "601 40 00 21 00 00 00 00 00", "581 43 00 21 00 AA BB 00 00");
}

/* TPDO1 event-driven (254) with an event timer of 100 ms: sent once on
 * entering Operational, then on a request and at the event timer, which
 * every transmission restarts; a change of its data sends nothing. */
static void tpdo_event_no_change(void **state)
{
    uint8_t v[4] = {0x44, 0x33, 0x22, 0x11};

    (void)state;
    assert_int_equal(co_od_write(&lean.node, 0x2200, 0, v, 4, true), CO_OK);
    tb_xfer(BUS, "601 2F 00 18 02 FE 00 00 00", "581 60 00 18 02 00 00 00 00");
    tb_xfer(BUS, "601 2B 00 18 05 64 00 00 00", "581 60 00 18 05 00 00 00 00");
    tb_expect_none(BUS);
    tb_send(BUS, "000 01 01");
    tb_expect(BUS, "181 44 33 22 11");
    tb_expect_none(BUS);
    /* a change: nothing */
    v[0] = 0x55;
    assert_int_equal(co_od_write(&lean.node, 0x2200, 0, v, 4, true), CO_OK);
    tb_advance(BUS, 40000);
    tb_expect_none(BUS);
    /* a request: sent with the data of now */
    assert_int_equal(co_tpdo_request(&lean.node, 0), CO_OK);
    tb_advance(BUS, 1000);
    tb_expect(BUS, "181 55 33 22 11");
    /* the event timer runs from there: 100 ms later, the data of then */
    v[1] = 0x66;
    assert_int_equal(co_od_write(&lean.node, 0x2200, 0, v, 4, true), CO_OK);
    tb_advance(BUS, 98000);
    tb_expect_none(BUS);
    tb_advance(BUS, 2000);
    tb_expect(BUS, "181 55 66 22 11");
    tb_expect_none(BUS);
    tb_advance(BUS, 100000);
    tb_expect(BUS, "181 55 66 22 11");
    tb_expect_none(BUS);
}

/* TPDO1 acyclic synchronous (0): at the first SYNC in Operational, then at
 * the SYNC after a request only, not after a change of its data. */
static void tpdo_acyclic_no_change(void **state)
{
    uint8_t v[4] = {0x44, 0x33, 0x22, 0x11};

    (void)state;
    assert_int_equal(co_od_write(&lean.node, 0x2200, 0, v, 4, true), CO_OK);
    tb_xfer(BUS, "601 2F 00 18 02 00 00 00 00", "581 60 00 18 02 00 00 00 00");
    tb_send(BUS, "000 01 01");
    tb_expect_none(BUS);
    tb_send(BUS, "080");
    tb_expect(BUS, "181 44 33 22 11");
    tb_send(BUS, "080");
    tb_expect_none(BUS);
    /* a change: not at the next SYNC */
    v[0] = 0x55;
    assert_int_equal(co_od_write(&lean.node, 0x2200, 0, v, 4, true), CO_OK);
    tb_advance(BUS, 1000);
    tb_send(BUS, "080");
    tb_expect_none(BUS);
    /* a request: at the next SYNC (not before), once */
    assert_int_equal(co_tpdo_request(&lean.node, 0), CO_OK);
    tb_advance(BUS, 1000);
    tb_expect_none(BUS);
    tb_send(BUS, "080");
    tb_expect(BUS, "181 55 33 22 11");
    tb_send(BUS, "080");
    tb_expect_none(BUS);
}

static void guarding_device_refused(void **state)
{
    td_node_t td;
    co_node_config_t cfg;

    (void)state;
    /* td_dev has 0x100C / 0x100D (and TIME, SYNC producer) */
    memset(&td, 0, sizeof td);
    memset(&cfg, 0, sizeof cfg);
    cfg.dev = &td_dev;
    cfg.hal = tb_hal(&bus, 1);
    cfg.node_id = 2;
    cfg.ram = &td.ram;
    assert_int_equal(co_node_init(&td.node, &cfg, bus.now), CO_RESULT_DEV_INCOMPAT);
    tb_expect_none(BUS);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(block_sdo_left_out, setup),
        cmocka_unit_test_setup(guarding_left_out, setup),
        cmocka_unit_test_setup(full_tx_path, setup),
        cmocka_unit_test_setup(tpdo_rtr_left_out, setup),
        cmocka_unit_test_setup(pdo_bitwise_left_out, setup),
        cmocka_unit_test_setup(tpdo_event_no_change, setup),
        cmocka_unit_test_setup(tpdo_acyclic_no_change, setup),
        cmocka_unit_test_setup(guarding_device_refused, setup),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
