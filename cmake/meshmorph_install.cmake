# SPDX-License-Identifier: MIT
# cmake --install: the executable, the static layers with their headers, and the package
# configuration of find_package(meshmorph) (cmake/meshmorphConfig.cmake.in) in lib/cmake/meshmorph.
include(CMakePackageConfigHelpers)
install(TARGETS meshmorph_exe RUNTIME DESTINATION bin)
install(TARGETS meshmorph EXPORT meshmorphTargets)
install(EXPORT meshmorphTargets NAMESPACE meshmorph:: DESTINATION lib/cmake/meshmorph)
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/meshmorphConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/meshmorphConfig.cmake INSTALL_DESTINATION lib/cmake/meshmorph)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/meshmorphConfigVersion.cmake COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/meshmorphConfig.cmake ${PROJECT_BINARY_DIR}/meshmorphConfigVersion.cmake
              ${PROJECT_SOURCE_DIR}/cmake/find_cholmod.cmake ${PROJECT_SOURCE_DIR}/cmake/find_petsc.cmake
              ${PROJECT_SOURCE_DIR}/cmake/find_cgns_exodus.cmake
        DESTINATION lib/cmake/meshmorph)

if(MESHMORPH_BUILD_TESTS)
  # A program outside the tree built against the installed package (a few seconds).
  add_test(NAME install.find_package
           COMMAND ${CMAKE_COMMAND} -DBUILD=${PROJECT_BINARY_DIR} -DSOURCE=${PROJECT_SOURCE_DIR}
                   -DMESH=${PROJECT_SOURCE_DIR}/tests/data/annulus_coarse.msh "-DEXPECT=^196 nodes, 332 cells, 0 inverted"
                   -DWORK=${PROJECT_BINARY_DIR}/install_check -P ${PROJECT_SOURCE_DIR}/cmake/check_install.cmake)
  set_tests_properties(install.find_package PROPERTIES LABELS install)
endif()
