// The null vector of a 3x3 matrix (null_space.h).
#include "null_space.h"

#include <Eigen/Geometry>

namespace trigrav {
namespace internal {

Eigen::Vector3d NullVector3(const Eigen::Matrix3d& M) {
  const double scale = M.cwiseAbs().maxCoeff();
  if (!(scale > 0.0) || !std::isfinite(scale)) return Eigen::Vector3d::Zero();
  const Eigen::Matrix3d A = M / scale;
  // adj(A) has columns r_j x r_k of the rows of A; for rank 2 every non-zero column spans the null
  // space.
  Eigen::Matrix3d adjugate;
  adjugate.col(0) = A.row(1).cross(A.row(2)).transpose();
  adjugate.col(1) = A.row(2).cross(A.row(0)).transpose();
  adjugate.col(2) = A.row(0).cross(A.row(1)).transpose();
  Eigen::Index best = 0;
  const double largest = adjugate.colwise().squaredNorm().maxCoeff(&best);
  if (!(largest > 0.0)) return Eigen::Vector3d::Zero();
  Eigen::Vector3d x = adjugate.col(best).normalized();
  // Inverse iteration: (A^T A)^-1 is proportional to adj(A) adj(A)^T.
  // Each step shrinks the error by (sigma_3 / sigma_2)^2; stop at convergence or at the rounding
  // floor.
  constexpr int kMaxIterations = 50;
  double previous_change = std::numeric_limits<double>::infinity();
  for (int iteration = 0; iteration < kMaxIterations; ++iteration) {
    Eigen::Vector3d next = adjugate * (adjugate.transpose() * x);
    const double norm = next.norm();
    if (!(norm > 0.0)) break;
    next /= norm;
    if (AcceptInverseIterate(&next, &x, &previous_change)) break;
  }
  return x;
}

}  // namespace internal
}  // namespace trigrav
