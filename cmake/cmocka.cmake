# cotest_cmocka: the cmocka library every unit test links (and the target's
# test runtime, cotest_runtime, with it).
#
# On the host: Debian's libcmocka-dev (pkg-config). For another CPU:
# -DCO_CMOCKA_SOURCE=<dir> names cmocka's source tree, unpacked from Debian's
# source package by tools/setup (.cache/cmocka/cmocka-<version>); its one
# source file is compiled here with the target's compiler as a static
# library, configured for the target (byte order, pointer size, and what its
# C library has: glibc, or newlib on a microcontroller).
#
# cotest_runtime: what a test program needs to run on the target besides
# cmocka: nothing on Linux; on a microcontroller the start-up code and link
# options the toolchain file names (CO_TEST_RUNTIME_SOURCES,
# CO_TEST_RUNTIME_LINK_OPTIONS, which pull the start-up code in with -u).
if(CO_TEST_RUNTIME_SOURCES)
  add_library(cotest_runtime STATIC ${CO_TEST_RUNTIME_SOURCES})
  target_compile_options(cotest_runtime PRIVATE ${CO_WARNINGS})
  target_link_options(cotest_runtime INTERFACE ${CO_TEST_RUNTIME_LINK_OPTIONS})
else()
  add_library(cotest_runtime INTERFACE)
endif()

if(CO_CMOCKA_SOURCE)
  if(NOT EXISTS "${CO_CMOCKA_SOURCE}/src/cmocka.c")
    message(FATAL_ERROR "CO_CMOCKA_SOURCE=${CO_CMOCKA_SOURCE}: no src/cmocka.c (tools/setup unpacks it)")
  endif()
  add_library(cotest_cmocka STATIC "${CO_CMOCKA_SOURCE}/src/cmocka.c")
  target_include_directories(cotest_cmocka SYSTEM PUBLIC "${CO_CMOCKA_SOURCE}/include")
  set(defs HAVE_SIGNAL_H HAVE_INTTYPES_H HAVE_STRINGS_H HAVE_SETJMP_H
           WORDS_SIZEOF_VOID_P=${CMAKE_SIZEOF_VOID_P})
  if(CMAKE_C_BYTE_ORDER STREQUAL "BIG_ENDIAN")
    list(APPEND defs WORDS_BIGENDIAN=1)
  endif()
  if(CMAKE_SYSTEM_NAME STREQUAL "Linux")
    list(APPEND defs _GNU_SOURCE HAVE_MALLOC_H HAVE_SIGLONGJMP HAVE_STRSIGNAL
                     HAVE_STRUCT_TIMESPEC HAVE_CLOCK_GETTIME HAVE_CLOCK_REALTIME
                     HAVE_GCC_THREAD_LOCAL_STORAGE)
  endif()
  target_compile_definitions(cotest_cmocka PRIVATE ${defs})
  # third-party code: its own dialect, none of the project's warnings
  set_target_properties(cotest_cmocka PROPERTIES C_EXTENSIONS ON)
  target_compile_options(cotest_cmocka PRIVATE -w)
else()
  find_package(PkgConfig REQUIRED)
  pkg_check_modules(CMOCKA REQUIRED IMPORTED_TARGET cmocka)
  add_library(cotest_cmocka INTERFACE)
  target_link_libraries(cotest_cmocka INTERFACE PkgConfig::CMOCKA)
endif()
target_link_libraries(cotest_cmocka INTERFACE cotest_runtime)
