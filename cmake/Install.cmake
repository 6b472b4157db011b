# `cmake --install`: headers, the three libraries, the technique shaders and a CMake package
# (ShadowPortConfig.cmake) exporting ShadowPort::rhi, ShadowPort::scene and
# ShadowPort::techniques with their dependencies as usage requirements.
include(CMakePackageConfigHelpers)

set(SP_PACKAGE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/ShadowPort)

install(TARGETS shadowport_rhi sp_scene sp_techniques EXPORT ShadowPortTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
# Public headers only: rhi/src, techniques/<name>/ and scene/procedural stay private.
install(DIRECTORY ${PROJECT_SOURCE_DIR}/rhi/include/sp ${PROJECT_SOURCE_DIR}/scene/include/sp
                  ${PROJECT_SOURCE_DIR}/techniques/include/sp
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR} FILES_MATCHING PATTERN "*.h")
install(DIRECTORY ${PROJECT_SOURCE_DIR}/shaders-hlsl/ DESTINATION ${CMAKE_INSTALL_DATADIR}/shadowport/shaders-hlsl)

install(EXPORT ShadowPortTargets NAMESPACE ShadowPort:: DESTINATION ${SP_PACKAGE_DIR})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/ShadowPortConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/ShadowPortConfig.cmake
                              INSTALL_DESTINATION ${SP_PACKAGE_DIR}
                              PATH_VARS CMAKE_INSTALL_DATADIR)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/ShadowPortConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/ShadowPortConfig.cmake ${PROJECT_BINARY_DIR}/ShadowPortConfigVersion.cmake
        DESTINATION ${SP_PACKAGE_DIR})
