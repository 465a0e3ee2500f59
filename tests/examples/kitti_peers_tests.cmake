# The ctests of the KITTI and peer tools (examples/kitti/kitti_triplets, examples/peers/
# peer_comparison), each added only when its tool is built: bad flags (trigrav_add_bad_flag_test of
# bad_flag_test.cmake, included before this file), peer_comparison's sections at a smoke-test size,
# and kitti_triplets on real KITTI frames.

# kitti_triplets (built when OpenCV is found). Flags are checked before any file is read, so an
# existing folder (tests/) stands in for the dataset; the output goes to the build tree.
set(kitti_output --output_dir=${CMAKE_CURRENT_BINARY_DIR}/kitti_bad_flags)
set(kitti_ok --kitti_dir=${CMAKE_CURRENT_SOURCE_DIR} ${kitti_output})
trigrav_add_bad_flag_test(kitti_triplets_no_kitti_dir kitti_triplets
  "--kitti_dir is required" ${kitti_output})
trigrav_add_bad_flag_test(kitti_triplets_missing_kitti_dir kitti_triplets
  "--kitti_dir: no folder /nonexistent_trigrav_kitti" --kitti_dir=/nonexistent_trigrav_kitti
  ${kitti_output})
trigrav_add_bad_flag_test(kitti_triplets_bad_sequence kitti_triplets
  "--sequence must be two digits" ${kitti_ok} --sequence=0x)
trigrav_add_bad_flag_test(kitti_triplets_short_range kitti_triplets
  "--last_frame must be at least --first_frame \\+ 2" ${kitti_ok} --first_frame=5 --last_frame=6)
trigrav_add_bad_flag_test(kitti_triplets_negative_first_frame kitti_triplets
  "--first_frame must be >= 0" ${kitti_ok} --first_frame=-1)
trigrav_add_bad_flag_test(kitti_triplets_no_output_dir kitti_triplets
  "--output_dir is required" --kitti_dir=${CMAKE_CURRENT_SOURCE_DIR})
trigrav_add_bad_flag_test(kitti_triplets_cache_inside_dataset kitti_triplets
  "--cache_dir \\(.*\\) must not be inside the dataset" ${kitti_ok}
  --cache_dir=${CMAKE_CURRENT_SOURCE_DIR}/cache)
trigrav_add_bad_flag_test(kitti_triplets_nan_threshold kitti_triplets
  "--threshold_px must be positive and finite" ${kitti_ok} --threshold_px=nan)
trigrav_add_bad_flag_test(kitti_triplets_zero_threshold kitti_triplets
  "--threshold_px must be positive and finite" ${kitti_ok} --threshold_px=0)
trigrav_add_bad_flag_test(kitti_triplets_confidence_one kitti_triplets
  "--confidence must be in \\(0, 1\\)" ${kitti_ok} --confidence=1)
trigrav_add_bad_flag_test(kitti_triplets_negative_imu_noise kitti_triplets
  "--imu_noise_deg must be >= 0 and finite" ${kitti_ok} --imu_noise_deg=-0.1)
trigrav_add_bad_flag_test(kitti_triplets_infinite_imu_noise kitti_triplets
  "--imu_noise_deg must be >= 0 and finite" ${kitti_ok} --imu_noise_deg=inf)
trigrav_add_bad_flag_test(kitti_triplets_ratio_above_one kitti_triplets
  "--ratio must be in \\(0, 1\\]" ${kitti_ok} --ratio=1.5)
trigrav_add_bad_flag_test(kitti_triplets_zero_threads kitti_triplets
  "--threads must be in 1..256" ${kitti_ok} --threads=0)
trigrav_add_bad_flag_test(kitti_triplets_unknown_method kitti_triplets
  "--methods: unknown method .9pt. \\(expected 3pt, 3pt-sextic, 4pt, 7pt-linear, 5pt, 8pt\\)"
  ${kitti_ok} --methods=3pt,9pt)
trigrav_add_bad_flag_test(kitti_triplets_refine_not_in_methods kitti_triplets
  "--refine: .4pt. is not in --methods" ${kitti_ok} --methods=3pt --refine=4pt)

# peer_comparison (built when OpenCV's calib3d or OpenGV is found): flags are checked before any
# section runs.
trigrav_add_bad_flag_test(peer_comparison_zero_threads peer_comparison
  "--threads must be positive" --threads=0)
trigrav_add_bad_flag_test(peer_comparison_seven_accuracy_points peer_comparison
  "--accuracy_points must be >= 8" --accuracy_points=7)
trigrav_add_bad_flag_test(peer_comparison_half_outliers peer_comparison
  "--accuracy_outlier_ratio must be in \\[0, 0.5\\)" --accuracy_outlier_ratio=0.5)
trigrav_add_bad_flag_test(peer_comparison_nan_threshold peer_comparison
  "--accuracy_threshold_px must be positive and finite" --accuracy_threshold_px=nan)

# Every section of peer_comparison at a smoke-test size: passes only if the three sections print
# their tables with trigrav's rows (3pt in (a), 3pt raw in (b), 3pt yaw-only in (c)) and the run
# reaches its last line (PASS_REGULAR_EXPRESSION replaces the exit-status check, so the closing
# "Total run time" stands in for it).
if(TARGET peer_comparison)
  add_test(NAME peer_comparison_quick
    COMMAND peer_comparison --solver_problems=20 --solver_passes=1 --robust_problems=1
      --robust_repetitions=1 --accuracy_scenes=2)
  set_tests_properties(peer_comparison_quick PROPERTIES TIMEOUT 300 PASS_REGULAR_EXPRESSION
    "## \\(a\\) Minimal solvers.*\\| 3pt \\|.*## \\(b\\) Robust estimates.*\\| 3pt \\| raw \\|.*## \\(c\\) Accuracy.*\\| 3pt \\| yaw-only \\|.*Total run time [0-9]+ s\\.")
endif()

# kitti_triplets on frames 20-29 of sequence 00 from ../shared/data/kitti next to the repository
# (or $TRIGRAV_KITTI_DIR): calibration, tracks, the feature cache, 3pt errors with exact gravity and
# with IMU noise, and with the peers (built exactly when peer_comparison is) their rows and the
# ratio table (check_kitti_triplets.cmake says what it checks). Skipped with a message when the
# data is absent.
if(TARGET kitti_triplets)
  if(TARGET peer_comparison)
    set(kitti_peers ON)
  else()
    set(kitti_peers OFF)
  endif()
  add_test(NAME kitti_real_data
    COMMAND ${CMAKE_COMMAND} -DEXE=$<TARGET_FILE:kitti_triplets>
      -DKITTI_DIR=${PROJECT_SOURCE_DIR}/../shared/data/kitti
      -DWORK_DIR=${CMAKE_CURRENT_BINARY_DIR}/kitti_real_data -DPEERS=${kitti_peers}
      -P ${CMAKE_CURRENT_LIST_DIR}/check_kitti_triplets.cmake)
  set_tests_properties(kitti_real_data PROPERTIES TIMEOUT 600
    SKIP_REGULAR_EXPRESSION "kitti_triplets test skipped")

  # The mistakes matrix on real tracks: every triplet of 00 and 02 with each input mistake and with
  # IMU noise, against the verdict's guarantees (check_kitti_mistakes.py; README, robustness).
  find_program(TRIGRAV_SYSTEM_PYTHON3 NAMES python3 PATHS /usr/bin NO_DEFAULT_PATH)
  find_program(TRIGRAV_SYSTEM_PYTHON3 NAMES python3)
  if(TRIGRAV_SYSTEM_PYTHON3)
    add_test(NAME kitti_mistakes_matrix
      COMMAND ${TRIGRAV_SYSTEM_PYTHON3} ${CMAKE_CURRENT_LIST_DIR}/check_kitti_mistakes.py
        $<TARGET_FILE:kitti_triplets> ${PROJECT_SOURCE_DIR}/../shared/data/kitti
        ${CMAKE_CURRENT_BINARY_DIR}/kitti_mistakes)
    set_tests_properties(kitti_mistakes_matrix PROPERTIES TIMEOUT 1800
      SKIP_REGULAR_EXPRESSION "kitti mistakes test skipped")
  endif()
endif()
