#ifndef TRIGRAV_FACTORS_ANGLE_MANIFOLD_H_
#define TRIGRAV_FACTORS_ANGLE_MANIFOLD_H_

// Manifold of a one-number angle (the yaw of trigrav's yaw-only rotations), wrapped to [-pi, pi),
// like Ceres examples/slam/pose_graph_2d/angle_manifold.h.

#include <ceres/autodiff_manifold.h>
#include <ceres/jet.h>
#include <ceres/manifold.h>

#include <cmath>

namespace trigrav {

// Wraps an angle in radians to [-pi, pi).
template <typename T>
inline T NormalizeAngle(const T& angle_rad) {
  using std::floor;
  constexpr double kPi = 3.14159265358979323846;
  const T two_pi(2.0 * kPi);
  return angle_rad - two_pi * floor((angle_rad + T(kPi)) / two_pi);
}

struct AngleManifoldFunctor {
  template <typename T>
  bool Plus(const T* x, const T* delta, T* x_plus_delta) const {
    *x_plus_delta = NormalizeAngle(*x + *delta);
    return true;
  }
  template <typename T>
  bool Minus(const T* y, const T* x, T* y_minus_x) const {
    *y_minus_x = NormalizeAngle(*y) - NormalizeAngle(*x);
    *y_minus_x = NormalizeAngle(*y_minus_x);
    return true;
  }
};

// The yaw manifold: ambient and tangent size 1.
using YawManifold = ceres::AutoDiffManifold<AngleManifoldFunctor, 1, 1>;

// New YawManifold (for ceres::Problem::SetManifold, which takes ownership).
ceres::Manifold* CreateYawManifold();

}  // namespace trigrav

#endif  // TRIGRAV_FACTORS_ANGLE_MANIFOLD_H_
