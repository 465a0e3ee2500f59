#ifndef TRIGRAV_INITIALIZERS_ROBUST_THREE_VIEW_H_
#define TRIGRAV_INITIALIZERS_ROBUST_THREE_VIEW_H_

#include <string>
#include <vector>

#include "trigrav/initializers/camera_pose.h"
#include "trigrav/initializers/initial_solver.h"
#include "trigrav/initializers/ransac.h"
#include "trigrav/initializers/three_view_observations.h"

namespace trigrav {

struct RobustThreeViewOptions {
  InitialSolver solver = InitialSolver::kTrifocal3pt;
  // ransac.max_error is the inlier threshold in pixels, the same for every method
  // (three_view_error.h says what it measures); ransac.seed makes a run reproducible. Local
  // optimisation re-estimates from the inliers with the method's own non-minimal solver: the
  // 4-point solver for the gravity-aware methods, the eight-point solver for the two-view ones, the
  // linear tensor for 7pt-linear.
  RansacOptions ransac;
  // Gravity-aware methods only: how far local optimisation may correct the relative tilt (pitch and
  // roll of cameras 2 and 3 relative to camera 1) that the given gravity implies, in degrees.
  // 0 (exact gravity): every model is upright, local optimisation included. > 0 (gravity from an
  // IMU): each local optimisation estimates the relative tilt from the inliers with the linear
  // trifocal tensor (7 or more inliers), turns the rays of views 2 and 3 by it when it lies within
  // this bound, and re-solves upright with the 4-point solver on the corrected rays. A relative
  // tilt error e moves distant points by about f e pixels (0.14 deg at f = 719 px: 1.8 px); under a
  // tight threshold every upright model of the true motion then loses its distant points, and
  // RANSAC may prefer a wrong motion. The minimal models stay upright; the estimate carries the
  // corrected tilt. No effect without ransac.local_optimization.
  // kTiltCorrectionFromGravitySigma (the default) derives the bound from the gravity's uncertainty
  // where one is known: InitializeAndRefine with the gravity-prior rotation model uses
  // 4 sqrt(2) gravity_sigma_deg (at most 45 deg; the relative tilt of two cameras with N(0,
  // sigma^2) pitch and roll errors exceeds it with probability 3e-4); with the yaw-only model,
  // which declares the gravity exact, and in EstimateThreeViewPoseRobust, which knows no sigma, it
  // means 0. Otherwise throws std::invalid_argument outside [0, 90).
  static constexpr double kTiltCorrectionFromGravitySigma = -1.0;
  double max_tilt_correction_deg = kTiltCorrectionFromGravitySigma;

  // Throws std::invalid_argument naming the first bad field.
  void Check() const;
};

struct RobustThreeViewEstimate {
  bool success = false;
  std::string message;        // why not, when !success
  ThreeViewPose pose;         // original camera frames, |cam2_from_cam1.Center()| = 1
  std::vector<char> inliers;  // per triplet; ransac.num_inliers of them are set
  RansacStatistics ransac;
};

// Robust three-view relative pose from pixel triplets with outliers: RANSAC (ransac.h) over the
// chosen minimal solver, every method scored by the same three-view reprojection error in pixels
// (three_view_error.h). Gravity is used by the gravity-aware methods only. Throws
// std::invalid_argument for invalid observations or options; numerical failure (too few triplets,
// no model) gives success == false with a message. So do data without parallax between views 1
// and 2: if a pure rotation of camera 2 (the best one for the winner's inliers, no baseline) puts
// more than 80 % of those inliers within ransac.max_error pixels, camera 2's centre, which sets the
// scale |C2| = 1, is not observable (zero baseline, pure rotation, points at infinity, identical
// views); the threshold follows COLMAP's planar-or-panoramic test of two-view geometries.
RobustThreeViewEstimate EstimateThreeViewPoseRobust(const ThreeViewObservations& observations,
                                                    const RobustThreeViewOptions& options);

}  // namespace trigrav

#endif  // TRIGRAV_INITIALIZERS_ROBUST_THREE_VIEW_H_
