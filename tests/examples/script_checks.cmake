# Shared by the tools' check scripts (check_*.cmake, run with cmake -P): each failed check appends
# its description to `failures`, and report_failures(<name>) ends the script, failing with every
# description, or printing that all passed.
#   expect(<description> <condition...>)          a check on an if() condition
#   expect_match(<description> <text> <regex>)    a regex check; the regex may hold spaces
# $TRIGRAV_KITTI_DIR, when set, replaces KITTI_DIR.
set(failures "")
if(DEFINED ENV{TRIGRAV_KITTI_DIR} AND NOT "$ENV{TRIGRAV_KITTI_DIR}" STREQUAL "")
  set(KITTI_DIR "$ENV{TRIGRAV_KITTI_DIR}")
endif()
macro(expect what)
  if(NOT (${ARGN}))
    list(APPEND failures "${what}")
  endif()
endmacro()
function(expect_match what text regex)
  if(NOT text MATCHES "${regex}")
    set(failures ${failures} "${what}" PARENT_SCOPE)
  endif()
endfunction()
macro(report_failures name)
  if(failures)
    list(JOIN failures "\n  " text)
    message(FATAL_ERROR "${name} checks failed:\n  ${text}")
  endif()
  message("${name}: every check passed")
endmacro()
