# Toolchain file: Cortex-R5 bare metal (ARM state, soft float) with Debian's
# gcc-arm-none-eabi; selects the firmware target for QEMU's xlnx-zcu102
# (targets/zynqmp-r5, port/xlnx-can). The AArch64 start-up of CPU 0 needs
# binutils-aarch64-linux-gnu.
# Use: cmake -S . -B build/r5 -DCMAKE_TOOLCHAIN_FILE=cmake/arm-none-eabi-r5.cmake
set(CMAKE_SYSTEM_NAME Generic)
set(CMAKE_SYSTEM_PROCESSOR arm)
set(CMAKE_C_COMPILER arm-none-eabi-gcc)
set(CMAKE_ASM_COMPILER arm-none-eabi-gcc)
set(CMAKE_SIZE arm-none-eabi-size)
set(CMAKE_TRY_COMPILE_TARGET_TYPE STATIC_LIBRARY)
# the firmware this toolchain builds (top-level CMakeLists: targets/${CO_FIRMWARE})
set(CO_FIRMWARE zynqmp-r5)

set(CO_ARM_CPU_FLAGS "-mcpu=cortex-r5 -marm -mfloat-abi=soft")
set(CMAKE_C_FLAGS_INIT "${CO_ARM_CPU_FLAGS} -ffunction-sections -fdata-sections")
set(CMAKE_ASM_FLAGS_INIT "${CO_ARM_CPU_FLAGS}")
set(CMAKE_C_FLAGS_MINSIZEREL_INIT "-Os -DNDEBUG")
set(CMAKE_EXE_LINKER_FLAGS_INIT "${CO_ARM_CPU_FLAGS} -Wl,--gc-sections --specs=nano.specs --specs=nosys.specs")

set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
