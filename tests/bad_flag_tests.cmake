# Bad flag values of the example tools: each must exit with status 2 and "error: <message>"
# (examples/require_flag.h), never abort or crash. trigrav_add_bad_flag_test is defined in
# bad_flag_test.cmake; a new tool's cases are one line each.
include(${CMAKE_CURRENT_LIST_DIR}/bad_flag_test.cmake)

set(nonnegative "must be finite and >= 0")
set(positive "must be positive and finite")
set(outlier_ratio_range "--outlier_ratio must be in \\[0, 1\\)")
set(threads_range "--threads must be in \\[1, 256\\]")

trigrav_add_bad_flag_test(synthetic_triplets_unknown_solver synthetic_triplets
  "unknown --solver=9pt" --solver=9pt)
trigrav_add_bad_flag_test(synthetic_triplets_zero_trials synthetic_triplets
  "--trials must be positive" --trials=0)
trigrav_add_bad_flag_test(synthetic_triplets_negative_trials synthetic_triplets
  "--trials must be positive" --trials=-3)
trigrav_add_bad_flag_test(synthetic_triplets_negative_print_trials synthetic_triplets
  "--print_trials must be >= 0" --print_trials=-1)
trigrav_add_bad_flag_test(synthetic_triplets_3pt_four_points synthetic_triplets
  "--solver=3pt takes exactly 3 triplets: --points=3" --solver=3pt --points=4)
trigrav_add_bad_flag_test(synthetic_triplets_4pt_three_points synthetic_triplets
  "--solver=4pt needs --points >= 4" --solver=4pt --points=3)
trigrav_add_bad_flag_test(synthetic_triplets_negative_noise synthetic_triplets
  "--noise_px ${nonnegative}" --noise_px=-1)
trigrav_add_bad_flag_test(synthetic_triplets_nan_noise synthetic_triplets
  "--noise_px ${nonnegative}" --noise_px=nan)
trigrav_add_bad_flag_test(synthetic_triplets_infinite_noise synthetic_triplets
  "--noise_px ${nonnegative}" --noise_px=inf)
trigrav_add_bad_flag_test(synthetic_triplets_nan_imu_noise synthetic_triplets
  "--imu_noise_deg ${nonnegative}" --imu_noise_deg=nan)
trigrav_add_bad_flag_test(synthetic_triplets_zero_focal synthetic_triplets
  "--focal_px ${positive}" --focal_px=0)
trigrav_add_bad_flag_test(synthetic_triplets_negative_focal synthetic_triplets
  "--focal_px ${positive}" --focal_px=-500)
trigrav_add_bad_flag_test(synthetic_triplets_nan_focal synthetic_triplets
  "--focal_px ${positive}" --focal_px=nan)

trigrav_add_bad_flag_test(solver_stability_zero_trials solver_stability
  "--trials must be positive" --trials=0)
trigrav_add_bad_flag_test(solver_stability_negative_trials solver_stability
  "--trials must be positive" --trials=-1)
trigrav_add_bad_flag_test(solver_stability_negative_noise solver_stability
  "--noise_px ${nonnegative}" --noise_px=-0.5)
trigrav_add_bad_flag_test(solver_stability_nan_noise solver_stability
  "--noise_px ${nonnegative}" --noise_px=nan)
trigrav_add_bad_flag_test(solver_stability_zero_found solver_stability
  "--found_deg ${positive}" --found_deg=0)
trigrav_add_bad_flag_test(solver_stability_nan_found solver_stability
  "--found_deg ${positive}" --found_deg=nan)

trigrav_add_bad_flag_test(refine_synthetic_triplets_unknown_solver refine_synthetic_triplets
  "unknown --solver=6pt" --solver=6pt)
trigrav_add_bad_flag_test(refine_synthetic_triplets_unknown_rotation_model refine_synthetic_triplets
  "--rotation_model must be yaw-only or gravity-prior" --rotation_model=free)
trigrav_add_bad_flag_test(refine_synthetic_triplets_unknown_loss refine_synthetic_triplets
  "--loss must be huber, cauchy or none" --loss=l2)
trigrav_add_bad_flag_test(refine_synthetic_triplets_zero_loss_scale refine_synthetic_triplets
  "--loss_scale_px ${positive}" --loss_scale_px=0)
trigrav_add_bad_flag_test(refine_synthetic_triplets_nan_loss_scale refine_synthetic_triplets
  "--loss_scale_px ${positive}" --loss_scale_px=nan)
trigrav_add_bad_flag_test(refine_synthetic_triplets_negative_gravity_sigma refine_synthetic_triplets
  "--gravity_sigma_deg ${positive}" --gravity_sigma_deg=-1)
trigrav_add_bad_flag_test(refine_synthetic_triplets_zero_threshold refine_synthetic_triplets
  "--threshold_px ${positive}" --threshold_px=0)
trigrav_add_bad_flag_test(refine_synthetic_triplets_infinite_threshold refine_synthetic_triplets
  "--threshold_px ${positive}" --threshold_px=inf)
trigrav_add_bad_flag_test(refine_synthetic_triplets_nan_noise refine_synthetic_triplets
  "--noise_px ${nonnegative}" --noise_px=nan)
trigrav_add_bad_flag_test(refine_synthetic_triplets_negative_imu_noise refine_synthetic_triplets
  "--imu_noise_deg ${nonnegative}" --imu_noise_deg=-1)
trigrav_add_bad_flag_test(refine_synthetic_triplets_all_outliers refine_synthetic_triplets
  "${outlier_ratio_range}" --outlier_ratio=1)
trigrav_add_bad_flag_test(refine_synthetic_triplets_nan_outliers refine_synthetic_triplets
  "${outlier_ratio_range}" --outlier_ratio=nan)
trigrav_add_bad_flag_test(refine_synthetic_triplets_negative_outliers refine_synthetic_triplets
  "${outlier_ratio_range}" --outlier_ratio=-0.1)
trigrav_add_bad_flag_test(refine_synthetic_triplets_too_few_points refine_synthetic_triplets
  "--points must be at least the minimal sample of --solver=3pt \\(3\\)" --points=2)
trigrav_add_bad_flag_test(refine_synthetic_triplets_8pt_seven_points refine_synthetic_triplets
  "--points must be at least the minimal sample of --solver=8pt \\(8\\)" --solver=8pt --points=7)
trigrav_add_bad_flag_test(refine_synthetic_triplets_zero_trials refine_synthetic_triplets
  "--trials must be positive" --trials=0)
trigrav_add_bad_flag_test(refine_synthetic_triplets_negative_print_trials refine_synthetic_triplets
  "--print_trials must be >= 0" --print_trials=-1)
trigrav_add_bad_flag_test(refine_synthetic_triplets_negative_iterations refine_synthetic_triplets
  "--max_iterations must be >= 0" --max_iterations=-1)
trigrav_add_bad_flag_test(refine_synthetic_triplets_negative_rounds refine_synthetic_triplets
  "--reclassification_rounds must be >= 0" --reclassification_rounds=-2)

trigrav_add_bad_flag_test(refinement_benchmark_zero_trials refinement_benchmark
  "--trials must be positive" --trials=0)
trigrav_add_bad_flag_test(refinement_benchmark_seven_points refinement_benchmark
  "--points must be >= 8" --points=7)
trigrav_add_bad_flag_test(refinement_benchmark_all_outliers refinement_benchmark
  "${outlier_ratio_range}" --outlier_ratio=1)
trigrav_add_bad_flag_test(refinement_benchmark_nan_outliers refinement_benchmark
  "${outlier_ratio_range}" --outlier_ratio=nan)
trigrav_add_bad_flag_test(refinement_benchmark_zero_threads refinement_benchmark
  "${threads_range}" --threads=0)
trigrav_add_bad_flag_test(refinement_benchmark_too_many_threads refinement_benchmark
  "${threads_range}" --threads=100000)
trigrav_add_bad_flag_test(refinement_benchmark_zero_threshold refinement_benchmark
  "--threshold_sigmas ${positive}" --threshold_sigmas=0)
trigrav_add_bad_flag_test(refinement_benchmark_nan_threshold refinement_benchmark
  "--threshold_sigmas ${positive}" --threshold_sigmas=nan)
trigrav_add_bad_flag_test(refinement_benchmark_unwritable_output refinement_benchmark
  "cannot write --output=/nonexistent_trigrav_dir/refinement.csv"
  --output=/nonexistent_trigrav_dir/refinement.csv)

trigrav_add_bad_flag_test(paper_experiments_zero_threads paper_experiments
  "${threads_range}" --threads=0)
trigrav_add_bad_flag_test(paper_experiments_negative_threads paper_experiments
  "${threads_range}" --threads=-2)
trigrav_add_bad_flag_test(paper_experiments_zero_trials paper_experiments
  "--trials must be in \\(0, 100\\]" --trials=0)
trigrav_add_bad_flag_test(paper_experiments_nan_trials paper_experiments
  "--trials must be in \\(0, 100\\]" --trials=nan)
trigrav_add_bad_flag_test(paper_experiments_huge_trials paper_experiments
  "--trials must be in \\(0, 100\\]" --trials=1e9)
trigrav_add_bad_flag_test(paper_experiments_seven_sample20_triplets paper_experiments
  "--sample20_triplets must be >= 8" --sample20_triplets=7)
trigrav_add_bad_flag_test(paper_experiments_uncreatable_output_dir paper_experiments
  "cannot create or write --output_dir=/nonexistent_trigrav_dir/paper"
  --output_dir=/nonexistent_trigrav_dir/paper)
trigrav_add_bad_flag_test(paper_experiments_output_dir_is_a_file paper_experiments
  "cannot create or write --output_dir=/dev/null" --output_dir=/dev/null)

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
  "--cache_dir \\(.*\\) must not be inside the dataset" ${kitti_ok} --cache_dir=${CMAKE_CURRENT_SOURCE_DIR}/cache)
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

# peer_comparison's KITTI section (--kitti_dir and kitti_triplets' flags; built with the peers and
# examples/kitti): flags are checked before any section runs.
if(TARGET trigrav_kitti_peers)
  trigrav_add_bad_flag_test(peer_comparison_missing_kitti_dir peer_comparison
    "--kitti_dir: no folder /nonexistent_trigrav_kitti" --kitti_dir=/nonexistent_trigrav_kitti)
  trigrav_add_bad_flag_test(peer_comparison_kitti_bad_sequence peer_comparison
    "--sequence must be two digits" --kitti_dir=${CMAKE_CURRENT_SOURCE_DIR} --sequence=0x)
  trigrav_add_bad_flag_test(peer_comparison_kitti_nan_threshold peer_comparison
    "--threshold_px must be positive and finite" --kitti_dir=${CMAKE_CURRENT_SOURCE_DIR}
    --threshold_px=nan)
endif()
