#ifndef TRIGRAV_EXAMPLES_BENCHMARKS_POSELIB_BENCHMARKS_H_
#define TRIGRAV_EXAMPLES_BENCHMARKS_POSELIB_BENCHMARKS_H_

// PoseLib (Larsson et al., github.com/PoseLib/PoseLib, BSD-3) as a peer in the benchmarks, on the
// same scenes as trigrav's rows. Compiled in only when CMake finds PoseLib (built outside the
// repository, README.md), which defines TRIGRAV_WITH_POSELIB; trigrav never depends on it.

namespace trigrav::benchmarks {

// solver_benchmark's rows (poselib_solver_benchmarks.cc), on BM_Solver's scenes:
//   BM_Peer/poselib_upright_3pt_two_pairs          relpose_upright_3pt on pairs (1,2) and (1,3)
//                                                  of the gravity-aligned rays (BM_Solver/3pt's)
//   BM_Peer/poselib_upright_3pt_gravity_two_pairs  its gravity wrapper on the raw rays and each
//                                                  camera's gravity (BM_Solver/3pt-gravity's)
//   BM_Peer/poselib_5pt                            relpose_5pt (poses) on pair (1,2) of
//                                                  BM_Solver/5pt's scenes, as unit bearings
// Counter truth_found: the share of scenes with the true pose (1e-6 deg) among the solutions of
// every pair.
void RegisterPoseLibSolverBenchmarks();

// robust_benchmark's rows (poselib_robust_benchmarks.cc), on the issue scenes (issue_scenes.h) of
// <n> = 375 and 875 triplets at the same 2 px threshold (PoseLib's Sampson error in pixels):
//   BM_PoseLib/estimate_relative_pose/trigrav_rule/<n>   pairs (1,2) and (1,3), one call each, at
//                                                        trigrav's stopping rule: confidence,
//                                                        min_iterations and max_iterations of its
//                                                        RansacOptions, dyn_num_trials_mult = 1
//   BM_PoseLib/estimate_relative_pose/trigrav_rule_ransac_only/<n>
//                                                        the same without the final refinement
//                                                        (bundle.max_iterations = 0): the RANSAC
//                                                        (with its local optimisation) alone
//   BM_PoseLib/estimate_relative_pose/defaults/<n>       PoseLib's RansacOptions (min_iterations =
//                                                        1000, dyn_num_trials_mult = 3)
//   BM_PoseLib/refine_relpose_two_pairs/<n>              PoseLib's Levenberg-Marquardt refinement
//                                                        of pairs (1,2) and (1,3), each on its
//                                                        inliers from trigrav_rule_ransac_only's
//                                                        model
// Counters, from one pass over all the scenes before the timing: rot_deg, trans_deg (medians,
// views 2 and 3 pooled as in BM_RobustEstimateIssueScenes, a failure counted as 180 deg),
// ransac_iterations (RANSAC samples) or lm_iterations (Levenberg-Marquardt iterations) and inliers
// (medians per pair).
void RegisterPoseLibRobustBenchmarks();

}  // namespace trigrav::benchmarks

#endif  // TRIGRAV_EXAMPLES_BENCHMARKS_POSELIB_BENCHMARKS_H_
