#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <cmocka.h>
#include "t402.h"
static void explore(void **s) {
    (void)s; static t402_t f; t402_start(&f, 1, 0, NULL);
    t402_set(&f, 0x605A, 0, 3, 2);
    t402_set(&f, 0x6060, 0, 3, 1);
    t402_set(&f, 0x6083, 0, 400000, 4);
    t402_set(&f, 0x6084, 0, 100000, 4);
    t402_cw(&f, 6); t402_cw(&f, 15);
    t402_set(&f, 0x60FF, 0, 40000, 4);
    t402_run(&f, 300000);
    t402_cw(&f, 0x000B);
    for (int i = 0; i < 600; i++) {
        t402_run(&f, 1000);
        if (i < 60)
            printf("%d simv %d pos %d dem %d trv %lld sw %04X\n", i, co402_sim_velocity(&f.sim), (int)t402_get(&f,0x6064,0), (int)t402_get(&f,0x6062,0), (long long)(f.ax.tr_v/65536), t402_sw(&f));
    }
}
int main(void) { const struct CMUnitTest t[] = { cmocka_unit_test(explore) }; return cmocka_run_group_tests(t, NULL, NULL); }
