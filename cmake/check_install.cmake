# SPDX-License-Identifier: MIT
# cmake -DBUILD=<build dir> -DSOURCE=<source dir> -DMESH=<mesh> -DEXPECT=<regex> -DWORK=<folder> -P check_install.cmake
# installs the build into WORK/prefix, builds cmake/consumer against it with find_package(meshmorph)
# and runs it on MESH; fails unless its output matches EXPECT.
file(REMOVE_RECURSE ${WORK})
foreach(step IN ITEMS "--install;${BUILD};--prefix;${WORK}/prefix"
                      "-S;${SOURCE}/cmake/consumer;-B;${WORK}/consumer;-G;Ninja;-DCMAKE_BUILD_TYPE=Release;-DCMAKE_PREFIX_PATH=${WORK}/prefix"
                      "--build;${WORK}/consumer")
  execute_process(COMMAND ${CMAKE_COMMAND} ${step} RESULT_VARIABLE failed OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(failed)
    message(FATAL_ERROR "cmake ${step}:\n${out}")
  endif()
endforeach()
execute_process(COMMAND ${WORK}/consumer/consumer ${MESH} RESULT_VARIABLE failed OUTPUT_VARIABLE out ERROR_VARIABLE out)
if(failed OR NOT out MATCHES "${EXPECT}")
  message(FATAL_ERROR "consumer ${MESH}: ${out}")
endif()
message(STATUS "consumer: ${out}")
file(REMOVE_RECURSE ${WORK})
