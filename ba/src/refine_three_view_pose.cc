#include "trigrav/ba/refine_three_view_pose.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "trigrav/ba/three_view_covariance.h"

namespace trigrav {

ThreeViewRefinement RefineThreeViewPose(const ThreeViewObservations& observations,
                                        const ThreeViewPose& initial,
                                        const std::vector<char>& inliers,
                                        const ThreeViewBundleAdjustmentOptions& options) {
  if (inliers.size() != observations.size()) {
    throw std::invalid_argument("trigrav: RefineThreeViewPose: the inlier mask has " +
                                std::to_string(inliers.size()) + " entries for " +
                                std::to_string(observations.size()) + " triplets");
  }
  // The adjuster checks the observations and options (once).
  ThreeViewBundleAdjuster adjuster(
      observations, ThreeViewBundleAdjustmentConfig::FromInlierMask(inliers), options);
  ThreeViewRefinement refinement;
  refinement.pose = initial;
  // An empty config means all triplets to the adjuster; an empty mask means none.
  if (std::none_of(inliers.begin(), inliers.end(), [](char inlier) { return inlier != 0; })) {
    refinement.summary.message = "no inlier triplets to refine on";
    return refinement;
  }
  if (!adjuster.Build(initial)) {
    refinement.summary.message = adjuster.message();
    return refinement;
  }
  refinement.summary = adjuster.Solve();
  refinement.pose = adjuster.CurrentPose();
  refinement.triplets = adjuster.triplet_indices();
  refinement.points_in_cam1 = adjuster.points();
  refinement.residual_norms = adjuster.ResidualNorms();
  double sum_squares = 0.0;
  for (const Eigen::Vector3d& norms : refinement.residual_norms) sum_squares += norms.squaredNorm();
  refinement.residual_rms =
      std::sqrt(sum_squares / (6.0 * static_cast<double>(refinement.residual_norms.size())));
  refinement.relative_scale = refinement.pose.cam3_from_cam1.Center().norm() /
                              refinement.pose.cam2_from_cam1.Center().norm();
  if (options.compute_covariance && refinement.summary.success) {
    ComputeThreeViewPoseCovariance(&adjuster, options.ObservationSigma(observations),
                                   &refinement.covariance, &refinement.summary.message);
  }
  return refinement;
}

}  // namespace trigrav
