// All AutoDiff instantiations of trigrav::factors, in one translation unit (compile time).
#include "trigrav/factors/reprojection_factors.h"

#include <ceres/autodiff_cost_function.h>
#include <ceres/rotation.h>

#include <Eigen/Geometry>
#include <cmath>
#include <stdexcept>

#include "trigrav/factors/angle_manifold.h"

namespace trigrav {
namespace {

// Pinhole projection of a point in camera coordinates, minus the observed pixel. Returns false for
// a point at or behind the camera plane, which Ceres treats as an invalid step.
template <typename T>
bool PixelResidual(const PinholeCamera& camera,
                   const Eigen::Vector2d& pixel,
                   const T* x_cam,
                   T* residuals) {
  if (!(x_cam[2] > T(0.0))) return false;
  const T inv_z = T(1.0) / x_cam[2];
  residuals[0] = T(camera.fx) * x_cam[0] * inv_z + T(camera.cx) - T(pixel.x());
  residuals[1] = T(camera.fy) * x_cam[1] * inv_z + T(camera.cy) - T(pixel.y());
  return true;
}

Eigen::Vector3d UnitOrThrow(const Eigen::Vector3d& v, const char* what) {
  const double n = v.norm();
  if (!(n > 0.0) || !std::isfinite(n)) {
    throw std::invalid_argument(std::string("trigrav: GravityPriorError: ") + what +
                                " must be finite and non-zero");
  }
  return v / n;
}

}  // namespace

template <typename T>
bool YawOnlyReprojectionError::operator()(const T* yaw,
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
  return PixelResidual(camera_, pixel_, x_cam, residuals);
}

ceres::CostFunction* YawOnlyReprojectionError::Create(const PinholeCamera& camera,
                                                      const Eigen::Matrix3d& alignment_cam,
                                                      const Eigen::Matrix3d& alignment_ref,
                                                      const Eigen::Vector2d& pixel) {
  return new ceres::AutoDiffCostFunction<YawOnlyReprojectionError, 2, 1, 3, 3>(
      new YawOnlyReprojectionError(camera, alignment_cam, alignment_ref, pixel));
}

template <typename T>
bool ReprojectionError::operator()(const T* quaternion,
                                   const T* center,
                                   const T* point,
                                   T* residuals) const {
  const T d[3] = {point[0] - center[0], point[1] - center[1], point[2] - center[2]};
  T x_cam[3];
  ceres::UnitQuaternionRotatePoint(quaternion, d, x_cam);
  return PixelResidual(camera_, pixel_, x_cam, residuals);
}

ceres::CostFunction* ReprojectionError::Create(const PinholeCamera& camera,
                                               const Eigen::Vector2d& pixel) {
  return new ceres::AutoDiffCostFunction<ReprojectionError, 2, 4, 3, 3>(
      new ReprojectionError(camera, pixel));
}

template <typename T>
bool ReferenceReprojectionError::operator()(const T* point, T* residuals) const {
  return PixelResidual(camera_, pixel_, point, residuals);
}

ceres::CostFunction* ReferenceReprojectionError::Create(const PinholeCamera& camera,
                                                        const Eigen::Vector2d& pixel) {
  return new ceres::AutoDiffCostFunction<ReferenceReprojectionError, 2, 3>(
      new ReferenceReprojectionError(camera, pixel));
}

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
  T scale(1.0);  // first order at v = 0, where sqrt has no derivative
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
