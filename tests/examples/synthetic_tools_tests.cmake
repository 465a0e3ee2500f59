# The ctests of the synthetic example tools (examples/initialize_and_refine, examples/experiments),
# each added only when its tool is built. They run the tools, never link them: the default run,
# the quick modes, and the bad flags (bad_flag_tests.cmake; trigrav_add_bad_flag_test comes from
# tests/bad_flag_test.cmake, included before this file). The Google Benchmark programs of
# examples/benchmarks are built, not run.

if(TARGET initialize_and_refine_synthetic)
  # The README's first command: the default run prints its summary and every call succeeds.
  add_test(NAME initialize_and_refine_synthetic_default COMMAND initialize_and_refine_synthetic)
  set_tests_properties(initialize_and_refine_synthetic_default PROPERTIES TIMEOUT 120
    PASS_REGULAR_EXPRESSION "RANSAC estimate \\(raw\\) .*refined .*inliers per scene.*time per call.*failures: 0 of 20 calls")
  # The raw-vs-refined sweep end to end (solvers, RANSAC, Ceres, CSV) on three settings.
  add_test(NAME initialize_and_refine_synthetic_sweep_quick
    COMMAND initialize_and_refine_synthetic --experiment=sweep --quick
      --output=${CMAKE_CURRENT_BINARY_DIR}/sweep_quick.csv)
  # The equal-sample-size experiment at 0 and 1 px: columns, finite errors, tiny noise-free errors
  # (check_paper_experiments.cmake fails otherwise).
  add_test(NAME initialize_and_refine_synthetic_sample20_quick
    COMMAND ${CMAKE_COMMAND}
      -DEXE=$<TARGET_FILE:initialize_and_refine_synthetic> -DEXPERIMENT=sample20
      -DDIR=${CMAKE_CURRENT_BINARY_DIR}/sample20_quick
      -P ${CMAKE_CURRENT_LIST_DIR}/check_paper_experiments.cmake)
endif()

if(TARGET paper_experiments)
  # The paper experiments' quick mode writes every CSV with the expected columns, finite errors and
  # tiny noise-free errors.
  add_test(NAME paper_experiments_quick
    COMMAND ${CMAKE_COMMAND}
      -DEXE=$<TARGET_FILE:paper_experiments> -DEXPERIMENT=paper
      -DDIR=${CMAKE_CURRENT_BINARY_DIR}/paper_quick
      -P ${CMAKE_CURRENT_LIST_DIR}/check_paper_experiments.cmake)
endif()

if(TARGET solver_stability)
  # 500 noise-free scenes: the decoupled 3-point solver's ranked candidate is the truth in every one.
  add_test(NAME solver_stability_quick COMMAND solver_stability --trials=500)
  set_tests_properties(solver_stability_quick PROPERTIES
    PASS_REGULAR_EXPRESSION "\n3pt +ranked +[-0-9.]+ +[-0-9.]+ +[-0-9.]+ +[-0-9.]+ +1\\.0000 ")
endif()

if(TARGET minimal_solver_accuracy)
  # The default run: 10 scenes through the 4-point solver, every one with a solution.
  add_test(NAME minimal_solver_accuracy_default COMMAND minimal_solver_accuracy)
  set_tests_properties(minimal_solver_accuracy_default PROPERTIES
    PASS_REGULAR_EXPRESSION "summary: 10 trials, 0 without solution")
endif()

if(TARGET covariance_calibration)
  # 50 scenes per case and 3 timed problems: every table, the normalised error and the cost lines.
  add_test(NAME covariance_calibration_quick COMMAND covariance_calibration --quick)
  set_tests_properties(covariance_calibration_quick PROPERTIES TIMEOUT 120
    PASS_REGULAR_EXPRESSION "yaw-only, exact gravity.*normalised error.*IMU pitch / roll noise.*ceres::Covariance SPARSE_QR")
endif()

include(${CMAKE_CURRENT_LIST_DIR}/bad_flag_tests.cmake)
# The help of every tool, also the COLMAP, KITTI and peer tools (all targets exist here).
include(${CMAKE_CURRENT_LIST_DIR}/help_tests.cmake)

if(TARGET gravity_pays)
  # 60-image drives (IMU 0.1 deg, short tracks, short baseline): every variant's row, no failed
  # refinement.
  add_test(NAME gravity_pays_quick COMMAND gravity_pays --quick --threads=1)
  set_tests_properties(gravity_pays_quick PROPERTIES TIMEOUT 300
    PASS_REGULAR_EXPRESSION "60 img, IMU 0.1 deg +start.*vision-only.*prior \\(IMU sigma\\).*default \\(verdict\\).*yaw-only.*tracks <= 3.*0.1 m steps.*total"
    FAIL_REGULAR_EXPRESSION "FAILED")
endif()
