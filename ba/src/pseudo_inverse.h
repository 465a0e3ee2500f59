#ifndef TRIGRAV_BA_SRC_PSEUDO_INVERSE_H_
#define TRIGRAV_BA_SRC_PSEUDO_INVERSE_H_

// The pseudo-inverse of a point's 3 x 3 information block, one definition for the covariances of
// both adjusters (three_view_covariance.cc, nview_covariance.cc) when they eliminate the points.
// Not installed; not part of the public API.

#include <Eigen/Core>
#include <Eigen/Eigenvalues>

namespace trigrav {
namespace internal {

// V^+ of a symmetric 3 x 3 V (a point's information J_p^T J_p): eigenvalues at or below
// relative_floor * max |eigenvalue| are dropped, so a direction the observations do not constrain
// (a distant point's depth, a point seen along a zero baseline) couples to no pose parameter. A
// zero matrix gives zero.
inline Eigen::Matrix3d PseudoInverse(const Eigen::Matrix3d& v, double relative_floor) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(v);
  const Eigen::Vector3d& values = eigen.eigenvalues();
  const double floor = relative_floor * values.cwiseAbs().maxCoeff();
  Eigen::Vector3d inverse = Eigen::Vector3d::Zero();
  for (int i = 0; i < 3; ++i) {
    if (values[i] > floor) inverse[i] = 1.0 / values[i];
  }
  return eigen.eigenvectors() * inverse.asDiagonal() * eigen.eigenvectors().transpose();
}

}  // namespace internal
}  // namespace trigrav

#endif  // TRIGRAV_BA_SRC_PSEUDO_INVERSE_H_
