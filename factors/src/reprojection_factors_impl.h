#ifndef TRIGRAV_FACTORS_SRC_REPROJECTION_FACTORS_IMPL_H_
#define TRIGRAV_FACTORS_SRC_REPROJECTION_FACTORS_IMPL_H_

// Definitions of the reprojection factors' templates, included by the translation unit of each
// residual type, which instantiates them (the AutoDiff code compiles slowly: one type per unit).

#include <ceres/autodiff_cost_function.h>
#include <ceres/rotation.h>

#include <cmath>

#include "trigrav/factors/reprojection_factors.h"

namespace trigrav {

template <typename Residual>
template <typename T>
bool YawOnlyReprojectionError<Residual>::operator()(const T* yaw,
                                                    const T* center,
                                                    const T* point,
                                                    T* residuals) const {
  // x_cam = A_k^T R_y(yaw) A_1 (X - C).
  T d[3] = {point[0] - center[0], point[1] - center[1], point[2] - center[2]};
  T a[3];
  for (int i = 0; i < 3; ++i) {
    a[i] = T(alignment_ref_(i, 0)) * d[0] + T(alignment_ref_(i, 1)) * d[1] +
           T(alignment_ref_(i, 2)) * d[2];
  }
  using std::cos;
  using std::sin;
  const T c = cos(yaw[0]);
  const T s = sin(yaw[0]);
  // R_y = [[c, 0, s], [0, 1, 0], [-s, 0, c]].
  const T b[3] = {c * a[0] + s * a[2], a[1], -s * a[0] + c * a[2]};
  T x_cam[3];
  for (int i = 0; i < 3; ++i) {
    x_cam[i] = T(alignment_cam_(0, i)) * b[0] + T(alignment_cam_(1, i)) * b[1] +
               T(alignment_cam_(2, i)) * b[2];
  }
  return residual_(x_cam, residuals);
}

template <typename Residual>
ceres::CostFunction* YawOnlyReprojectionError<Residual>::Create(
    const Residual& residual,
    const Eigen::Matrix3d& alignment_cam,
    const Eigen::Matrix3d& alignment_ref) {
  return new ceres::AutoDiffCostFunction<YawOnlyReprojectionError, 2, 1, 3, 3>(
      new YawOnlyReprojectionError(residual, alignment_cam, alignment_ref));
}

template <typename Residual>
template <typename T>
bool ReprojectionError<Residual>::operator()(const T* quaternion,
                                             const T* center,
                                             const T* point,
                                             T* residuals) const {
  const T d[3] = {point[0] - center[0], point[1] - center[1], point[2] - center[2]};
  T x_cam[3];
  ceres::UnitQuaternionRotatePoint(quaternion, d, x_cam);
  return residual_(x_cam, residuals);
}

template <typename Residual>
ceres::CostFunction* ReprojectionError<Residual>::Create(const Residual& residual) {
  return new ceres::AutoDiffCostFunction<ReprojectionError, 2, 4, 3, 3>(
      new ReprojectionError(residual));
}

template <typename Residual>
template <typename T>
bool ReferenceReprojectionError<Residual>::operator()(const T* point, T* residuals) const {
  return residual_(point, residuals);
}

template <typename Residual>
ceres::CostFunction* ReferenceReprojectionError<Residual>::Create(const Residual& residual) {
  return new ceres::AutoDiffCostFunction<ReferenceReprojectionError, 2, 3>(
      new ReferenceReprojectionError(residual));
}

}  // namespace trigrav

#endif  // TRIGRAV_FACTORS_SRC_REPROJECTION_FACTORS_IMPL_H_
