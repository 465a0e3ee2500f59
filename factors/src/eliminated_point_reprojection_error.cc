// EliminatedPointReprojectionError (ba/derivations.md section 15).
#include "trigrav/factors/eliminated_point_reprojection_error.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "observation_jacobian.h"
#include "point_gauss_newton.h"
#include "trigrav/initializers/gravity.h"
#include "trigrav/initializers/skew.h"

namespace trigrav {
namespace {

// The rotation Ceres' UnitQuaternionRotatePoint applies, x -> x + 2w (v x x) + 2 v x (v x x),
// as a matrix (q = [w, v]).
Eigen::Matrix3d UnitQuaternionMatrix(const double* q) {
  const Eigen::Matrix3d v = Skew(Eigen::Vector3d(q[1], q[2], q[3]));
  return Eigen::Matrix3d::Identity() + 2.0 * q[0] * v + 2.0 * v * v;
}

// d/dq of that map at d (3 x 4, ambient): with u = v x d, d/dw = 2u and
// d/dv = -2w [d]x - 2 [u]x - 2 [v]x [d]x.
Eigen::Matrix<double, 3, 4> UnitQuaternionRotateJacobian(const double* q,
                                                         const Eigen::Vector3d& d) {
  const Eigen::Vector3d v(q[1], q[2], q[3]);
  const Eigen::Vector3d u = v.cross(d);
  Eigen::Matrix<double, 3, 4> jacobian;
  jacobian.col(0) = 2.0 * u;
  jacobian.rightCols<3>() = -2.0 * q[0] * Skew(d) - 2.0 * Skew(u) - 2.0 * Skew(v) * Skew(d);
  return jacobian;
}

}  // namespace

template <typename Residual>
EliminatedPointReprojectionError<Residual>::EliminatedPointReprojectionError(
    const Observations& observations,
    bool yaw_only,
    const std::array<Eigen::Matrix3d, 3>& alignments,
    const ceres::LossFunction* loss,
    double* point)
    : observations_(observations),
      yaw_only_(yaw_only),
      alignments_(alignments),
      loss_(loss),
      point_(point) {
  const int rotation_size = yaw_only ? 1 : 4;
  set_num_residuals(6);
  *mutable_parameter_block_sizes() = {rotation_size, 3, rotation_size, 3};
}

template <typename Residual>
EliminatedPointReprojectionError<Residual>*
EliminatedPointReprojectionError<Residual>::CreateYawOnly(
    const Observations& observations,
    const std::array<Eigen::Matrix3d, 3>& alignments,
    const ceres::LossFunction* loss,
    double* point) {
  return new EliminatedPointReprojectionError(observations, true, alignments, loss, point);
}

template <typename Residual>
EliminatedPointReprojectionError<Residual>*
EliminatedPointReprojectionError<Residual>::CreateWithQuaternions(const Observations& observations,
                                                                  const ceres::LossFunction* loss,
                                                                  double* point) {
  const Eigen::Matrix3d identity = Eigen::Matrix3d::Identity();
  return new EliminatedPointReprojectionError(observations, false, {identity, identity, identity},
                                              loss, point);
}

template <typename Residual>
std::array<double, 14> EliminatedPointReprojectionError<Residual>::ParameterValues(
    double const* const* parameters) const {
  std::array<double, 14> values{};
  const int rotation_size = yaw_only_ ? 1 : 4;
  double* out = values.data();
  for (int b = 0; b < 4; ++b) out = std::copy_n(parameters[b], b % 2 == 0 ? rotation_size : 3, out);
  return values;
}

template <typename Residual>
bool EliminatedPointReprojectionError<Residual>::Evaluate(double const* const* parameters,
                                                          double* residuals,
                                                          double** jacobians) const {
  Eigen::Matrix3d rotation[3];
  Eigen::Vector3d center[3];
  rotation[0].setIdentity();
  center[0].setZero();
  for (int j = 0; j < 2; ++j) {
    const double* rotation_block = parameters[2 * j];
    rotation[j + 1] = yaw_only_
                          ? Eigen::Matrix3d(alignments_[j + 1].transpose() *
                                            RotationAboutY(rotation_block[0]) * alignments_[0])
                          : UnitQuaternionMatrix(rotation_block);
    center[j + 1] = Eigen::Map<const Eigen::Vector3d>(parameters[2 * j + 1]);
  }

  // The point: minimised from the stored one, or, for Jacobians at the cameras of the last
  // evaluation without them (Ceres' accepted trial step) and from the same stored point, from
  // that evaluation's point (section 15.1).
  const std::array<double, 14> values = ParameterValues(parameters);
  const Eigen::Vector3d stored = Eigen::Map<const Eigen::Vector3d>(point_);
  const bool at_trial =
      jacobians != nullptr && trial_valid_ && values == trial_parameters_ && stored == trial_start_;
  Eigen::Vector3d point = at_trial ? trial_point_ : stored;
  const auto observe = [this](int k, const Eigen::Vector3d& x_cam, Eigen::Vector2d* r,
                              Eigen::Matrix<double, 2, 3>* d_r_d_x) {
    return LinearizeObservation(observations_[k], x_cam, r, d_r_d_x);
  };
  TripletLinearization lin;
  trial_valid_ = false;
  if (!LinearizeTriplet(observe, loss_, rotation, center, point, &lin) ||
      !MinimizeTripletCost(observe, loss_, rotation, center, &point, &lin)) {
    return false;
  }

  // Ceres asks for Jacobians at its accepted iterates only: keep the point of those. A rejected
  // step's point may lie in another basin of an outlier's robust cost, and starting from it would
  // make the cost at the iterate depend on the steps tried (section 15.1). A trial's point is kept
  // aside, for the Jacobians should Ceres accept the trial.
  if (jacobians != nullptr) {
    std::copy_n(point.data(), 3, point_);
  } else {
    trial_parameters_ = values;
    trial_start_ = stored;
    trial_point_ = point;
    trial_valid_ = true;
  }
  return yaw_only_
             ? WriteResiduals<1>(lin, rotation, center, point, parameters, residuals, jacobians)
             : WriteResiduals<4>(lin, rotation, center, point, parameters, residuals, jacobians);
}

template <typename Residual>
template <int kRotationSize>
bool EliminatedPointReprojectionError<Residual>::WriteResiduals(const TripletLinearization& lin,
                                                                const Eigen::Matrix3d* rotation,
                                                                const Eigen::Vector3d* center,
                                                                const Eigen::Vector3d& point,
                                                                double const* const* parameters,
                                                                double* residuals,
                                                                double** jacobians) const {
  // Residuals sqrt(rho / s) r and their derivative (w I + 2 w' r r^T) J with w = sqrt(rho / s),
  // w' = dw/ds = (rho' s - rho) / (2 w s^2), or rho'' / (4 w) near s = 0 (section 15.2).
  constexpr int kCameraSize = kRotationSize + 3;
  Eigen::Matrix<double, 6, 3> jx;
  Eigen::Matrix<double, 6, 2 * kCameraSize> jc = Eigen::Matrix<double, 6, 2 * kCameraSize>::Zero();
  for (int k = 0; k < 3; ++k) {
    const double s = lin.r[k].squaredNorm();
    const double* rho = lin.rho[k];
    const double w = s > 0.0 ? std::sqrt(rho[0] / s) : std::sqrt(rho[1]);
    const double dw = s * std::abs(rho[2]) > 1e-6 ? (rho[1] * s - rho[0]) / (2.0 * w * s * s)
                                                  : rho[2] / (4.0 * w);
    Eigen::Map<Eigen::Vector2d>(residuals + 2 * k) = w * lin.r[k];
    if (jacobians == nullptr) continue;
    const Eigen::Matrix2d scale =
        w * Eigen::Matrix2d::Identity() + 2.0 * dw * lin.r[k] * lin.r[k].transpose();
    const Eigen::Matrix<double, 2, 3> jr = scale * lin.jr[k];
    jx.middleRows<2>(2 * k) = jr * rotation[k];
    if (k == 0) continue;
    const int offset = (k - 1) * kCameraSize;
    if constexpr (kRotationSize == 1) {
      // d x_cam / d yaw = g_k x x_cam, g_k = A_k^T e_y (section 13.1).
      const Eigen::Vector3d axis = alignments_[k].row(1).transpose();
      jc.template block<2, 1>(2 * k, offset) = jr * axis.cross(lin.x_cam[k]);
    } else {
      jc.template block<2, 4>(2 * k, offset) =
          jr * UnitQuaternionRotateJacobian(parameters[2 * (k - 1)], point - center[k]);
    }
    jc.template block<2, 3>(2 * k, offset + kRotationSize) = -jx.middleRows<2>(2 * k);
  }
  if (jacobians == nullptr) return true;
  // The point follows the cameras: project J_cameras off the columns of J_X.
  Eigen::Matrix3d normal_inverse;
  if (!InvertDampedPointMatrix(jx.transpose() * jx, &normal_inverse)) return false;
  const Eigen::Matrix<double, 6, 2 * kCameraSize> reduced =
      jc - jx * (normal_inverse * (jx.transpose() * jc));
  if (!reduced.allFinite()) return false;
  constexpr int kSizes[4] = {kRotationSize, 3, kRotationSize, 3};
  int column = 0;
  for (int b = 0; b < 4; ++b) {
    if (jacobians[b] != nullptr) {
      for (int row = 0; row < 6; ++row) {
        for (int c = 0; c < kSizes[b]; ++c) {
          jacobians[b][row * kSizes[b] + c] = reduced(row, column + c);
        }
      }
    }
    column += kSizes[b];
  }
  return true;
}

template class EliminatedPointReprojectionError<PixelResidual>;
template class EliminatedPointReprojectionError<BearingResidual>;

}  // namespace trigrav
