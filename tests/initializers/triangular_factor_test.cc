// The solvers' internal fixed-size symmetric positive definite solve (initializers/src/
// triangular_factor.h), which the 4-point polish relies on: its answer against Eigen's LDLT, that
// it reads the upper triangle only, and its refusal of a matrix with a non-positive pivot.
#include "triangular_factor.h"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <limits>
#include <random>

namespace trigrav {
namespace internal {
namespace {

template <int N>
Eigen::Matrix<double, N, N> RandomPositiveDefinite(std::mt19937_64* rng) {
  std::normal_distribution<double> normal;
  Eigen::Matrix<double, N, N> M;
  for (int i = 0; i < N; ++i) {
    for (int j = 0; j < N; ++j) M(i, j) = normal(*rng);
  }
  return M.transpose() * M + 0.1 * Eigen::Matrix<double, N, N>::Identity();
}

template <int N>
void ExpectEqualsLdlt(std::mt19937_64* rng) {
  for (int trial = 0; trial < 200; ++trial) {
    const Eigen::Matrix<double, N, N> A = RandomPositiveDefinite<N>(rng);
    Eigen::Matrix<double, N, 1> b;
    for (int i = 0; i < N; ++i) b[i] = std::normal_distribution<double>()(*rng);
    const Eigen::Matrix<double, N, 1> expected = A.ldlt().solve(b);
    // The strict lower triangle is never read: NaN there changes nothing.
    Eigen::Matrix<double, N, N> upper = A;
    upper.template triangularView<Eigen::StrictlyLower>().setConstant(
        std::numeric_limits<double>::quiet_NaN());
    Eigen::Matrix<double, N, 1> x = b;
    ASSERT_TRUE(SolveSymmetricPositiveDefiniteInPlace<N>(upper, &x));
    EXPECT_LT((x - expected).norm(), 1e-9 * expected.norm()) << "N = " << N << ", trial " << trial;
    EXPECT_LT((A * x - b).norm(), 1e-9 * b.norm());
  }
}

TEST(SymmetricPositiveDefiniteSolveTest, EqualsLdltAndReadsTheUpperTriangleOnly) {
  std::mt19937_64 rng(3);
  ExpectEqualsLdlt<1>(&rng);
  ExpectEqualsLdlt<3>(&rng);
  ExpectEqualsLdlt<8>(&rng);
  ExpectEqualsLdlt<16>(&rng);
}

// A pivot that is negative, zero (a singular matrix, exactly in integers) or NaN: false, and the
// right-hand side is left as it was.
TEST(SymmetricPositiveDefiniteSolveTest, RefusesANonPositivePivotAndLeavesXUnchanged) {
  const Eigen::Vector3d b(1.0, -2.0, 0.5);
  const Eigen::Vector3d v(1.0, 2.0, 3.0);
  Eigen::Matrix3d indefinite = Eigen::Matrix3d::Identity();
  indefinite(2, 2) = -1.0;
  Eigen::Matrix3d nan = Eigen::Matrix3d::Identity();
  nan(1, 1) = std::numeric_limits<double>::quiet_NaN();
  for (const Eigen::Matrix3d& A : {indefinite, Eigen::Matrix3d(v * v.transpose()),
                                   Eigen::Matrix3d(-Eigen::Matrix3d::Identity()), nan,
                                   Eigen::Matrix3d(Eigen::Matrix3d::Zero())}) {
    Eigen::Vector3d x = b;
    EXPECT_FALSE(SolveSymmetricPositiveDefiniteInPlace<3>(A, &x)) << A;
    EXPECT_EQ(x, b);
  }
}

}  // namespace
}  // namespace internal
}  // namespace trigrav
