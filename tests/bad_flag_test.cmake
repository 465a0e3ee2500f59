# trigrav_add_bad_flag_test(<name> <target> <regex> <args>...)
#
# Adds the ctest <name>: runs the example program <target> with <args> and passes only if it exits
# with status 2 (trigrav::examples::kBadFlagExitCode, examples/common/require_flag.h) and its stderr
# contains "error: " followed by a match of <regex>. A crash, an abort (glog CHECK), a timeout or
# acceptance of the flag fails the test. Nothing is added when <target> is not built. One line per
# bad flag, e.g.
#   trigrav_add_bad_flag_test(synthetic_triplets_negative_trials synthetic_triplets
#                             "--trials must be positive" --trials=-1)
# Arguments must not contain ';'.
set(TRIGRAV_RUN_BAD_FLAG_TEST ${CMAKE_CURRENT_LIST_DIR}/run_bad_flag_test.cmake)

function(trigrav_add_bad_flag_test name target regex)
  if(NOT TARGET ${target})
    return()
  endif()
  set(arg_definitions "")
  set(num_args 0)
  foreach(arg IN LISTS ARGN)
    list(APPEND arg_definitions "-DARG${num_args}=${arg}")
    math(EXPR num_args "${num_args} + 1")
  endforeach()
  add_test(NAME ${name}
    COMMAND ${CMAKE_COMMAND} -DEXE=$<TARGET_FILE:${target}> "-DREGEX=${regex}"
      -DNUM_ARGS=${num_args} ${arg_definitions} -P ${TRIGRAV_RUN_BAD_FLAG_TEST})
  set_tests_properties(${name} PROPERTIES LABELS bad_flags TIMEOUT 120)
endfunction()
