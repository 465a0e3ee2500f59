#include "pairwise_estimator.h"

#include <chrono>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "trigrav/initializers/two_view_to_three_view.h"

namespace trigrav::peers {
namespace {

// The pose with its centre scaled to unit length (t = -R C scales with C).
CameraPose WithUnitCenter(CameraPose pose) {
  pose.t /= pose.Center().norm();
  return pose;
}

// Both pair estimates succeeded: the three-view pose, scaled by CombineTwoViewPairs when it can.
EstimatorResult Combine(const ThreeViewObservations& observations,
                        const PairEstimate& pair12,
                        const PairEstimate& pair13) {
  EstimatorResult result;
  result.success = true;
  std::vector<Eigen::Vector3d> x1, x2, x3;
  result.inliers.assign(observations.size(), 0);
  for (std::size_t n = 0; n < observations.size(); ++n) {
    if (!pair12.inliers[n] || !pair13.inliers[n]) continue;
    result.inliers[n] = 1;
    x1.push_back(observations.Ray(0, n));
    x2.push_back(observations.Ray(1, n));
    x3.push_back(observations.Ray(2, n));
  }
  result.ransac.num_inliers = static_cast<int>(x1.size());
  const CameraPose cam2_from_cam1 = WithUnitCenter(pair12.cam_from_cam1);
  const CameraPose cam3_from_cam1 = WithUnitCenter(pair13.cam_from_cam1);
  std::vector<ThreeViewPose> poses;
  CombineTwoViewPairs(x1, x2, x3, {cam2_from_cam1}, {cam3_from_cam1}, &poses);
  if (poses.empty()) {
    result.relative_scale_known = false;
    result.message = "relative scale unknown (no common inlier or kappa <= 0): |c3| = 1";
    result.pose.cam2_from_cam1 = cam2_from_cam1;
    result.pose.cam3_from_cam1 = cam3_from_cam1;
  } else {
    result.pose = poses.front();
  }
  return result;
}

}  // namespace

Estimator PairwiseEstimator(PairEstimator pair_estimator) {
  return [pair_estimator = std::move(pair_estimator)](const ThreeViewObservations& observations,
                                                      double threshold_px) {
    const auto start = std::chrono::steady_clock::now();
    // Misuse throws, as in trigrav's estimators.
    observations.Check();
    if (!(threshold_px > 0.0) || !std::isfinite(threshold_px))
      throw std::invalid_argument("threshold_px must be positive and finite");
    const PairEstimate pair12 = pair_estimator(observations, 1, threshold_px);
    const PairEstimate pair13 = pair_estimator(observations, 2, threshold_px);
    EstimatorResult result;
    if (!pair12.success) {
      result.message = "pair (1,2): " + pair12.message;
    } else if (!pair13.success) {
      result.message = "pair (1,3): " + pair13.message;
    } else if (!pair12.cam_from_cam1.IsFinite() || !pair13.cam_from_cam1.IsFinite() ||
               !(pair12.cam_from_cam1.Center().norm() > 0.0) ||
               !(pair13.cam_from_cam1.Center().norm() > 0.0)) {
      result.message = "a pair estimate is not finite or has no translation";
    } else {
      result = Combine(observations, pair12, pair13);
    }
    result.time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return result;
  };
}

}  // namespace trigrav::peers
