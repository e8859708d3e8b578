/* The configuration header reached the core's headers (and so the core,
 * which is compiled with the same PUBLIC definition): a build without it
 * stops here. */
#include "co/co_config.h"

#if CO_EMCY_QUEUE_LEN != 8U || CO_HB_CONSUMERS_MAX != 2U || CO_TIME != 0
#error "my_co_config.h was not used by co_config.h"
#endif

typedef int config_check_unit_not_empty;
