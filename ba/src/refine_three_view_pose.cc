#include "trigrav/ba/refine_three_view_pose.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "refine_with_shared_error.h"
#include "trigrav/ba/three_view_covariance.h"

namespace trigrav {

namespace {

double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

namespace internal {

ThreeViewRefinement RefineThreeViewPose(const ThreeViewObservations& observations,
                                        std::shared_ptr<const ThreeViewReprojectionError> error,
                                        const ThreeViewPose& initial,
                                        const std::vector<char>& inliers,
                                        const ThreeViewBundleAdjustmentOptions& options,
                                        const ThreeViewRefinement* previous) {
  auto start = std::chrono::steady_clock::now();
  if (inliers.size() != observations.size()) {
    throw std::invalid_argument("trigrav: RefineThreeViewPose: the inlier mask has " +
                                std::to_string(inliers.size()) + " entries for " +
                                std::to_string(observations.size()) + " triplets");
  }
  // The adjuster (or the error, built from them) checks the observations, and the options.
  const ThreeViewBundleAdjustmentConfig config =
      ThreeViewBundleAdjustmentConfig::FromInlierMask(inliers);
  ThreeViewBundleAdjuster adjuster =
      error == nullptr ? ThreeViewBundleAdjuster(observations, config, options)
                       : ThreeViewBundleAdjuster(observations, std::move(error), config, options);
  ThreeViewRefinement refinement;
  refinement.pose = initial;
  // An empty config means all triplets to the adjuster; an empty mask means none.
  if (std::none_of(inliers.begin(), inliers.end(), [](char inlier) { return inlier != 0; })) {
    refinement.summary.message = "no inlier triplets to refine on";
    return refinement;
  }
  const bool built = previous == nullptr
                         ? adjuster.Build(initial)
                         : adjuster.Build(initial, previous->triplets, previous->points_in_cam1);
  refinement.build_s = SecondsSince(start);
  if (!built) {
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
    start = std::chrono::steady_clock::now();
    ComputeThreeViewPoseCovariance(&adjuster, options.ObservationSigma(observations),
                                   &refinement.covariance, &refinement.summary.message);
    refinement.covariance_s = SecondsSince(start);
  }
  return refinement;
}

}  // namespace internal

ThreeViewRefinement RefineThreeViewPose(const ThreeViewObservations& observations,
                                        const ThreeViewPose& initial,
                                        const std::vector<char>& inliers,
                                        const ThreeViewBundleAdjustmentOptions& options) {
  return internal::RefineThreeViewPose(observations, nullptr, initial, inliers, options, nullptr);
}

ThreeViewRefinement RefineThreeViewPose(const ThreeViewObservations& observations,
                                        const ThreeViewPose& initial,
                                        const std::vector<char>& inliers,
                                        const ThreeViewBundleAdjustmentOptions& options,
                                        const ThreeViewRefinement& previous) {
  return internal::RefineThreeViewPose(observations, nullptr, initial, inliers, options, &previous);
}

}  // namespace trigrav
