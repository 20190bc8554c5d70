# wqmesh: the install test (ctest: install_example). Installs this build to a
# fresh prefix, configures and builds examples/cpp against the installed
# package (find_package(wqmesh CONFIG)), meshes examples/models/spike.off with
# it and checks what it wrote: a Medit file with tets and statistics that say
# the mesh conforms and the run was not stopped.
#   cmake -DBUILD=<build dir> -DSOURCE=<source dir> -DWORK=<scratch dir> -P install_example.cmake
# SPDX-License-Identifier: GPL-3.0-or-later
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGN}\n${out}\n${err}")
  endif()
  set(run_out "${out}" PARENT_SCOPE)
endfunction()
run(${CMAKE_COMMAND} --install ${BUILD} --prefix ${WORK}/prefix)
foreach(f include/wqmesh/wqmesh.h include/wqmesh/version.h lib/libwqmesh.a lib/cmake/wqmesh/wqmeshConfig.cmake)
  if(NOT EXISTS ${WORK}/prefix/${f})
    message(FATAL_ERROR "not installed: ${f}")
  endif()
endforeach()
run(${CMAKE_COMMAND} -S ${SOURCE}/examples/cpp -B ${WORK}/build -DCMAKE_PREFIX_PATH=${WORK}/prefix
    -DCMAKE_BUILD_TYPE=Release)
run(${CMAKE_COMMAND} --build ${WORK}/build)
run(${WORK}/build/wqmesh_example ${SOURCE}/examples/models/spike.off ${WORK}/spike.mesh)
set(stats "${run_out}")
string(JSON conforming GET "${stats}" conforming)
string(JSON stopped GET "${stats}" stopped)
string(JSON tets GET "${stats}" tets)
if(NOT conforming STREQUAL "ON" OR NOT stopped STREQUAL "" OR tets LESS 1)
  message(FATAL_ERROR "examples/cpp: conforming ${conforming}, stopped '${stopped}', ${tets} tets")
endif()
file(READ ${WORK}/spike.mesh mesh)
string(REGEX MATCH "Tetrahedra\n([0-9]+)" _ "${mesh}")
if(NOT CMAKE_MATCH_1 EQUAL tets)
  message(FATAL_ERROR "spike.mesh holds '${CMAKE_MATCH_1}' tets, the statistics say ${tets}")
endif()
message(STATUS "examples/cpp meshed spike.off: ${tets} tets")
file(REMOVE_RECURSE ${WORK})
