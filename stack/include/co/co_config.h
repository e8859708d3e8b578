/*
 * Build-time configuration of the core: every option with its default, in
 * one place. The defaults are the full core; the unit tests run against it.
 * A build overrides options with -D for the core and everything that
 * includes its headers (CMake: co_core(<library> <NAME=VALUE>...), see
 * stack/CMakeLists.txt). The features a build leaves out are refused at
 * co_node_init (CO_ERR_DEV_INCOMPAT) for a device that would need them, so
 * a device never runs with less than its description says.
 */
#ifndef CO_CONFIG_H
#define CO_CONFIG_H

/* The user's configuration header (CMake: -DCO_CONFIG_HEADER=path/my_co_config.h,
 * which defines CO_CONFIG_HEADER="my_co_config.h" for the core and its users):
 * its #defines of the options below win over the defaults, like lwIP's
 * lwipopts.h. Options given with -D and in the header must not overlap. */
#ifdef CO_CONFIG_HEADER
#include CO_CONFIG_HEADER
#endif

/* ---- services a device may not need (1: in, 0: left out); more below */

#ifndef CO_LSS
/** LSS slave, CiA 305 (co_lss.c): node-ID and bit timing over the bus,
 *  unconfigured nodes, fastscan. Left out: a device with set.lss.slave is
 *  refused (configured node-IDs still change with co_node_set_id). */
#define CO_LSS 1
#endif

/* ---- sizes of the node's fixed tables (co_node_t) */

/* (CO_TXQ_LEN, the depth of a queue of frames held back while the HAL's TX
 * path is full, is gone: a producer whose frame the HAL refuses makes it
 * again from its own state when the path takes it (SYNC, EMCY from the EMCY
 * queue, boot-up, heartbeat, guarding reply; TPDOs), in CAN priority order,
 * so only the answers of the request/response services are held as frames:
 * one each, as such a service has at most one answer outstanding (the SDO
 * server's, and with CO_LSS the LSS slave's: co_node.h, CO_TX_ANSWERS,
 * 8 bytes each). A definition of it is ignored.) */
#ifndef CO_EMCY_ACTIVE_MAX
#define CO_EMCY_ACTIVE_MAX 8U  /**< distinct error codes active at once */
#endif
#ifndef CO_EMCY_QUEUE_LEN
#define CO_EMCY_QUEUE_LEN 4U   /**< EMCYs waiting for the inhibit time or the TX path */
#endif
#ifndef CO_HB_CONSUMERS_MAX
#define CO_HB_CONSUMERS_MAX 8U /**< heartbeat consumer entries the core tracks (0x1016
                                    sub-entries beyond are not monitored) */
#endif
#ifndef CO_RX_SLOTS_MAX
/** Receive table of the core's services: NMT, SDO, SYNC, and guarding,
 *  TIME and LSS where the build has them, and the heartbeat consumers
 *  (2 bytes each; at most 127). */
#define CO_RX_SLOTS_MAX (3U + (unsigned)(CO_NODE_GUARDING) + (unsigned)(CO_TIME) + \
                         (unsigned)(CO_LSS) + CO_HB_CONSUMERS_MAX)
#endif

/* ---- PDO */

/* (CO_PDO_FAST_MAX, the mapping entries per PDO once resolved into the
 * PDO's RAM state, is gone: every PDO whose entries are all plain values is
 * copied directly, whatever their number, from the device's const table of
 * mappable objects (co_od_map_t); a definition of it is ignored.) */

#ifndef CO_PDO_RTR
/** Remote requests of TPDOs (CiA 301: COB-ID bit 30 clear) and the
 *  RTR-only transmission types 252 and 253. Left out: TPDOs answer no
 *  remote request whatever bit 30 says, types 252 and 253 answer 0x06090030
 *  like 241..251, and the generator refuses a device whose TPDO defaults
 *  to one of them (CANopenNode v4 has no RTR either). */
#define CO_PDO_RTR 1
#endif

#ifndef CO_PDO_BITWISE
/** Bit-granular PDO mapping (CiA 301: an entry maps any number of bits).
 *  Left out: every mapping length is a multiple of 8 (an entry of another
 *  length answers 0x06040041, as a device with set.pdo.granularity bytes
 *  does), the bit copy is not built, and the generator refuses a device
 *  whose default mapping has such an entry (CANopenNode v4 maps whole bytes
 *  by default: CO_CONFIG_PDO_BITWISE_MAPPING is not in its CO_CONFIG_PDO). */
#define CO_PDO_BITWISE 1
#endif

#ifndef CO_TPDO_CHANGE
/** Change detection of event-driven (254, 255) and acyclic synchronous (0)
 *  TPDOs: their mapped data are compared at every co_node_process (254/255)
 *  or SYNC (0) and a change sends them. Left out: they compare nothing and
 *  go out on a request (co_tpdo_request, set.pdo.tpdo_after_rpdo), at their
 *  event timer and once on entering Operational (type 0: at a SYNC after
 *  one of these); the tpdo_event callback is not called, and the generator
 *  refuses a device with set.tpdo.change_mask, a tpdo_mask or
 *  set.tpdo.change_detection off (CANopenNode v4 compares no PDO data:
 *  its TPDOs send on the application's request, the event timer and once
 *  when they become valid in Operational). */
#define CO_TPDO_CHANGE 1
#endif

/* ---- services a device may not need (1: in, 0: left out) */

#ifndef CO_SDO_BLOCK
/** SDO block upload and download (CiA 301 7.2.4.3.9..). Left out: block
 *  requests answer 0x05040001 like an unknown command; a device whose
 *  description offers block transfer ([sdo] block) is refused. */
#define CO_SDO_BLOCK 1
#endif
#ifndef CO_NODE_GUARDING
/** Node guarding and life guarding (0x100C, 0x100D, guarding RTRs). Left
 *  out: a device with 0x100C or 0x100D is refused; guarding RTRs are not
 *  answered (heartbeat only). */
#define CO_NODE_GUARDING 1
#endif
#ifndef CO_STORAGE
/** Parameter storage, 0x1010 / 0x1011 (co_store.c). Left out, the node
 *  behaves as with a HAL without non-volatile memory: 0x1010 / 0x1011 read 0
 *  and writes answer 0x08000020; values start from the defaults. */
#define CO_STORAGE 1
#endif
#ifndef CO_TIME
/** TIME consumer and producer (0x1012). Left out: a device with 0x1012 is
 *  refused. */
#define CO_TIME 1
#endif
#ifndef CO_SYNC_PRODUCER
/** SYNC producer (0x1005 bit 30, 0x1006). Left out: a device with 0x1006 is
 *  refused (the SYNC consumer is always in). */
#define CO_SYNC_PRODUCER 1
#endif
#ifndef CO_ERROR_BEHAVIOUR
/** Error behaviour 0x1029: the NMT reaction to communication errors and
 *  device-specific error classes (co_node_error_behaviour). Left out: a
 *  device with 0x1029 is refused, errors never change the NMT state. */
#define CO_ERROR_BEHAVIOUR 1
#endif
#ifndef CO_LIMITS
/** Value limits of the dictionary (CO_SUB_LIMIT, co_dev_t.limits). Left out:
 *  a device with a limit table is refused. */
#define CO_LIMITS 1
#endif
#ifndef CO_PERSONALITY
/** Device personalities (co_settings.h, co_dev_t.set): 1 implements every
 *  setting; 0 only the CiA 301 ones (every field 0), the code of the
 *  deviations is not built and a device that needs one is refused (with
 *  CO_LSS=0 too, co_dev_t has no field set: the generated dictionary of
 *  such a device does not compile, #error). */
#define CO_PERSONALITY 1
#endif

#endif /* CO_CONFIG_H */
