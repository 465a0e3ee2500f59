// Internal null-space routines of the minimal solvers: the null vector of a 3x3 matrix, of a wide
// (C-1) x C system, and the smallest right singular vector of a triangular factor, with the rank
// tolerances that flag a null space of more than one dimension. Not installed; not part of the
// public API. Fixed sizes throughout: no heap allocation.
#ifndef TRIGRAV_INITIALIZERS_SRC_NULL_SPACE_H_
#define TRIGRAV_INITIALIZERS_SRC_NULL_SPACE_H_

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>

#include "triangular_factor.h"

namespace trigrav {
namespace internal {

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

// One step of the inverse iterations here: makes the new unit iterate *next the current one *x,
// its sign first turned to agree with *x. True once they should stop: at convergence, or once
// rounding noise keeps the step from shrinking (*previous_change holds the last squared step).
template <typename Vector>
bool AcceptInverseIterate(Vector* next, Vector* x, double* previous_change) {
  if (next->dot(*x) < 0.0) *next = -*next;
  const double change = (*next - *x).squaredNorm();
  *x = *next;
  if (change < 1e-30 || (change < 1e-20 && change > 0.25 * *previous_change)) return true;
  *previous_change = change;
  return false;
}

// Smallest right singular vector (unit) of an upper-triangular n x n matrix R: the dominant
// eigenvector of M = (R^T R)^-1, by inverse iteration x <- M x started from R^-1 e_n
// (derivations.md section 9). Diagonal entries below eps * max|diag| are raised to that floor,
// which keeps the solves finite and makes the exact null vector a fixed point. A nearly exact null
// vector (the minimal solvers' usual case) converges in the first step, made by two triangular
// solves. Otherwise, for n <= 9, M = W W^T with W = R^-1 is formed once and squared (and rescaled)
// after every further step, so that step k applies M^(2^k); larger n take up to 100 plain steps.
template <int N>
Eigen::Matrix<double, N, 1> SmallestRightSingularVectorOfTriangular(
    const Eigen::Matrix<double, N, N>& R) {
  using Vector = Eigen::Matrix<double, N, 1>;
  using Matrix = Eigen::Matrix<double, N, N>;
  // Scaled to a largest diagonal entry of 1 (the singular vectors do not change), so that neither
  // the solves' reciprocals nor the powers of M overflow whatever the scale of R.
  const double scale = std::max(R.diagonal().cwiseAbs().maxCoeff(), 1e-300);
  Matrix R_floor = R.template triangularView<Eigen::Upper>();
  R_floor /= scale;
  const double floor = std::numeric_limits<double>::epsilon();
  for (int i = 0; i < N; ++i) {
    if (std::abs(R_floor(i, i)) < floor) R_floor(i, i) = R_floor(i, i) < 0.0 ? -floor : floor;
  }
  Vector x = Vector::Unit(N - 1);
  SolveUpperInPlace(R_floor, &x);
  x.normalize();
  // A squaring costs about n^3 multiply-adds, a plain step n^2: beyond n = 9 the plain steps are
  // kept (at n = 27 the squarings doubled the time of the linear solver on 20 noisy triplets).
  constexpr bool kSquare = N <= 9;
  constexpr int kPlainSteps = kSquare ? 1 : 100;
  double previous_change = std::numeric_limits<double>::infinity();
  Vector next;
  for (int step = 0; step < kPlainSteps; ++step) {
    next = x;
    SolveUpperTransposedInPlace(R_floor, &next);
    SolveUpperInPlace(R_floor, &next);
    next.normalize();
    if (AcceptInverseIterate(&next, &x, &previous_change)) return x;
  }
  if constexpr (!kSquare) return x;
  // Powers M^(2^k), up to M^128.
  Matrix W = Matrix::Identity();
  for (int j = 0; j < N; ++j) {
    Vector column = W.col(j);
    SolveUpperInPlace(R_floor, &column);
    W.col(j) = column;
  }
  Matrix power = W.lazyProduct(W.transpose());
  constexpr int kMaxSquarings = 7;
  for (int squaring = 0; squaring <= kMaxSquarings; ++squaring) {
    const double largest = power.cwiseAbs().maxCoeff();
    if (!(largest > 0.0) || !std::isfinite(largest)) break;
    power /= largest;
    next = power * x;
    next.normalize();
    if (AcceptInverseIterate(&next, &x, &previous_change)) break;
    if (squaring < kMaxSquarings) power = power.lazyProduct(power).eval();
  }
  return x;
}

// Step K of NullVectorOfWideMatrix on the column-major R x C matrix A, in place: partial pivoting
// (the largest |entry| of column K at or below row K; rows swapped from column K on, as only the
// upper triangle is read later), then column K removed from the rows below by one fixed-size
// rank-1 update. Stores 1 / pivot; false if the pivot is numerically zero.
template <int K, int R, int C>
bool EliminateWideColumn(double tolerance,
                         Eigen::Matrix<double, R, C>* A,
                         Eigen::Matrix<double, R, 1>* inverse_pivots) {
  Eigen::Index offset = 0;
  const double largest = A->col(K).template tail<R - K>().cwiseAbs().maxCoeff(&offset);
  if (!(largest > tolerance)) return false;
  if (offset != 0) {
    A->row(K).template tail<C - K>().swap(A->row(K + offset).template tail<C - K>());
  }
  const double inverse_pivot = 1.0 / (*A)(K, K);
  (*inverse_pivots)[K] = inverse_pivot;
  if constexpr (K + 1 < R) {
    constexpr int kRows = R - K - 1;
    const Eigen::Matrix<double, kRows, 1> multipliers =
        inverse_pivot * A->col(K).template tail<kRows>();
    A->template bottomRightCorner<kRows, C - K - 1>().noalias() -=
        multipliers * A->row(K).template tail<C - K - 1>();
  }
  return true;
}

template <int R, int C, int... K>
bool EliminateWideColumns(double tolerance,
                          Eigen::Matrix<double, R, C>* A,
                          Eigen::Matrix<double, R, 1>* inverse_pivots,
                          std::integer_sequence<int, K...>) {
  return (EliminateWideColumn<K>(tolerance, A, inverse_pivots) && ...);
}

// Unit null vector of an (C-1) x C matrix, by Gaussian elimination with partial pivoting and back
// substitution with x_C = 1: half the flops of a QR for the exactly determined minimal systems.
// Each elimination step is unrolled with compile-time block sizes. Returns the zero vector when the
// matrix is not of full row rank (a pivot below kRankTolerance times the largest entry): its null
// space is then more than one-dimensional and no single answer exists.
template <int C>
Eigen::Matrix<double, C, 1> NullVectorOfWideMatrix(Eigen::Matrix<double, C - 1, C> A) {
  constexpr int R = C - 1;
  const double tolerance = kRankTolerance * A.cwiseAbs().maxCoeff();
  if (!(tolerance > 0.0)) return Eigen::Matrix<double, C, 1>::Zero();
  Eigen::Matrix<double, R, 1> inverse_pivots;
  if (!EliminateWideColumns(tolerance, &A, &inverse_pivots, std::make_integer_sequence<int, R>())) {
    return Eigen::Matrix<double, C, 1>::Zero();
  }
  // U x = 0 with x_C = 1, column by column: b holds -(the solved columns of U) x.
  Eigen::Matrix<double, R, 1> b = -A.col(C - 1);
  Eigen::Matrix<double, C, 1> x;
  x[C - 1] = 1.0;
  for (int k = R - 1; k >= 0; --k) {
    x[k] = b[k] * inverse_pivots[k];
    b.head(k) -= x[k] * A.col(k).head(k);
  }
  return x.normalized();
}

}  // namespace internal
}  // namespace trigrav

#endif  // TRIGRAV_INITIALIZERS_SRC_NULL_SPACE_H_
