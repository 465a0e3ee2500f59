# Runs EXE with ARG0 .. ARG<NUM_ARGS - 1> (see bad_flag_test.cmake) and fails unless it exits with
# status 2 and prints "error: <REGEX>" on stderr.
set(args "")
if(NUM_ARGS GREATER 0)
  math(EXPR last "${NUM_ARGS} - 1")
  foreach(i RANGE ${last})
    list(APPEND args "${ARG${i}}")
  endforeach()
endif()
execute_process(COMMAND ${EXE} ${args}
  RESULT_VARIABLE status OUTPUT_VARIABLE output ERROR_VARIABLE error TIMEOUT 100)
# A signal or a timeout gives a string ("Child aborted", "Segmentation fault", ...), not a number.
if(NOT status STREQUAL "2")
  message(FATAL_ERROR "${EXE} ${args}: exit status '${status}', want 2\nstderr:\n${error}")
endif()
if(NOT error MATCHES "error: ${REGEX}")
  message(FATAL_ERROR "${EXE} ${args}: stderr does not match 'error: ${REGEX}':\n${error}")
endif()
message(STATUS "exit status 2: ${error}")
