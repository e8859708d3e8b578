# Toolchain file: the unit tests on a Cortex-M3, run on QEMU's MPS2 AN385
# board (qemu-system-arm, tools/qemu-mps2) with semihosting: Debian's
# gcc-arm-none-eabi with newlib (full printf) and librdimon for the C
# library's I/O, the start-up code and linker script in tests/support/mps2.
# No firmware (cmake/arm-none-eabi.cmake builds that). cmocka comes from
# source (-DCO_CMOCKA_SOURCE=..., tools/test-matrix passes it).
set(CMAKE_SYSTEM_NAME Generic)
set(CMAKE_SYSTEM_PROCESSOR arm)
set(CMAKE_C_COMPILER arm-none-eabi-gcc)
set(CMAKE_TRY_COMPILE_TARGET_TYPE STATIC_LIBRARY)

get_filename_component(_co_root "${CMAKE_CURRENT_LIST_DIR}/.." ABSOLUTE)
set(CMAKE_C_FLAGS_INIT "-mcpu=cortex-m3 -mthumb -ffunction-sections -fdata-sections")
set(CMAKE_EXE_LINKER_FLAGS_INIT "-mcpu=cortex-m3 -mthumb --specs=rdimon.specs -nostartfiles -Wl,--gc-sections -T${_co_root}/tests/support/mps2/mps2-an385.ld")
set(CMAKE_CROSSCOMPILING_EMULATOR "${_co_root}/tools/qemu-mps2")
set(CO_TEST_RUNTIME_SOURCES "${_co_root}/tests/support/mps2/mps2_start.c")
set(CO_TEST_RUNTIME_LINK_OPTIONS "-Wl,-u,co_mps2_vectors")

set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
