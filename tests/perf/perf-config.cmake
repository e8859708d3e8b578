# Build-time options (stack/include/co/co_config.h) of the feature sets the
# comparison with CANopenNode uses (../shared/perf-reference.md):
#   SEG: NMT, heartbeat producer and 8 consumers, SDO expedited + segmented,
#        4+4 PDO, SYNC consumer, EMCY; no block SDO, guarding, LSS, TIME,
#        SYNC producer or storage;
#   BLK: SEG with SDO block transfer.
set(CO_PERF_SEG_CONFIG
  CO_SDO_BLOCK=0
  CO_NODE_GUARDING=0
  CO_LSS=0
  CO_TIME=0
  CO_SYNC_PRODUCER=0
  CO_STORAGE=0)
set(CO_PERF_BLK_CONFIG
  CO_SDO_BLOCK=1
  CO_NODE_GUARDING=0
  CO_LSS=0
  CO_TIME=0
  CO_SYNC_PRODUCER=0
  CO_STORAGE=0)
