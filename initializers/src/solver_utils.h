// Internal helpers shared by the trifocal solvers: input checks, small null-space routines, view-1
// depths and the gravity wrapper. Not installed; not part of the public API.
#ifndef TRIGRAV_INITIALIZERS_SRC_SOLVER_UTILS_H_
#define TRIGRAV_INITIALIZERS_SRC_SOLVER_UTILS_H_

#include <cmath>
#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <Eigen/QR>

#include "trigrav/initializers/camera_pose.h"
#include "trigrav/initializers/gravity.h"

namespace trigrav {
namespace internal {

// Throws std::invalid_argument unless x1, x2, x3 have the same size within
// [min_triplets, max_triplets], every ray is finite with non-zero length, and solutions is not null.
void CheckTriplets(const char* solver, std::size_t min_triplets, std::size_t max_triplets,
                   const std::vector<Eigen::Vector3d>& x1, const std::vector<Eigen::Vector3d>& x2,
                   const std::vector<Eigen::Vector3d>& x3, const void* solutions);

// Throws std::invalid_argument if a gravity direction is non-finite or has zero length.
void CheckGravity(const char* solver, const char* name, const Eigen::Vector3d& gravity);

// Unit vector spanning the (numerical) null space of a 3x3 matrix: its smallest right singular vector,
// by inverse iteration on the adjugate (adj(M^T M) = adj(M) adj(M)^T). Zero if M has rank <= 1.
Eigen::Vector3d NullVector3(const Eigen::Matrix3d& M);

// Smallest right singular vector (unit) of an upper-triangular n x n matrix R, by inverse iteration
// x <- (R^T R)^-1 x started from R^-1 e_n. Diagonal entries below eps * max|diag| are raised to that
// floor, which keeps the solves finite and makes the exact null vector a fixed point.
template <int N>
Eigen::Matrix<double, N, 1> SmallestRightSingularVectorOfTriangular(
    const Eigen::Matrix<double, N, N>& R) {
  Eigen::Matrix<double, N, N> R_floor = R.template triangularView<Eigen::Upper>();
  const double floor = std::numeric_limits<double>::epsilon() *
                       std::max(R.diagonal().cwiseAbs().maxCoeff(), 1e-300);
  for (int i = 0; i < N; ++i) {
    if (std::abs(R_floor(i, i)) < floor) R_floor(i, i) = R_floor(i, i) < 0.0 ? -floor : floor;
  }
  Eigen::Matrix<double, N, 1> x = Eigen::Matrix<double, N, 1>::Unit(N - 1);
  R_floor.template triangularView<Eigen::Upper>().solveInPlace(x);
  x.normalize();
  constexpr int kMaxIterations = 100;
  for (int iteration = 0; iteration < kMaxIterations; ++iteration) {
    Eigen::Matrix<double, N, 1> next = x;
    R_floor.transpose().template triangularView<Eigen::Lower>().solveInPlace(next);
    R_floor.template triangularView<Eigen::Upper>().solveInPlace(next);
    next.normalize();
    if (next.dot(x) < 0.0) next = -next;
    const double change = (next - x).squaredNorm();
    x = next;
    if (change < 1e-30) break;
  }
  return x;
}

// Upper-triangular C x C factor R of a tall matrix (R^T R = A^T A), padded with zero rows when A has
// fewer rows than columns.
template <typename Derived>
Eigen::Matrix<double, Derived::ColsAtCompileTime, Derived::ColsAtCompileTime> TriangularFactor(
    const Eigen::MatrixBase<Derived>& A) {
  constexpr int C = Derived::ColsAtCompileTime;
  using PlainMatrix = typename Derived::PlainObject;
  const Eigen::HouseholderQR<PlainMatrix> qr(A.derived());
  Eigen::Matrix<double, C, C> R = Eigen::Matrix<double, C, C>::Zero();
  const Eigen::Index rows = std::min<Eigen::Index>(A.rows(), C);
  R.topRows(rows) = qr.matrixQR().topRows(rows).template triangularView<Eigen::Upper>();
  return R;
}

// View-1 depth of the point seen along x1 and xk, from the pair (1, k) alone, with
// xk ~ R (X - center): lambda = ((xk x R center) . (xk x R x1)) / |xk x R x1|^2 (math note 3.4).
// NaN-free: returns 0 when the rays are parallel after rotation.
inline double ViewOneDepth(const Eigen::Vector3d& x1, const Eigen::Vector3d& xk,
                           const Eigen::Matrix3d& R, const Eigen::Vector3d& center) {
  const Eigen::Vector3d a = xk.cross(R * x1);
  const double denominator = a.squaredNorm();
  if (!(denominator > 0.0)) return 0.0;
  return xk.cross(R * center).dot(a) / denominator;
}

// Orthonormal basis (p1, p2) of the plane orthogonal to x (x non-zero).
inline void PerpendicularBasis(const Eigen::Vector3d& x, Eigen::Vector3d* p1, Eigen::Vector3d* p2) {
  const Eigen::Vector3d unit = x.normalized();
  *p1 = unit.unitOrthogonal();
  *p2 = unit.cross(*p1);
}

// The 4 trifocal incidence equations of one aligned triplet as linear functions of the centres
// (c_2; c_3) for fixed yaws (math note 4.1): with u = x2 x R2 x1, z = R3 x1 x x3 and (p_a), (r_b) bases
// of x2^perp and x3^perp, row (a, b) = [ (z . r_b) (p_a x x2)^T R2 , (p_a . u) (r_b x x3)^T R3 ].
Eigen::Matrix<double, 4, 6> TranslationRows(const Eigen::Vector3d& x1, const Eigen::Vector3d& x2,
                                            const Eigen::Vector3d& x3, const Eigen::Matrix3d& R2,
                                            const Eigen::Matrix3d& R3);

// Finishes an aligned three-view estimate known up to a common factor of the centres: flips the sign
// of (c2, c3) if most view-1 depths of pairs (1,2) and (1,3) are negative, scales to |c2| = 1 and
// writes the pose. Returns false (writing nothing) if the result is degenerate or not finite.
bool OrientScaleAndMakePose(const std::vector<Eigen::Vector3d>& x1,
                            const std::vector<Eigen::Vector3d>& x2,
                            const std::vector<Eigen::Vector3d>& x3, double theta2,
                            Eigen::Vector3d center2, double theta3, Eigen::Vector3d center3,
                            ThreeViewPose* pose);

// Pose of camera k in the aligned frames from its yaw and its centre: R = R_y(theta), t = -R c.
inline CameraPose PoseFromYawAndCenter(double theta, const Eigen::Vector3d& center) {
  CameraPose pose;
  pose.R = RotationAboutY(theta);
  pose.t = -pose.R * center;
  return pose;
}

// Runs a solver for gravity-aligned rays on raw rays: aligns the rays with each camera's gravity
// (R_align g = e_y), solves, and maps every pose back with the corrected eq. b4 (UnalignPose).
template <typename AlignedSolver>
int SolveWithGravity(const char* solver, const std::vector<Eigen::Vector3d>& x1,
                     const std::vector<Eigen::Vector3d>& x2, const std::vector<Eigen::Vector3d>& x3,
                     const Eigen::Vector3d& gravity_in_cam1, const Eigen::Vector3d& gravity_in_cam2,
                     const Eigen::Vector3d& gravity_in_cam3, std::vector<ThreeViewPose>* solutions,
                     AlignedSolver&& solve_aligned) {
  CheckGravity(solver, "gravity_in_cam1", gravity_in_cam1);
  CheckGravity(solver, "gravity_in_cam2", gravity_in_cam2);
  CheckGravity(solver, "gravity_in_cam3", gravity_in_cam3);
  const Eigen::Matrix3d align1 = GravityAlignmentFromGravity(gravity_in_cam1);
  const Eigen::Matrix3d align2 = GravityAlignmentFromGravity(gravity_in_cam2);
  const Eigen::Matrix3d align3 = GravityAlignmentFromGravity(gravity_in_cam3);
  const int count =
      solve_aligned(AlignRays(align1, x1), AlignRays(align2, x2), AlignRays(align3, x3), solutions);
  for (ThreeViewPose& pose : *solutions) pose = UnalignThreeViewPose(pose, align1, align2, align3);
  return count;
}

}  // namespace internal
}  // namespace trigrav

#endif  // TRIGRAV_INITIALIZERS_SRC_SOLVER_UTILS_H_
