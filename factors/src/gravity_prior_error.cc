// The gravity prior's AutoDiff instantiation and the yaw manifold.
#include <ceres/autodiff_cost_function.h>
#include <ceres/rotation.h>

#include <Eigen/Geometry>
#include <cmath>
#include <stdexcept>
#include <string>

#include "trigrav/factors/angle_manifold.h"
#include "trigrav/factors/reprojection_factors.h"

namespace trigrav {
namespace {

Eigen::Vector3d UnitOrThrow(const Eigen::Vector3d& v, const char* what) {
  const double n = v.norm();
  if (!(n > 0.0) || !std::isfinite(n)) {
    throw std::invalid_argument(std::string("trigrav: GravityPriorError: ") + what +
                                " must be finite and non-zero");
  }
  return v / n;
}

}  // namespace

GravityPriorError::GravityPriorError(const Eigen::Vector3d& gravity_in_ref,
                                     const Eigen::Vector3d& gravity_in_cam)
    : gravity_in_ref_(UnitOrThrow(gravity_in_ref, "gravity_in_ref")),
      gravity_in_cam_(UnitOrThrow(gravity_in_cam, "gravity_in_cam")) {
  // Any unit vector not parallel to g, orthogonalised.
  const Eigen::Vector3d& g = gravity_in_cam_;
  Eigen::Vector3d seed =
      std::abs(g.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitZ();
  tangent_basis_[0] = (seed - g.dot(seed) * g).normalized();
  tangent_basis_[1] = g.cross(tangent_basis_[0]);
}

template <typename T>
bool GravityPriorError::operator()(const T* quaternion, T* residuals) const {
  const T g_ref[3] = {T(gravity_in_ref_.x()), T(gravity_in_ref_.y()), T(gravity_in_ref_.z())};
  T p[3];
  ceres::UnitQuaternionRotatePoint(quaternion, g_ref, p);
  // Log map of p at g: v = p - (g.p) g, angle = atan2(|v|, g.p), log = angle / |v| * v.
  const T cos_angle =
      T(gravity_in_cam_.x()) * p[0] + T(gravity_in_cam_.y()) * p[1] + T(gravity_in_cam_.z()) * p[2];
  T v[3];
  for (int i = 0; i < 3; ++i) v[i] = p[i] - cos_angle * T(gravity_in_cam_[i]);
  const T sin_squared = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
  if (!(sin_squared > T(1e-24)) && cos_angle < T(0.0)) {
    // p = -g: the log map has no direction there; the angle is pi from every side (a maximum of
    // the cost), so the residual has norm pi and no gradient. Returning v = 0 here would make the
    // exact antipode (a flipped gravity sign) look like a perfect match.
    residuals[0] = T(M_PI);
    residuals[1] = T(0.0);
    return true;
  }
  T scale(1.0);  // first order at v = 0 (p = g), where sqrt has no derivative
  if (sin_squared > T(1e-24)) {
    using std::atan2;
    using std::sqrt;
    const T sin_angle = sqrt(sin_squared);
    scale = atan2(sin_angle, cos_angle) / sin_angle;
  }
  for (int j = 0; j < 2; ++j) {
    residuals[j] = scale * (T(tangent_basis_[j].x()) * v[0] + T(tangent_basis_[j].y()) * v[1] +
                            T(tangent_basis_[j].z()) * v[2]);
  }
  return true;
}

ceres::CostFunction* GravityPriorError::Create(const Eigen::Vector3d& gravity_in_ref,
                                               const Eigen::Vector3d& gravity_in_cam) {
  return new ceres::AutoDiffCostFunction<GravityPriorError, 2, 4>(
      new GravityPriorError(gravity_in_ref, gravity_in_cam));
}

ceres::Manifold* CreateYawManifold() { return new YawManifold; }

}  // namespace trigrav
