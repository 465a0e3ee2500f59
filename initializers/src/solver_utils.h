// Internal helpers shared by the trifocal solvers: input checks, small null-space routines, view-1
// depths and the gravity wrapper. Not installed; not part of the public API.
#ifndef TRIGRAV_INITIALIZERS_SRC_SOLVER_UTILS_H_
#define TRIGRAV_INITIALIZERS_SRC_SOLVER_UTILS_H_

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <Eigen/QR>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include "trigrav/initializers/camera_pose.h"
#include "trigrav/initializers/gravity.h"

namespace trigrav {
namespace internal {

// True if v is finite with a non-zero length whose square does not overflow, which the input checks
// demand of rays and gravity. One comparison: NaN fails it, and an infinite entry or an overflowing
// length gives an infinite squared length.
inline bool IsUsableDirection(const Eigen::Vector3d& v) {
  const double squared = v.squaredNorm();
  return squared > 0.0 && squared <= std::numeric_limits<double>::max();
}

// Throws std::invalid_argument unless x1, x2, x3 have the same size within
// [min_triplets, max_triplets], every ray is finite with non-zero length, and solutions is not
// null.
void CheckTriplets(const char* solver,
                   std::size_t min_triplets,
                   std::size_t max_triplets,
                   const std::vector<Eigen::Vector3d>& x1,
                   const std::vector<Eigen::Vector3d>& x2,
                   const std::vector<Eigen::Vector3d>& x3,
                   const void* solutions);

// The two-view counterpart of CheckTriplets: throws std::invalid_argument unless x1, x2 have the
// same size within [min_pairs, max_pairs], every ray is finite with non-zero length, and solutions
// is not null.
void CheckPairs(const char* solver,
                std::size_t min_pairs,
                std::size_t max_pairs,
                const std::vector<Eigen::Vector3d>& x1,
                const std::vector<Eigen::Vector3d>& x2,
                const void* solutions);

// Throws std::invalid_argument if a gravity direction is non-finite or has zero length.
void CheckGravity(const char* solver, const char* name, const Eigen::Vector3d& gravity);

// Throws std::invalid_argument naming the first pose with a non-finite entry, as "name[i]".
void CheckPoses(const char* solver, const char* name, const std::vector<CameraPose>& poses);

// Unit vector spanning the (numerical) null space of a 3x3 matrix: its smallest right singular
// vector, by inverse iteration on the adjugate (adj(M^T M) = adj(M) adj(M)^T). Zero if M has rank
// <= 1.
Eigen::Vector3d NullVector3(const Eigen::Matrix3d& M);

// Relative size below which a pivot counts as zero when deciding that a minimal system has more
// than a one-dimensional null space (degenerate input).
constexpr double kRankTolerance = 1e-10;
// The same for the diagonal of a triangular factor, which may come from the ridged Gram matrix of
// StackedTriangularFactor (null directions then sit near sqrt(1e-15) = 3e-8 of the largest entry,
// plus the rounding of a rank-deficient Cholesky factorisation).
constexpr double kTriangularRankTolerance = 1e-6;

// True if the upper-triangular R (R^T R = A^T A) shows a null space of A of dimension 2 or more: a
// triangular matrix of rank n - 2 or less has at least two (numerically) zero diagonal entries.
template <int N>
bool HasMultipleNullDirections(const Eigen::Matrix<double, N, N>& R) {
  const Eigen::Matrix<double, N, 1> diagonal = R.diagonal().cwiseAbs();
  const double tolerance = kTriangularRankTolerance * diagonal.maxCoeff();
  return (diagonal.array() <= tolerance).count() >= 2;
}

// Smallest right singular vector (unit) of an upper-triangular n x n matrix R, by inverse iteration
// x <- (R^T R)^-1 x started from R^-1 e_n. Diagonal entries below eps * max|diag| are raised to
// that floor, which keeps the solves finite and makes the exact null vector a fixed point.
template <int N>
Eigen::Matrix<double, N, 1> SmallestRightSingularVectorOfTriangular(
    const Eigen::Matrix<double, N, N>& R) {
  Eigen::Matrix<double, N, N> R_floor = R.template triangularView<Eigen::Upper>();
  const double floor =
      std::numeric_limits<double>::epsilon() * std::max(R.diagonal().cwiseAbs().maxCoeff(), 1e-300);
  for (int i = 0; i < N; ++i) {
    if (std::abs(R_floor(i, i)) < floor) R_floor(i, i) = R_floor(i, i) < 0.0 ? -floor : floor;
  }
  Eigen::Matrix<double, N, 1> x = Eigen::Matrix<double, N, 1>::Unit(N - 1);
  R_floor.template triangularView<Eigen::Upper>().solveInPlace(x);
  x.normalize();
  // Stops at convergence or once rounding noise keeps the step from shrinking.
  constexpr int kMaxIterations = 100;
  double previous_change = std::numeric_limits<double>::infinity();
  for (int iteration = 0; iteration < kMaxIterations; ++iteration) {
    Eigen::Matrix<double, N, 1> next = x;
    R_floor.transpose().template triangularView<Eigen::Lower>().solveInPlace(next);
    R_floor.template triangularView<Eigen::Upper>().solveInPlace(next);
    next.normalize();
    if (next.dot(x) < 0.0) next = -next;
    const double change = (next - x).squaredNorm();
    x = next;
    if (change < 1e-30 || (change < 1e-20 && change > 0.25 * previous_change)) break;
    previous_change = change;
  }
  return x;
}

// Unit null vector of an (C-1) x C matrix, by Gaussian elimination with partial pivoting and back
// substitution with x_C = 1: half the flops of a QR for the exactly determined minimal systems.
// Returns the zero vector when the matrix is not of full row rank (a pivot below kRankTolerance
// times the largest entry): its null space is then more than one-dimensional and no single answer
// exists.
template <int C>
Eigen::Matrix<double, C, 1> NullVectorOfWideMatrix(const Eigen::Matrix<double, C - 1, C>& A) {
  constexpr int R = C - 1;
  // Row operations span the full fixed-size row (the zeros left of the pivot included): more flops
  // than trimmed rows, but unrolled and vectorised, which is faster at this size.
  using Row = Eigen::Matrix<double, 1, C>;
  std::array<Row, R> U;
  for (int i = 0; i < R; ++i) U[i] = A.row(i);
  const double tolerance = kRankTolerance * A.cwiseAbs().maxCoeff();
  if (!(tolerance > 0.0)) return Eigen::Matrix<double, C, 1>::Zero();
  for (int k = 0; k < R; ++k) {
    int pivot = k;
    for (int i = k + 1; i < R; ++i) {
      if (std::abs(U[i][k]) > std::abs(U[pivot][k])) pivot = i;
    }
    std::swap(U[k], U[pivot]);
    if (!(std::abs(U[k][k]) > tolerance)) return Eigen::Matrix<double, C, 1>::Zero();
    const double inverse_pivot = 1.0 / U[k][k];
    for (int i = k + 1; i < R; ++i) U[i] -= (U[i][k] * inverse_pivot) * U[k];
  }
  Eigen::Matrix<double, C, 1> x = Eigen::Matrix<double, C, 1>::Zero();
  x[C - 1] = 1.0;
  for (int k = R - 1; k >= 0; --k) x[k] = -U[k].dot(x.transpose()) / U[k][k];
  return x.normalized();
}

// Upper Cholesky factor R (R^T R = G + ridge I) of a Gram matrix G = A^T A, with a relative ridge
// of 1e-15 so that an exact null space stays factorable.
template <int C>
Eigen::Matrix<double, C, C> CholeskyFactorOfGram(Eigen::Matrix<double, C, C> gram) {
  const double ridge = 1e-15 * gram.trace();
  gram.diagonal().array() += ridge > 0.0 ? ridge : 1e-300;
  return Eigen::LLT<Eigen::Matrix<double, C, C>>(gram).matrixU();
}

// Upper-triangular C x C factor R of a matrix with C columns (R^T R = A^T A), padded with zero rows
// when A has fewer rows than columns. Up to kMaxHouseholderRows rows: unblocked Householder
// triangularisation in place (for the small fixed-size systems of the solvers several times faster
// than Eigen's blocked HouseholderQR, and allocation-free). Taller systems, the non-minimal
// least-squares solves on many inliers, use CholeskyFactorOfGram(A^T A): 4x fewer flops, no copy of
// A; the squared conditioning is far below the noise of such problems, and the solvers polish
// afterwards.
constexpr int kMaxHouseholderRows = 64;

template <typename Derived>
Eigen::Matrix<double, Derived::ColsAtCompileTime, Derived::ColsAtCompileTime> TriangularFactor(
    const Eigen::MatrixBase<Derived>& A_in) {
  constexpr int C = Derived::ColsAtCompileTime;
  if (Derived::RowsAtCompileTime == Eigen::Dynamic && A_in.rows() > kMaxHouseholderRows) {
    Eigen::Matrix<double, C, C> gram = Eigen::Matrix<double, C, C>::Zero();
    gram.template selfadjointView<Eigen::Lower>().rankUpdate(A_in.transpose());
    return CholeskyFactorOfGram<C>(gram);
  }
  using Column =
      Eigen::Matrix<double, Derived::RowsAtCompileTime, 1, 0, Derived::MaxRowsAtCompileTime, 1>;
  typename Derived::PlainObject A = A_in;
  const Eigen::Index m = A.rows();
  const Eigen::Index steps = std::min<Eigen::Index>(m, C);
  for (Eigen::Index j = 0; j < steps; ++j) {
    // Reflector H = I - 2 v v^T / (v^T v), v = x - alpha e_j with x = column j below row j, mapping
    // x to alpha e_j. v is kept at full column length (zeros above j) so the updates are
    // fixed-size.
    Column v = A.col(j);
    v.head(j).setZero();
    const double x0 = v[j];
    const double norm = v.norm();
    const double alpha = x0 <= 0.0 ? norm : -norm;
    v[j] = x0 - alpha;
    const double v_squared = v.squaredNorm();
    if (v_squared > 0.0) {
      const double scale = 2.0 / v_squared;
      for (Eigen::Index k = j + 1; k < C; ++k) A.col(k) -= (scale * v.dot(A.col(k))) * v;
    }
    A.col(j).tail(m - j).setZero();
    A(j, j) = v_squared > 0.0 ? alpha : x0;
  }
  Eigen::Matrix<double, C, C> R = Eigen::Matrix<double, C, C>::Zero();
  R.topRows(steps) = A.topRows(steps);
  return R;
}

// Triangular factor R (R^T R = sum_n B_n^T B_n) of the system stacked from the row blocks
// B_n = block(n), n < count (each with C columns): Householder on the stacked rows while they fit
// in kMaxHouseholderRows (on the stack, no allocation), otherwise the Cholesky factor of the Gram
// matrix streamed block by block, so a tall system is never formed.
template <int C, typename BlockFunction>
Eigen::Matrix<double, C, C> StackedTriangularFactor(std::size_t count, BlockFunction block) {
  using Block = decltype(block(std::size_t{0}));
  constexpr int kBlockRows = Block::RowsAtCompileTime;
  if (count * kBlockRows <= static_cast<std::size_t>(kMaxHouseholderRows)) {
    Eigen::Matrix<double, Eigen::Dynamic, C, 0, kMaxHouseholderRows, C> stacked(count * kBlockRows,
                                                                                C);
    for (std::size_t n = 0; n < count; ++n) {
      stacked.template middleRows<kBlockRows>(n * kBlockRows) = block(n);
    }
    return TriangularFactor(stacked);
  }
  Eigen::Matrix<double, C, C> gram = Eigen::Matrix<double, C, C>::Zero();
  for (std::size_t n = 0; n < count; ++n) {
    const Block B = block(n);
    gram.noalias() += B.transpose().lazyProduct(B);
  }
  return CholeskyFactorOfGram<C>(gram);
}

// View-1 depth of the point seen along x1 and xk, from the pair (1, k) alone, with
// xk ~ R (X - center): lambda = ((xk x R center) . (xk x R x1)) / |xk x R x1|^2 (math note 3.4).
// NaN-free: returns 0 when the rays are parallel after rotation.
inline double ViewOneDepth(const Eigen::Vector3d& x1,
                           const Eigen::Vector3d& xk,
                           const Eigen::Matrix3d& R,
                           const Eigen::Vector3d& center) {
  const Eigen::Vector3d a = xk.cross(R * x1);
  const double denominator = a.squaredNorm();
  if (!(denominator > 0.0)) return 0.0;
  return xk.cross(R * center).dot(a) / denominator;
}

// Sine of the angle below which the rays of a view pair count as parallel: baseline / depth below
// 1e-4, a twentieth of a pixel at f = 500 px.
constexpr double kMinPairParallax = 1e-4;

// True if one rotation about the y axis (gravity, in aligned frames) maps every ray x1_n onto xk_n
// to within kMinPairParallax: the pair (1,k) has no parallax (zero baseline, identical views,
// points at infinity) and the direction of camera k's centre is not determined. The yaw maximises
// sum_n xk_n . R_y(theta) x1_n (Wahba's problem about one axis, rays weighted by their lengths,
// which leaves an exact rotation exact). Cheap enough for every minimal solve: a yaw keeps the
// elevation of a ray, so a first triplet whose elevations differ settles it without the fit.
inline bool PairExplainedByYaw(const std::vector<Eigen::Vector3d>& x1,
                               const std::vector<Eigen::Vector3d>& xk) {
  // Elevations y / |x| within kMinPairParallax of each other: a necessary condition, compared
  // squared (|a^2 - b^2| <= 2 |a - b| for |a|, |b| <= 1) with the signs, without division.
  const double y1 = x1[0].y(), yk = xk[0].y();
  const double n1 = x1[0].squaredNorm(), nk = xk[0].squaredNorm();
  constexpr double kTolerance2 = kMinPairParallax * kMinPairParallax;
  if (std::abs(y1 * y1 * nk - yk * yk * n1) > 2.0 * kMinPairParallax * n1 * nk ||
      (y1 * yk < 0.0 && (y1 * y1 > kTolerance2 * n1 || yk * yk > kTolerance2 * nk))) {
    return false;
  }
  double cosine = 0.0, sine = 0.0;
  for (std::size_t n = 0; n < x1.size(); ++n) {
    cosine += xk[n].x() * x1[n].x() + xk[n].z() * x1[n].z();
    sine += xk[n].x() * x1[n].z() - xk[n].z() * x1[n].x();
  }
  const double norm = std::sqrt(cosine * cosine + sine * sine);
  const double c = norm > 0.0 ? cosine / norm : 1.0, s = norm > 0.0 ? sine / norm : 0.0;
  for (std::size_t n = 0; n < x1.size(); ++n) {
    const Eigen::Vector3d rotated(c * x1[n].x() + s * x1[n].z(), x1[n].y(),
                                  c * x1[n].z() - s * x1[n].x());
    if (rotated.cross(xk[n]).squaredNorm() >=
        kMinPairParallax * kMinPairParallax * rotated.squaredNorm() * xk[n].squaredNorm()) {
      return false;
    }
  }
  return true;
}

// Orthonormal basis (p1, p2) of the plane orthogonal to x (x non-zero).
inline void PerpendicularBasis(const Eigen::Vector3d& x, Eigen::Vector3d* p1, Eigen::Vector3d* p2) {
  const Eigen::Vector3d unit = x.normalized();
  *p1 = unit.unitOrthogonal();
  *p2 = unit.cross(*p1);
}

// The 4 trifocal incidence equations of one aligned triplet as linear functions of the centres
// (c_2; c_3) for fixed yaws (math note 4.1): with u = x2 x R2 x1, z = R3 x1 x x3 and (p_a), (r_b)
// bases of x2^perp and x3^perp, row (a, b) = [ (z . r_b) (p_a x x2)^T R2 , (p_a . u) (r_b x x3)^T
// R3 ].
Eigen::Matrix<double, 4, 6> TranslationRows(const Eigen::Vector3d& x1,
                                            const Eigen::Vector3d& x2,
                                            const Eigen::Vector3d& x3,
                                            const Eigen::Matrix3d& R2,
                                            const Eigen::Matrix3d& R3);

// One Gauss-Newton step on the incidence residuals r = F(theta2, theta3) (c2; c3) of all triplets
// (the rows of TranslationRows), jointly over the yaws and the centres, with |(c2; c3)| held fixed
// to first order. Noise-free it converges quadratically to the exact pose, removing the rounding
// tail of the linear solvers (whose yaw error the translation solve amplifies); with noise it moves
// the estimate to the nearest minimum of the algebraic residual. Leaves the inputs unchanged if the
// step is not finite.
void RefineYawsAndCenters(const std::vector<Eigen::Vector3d>& x1,
                          const std::vector<Eigen::Vector3d>& x2,
                          const std::vector<Eigen::Vector3d>& x3,
                          double* theta2,
                          double* theta3,
                          Eigen::Vector3d* center2,
                          Eigen::Vector3d* center3);

// Finishes an aligned three-view estimate known up to a common factor of the centres: flips the
// sign of (c2, c3) if most view-1 depths of pairs (1,2) and (1,3) are negative, scales to |c2| = 1
// and writes the pose. Returns false (writing nothing) if the result is degenerate or not finite.
bool OrientScaleAndMakePose(const std::vector<Eigen::Vector3d>& x1,
                            const std::vector<Eigen::Vector3d>& x2,
                            const std::vector<Eigen::Vector3d>& x3,
                            double theta2,
                            Eigen::Vector3d center2,
                            double theta3,
                            Eigen::Vector3d center3,
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
int SolveWithGravity(const char* solver,
                     const std::vector<Eigen::Vector3d>& x1,
                     const std::vector<Eigen::Vector3d>& x2,
                     const std::vector<Eigen::Vector3d>& x3,
                     const Eigen::Vector3d& gravity_in_cam1,
                     const Eigen::Vector3d& gravity_in_cam2,
                     const Eigen::Vector3d& gravity_in_cam3,
                     std::vector<ThreeViewPose>* solutions,
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
