#include "parallax_check.h"

#include <Eigen/LU>
#include <Eigen/SVD>
#include <cmath>
#include <string>
#include <vector>

namespace trigrav {
namespace internal {
namespace {

// Share of the inliers that a camera 2 without baseline explains within `threshold` pixels: the
// rotation R maximising sum_n x2_n . R x1_n over the inliers' rays (Wahba's problem, solved by the
// SVD of sum_n x2_n x1_n^T; rays K^-1 [u v 1]^T weighted by their lengths), each inlier counted if
// the direction R x1_n lands within the threshold of its pixel in view 2.
double ShareExplainedByRotation(const TripletData& data,
                                const std::vector<char>& inliers,
                                double threshold) {
  Eigen::Matrix3d correlation = Eigen::Matrix3d::Zero();
  int num_inliers = 0;
  for (std::size_t n = 0; n < inliers.size(); ++n) {
    if (!inliers[n]) continue;
    correlation += data.raw[1][n] * data.raw[0][n].transpose();
    ++num_inliers;
  }
  if (num_inliers == 0) return 0.0;
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(correlation,
                                              Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d R = svd.matrixU() * svd.matrixV().transpose();
  if (R.determinant() < 0.0) {
    R = svd.matrixU() * Eigen::Vector3d(1.0, 1.0, -1.0).asDiagonal() * svd.matrixV().transpose();
  }
  int explained = 0;
  for (std::size_t n = 0; n < inliers.size(); ++n) {
    if (!inliers[n]) continue;
    const Eigen::Vector3d direction = R * data.raw[0][n];
    explained += data.error.ObservationError(1, n, direction) <= threshold;
  }
  return static_cast<double>(explained) / num_inliers;
}

// Like COLMAP's two-view classification, which calls a pair planar or panoramic when a homography
// explains more than 80 % of the inliers of the essential matrix (max_H_inlier_ratio = 0.8).
constexpr double kMaxShareExplainedByRotation = 0.8;

}  // namespace

void RejectWithoutParallax(const TripletData& data,
                           double max_error,
                           RobustThreeViewEstimate* estimate) {
  const double share = ShareExplainedByRotation(data, estimate->inliers, max_error);
  if (!(share > kMaxShareExplainedByRotation)) return;
  estimate->message =
      "no parallax between views 1 and 2: a rotation of camera 2 without baseline explains " +
      std::to_string(static_cast<int>(std::round(100.0 * share))) + " % of the " +
      std::to_string(estimate->ransac.num_inliers) +
      " inliers: camera 2's centre (the scale) is not observable; give views with a baseline";
  estimate->success = false;
  estimate->pose = ThreeViewPose();
  estimate->inliers.clear();
  estimate->ransac.num_inliers = 0;
}

}  // namespace internal
}  // namespace trigrav
