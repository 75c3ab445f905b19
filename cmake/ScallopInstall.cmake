# `cmake --install`: the programs, and the libraries with their headers and a
# package config, so that a project outside this tree can write
#   find_package(Scallop REQUIRED)
#   target_link_libraries(app PRIVATE Scallop::core)      # or Scallop::client
# Static libraries: the config finds their dependencies (CGAL, Boost, FFTW3,
# Protobuf, gRPC) again on the consumer's side.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

install(TARGETS scallopd scallop RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})

set_target_properties(scallop_core PROPERTIES EXPORT_NAME core)
set_target_properties(scallop_proto PROPERTIES EXPORT_NAME proto)
set_target_properties(scallop_proto_conversions PROPERTIES EXPORT_NAME proto_conversions)
set_target_properties(scallop_client PROPERTIES EXPORT_NAME client)
install(TARGETS scallop_core scallop_proto scallop_proto_conversions scallop_client
        EXPORT ScallopTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})

install(DIRECTORY ${PROJECT_SOURCE_DIR}/core/scallop DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
        FILES_MATCHING PATTERN "*.h")
install(DIRECTORY ${PROJECT_BINARY_DIR}/proto/generated/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
        FILES_MATCHING PATTERN "*.h")
install(DIRECTORY ${PROJECT_SOURCE_DIR}/proto/conversions/
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/scallop/conversions FILES_MATCHING PATTERN "*.h")
install(DIRECTORY ${PROJECT_SOURCE_DIR}/client/library/
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/scallop/client FILES_MATCHING PATTERN "*.h")
install(FILES ${PROJECT_SOURCE_DIR}/proto/scallop/v1/scallop.proto
        DESTINATION ${CMAKE_INSTALL_DATADIR}/scallop/proto/scallop/v1)

set(config_dir ${CMAKE_INSTALL_LIBDIR}/cmake/Scallop)
install(EXPORT ScallopTargets NAMESPACE Scallop:: DESTINATION ${config_dir})
configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/ScallopConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/ScallopConfig.cmake
                              INSTALL_DESTINATION ${config_dir})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/ScallopConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/ScallopConfig.cmake
              ${PROJECT_BINARY_DIR}/ScallopConfigVersion.cmake
        DESTINATION ${config_dir})
