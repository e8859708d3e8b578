/* This project's options of the core (stack/include/co/co_config.h), picked
 * up through -DCO_CONFIG_HEADER: a sensor that needs no TIME, no SYNC
 * producer and only two heartbeat consumers, with a deeper EMCY queue. */
#ifndef MY_CO_CONFIG_H
#define MY_CO_CONFIG_H

#define CO_TIME 0
#define CO_SYNC_PRODUCER 0
#define CO_HB_CONSUMERS_MAX 2U
#define CO_EMCY_QUEUE_LEN 8U

#endif
