# Toolchain file: 32-bit x86 (i386) Linux with Debian's gcc-i686-linux-gnu.
# The unit tests are linked statically and run natively: x86-64 Linux runs
# i686 programs itself. cmocka comes from source (-DCO_CMOCKA_SOURCE=...,
# tools/test-matrix passes it).
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR i686)
set(CMAKE_C_COMPILER i686-linux-gnu-gcc)
set(CMAKE_EXE_LINKER_FLAGS_INIT "-static")
set(CO_TESTS_RUN_ON_HOST ON)

set(CMAKE_FIND_ROOT_PATH /usr/i686-linux-gnu)
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
