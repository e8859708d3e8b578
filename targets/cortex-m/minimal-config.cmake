# Build-time options (stack/include/co/co_config.h) of the minimal slave's
# core: it leaves out what the device (minimal-slave.toml) does not use: no
# 0x1010/0x1011, no TIME, no SYNC producer, no error behaviour 0x1029, no
# value limits, no personality deviations (CO_PERSONALITY=0), no LSS, 4 heartbeat consumers. The Cortex-M3 image and tests/unit/test_lean.c use it.
set(CO_MINIMAL_CONFIG
  CO_STORAGE=0
  CO_TIME=0
  CO_SYNC_PRODUCER=0
  CO_ERROR_BEHAVIOUR=0
  CO_LIMITS=0
  CO_PERSONALITY=0
  CO_LSS=0
  CO_HB_CONSUMERS_MAX=4U)
