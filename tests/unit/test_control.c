/*
 * The control interface's line parser (targets/linux/control.c): every
 * command with its operands, the node prefix, and the refusals with their
 * one-line reasons.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "control.h"

static ctl_cmd_t ok(const char *line)
{
    ctl_cmd_t c;
    char err[128] = "";

    if (ctl_parse(line, &c, err, sizeof err) != 0) {
        fail_msg("'%s' refused: %s", line, err);
    }
    return c;
}

static void refused(const char *line, const char *reason)
{
    ctl_cmd_t c;
    char err[128] = "";

    assert_int_equal(ctl_parse(line, &c, err, sizeof err), -1);
    assert_string_equal(err, reason);
}

static void set_get_nodes_help(void **state)
{
    ctl_cmd_t c;

    (void)state;
    c = ok("set 0x6000 1 0x55");
    assert_int_equal(c.op, CTL_SET);
    assert_int_equal(c.node_id, -1);
    assert_int_equal(c.index, 0x6000);
    assert_int_equal(c.sub, 1);
    assert_int_equal(c.value, 0x55);
    c = ok("@7 set 0x6401 1 -5");
    assert_int_equal(c.node_id, 7);
    assert_int_equal(c.value, -5);
    c = ok("  get\t0x1017 0\r");
    assert_int_equal(c.op, CTL_GET);
    assert_int_equal(c.index, 0x1017);
    assert_int_equal(ok("nodes").op, CTL_NODES);
    assert_int_equal(ok("help").op, CTL_HELP);
    refused("set 0x6000 1", "usage: set INDEX SUB VALUE");
    refused("get 0x10000 0", "bad index 0x10000");
    refused("get 0x1000 256", "bad sub-index 256");
    refused("set 0x1000 0 x", "bad value x");
    refused("@0 help", "bad node-ID @0");
    refused("@128 help", "bad node-ID @128");
    refused("@5", "empty command");
    refused("", "empty command");
    refused("frobnicate", "unknown command frobnicate (help)");
}

static void emcy_raise_and_clear(void **state)
{
    ctl_cmd_t c;

    (void)state;
    c = ok("@5 emcy 0x5000");
    assert_int_equal(c.op, CTL_EMCY_RAISE);
    assert_int_equal(c.node_id, 5);
    assert_int_equal(c.code, 0x5000);
    assert_int_equal(c.reg, 0);
    assert_false(c.has_mfr);
    c = ok("emcy 0x2311 0x02");
    assert_int_equal(c.code, 0x2311);
    assert_int_equal(c.reg, 0x02);
    assert_false(c.has_mfr);
    c = ok("emcy 0xFF01 0x80 1 2 3 4 0xFF");
    assert_int_equal(c.reg, 0x80);
    assert_true(c.has_mfr);
    assert_memory_equal(c.mfr, "\x01\x02\x03\x04\xFF", 5);
    c = ok("emcy clear 0x5000");
    assert_int_equal(c.op, CTL_EMCY_CLEAR);
    assert_int_equal(c.code, 0x5000);
    refused("emcy", "usage: emcy CODE [REG [B0 B1 B2 B3 B4]] | emcy clear CODE");
    refused("emcy 0x5000 0 1 2", "usage: emcy CODE [REG [B0 B1 B2 B3 B4]] | emcy clear CODE");
    refused("emcy 0", "error code 0 is not an error (emcy clear CODE)");
    refused("emcy 0x10000", "bad error code 0x10000");
    refused("emcy 0x5000 0x100", "bad error register bits 0x100");
    refused("emcy 0x5000 1 1 2 3 4 256", "bad manufacturer byte 256");
    refused("emcy clear x", "bad error code x");
    refused("emcy 1 1 1 1 1 1 1 1 1", "too many words");
}

static void heartbeat_and_offbus(void **state)
{
    ctl_cmd_t c;

    (void)state;
    assert_int_equal(ok("heartbeat stop").op, CTL_HB_STOP);
    c = ok("@9 heartbeat resume");
    assert_int_equal(c.op, CTL_HB_RESUME);
    assert_int_equal(c.node_id, 9);
    refused("heartbeat", "usage: heartbeat stop|resume");
    refused("heartbeat pause", "usage: heartbeat stop|resume");
    c = ok("offbus 500");
    assert_int_equal(c.op, CTL_OFFBUS);
    assert_int_equal(c.ms, 500);
    assert_int_equal(ok("offbus 3600000").ms, 3600000);
    refused("offbus", "usage: offbus MS");
    refused("offbus 0", "bad time 0 (1..3600000 ms)");
    refused("offbus 3600001", "bad time 3600001 (1..3600000 ms)");
    refused("offbus -1", "bad time -1 (1..3600000 ms)");
}

static void too_long(void **state)
{
    char line[CTL_LINE_MAX + 2U];

    (void)state;
    memset(line, 'a', sizeof line - 1U);
    line[sizeof line - 1U] = '\0';
    refused(line, "line too long");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(set_get_nodes_help),
        cmocka_unit_test(emcy_raise_and_clear),
        cmocka_unit_test(heartbeat_and_offbus),
        cmocka_unit_test(too_long),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
