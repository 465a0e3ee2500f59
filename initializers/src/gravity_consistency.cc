#include "gravity_consistency.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

#include "robust_estimator.h"
#include "robust_methods.h"

namespace trigrav {
namespace internal {
namespace {

constexpr double kDegPerRad = 180.0 / M_PI;

double AngleDeg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return kDegPerRad * std::atan2(a.cross(b).norm(), a.dot(b));
}

double RotationAngleDeg(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  return kDegPerRad * Eigen::AngleAxisd(a * b.transpose()).angle();
}

}  // namespace

GravityConsistency MeasureGravityConsistency(const TripletData& data,
                                             const RansacOptions& ransac,
                                             const ThreeViewPose& gravity_aware,
                                             bool has_gravity_aware_pose,
                                             RobustThreeViewEstimate* gravity_free) {
  GravityConsistency consistency;
  RobustThreeViewEstimate free = Run<Method5pt>(data, ransac);
  if (!free.success) return consistency;
  // The alignment A_k takes g_k to e_y, so g_k = A_k^T e_y, its second row.
  std::array<Eigen::Vector3d, 3> g;
  for (int k = 0; k < 3; ++k) g[k] = data.alignment[k].row(1).transpose();
  const Eigen::Matrix3d& R2 = free.pose.cam2_from_cam1.R;
  const Eigen::Matrix3d& R3 = free.pose.cam3_from_cam1.R;
  consistency.measured = true;
  consistency.num_inliers = free.ransac.num_inliers;
  consistency.pair_inconsistency_deg = {AngleDeg(R2 * g[0], g[1]), AngleDeg(R3 * g[0], g[2]),
                                        AngleDeg(R3 * R2.transpose() * g[1], g[2])};
  consistency.swapped_pair_inconsistency_deg = {AngleDeg(R2 * g[0], g[2]),
                                                AngleDeg(R3 * g[0], g[1])};
  if (has_gravity_aware_pose) {
    consistency.rotation_disagreement_deg = {RotationAngleDeg(gravity_aware.cam2_from_cam1.R, R2),
                                             RotationAngleDeg(gravity_aware.cam3_from_cam1.R, R3)};
    consistency.direction_disagreement_deg = {
        AngleDeg(gravity_aware.cam2_from_cam1.Center(), free.pose.cam2_from_cam1.Center()),
        AngleDeg(gravity_aware.cam3_from_cam1.Center(), free.pose.cam3_from_cam1.Center())};
  }
  if (gravity_free != nullptr) *gravity_free = std::move(free);
  return consistency;
}

}  // namespace internal
}  // namespace trigrav
