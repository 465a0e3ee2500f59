#ifndef TRIGRAV_BA_INITIALIZE_AND_REFINE_H_
#define TRIGRAV_BA_INITIALIZE_AND_REFINE_H_

// Initialise-then-refine, the call a pipeline makes: a robust minimal-solver estimate (RANSAC over
// the chosen method, robust_three_view.h) refined by three-view bundle adjustment on its inliers
// (RefineThreeViewPose, refine_three_view_pose.h).

#include <Eigen/Core>
#include <string>
#include <vector>

#include "trigrav/ba/refine_three_view_pose.h"
#include "trigrav/ba/three_view_bundle_adjustment.h"
#include "trigrav/initializers/camera_pose.h"
#include "trigrav/initializers/ransac.h"
#include "trigrav/initializers/robust_three_view.h"
#include "trigrav/initializers/three_view_observations.h"

namespace trigrav {

struct InitializeAndRefineOptions {
  // The initial estimate: solver, RANSAC (robust.ransac.max_error is the one inlier threshold, in
  // pixels, of RANSAC and of the re-classification; robust.ransac.seed its seed) and the tilt
  // correction bound (kTiltCorrectionFromGravitySigma by default: 4 sqrt(2)
  // bundle_adjustment.gravity_sigma_deg with the gravity-prior model, 0 with yaw-only), the
  // inlier-ratio floor (robust.ransac.min_inlier_ratio) and the gravity consistency bound
  // (kGravityConsistencyFromGravitySigma by default: 4 sqrt(2) bundle_adjustment.gravity_sigma_deg,
  // at least 1 deg, with either rotation model, since the sigma describes the IMU).
  // robust.refined_afterwards is set to `refine`: the RANSAC pose's offset from its inliers'
  // optimum is judged when it is the answer (refine false, or the refinement failed), not when the
  // refinement replaces it.
  RobustThreeViewOptions robust;
  bool refine = true;
  // After a refinement, the triplets are re-classified against the refined pose (same threshold)
  // and, if the inlier set changed, the refinement is run again from the refined pose and the
  // refined points (new inliers triangulated), up to this many times. Recovers inliers a noisy
  // minimal model missed.
  int reclassification_rounds = 1;
  // Rotation model, loss and its scale, gravity sigma, iterations, threads, linear solver.
  ThreeViewBundleAdjustmentOptions bundle_adjustment;

  // Throws std::invalid_argument naming the first bad field.
  void Check() const;
};

// Wall-clock time of each stage of a call, in seconds. refinement_s splits into build_s, solve_s,
// covariance_s and reclassification_s (summed over the refinement runs), and small bookkeeping.
struct ThreeViewEstimateTimings {
  double ransac_s = 0.0;
  double refinement_s = 0.0;  // every bundle adjustment and re-classification
  double total_s = 0.0;
  double build_s = 0.0;  // adjuster set-up: parameters, points, the Ceres problem (kCeres)
  double solve_s = 0.0;  // ThreeViewBundleAdjuster::Solve
  double covariance_s = 0.0;
  double reclassification_s = 0.0;
};

struct ThreeViewEstimate {
  bool success = false;
  std::string message;  // why not, when !success; a note when the refinement fell back
  FailureCause cause = FailureCause::kNone;  // why not, for a pipeline (robust_three_view.h)
  // The RANSAC stage as EstimateThreeViewPoseRobust returned it (robust_three_view.h): the RANSAC
  // winner's pose and inliers, the RANSAC statistics, what the images say about the gravity (also
  // when !success) and the consensus evidence; its success, message and cause are the verdict on
  // the RANSAC pose, the ones above the whole call's.
  RobustThreeViewEstimate robust;
  // The answer: the refined pose, or the initial one when refine is false or the refinement failed.
  ThreeViewPose refined;
  std::vector<char> inliers;  // per triplet: inliers of `refined` (those the last refinement used)
  int num_inliers = 0;
  // The bundle adjustment that produced `refined` (the last successful run): the refined points,
  // per-triplet residual norms, residual RMS, relative scale and, with
  // bundle_adjustment.compute_covariance, the pose covariance (computed in every run, the last one
  // kept; its cost: examples/experiments/README.md, covariance_calibration). When none succeeded,
  // the first run, its summary.success false and the reason in its summary.message.
  ThreeViewRefinement refinement;
  int refinement_runs = 0;  // successful bundle adjustments (1 + re-classification rounds used)
  ThreeViewEstimateTimings timings;
};

// Throws std::invalid_argument for invalid observations (ThreeViewObservations::Check) or options.
// success means the evidence supports the pose (EstimateThreeViewPoseRobust's verdict,
// robust_three_view.h) and, with the yaw-only model, the refinement moved it by at most 5 deg
// (rotations and centre directions; beyond, the exact gravity the model imposes contradicts the
// verified pose: FailureCause::kRefinementShift); anything else gives success == false with a
// message, the likely cause first. If the refinement fails, `refined` is the initial pose and the
// message says why; success stays true unless that pose lies off its inliers' optimum
// (ConsensusEvidence::SigmaWithOffsetDeg beyond robust.max_pose_sigma_deg: kUncertainPose). The
// returned poses are always finite when success is true.
ThreeViewEstimate InitializeAndRefine(const ThreeViewObservations& observations,
                                      const InitializeAndRefineOptions& options);

}  // namespace trigrav

#endif  // TRIGRAV_BA_INITIALIZE_AND_REFINE_H_
