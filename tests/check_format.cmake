# Fails if any C++ file of the repository differs from its .clang-format formatting.
#   cmake -DCLANG_FORMAT=<clang-format> -DSOURCE_DIR=<repository> -P check_format.cmake
file(GLOB_RECURSE files RELATIVE ${SOURCE_DIR}
  ${SOURCE_DIR}/initializers/*.h ${SOURCE_DIR}/initializers/*.cc
  ${SOURCE_DIR}/factors/*.h ${SOURCE_DIR}/factors/*.cc
  ${SOURCE_DIR}/ba/*.h ${SOURCE_DIR}/ba/*.cc
  ${SOURCE_DIR}/examples/*.h ${SOURCE_DIR}/examples/*.cc
  ${SOURCE_DIR}/tests/*.h ${SOURCE_DIR}/tests/*.cc)
list(LENGTH files count)
execute_process(COMMAND ${CLANG_FORMAT} --dry-run --Werror ${files}
  WORKING_DIRECTORY ${SOURCE_DIR} RESULT_VARIABLE result ERROR_VARIABLE diagnostics)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "${diagnostics}\nnot formatted (apply: clang-format -i <file>); ${count} files checked")
endif()
message(STATUS "${count} files formatted")
