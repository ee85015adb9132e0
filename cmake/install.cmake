# `cmake --install build --prefix P` installs the library, the public headers (include/afemp/),
# the `afemp` command, a CMake package (find_package(afemp CONFIG) -> afemp::afemp) and a
# pkg-config file. A static libafemp carries its dependencies as link-only usage
# requirements, which afempConfig.cmake finds again.
include(CMakePackageConfigHelpers)
set(AFEMP_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/afemp)

install(TARGETS afemp EXPORT afempTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/afemp DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(EXPORT afempTargets NAMESPACE afemp:: DESTINATION ${AFEMP_CMAKE_DIR})

configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/afempConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/afempConfig.cmake
                              INSTALL_DESTINATION ${AFEMP_CMAKE_DIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/afempConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/afempConfig.cmake ${PROJECT_BINARY_DIR}/afempConfigVersion.cmake
        DESTINATION ${AFEMP_CMAKE_DIR})

# pkg-config: Libs.private and Requires.private are what a static link adds.
if(AFEMP_OPENMP)
  set(AFEMP_PC_OPENMP ${OpenMP_CXX_FLAGS})
endif()
configure_file(${PROJECT_SOURCE_DIR}/cmake/afemp.pc.in ${PROJECT_BINARY_DIR}/afemp.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/afemp.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
