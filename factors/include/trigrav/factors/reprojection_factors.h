#ifndef TRIGRAV_FACTORS_REPROJECTION_FACTORS_H_
#define TRIGRAV_FACTORS_REPROJECTION_FACTORS_H_

// Ceres cost functions of trigrav's three-view bundle adjustment. Functor shape of Ceres
// examples/snavely_reprojection_error.h: observations and fixed quantities as const members,
// a templated operator() and a static Create(...) returning a new AutoDiffCostFunction (the caller,
// usually ceres::Problem, takes ownership). Residuals are unweighted (pixels, degrees for bearings,
// radians for the gravity prior): weighting and robust losses are applied by the caller
// (ceres::LossFunction, ceres::ScaledLoss).
//
// Conventions: camera 1 is the reference frame; a camera k has rotation R_k (x_cam = R_k (X - C_k))
// and centre C_k in reference coordinates. Gravity alignments A_k satisfy A_k g_k = |g_k| e_y
// (gravity.h), so the yaw-only model of camera k is R_k = A_k^T R_y(yaw_k) A_1.
//
// The AutoDiff instantiations live in src/ (one translation unit per residual type); this header
// only declares.

#include <ceres/cost_function.h>

#include <Eigen/Core>

#include "trigrav/initializers/observation_residual.h"

namespace trigrav {

// The three reprojection factors are templated on the observation's residual
// (trigrav/initializers/observation_residual.h): PixelResidual (a camera model and a pixel;
// residual in pixels) or BearingResidual (a unit bearing; residual in degrees). Both are
// instantiated.

// Residual (2) of a point (parameter block of 3, reference frame) seen by camera k with the
// yaw-only rotation R = A_k^T R_y(yaw) A_1. Parameter blocks: yaw (1), centre C_k (3), point (3).
template <typename Residual>
class YawOnlyReprojectionError {
 public:
  YawOnlyReprojectionError(const Residual& residual,
                           const Eigen::Matrix3d& alignment_cam,
                           const Eigen::Matrix3d& alignment_ref)
      : residual_(residual), alignment_cam_(alignment_cam), alignment_ref_(alignment_ref) {}

  template <typename T>
  bool operator()(const T* yaw, const T* center, const T* point, T* residuals) const;

  static ceres::CostFunction* Create(const Residual& residual,
                                     const Eigen::Matrix3d& alignment_cam,
                                     const Eigen::Matrix3d& alignment_ref);

 private:
  Residual residual_;
  Eigen::Matrix3d alignment_cam_;
  Eigen::Matrix3d alignment_ref_;
};

// Residual (2) of a point seen by a camera with a general rotation. Parameter blocks: rotation
// cam_from_ref as a unit quaternion in Ceres order [w, x, y, z] (4, use ceres::QuaternionManifold),
// centre C_k (3), point (3).
template <typename Residual>
class ReprojectionError {
 public:
  explicit ReprojectionError(const Residual& residual) : residual_(residual) {}

  template <typename T>
  bool operator()(const T* quaternion, const T* center, const T* point, T* residuals) const;

  static ceres::CostFunction* Create(const Residual& residual);

 private:
  Residual residual_;
};

// Residual (2) of a point seen by the fixed reference camera (identity rotation, centre at the
// origin). Parameter block: point (3).
template <typename Residual>
class ReferenceReprojectionError {
 public:
  explicit ReferenceReprojectionError(const Residual& residual) : residual_(residual) {}

  template <typename T>
  bool operator()(const T* point, T* residuals) const;

  static ceres::CostFunction* Create(const Residual& residual);

 private:
  Residual residual_;
};

// Gravity prior of camera k (2 residuals, radians): the direction its rotation predicts for
// gravity, p = R_k g_ref / |g_ref|, against the measured direction g_k / |g_k|, as the log map of p
// at g_k expressed in a fixed orthonormal basis of the tangent plane at g_k. Its norm is the angle
// between the two directions. Parameter block: rotation cam_from_ref as a quaternion [w, x, y, z]
// (4). Weight it with ceres::ScaledLoss (1 / sigma^2, sigma the IMU's angular sigma in radians).
// Throws std::invalid_argument for a zero-length or non-finite gravity vector.
class GravityPriorError {
 public:
  GravityPriorError(const Eigen::Vector3d& gravity_in_ref, const Eigen::Vector3d& gravity_in_cam);

  template <typename T>
  bool operator()(const T* quaternion, T* residuals) const;

  static ceres::CostFunction* Create(const Eigen::Vector3d& gravity_in_ref,
                                     const Eigen::Vector3d& gravity_in_cam);

 private:
  Eigen::Vector3d gravity_in_ref_;    // unit
  Eigen::Vector3d gravity_in_cam_;    // unit
  Eigen::Vector3d tangent_basis_[2];  // orthonormal, perpendicular to gravity_in_cam_
};

}  // namespace trigrav

#endif  // TRIGRAV_FACTORS_REPROJECTION_FACTORS_H_
