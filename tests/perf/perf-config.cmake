# Build-time options (stack/include/co/co_config.h) of the feature sets the
# comparison with CANopenNode uses (../shared/perf-reference.md), the same
# as tools/bench-size's (COMMON, SETS):
#   SEG: NMT, heartbeat producer and 8 consumers, SDO expedited + segmented,
#        4+4 PDO, SYNC consumer, EMCY; no block SDO, guarding, LSS, TIME,
#        SYNC producer, storage, error behaviour, limits or options (but
#        CO_OPT_SDO_NO_BLOCK, which a device without block transfer has), no
#        TPDO remote requests (CANopenNode v4 has none), no bit-granular PDO
#        mapping (CANopenNode v4's default CO_CONFIG_PDO leaves out
#        CO_CONFIG_PDO_BITWISE_MAPPING: whole bytes only), no TPDO change
#        detection (CANopenNode v4's CO_TPDO_process compares no data: a
#        TPDO goes out on the application's request, its event timer and
#        once when it becomes valid in Operational);
#   BLK: SEG with SDO block transfer.
set(CO_PERF_COMMON_CONFIG
  CO_NODE_GUARDING=0
  CO_TIME=0
  CO_SYNC_PRODUCER=0
  CO_STORAGE=0
  CO_LSS=0
  CO_ERROR_BEHAVIOUR=0
  CO_LIMITS=0
  CO_HB_CONSUMERS_MAX=8U
  CO_PDO_RTR=0
  CO_PDO_BITWISE=0
  CO_TPDO_CHANGE=0)
set(CO_PERF_SEG_CONFIG ${CO_PERF_COMMON_CONFIG} CO_SDO_BLOCK=0 CO_PERSONALITY=0)
set(CO_PERF_BLK_CONFIG ${CO_PERF_COMMON_CONFIG} CO_SDO_BLOCK=1 CO_PERSONALITY=0)
