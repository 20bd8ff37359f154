# cmake -DBUILD_DIR=... -DOUTSIDE_DIR=... -DWORK_DIR=... -DDATA_DIR=... -P run_install_test.cmake
# Installs the build tree into a fresh prefix, then builds and runs an outside project
# against it with find_package(kiri).
file(REMOVE_RECURSE "${WORK_DIR}")
function(step)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGN}\n${out}\n${err}")
  endif()
  message(STATUS "${out}")
endfunction()
step(${CMAKE_COMMAND} --install "${BUILD_DIR}" --prefix "${WORK_DIR}/prefix")
step(${CMAKE_COMMAND} -S "${OUTSIDE_DIR}" -B "${WORK_DIR}/build" -DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix
     -DCMAKE_BUILD_TYPE=Release)
step(${CMAKE_COMMAND} --build "${WORK_DIR}/build")
step("${WORK_DIR}/build/outside")
# The installed tool finds its shared libraries through its RUNPATH ($ORIGIN/../lib), with the
# build tree out of the way.
step(${CMAKE_COMMAND} -E env --unset=LD_LIBRARY_PATH "${WORK_DIR}/prefix/bin/kiri" --version)
execute_process(COMMAND "${WORK_DIR}/prefix/bin/kiri" info "${DATA_DIR}/terrains/jacksboro_fault_dem.tif"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT out MATCHES "403 x 344 cells")
  message(FATAL_ERROR "installed kiri info failed (${rc}):\n${out}\n${err}")
endif()
