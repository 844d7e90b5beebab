# Install rules and the exported CMake package `prtkit` (included by the top-level CMakeLists.txt
# when PRT_INSTALL is ON):
#   find_package(prtkit CONFIG) -> prtkit::runtime (always), prtkit::io (when prt_io was built),
#   prtkit::baker and prtkit::prt-bake (when the baker was built), each when its dependencies are
#   found. Also installs the headers and the pkg-config file prtkit.pc (the runtime only).
include(CMakePackageConfigHelpers)
set(PRT_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/prtkit)

# --- runtime (+ the reader core it links privately, needed by static consumers) ---------------
install(TARGETS prt_runtime prt_formats EXPORT prtkitTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR}
  INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/sdk/include/prt DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
  FILES_MATCHING PATTERN "*.h" PATTERN "*.hpp")  # the C headers and the C++ layer prt.hpp
install(FILES ${PROJECT_BINARY_DIR}/sdk/include/prt/prt_version.h
  DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/prt)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/formats/include/prt/format
  DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/prt FILES_MATCHING PATTERN "*.h")
install(EXPORT prtkitTargets NAMESPACE prtkit:: DESTINATION ${PRT_INSTALL_CMAKEDIR})

# --- prt_io (when built): the C++ helpers for tools and samples, a static library on GLM and stb
set(PRT_INSTALLED_IO OFF)
if(TARGET prt_io)
  set(PRT_INSTALLED_IO ON)
  install(TARGETS prt_io EXPORT prtkitIoTargets
    ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
    INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/runtime/io/include/prt/io
    DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/prt)
  install(EXPORT prtkitIoTargets NAMESPACE prtkit:: DESTINATION ${PRT_INSTALL_CMAKEDIR})
endif()

# --- baker (optional) ---------------------------------------------------------------------------
# The baker is a static library: its private link dependencies become link-only dependencies of
# the imported target, so first-party static libraries it links are exported with it and its
# third-party packages are looked up again by prtkitConfig.cmake.
set(PRT_INSTALLED_BAKER OFF)
if(TARGET prt_baker)
  set(PRT_INSTALLED_BAKER ON)
  # First-party static libraries the baker links, directly or through each other.
  set(baker_targets)
  set(pending prt_baker)
  while(pending)
    list(POP_FRONT pending item)
    if(NOT TARGET ${item})
      continue()
    endif()
    get_target_property(aliased ${item} ALIASED_TARGET)
    if(aliased)
      set(item ${aliased})
    endif()
    get_target_property(imported ${item} IMPORTED)
    get_target_property(type ${item} TYPE)
    if(imported OR item IN_LIST baker_targets OR item MATCHES "^prt_(runtime|formats|io)$"
       OR NOT type MATCHES "STATIC_LIBRARY|INTERFACE_LIBRARY|OBJECT_LIBRARY")
      continue()
    endif()
    list(APPEND baker_targets ${item})
    get_target_property(links ${item} LINK_LIBRARIES)
    get_target_property(interface_links ${item} INTERFACE_LINK_LIBRARIES)
    foreach(link IN LISTS links interface_links)
      string(REGEX REPLACE "^\\$<LINK_ONLY:(.*)>$" "\\1" link "${link}")
      if(TARGET ${link})
        list(APPEND pending ${link})
      endif()
    endforeach()
  endwhile()
  if(TARGET prt-bake)
    list(APPEND baker_targets prt-bake)
  endif()
  install(TARGETS ${baker_targets} EXPORT prtkitBakerTargets
    ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
    LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
    RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR}
    INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/baker/include/prt/baker
    DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/prt)
  if(TARGET prt_formats_writer)
    install(FILES ${PROJECT_SOURCE_DIR}/formats/include/prt/format/blob_writer.hpp
      ${PROJECT_SOURCE_DIR}/formats/include/prt/format/scene_writer.hpp
      DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/prt/format)
  endif()
  install(EXPORT prtkitBakerTargets NAMESPACE prtkit:: DESTINATION ${PRT_INSTALL_CMAKEDIR})
endif()

# --- package config, version file -----------------------------------------------------------
configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/prtkitConfig.cmake.in
  ${PROJECT_BINARY_DIR}/prtkitConfig.cmake
  INSTALL_DESTINATION ${PRT_INSTALL_CMAKEDIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/prtkitConfigVersion.cmake
  VERSION ${PROJECT_VERSION} COMPATIBILITY SameMajorVersion)
install(FILES ${PROJECT_BINARY_DIR}/prtkitConfig.cmake ${PROJECT_BINARY_DIR}/prtkitConfigVersion.cmake
  DESTINATION ${PRT_INSTALL_CMAKEDIR})

# --- pkg-config (runtime only) ----------------------------------------------------------------
get_target_property(PRT_RUNTIME_TYPE prt_runtime TYPE)
if(PRT_RUNTIME_TYPE STREQUAL "STATIC_LIBRARY")
  # A static runtime needs the reader core, zstd and libm at the consumer's link, also without
  # --static: `cc app.c $(pkg-config --cflags --libs prtkit)` must link.
  set(PRT_PC_LIBS "-L\${libdir} -lprt -lprt_formats -lm")
  set(PRT_PC_LIBS_PRIVATE "")
  set(PRT_PC_REQUIRES "Requires: libzstd")
else()
  set(PRT_PC_LIBS "-L\${libdir} -lprt")
  set(PRT_PC_LIBS_PRIVATE "Libs.private: -lm")
  set(PRT_PC_REQUIRES "Requires.private: libzstd")
endif()
configure_file(${CMAKE_CURRENT_LIST_DIR}/prtkit.pc.in ${PROJECT_BINARY_DIR}/prtkit.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/prtkit.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
