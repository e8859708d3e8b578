/*
 * The services compiled into the core, in the order the node walks them
 * (docs/core.md, "The service table"): receive-table slots, resets, timers
 * and NMT state changes all go down this list. Adding a service: its file
 * defines one const co_service_t, declared next to the others in
 * co_priv.h; its row goes here.
 */
#include "co_priv.h"

const co_service_t *const co_services[CO_N_SERVICES] = {
#if CO_LSS
    [0] = &co_svc_lss,    /* LSS slave, CiA 305 (alone while unconfigured: CO_SVC_UNCONFIGURED_ROWS) */
#endif
    [CO_ROW_NMT] = &co_svc_nmt,    /* NMT command, 0x1029 */
    [CO_ROW_SDO] = &co_svc_sdo,    /* SDO server */
    [CO_ROW_ERRCTL] = &co_svc_errctl, /* heartbeat, node / life guarding: 0x100C, 0x100D, 0x1016, 0x1017 */
    [CO_ROW_EMCY] = &co_svc_emcy,   /* EMCY: 0x1001, 0x1003, 0x1014, 0x1015 */
    [CO_ROW_SYNC] = &co_svc_sync,   /* SYNC: 0x1005..0x1007, 0x1019 */
#if CO_TIME
    [CO_ROW_TIME] = &co_svc_time,   /* TIME: 0x1012 */
#endif
    [CO_ROW_PDO] = &co_svc_pdo,    /* RPDO, TPDO: 0x1400..0x1BFF */
#if CO_STORAGE
    [CO_ROW_STORE] = &co_svc_store,  /* parameter storage: 0x1010, 0x1011 */
#endif
};

/* (a receive slot holds the row above the 11-bit COB-ID: at most 32 rows) */

/* The services' hooks on the objects they own: slot k - 1 for the entries
 * whose svc is k (CO_OD_SVC_OF in co_od.h names the objects of each slot;
 * a write of one makes the service of 'row' run at the next
 * co_node_process unless CO_SVC_SELF). Const: nothing registers at run time. */
const co_svc_hook_t co_svc_hooks[CO_SVC_N_HOOKS] = {
    /* 1: 0x1003 */
    {CO_SVC_READ | CO_SVC_CHECK, CO_ROW_EMCY, co_emcy_obj},
    /* 2: 0x1014, 0x1015 */
    {CO_SVC_CHECK | CO_SVC_SELF, CO_ROW_EMCY, co_emcy_obj},
    /* 3: 0x1005..0x1007, 0x1019 */
    {CO_SVC_CHECK | CO_SVC_WRITTEN, CO_ROW_SYNC, co_sync_obj},
    /* 4: 0x1016 (and 0x100C, 0x100D with guarding) */
    {CO_SVC_CHECK | CO_SVC_WRITTEN | CO_SVC_SELF, CO_ROW_ERRCTL, co_errctl_obj},
    /* 5: 0x1017 */
    {CO_SVC_CHECK | (CO_NODE_GUARDING ? CO_SVC_WRITTEN : 0U) | CO_SVC_SELF, CO_ROW_ERRCTL,
     co_hb_prod_obj},
    /* 6: 0x1010, 0x1011 (without storage a check that refuses the commands) */
    {CO_STORAGE ? CO_SVC_COMMIT : (CO_SVC_CHECK | CO_SVC_SELF), CO_ROW_STORE, co_store_obj},
    /* 7: 0x1400..0x1BFF */
    {CO_SVC_CHECK | CO_SVC_WRITTEN, CO_ROW_PDO, co_pdo_obj},
#if CO_TIME
    /* 8: 0x1012 */
    {CO_SVC_CHECK | CO_SVC_WRITTEN, CO_ROW_TIME, co_time_obj},
#endif
#if CO_ERROR_BEHAVIOUR
    /* 8 or 9: 0x1029 */
    {CO_SVC_CHECK, CO_ROW_NMT, co_errbeh_obj},
#endif
};

/* The core objects the services use (co_bind_t; co_node_init binds them,
 * in this order). The others have their places in the RAM image (co_node.h,
 * CO_RAM_*: 0x1001, 0x1003, 0x1005, 0x1007, 0x1014..0x1017, 0x1019). */
#define BIND(index, type, kind, field) \
    {(uint8_t)((index) - 0x1000U), (uint8_t)((uint8_t)(type) | (kind)), \
     (uint16_t)offsetof(co_node_t, field)}
const co_bind_t co_binds[CO_N_BINDS] = {
    /* error control: 0x1016 heartbeat consumers (at most CO_HB_CONSUMERS_MAX
     * of them; read only for entries 1..n_hb_cons), 0x100C / 0x100D life
     * guarding (a build without refuses a device with
     * them) */
    BIND(0x1016U, CO_UNSIGNED32, CO_BIND_LEN_HB, n_hb_cons),
#if CO_NODE_GUARDING
    BIND(0x100CU, CO_UNSIGNED16, CO_BIND_PTR, errctl.guard_time),
    BIND(0x100DU, CO_UNSIGNED8, CO_BIND_PTR, errctl.life_factor),
#else
    BIND(0x100CU, 0U, CO_BIND_NONE, errctl),
    BIND(0x100DU, 0U, CO_BIND_NONE, errctl),
#endif
    /* SYNC: 0x1006 (a period only with the producer) */
#if CO_SYNC_PRODUCER
    BIND(0x1006U, CO_UNSIGNED32, CO_BIND_PTR, sync.period),
#else
    BIND(0x1006U, 0U, CO_BIND_NONE, sync),
#endif
#if CO_TIME
    /* TIME: 0x1012 */
    BIND(0x1012U, CO_UNSIGNED32, CO_BIND_PTR, time.cob),
#else
    BIND(0x1012U, 0U, CO_BIND_NONE, sync),
#endif
#if !CO_ERROR_BEHAVIOUR
    /* error behaviour: 0x1029 (its hook is the NMT service's) */
    BIND(0x1029U, 0U, CO_BIND_NONE, errctl),
#endif
};
