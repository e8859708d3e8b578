/*
 * The EDS/DCF loader of the daemon (targets/linux/eds_load.c): a dictionary
 * built in memory from the text, run by the core on the in-memory bus with
 * exact frames: identity, $NODEID defaults, a DCF ParameterValue over the
 * default, limits, CompactSubObj with [xxxxValue], 24-bit, REAL32, strings,
 * heartbeat, a TPDO at SYNC and an RPDO; then every kind of bad file with
 * the one-line message naming file, line, section and key, and the objects
 * left out with a warning.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "eds_load.h"
#include "test_bus.h"

static const char EDS[] =
    "; a device for the loader's test\r\n"
    "[FileInfo]\r\n"
    "FileName=t.eds\r\n"
    "[DeviceInfo]\r\n"
    "ProductName=loader test\r\n"
    "[1000]\r\nParameterName=Device type\r\nObjectType=0x7\r\nDataType=0x0007\r\n"
    "AccessType=ro\r\nDefaultValue=0x00020191\r\n"
    "[1001]\r\nDataType=0x0005\r\nAccessType=ro\r\n"
    "[1014]\r\nDataType=0x0007\r\nAccessType=rw\r\nDefaultValue=$NODEID+0x80\r\n"
    "[1017]\r\nDataType=0x0006\r\nAccessType=rw\r\nDefaultValue=100\r\n"
    "[1018]\r\nObjectType=0x9\r\nSubNumber=2\r\n"
    "[1018sub0]\r\nDataType=0x0005\r\nAccessType=ro\r\nDefaultValue=1\r\n"
    "[1018sub1]\r\nDataType=0x0007\r\nAccessType=ro\r\nDefaultValue=0x12345678\r\n"
    "[1005]\r\nDataType=0x0007\r\nAccessType=rw\r\nDefaultValue=0x80\r\n"
    "[1200]\r\nObjectType=0x9\r\n"
    "[1200sub0]\r\nDataType=0x0005\r\nAccessType=const\r\nDefaultValue=2\r\n"
    "[1200sub1]\r\nDataType=0x0007\r\nAccessType=ro\r\nDefaultValue=$NODEID+0x600\r\n"
    "[1200sub2]\r\nDataType=0x0007\r\nAccessType=ro\r\nDefaultValue=$NODEID+0x580\r\n"
    "[1400]\r\nObjectType=0x9\r\n"
    "[1400sub0]\r\nDataType=0x0005\r\nAccessType=const\r\nDefaultValue=2\r\n"
    "[1400sub1]\r\nDataType=0x0007\r\nAccessType=rw\r\nDefaultValue=0x200+$NODEID\r\n"
    "[1400sub2]\r\nDataType=0x0005\r\nAccessType=rw\r\nDefaultValue=255\r\n"
    "[1600]\r\nObjectType=0x9\r\n"
    "[1600sub0]\r\nDataType=0x0005\r\nAccessType=rw\r\nDefaultValue=1\r\n"
    "[1600sub1]\r\nDataType=0x0007\r\nAccessType=rw\r\nDefaultValue=0x20020010\r\n"
    "[1800]\r\nObjectType=0x9\r\n"
    "[1800sub0]\r\nDataType=0x0005\r\nAccessType=const\r\nDefaultValue=2\r\n"
    "[1800sub1]\r\nDataType=0x0007\r\nAccessType=rw\r\nDefaultValue=$NODEID+0x180\r\n"
    "[1800sub2]\r\nDataType=0x0005\r\nAccessType=rw\r\nDefaultValue=1\r\n"
    "[1A00]\r\nObjectType=0x9\r\n"
    "[1A00sub0]\r\nDataType=0x0005\r\nAccessType=rw\r\nDefaultValue=1\r\n"
    "[1A00sub1]\r\nDataType=0x0007\r\nAccessType=rw\r\nDefaultValue=0x20010008\r\n"
    "[2001]\r\nDataType=0x0005\r\nAccessType=rw\r\nPDOMapping=1\r\nDefaultValue=1\r\n"
    "ParameterValue=7\r\n"
    "[2002]\r\nDataType=0x0006\r\naccesstype=RW\r\nPDOMapping=1\r\nDefaultValue=20\r\n"
    "LowLimit=10\r\nHighLimit=100\r\n"
    "[2003]\r\nObjectType=0x8\r\nCompactSubObj=3\r\nDataType=0x0006\r\nAccessType=rw\r\n"
    "DefaultValue=0x11\r\n"
    "[2003Value]\r\nNrOfEntries=1\r\n2=0x22\r\n"
    "[2004]\r\nDataType=0x0010\r\nAccessType=ro\r\nDefaultValue=-1\r\n"
    "[2005]\r\nDataType=0x0008\r\nAccessType=rw\r\nDefaultValue=1.5\r\n"
    "[2006]\r\nDataType=0x0009\r\nAccessType=ro\r\nDefaultValue=abc\r\n"
    "[2007]\r\nDataType=0x000A\r\nAccessType=ro\r\nDefaultValue=DE AD\r\n"
    "[2008]\r\nDataType=0x0003\r\nAccessType=rw\r\nDefaultValue=0xFFFE\r\n"
    "LowLimit=-5\r\nHighLimit=0x0005\r\n";

typedef struct fx {
    tb_bus_t bus;
    eds_dev_t *eds;
    co_node_t node;
    void *ram;
} fx_t;

static int setup(void **state)
{
    fx_t *f = calloc(1U, sizeof *f);
    char err[256] = "";
    co_node_config_t cfg;

    assert_non_null(f);
    f->eds = eds_load_text("t.eds", EDS, err, sizeof err);
    assert_string_equal(err, "");
    assert_non_null(f->eds);
    f->ram = calloc(1U, co_dev_storage_size(eds_device(f->eds)));
    tb_init(&f->bus);
    (void)memset(&cfg, 0, sizeof cfg);
    cfg.dev = eds_device(f->eds);
    cfg.hal = tb_hal(&f->bus, 0U);
    cfg.node_id = 5U;
    cfg.ram = f->ram;
    assert_int_equal(co_node_init(&f->node, &cfg, 0U), CO_RESULT_OK);
    tb_attach(&f->bus, 0U, &f->node);
    tb_expect(&f->bus, "705 00");
    tb_expect_none(&f->bus);
    *state = f;
    return 0;
}

static int teardown(void **state)
{
    fx_t *f = *state;
    eds_free(f->eds);
    free(f->ram);
    free(f);
    return 0;
}

static void the_device(void **state)
{
    fx_t *f = *state;
    const co_dev_t *d = eds_device(f->eds);
    const uint8_t *ram = (const uint8_t *)f->ram;

    assert_int_equal(d->n_rpdo, 1);
    assert_int_equal(d->n_tpdo, 1);
    assert_string_equal(eds_summary(f->eds), "loader test: 19 objects, 1 RPDOs, 1 TPDOs");
    assert_string_equal(eds_warnings(f->eds), "");
    assert_non_null(strstr(eds_text(f->eds), "ProductName=loader test"));
    /* the core's objects at their places (co_node.h, CO_RAM_*): the image
     * starts with them, the values not stored with 0x1001 (app_end a
     * multiple of 4); 0x1007 absent: zeros in its place */
    assert_ptr_equal(co_od_value_ptr(&f->node, 0x1005U, 0U), ram + CO_RAM_1005);
    assert_ptr_equal(co_od_value_ptr(&f->node, 0x1014U, 0U), ram + CO_RAM_1014);
    assert_ptr_equal(co_od_value_ptr(&f->node, 0x1017U, 0U), ram + CO_RAM_1017);
    assert_ptr_equal(co_od_value_ptr(&f->node, 0x1001U, 0U),
                     ram + d->app_end + CO_RAM_END_1001);
    assert_int_equal(d->app_end % 4U, 0U);
    assert_null(co_od_value_ptr(&f->node, 0x1007U, 0U));
    assert_int_equal(ram[CO_RAM_1007] | ram[CO_RAM_1007 + 3U], 0);
    /* the COB-IDs the core reads in their 16-bit forms (co_od.h,
     * CO_SUB_COB16), as the generator makes them: the EMCY's and the PDOs'
     * with the node-ID */
    {
        uint16_t v;
        const uint8_t *tp = (const uint8_t *)co_od_value_ptr(&f->node, 0x1800U, 1U);
        (void)memcpy(&v, ram + CO_RAM_1005, 2U);
        assert_int_equal(v, 0x0080U);
        (void)memcpy(&v, ram + CO_RAM_1014, 2U);
        assert_int_equal(v, 0x0085U);
        assert_non_null(tp);
        (void)memcpy(&v, tp, 2U);
        assert_int_equal(v, 0x0185U);
        assert_int_equal(co_od_find(d->od, d->od_count, 0x1800U) != NULL, 1);
        assert_int_equal(co_od_rows(d, co_od_find(d->od, d->od_count, 0x1800U))[1].flags &
                             CO_SUB_COB16, CO_SUB_COB16);
        /* (and the SDO server's, read-only) */
        (void)memcpy(&v, co_od_value_ptr(&f->node, 0x1200U, 2U), 2U);
        assert_int_equal(v, 0x0585U);
    }
}

static void values_over_sdo(void **state)
{
    tb_bus_t *b = &((fx_t *)*state)->bus;

    tb_xfer(b, "605 40 00 10 00 00 00 00 00", "585 43 00 10 00 91 01 02 00");
    tb_xfer(b, "605 40 18 10 01 00 00 00 00", "585 43 18 10 01 78 56 34 12");
    /* $NODEID+0x80, 0x200+$NODEID */
    tb_xfer(b, "605 40 14 10 00 00 00 00 00", "585 43 14 10 00 85 00 00 00");
    tb_xfer(b, "605 40 00 14 01 00 00 00 00", "585 43 00 14 01 05 02 00 00");
    tb_xfer(b, "605 40 00 12 01 00 00 00 00", "585 43 00 12 01 05 06 00 00");
    tb_xfer(b, "605 40 00 12 02 00 00 00 00", "585 43 00 12 02 85 05 00 00");
    /* a PDO COB-ID (its 16-bit form in RAM): bit 31 round trip, bits 29..11 refused */
    tb_xfer(b, "605 23 00 18 01 85 01 00 80", "585 60 00 18 01 00 00 00 00");
    tb_xfer(b, "605 23 00 18 01 85 01 00 90", "585 80 00 18 01 30 00 09 06");
    tb_xfer(b, "605 40 00 18 01 00 00 00 00", "585 43 00 18 01 85 01 00 80");
    /* DCF: ParameterValue 7 over DefaultValue 1 */
    tb_xfer(b, "605 40 01 20 00 00 00 00 00", "585 4F 01 20 00 07 00 00 00");
    /* CompactSubObj=3: NrOfObjects, the default, the [2003Value] entry */
    tb_xfer(b, "605 40 03 20 00 00 00 00 00", "585 4F 03 20 00 03 00 00 00");
    tb_xfer(b, "605 40 03 20 01 00 00 00 00", "585 4B 03 20 01 11 00 00 00");
    tb_xfer(b, "605 40 03 20 02 00 00 00 00", "585 4B 03 20 02 22 00 00 00");
    tb_xfer(b, "605 40 03 20 04 00 00 00 00", "585 80 03 20 04 11 00 09 06");
    /* INTEGER24 -1, REAL32 1.5, VISIBLE_STRING, OCTET_STRING, INTEGER16 0xFFFE = -2 */
    tb_xfer(b, "605 40 04 20 00 00 00 00 00", "585 47 04 20 00 FF FF FF 00");
    tb_xfer(b, "605 40 05 20 00 00 00 00 00", "585 43 05 20 00 00 00 C0 3F");
    tb_xfer(b, "605 40 06 20 00 00 00 00 00", "585 47 06 20 00 61 62 63 00");
    tb_xfer(b, "605 40 07 20 00 00 00 00 00", "585 4B 07 20 00 DE AD 00 00");
    tb_xfer(b, "605 40 08 20 00 00 00 00 00", "585 4B 08 20 00 FE FF 00 00");
    /* ro and const refuse writes; a missing object */
    tb_xfer(b, "605 23 00 10 00 00 00 00 00", "585 80 00 10 00 02 00 01 06");
    tb_xfer(b, "605 2F 00 14 00 03 00 00 00", "585 80 00 14 00 02 00 01 06");
    tb_xfer(b, "605 40 09 20 00 00 00 00 00", "585 80 09 20 00 00 00 02 06");
}

static void limits(void **state)
{
    tb_bus_t *b = &((fx_t *)*state)->bus;

    tb_xfer(b, "605 2B 02 20 00 09 00 00 00", "585 80 02 20 00 32 00 09 06");
    tb_xfer(b, "605 2B 02 20 00 65 00 00 00", "585 80 02 20 00 31 00 09 06");
    tb_xfer(b, "605 2B 02 20 00 64 00 00 00", "585 60 02 20 00 00 00 00 00");
    tb_xfer(b, "605 40 02 20 00 00 00 00 00", "585 4B 02 20 00 64 00 00 00");
    /* signed limits -5..5 (HighLimit in hex) */
    tb_xfer(b, "605 2B 08 20 00 FA FF 00 00", "585 80 08 20 00 32 00 09 06");
    tb_xfer(b, "605 2B 08 20 00 06 00 00 00", "585 80 08 20 00 31 00 09 06");
    tb_xfer(b, "605 2B 08 20 00 FB FF 00 00", "585 60 08 20 00 00 00 00 00");
}

static void heartbeat_and_pdos(void **state)
{
    tb_bus_t *b = &((fx_t *)*state)->bus;

    tb_advance(b, 100000U);
    tb_expect(b, "705 7F");
    tb_expect_none(b);
    tb_send(b, "000 01 05");
    tb_flush(b);
    tb_send(b, "080");
    tb_expect(b, "185 07");
    tb_expect_none(b);
    /* RPDO1 (0x205) writes 0x2002 */
    tb_send(b, "205 32 00");
    tb_xfer(b, "605 40 02 20 00 00 00 00 00", "585 4B 02 20 00 32 00 00 00");
}

typedef struct bad {
    const char *text;
    const char *err;
} bad_t;

static void bad_files(void **state)
{
    static const bad_t cases[] = {
        {"[1000]\nDataType=0x0007\nAccessType=ro\nDefaultValue=0x1G\n",
         "b.eds:4: [1000] DefaultValue: '0x1G' is not a value of data type 0x0007"},
        {"[1000]\nDataType=0x0005\nAccessType=ro\nDefaultValue=256\n",
         "b.eds:4: [1000] DefaultValue: '256' is not a value of data type 0x0005"},
        {"[1000]\nDataType=0x0007\nAccessType=rx\n",
         "b.eds:3: [1000] AccessType: unknown access type 'rx' (ro, wo, rw, rwr, rww, const)"},
        {"[1000]\nDataType=0x0007\n", "b.eds:1: [1000]: AccessType missing"},
        {"[1000]\nAccessType=ro\n", "b.eds:1: [1000]: DataType missing"},
        {"[1000]\nDataType=0x0007\nAccessType=ro\n[2000]\nObjectType=0x4\n",
         "b.eds:5: [2000] ObjectType: object type 0x4 (VAR 7, DOMAIN 2, ARRAY 8, RECORD 9)"},
        {"[2000]\nDataType=0x001B\nAccessType=rw\nDefaultValue=$NODEID+1\n",
         "b.eds:4: [2000] DefaultValue: $NODEID in a 8-byte value (8, 16 or 32 bits only)"},
        {"[1000]\nDataType=0x0007\nAccessType=ro\n[1000]\nDataType=0x0007\nAccessType=ro\n",
         "b.eds:4: [1000]: object 0x1000 given twice"},
        {"[2000]\nDataType=0x000A\nAccessType=ro\nDefaultValue=ABC\n",
         "b.eds:4: [2000] DefaultValue: 'ABC' is not hex bytes"},
        {"[2000]\nDataType=0x0005\nAccessType=ro\nLowLimit=x\n",
         "b.eds:4: [2000] LowLimit: 'x' is not a value of the object's data type"},
        {"[2000\nDataType=0x0005\n", "b.eds:1: [[2000]: section name without ']'"},
        {"[2000]\nDataType 5\n", "b.eds:2: [2000] DataType 5: a line without '='"},
        {"DataType=5\n", "b.eds:1: [] DataType=5: a key before the first section"},
        {"[FileInfo]\nFileName=x\n", "b.eds: no objects (is this an EDS?)"},
        {"[2000]\nObjectType=0x8\nCompactSubObj=300\nDataType=0x0005\nAccessType=ro\n",
         "b.eds:3: [2000] CompactSubObj: '300' is not a number of sub-entries (1..254)"},
    };
    (void)state;
    for (size_t i = 0U; i < sizeof cases / sizeof cases[0]; i++) {
        char err[256] = "";
        eds_dev_t *d = eds_load_text("b.eds", cases[i].text, err, sizeof err);
        if (d != NULL || strcmp(err, cases[i].err) != 0) {
            print_error("case %zu: got '%s'\n", i, err);
        }
        assert_null(d);
        assert_string_equal(err, cases[i].err);
    }
}

static void objects_left_out(void **state)
{
    char err[256] = "";
    eds_dev_t *d = eds_load_text(
        "w.eds",
        "[1000]\nDataType=0x0007\nAccessType=ro\n"
        "[2000]\nDataType=0x0040\nAccessType=rw\n"
        "[2001]\nObjectType=0x8\nSubNumber=0\n"
        "[2002]\nDataType=0x000F\nAccessType=rw\nDefaultValue=@AB\n"
        "[0040]\nObjectType=0x6\nSubNumber=1\n",
        err, sizeof err);

    (void)state;
    assert_non_null(d);
    assert_string_equal(eds_warnings(d),
                        "w.eds:5: [2000] DataType: object 0x2000 skipped: data type 0x0040 is "
                        "not a CiA 301 basic type\n"
                        "w.eds:7: [2001]: object 0x2001 skipped: an ARRAY/RECORD without "
                        "sub-entries\n"
                        "w.eds:13: [2002] DefaultValue: '@AB' is not hex bytes: taken as the "
                        "text's bytes\n");
    assert_int_equal(eds_device(d)->od_count, 2);
    assert_int_equal(eds_device(d)->od[1].index, 0x2002);
    assert_int_equal(co_od_rows(eds_device(d), &eds_device(d)->od[1])[0].size, 3);
    eds_free(d);
}

/* A PDO mapping entry is held in its 16-bit form (co_od.h), a row of the
 * mappable-object table: a default that names an object the EDS lacks
 * still loads and reads back as written (a row of its own), its PDO waits
 * for a valid mapping, and a mapping written over SDO then runs. */
static void mapping_default_of_an_absent_object(void **state)
{
    static const char from[] = "DefaultValue=0x20020010";
    char *text = malloc(sizeof EDS);
    char *at;
    char err[256] = "";
    fx_t *f = calloc(1U, sizeof *f);
    co_node_config_t cfg;
    tb_bus_t *b;

    (void)state;
    assert_non_null(text);
    assert_non_null(f);
    if ((text == NULL) || (f == NULL)) {
        free(text);
        free(f);
        return;
    }
    (void)memcpy(text, EDS, sizeof EDS);
    at = strstr(text, from);
    assert_non_null(at);
    (void)memcpy(at, "DefaultValue=0x60400010", sizeof from - 1U);
    f->eds = eds_load_text("t.eds", text, err, sizeof err);
    assert_string_equal(err, "");
    assert_non_null(f->eds);
    f->ram = calloc(1U, co_dev_storage_size(eds_device(f->eds)));
    tb_init(&f->bus);
    b = &f->bus;
    (void)memset(&cfg, 0, sizeof cfg);
    cfg.dev = eds_device(f->eds);
    cfg.hal = tb_hal(b, 0U);
    cfg.node_id = 5U;
    cfg.ram = f->ram;
    assert_int_equal(co_node_init(&f->node, &cfg, 0U), CO_RESULT_OK);
    tb_attach(b, 0U, &f->node);
    tb_expect(b, "705 00");
    tb_xfer(b, "605 40 00 16 01 00 00 00 00", "585 43 00 16 01 10 00 40 60");
    tb_send(b, "000 01 05");
    tb_send(b, "205 32 00");
    tb_xfer(b, "605 40 02 20 00 00 00 00 00", "585 4B 02 20 00 14 00 00 00");
    /* remapped to 0x2002 */
    tb_send(b, "000 80 05");
    tb_xfer(b, "605 23 00 14 01 05 02 00 80", "585 60 00 14 01 00 00 00 00");
    tb_xfer(b, "605 2F 00 16 00 00 00 00 00", "585 60 00 16 00 00 00 00 00");
    tb_xfer(b, "605 23 00 16 01 10 00 02 20", "585 60 00 16 01 00 00 00 00");
    tb_xfer(b, "605 2F 00 16 00 01 00 00 00", "585 60 00 16 00 00 00 00 00");
    tb_xfer(b, "605 23 00 14 01 05 02 00 00", "585 60 00 14 01 00 00 00 00");
    tb_send(b, "000 01 05");
    tb_send(b, "205 32 00");
    tb_xfer(b, "605 40 02 20 00 00 00 00 00", "585 4B 02 20 00 32 00 00 00");
    eds_free(f->eds);
    free(f->ram);
    free(f);
    free(text);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(the_device, setup, teardown),
        cmocka_unit_test_setup_teardown(values_over_sdo, setup, teardown),
        cmocka_unit_test_setup_teardown(limits, setup, teardown),
        cmocka_unit_test_setup_teardown(heartbeat_and_pdos, setup, teardown),
        cmocka_unit_test(mapping_default_of_an_absent_object),
        cmocka_unit_test(bad_files),
        cmocka_unit_test(objects_left_out),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
