# The real COLMAP 3.8 CLI (Debian's colmap; the library never links it) on five KITTI 00 frames
# from ../shared/data/kitti, read and written by trigrav::colmap (run_colmap_real.cmake). Tests
# colmap_real_database and colmap_real_model_round_trip, label colmap_real; skipped when colmap
# or the frames are missing. About 25 s on 2 cores.
find_program(TRIGRAV_COLMAP_EXECUTABLE colmap)
add_executable(colmap_real_check ${CMAKE_CURRENT_LIST_DIR}/colmap_real_check.cc)
target_link_libraries(colmap_real_check PRIVATE trigrav::colmap trigrav_warnings)
foreach(step database model)
  set(name colmap_real_${step})
  if(step STREQUAL "model")
    set(name colmap_real_model_round_trip)
  endif()
  add_test(NAME ${name}
    COMMAND ${CMAKE_COMMAND} -DSTEP=${step} -DCOLMAP=${TRIGRAV_COLMAP_EXECUTABLE}
      -DCHECKER=$<TARGET_FILE:colmap_real_check> -DKITTI_DIR=${PROJECT_SOURCE_DIR}/../shared/data/kitti
      -DWORK_DIR=${CMAKE_CURRENT_BINARY_DIR}/colmap_real
      -P ${CMAKE_CURRENT_LIST_DIR}/run_colmap_real.cmake)
  set_tests_properties(${name} PROPERTIES
    LABELS colmap_real
    TIMEOUT 300
    SKIP_REGULAR_EXPRESSION "colmap_real test skipped")
endforeach()
# The round trip reuses the database of the first test (one scratch folder: never at once).
set_tests_properties(colmap_real_model_round_trip PROPERTIES DEPENDS colmap_real_database)
set_tests_properties(colmap_real_database colmap_real_model_round_trip PROPERTIES
  RESOURCE_LOCK colmap_real_work_dir)
