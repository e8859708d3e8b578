#include "test_frames.h"

#include <ctype.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

static const char *skip_space(const char *p)
{
    while ((*p != '\0') && isspace((unsigned char)*p)) {
        p++;
    }
    return p;
}

co_frame_t tf_parse(const char *text)
{
    co_frame_t f;
    const char *p = skip_space(text);
    char *end = NULL;
    unsigned long id = strtoul(p, &end, 16);
    uint8_t data[8] = {0};
    uint8_t n = 0;

    if (end == p) {
        fail_msg("bad frame text (no COB-ID): '%s'", text);
    }
    p = skip_space(end);
    if ((*p == 'R') || (*p == 'r')) {
        unsigned long dlc = 0;
        p++;
        if (isdigit((unsigned char)*p)) {
            dlc = strtoul(p, &end, 10);
        }
        co_frame_set(&f, (uint32_t)id | CO_FRAME_RTR, NULL, 0);
        f.dlc = (uint8_t)dlc;
        return f;
    }
    while (*p != '\0') {
        unsigned long b = strtoul(p, &end, 16);
        if ((end == p) || (b > 0xFFUL) || (n >= 8U)) {
            fail_msg("bad frame text: '%s'", text);
        }
        data[n++] = (uint8_t)b;
        p = skip_space(end);
    }
    co_frame_set(&f, (uint32_t)id, data, n);
    return f;
}

void tf_format(const co_frame_t *f, char *buf, size_t cap)
{
    size_t used = 0;
    int w = snprintf(buf, cap, "%03lX", (unsigned long)co_frame_cob(f));

    if (w > 0) {
        used = (size_t)w;
    }
    if (co_frame_is_rtr(f)) {
        (void)snprintf(&buf[used], cap - used, " R%u", (unsigned)f->dlc);
        return;
    }
    for (uint8_t i = 0; (i < f->dlc) && (i < 8U) && (used + 4U < cap); i++) {
        w = snprintf(&buf[used], cap - used, " %02X", (unsigned)f->data[i]);
        if (w > 0) {
            used += (size_t)w;
        }
    }
}

void tf_assert_frame(const co_frame_t *f, const char *expected, const char *file, int line)
{
    co_frame_t want = tf_parse(expected);
    char got_txt[64];
    char want_txt[64];

    if (!co_frame_equal(f, &want)) {
        tf_format(f, got_txt, sizeof got_txt);
        tf_format(&want, want_txt, sizeof want_txt);
        print_error("%s:%d: frame mismatch\n  expected: %s\n  got:      %s\n", file, line,
                       want_txt, got_txt);
        _fail(file, line);
    }
}
