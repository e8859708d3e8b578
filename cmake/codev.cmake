# co_device(<name> <description.toml> [CORE <core library>])
#
# Runs the object-dictionary generator (tools/odgen) at build time on a device
# description and defines the static library codev_<name> (the generated const
# dictionary, linked with the core: canopen::stack, or a core built by
# co_core() with other build-time options). The same file is installed with
# the package (find_package(canopen-stack) includes it), so an outside project
# generates its own devices from its own descriptions; it also works from a
# parent project that added this one with add_subdirectory.
# Outputs go to ${CMAKE_BINARY_DIR}/codev/<name>/:
#   <cname>.h/.c   the dictionary (<cname> = <name> with '-' -> '_')
#   <name>.eds     CiA 306 electronic data sheet
#   <name>.md      object table
# They are build outputs, never committed. A mistake in the description stops
# the build with "<file>: error: object 0xIIII sub S: <problem>".
#
# Python: the repository's .venv/bin/python if it exists, else python3 (>= 3.11,
# for tomllib); override with -DCO_PYTHON=... . The generator needs only the
# standard library.
#
# Where the generator and the core's co_node.h are: in the source tree, or,
# installed, CO_ODGEN_DIR and CO_CORE_HEADER set by canopen-stackConfig.cmake.
# They are kept as global properties so that co_device() works from any
# directory (a parent project's too).

get_filename_component(CO_REPO_ROOT "${CMAKE_CURRENT_LIST_DIR}/.." ABSOLUTE)
if(NOT CO_ODGEN_DIR)
  set(CO_ODGEN_DIR "${CO_REPO_ROOT}/tools/odgen")
  set(CO_CORE_HEADER "${CO_REPO_ROOT}/stack/include/co/co_node.h")
endif()
if(NOT CO_PYTHON)
  if(EXISTS "${CO_REPO_ROOT}/.venv/bin/python")
    set(CO_PYTHON "${CO_REPO_ROOT}/.venv/bin/python")
  else()
    find_package(Python3 3.11 REQUIRED COMPONENTS Interpreter)
    set(CO_PYTHON "${Python3_EXECUTABLE}")
  endif()
endif()
set(CO_ODGEN "${CO_ODGEN_DIR}/odgen.py")
file(GLOB CO_ODGEN_SOURCES CONFIGURE_DEPENDS "${CO_ODGEN_DIR}/*.py")
set_property(GLOBAL PROPERTY CO_PYTHON "${CO_PYTHON}")
set_property(GLOBAL PROPERTY CO_ODGEN "${CO_ODGEN}")
set_property(GLOBAL PROPERTY CO_ODGEN_SOURCES "${CO_ODGEN_SOURCES}")
set_property(GLOBAL PROPERTY CO_CORE_HEADER "${CO_CORE_HEADER}")

function(co_device name toml)
  cmake_parse_arguments(PARSE_ARGV 2 arg "" "CORE" "")
  if(NOT arg_CORE AND TARGET canopen::stack)
    set(arg_CORE canopen::stack)
  elseif(NOT arg_CORE)
    set(arg_CORE costack)     # a project that defines the core target itself
  endif()
  get_property(python GLOBAL PROPERTY CO_PYTHON)
  get_property(odgen GLOBAL PROPERTY CO_ODGEN)
  get_property(odgen_sources GLOBAL PROPERTY CO_ODGEN_SOURCES)
  get_property(core_header GLOBAL PROPERTY CO_CORE_HEADER)
  get_filename_component(core_dir "${core_header}" DIRECTORY)
  get_filename_component(toml "${toml}" ABSOLUTE BASE_DIR "${CMAKE_CURRENT_SOURCE_DIR}")
  string(MAKE_C_IDENTIFIER "${name}" cname)
  set(out "${CMAKE_BINARY_DIR}/codev/${name}")
  set(products "${out}/${cname}.c" "${out}/${cname}.h" "${out}/${name}.eds" "${out}/${name}.md")
  # a description that includes another (include = "base.toml") depends on it
  set(included)
  file(STRINGS "${toml}" inc_lines REGEX "^include[ \t]*=")
  if(inc_lines)
    set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS "${toml}")
    get_filename_component(tdir "${toml}" DIRECTORY)
    foreach(line IN LISTS inc_lines)
      string(REGEX REPLACE "^include[ \t]*=[ \t]*\"([^\"]+)\".*" "\\1" inc "${line}")
      list(APPEND included "${tdir}/${inc}")
    endforeach()
  endif()
  add_custom_command(
    OUTPUT ${products}
    COMMAND "${python}" "${odgen}" --base "${name}" --out "${out}"
            "--build=$<JOIN:$<TARGET_PROPERTY:${arg_CORE},INTERFACE_COMPILE_DEFINITIONS>,$<COMMA>>"
            "--build-header=$<TARGET_PROPERTY:${arg_CORE},CO_CONFIG_FILE>"
            "${toml}"
    DEPENDS "${toml}" ${included} ${odgen_sources} "${core_header}" "${core_dir}/co_config.h"
    COMMENT "odgen: ${name} (C dictionary, EDS, object table)"
    VERBATIM)
  add_library(codev_${name} STATIC "${out}/${cname}.c" "${out}/${cname}.h")
  target_include_directories(codev_${name} PUBLIC "${out}")
  target_link_libraries(codev_${name} PUBLIC ${arg_CORE})
  target_compile_options(codev_${name} PRIVATE ${CO_WARNINGS})
  # One target owns the generator run (EDS and table are built with 'all' even
  # though nothing links them); the library waits for it, so the command never
  # runs twice in parallel.
  add_custom_target(codev_${name}_files ALL DEPENDS ${products})
  add_dependencies(codev_${name} codev_${name}_files)
endfunction()
