#include "trigrav/initializers/essential_8pt.h"

#include <Eigen/Geometry>
#include <cmath>
#include <cstddef>
#include <limits>

#include "essential_decomposition.h"
#include "input_checks.h"
#include "null_space.h"
#include "triangular_factor.h"

namespace trigrav {
namespace {

constexpr std::size_t kMinPoints = 8;
// Rays are dehomogenised only if all are within acos(0.1) = 84 deg of the optical axis.
constexpr double kMinForwardCosine = 0.1;

// Hartley's normalisation of one view, applied by Apply(): p = T (x / x_z), with T moving the
// centroid to 0 and the mean distance to sqrt(2) in the z = 1 plane, when every ray points forward;
// otherwise p = x / |x| and T = I.
struct Normalisation {
  Eigen::Matrix3d T = Eigen::Matrix3d::Identity();
  bool dehomogenise = false;

  explicit Normalisation(const std::vector<Eigen::Vector3d>& x) {
    const std::size_t n = x.size();
    dehomogenise = true;
    for (std::size_t i = 0; i < n && dehomogenise; ++i) {
      dehomogenise = x[i].z() > kMinForwardCosine * x[i].norm();
    }
    if (!dehomogenise) return;
    Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
    for (std::size_t i = 0; i < n; ++i) centroid += x[i].hnormalized();
    centroid /= static_cast<double>(n);
    double mean_distance = 0.0;
    for (std::size_t i = 0; i < n; ++i) mean_distance += (x[i].hnormalized() - centroid).norm();
    mean_distance /= static_cast<double>(n);
    // Coincident points: keep the translation, skip the scaling (the problem is degenerate anyway).
    const double s = mean_distance > 0.0 ? std::sqrt(2.0) / mean_distance : 1.0;
    T << s, 0.0, -s * centroid.x(), 0.0, s, -s * centroid.y(), 0.0, 0.0, 1.0;
  }

  Eigen::Vector3d Apply(const Eigen::Vector3d& x) const {
    return dehomogenise ? Eigen::Vector3d(T * (x / x.z())) : Eigen::Vector3d(x.normalized());
  }
};

}  // namespace

int SolveEssential8pt(const std::vector<Eigen::Vector3d>& x1,
                      const std::vector<Eigen::Vector3d>& x2,
                      std::vector<CameraPose>* solutions) {
  internal::CheckPairs("SolveEssential8pt", kMinPoints, std::numeric_limits<std::size_t>::max(), x1,
                       x2, solutions);
  solutions->clear();
  const std::size_t n = x1.size();

  const Normalisation normalisation1(x1), normalisation2(x2);

  // Row i of the N x 9 system: kron(p2_i, p1_i)^T, E vectorised row by row.
  auto epipolar_row = [&](std::size_t i) {
    const Eigen::Vector3d p1 = normalisation1.Apply(x1[i]);
    const Eigen::Vector3d p2 = normalisation2.Apply(x2[i]);
    Eigen::Matrix<double, 1, 9> row;
    for (int k = 0; k < 3; ++k) row.segment<3>(3 * k) = p2[k] * p1.transpose();
    return row;
  };
  // Triangular factor R of A (R^T R = A^T A), without storing A: up to 9 rows directly, else the
  // first 18, then 9 more at a time through [R; rows] (fixed sizes, no allocation).
  constexpr int kChunk = 9;
  Eigen::Matrix<double, 9, 9> R;
  if (n <= kChunk) {
    Eigen::Matrix<double, kChunk, 9> A = Eigen::Matrix<double, kChunk, 9>::Zero();
    for (std::size_t i = 0; i < n; ++i) A.row(static_cast<int>(i)) = epipolar_row(i);
    R = internal::TriangularFactor(A);
  } else {
    Eigen::Matrix<double, 2 * kChunk, 9> stacked = Eigen::Matrix<double, 2 * kChunk, 9>::Zero();
    std::size_t next = 0;
    for (; next < n && next < 2 * kChunk; ++next) {
      stacked.row(static_cast<int>(next)) = epipolar_row(next);
    }
    R = internal::TriangularFactor(stacked).topRows<kChunk>();
    while (next < n) {
      stacked.topRows<kChunk>() = R;
      stacked.bottomRows<kChunk>().setZero();
      for (int row = kChunk; row < 2 * kChunk && next < n; ++row, ++next) {
        stacked.row(row) = epipolar_row(next);
      }
      R = internal::TriangularFactor(stacked).topRows<kChunk>();
    }
  }
  if (!R.allFinite()) return 0;
  // A triangular matrix has at least as many zero diagonal entries as its rank deficiency: two or
  // more (numerically) zero ones mean a null space of dimension >= 2, i.e. E is not determined
  // (fewer than 8 distinct points, or no translation: then every [t]_x R fits). Generic data has at
  // most one.
  const double largest_diagonal = R.diagonal().cwiseAbs().maxCoeff();
  int zero_diagonals = 0;
  for (int i = 0; i < 9; ++i) zero_diagonals += !(std::abs(R(i, i)) > 1e-10 * largest_diagonal);
  if (zero_diagonals >= 2) return 0;
  const Eigen::Matrix<double, 9, 1> e = internal::SmallestRightSingularVectorOfTriangular<9>(R);
  const Eigen::Matrix3d E_normalised =
      Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(e.data());
  // x2^T E x1 = (T2 x2)^T E_normalised (T1 x1); the projection to the essential manifold happens in
  // PoseFromEssential (singular values replaced by (1, 1, 0)).
  const Eigen::Matrix3d E = normalisation2.T.transpose() * E_normalised * normalisation1.T;

  CameraPose pose;
  const int in_front = internal::PoseFromEssential(E, x1, x2, &pose);
  if (2 * static_cast<std::size_t>(in_front) <= n) return 0;
  solutions->push_back(pose);
  return 1;
}

}  // namespace trigrav
