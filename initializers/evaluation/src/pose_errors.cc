#include "trigrav/evaluation/pose_errors.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace trigrav {
namespace {
constexpr double kRadToDeg = 180.0 / EIGEN_PI;
}  // namespace

double RotationErrorDeg(const Eigen::Matrix3d& R_gt, const Eigen::Matrix3d& R) {
  const Eigen::Matrix3d M = R_gt * R.transpose();
  const Eigen::Vector3d vee(M(2, 1) - M(1, 2), M(0, 2) - M(2, 0), M(1, 0) - M(0, 1));
  return std::atan2(0.5 * vee.norm(), 0.5 * (M.trace() - 1.0)) * kRadToDeg;
}

double DirectionErrorDeg(const Eigen::Vector3d& a_gt, const Eigen::Vector3d& a) {
  const double n_gt = a_gt.norm();
  const double n = a.norm();
  if (!(n_gt > 0.0) || !(n > 0.0)) return 180.0;
  const Eigen::Vector3d u = a_gt / n_gt;
  const Eigen::Vector3d v = a / n;
  return std::atan2(u.cross(v).norm(), u.dot(v)) * kRadToDeg;
}

double ThreeViewPoseErrors::MaxRotationDeg() const {
  return std::max(rotation_deg[0], rotation_deg[1]);
}

double ThreeViewPoseErrors::MaxTranslationDeg() const {
  return std::max(translation_deg[0], translation_deg[1]);
}

double ThreeViewPoseErrors::MaxAngleDeg() const {
  return std::max(MaxRotationDeg(), MaxTranslationDeg());
}

ThreeViewPoseErrors ComputeThreeViewPoseErrors(const ThreeViewPose& ground_truth,
                                               const ThreeViewPose& estimate) {
  ThreeViewPoseErrors errors;
  const CameraPose* gt[2] = {&ground_truth.cam2_from_cam1, &ground_truth.cam3_from_cam1};
  const CameraPose* est[2] = {&estimate.cam2_from_cam1, &estimate.cam3_from_cam1};
  for (int k = 0; k < 2; ++k) {
    errors.rotation_deg[k] = RotationErrorDeg(gt[k]->R, est[k]->R);
    errors.translation_deg[k] = DirectionErrorDeg(gt[k]->Center(), est[k]->Center());
  }
  const double scale_gt =
      ground_truth.cam3_from_cam1.Center().norm() / ground_truth.cam2_from_cam1.Center().norm();
  const double scale_est =
      estimate.cam3_from_cam1.Center().norm() / estimate.cam2_from_cam1.Center().norm();
  errors.relative_scale = std::abs(std::log(scale_est / scale_gt));
  if (!std::isfinite(errors.relative_scale)) {
    errors.relative_scale = std::numeric_limits<double>::infinity();
  }
  return errors;
}

YawTiltErrorDeg SplitRotationErrorDeg(const Eigen::Matrix3d& R_gt,
                                      const Eigen::Matrix3d& R,
                                      const Eigen::Vector3d& gravity_in_cam) {
  const double g_norm = gravity_in_cam.norm();
  if (!(g_norm > 0.0) || !std::isfinite(g_norm)) {
    throw std::invalid_argument(
        "trigrav: SplitRotationErrorDeg: gravity_in_cam must be non-zero and finite");
  }
  const Eigen::Vector3d g = gravity_in_cam / g_norm;
  const Eigen::Quaterniond q(Eigen::Matrix3d(R_gt * R.transpose()));
  const double w = std::abs(q.w());
  const double v_g = q.vec().dot(g);
  const double v_perp = (q.vec() - v_g * g).norm();
  YawTiltErrorDeg split;
  split.yaw_deg = 2.0 * std::atan2(std::abs(v_g), w) * kRadToDeg;
  split.tilt_deg = 2.0 * std::atan2(v_perp, std::hypot(w, v_g)) * kRadToDeg;
  return split;
}

}  // namespace trigrav
