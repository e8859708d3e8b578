#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <cmocka.h>
#include "t402.h"
static void explore(void **s) {
    (void)s; static t402_t f; co402_sim_config_t c;
    t402_sim_defaults(&c);
    c.index_offset = 100; c.switches = CO402_IN_NEG_LIMIT | CO402_IN_POS_LIMIT; c.neg_limit=-50000; c.pos_limit=50000;
    t402_start(&f, 1, 0, &c);
    t402_set(&f, 0x6060, 0, 6, 1);
    t402_set(&f, 0x6098, 0, 4, 1);
    t402_enable(&f);
    t402_cw(&f, 0x001F);
    for (int i = 0; i < 4000; i++) {
        t402_run(&f, 1000);
        if (i % 200 == 0 || f.ax.hm_phase != 1)
            printf("%d simv %d pos %d ph %d dir %d in %x sw %04X st %d\n", i, co402_sim_velocity(&f.sim), co402_sim_position(&f.sim), f.ax.hm_phase, f.ax.hm_dir, f.ax.fb.inputs, t402_sw(&f), f.ax.state);
        if ((t402_sw(&f) & 0x400) && i > 10) break;
    }
}
int main(void) { const struct CMUnitTest t[] = { cmocka_unit_test(explore) }; return cmocka_run_group_tests(t, NULL, NULL); }
