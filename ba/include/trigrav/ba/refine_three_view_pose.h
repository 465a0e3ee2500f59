#ifndef TRIGRAV_BA_REFINE_THREE_VIEW_POSE_H_
#define TRIGRAV_BA_REFINE_THREE_VIEW_POSE_H_

// Refine-only: the call a pipeline with its own RANSAC (or a second pass) makes. One three-view
// bundle adjustment (three_view_bundle_adjustment.h) of a given pose on given inlier triplets.

#include <Eigen/Core>
#include <vector>

#include "trigrav/ba/three_view_bundle_adjustment.h"
#include "trigrav/initializers/camera_pose.h"
#include "trigrav/initializers/three_view_observations.h"

namespace trigrav {

struct ThreeViewRefinement {
  // The refined pose, |cam2_from_cam1.Center()| = 1. When !summary.success: the initial pose,
  // rescaled to |C2| = 1 if the problem could be built.
  ThreeViewPose pose;
  // Triplets in the problem (indices into the observations): the inliers that could be
  // triangulated in front of all three cameras.
  std::vector<int> triplets;
  // The refined points in camera 1's frame, one per entry of `triplets` (empty when the problem
  // could not be built).
  std::vector<Eigen::Vector3d> points_in_cam1;
  // Per entry of `triplets`: the residual norms of its observations in views 1, 2, 3 at the refined
  // pose and point (pixels, degrees for bearings). maxCoeff() is the inlier error of
  // three_view_error.h, evaluated at the refined point instead of the midpoint.
  std::vector<Eigen::Vector3d> residual_norms;
  // RMS of the residual components, sqrt(sum |r|^2 / (6 triplets)) (pixels, degrees for bearings),
  // gravity prior excluded. With Gaussian noise of sigma per component it is near
  // sigma sqrt(1 - (3 triplets + pose dof) / (6 triplets)): points and pose absorb part of the
  // noise (about 0.71 sigma for 80 triplets).
  double residual_rms = 0.0;
  double relative_scale = 0.0;  // |C3| / |C2| of `pose`
  // With options.compute_covariance: the pose's covariance (three_view_covariance.h: 7 x 7 for
  // kYawOnly, 11 x 11 for kGravityPrior), scaled by options.ObservationSigma()^2. Empty when not
  // asked for, when the refinement failed, or when it cannot be computed (rank-deficient; the
  // reason in summary.message, summary.success stays true). Never NaN.
  Eigen::MatrixXd covariance;
  ThreeViewBundleAdjustmentSummary summary;  // success, message, costs, the full Ceres summary
  // Wall-clock seconds of the stages around the solve (summary.solve_s): adjuster construction
  // and Build(), the covariance.
  double build_s = 0.0;
  double covariance_s = 0.0;
};

// Refines `initial` on the triplets whose `inliers` entry is non-zero (inliers.size() ==
// observations.size()). Throws std::invalid_argument for invalid observations or options or a mask
// of the wrong size. A pose that is not finite, |C2| <= 1e-12 (no baseline;
// ThreeViewBundleAdjuster::Build), fewer than 3 triangulable triplets or a Ceres failure give
// summary.success == false with the reason in summary.message.
ThreeViewRefinement RefineThreeViewPose(const ThreeViewObservations& observations,
                                        const ThreeViewPose& initial,
                                        const std::vector<char>& inliers,
                                        const ThreeViewBundleAdjustmentOptions& options);

// The same, starting the points of the triplets a previous refinement had (its `triplets` and
// `points_in_cam1`, at the scale of `initial`, normally previous.pose) from its points and
// triangulating only the others (ThreeViewBundleAdjuster::Build with known points): a second
// refinement on a changed inlier set that does not undo what the first one did.
ThreeViewRefinement RefineThreeViewPose(const ThreeViewObservations& observations,
                                        const ThreeViewPose& initial,
                                        const std::vector<char>& inliers,
                                        const ThreeViewBundleAdjustmentOptions& options,
                                        const ThreeViewRefinement& previous);

}  // namespace trigrav

#endif  // TRIGRAV_BA_REFINE_THREE_VIEW_POSE_H_
