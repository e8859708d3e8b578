# co_device(<name> <description.toml> [CORE <core library>])
#
# Runs the object-dictionary generator (tools/odgen) at build time on a device
# description and defines the static library codev_<name> (the generated const
# dictionary, linked with the core: costack, or a core built by co_core() with
# other build-time options). Outputs go to ${CMAKE_BINARY_DIR}/codev/<name>/:
#   <cname>.h/.c   the dictionary (<cname> = <name> with '-' -> '_')
#   <name>.eds     CiA 306 electronic data sheet
#   <name>.md      object table
# They are build outputs, never committed. A mistake in the description stops
# the build with "<file>: error: object 0xIIII sub S: <problem>".
#
# Python: ${CMAKE_SOURCE_DIR}/.venv/bin/python if it exists, else python3 (>= 3.11,
# for tomllib); override with -DCO_PYTHON=... . The generator needs only the
# standard library.

if(NOT CO_PYTHON)
  if(EXISTS "${CMAKE_SOURCE_DIR}/.venv/bin/python")
    set(CO_PYTHON "${CMAKE_SOURCE_DIR}/.venv/bin/python")
  else()
    find_package(Python3 3.11 REQUIRED COMPONENTS Interpreter)
    set(CO_PYTHON "${Python3_EXECUTABLE}")
  endif()
endif()

get_filename_component(CO_REPO_ROOT "${CMAKE_CURRENT_LIST_DIR}/.." ABSOLUTE)
set(CO_ODGEN "${CO_REPO_ROOT}/tools/odgen/odgen.py")
file(GLOB CO_ODGEN_SOURCES CONFIGURE_DEPENDS "${CO_REPO_ROOT}/tools/odgen/*.py")

function(co_device name toml)
  cmake_parse_arguments(PARSE_ARGV 2 arg "" "CORE" "")
  if(NOT arg_CORE)
    set(arg_CORE costack)
  endif()
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
    COMMAND "${CO_PYTHON}" "${CO_ODGEN}" --base "${name}" --out "${out}"
            "--build=$<JOIN:$<TARGET_PROPERTY:${arg_CORE},INTERFACE_COMPILE_DEFINITIONS>,$<COMMA>>"
            "${toml}"
    DEPENDS "${toml}" ${included} ${CO_ODGEN_SOURCES} "${CO_REPO_ROOT}/stack/include/co/co_node.h"
            "${CO_REPO_ROOT}/stack/include/co/co_config.h"
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
