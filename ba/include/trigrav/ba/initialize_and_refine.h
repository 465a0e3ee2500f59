#ifndef TRIGRAV_BA_INITIALIZE_AND_REFINE_H_
#define TRIGRAV_BA_INITIALIZE_AND_REFINE_H_

// Initialise-then-refine, the call a pipeline makes: a robust minimal-solver estimate (RANSAC over
// the chosen method, robust_three_view.h) refined by three-view bundle adjustment on its inliers.
// PinholeCamera, ThreeViewObservations (three_view_observations.h) and InitialSolver
// (robust_three_view.h) are the types of issue 5; they are included here, not redefined.

#include <cstdint>
#include <string>
#include <vector>

#include "trigrav/ba/three_view_bundle_adjustment.h"
#include "trigrav/initializers/camera_pose.h"
#include "trigrav/initializers/ransac.h"
#include "trigrav/initializers/robust_three_view.h"
#include "trigrav/initializers/three_view_observations.h"

namespace trigrav {

struct InitializeAndRefineOptions {
  InitialSolver solver = InitialSolver::kTrifocal3pt;
  double inlier_threshold_px = 2.0;  // overrides ransac.max_error
  bool refine = true;
  std::uint64_t seed = 0;  // overrides ransac.seed
  // After a refinement, the triplets are re-classified against the refined pose (same threshold)
  // and, if the inlier set changed, the refinement is run again from the refined pose, up to this
  // many times. Recovers inliers a noisy minimal model missed.
  int reclassification_rounds = 1;
  // RANSAC settings other than max_error and seed.
  RansacOptions ransac;
  // With the gravity-prior rotation model, which declares the gravity uncertain: RANSAC's local
  // optimisation may correct the relative tilt by up to 4 sqrt(2) gravity_sigma_deg, at most
  // 45 deg (RobustThreeViewOptions::max_tilt_correction_deg; the relative tilt of two cameras
  // exceeds that bound with probability 3e-4). false keeps every RANSAC model upright, as in the
  // paper. With yaw-only, every RANSAC model is upright either way.
  bool correct_tilt_in_ransac = true;
  // Rotation model, loss and its scale, gravity sigma, iterations, threads, linear solver.
  ThreeViewBundleAdjustmentOptions bundle_adjustment;

  // Throws std::invalid_argument naming the first bad field.
  void Check() const;
};

struct ThreeViewEstimate {
  bool success = false;
  std::string message;        // why not, when !success; a note when refinement fell back
  ThreeViewPose initial;      // RANSAC winner, before refinement
  ThreeViewPose refined;      // after Ceres (== initial when refine is false or Ceres failed)
  std::vector<char> inliers;  // per triplet: inliers of `refined` (those the refinement used)
  int num_inliers = 0;
  std::vector<char> initial_inliers;  // per triplet: inliers of the RANSAC winner
  int num_initial_inliers = 0;
  int refinement_runs = 0;      // bundle adjustments run (1 + re-classification rounds used)
  bool refinement_ran = false;  // Ceres produced `refined`
  int ransac_iterations = 0;
  int ba_iterations = 0;      // summed over refinement runs
  int ba_num_points = 0;      // triplets in the last bundle adjustment
  double initial_cost = 0.0;  // Ceres cost before the first / after the last refinement run
  double final_cost = 0.0;
  std::string ceres_brief_report;
  double ransac_time_s = 0.0;
  double ba_time_s = 0.0;  // problem building + solving
  double total_time_s = 0.0;
};

// Throws std::invalid_argument for invalid observations (ThreeViewObservations::Check) or options.
// Numerical failure (too few triplets, no model) gives success == false with a message. If the
// refinement fails, `refined` is the initial pose and the message says why (success stays true).
// The returned poses are always finite when success is true.
ThreeViewEstimate InitializeAndRefine(const ThreeViewObservations& observations,
                                      const InitializeAndRefineOptions& options);

}  // namespace trigrav

#endif  // TRIGRAV_BA_INITIALIZE_AND_REFINE_H_
