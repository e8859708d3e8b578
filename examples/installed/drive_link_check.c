/* Links the CiA 402 simulated plant and the Linux port from the installed
 * package (the export set is complete and usable): a simulated motor's
 * position after its defaults, and the monotonic clock running. */
#include <stdint.h>
#include <stdio.h>

#include "co/co402_sim.h"
#include "co_lx/clock.h"

int main(void)
{
    co402_sim_config_t cfg;
    static co402_sim_t sim;

    co402_sim_defaults(&cfg);
    co402_sim_init(&sim, &cfg, co_lx_now_us());
    printf("co402 simulated plant at position %ld\n", (long)co402_sim_position(&sim));
    return co402_sim_position(&sim) == 0 ? 0 : 1;
}
