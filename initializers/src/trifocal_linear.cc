#include "trigrav/initializers/trifocal_linear.h"

#include <Eigen/Core>
#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "essential_decomposition.h"
#include "input_checks.h"
#include "null_space.h"
#include "triangular_factor.h"
#include "trifocal_common.h"
#include "trigrav/initializers/skew.h"
#include "two_view_geometry.h"

namespace trigrav {
namespace {

using Vector27d = Eigen::Matrix<double, 27, 1>;
using internal::TensorSlices;
using internal::Vector6d;

// Hartley normalisation of one view (header step 1): writes x^ = H x / x_3 with the centroid of the
// dehomogenised points at the origin and their mean distance sqrt(2), or, if some ray has x_3 = 0,
// the unit rays and H = I. False if the points of the view (nearly) coincide.
bool NormaliseView(const std::vector<Eigen::Vector3d>& x,
                   std::vector<Eigen::Vector3d>* normalised,
                   Eigen::Matrix3d* H) {
  const std::size_t n = x.size();
  normalised->resize(n);
  bool dehomogenise = true;
  for (const Eigen::Vector3d& ray : x) {
    if (!(std::abs(ray.z()) > 1e-12 * ray.norm())) dehomogenise = false;
  }
  if (!dehomogenise) {
    H->setIdentity();
    for (std::size_t i = 0; i < n; ++i) (*normalised)[i] = x[i].normalized();
    return true;
  }
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  for (const Eigen::Vector3d& ray : x) centroid += ray.head<2>() / ray.z();
  centroid /= static_cast<double>(n);
  double mean_distance = 0.0;
  for (const Eigen::Vector3d& ray : x) mean_distance += (ray.head<2>() / ray.z() - centroid).norm();
  mean_distance /= static_cast<double>(n);
  // Coincident points: the spread is rounding noise only.
  if (!(mean_distance > 1e-12 * std::max(1.0, centroid.norm())) || !std::isfinite(mean_distance)) {
    return false;
  }
  const double s = std::sqrt(2.0) / mean_distance;
  *H << s, 0.0, -s * centroid.x(), 0.0, s, -s * centroid.y(), 0.0, 0.0, 1.0;
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d y = s * (x[i].head<2>() / x[i].z() - centroid);
    (*normalised)[i] = Eigen::Vector3d(y.x(), y.y(), 1.0);
  }
  return true;
}

// The 4 incidence rows of one triplet in the 27 entries of T, entry T_i(j, k) at 9 i + 3 j + k:
// p_a^T (sum_i x1_i T_i) r_b = 0 for orthonormal bases (p_a) of x2^perp and (r_b) of x3^perp.
Eigen::Matrix<double, 4, 27> IncidenceRows(const Eigen::Vector3d& x1,
                                           const Eigen::Vector3d& x2,
                                           const Eigen::Vector3d& x3) {
  Eigen::Vector3d p[2], r[2];
  internal::PerpendicularBasis(x2, &p[0], &p[1]);
  internal::PerpendicularBasis(x3, &r[0], &r[1]);
  Eigen::Matrix<double, 4, 27> rows;
  for (int a = 0; a < 2; ++a) {
    for (int b = 0; b < 2; ++b) {
      for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) {
          for (int k = 0; k < 3; ++k) {
            rows(2 * a + b, 9 * i + 3 * j + k) = x1[i] * p[a][j] * r[b][k];
          }
        }
      }
    }
  }
  return rows;
}

// Tensor of the original rays from the tensor t^ of the normalised ones (H&Z algorithm 16.1):
// T_i = sum_r (H_1)_{ri} H_2^-1 T^_r H_3^-T.
TensorSlices DenormaliseTensor(const Vector27d& t,
                               const Eigen::Matrix3d& H1,
                               const Eigen::Matrix3d& H2,
                               const Eigen::Matrix3d& H3) {
  TensorSlices normalised;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      for (int k = 0; k < 3; ++k) normalised[i](j, k) = t[9 * i + 3 * j + k];
    }
  }
  const Eigen::Matrix3d H2_inverse = H2.inverse();
  const Eigen::Matrix3d H3_inverse_transpose = H3.inverse().transpose();
  TensorSlices T;
  for (int i = 0; i < 3; ++i) {
    Eigen::Matrix3d sum = Eigen::Matrix3d::Zero();
    for (int r = 0; r < 3; ++r) sum += H1(r, i) * normalised[r];
    T[i] = H2_inverse * sum * H3_inverse_transpose;
  }
  return T;
}

// Essential matrices E_21, E_31 from the tensor (header step 3): epipoles from the null vectors of
// the slices (H&Z algorithm 15.1), cameras P_2, P_3 (same algorithm), E_k1 = [m_k]_x M_k.
bool EssentialMatricesFromTensor(const TensorSlices& T,
                                 Eigen::Matrix3d* E21,
                                 Eigen::Matrix3d* E31) {
  Eigen::Vector3d epipole2, epipole3;  // e', e''
  if (!internal::EpipolesFromTensor(T, &epipole2, &epipole3)) return false;
  Eigen::Matrix3d M2, M3;
  const Eigen::Matrix3d projector = epipole3 * epipole3.transpose() - Eigen::Matrix3d::Identity();
  for (int i = 0; i < 3; ++i) {
    M2.col(i) = T[i] * epipole3;
    M3.col(i) = projector * (T[i].transpose() * epipole2);
  }
  *E21 = Skew(epipole2) * M2;
  *E31 = Skew(epipole3) * M3;
  return E21->allFinite() && E31->allFinite();
}

// +1 if the point of a triplet is in front of cameras 1 and k for x_k ~ R (X - center), -1 if it is
// behind both (in front for the negated centre), 0 otherwise. Depths: the view-1 depth from the
// pair (derivations.md section 4.6) and the depth of that point in camera k.
int Cheirality(const Eigen::Vector3d& x1,
               const Eigen::Vector3d& xk,
               const Eigen::Matrix3d& R,
               const Eigen::Vector3d& center) {
  const double depth1 = internal::ViewOneDepth(x1, xk, R, center);
  const double depthk = xk.dot(R * (depth1 * x1 - center));
  return (depth1 > 0.0 && depthk > 0.0) - (depth1 < 0.0 && depthk < 0.0);
}

// The twisted pair of E_k1 (header step 4), the rotation that puts more triplets of pair (1,k) in
// front of both cameras first: internal::PoseFromEssential gives that rotation R and the unit
// translation t = +-u_3; the other one is U W^T V^T = (2 t t^T - I) U W V^T. False if no rotation
// puts any triplet in front.
bool RotationsFromEssential(const Eigen::Matrix3d& E,
                            const std::vector<Eigen::Vector3d>& x1,
                            const std::vector<Eigen::Vector3d>& xk,
                            std::array<Eigen::Matrix3d, 2>* rotations) {
  CameraPose pose;
  if (internal::PoseFromEssential(E, x1, xk, &pose) == 0) return false;
  (*rotations)[0] = pose.R;
  (*rotations)[1] = (2.0 * pose.t * pose.t.transpose() - Eigen::Matrix3d::Identity()) * pose.R;
  return (*rotations)[1].allFinite();
}

// Rotations, unit centres (c_2; c_3) oriented by cheirality, the number of triplets in front of all
// three cameras, and the residual |F c| / |F| of the centre solve.
struct Candidate {
  Eigen::Matrix3d R2, R3;
  Vector6d centers = Vector6d::Zero();
  int in_front = -1;
  double residual = std::numeric_limits<double>::infinity();
};

// Centres for fixed rotations: least-squares null vector of the incidence rows of derivations.md
// section 3.4 (header step 5), with the sign that puts the most triplets in front of all three
// cameras (step 6).
template <int Rows>
Candidate SolveCenters(const std::vector<Eigen::Vector3d>& x1,
                       const std::vector<Eigen::Vector3d>& x2,
                       const std::vector<Eigen::Vector3d>& x3,
                       const Eigen::Matrix3d& R2,
                       const Eigen::Matrix3d& R3) {
  Candidate candidate;
  candidate.R2 = R2;
  candidate.R3 = R3;
  Eigen::Matrix<double, Rows, 6> F(4 * x1.size(), 6);
  for (std::size_t n = 0; n < x1.size(); ++n) {
    F.template middleRows<4>(4 * n) = internal::TranslationRows(x1[n], x2[n], x3[n], R2, R3);
  }
  const Eigen::Matrix<double, 6, 6> R_F = internal::TriangularFactor(F);
  const Vector6d centers = internal::SmallestRightSingularVectorOfTriangular<6>(R_F);
  const double norm = R_F.norm();
  if (!centers.allFinite() || !(norm > 0.0) || !std::isfinite(norm)) return candidate;
  int plus = 0, minus = 0;
  for (std::size_t n = 0; n < x1.size(); ++n) {
    const int sign2 = Cheirality(x1[n], x2[n], R2, centers.head<3>());
    const int sign3 = Cheirality(x1[n], x3[n], R3, centers.tail<3>());
    plus += sign2 > 0 && sign3 > 0;
    minus += sign2 < 0 && sign3 < 0;
  }
  candidate.centers = minus > plus ? Vector6d(-centers) : centers;
  candidate.in_front = std::max(plus, minus);
  candidate.residual = (R_F.triangularView<Eigen::Upper>() * centers).norm() / norm;
  return candidate;
}

// Rows = 28 for 7 triplets (fixed-size systems) or Eigen::Dynamic.
template <int Rows>
int Solve(const std::vector<Eigen::Vector3d>& x1,
          const std::vector<Eigen::Vector3d>& x2,
          const std::vector<Eigen::Vector3d>& x3,
          std::vector<ThreeViewPose>* solutions) {
  std::vector<Eigen::Vector3d> y1, y2, y3;
  Eigen::Matrix3d H1, H2, H3;
  if (!NormaliseView(x1, &y1, &H1) || !NormaliseView(x2, &y2, &H2) ||
      !NormaliseView(x3, &y3, &H3)) {
    return 0;
  }
  Eigen::Matrix<double, Rows, 27> A(4 * x1.size(), 27);
  for (std::size_t n = 0; n < x1.size(); ++n) {
    A.template middleRows<4>(4 * n) = IncidenceRows(y1[n], y2[n], y3[n]);
  }
  if (!A.allFinite()) return 0;
  const Eigen::Matrix<double, 27, 27> R_A = internal::TriangularFactor(A);
  // A null space of dimension 2 or more (e.g. a repeated triplet among 7) leaves T undetermined.
  if (internal::HasMultipleNullDirections<27>(R_A)) return 0;
  const Vector27d t = internal::SmallestRightSingularVectorOfTriangular<27>(R_A);
  if (!t.allFinite() || t.isZero()) return 0;
  const TensorSlices T = DenormaliseTensor(t, H1, H2, H3);

  Eigen::Matrix3d E21, E31;
  std::array<Eigen::Matrix3d, 2> rotations2, rotations3;
  if (!EssentialMatricesFromTensor(T, &E21, &E31) ||
      !RotationsFromEssential(E21, x1, x2, &rotations2) ||
      !RotationsFromEssential(E31, x1, x3, &rotations3)) {
    return 0;
  }
  // The 2 x 2 rotation pairs, the two-view choices first; the first pair with all triplets in front
  // of all three cameras ends the search.
  constexpr std::array<std::array<int, 2>, 4> kOrder = {{{0, 0}, {0, 1}, {1, 0}, {1, 1}}};
  Candidate best;
  for (const auto& pair : kOrder) {
    const Candidate candidate =
        SolveCenters<Rows>(x1, x2, x3, rotations2[pair[0]], rotations3[pair[1]]);
    if (candidate.in_front > best.in_front ||
        (candidate.in_front == best.in_front && candidate.residual < best.residual)) {
      best = candidate;
    }
    if (best.in_front == static_cast<int>(x1.size())) break;
  }
  // Cheirality-consistent: a strict majority of the triplets in front of all three cameras.
  if (!(best.in_front > 0 && 2 * static_cast<std::size_t>(best.in_front) > x1.size())) return 0;

  Eigen::Vector3d c2 = best.centers.head<3>(), c3 = best.centers.tail<3>();
  const Eigen::Matrix3d& R2 = best.R2;
  const Eigen::Matrix3d& R3 = best.R3;
  const double scale = c2.norm();  // |(c2; c3)| = 1
  constexpr double kMinScale = 1e-12;
  if (!(scale > kMinScale)) return 0;
  c2 /= scale;
  c3 /= scale;
  ThreeViewPose pose;
  pose.cam2_from_cam1.R = R2;
  pose.cam2_from_cam1.t = -R2 * c2;
  pose.cam3_from_cam1.R = R3;
  pose.cam3_from_cam1.t = -R3 * c3;
  if (!pose.IsFinite()) return 0;
  solutions->push_back(pose);
  return 1;
}

}  // namespace

int SolveTrifocalLinear(const std::vector<Eigen::Vector3d>& x1,
                        const std::vector<Eigen::Vector3d>& x2,
                        const std::vector<Eigen::Vector3d>& x3,
                        std::vector<ThreeViewPose>* solutions) {
  internal::CheckTriplets("SolveTrifocalLinear", internal::kTrifocalLinearMinTriplets,
                          std::numeric_limits<std::size_t>::max(), x1, x2, x3, solutions);
  solutions->clear();
  if (x1.size() == internal::kTrifocalLinearMinTriplets) {
    return Solve<4 * internal::kTrifocalLinearMinTriplets>(x1, x2, x3, solutions);
  }
  return Solve<Eigen::Dynamic>(x1, x2, x3, solutions);
}

}  // namespace trigrav
