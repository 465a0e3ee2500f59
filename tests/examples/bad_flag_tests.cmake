# Bad flag values of the synthetic example tools: each must exit with status 2 and
# "error: <message>" (examples/common/require_flag.h), never abort or crash.
# trigrav_add_bad_flag_test is defined in tests/bad_flag_test.cmake (included before this file); a
# case is one line.

set(nonnegative "must be finite and >= 0")
set(positive "must be positive and finite")
set(outlier_ratio_range "--outlier_ratio must be in \\[0, 1\\)")
set(threads_range "--threads must be in \\[1, 256\\]")

trigrav_add_bad_flag_test(minimal_solver_accuracy_unknown_solver minimal_solver_accuracy
  "unknown --solver=9pt" --solver=9pt)
trigrav_add_bad_flag_test(minimal_solver_accuracy_zero_trials minimal_solver_accuracy
  "--trials must be positive" --trials=0)
trigrav_add_bad_flag_test(minimal_solver_accuracy_negative_trials minimal_solver_accuracy
  "--trials must be positive" --trials=-3)
trigrav_add_bad_flag_test(minimal_solver_accuracy_negative_print_trials minimal_solver_accuracy
  "--print_trials must be >= 0" --print_trials=-1)
trigrav_add_bad_flag_test(minimal_solver_accuracy_3pt_four_points minimal_solver_accuracy
  "--solver=3pt takes exactly 3 triplets: --points=3" --solver=3pt --points=4)
trigrav_add_bad_flag_test(minimal_solver_accuracy_4pt_three_points minimal_solver_accuracy
  "--solver=4pt needs --points >= 4" --solver=4pt --points=3)
trigrav_add_bad_flag_test(minimal_solver_accuracy_negative_noise minimal_solver_accuracy
  "--noise_px ${nonnegative}" --noise_px=-1)
trigrav_add_bad_flag_test(minimal_solver_accuracy_nan_noise minimal_solver_accuracy
  "--noise_px ${nonnegative}" --noise_px=nan)
trigrav_add_bad_flag_test(minimal_solver_accuracy_infinite_noise minimal_solver_accuracy
  "--noise_px ${nonnegative}" --noise_px=inf)
trigrav_add_bad_flag_test(minimal_solver_accuracy_nan_imu_noise minimal_solver_accuracy
  "--imu_noise_deg ${nonnegative}" --imu_noise_deg=nan)
trigrav_add_bad_flag_test(minimal_solver_accuracy_zero_focal minimal_solver_accuracy
  "--focal_px ${positive}" --focal_px=0)
trigrav_add_bad_flag_test(minimal_solver_accuracy_negative_focal minimal_solver_accuracy
  "--focal_px ${positive}" --focal_px=-500)
trigrav_add_bad_flag_test(minimal_solver_accuracy_nan_focal minimal_solver_accuracy
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

trigrav_add_bad_flag_test(initialize_and_refine_synthetic_unknown_solver
  initialize_and_refine_synthetic
  "unknown --solver=6pt" --solver=6pt)
trigrav_add_bad_flag_test(initialize_and_refine_synthetic_unknown_rotation_model
  initialize_and_refine_synthetic
  "--rotation_model must be yaw-only or gravity-prior" --rotation_model=free)
trigrav_add_bad_flag_test(initialize_and_refine_synthetic_unknown_loss
  initialize_and_refine_synthetic
  "--loss must be huber, cauchy or none" --loss=l2)
trigrav_add_bad_flag_test(initialize_and_refine_synthetic_zero_loss_scale
  initialize_and_refine_synthetic
  "--loss_scale_px ${positive}" --loss_scale_px=0)
trigrav_add_bad_flag_test(initialize_and_refine_synthetic_nan_loss_scale
  initialize_and_refine_synthetic
  "--loss_scale_px ${positive}" --loss_scale_px=nan)
trigrav_add_bad_flag_test(initialize_and_refine_synthetic_negative_gravity_sigma
  initialize_and_refine_synthetic
  "--gravity_sigma_deg ${positive}" --gravity_sigma_deg=-1)
trigrav_add_bad_flag_test(initialize_and_refine_synthetic_zero_threshold
  initialize_and_refine_synthetic
  "--threshold_px ${positive}" --threshold_px=0)
trigrav_add_bad_flag_test(initialize_and_refine_synthetic_infinite_threshold
  initialize_and_refine_synthetic
  "--threshold_px ${positive}" --threshold_px=inf)
trigrav_add_bad_flag_test(initialize_and_refine_synthetic_nan_noise initialize_and_refine_synthetic
  "--noise_px ${nonnegative}" --noise_px=nan)
trigrav_add_bad_flag_test(initialize_and_refine_synthetic_negative_imu_noise
  initialize_and_refine_synthetic
  "--imu_noise_deg ${nonnegative}" --imu_noise_deg=-1)
trigrav_add_bad_flag_test(initialize_and_refine_synthetic_all_outliers
  initialize_and_refine_synthetic
  "${outlier_ratio_range}" --outlier_ratio=1)
trigrav_add_bad_flag_test(initialize_and_refine_synthetic_nan_outliers
  initialize_and_refine_synthetic
  "${outlier_ratio_range}" --outlier_ratio=nan)
trigrav_add_bad_flag_test(initialize_and_refine_synthetic_negative_outliers
  initialize_and_refine_synthetic
  "${outlier_ratio_range}" --outlier_ratio=-0.1)
trigrav_add_bad_flag_test(initialize_and_refine_synthetic_too_few_points
  initialize_and_refine_synthetic
  "--points must be at least the minimal sample of --solver=3pt \\(3\\)" --points=2)
trigrav_add_bad_flag_test(initialize_and_refine_synthetic_8pt_seven_points
  initialize_and_refine_synthetic
  "--points must be at least the minimal sample of --solver=8pt \\(8\\)" --solver=8pt --points=7)
trigrav_add_bad_flag_test(initialize_and_refine_synthetic_zero_trials
  initialize_and_refine_synthetic
  "--trials must be positive" --trials=0)
trigrav_add_bad_flag_test(initialize_and_refine_synthetic_negative_print_trials
  initialize_and_refine_synthetic
  "--print_trials must be >= 0" --print_trials=-1)
trigrav_add_bad_flag_test(initialize_and_refine_synthetic_negative_iterations
  initialize_and_refine_synthetic
  "--max_iterations must be >= 0" --max_iterations=-1)
trigrav_add_bad_flag_test(initialize_and_refine_synthetic_negative_rounds
  initialize_and_refine_synthetic
  "--reclassification_rounds must be >= 0" --reclassification_rounds=-2)

trigrav_add_bad_flag_test(initialize_and_refine_synthetic_sweep_zero_trials
  initialize_and_refine_synthetic
  "--trials must be positive" --trials=0 --experiment=sweep)
trigrav_add_bad_flag_test(initialize_and_refine_synthetic_sweep_seven_points
  initialize_and_refine_synthetic
  "--points must be >= 8" --points=7 --experiment=sweep)
trigrav_add_bad_flag_test(initialize_and_refine_synthetic_sweep_all_outliers
  initialize_and_refine_synthetic
  "${outlier_ratio_range}" --outlier_ratio=1 --experiment=sweep)
trigrav_add_bad_flag_test(initialize_and_refine_synthetic_sweep_nan_outliers
  initialize_and_refine_synthetic
  "${outlier_ratio_range}" --outlier_ratio=nan --experiment=sweep)
trigrav_add_bad_flag_test(initialize_and_refine_synthetic_sweep_zero_threads
  initialize_and_refine_synthetic
  "${threads_range}" --threads=0 --experiment=sweep)
trigrav_add_bad_flag_test(initialize_and_refine_synthetic_sweep_too_many_threads
  initialize_and_refine_synthetic
  "${threads_range}" --threads=100000 --experiment=sweep)
trigrav_add_bad_flag_test(initialize_and_refine_synthetic_sweep_zero_threshold
  initialize_and_refine_synthetic
  "--threshold_sigmas ${positive}" --threshold_sigmas=0 --experiment=sweep)
trigrav_add_bad_flag_test(initialize_and_refine_synthetic_sweep_nan_threshold
  initialize_and_refine_synthetic
  "--threshold_sigmas ${positive}" --threshold_sigmas=nan --experiment=sweep)
trigrav_add_bad_flag_test(initialize_and_refine_synthetic_sweep_unwritable_output
  initialize_and_refine_synthetic
  "cannot write --output=/nonexistent_trigrav_dir/refinement.csv"
  --output=/nonexistent_trigrav_dir/refinement.csv --experiment=sweep)

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
trigrav_add_bad_flag_test(paper_experiments_uncreatable_output_dir paper_experiments
  "cannot create or write --output_dir=/nonexistent_trigrav_dir/paper"
  --output_dir=/nonexistent_trigrav_dir/paper)
trigrav_add_bad_flag_test(paper_experiments_output_dir_is_a_file paper_experiments
  "cannot create or write --output_dir=/dev/null" --output_dir=/dev/null)

# initialize_and_refine_synthetic: experiments, and flags given to an experiment that does not read
# them.
trigrav_add_bad_flag_test(initialize_and_refine_synthetic_unknown_experiment
  initialize_and_refine_synthetic
  "--experiment must be single, sweep or sample20" --experiment=all)
trigrav_add_bad_flag_test(initialize_and_refine_synthetic_single_threshold_sigmas
  initialize_and_refine_synthetic
  "--threshold_sigmas does not apply to --experiment=single" --threshold_sigmas=2)
trigrav_add_bad_flag_test(initialize_and_refine_synthetic_single_output
  initialize_and_refine_synthetic
  "--output does not apply to --experiment=single" --output=single.csv)
trigrav_add_bad_flag_test(initialize_and_refine_synthetic_sweep_solver
  initialize_and_refine_synthetic
  "--solver does not apply to --experiment=sweep" --experiment=sweep --solver=5pt)
trigrav_add_bad_flag_test(initialize_and_refine_synthetic_sweep_peers
  initialize_and_refine_synthetic
  "--peers does not apply to --experiment=sweep" --experiment=sweep --peers=false)
trigrav_add_bad_flag_test(initialize_and_refine_synthetic_sample20_outliers
  initialize_and_refine_synthetic
  "--outlier_ratio does not apply to --experiment=sample20" --experiment=sample20
  --outlier_ratio=0.1)
trigrav_add_bad_flag_test(initialize_and_refine_synthetic_sample20_seven_points
  initialize_and_refine_synthetic
  "--points must be >= 8" --experiment=sample20 --points=7)
trigrav_add_bad_flag_test(initialize_and_refine_synthetic_sample20_zero_trials
  initialize_and_refine_synthetic
  "--trials must be positive" --experiment=sample20 --trials=0)
trigrav_add_bad_flag_test(initialize_and_refine_synthetic_sample20_unwritable_output
  initialize_and_refine_synthetic
  "cannot write --output=/nonexistent_trigrav_dir/sample20.csv" --experiment=sample20
  --output=/nonexistent_trigrav_dir/sample20.csv)

trigrav_add_bad_flag_test(verdict_matrix_unknown_mistake verdict_matrix
  "--mistakes must be all or a mistake's name" --mistakes=typo)
trigrav_add_bad_flag_test(verdict_matrix_floor_one verdict_matrix
  "--min_inlier_ratio must be in \\[0, 1\\)" --min_inlier_ratio=1)
trigrav_add_bad_flag_test(verdict_matrix_nan_noise verdict_matrix
  "--noise_px must be finite and >= 0" --noise_px=nan)

trigrav_add_bad_flag_test(covariance_calibration_zero_scenes covariance_calibration
  "--scenes must be positive" --scenes=0)
trigrav_add_bad_flag_test(covariance_calibration_zero_noise covariance_calibration
  "--noise_px ${positive}" --noise_px=0)
trigrav_add_bad_flag_test(covariance_calibration_nan_imu_noise covariance_calibration
  "--imu_noise_deg ${positive}" --imu_noise_deg=nan)
trigrav_add_bad_flag_test(covariance_calibration_all_outliers covariance_calibration
  "${outlier_ratio_range}" --outlier_ratio=1)
trigrav_add_bad_flag_test(covariance_calibration_infinite_threshold covariance_calibration
  "--threshold_px ${positive}" --threshold_px=inf)
