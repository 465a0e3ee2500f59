// Internal triangular factors R (R^T R = A^T A) of the solvers' linear systems: Householder
// triangularisation of small systems, the Cholesky factor of the Gram matrix for tall ones, and a
// stacked system factored block by block without forming it; triangular and symmetric positive
// definite solves at fixed size. Not installed; not part of the public API. Fixed sizes and stack
// storage throughout: no heap allocation.
#ifndef TRIGRAV_INITIALIZERS_SRC_TRIANGULAR_FACTOR_H_
#define TRIGRAV_INITIALIZERS_SRC_TRIANGULAR_FACTOR_H_

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <utility>

namespace trigrav {
namespace internal {

// Solves R x = b (upper) and R^T x = b in place for a fixed-size upper-triangular R, by plain row
// loops: Eigen's triangular solver goes through dynamic-size blocks and matrix-vector kernels,
// several times slower at the solvers' sizes. The reciprocals of the diagonal come first, out of
// the chain of dependent rows, which then multiplies instead of dividing.
template <int N>
void SolveUpperInPlace(const Eigen::Matrix<double, N, N>& R, Eigen::Matrix<double, N, 1>* x) {
  const Eigen::Matrix<double, N, 1> inverse_diagonal = R.diagonal().cwiseInverse();
  for (int i = N - 1; i >= 0; --i) {
    double sum = (*x)[i];
    for (int j = i + 1; j < N; ++j) sum -= R(i, j) * (*x)[j];
    (*x)[i] = sum * inverse_diagonal[i];
  }
}

template <int N>
void SolveUpperTransposedInPlace(const Eigen::Matrix<double, N, N>& R,
                                 Eigen::Matrix<double, N, 1>* x) {
  const Eigen::Matrix<double, N, 1> inverse_diagonal = R.diagonal().cwiseInverse();
  for (int i = 0; i < N; ++i) {
    double sum = (*x)[i];
    for (int j = 0; j < i; ++j) sum -= R(j, i) * (*x)[j];
    (*x)[i] = sum * inverse_diagonal[i];
  }
}

// Upper Cholesky factor R (R^T R = A) of a fixed-size symmetric A, from its upper triangle, row by
// row with plain loops (the role of Eigen's LLT, several times cheaper at these sizes). False if a
// pivot is not positive (A not numerically positive definite).
template <int N>
bool UpperCholesky(const Eigen::Matrix<double, N, N>& A, Eigen::Matrix<double, N, N>* R) {
  R->setZero();
  for (int j = 0; j < N; ++j) {
    double pivot = A(j, j);
    for (int k = 0; k < j; ++k) pivot -= (*R)(k, j) * (*R)(k, j);
    if (!(pivot > 0.0)) return false;
    const double diagonal = std::sqrt(pivot);
    (*R)(j, j) = diagonal;
    const double inverse = 1.0 / diagonal;
    for (int i = j + 1; i < N; ++i) {
      double entry = A(j, i);
      for (int k = 0; k < j; ++k) entry -= (*R)(k, j) * (*R)(k, i);
      (*R)(j, i) = entry * inverse;
    }
  }
  return true;
}

// Solves A x = b in place for a fixed-size symmetric positive definite A, read from its upper
// triangle, by the square-root-free factorisation A = U^T D U (U unit upper triangular): per pivot
// one division and no square root, the long-latency chain of a Cholesky factor. Plain arrays and
// unrolled loops (up to N = 16; at N = 8 about 2.5x faster than indexed Eigen loops). False, with x
// unchanged, if a pivot is not positive.
template <int N>
bool SolveSymmetricPositiveDefiniteInPlace(const Eigen::Matrix<double, N, N>& A,
                                           Eigen::Matrix<double, N, 1>* x) {
  // Row j of U before scaling, W[j][i] = D_j U(j, i) (i >= j), and U(j, i) itself (i > j).
  double W[N][N], U[N][N], inverse_pivot[N];
#pragma GCC unroll 16
  for (int j = 0; j < N; ++j) {
#pragma GCC unroll 16
    for (int i = j; i < N; ++i) {
      double entry = A(j, i);
#pragma GCC unroll 16
      for (int k = 0; k < j; ++k) entry -= U[k][j] * W[k][i];
      W[j][i] = entry;
    }
    if (!(W[j][j] > 0.0)) return false;
    inverse_pivot[j] = 1.0 / W[j][j];
#pragma GCC unroll 16
    for (int i = j + 1; i < N; ++i) U[j][i] = W[j][i] * inverse_pivot[j];
  }
  // U^T y = b, then D U x = y, in place.
  Eigen::Matrix<double, N, 1>& y = *x;
#pragma GCC unroll 16
  for (int i = 0; i < N; ++i) {
#pragma GCC unroll 16
    for (int k = 0; k < i; ++k) y[i] -= U[k][i] * y[k];
  }
#pragma GCC unroll 16
  for (int i = N - 1; i >= 0; --i) {
    double sum = y[i] * inverse_pivot[i];
#pragma GCC unroll 16
    for (int k = i + 1; k < N; ++k) sum -= U[i][k] * y[k];
    y[i] = sum;
  }
  return true;
}

// Upper Cholesky factor R (R^T R = G + ridge I) of a Gram matrix G = A^T A, with a relative ridge
// of 1e-15 so that an exact null space stays factorable.
template <int C>
Eigen::Matrix<double, C, C> CholeskyFactorOfGram(Eigen::Matrix<double, C, C> gram) {
  const double ridge = 1e-15 * gram.trace();
  gram.diagonal().array() += ridge > 0.0 ? ridge : 1e-300;
  return Eigen::LLT<Eigen::Matrix<double, C, C>>(gram).matrixU();
}

// Step J of the Householder triangularisation of a fixed-size M x C matrix A in place: the
// reflector H = I - 2 v v^T / (v^T v), v = x - alpha e_1 with x = column J from row J down, maps x
// to alpha e_1 and is applied to the trailing columns as one rank-1 update, A <- A - v w with
// w = 2 v^T A / (v^T v). The entries below the diagonal are left stale (TriangularFactor reads the
// upper triangle only).
template <int J, int M, int C>
void HouseholderStep(Eigen::Matrix<double, M, C>* A) {
  constexpr int kLength = M - J;
  constexpr int kTrailing = C - J - 1;
  Eigen::Matrix<double, kLength, 1> v = A->template block<kLength, 1>(J, J);
  const double x0 = v[0];
  const double norm = v.norm();
  const double alpha = x0 <= 0.0 ? norm : -norm;
  v[0] = x0 - alpha;
  const double v_squared = v.squaredNorm();
  if (!(v_squared > 0.0)) return;
  if constexpr (kTrailing > 0) {
    auto trailing = A->template block<kLength, kTrailing>(J, J + 1);
    const Eigen::Matrix<double, 1, kTrailing> w =
        (2.0 / v_squared) * v.transpose().lazyProduct(trailing);
    trailing.noalias() -= v.lazyProduct(w);
  }
  (*A)(J, J) = alpha;
}

template <int M, int C, int... J>
void HouseholderSteps(Eigen::Matrix<double, M, C>* A, std::integer_sequence<int, J...>) {
  (HouseholderStep<J>(A), ...);
}

// Upper-triangular C x C factor R of a matrix with C columns (R^T R = A^T A), padded with zero rows
// when A has fewer rows than columns. Fixed-size A, and dynamic A up to kMaxHouseholderRows rows:
// unblocked Householder triangularisation in place (for the small fixed-size systems of the
// solvers several times faster than Eigen's blocked HouseholderQR, and allocation-free; with fixed
// sizes every step is unrolled). Taller systems, the non-minimal least-squares solves on many
// inliers, use CholeskyFactorOfGram(A^T A): 4x fewer flops, no copy of A; the squared conditioning
// is far below the noise of such problems, and the solvers polish afterwards.
constexpr int kMaxHouseholderRows = 64;

template <typename Derived>
Eigen::Matrix<double, Derived::ColsAtCompileTime, Derived::ColsAtCompileTime> TriangularFactor(
    const Eigen::MatrixBase<Derived>& A_in) {
  constexpr int C = Derived::ColsAtCompileTime;
  constexpr int M = Derived::RowsAtCompileTime;
  if constexpr (M != Eigen::Dynamic) {
    Eigen::Matrix<double, M, C> A = A_in;
    HouseholderSteps(&A, std::make_integer_sequence<int, std::min(M, C)>());
    Eigen::Matrix<double, C, C> R = Eigen::Matrix<double, C, C>::Zero();
    R.template topRows<std::min(M, C)>() =
        A.template topRows<std::min(M, C)>().template triangularView<Eigen::Upper>();
    return R;
  } else {
    if (A_in.rows() > kMaxHouseholderRows) {
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
      // Reflector H = I - 2 v v^T / (v^T v), v = x - alpha e_j with x = column j below row j,
      // mapping x to alpha e_j. v is kept at full column length (zeros above j) so the updates are
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

}  // namespace internal
}  // namespace trigrav

#endif  // TRIGRAV_INITIALIZERS_SRC_TRIANGULAR_FACTOR_H_
