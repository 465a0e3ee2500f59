#include "essential_decomposition.h"

#include <Eigen/Geometry>
#include <Eigen/SVD>
#include <cmath>
#include <cstddef>

#include "null_space.h"
#include "two_view_geometry.h"

namespace trigrav {
namespace internal {

namespace {

// Below this parallax (rad) a correspondence is treated as a point at infinity.
constexpr double kMinParallax = 1e-10;

}  // namespace

int ChoosePoseByCheirality(const Eigen::Matrix3d& R_a,
                           const Eigen::Matrix3d& R_b,
                           const Eigen::Vector3d& t,
                           const std::vector<Eigen::Vector3d>& x1,
                           const std::vector<Eigen::Vector3d>& x2,
                           CameraPose* pose) {
  int best_count = 0;
  for (const Eigen::Matrix3d* R : {&R_a, &R_b}) {
    // Both depths are linear in t: flipping t flips both, so one pass counts both signs of t.
    // lambda1 x1 = X in camera 1 (centre -R^T t); lambda2 x2 = R X + t, i.e. camera 1 seen from
    // camera 2 has rotation R^T and centre t.
    const Eigen::Matrix3d R_transpose = R->transpose();
    const Eigen::Vector3d center = -R_transpose * t;
    int positive = 0, negative = 0;
    for (std::size_t n = 0; n < x1.size(); ++n) {
      // Rays parallel after rotation (parallax below kMinParallax rad) carry no depth: no vote.
      const Eigen::Vector3d rotated = *R * x1[n];
      if (!(x2[n].cross(rotated).squaredNorm() >
            kMinParallax * kMinParallax * x2[n].squaredNorm() * rotated.squaredNorm())) {
        continue;
      }
      const double depth1 = ViewOneDepth(x1[n], x2[n], *R, center);
      const double depth2 = ViewOneDepth(x2[n], x1[n], R_transpose, t);
      positive += depth1 > 0.0 && depth2 > 0.0;
      negative += depth1 < 0.0 && depth2 < 0.0;
    }
    if (positive > best_count || negative > best_count) {
      CameraPose candidate;
      candidate.R = *R;
      candidate.t = positive >= negative ? t : Eigen::Vector3d(-t);
      if (!candidate.IsFinite()) continue;
      best_count = positive >= negative ? positive : negative;
      *pose = candidate;
    }
  }
  return best_count;
}

int PoseFromEssential(const Eigen::Matrix3d& E,
                      const std::vector<Eigen::Vector3d>& x1,
                      const std::vector<Eigen::Vector3d>& x2,
                      CameraPose* pose) {
  const double scale = E.cwiseAbs().maxCoeff();
  if (!(scale > 0.0) || !std::isfinite(scale)) return 0;
  // Fixed 3x3 Jacobi SVD: no heap allocation, no QR preconditioner for a square matrix.
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(E / scale, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d U = svd.matrixU();
  Eigen::Matrix3d V = svd.matrixV();
  // E is known up to sign, so U and V may each be negated to make them rotations.
  if (U.determinant() < 0.0) U = -U;
  if (V.determinant() < 0.0) V = -V;
  Eigen::Matrix3d W;
  W << 0.0, -1.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0;
  return ChoosePoseByCheirality(U * W * V.transpose(), U * W.transpose() * V.transpose(), U.col(2),
                                x1, x2, pose);
}

int PoseFromExactEssential(const Eigen::Matrix3d& E_in,
                           const std::vector<Eigen::Vector3d>& x1,
                           const std::vector<Eigen::Vector3d>& x2,
                           CameraPose* pose) {
  const double norm = E_in.norm();
  if (!(norm > 0.0) || !std::isfinite(norm)) return 0;
  const Eigen::Matrix3d E = (std::sqrt(2.0) / norm) * E_in;
  const Eigen::Vector3d t = NullVector3(E.transpose());
  if (!(t.squaredNorm() > 0.0)) return 0;
  Eigen::Matrix3d cofactor;
  cofactor.row(0) = E.row(1).cross(E.row(2));
  cofactor.row(1) = E.row(2).cross(E.row(0));
  cofactor.row(2) = E.row(0).cross(E.row(1));
  Eigen::Matrix3d t_cross;
  t_cross << 0.0, -t.z(), t.y(), t.z(), 0.0, -t.x(), -t.y(), t.x(), 0.0;
  const Eigen::Matrix3d t_cross_E = t_cross * E;
  Eigen::Matrix3d rotations[2] = {cofactor - t_cross_E, cofactor + t_cross_E};
  // Far from essential (e.g. a root of the five-point polynomial that did not converge): project.
  const double orthogonality_error =
      (rotations[0].transpose() * rotations[0] - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  if (!(orthogonality_error < 1e-6)) return PoseFromEssential(E_in, x1, x2, pose);
  for (Eigen::Matrix3d& R : rotations) {
    for (int step = 0; step < 2; ++step) {
      const Eigen::Matrix3d RtR = R.transpose() * R;
      R = R * (1.5 * Eigen::Matrix3d::Identity() - 0.5 * RtR);
    }
  }
  return ChoosePoseByCheirality(rotations[0], rotations[1], t, x1, x2, pose);
}

}  // namespace internal
}  // namespace trigrav
