# Toolchain file: Cortex-M3 bare metal with Debian's gcc-arm-none-eabi.
# Use: cmake -S . -B build-arm -DCMAKE_TOOLCHAIN_FILE=cmake/arm-none-eabi.cmake
set(CMAKE_SYSTEM_NAME Generic)
set(CMAKE_SYSTEM_PROCESSOR arm)
set(CMAKE_C_COMPILER arm-none-eabi-gcc)
set(CMAKE_ASM_COMPILER arm-none-eabi-gcc)
set(CMAKE_SIZE arm-none-eabi-size)
# The firmware this target builds (targets/cortex-m: the minimal slave and
# the size report). No unit tests: nothing runs them (cmake/cortex-m3-mps2.cmake
# is the Cortex-M3 build that does).
set(CO_FIRMWARE cortex-m)
# Link tests as static libraries: there is no host to run an executable on.
set(CMAKE_TRY_COMPILE_TARGET_TYPE STATIC_LIBRARY)

set(CO_ARM_CPU_FLAGS "-mcpu=cortex-m3 -mthumb")
# Link-time optimisation across the core's modules (fat objects, so that
# arm-none-eabi-size of each object still shows its own code); unused
# sections are dropped at link time.
set(CMAKE_C_FLAGS_INIT "${CO_ARM_CPU_FLAGS} -ffunction-sections -fdata-sections -flto -ffat-lto-objects")
set(CMAKE_C_FLAGS_MINSIZEREL_INIT "-Os -DNDEBUG")
set(CMAKE_EXE_LINKER_FLAGS_INIT "${CO_ARM_CPU_FLAGS} -flto -Wl,--gc-sections --specs=nano.specs --specs=nosys.specs")

set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
