# The help of every tool (examples/common/tool_flags.h): --help and --helpshort list the tool's own
# flags, not glog's and gflags', --helpfull every flag, doubles with the fewest digits that read
# back the same (0.9999, not gflags' 0.99990000000000001); exit status 0 (run_help_test.cmake).
#   trigrav_add_help_test(<target> <one of its flags> [<regex the --help output must match>])
# adds the ctest <target>_help when <target> is built (the regex has no newline: it is passed on
# the command line).
set(TRIGRAV_RUN_HELP_TEST ${CMAKE_CURRENT_LIST_DIR}/run_help_test.cmake)

function(trigrav_add_help_test target own_flag)
  if(NOT TARGET ${target})
    return()
  endif()
  set(expect "")
  if(ARGC GREATER 2)
    set(expect "-DEXPECT=${ARGV2}")
  endif()
  add_test(NAME ${target}_help
    COMMAND ${CMAKE_COMMAND} -DEXE=$<TARGET_FILE:${target}> -DOWN_FLAG=${own_flag} ${expect}
      -P ${TRIGRAV_RUN_HELP_TEST})
  set_tests_properties(${target}_help PROPERTIES LABELS help TIMEOUT 120)
endfunction()

trigrav_add_help_test(initialize_and_refine_synthetic threshold_px)
trigrav_add_help_test(paper_experiments output_dir)
trigrav_add_help_test(minimal_solver_accuracy focal_px)
# 1e-6, not 9.9999999999999995e-07.
trigrav_add_help_test(solver_stability found_deg "default: 1e-06[^0-9]")
trigrav_add_help_test(verdict_matrix min_inlier_ratio)
trigrav_add_help_test(covariance_calibration threshold_px)
trigrav_add_help_test(peer_comparison accuracy_threshold_px)
trigrav_add_help_test(make_gravity_csv poses_path)
trigrav_add_help_test(triplet_initializer threshold_px)
trigrav_add_help_test(gravity_bundle_adjuster input_path)
# The RANSAC confidence, 0.9999.
trigrav_add_help_test(kitti_triplets confidence
  "-confidence \\([^)]*\\)[^-]*type: double[^-]*default: 0\\.9999[^0-9]")
trigrav_add_help_test(gravity_pays frames)
