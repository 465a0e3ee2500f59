#ifndef TRIGRAV_INITIALIZERS_OBSERVATION_RESIDUAL_H_
#define TRIGRAV_INITIALIZERS_OBSERVATION_RESIDUAL_H_

// The residual of one observation of a point given in the observing camera's frame: the one
// definition shared by the robust estimators' inlier error (three_view_error.h) and the bundle
// adjustment's factors (trigrav/factors/reprojection_factors.h); derivations.md section 11.
//  - PixelResidual: the camera model's projection of the point minus the observed pixel, in pixels.
//  - BearingResidual: the point's offset from a measured bearing b in the tangent plane at b,
//    (180 / pi) [e1 . x, e2 . x] / (b . x) with (e1, e2, b) orthonormal, in degrees: its norm is
//    (180 / pi) tan(theta) for the angle theta between x and b, theta in degrees to 1e-4 relative
//    below one degree.
// Both are templated for Ceres' automatic differentiation and return false (residual not written)
// for a point the observation cannot see: behind the camera (Z <= 0) or behind the bearing
// (b . x <= 0).

#include <Eigen/Core>
#include <cmath>

#include "trigrav/initializers/camera_model.h"

namespace trigrav {

inline constexpr double kRadiansToDegrees = 180.0 / M_PI;

struct PixelResidual {
  Camera camera;
  Eigen::Vector2d pixel;

  template <typename T>
  bool operator()(const T* point_in_cam, T* residual) const {
    T projected[2];
    if (!camera.Project(point_in_cam, projected)) return false;
    residual[0] = projected[0] - T(pixel.x());
    residual[1] = projected[1] - T(pixel.y());
    return true;
  }
};

class BearingResidual {
 public:
  BearingResidual() = default;
  // Any positive length; the caller checks that the bearing is finite and non-zero.
  explicit BearingResidual(const Eigen::Vector3d& bearing_in_cam);

  template <typename T>
  bool operator()(const T* point_in_cam, T* residual) const {
    const T along = Dot(2, point_in_cam);
    if (!(along > T(0))) return false;
    residual[0] = T(kRadiansToDegrees) * Dot(0, point_in_cam) / along;
    residual[1] = T(kRadiansToDegrees) * Dot(1, point_in_cam) / along;
    return true;
  }

  // Rows e1, e2, b: the tangent basis and the unit bearing.
  const Eigen::Matrix3d& frame() const { return frame_; }

 private:
  template <typename T>
  T Dot(int row, const T* x) const {
    return T(frame_(row, 0)) * x[0] + T(frame_(row, 1)) * x[1] + T(frame_(row, 2)) * x[2];
  }
  Eigen::Matrix3d frame_ = Eigen::Matrix3d::Identity();
};

}  // namespace trigrav

#endif  // TRIGRAV_INITIALIZERS_OBSERVATION_RESIDUAL_H_
