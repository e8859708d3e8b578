#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include "t402.h"
static void placeholder(void **s) { (void)s; t402_t f; t402_start(&f, 1, 0, NULL); assert_int_equal(t402_sw(&f), 0x0250); }
int main(void) { const struct CMUnitTest t[] = { cmocka_unit_test(placeholder) }; return cmocka_run_group_tests(t, NULL, NULL); }
