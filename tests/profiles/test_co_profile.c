#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <cmocka.h>
#include "t402.h"
static void explore(void **s) {
    (void)s; static t402_t f; co402_sim_config_t sc;
    t402_sim_defaults(&sc); sc.torque_max = 30;
    t402_start(&f, 1, CO402_OPT_FE_WARN_ONLY, &sc);
    t402_set(&f, 0x6065, 0, 200, 4);
    t402_enable(&f);
    t402_set(&f, 0x607A, 0, 50000, 4);
    t402_cw(&f, 0x001F); t402_cw(&f, 0x000F);
    for (int i = 0; i < 8000; i++) {
        t402_run(&f, 1000);
        if (i % 250 == 0)
            printf("%d simv %d pos %d dem %d fe %d trq %d sw %04X\n", i, co402_sim_velocity(&f.sim), (int)t402_get(&f,0x6064,0), (int)t402_get(&f,0x6062,0), (int)t402_get(&f,0x60F4,0), (int)t402_get(&f,0x6077,0), t402_sw(&f));
    }
}
int main(void) { const struct CMUnitTest t[] = { cmocka_unit_test(explore) }; return cmocka_run_group_tests(t, NULL, NULL); }
