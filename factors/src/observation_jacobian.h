#ifndef TRIGRAV_FACTORS_SRC_OBSERVATION_JACOBIAN_H_
#define TRIGRAV_FACTORS_SRC_OBSERVATION_JACOBIAN_H_

// The residual of one observation (trigrav/initializers/observation_residual.h) at a point given in
// the observing camera's frame, with its derivative d r / d x_cam (2 x 3), for the analytic
// factors and EliminatedPointReprojectionError (ba/derivations.md 13.1): closed form for pinhole
// cameras and bearings, forward-mode automatic differentiation (Jets of 3, no allocation) for the
// distortion models. Each returns false where the residual functor does (the observation cannot
// see the point) or where the result is not finite.
//
// Internal to the factors (factors/src, not installed): no installed header includes it.

#include <Eigen/Core>

#include "trigrav/initializers/camera_model.h"
#include "trigrav/initializers/observation_residual.h"

namespace trigrav {

// Any camera model, by Jets.
bool LinearizeObservationByJets(const PixelResidual& residual,
                                const Eigen::Vector3d& x_cam,
                                Eigen::Vector2d* r,
                                Eigen::Matrix<double, 2, 3>* d_r_d_x);

// A pinhole model (Camera::IsPinhole()) of focal lengths fx, fy at a point with Z > 0:
// u = fx X / Z + cx, so du/dX = fx / Z and du/dZ = -fx X / Z^2 (v alike).
inline Eigen::Matrix<double, 2, 3> PinholeJacobian(double fx,
                                                   double fy,
                                                   const Eigen::Vector3d& x_cam) {
  const double inv_z = 1.0 / x_cam.z();
  const double gx = fx * inv_z;
  const double gy = fy * inv_z;
  Eigen::Matrix<double, 2, 3> jacobian;
  jacobian << gx, 0.0, -gx * x_cam.x() * inv_z, 0.0, gy, -gy * x_cam.y() * inv_z;
  return jacobian;
}

inline bool LinearizeObservation(const PixelResidual& residual,
                                 const Eigen::Vector3d& x_cam,
                                 Eigen::Vector2d* r,
                                 Eigen::Matrix<double, 2, 3>* d_r_d_x) {
  const Camera& camera = residual.camera;
  if (!camera.IsPinhole()) return LinearizeObservationByJets(residual, x_cam, r, d_r_d_x);
  if (!camera.Project(x_cam.data(), r->data())) return false;
  *r -= residual.pixel;
  *d_r_d_x = PinholeJacobian(camera.FocalX(), camera.FocalY(), x_cam);
  return r->allFinite() && d_r_d_x->allFinite();
}

// r_i = K (e_i . x) / (b . x) with K = 180 / pi (section 11.3): d r_i / dx = (K e_i - r_i b) / (b .
// x).
inline bool LinearizeObservation(const BearingResidual& residual,
                                 const Eigen::Vector3d& x_cam,
                                 Eigen::Vector2d* r,
                                 Eigen::Matrix<double, 2, 3>* d_r_d_x) {
  if (!residual(x_cam.data(), r->data())) return false;
  const Eigen::Matrix3d& frame = residual.frame();
  const double inv_along = 1.0 / frame.row(2).dot(x_cam);
  for (int i = 0; i < 2; ++i) {
    d_r_d_x->row(i) = (kRadiansToDegrees * frame.row(i) - (*r)[i] * frame.row(2)) * inv_along;
  }
  return r->allFinite() && d_r_d_x->allFinite();
}

}  // namespace trigrav

#endif  // TRIGRAV_FACTORS_SRC_OBSERVATION_JACOBIAN_H_
