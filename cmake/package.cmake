# Install rules and the CMake package (included by the top-level
# CMakeLists.txt when CO_INSTALL is on; off by default in a parent project).
#
#   cmake --install build --prefix /opt/canopen
#
# installs the libraries (targets canopen::stack, canopen::profile,
# canopen::profile_cia402, canopen::profile_cia402_sim,
# canopen::profile_cia402_device, canopen::profile_cia408,
# canopen::profile_cia408_sim, canopen::profile_cia408_device, canopen::port_linux), their headers
# under include/canopen-stack, the object-dictionary generator and co_device()
# (share/canopen-stack/odgen, lib/cmake/canopen-stack/codev.cmake),
# canopen-stackConfig.cmake with its version file, pkg-config files
# (canopen-stack, canopen-stack-cia402, canopen-stack-linux) and, when built,
# the canopen-device daemon. An outside project:
#
#   find_package(canopen-stack 0.1 REQUIRED)
#   co_device(my-io my-io.toml)                  # its own description
#   target_link_libraries(app PRIVATE codev_my-io)
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(CO_PKG_NAME canopen-stack)
set(CO_PKG_CMAKEDIR "${CMAKE_INSTALL_LIBDIR}/cmake/${CO_PKG_NAME}")
set(CO_PKG_INCDIR "${CMAKE_INSTALL_INCLUDEDIR}/${CO_PKG_NAME}")
set(CO_PKG_DATADIR "${CMAKE_INSTALL_DATADIR}/${CO_PKG_NAME}")

set(co_exported costack coprofile co402 co402sim co402dev co408 co408sim co408dev)
set(co_header_dirs stack/include/ profiles/common/include/ profiles/cia402/include/
    profiles/cia408/include/)
if(TARGET coport_linux)
  list(APPEND co_exported coport_linux)
  list(APPEND co_header_dirs port/linux/include/)
endif()
install(TARGETS ${co_exported} EXPORT canopen-stack-targets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        INCLUDES DESTINATION ${CO_PKG_INCDIR})
foreach(d IN LISTS co_header_dirs)
  install(DIRECTORY ${d} DESTINATION ${CO_PKG_INCDIR} FILES_MATCHING PATTERN "*.h")
endforeach()
get_target_property(co_cfg_file costack CO_CONFIG_FILE)
if(co_cfg_file)
  install(FILES ${co_cfg_file} DESTINATION ${CO_PKG_INCDIR})
  get_filename_component(co_cfg_name "${co_cfg_file}" NAME)
  set(CO_PC_CFLAGS "-DCO_CONFIG_HEADER=\\\"${co_cfg_name}\\\"")
endif()
if(TARGET canopen-device)
  install(TARGETS canopen-device RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endif()

# the generator and its CMake function
install(DIRECTORY tools/odgen/ DESTINATION ${CO_PKG_DATADIR}/odgen USE_SOURCE_PERMISSIONS
        FILES_MATCHING PATTERN "*.py" PATTERN "README.md" PATTERN "__pycache__" EXCLUDE)
install(FILES cmake/codev.cmake DESTINATION ${CO_PKG_CMAKEDIR})

install(EXPORT canopen-stack-targets NAMESPACE canopen::
        FILE ${CO_PKG_NAME}-targets.cmake DESTINATION ${CO_PKG_CMAKEDIR})
configure_package_config_file(cmake/canopen-stackConfig.cmake.in
  "${PROJECT_BINARY_DIR}/${CO_PKG_NAME}Config.cmake"
  INSTALL_DESTINATION ${CO_PKG_CMAKEDIR}
  PATH_VARS CO_PKG_INCDIR CO_PKG_DATADIR)
write_basic_package_version_file("${PROJECT_BINARY_DIR}/${CO_PKG_NAME}ConfigVersion.cmake"
  VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES "${PROJECT_BINARY_DIR}/${CO_PKG_NAME}Config.cmake"
              "${PROJECT_BINARY_DIR}/${CO_PKG_NAME}ConfigVersion.cmake"
        DESTINATION ${CO_PKG_CMAKEDIR})

# pkg-config: the core; the CiA 402 profile with its plant; the Linux port
function(co_pkgconfig name description requires libs cflags)
  set(PC_NAME ${name})
  set(PC_DESCRIPTION "${description}")
  set(PC_REQUIRES "${requires}")
  set(PC_LIBS "${libs}")
  set(PC_CFLAGS "${cflags}")
  configure_file(cmake/canopen-stack.pc.in "${PROJECT_BINARY_DIR}/pkgconfig/${name}.pc" @ONLY)
  install(FILES "${PROJECT_BINARY_DIR}/pkgconfig/${name}.pc"
          DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
endfunction()
co_pkgconfig(canopen-stack "CANopen slave stack: the CiA 301 core" "" "-lcostack"
             "${CO_PC_CFLAGS}")
co_pkgconfig(canopen-stack-cia402 "CANopen slave stack: CiA 402 drive profile and plant"
             "canopen-stack" "-lco402dev -lco402 -lco402sim -lcoprofile" "")
co_pkgconfig(canopen-stack-cia408 "CANopen slave stack: CiA 408 valve profile and valve"
             "canopen-stack" "-lco408dev -lco408 -lco408sim -lcoprofile" "")
if(TARGET coport_linux)
  co_pkgconfig(canopen-stack-linux "CANopen slave stack: Linux SocketCAN port"
               "canopen-stack" "-lcoport_linux -pthread" "-D_GNU_SOURCE -pthread")
endif()
