# Installs a trigrav build into a scratch prefix, then configures, builds and runs the consumer
# against it:
#   -DTRIGRAV_BINARY_DIR=<build>   the build to install (static or shared libraries, as built)
#   -DPYTHON=<interpreter> -DPYTHON_INSTALL_DIR=<relative folder>   also import the installed
#                                               Python module with that interpreter
file(REMOVE_RECURSE ${WORK_DIR})
function(run)
  execute_process(COMMAND ${ARGV} RESULT_VARIABLE result)
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "failed (${result}): ${ARGV}")
  endif()
endfunction()
run(${CMAKE_COMMAND} --install ${TRIGRAV_BINARY_DIR} --prefix ${WORK_DIR}/prefix)
# The installed headers are the library's: no experiment scaffolding (examples/common/,
# tests/scenes/) and no internals (factors/src/).
foreach(header evaluation/paper_protocol.h evaluation/pooled_errors.h
               evaluation/robust_benchmark_scenes.h evaluation/input_mistakes.h
               factors/point_gauss_newton.h factors/observation_jacobian.h)
  if(EXISTS ${WORK_DIR}/prefix/include/trigrav/${header})
    message(FATAL_ERROR "installed, but not part of the library: include/trigrav/${header}")
  endif()
endforeach()
run(${CMAKE_COMMAND} -S ${CONSUMER_SOURCE_DIR} -B ${WORK_DIR}/build
    -DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix -DCMAKE_BUILD_TYPE=Release
    -DCMAKE_BUILD_RPATH=${WORK_DIR}/prefix/lib)
run(${CMAKE_COMMAND} --build ${WORK_DIR}/build)
run(${WORK_DIR}/build/consumer)
if(EXISTS ${WORK_DIR}/build/consumer_colmap)
  run(${WORK_DIR}/build/consumer_colmap ${WORK_DIR})
endif()
if(PYTHON)
  # The module and its stub in the prefix's site folder: imported from there, a call run.
  set(site ${WORK_DIR}/prefix/${PYTHON_INSTALL_DIR})
  run(${CMAKE_COMMAND} -E env PYTHONPATH=${site} PYTHONDONTWRITEBYTECODE=1 ${PYTHON}
      ${CMAKE_CURRENT_LIST_DIR}/check_python_module.py ${site})
endif()
