#ifndef TRIGRAV_INITIALIZERS_ROBUST_THREE_VIEW_H_
#define TRIGRAV_INITIALIZERS_ROBUST_THREE_VIEW_H_

#include <string>
#include <vector>

#include "trigrav/initializers/camera_pose.h"
#include "trigrav/initializers/ransac.h"
#include "trigrav/initializers/three_view_observations.h"

namespace trigrav {

// The minimal solvers a robust estimate can be seeded with: the paper's methods and its baselines.
enum class InitialSolver {
  kTrifocal3pt,        // decoupled 3-point, gravity-aware (trifocal_3pt.h): the default
  kTrifocal3ptSextic,  // the paper's 3-point system (3pt-Our-3view), gravity-aware
  kTrifocal4pt,        // 4-point linear trifocal (4pt-Our-3view), gravity-aware
  kTrifocalLinear,     // normalised linear trifocal tensor, 7 triplets (7pt-Hartley-3view)
  kEssential5pt,       // Nister's five-point on pairs (1,2) and (1,3) (5pt-Nister-2view)
  kEssential8pt,       // normalised eight-point on pairs (1,2) and (1,3) (8pt-Hartley-2view)
};

// "3pt", "3pt-sextic", "4pt", "7pt-linear", "5pt", "8pt".
const char* InitialSolverName(InitialSolver solver);
// Inverse of InitialSolverName; false for an unknown name.
bool ParseInitialSolver(const std::string& name, InitialSolver* solver);
// Triplets in a minimal sample of the method (3, 3, 4, 7, 5, 8).
int MinimalSampleSize(InitialSolver solver);

struct RobustThreeViewOptions {
  InitialSolver solver = InitialSolver::kTrifocal3pt;
  // ransac.max_error is the inlier threshold in pixels, the same for every method. Local
  // optimisation re-estimates from the inliers with the method's own non-minimal solver: the 4-point
  // solver for the gravity-aware methods, the eight-point solver for the two-view ones, the linear
  // tensor for 7pt-linear.
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
  // corrected tilt. No effect without ransac.local_optimization. Throws std::invalid_argument
  // outside [0, 90).
  double max_tilt_correction_deg = 0.0;
};

struct RobustThreeViewEstimate {
  bool success = false;
  std::string message;              // why not, when !success
  ThreeViewPose pose;               // original camera frames, |cam2_from_cam1.Center()| = 1
  std::vector<char> inliers;        // per triplet
  int num_inliers = 0;
  int iterations = 0;
  int num_models_scored = 0;
  int num_local_optimizations = 0;
};

// Robust three-view relative pose from pixel triplets with outliers: RANSAC (ransac.h) over the chosen
// minimal solver, every method scored by the same three-view reprojection error in pixels
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
