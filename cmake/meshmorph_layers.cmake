# SPDX-License-Identifier: MIT
# meshmorph_add_layer(<layer> DEPENDS ... [PRIVATE_DEPENDS ...]) builds src/<layer>/*.cpp with
# the public headers of include/meshmorph/<layer> into meshmorph_<layer> (alias meshmorph::<layer>).

set(MESHMORPH_WARNINGS -Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wno-sign-conversion)
# GCC 12 at -O3 reports false array-bounds / stringop overflows inside std::sort and
# std::vector (GCC bugs 105651, 106199); keep them visible as warnings, not errors.
if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
  list(APPEND MESHMORPH_WARNINGS -Wno-error=array-bounds -Wno-error=stringop-overflow -Wno-error=restrict)
endif()
if(PROJECT_IS_TOP_LEVEL)
  list(APPEND MESHMORPH_WARNINGS -Werror)
endif()

function(meshmorph_add_layer layer)
  cmake_parse_arguments(ARG "" "" "DEPENDS;PRIVATE_DEPENDS" ${ARGN})
  file(GLOB sources CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/src/${layer}/*.cpp)
  file(GLOB_RECURSE headers CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/include/meshmorph/${layer}/*.h)
  set(target meshmorph_${layer})
  add_library(${target} STATIC ${sources})
  add_library(meshmorph::${layer} ALIAS ${target})
  target_sources(${target} PUBLIC FILE_SET HEADERS BASE_DIRS ${PROJECT_SOURCE_DIR}/include FILES ${headers})
  target_include_directories(${target} PRIVATE ${PROJECT_SOURCE_DIR}/src)
  target_compile_features(${target} PUBLIC cxx_std_20)
  target_compile_options(${target} PRIVATE ${MESHMORPH_WARNINGS})
  set_target_properties(${target} PROPERTIES POSITION_INDEPENDENT_CODE ON EXPORT_NAME ${layer})
  target_link_libraries(${target} PUBLIC ${ARG_DEPENDS} PRIVATE ${ARG_PRIVATE_DEPENDS})
  install(TARGETS ${target} EXPORT meshmorphTargets ARCHIVE DESTINATION lib FILE_SET HEADERS DESTINATION include)
endfunction()

# meshmorph_add_test(<layer> [LIBS ...] [SLOW <gtest filter>]) builds tests/<layer>/*_test.cpp into
# test_meshmorph_<layer>; its tests get the label "unit", and those that match SLOW (a gtest
# filter, "Suite.Name:Suite.*") "slow" too: they are discovered apart (TEST_FILTER).
function(meshmorph_add_test layer)
  cmake_parse_arguments(ARG "" "SLOW" "LIBS" ${ARGN})
  file(GLOB sources CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/tests/${layer}/*_test.cpp)
  if(NOT sources)
    return()
  endif()
  set(target test_meshmorph_${layer})
  add_executable(${target} ${sources})
  target_include_directories(${target} PRIVATE ${PROJECT_SOURCE_DIR}/tests ${PROJECT_SOURCE_DIR}/src)
  target_link_libraries(${target} PRIVATE meshmorph::${layer} ${ARG_LIBS} GTest::gtest GTest::gtest_main)
  target_compile_options(${target} PRIVATE ${MESHMORPH_WARNINGS})
  target_compile_definitions(${target} PRIVATE MESHMORPH_TEST_DATA="${PROJECT_SOURCE_DIR}/tests/data")
  # The tests call the library, which sets no wait policy (the meshmorph executable does): with
  # ctest -j2, libgomp's spinning threads of one test kept the other's paused, and the whole
  # suite took 72 s instead of 39 s on 2 cores (bench/README.md, "Threads on a shared machine").
  set(env ENVIRONMENT OMP_WAIT_POLICY=passive)
  if(ARG_SLOW)
    gtest_discover_tests(${target} TEST_FILTER "-${ARG_SLOW}" PROPERTIES LABELS unit ${env} DISCOVERY_TIMEOUT 60)
    # Discovery cannot carry a list-valued property: the labels are set by ctest, after it.
    gtest_discover_tests(${target} TEST_FILTER "${ARG_SLOW}" TEST_LIST ${target}_slow PROPERTIES ${env}
                         DISCOVERY_TIMEOUT 60)
    set(labels ${CMAKE_CURRENT_BINARY_DIR}/${target}_slow_labels.cmake)
    file(WRITE ${labels} "if(${target}_slow)\n  set_tests_properties(\${${target}_slow} PROPERTIES LABELS \"unit;slow\")\nendif()\n")
    set_property(DIRECTORY APPEND PROPERTY TEST_INCLUDE_FILES ${labels})
  else()
    gtest_discover_tests(${target} PROPERTIES LABELS unit ${env} DISCOVERY_TIMEOUT 60)
  endif()
endfunction()
