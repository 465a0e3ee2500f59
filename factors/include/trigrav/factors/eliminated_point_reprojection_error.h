#ifndef TRIGRAV_FACTORS_ELIMINATED_POINT_REPROJECTION_ERROR_H_
#define TRIGRAV_FACTORS_ELIMINATED_POINT_REPROJECTION_ERROR_H_

// The reprojection error of one triplet with its point eliminated by variable projection
// (ba/derivations.md section 15): a residual block over the two cameras alone, for a Ceres problem
// with a handful of parameter blocks instead of one per point.
//
// For the cameras in its parameter blocks, Evaluate first minimises the triplet's robust cost
// 1/2 sum_k rho(|r_k|^2) over the point X (camera 1's frame) by Gauss-Newton, then returns the six
// residuals sqrt(rho(s_k) / s_k) r_k (s_k = |r_k|^2, views k = 1, 2, 3), whose 1/2 |.|^2 is that
// cost, and their Jacobian with X moving along: (I - J_X (J_X^T J_X)^-1 J_X^T) J_cameras. The loss
// is applied inside, per observation, as with one reprojection factor per observation
// (reprojection_factors.h); add the block without a loss function.
//
// Parameter blocks, in camera 1's frame (x_cam = R_k (X - C_k); camera 1 is the reference):
//  - CreateYawOnly: yaw_2 (1), C_2 (3), yaw_3 (1), C_3 (3), with R_k = A_k^T R_y(yaw_k) A_1 and
//    A_k the gravity alignments (gravity.h), as YawOnlyReprojectionError;
//  - CreateWithQuaternions: q_2 (4), C_2 (3), q_3 (4), C_3 (3), each q_k the rotation cam_from_ref
//    as a unit quaternion [w, x, y, z] (ceres::QuaternionManifold), as ReprojectionError.
//
// The point is the factor's state, in memory the caller owns: every evaluation starts its
// minimisation from *point (3 numbers, camera 1's frame), and an evaluation that computes Jacobians
// stores its result there. Ceres computes Jacobians at its accepted iterates only, so the trial
// steps it rejects leave the point alone, and after ceres::Solve *point is the point of the
// solution. An evaluation with Jacobians at exactly the parameters of the evaluation without them
// just before (Ceres' accepted trial step), with *point unchanged since, starts from that
// evaluation's point instead, already minimised for those cameras. Evaluate returns false when the
// point cannot be found: an observation that cannot see it, or a singular system (no parallax).
// Evaluations of one factor must not run concurrently (Ceres evaluates each residual block once at
// a time).

#include <ceres/cost_function.h>
#include <ceres/loss_function.h>

#include <Eigen/Core>
#include <array>

#include "trigrav/initializers/observation_residual.h"

namespace trigrav {
struct TripletLinearization;  // factors/src/point_gauss_newton.h (internal)

// Residual: PixelResidual or BearingResidual (observation_residual.h); both are instantiated.
template <typename Residual>
class EliminatedPointReprojectionError final : public ceres::CostFunction {
 public:
  // The observations of the triplet in views 1, 2, 3.
  using Observations = std::array<Residual, 3>;

  // loss: not owned, nullptr for the squared loss; it must outlive the factor. point: see above.
  static EliminatedPointReprojectionError* CreateYawOnly(
      const Observations& observations,
      const std::array<Eigen::Matrix3d, 3>& alignments,
      const ceres::LossFunction* loss,
      double* point);
  static EliminatedPointReprojectionError* CreateWithQuaternions(const Observations& observations,
                                                                 const ceres::LossFunction* loss,
                                                                 double* point);

  bool Evaluate(double const* const* parameters,
                double* residuals,
                double** jacobians) const override;

 private:
  EliminatedPointReprojectionError(const Observations& observations,
                                   bool yaw_only,
                                   const std::array<Eigen::Matrix3d, 3>& alignments,
                                   const ceres::LossFunction* loss,
                                   double* point);
  // The residuals and Jacobian blocks at the point of `lin` (kRotationSize 1: yaws, 4:
  // quaternions).
  template <int kRotationSize>
  bool WriteResiduals(const TripletLinearization& lin,
                      const Eigen::Matrix3d* rotation,
                      const Eigen::Vector3d* center,
                      const Eigen::Vector3d& point,
                      double const* const* parameters,
                      double* residuals,
                      double** jacobians) const;

  // The values of the parameter blocks in order (yaw-only: the first 8, then zeros).
  std::array<double, 14> ParameterValues(double const* const* parameters) const;

  Observations observations_;
  bool yaw_only_;
  std::array<Eigen::Matrix3d, 3> alignments_;  // yaw-only: A_1, A_2, A_3
  const ceres::LossFunction* loss_;
  double* point_;
  // The last evaluation without Jacobians, if it succeeded: its parameter values, the *point it
  // started from and the point it found.
  mutable bool trial_valid_ = false;
  mutable std::array<double, 14> trial_parameters_;
  mutable Eigen::Vector3d trial_start_;
  mutable Eigen::Vector3d trial_point_;
};

}  // namespace trigrav

#endif  // TRIGRAV_FACTORS_ELIMINATED_POINT_REPROJECTION_ERROR_H_
