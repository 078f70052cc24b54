# The installed package: coopmap::core (and, with the simulator, coopmap::sim and
# coopmap::replay), their headers under include/coopmap, the coopmap program, and a package
# config so that another project finds them with find_package(coopmap).
include(CMakePackageConfigHelpers)

set(COOPMAP_CMAKE_DIR "${CMAKE_INSTALL_LIBDIR}/cmake/coopmap")
set(coopmap_exported coopmap_core)
if(COOPMAP_BUILD_SIM)
  list(APPEND coopmap_exported coopmap_sim coopmap_replay)
endif()

install(TARGETS ${coopmap_exported} EXPORT coopmapTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        INCLUDES DESTINATION ${COOPMAP_INSTALL_INCLUDEDIR})
install(DIRECTORY core DESTINATION ${COOPMAP_INSTALL_INCLUDEDIR} FILES_MATCHING PATTERN "*.h")
if(COOPMAP_BUILD_SIM)
  install(DIRECTORY sim DESTINATION ${COOPMAP_INSTALL_INCLUDEDIR} FILES_MATCHING PATTERN "*.h"
          PATTERN runner EXCLUDE)
  install(DIRECTORY robots/replay DESTINATION ${COOPMAP_INSTALL_INCLUDEDIR}/robots
          FILES_MATCHING PATTERN "*.h")
  install(TARGETS coopmap RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endif()

install(EXPORT coopmapTargets NAMESPACE coopmap:: DESTINATION ${COOPMAP_CMAKE_DIR})
configure_package_config_file(cmake/coopmapConfig.cmake.in
                              "${PROJECT_BINARY_DIR}/coopmapConfig.cmake"
                              INSTALL_DESTINATION ${COOPMAP_CMAKE_DIR})
# 0.x: a minor version may change the interface.
write_basic_package_version_file("${PROJECT_BINARY_DIR}/coopmapConfigVersion.cmake"
                                 COMPATIBILITY SameMinorVersion)
install(FILES "${PROJECT_BINARY_DIR}/coopmapConfig.cmake"
              "${PROJECT_BINARY_DIR}/coopmapConfigVersion.cmake"
        DESTINATION ${COOPMAP_CMAKE_DIR})
