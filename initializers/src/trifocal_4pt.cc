#include "trigrav/initializers/trifocal_4pt.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "gravity_wrapper.h"
#include "input_checks.h"
#include "null_space.h"
#include "triangular_factor.h"
#include "trifocal_common.h"

namespace trigrav {
namespace {

using Vector17d = Eigen::Matrix<double, 17, 1>;
using internal::TensorSlices;
using internal::Vector6d;

// Where Q_1..Q_17 sit in the aligned trifocal tensor (paper eqs c2-c4, checked in derivations.md
// section 3): entry T_slice(row, col) = sign * Q_q, all indices 0-based. Six entries of T are
// always zero.
struct TensorEntry {
  int q, slice, row, col;
  double sign;
};
constexpr std::array<TensorEntry, 21> kTensorEntries = {{
    {0, 0, 0, 0, 1},  {1, 0, 0, 1, 1},  {1, 2, 2, 1, 1},  {2, 0, 0, 2, 1},  {3, 0, 1, 0, 1},
    {3, 2, 1, 2, 1},  {4, 0, 1, 2, 1},  {4, 2, 1, 0, -1}, {5, 0, 2, 0, 1},  {6, 0, 2, 1, 1},
    {6, 2, 0, 1, -1}, {7, 0, 2, 2, 1},  {8, 1, 0, 1, 1},  {9, 1, 1, 0, 1},  {10, 1, 1, 1, 1},
    {11, 1, 1, 2, 1}, {12, 1, 2, 1, 1}, {13, 2, 0, 0, 1}, {14, 2, 0, 2, 1}, {15, 2, 2, 0, 1},
    {16, 2, 2, 2, 1},
}};

// The 4 incidence rows of one triplet in q (derivations.md section 3): p_a^T (sum_i x1_i T_i) r_b =
// 0 for orthonormal bases (p_a) of x2^perp and (r_b) of x3^perp, equivalent to eq. c6.
Eigen::Matrix<double, 4, 17> IncidenceRows(const internal::TripletFrame& frame) {
  Eigen::Matrix<double, 4, 17> rows;
  for (int a = 0; a < 2; ++a) {
    for (int b = 0; b < 2; ++b) {
      const Eigen::Matrix3d outer = frame.p[a] * frame.r[b].transpose();
      double row[17] = {};
      // Unrolled, the table indices become constants (about 4x fewer instructions).
#pragma GCC unroll 32
      for (const TensorEntry& e : kTensorEntries) {
        row[e.q] += e.sign * frame.x1[e.slice] * outer(e.row, e.col);
      }
      rows.row(2 * a + b) = Eigen::Map<const Eigen::Matrix<double, 1, 17>>(row);
    }
  }
  return rows;
}

TensorSlices TensorFromQ(const Vector17d& q) {
  TensorSlices T = {Eigen::Matrix3d::Zero(), Eigen::Matrix3d::Zero(), Eigen::Matrix3d::Zero()};
  for (const TensorEntry& e : kTensorEntries) T[e.slice](e.row, e.col) = e.sign * q[e.q];
  return T;
}

// q = E a for the constrained tensor with epipoles e' = e, e'' = f (eqs f2-f6, derivations.md
// section 4.3): the 26 non-zeros of the 17 x 6 matrix E, as (row of q, column of a, value).
struct BasisEntry {
  int q, a;
  double value;
};
std::array<BasisEntry, 26> ConstrainedTensorBasis(const Eigen::Vector3d& e,
                                                  const Eigen::Vector3d& f) {
  return {{
      {0, 0, f[0]},   {0, 3, -e[0]},   // Q1  = f1 a1 - e1 a4
      {1, 0, f[1]},                    // Q2  = f2 a1
      {2, 0, f[2]},   {2, 4, e[0]},    // Q3  = f3 a1 + e1 a5
      {3, 3, -e[1]},                   // Q4  = -e2 a4
      {4, 4, e[1]},                    // Q5  = e2 a5
      {5, 1, -f[0]},  {5, 3, -e[2]},   // Q6  = -f1 a2 - e3 a4
      {6, 1, -f[1]},                   // Q7  = -f2 a2
      {7, 1, -f[2]},  {7, 4, e[2]},    // Q8  = -f3 a2 + e3 a5
      {8, 5, -e[0]},                   // Q9  = -e1 a6
      {9, 2, f[0]},                    // Q10 = f1 a3
      {10, 2, f[1]},  {10, 5, -e[1]},  // Q11 = f2 a3 - e2 a6
      {11, 2, f[2]},                   // Q12 = f3 a3
      {12, 5, -e[2]},                  // Q13 = -e3 a6
      {13, 1, f[0]},  {13, 4, -e[0]},  // Q14 = f1 a2 - e1 a5
      {14, 1, f[2]},  {14, 3, -e[0]},  // Q15 = f3 a2 - e1 a4
      {15, 0, f[0]},  {15, 4, -e[2]},  // Q16 = f1 a1 - e3 a5
      {16, 0, f[2]},  {16, 3, -e[2]},  // Q17 = f3 a1 - e3 a4
  }};
}

using internal::Yaw;

// Yaws and centres (up to a common factor) of an aligned estimate.
struct AlignedEstimate {
  Yaw yaw2, yaw3;
  Eigen::Vector3d center2 = Eigen::Vector3d::Zero(), center3 = Eigen::Vector3d::Zero();
};

// R2 c2 = (Q9, ty2, Q13) and R3 c3 = (-Q10, ty3, -Q12) (derivations.md section 3): the centres in
// their cameras' aligned frames, which are also the epipoles e', e'' up to scale.
std::array<Eigen::Vector3d, 2> RotatedCentersFromQ(const Vector17d& q, double ty2, double ty3) {
  return {Eigen::Vector3d(q[8], ty2, q[12]), Eigen::Vector3d(-q[9], ty3, -q[11])};
}

// Centres from q given the yaws.
void CentersFromQ(const Vector17d& q, double ty2, double ty3, AlignedEstimate* estimate) {
  const std::array<Eigen::Vector3d, 2> rotated = RotatedCentersFromQ(q, ty2, ty3);
  estimate->center2 = estimate->yaw2.RotateBack(rotated[0]);
  estimate->center3 = estimate->yaw3.RotateBack(rotated[1]);
}

// Constraint enforcement for given epipoles (eqs f2-f7) and the pose read from a (derivations.md
// section 4.3 step 4). M is the incidence matrix A itself (minimal case) or its triangular factor
// R_A (|A y| = |R_A y|). False if the basis E is degenerate.
template <typename IncidenceMatrix>
bool EnforceConstraints(const IncidenceMatrix& M,
                        const Eigen::Vector3d& epipole2,
                        const Eigen::Vector3d& epipole3,
                        AlignedEstimate* estimate) {
  // min |M E a| s.t. |E a| = 1 (eq. f7). With E^T E = R_E^T R_E (Cholesky; E is well conditioned
  // unless an epipole degenerates) and b = R_E a: b = smallest right singular vector of M E R_E^-1,
  // then a = R_E^-1 b. E is used through its non-zeros only.
  const std::array<BasisEntry, 26> E = ConstrainedTensorBasis(epipole2, epipole3);
  Eigen::Matrix<double, IncidenceMatrix::RowsAtCompileTime, 6> ME =
      Eigen::Matrix<double, IncidenceMatrix::RowsAtCompileTime, 6>::Zero(M.rows(), 6);
  for (const BasisEntry& entry : E) ME.col(entry.a) += entry.value * M.col(entry.q);
  // E^T E from the non-zeros: a row q of E adds the products of its own entries (the table lists
  // each row's entries next to each other).
  Eigen::Matrix<double, 6, 6> gram = Eigen::Matrix<double, 6, 6>::Zero();
  for (std::size_t i = 0; i < E.size(); ++i) {
    for (std::size_t j = i; j < E.size() && E[j].q == E[i].q; ++j) {
      gram(E[i].a, E[j].a) += E[i].value * E[j].value;
      if (j != i) gram(E[j].a, E[i].a) += E[i].value * E[j].value;
    }
  }
  Eigen::Matrix<double, 6, 6> R_E;
  if (!internal::UpperCholesky(gram, &R_E)) return false;
  const double largest = R_E.diagonal().cwiseAbs().maxCoeff();
  if (!(R_E.diagonal().cwiseAbs().minCoeff() > 1e-8 * largest)) return false;
  // ME = Q R_ME gives M E R_E^-1 = Q (R_ME R_E^-1): the 6 x 6 triangular factor of the scaled
  // system without scaling the tall one.
  Eigen::Matrix<double, 6, 6> R = internal::TriangularFactor(ME);
  for (int j = 0; j < 6; ++j) {  // R <- R R_E^-1, column by column
    for (int i = 0; i < j; ++i) R.col(j) -= R_E(i, j) * R.col(i);
    R.col(j) /= R_E(j, j);
  }
  Vector6d a = internal::SmallestRightSingularVectorOfTriangular<6>(R);
  internal::SolveUpperInPlace(R_E, &a);

  // a = lambda (beta c2, beta s2, beta, alpha c3, alpha s3, alpha), e' = -R2 c2 / alpha,
  // e'' = -R3 c3 / beta: c2 = -a6 R2^T e', c3 = -a3 R3^T e'' up to the common factor 1/lambda.
  const double sign3 = a[2] < 0.0 ? -1.0 : 1.0;
  const double sign6 = a[5] < 0.0 ? -1.0 : 1.0;
  estimate->yaw2 = Yaw::FromDirection(sign3 * a[0], sign3 * a[1]);
  estimate->yaw3 = Yaw::FromDirection(sign6 * a[3], sign6 * a[4]);
  estimate->center2 = -a[5] * estimate->yaw2.RotateBack(epipole2);
  estimate->center3 = -a[2] * estimate->yaw3.RotateBack(epipole3);
  return true;
}

// The least-squares read of q (derivations.md section 4.2): the yaws from the 8 relations of eq.
// c5, then ty2, ty3 from those of Q4, Q5, Q11, Q2, Q7, both by their normal equations in closed
// form. False if a horizontal epipole vanishes (relative to the other): the yaws are then
// undefined.
struct LeastSquaresRead {
  Yaw yaw2, yaw3;
  double ty2 = 0.0, ty3 = 0.0;
};

bool ReadLeastSquares(const Vector17d& q, LeastSquaresRead* read) {
  // Normal equations in z2 = c2 + i s2, z3 = c3 + i s3: [2A, conj(w); w, 2B] (z2; z3) = (b01; b23)
  // with A = Q10^2 + Q12^2, B = Q9^2 + Q13^2, |w|^2 = AB, determinant 3AB.
  const double A = q[9] * q[9] + q[11] * q[11];
  const double B = q[8] * q[8] + q[12] * q[12];
  constexpr double kMinRatio = 1e-8;
  if (!(std::min(A, B) > kMinRatio * std::max(A, B))) return false;
  const double u = q[8] * q[9] + q[11] * q[12], v = q[9] * q[12] - q[8] * q[11];
  const double b0 = q[9] * (q[0] + q[15]) + q[11] * (q[2] + q[16]);
  const double b1 = q[9] * (q[13] - q[5]) + q[11] * (q[14] - q[7]);
  const double b2 = q[8] * (q[0] + q[14]) + q[12] * (q[5] + q[16]);
  const double b3 = q[8] * (q[13] - q[2]) + q[12] * (q[15] - q[7]);
  // z2 ~ 2B b01 - conj(w) b23, z3 ~ 2A b23 - w b01 (the common factor 1 / (3AB) drops out).
  read->yaw2 =
      Yaw::FromDirection(2.0 * B * b0 - (u * b2 + v * b3), 2.0 * B * b1 - (u * b3 - v * b2));
  read->yaw3 =
      Yaw::FromDirection(2.0 * A * b2 - (u * b0 - v * b1), 2.0 * A * b3 - (u * b1 + v * b0));
  const double c2 = read->yaw2.c, s2 = read->yaw2.s;
  const double c3 = read->yaw3.c, s3 = read->yaw3.s;
  // Q4 = c3 ty2, Q5 = -s3 ty2, Q11 = ty2 - ty3, Q2 = -c2 ty3, Q7 = s2 ty3: normal matrix
  // [2, -1; -1, 2] for unit yaws, whose inverse is [2, 1; 1, 2] / 3.
  const double n0 = c3 * q[3] - s3 * q[4] + q[10];
  const double n1 = -q[10] - c2 * q[1] + s2 * q[6];
  read->ty2 = (2.0 * n0 + n1) / 3.0;
  read->ty3 = (n0 + 2.0 * n1) / 3.0;
  return read->yaw2.IsFinite() && read->yaw3.IsFinite() && std::isfinite(read->ty2) &&
         std::isfinite(read->ty3);
}

// The pose of the least-squares read (derivations.md section 4.2).
bool EstimateLeastSquares(const Vector17d& q, AlignedEstimate* estimate) {
  LeastSquaresRead read;
  if (!ReadLeastSquares(q, &read)) return false;
  estimate->yaw2 = read.yaw2;
  estimate->yaw3 = read.yaw3;
  CentersFromQ(q, read.ty2, read.ty3, estimate);
  return true;
}

// Epipoles e' ~ R2 c2 and e'' ~ R3 c3 of the least-squares read; where that is undefined (a
// horizontal epipole vanishes), the tensor's own epipoles (eq. f1). Derivations.md section 4.3
// step 1.
bool EpipolesFromQ(const Vector17d& q, Eigen::Vector3d* epipole2, Eigen::Vector3d* epipole3) {
  LeastSquaresRead read;
  if (!ReadLeastSquares(q, &read))
    return internal::EpipolesFromTensor(TensorFromQ(q), epipole2, epipole3);
  const std::array<Eigen::Vector3d, 2> rotated = RotatedCentersFromQ(q, read.ty2, read.ty3);
  *epipole2 = rotated[0].normalized();
  *epipole3 = rotated[1].normalized();
  return true;
}

// The paper's closed forms, eqs c8-c11 (exact, but singular when Q10 Q13 = Q9 Q12, Q9 = 0 or Q13 =
// 0).
bool EstimatePaperClosedForm(const Vector17d& q, AlignedEstimate* estimate) {
  const double denominator = q[9] * q[12] - q[8] * q[11];
  const double s2 = (q[7] * q[8] + q[12] * q[13]) / denominator;
  const double c2 = (q[0] * q[12] - q[8] * q[16]) / denominator;
  estimate->yaw2 = Yaw::FromDirection(c2, s2);
  const double c2n = estimate->yaw2.c, s2n = estimate->yaw2.s;
  const double s3 = -(q[7] + s2n * q[11]) / q[12];
  const double c3 = (q[0] - c2n * q[9]) / q[8];
  estimate->yaw3 = Yaw::FromDirection(c3, s3);
  const double c3n = estimate->yaw3.c, s3n = estimate->yaw3.s;
  CentersFromQ(q, c3n * q[3] - s3n * q[4], s2n * q[6] - c2n * q[1], estimate);  // eqs c9, c11
  return estimate->yaw2.IsFinite() && estimate->yaw3.IsFinite();
}

// (c2; c3) = null vector of the stacked translation rows with the yaws fixed (derivations.md
// section 3.4). Rows = 16: the minimal system at fixed size. frame(n): TripletFrame of triplet n.
template <int Rows, typename FrameFunction>
void ResolveCenters(std::size_t count, const FrameFunction& frame, AlignedEstimate* estimate) {
  const Eigen::Matrix3d R2 = estimate->yaw2.Matrix();
  const Eigen::Matrix3d R3 = estimate->yaw3.Matrix();
  const auto rows = [&](std::size_t n) {
    return internal::TranslationRows(internal::MakeTranslationTerms(frame(n), R2, R3));
  };
  Eigen::Matrix<double, 6, 6> R_F;
  if constexpr (Rows == 16) {
    Eigen::Matrix<double, 16, 6> F;
    for (std::size_t n = 0; n < 4; ++n) F.middleRows<4>(4 * n) = rows(n);
    R_F = internal::TriangularFactor(F);
  } else {
    R_F = internal::StackedTriangularFactor<6>(count, rows);
  }
  const Vector6d centers = internal::SmallestRightSingularVectorOfTriangular<6>(R_F);
  // Keep the sign of the previous centres so the cheirality vote starts from a consistent guess.
  const double sign =
      centers.head<3>().dot(estimate->center2) + centers.tail<3>().dot(estimate->center3);
  estimate->center2 = (sign < 0.0 ? -1.0 : 1.0) * centers.head<3>();
  estimate->center3 = (sign < 0.0 ? -1.0 : 1.0) * centers.tail<3>();
}

// One Gauss-Newton step on the incidence residuals of all triplets (the rows of TranslationRows),
// jointly over the yaws and the rotated centres rho_k = R_k c_k, with |(rho2; rho3)| held fixed to
// first order (derivations.md section 4.5). In rho the rows of a triplet are
// r_ab = zr_b (left_a . rho2) + pu_a (right_b . rho3) with pu_a = left_a . R2 x1 and
// zr_b = -right_b . R3 x1: the yaws enter through R2 x1 and R3 x1 only. Writes the cost |r|^2 at
// the estimate it started from (|rho| = 1). Returns true if the step was at rounding level
// (converged); leaves the estimate unchanged, and returns true, if the centres are zero or the
// step is not finite.
template <typename FrameFunction>
bool PolishYawsAndCenters(std::size_t count,
                          const FrameFunction& frame,
                          AlignedEstimate* estimate,
                          double* cost_at_start) {
  Vector6d rho;
  rho << estimate->yaw2.Rotate(estimate->center2), estimate->yaw3.Rotate(estimate->center3);
  const double norm = rho.norm();
  *cost_at_start = 0.0;
  if (!(norm > 0.0)) return true;
  rho /= norm;
  const Eigen::Vector3d rho2 = rho.head<3>(), rho3 = rho.tail<3>();
  // dR_y/dtheta x = K R_y x with K v = (v_z, 0, -v_x).
  const auto K = [](const Eigen::Vector3d& v) { return Eigen::Vector3d(v.z(), 0.0, -v.x()); };
  // Normal equations of the 4N x 8 Jacobian [dr/dtheta2, dr/dtheta3, dr/drho], accumulated per
  // triplet in factored form: the rho block of row (a, b) is [zr_b left_a^T, pu_a right_b^T], so
  // the triplet's 6 x 6 block is [(sum_b zr_b^2) S2, (sum_a pu_a left_a)(sum_b zr_b right_b)^T; .,
  // (sum_a pu_a^2) S3] with S2 = sum_a left_a left_a^T = |x2|^2 I - x2 x2^T (left_a = p_a x x2 for
  // an orthonormal basis (p_a) of x2^perp; likewise S3), and a column v of the other entries gives
  // (sum_a (sum_b v_ab zr_b) left_a; sum_b (sum_a v_ab pu_a) right_b).
  Eigen::Matrix<double, 8, 8> JtJ = Eigen::Matrix<double, 8, 8>::Zero();
  Eigen::Matrix<double, 8, 1> Jtr = Eigen::Matrix<double, 8, 1>::Zero();
  Eigen::Matrix3d ll = Eigen::Matrix3d::Zero(), mm = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d lm = Eigen::Matrix3d::Zero();
  double cost = 0.0;
  for (std::size_t n = 0; n < count; ++n) {
    const internal::TripletFrame& f = frame(n);
    const Eigen::Vector3d u = estimate->yaw2.Rotate(f.x1), Ku = K(u);
    const Eigen::Vector3d z = estimate->yaw3.Rotate(f.x1), Kz = K(z);
    double alpha[2], pu[2], dpu[2], beta[2], zr[2], dzr[2];
    for (int i = 0; i < 2; ++i) {
      alpha[i] = f.left[i].dot(rho2);
      pu[i] = f.left[i].dot(u);
      dpu[i] = f.left[i].dot(Ku);
      beta[i] = f.right[i].dot(rho3);
      zr[i] = -f.right[i].dot(z);
      dzr[i] = -f.right[i].dot(Kz);
    }
    // The yaw columns and the residual, entry (a, b) at index 2 a + b.
    Eigen::Matrix<double, 4, 3> v;
    for (int a = 0; a < 2; ++a) {
      for (int b = 0; b < 2; ++b) {
        v(2 * a + b, 0) = dpu[a] * beta[b];
        v(2 * a + b, 1) = dzr[b] * alpha[a];
        v(2 * a + b, 2) = zr[b] * alpha[a] + pu[a] * beta[b];
      }
    }
    const Eigen::Matrix3d vtv = v.transpose() * v;
    JtJ.topLeftCorner<2, 2>() += vtv.topLeftCorner<2, 2>();
    Jtr.head<2>() += vtv.block<2, 1>(0, 2);
    cost += vtv(2, 2);
    Eigen::Matrix<double, 6, 3> Ftv;
    for (int j = 0; j < 3; ++j) {
      const double za0 = v(0, j) * zr[0] + v(1, j) * zr[1];
      const double za1 = v(2, j) * zr[0] + v(3, j) * zr[1];
      const double pb0 = v(0, j) * pu[0] + v(2, j) * pu[1];
      const double pb1 = v(1, j) * pu[0] + v(3, j) * pu[1];
      Ftv.block<3, 1>(0, j) = za0 * f.left[0] + za1 * f.left[1];
      Ftv.block<3, 1>(3, j) = pb0 * f.right[0] + pb1 * f.right[1];
    }
    JtJ.block<6, 2>(2, 0) += Ftv.leftCols<2>();
    Jtr.tail<6>() += Ftv.col(2);
    const double zz = zr[0] * zr[0] + zr[1] * zr[1];
    const double pp = pu[0] * pu[0] + pu[1] * pu[1];
    ll.diagonal().array() += zz * f.x2.squaredNorm();
    ll.noalias() -= (zz * f.x2) * f.x2.transpose();
    mm.diagonal().array() += pp * f.x3.squaredNorm();
    mm.noalias() -= (pp * f.x3) * f.x3.transpose();
    lm.noalias() += (pu[0] * f.left[0] + pu[1] * f.left[1]) *
                    (zr[0] * f.right[0] + zr[1] * f.right[1]).transpose();
  }
  *cost_at_start = cost;
  JtJ.block<2, 6>(0, 2) = JtJ.block<6, 2>(2, 0).transpose();
  JtJ.block<3, 3>(2, 2) = ll;
  JtJ.block<3, 3>(2, 5) = lm;
  JtJ.block<3, 3>(5, 2) = lm.transpose();
  JtJ.block<3, 3>(5, 5) = mm;
  // Gauge: the step keeps rho . delta_rho = 0, weighted like an average row.
  Eigen::Matrix<double, 8, 1> gauge = Eigen::Matrix<double, 8, 1>::Zero();
  gauge.tail<6>() = rho;
  JtJ.noalias() += (JtJ.trace() / 8.0) * gauge * gauge.transpose();
  // With the gauge row JtJ is positive definite unless the data are degenerate: the
  // square-root-free U^T D U solve, pivoted LDLT only where a pivot is not positive.
  Eigen::Matrix<double, 8, 1> step = -Jtr;
  if (!internal::SolveSymmetricPositiveDefiniteInPlace(JtJ, &step)) step = -JtJ.ldlt().solve(Jtr);
  if (!step.allFinite()) return true;
  // theta_k + delta applied as the direction (cos, sin) + delta (-sin, cos), i.e. theta_k +
  // atan(delta), which differs by O(delta^3): the step keeps its quadratic convergence, with no
  // trigonometric call.
  const auto turn = [](const Yaw& yaw, double delta) {
    return Yaw::FromDirection(yaw.c - delta * yaw.s, yaw.s + delta * yaw.c);
  };
  estimate->yaw2 = turn(estimate->yaw2, step[0]);
  estimate->yaw3 = turn(estimate->yaw3, step[1]);
  rho += step.tail<6>();
  estimate->center2 = norm * estimate->yaw2.RotateBack(rho.head<3>());
  estimate->center3 = norm * estimate->yaw3.RotateBack(rho.tail<3>());
  // Quadratic convergence: after a step below 1e-8 the next one would be at rounding level.
  return step.squaredNorm() < 1e-16;
}

// Up to max_steps polish steps, ending early once a step is at rounding level (noise-free data:
// one step) or the step before the last changed the cost by less than kPolishCostTolerance of it
// (with noise the steps converge linearly; derivations.md section 4.5).
constexpr double kPolishCostTolerance = 1e-2;

template <typename FrameFunction>
void Polish(std::size_t count,
            const FrameFunction& frame,
            int max_steps,
            AlignedEstimate* estimate) {
  double previous_cost = -1.0;
  for (int step = 0; step < max_steps; ++step) {
    double cost = 0.0;
    if (PolishYawsAndCenters(count, frame, estimate, &cost)) return;
    if (previous_cost >= 0.0 &&
        std::abs(previous_cost - cost) <= kPolishCostTolerance * previous_cost)
      return;
    previous_cost = cost;
  }
}

// The steps SolveAligned runs for the options and the size of the system (derivations.md section
// 4.7).
struct Pipeline {
  Trifocal4ptRecovery recovery;
  bool resolve_translations;
  int max_polish_steps;
};

Pipeline PipelineFor(const Trifocal4ptOptions& options, bool minimal) {
  if (options.recovery != Trifocal4ptRecovery::kLeastSquaresIfMinimal) {
    return {options.recovery, options.resolve_translations, options.polish_iterations};
  }
  // 4 triplets: the least-squares read, no re-solve (at the read's yaws it moves the centres away
  // from the polish's optimum); more: the enforcement, the re-solve and at most one polish step.
  if (minimal) return {Trifocal4ptRecovery::kLeastSquares, false, options.polish_iterations};
  return {Trifocal4ptRecovery::kEnforced, options.resolve_translations,
          std::min(options.polish_iterations, 1)};
}

// Rows = 16 for the minimal case (fixed size, no heap allocation) or Eigen::Dynamic.
template <int Rows>
int SolveAligned(const std::vector<Eigen::Vector3d>& x1,
                 const std::vector<Eigen::Vector3d>& x2,
                 const std::vector<Eigen::Vector3d>& x3,
                 const Trifocal4ptOptions& options,
                 std::vector<ThreeViewPose>* solutions) {
  // The rotation-independent parts of every triplet's rows: computed once for the 4 triplets of
  // the minimal case, on the fly otherwise (no storage that grows with N).
  std::array<internal::TripletFrame, Rows == 16 ? 4 : 0> frames;
  using FrameResult =
      std::conditional_t<Rows == 16, const internal::TripletFrame&, internal::TripletFrame>;
  const auto frame = [&](std::size_t n) -> FrameResult {
    if constexpr (Rows == 16) {
      return frames[n];
    } else {
      return internal::MakeTripletFrame(x1[n], x2[n], x3[n]);
    }
  };
  // q: exact null vector of the 16 x 17 system in the minimal case, least-squares otherwise; M is
  // the system itself or its triangular factor (|A y| = |R_A y|), as enforcement needs it.
  Vector17d q;
  Eigen::Matrix<double, Rows == 16 ? 16 : 17, 17> M;
  if constexpr (Rows == 16) {
    for (std::size_t n = 0; n < 4; ++n) {
      frames[n] = internal::MakeTripletFrame(x1[n], x2[n], x3[n]);
      M.template middleRows<4>(4 * n) = IncidenceRows(frames[n]);
    }
    if (!M.allFinite()) return 0;
    q = internal::NullVectorOfWideMatrix<17>(M);
  } else {
    M = internal::StackedTriangularFactor<17>(
        x1.size(), [&](std::size_t n) { return IncidenceRows(frame(n)); });
    if (!M.allFinite() || internal::HasMultipleNullDirections<17>(M)) return 0;
    q = internal::SmallestRightSingularVectorOfTriangular<17>(M);
  }
  if (q.isZero()) return 0;

  Pipeline pipeline = PipelineFor(options, Rows == 16);
  AlignedEstimate estimate;
  bool ok = false;
  Eigen::Vector3d epipole2, epipole3;
  switch (pipeline.recovery) {
    case Trifocal4ptRecovery::kLeastSquares:
      ok = EstimateLeastSquares(q, &estimate);
      if (ok || options.recovery != Trifocal4ptRecovery::kLeastSquaresIfMinimal) break;
      // The read is undefined (a horizontal epipole vanishes): kEnforced, whose epipoles then
      // come from the tensor, and the re-solve.
      pipeline.recovery = Trifocal4ptRecovery::kEnforced;
      pipeline.resolve_translations = options.resolve_translations;
      [[fallthrough]];
    case Trifocal4ptRecovery::kEnforced:
      // Epipoles (derivations.md section 4.3 step 1): by default the least-squares read of q for
      // the minimal system, the tensor's null vectors for more triplets.
      ok = (Rows == 16 && options.epipoles == Trifocal4ptEpipoles::kLeastSquaresReadIfMinimal
                ? EpipolesFromQ(q, &epipole2, &epipole3)
                : internal::EpipolesFromTensor(TensorFromQ(q), &epipole2, &epipole3)) &&
           EnforceConstraints(M, epipole2, epipole3, &estimate);
      break;
    case Trifocal4ptRecovery::kPaperClosedForm:
      ok = EstimatePaperClosedForm(q, &estimate);
      break;
    case Trifocal4ptRecovery::kLeastSquaresIfMinimal:  // resolved by PipelineFor
      break;
  }
  if (!ok || !estimate.yaw2.IsFinite() || !estimate.yaw3.IsFinite()) return 0;
  if (pipeline.resolve_translations) ResolveCenters<Rows>(x1.size(), frame, &estimate);
  if (pipeline.recovery == Trifocal4ptRecovery::kEnforced) {
    // Epipoles of the current pose, e' ~ R2 c2 and e'' ~ R3 c3, then enforcement and centres again.
    for (int iteration = 0; iteration < options.epipole_iterations; ++iteration) {
      epipole2 = estimate.yaw2.Rotate(estimate.center2).normalized();
      epipole3 = estimate.yaw3.Rotate(estimate.center3).normalized();
      if (!epipole2.allFinite() || !epipole3.allFinite() ||
          !EnforceConstraints(M, epipole2, epipole3, &estimate)) {
        return 0;
      }
      if (pipeline.resolve_translations) ResolveCenters<Rows>(x1.size(), frame, &estimate);
    }
  }
  Polish(x1.size(), frame, pipeline.max_polish_steps, &estimate);

  ThreeViewPose pose;
  if (!internal::OrientScaleAndMakePose(x1, x2, x3, estimate.yaw2, estimate.center2, estimate.yaw3,
                                        estimate.center3, &pose)) {
    return 0;
  }
  solutions->push_back(pose);
  return 1;
}

}  // namespace

void Trifocal4ptOptions::Check() const {
  auto require = [](bool ok, const char* what) {
    if (!ok) throw std::invalid_argument(std::string("trigrav: Trifocal4ptOptions: ") + what);
  };
  require(recovery == Trifocal4ptRecovery::kLeastSquaresIfMinimal ||
              recovery == Trifocal4ptRecovery::kEnforced ||
              recovery == Trifocal4ptRecovery::kLeastSquares ||
              recovery == Trifocal4ptRecovery::kPaperClosedForm,
          "unknown recovery");
  require(epipoles == Trifocal4ptEpipoles::kLeastSquaresReadIfMinimal ||
              epipoles == Trifocal4ptEpipoles::kTensorNullVectors,
          "unknown epipoles");
  require(epipole_iterations >= 0, "epipole_iterations must be >= 0");
  require(polish_iterations >= 0, "polish_iterations must be >= 0");
}

int SolveTrifocal4pt(const std::vector<Eigen::Vector3d>& x1,
                     const std::vector<Eigen::Vector3d>& x2,
                     const std::vector<Eigen::Vector3d>& x3,
                     const Trifocal4ptOptions& options,
                     std::vector<ThreeViewPose>* solutions) {
  options.Check();
  internal::CheckTriplets("SolveTrifocal4pt", internal::kTrifocal4ptMinTriplets,
                          std::numeric_limits<std::size_t>::max(), x1, x2, x3, solutions);
  solutions->clear();
  if (x1.size() == internal::kTrifocal4ptMinTriplets) {
    return SolveAligned<16>(x1, x2, x3, options, solutions);
  }
  return SolveAligned<Eigen::Dynamic>(x1, x2, x3, options, solutions);
}

int SolveTrifocal4pt(const std::vector<Eigen::Vector3d>& x1,
                     const std::vector<Eigen::Vector3d>& x2,
                     const std::vector<Eigen::Vector3d>& x3,
                     std::vector<ThreeViewPose>* solutions) {
  return SolveTrifocal4pt(x1, x2, x3, Trifocal4ptOptions(), solutions);
}

int SolveTrifocal4pt(const std::vector<Eigen::Vector3d>& x1,
                     const std::vector<Eigen::Vector3d>& x2,
                     const std::vector<Eigen::Vector3d>& x3,
                     const Eigen::Vector3d& gravity_in_cam1,
                     const Eigen::Vector3d& gravity_in_cam2,
                     const Eigen::Vector3d& gravity_in_cam3,
                     const Trifocal4ptOptions& options,
                     std::vector<ThreeViewPose>* solutions) {
  return internal::SolveWithGravity(
      "SolveTrifocal4pt", x1, x2, x3, gravity_in_cam1, gravity_in_cam2, gravity_in_cam3, solutions,
      [&options](const std::vector<Eigen::Vector3d>& y1, const std::vector<Eigen::Vector3d>& y2,
                 const std::vector<Eigen::Vector3d>& y3, std::vector<ThreeViewPose>* out) {
        return SolveTrifocal4pt(y1, y2, y3, options, out);
      });
}

int SolveTrifocal4pt(const std::vector<Eigen::Vector3d>& x1,
                     const std::vector<Eigen::Vector3d>& x2,
                     const std::vector<Eigen::Vector3d>& x3,
                     const Eigen::Vector3d& gravity_in_cam1,
                     const Eigen::Vector3d& gravity_in_cam2,
                     const Eigen::Vector3d& gravity_in_cam3,
                     std::vector<ThreeViewPose>* solutions) {
  return SolveTrifocal4pt(x1, x2, x3, gravity_in_cam1, gravity_in_cam2, gravity_in_cam3,
                          Trifocal4ptOptions(), solutions);
}

}  // namespace trigrav
