# Runs the tool EXE with --help, --helpshort and --helpfull (help_tests.cmake) and fails unless each
# exits with status 0 and prints on stdout the usage line and the tool's own flag -OWN_FLAG, and no
# number with 12 or more decimals (gflags prints doubles with %.17g: 0.99990000000000001). --help
# and --helpshort must not list flags of other files (glog's -logtostderr, gflags' -flagfile),
# --helpfull must list gflags' -flagfile. EXPECT, when given, is one more regex the --help output
# must match.
get_filename_component(tool ${EXE} NAME)
string(REPEAT "[0-9]" 12 twelve_digits)  # CMake's regex has no {n}
foreach(help_flag --help --helpshort --helpfull)
  execute_process(COMMAND ${EXE} ${help_flag}
    RESULT_VARIABLE status OUTPUT_VARIABLE output ERROR_VARIABLE error TIMEOUT 60)
  if(NOT status STREQUAL "0")
    message(FATAL_ERROR "${tool} ${help_flag}: exit status '${status}', want 0\nstderr:\n${error}")
  endif()
  set(want "^${tool}: [^\n]+\n" "\n +-${OWN_FLAG} \\(")
  set(refuse "\\.${twelve_digits}")
  if(help_flag STREQUAL "--helpfull")
    list(APPEND want "\n +-flagfile \\(")
  else()
    list(APPEND refuse "-logtostderr \\(" "-flagfile \\(")
    if(help_flag STREQUAL "--help" AND DEFINED EXPECT)
      list(APPEND want "${EXPECT}")
    endif()
  endif()
  foreach(regex IN LISTS want)
    if(NOT output MATCHES "${regex}")
      message(FATAL_ERROR "${tool} ${help_flag}: stdout does not match '${regex}':\n${output}")
    endif()
  endforeach()
  foreach(regex IN LISTS refuse)
    if(output MATCHES "${regex}")
      message(FATAL_ERROR "${tool} ${help_flag}: stdout matches '${regex}' "
        "('${CMAKE_MATCH_0}'):\n${output}")
    endif()
  endforeach()
endforeach()
message(STATUS "${tool}: --help, --helpshort and --helpfull as wanted")
