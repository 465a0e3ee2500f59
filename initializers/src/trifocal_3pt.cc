#include "trigrav/initializers/trifocal_3pt.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>

#include "gravity_wrapper.h"
#include "input_checks.h"
#include "null_space.h"
#include "polynomial.h"
#include "triangular_factor.h"
#include "trifocal_common.h"
#include "two_view_geometry.h"

namespace trigrav {
namespace {

using Rays = std::vector<Eigen::Vector3d>;
// The rays of one view of a minimal sample, copied to fixed storage.
using MinimalRays = std::array<Eigen::Vector3d, 3>;
using internal::Vector6d;

constexpr std::size_t kNumTriplets = 3;

// Offsets theta_0 of the Cayley parameter t = tan((theta - theta_0)/2), tried in this order. The
// parameterisation misses theta = theta_0 + pi, where the leading coefficient of the polynomial in
// t vanishes; 0 is the paper's choice, the others take over when a root lies at or near pi (see
// ChooseOffset). The polynomials are trigonometric of degree <= 4 in theta, with at most 8 zeros in
// a period, so one of the 9 offsets has a leading coefficient well away from zero.
struct Offset {
  double c, s;    // cos and sin of theta_0
  double c2, s2;  // cos and sin of 2 theta_0
};
constexpr double kSqrtHalf = 0.70710678118654752;  // cos(pi/4)
constexpr double kCos8 = 0.92387953251128676;      // cos(pi/8)
constexpr double kSin8 = 0.38268343236508977;      // sin(pi/8)
constexpr std::array<Offset, 9> kOffsets = {{
    {1.0, 0.0, 1.0, 0.0},                    // 0
    {0.0, 1.0, -1.0, 0.0},                   // pi/2
    {0.0, -1.0, -1.0, 0.0},                  // -pi/2
    {kSqrtHalf, kSqrtHalf, 0.0, 1.0},        // pi/4
    {kSqrtHalf, -kSqrtHalf, 0.0, -1.0},      // -pi/4
    {-kSqrtHalf, kSqrtHalf, 0.0, -1.0},      // 3pi/4
    {-kSqrtHalf, -kSqrtHalf, 0.0, 1.0},      // -3pi/4
    {kCos8, kSin8, kSqrtHalf, kSqrtHalf},    // pi/8
    {kCos8, -kSin8, kSqrtHalf, -kSqrtHalf},  // -pi/8
}};
// The leading coefficient counts as tiny below this fraction of the largest coefficient: sextic
// solver.
constexpr double kMinRelativeLeading = 1e-2;
// Decoupled solver: the same for the trigonometric coefficients of D (TrigQuadratic). Stricter,
// since a small leading coefficient means a root of large |t|, and Ferrari's shift by a quarter of
// the root sum then costs the other roots digits: at 1e-2 a scene with roots near 199 and two 5e-5
// apart near 0.04 lost the pair (a 0.03 deg error noise-free).
constexpr double kMinRelativeQuarticLeading = 0.1;
// Decoupled solver: at most this many guarded Newton steps polish each quartic root (usually one,
// taken unchecked once converged; near-double roots need more).
constexpr int kQuarticNewtonSteps = 6;
// Decoupled solver: a complex pair of quartic roots with |Im t| below this times 1 + (Re t)^2 (an
// imaginary part of theta below about 0.2 wherever the Cayley offset puts the root) also gives a
// candidate, at its real part (about where the epipolar constraints of the pair come closest to
// consistent). Noise turns near-double real roots, often the true one among them, into such pairs.
// On the synthetic scenes of derivations.md section 8.5 at 1 px this cuts the scenes without any
// candidate from 5.3 % to 0.9 % and the median rotation error of the best-ranked candidate
// from 1.15 to 0.95 deg, for 0.2 more candidates per call noise-free (0.6 at 1 px). Exact roots are
// unaffected. trigrav's own addition.
constexpr double kMaxImaginaryPart = 0.1;

// Sorts the first `count` entries of a small array by key, ascending (insertion sort, no heap).
template <typename T, std::size_t N, typename Key>
void SortByKey(int count, Key&& key, std::array<T, N>* items) {
  for (int i = 1; i < count; ++i) {
    const T item = (*items)[i];
    int j = i;
    for (; j > 0 && key(item) < key((*items)[j - 1]); --j) (*items)[j] = (*items)[j - 1];
    (*items)[j] = item;
  }
}

using internal::Yaw;

// w (cos theta, sin theta) for theta = theta_0 + 2 atan(t), w = 1 + t^2: the half-angle formulas
// without their common denominator w.
Eigen::Vector2d ScaledCayleyDirection(double t, const Offset& offset) {
  const double c_phi = 1.0 - t * t, s_phi = 2.0 * t;
  return {c_phi * offset.c - s_phi * offset.s, s_phi * offset.c + c_phi * offset.s};
}

Yaw YawFromCayley(double t, const Offset& offset) {
  const Eigen::Vector2d direction = ScaledCayleyDirection(t, offset) / (1.0 + t * t);
  return {direction.x(), direction.y()};
}

// R_y(theta) x = cos(theta) A + sin(theta) B + C with A = (x, 0, z), B = (z, 0, -x), C = (0, y, 0)
// (derivations.md section 1.4).
struct TrigLinear {
  Eigen::Vector3d A, B, C;
  explicit TrigLinear(const Eigen::Vector3d& x)
      : A(x.x(), 0.0, x.z()), B(x.z(), 0.0, -x.x()), C(0.0, x.y(), 0.0) {}
};

// Picks the Cayley offset: the first of kOffsets whose leading coefficient (the value of the
// trigonometric polynomial at theta_0 + pi, evaluated by `leading`) is at least min_relative *
// scale, else the one with the largest leading coefficient.
template <typename Leading>
const Offset& ChooseOffset(double min_relative, double scale, Leading&& leading) {
  const Offset* best_offset = &kOffsets[0];
  double best = -1.0;
  for (const Offset& offset : kOffsets) {
    const double value = std::abs(leading(offset));
    if (value >= min_relative * scale) return offset;
    if (value > best) {
      best = value;
      best_offset = &offset;
    }
  }
  return *best_offset;
}

// ------------------------------------------------------------------------------------------------
// Decoupled solver (derivations.md section 5.5).

// One real root of the upright 2-view problem of pair (1,k) that passes cheirality.
struct PairRoot {
  Yaw yaw;
  Eigen::Vector3d epipole;  // R_k c_k = -t_k (camera k's fourth column, negated), unit
  Eigen::Vector3d depth;    // view-1 depths lambda_n of the 3 points, |c_k| = 1
};

// det[m_1; m_2; m_3], m_n(theta) = (R_y(theta) x1_n) x xk_n = cos P_n + sin Q_n + S_n, is a
// trigonometric polynomial of degree 2 (the degree-6 polynomial in tan(theta/2) has the factor
// 1 + tan^2, derivations.md section 5.5), D = a0 + a1 cos + b1 sin + a2 cos 2theta + b2 sin 2theta,
// with coefficients in closed form (TrigQuadratic::FromNormals).
struct TrigQuadratic {
  double a0 = 0.0, a1 = 0.0, b1 = 0.0, a2 = 0.0, b2 = 0.0;
  // D from P_n, Q_n, S_n (S_n has no y part) by multilinearity, w_n = cos P_n + sin Q_n
  // (derivations.md section 5.5): det[S] = 0; the terms with two S give sum_n sigma_n w_n.y,
  // sigma_n = (S_i x S_j).y; det[w] = det[P] cos + det[Q] sin on the unit circle; the terms with
  // one S give A cos^2 + B cos sin + C sin^2, A = sum_n S_n . (P_i x P_j), B = sum_n S_n . (P_i x
  // Q_j + Q_i x P_j), C = sum_n S_n . (Q_i x Q_j), over (n, i, j) = (0, 1, 2), (1, 2, 0), (2, 0,
  // 1).
  static TrigQuadratic FromNormals(const std::array<Eigen::Vector3d, 3>& P,
                                   const std::array<Eigen::Vector3d, 3>& Q,
                                   const std::array<Eigen::Vector3d, 3>& S) {
    // S . (u x v) for S with S.y = 0.
    auto s_dot_cross = [](const Eigen::Vector3d& S, const Eigen::Vector3d& u,
                          const Eigen::Vector3d& v) {
      return S.x() * (u.y() * v.z() - u.z() * v.y()) + S.z() * (u.x() * v.y() - u.y() * v.x());
    };
    double A = 0.0, B = 0.0, C = 0.0, linear_cos = 0.0, linear_sin = 0.0;
    for (int n = 0; n < 3; ++n) {
      const int i = n == 2 ? 0 : n + 1, j = n == 0 ? 2 : n - 1;
      A += s_dot_cross(S[n], P[i], P[j]);
      B += s_dot_cross(S[n], P[i], Q[j]) + s_dot_cross(S[n], Q[i], P[j]);
      C += s_dot_cross(S[n], Q[i], Q[j]);
      const double sigma = S[i].z() * S[j].x() - S[i].x() * S[j].z();
      linear_cos += sigma * P[n].y();
      linear_sin += sigma * Q[n].y();
    }
    TrigQuadratic D;
    D.a0 = 0.5 * (A + C);
    D.a1 = P[0].dot(P[1].cross(P[2])) + linear_cos;
    D.b1 = Q[0].dot(Q[1].cross(Q[2])) + linear_sin;
    D.a2 = 0.5 * (A - C);
    D.b2 = 0.5 * B;
    return D;
  }
  // Value at theta_0 + pi, the leading coefficient of the quartic in tan((theta - theta_0)/2).
  double AtOffsetPlusPi(const Offset& o) const {
    return a0 - a1 * o.c - b1 * o.s + a2 * o.c2 + b2 * o.s2;
  }
  double Scale() const {
    return std::max({std::abs(a0), std::abs(a1), std::abs(b1), std::abs(a2), std::abs(b2)});
  }
  // q(t) = (1 + t^2)^2 D(theta_0 + 2 atan t), lowest degree first.
  std::array<double, 5> Quartic(const Offset& o) const {
    const double A1 = a1 * o.c + b1 * o.s, B1 = b1 * o.c - a1 * o.s;
    const double A2 = a2 * o.c2 + b2 * o.s2, B2 = b2 * o.c2 - a2 * o.s2;
    return {a0 + A1 + A2, 2 * B1 + 4 * B2, 2 * a0 - 6 * A2, 2 * B1 - 4 * B2, a0 - A1 + A2};
  }
};

// The upright two-view problem of pair (1, k): the epipolar normals m_n(theta) = cos P_n + sin
// Q_n + S_n and the real roots t of det[m_1; m_2; m_3] in t = tan((theta - theta_0)/2).
struct UprightPair {
  std::array<Eigen::Vector3d, 3> P, Q, S;
  // (R_y(theta) x1_n) . xk_n = cos p_n + sin q_n + s_n.
  std::array<double, 3> p, q, s;
  const Offset* offset = &kOffsets[0];
  std::array<double, 4> t;
  int num_t = 0;
};

// Sets up pair (1, k) and solves its quartic. No roots (num_t = 0) when det[m_1; m_2; m_3]
// vanishes for every yaw (two of the three triplets coincide, or all three points coincide): the
// pair then has a continuum of solutions, not a few.
void SolveUprightQuartic(const MinimalRays& x1, const MinimalRays& xk, UprightPair* pair) {
  // P_n = A_n x xk_n, Q_n = B_n x xk_n, S_n = C_n x xk_n (TrigLinear), written out for the zeros
  // of A, B, C (S_n has no y part).
  std::array<Eigen::Vector3d, 3>& P = pair->P;
  std::array<Eigen::Vector3d, 3>& Q = pair->Q;
  std::array<Eigen::Vector3d, 3>& S = pair->S;
  for (std::size_t n = 0; n < kNumTriplets; ++n) {
    const double x = x1[n].x(), y = x1[n].y(), z = x1[n].z();
    const double a = xk[n].x(), b = xk[n].y(), c = xk[n].z();
    P[n] = Eigen::Vector3d(-z * b, z * a - x * c, x * b);
    Q[n] = Eigen::Vector3d(x * b, -x * a - z * c, z * b);
    S[n] = Eigen::Vector3d(y * c, 0.0, -y * a);
    pair->p[n] = x * a + z * c;
    pair->q[n] = z * a - x * c;
    pair->s[n] = y * b;
  }
  pair->num_t = 0;
  const TrigQuadratic D = TrigQuadratic::FromNormals(P, Q, S);
  double squared_hadamard_bound = 1.0;  // prod_n |m_n|^2 at theta = 0, >= det^2 there
  for (std::size_t n = 0; n < kNumTriplets; ++n) {
    squared_hadamard_bound *= (P[n] + S[n]).squaredNorm();
  }
  const double scale = D.Scale();
  // The determinant vanishes identically (rounding leaves about 1e-16 of the Hadamard bound) when
  // two triplets coincide.
  constexpr double kMinRelativeDeterminant = 1e-10;
  if (!(scale * scale >
        kMinRelativeDeterminant * kMinRelativeDeterminant * squared_hadamard_bound) ||
      !std::isfinite(scale)) {
    return;
  }
  pair->offset = &ChooseOffset(kMinRelativeQuarticLeading, scale,
                               [&D](const Offset& theta0) { return D.AtOffsetPlusPi(theta0); });
  pair->num_t = internal::SolveQuarticReal(D.Quartic(*pair->offset), &pair->t, kQuarticNewtonSteps,
                                           kMaxImaginaryPart);
}

// The roots of pair (1, k) that pass cheirality.
int UprightPairRoots(const MinimalRays& xk,
                     const UprightPair& pair,
                     std::array<PairRoot, 4>* roots) {
  const std::array<Eigen::Vector3d, 3>& P = pair.P;
  const std::array<Eigen::Vector3d, 3>& Q = pair.Q;
  const std::array<Eigen::Vector3d, 3>& S = pair.S;
  const std::array<double, 3>& p = pair.p;
  const std::array<double, 3>& q = pair.q;
  const std::array<double, 3>& s = pair.s;
  const Offset& offset = *pair.offset;
  const std::array<double, 4>& t = pair.t;
  const int num_t = pair.num_t;
  int count = 0;
  for (int i = 0; i < num_t; ++i) {
    // Everything below is homogeneous in w = 1 + t^2 > 0, so the yaw is carried unnormalised,
    // (c, sn) = w (cos theta, sin theta), and m_n = w m_n(theta).
    const Eigen::Vector2d direction = ScaledCayleyDirection(t[i], offset);
    const double w = 1.0 + t[i] * t[i], c = direction.x(), sn = direction.y();
    // m_n by components (S_n.y = 0), in plain scalars: Eigen's 3-vectors cost shuffles here.
    std::array<double, 3> mx, my, mz;
    for (std::size_t n = 0; n < kNumTriplets; ++n) {
      mx[n] = c * P[n].x() + sn * Q[n].x() + w * S[n].x();
      my[n] = c * P[n].y() + sn * Q[n].y();
      mz[n] = c * P[n].z() + sn * Q[n].z() + w * S[n].z();
    }
    // The epipole R_k c_k is orthogonal to the three epipolar normals m_n: take the best
    // conditioned of the cross products m_n x m_(n+1) (normalised once the root is kept).
    std::array<double, 3> ex, ey, ez, squared_norm;
    for (std::size_t n = 0; n < kNumTriplets; ++n) {
      const std::size_t j = n == 2 ? 0 : n + 1;
      ex[n] = my[n] * mz[j] - mz[n] * my[j];
      ey[n] = mz[n] * mx[j] - mx[n] * mz[j];
      ez[n] = mx[n] * my[j] - my[n] * mx[j];
      squared_norm[n] = ex[n] * ex[n] + ey[n] * ey[n] + ez[n] * ez[n];
    }
    std::size_t best = squared_norm[1] > squared_norm[0] ? 1 : 0;
    best = squared_norm[2] > squared_norm[best] ? 2 : best;
    const Eigen::Vector3d epipole(ex[best], ey[best], ez[best]);
    // View-1 depths lambda_n = ((xk x e) . (xk x R x1)) / |xk x R x1|^2, xk x R x1 = -m_n
    // (derivations.md section 4.6), and in front of camera k too: (R (lambda x1 - c)) . xk =
    // lambda (R x1) . xk - e . xk > 0. The sign of c_k is free: both tests hold for one of the two
    // signs, which the first numerator decides; multiplied by |m_n|^2 > 0, they need no division.
    std::array<double, 3> numerator, denominator, epipole_dot;
    bool in_front = true;
    for (std::size_t n = 0; n < kNumTriplets; ++n) {
      const double a = xk[n].x(), b = xk[n].y(), d = xk[n].z();
      // -(xk x e) . m
      numerator[n] = -((b * epipole.z() - d * epipole.y()) * mx[n] +
                       (d * epipole.x() - a * epipole.z()) * my[n] +
                       (a * epipole.y() - b * epipole.x()) * mz[n]);
      denominator[n] = mx[n] * mx[n] + my[n] * my[n] + mz[n] * mz[n];
      epipole_dot[n] = a * epipole.x() + b * epipole.y() + d * epipole.z();
    }
    const double sign = numerator[0] < 0.0 ? -1.0 : 1.0;
    for (std::size_t n = 0; n < kNumTriplets; ++n) {
      in_front &= (sign * numerator[n] > 0.0) & (denominator[n] > 0.0) &
                  (sign * (numerator[n] * (c * p[n] + sn * q[n] + w * s[n]) -
                           denominator[n] * epipole_dot[n]) >
                   0.0);
    }
    if (!in_front) continue;
    const double norm = epipole.norm();
    if (!(norm > 0.0) || !std::isfinite(norm)) continue;
    PairRoot& root = (*roots)[count];
    root.yaw = {c / w, sn / w};
    // lambda_n = w numerator_n / (|e| denominator_n) for the unnormalised m_n and e.
    const double unit = sign / norm;
    root.epipole = unit * epipole;
    for (std::size_t n = 0; n < kNumTriplets; ++n) {
      root.depth[n] = w * unit * numerator[n] / denominator[n];
    }
    if (!root.depth.allFinite()) continue;
    ++count;
  }
  return count;
}

// The decoupled solver's result between gravity-aligned frames: the kept roots of both pairs and
// the candidates, combinations (i2, i3) with the scale kappa of c_3, best first.
struct DecoupledSolution {
  struct Candidate {
    double residual_squared, kappa;
    int i2, i3;
  };
  std::array<PairRoot, 4> roots2, roots3;
  std::array<Candidate, 16> candidates;
  int count2 = 0, count3 = 0, count = 0;
};

// The decoupled solver on aligned rays (steps 1-3 of trifocal_3pt.h): fills *solution and returns
// its candidate count. Every candidate is finite: yaws from finite roots, unit epipoles, finite
// kappa.
int SolveDecoupledAligned(const MinimalRays& x1,
                          const MinimalRays& x2,
                          const MinimalRays& x3,
                          DecoupledSolution* solution) {
  solution->count = 0;
  // Camera 2 sets the scale |c_2| = 1, undefined without parallax in pair (1,2); camera 3 may
  // have none (c_3 = 0 is a valid pose).
  if (internal::PairExplainedByYaw(x1, x2)) return 0;
  // Both quartics first: their long chains of dependent divisions and roots are independent, and
  // back to back the processor overlaps them.
  UprightPair pair2, pair3;
  SolveUprightQuartic(x1, x2, &pair2);
  SolveUprightQuartic(x1, x3, &pair3);
  const int count2 = UprightPairRoots(x2, pair2, &solution->roots2);
  solution->count2 = count2;
  if (count2 == 0) return 0;
  const int count3 = UprightPairRoots(x3, pair3, &solution->roots3);
  solution->count3 = count3;

  std::array<double, 4> inverse_squared_norm2, inverse_squared_norm3;
  for (int i = 0; i < count2; ++i) {
    inverse_squared_norm2[i] = 1.0 / solution->roots2[i].depth.squaredNorm();
  }
  for (int i = 0; i < count3; ++i) {
    inverse_squared_norm3[i] = 1.0 / solution->roots3[i].depth.squaredNorm();
  }
  int count = 0;
  for (int i2 = 0; i2 < count2; ++i2) {
    const Eigen::Vector3d& depth2 = solution->roots2[i2].depth;
    for (int i3 = 0; i3 < count3; ++i3) {
      const Eigen::Vector3d& depth3 = solution->roots3[i3].depth;
      // Scale of c_3 that best matches the depths of pair (1,2); the depth-ratio residual
      // |lambda_2 - kappa lambda_3| / |lambda_2| ranks (compared squared).
      const double kappa = depth2.dot(depth3) * inverse_squared_norm3[i3];
      const double residual_squared =
          (depth2 - kappa * depth3).squaredNorm() * inverse_squared_norm2[i2];
      if (!(kappa > 0.0) || !std::isfinite(kappa) || !std::isfinite(residual_squared)) continue;
      solution->candidates[count++] = {residual_squared, kappa, i2, i3};
    }
  }
  SortByKey(
      count, [](const DecoupledSolution::Candidate& c) { return c.residual_squared; },
      &solution->candidates);
  solution->count = count;
  return count;
}

// Writes the candidates of `solution` to *solutions (cleared), best first, in place, and returns
// their count. write_pose(camera, index, scale, pose) writes the pose of camera k = camera + 1 for
// its pair root `index`, whose fourth column is t = -scale * epipole (scale 1 for camera 2, |c_2| =
// 1, and kappa for camera 3).
template <typename WritePose>
int WriteCandidates(const DecoupledSolution& solution,
                    WritePose&& write_pose,
                    std::vector<ThreeViewPose>* solutions) {
  solutions->resize(solution.count);
  for (int i = 0; i < solution.count; ++i) {
    const DecoupledSolution::Candidate& candidate = solution.candidates[i];
    ThreeViewPose& pose = (*solutions)[i];
    write_pose(1, candidate.i2, 1.0, &pose.cam2_from_cam1);
    write_pose(2, candidate.i3, candidate.kappa, &pose.cam3_from_cam1);
  }
  return solution.count;
}

// ------------------------------------------------------------------------------------------------
// Sextic solver (derivations.md section 5.4).

// True if all 3 points triangulated from pair (1,k) with this pose lie in front of cameras 1 and k.
bool PointsInFront(const Rays& x1, const Rays& xk, const CameraPose& pose) {
  const Eigen::Vector3d center = pose.Center();
  for (std::size_t n = 0; n < kNumTriplets; ++n) {
    const double depth = internal::ViewOneDepth(x1[n], xk[n], pose.R, center);
    if (!(depth > 0.0) || !((pose.R * (depth * x1[n] - center)).dot(xk[n]) > 0.0)) return false;
  }
  return true;
}

// Largest singular value of an upper-triangular 6x6 matrix by power iteration on R^T R (only used
// to normalise the ranking score, so a few iterations suffice).
double LargestSingularValue(const Eigen::Matrix<double, 6, 6>& R) {
  Vector6d x = Vector6d::Ones().normalized();
  double sigma_squared = 0.0;
  for (int iteration = 0; iteration < 8; ++iteration) {
    const Vector6d next = R.transpose().lazyProduct(R.lazyProduct(x));
    sigma_squared = next.norm();
    if (!(sigma_squared > 0.0)) return 0.0;
    x = next / sigma_squared;
  }
  return std::sqrt(sigma_squared);
}

// The two cores C_12 and C_13 as polynomials in t = tan((theta_2 - theta_0)/2) (derivations.md
// sections 5.2-5.4).
class SexticSystem {
 public:
  SexticSystem(const Rays& x1, const Rays& x2, const Rays& x3) {
    static constexpr int kPairs[2][2] = {{0, 1}, {0, 2}};
    for (int p = 0; p < 2; ++p) {
      const int a = kPairs[p][0], b = kPairs[p][1];
      const Eigen::Vector3d w2 = x2[a].cross(x2[b]);
      const Eigen::Vector3d w3 = x3[a].cross(x3[b]);
      for (int i = 0; i < 2; ++i) {
        const TrigLinear rotated(x1[i == 0 ? a : b]);
        // f_kn(theta) = alpha cos + beta sin + gamma, (alpha, beta, gamma) = (A.w_k, B.w_k, C.w_k).
        view2_[p][i] = Eigen::Vector3d(rotated.A.dot(w2), rotated.B.dot(w2), rotated.C.dot(w2));
        view3_[p][i] = Eigen::Vector3d(rotated.A.dot(w3), rotated.B.dot(w3), rotated.C.dot(w3));
      }
    }
  }

  // row_ab(t) = F_b(t) v_3a - F_a(t) v_3b with F_n(t) = (1 + t^2) f_2n(theta_0 + 2 atan t), so that
  // C_ab = row_ab . (cos theta_3, sin theta_3, 1); coefficients of t^0, t^1, t^2.
  std::array<Eigen::Vector3d, 3> Row(int pair, const Offset& offset) const {
    std::array<std::array<double, 3>, 2> F;
    for (int i = 0; i < 2; ++i) {
      const Eigen::Vector3d& v = view2_[pair][i];
      const double alpha = v[0] * offset.c + v[1] * offset.s;
      const double beta = v[1] * offset.c - v[0] * offset.s;
      F[i] = {v[2] + alpha, 2.0 * beta, v[2] - alpha};
    }
    std::array<Eigen::Vector3d, 3> row;
    for (int d = 0; d < 3; ++d) row[d] = F[1][d] * view3_[pair][0] - F[0][d] * view3_[pair][1];
    return row;
  }

  // (cx, cy, cz)(t) = row_12(t) x row_13(t), degree 4.
  std::array<Eigen::Vector3d, 5> Cross(const Offset& offset) const {
    const std::array<Eigen::Vector3d, 3> row12 = Row(0, offset);
    const std::array<Eigen::Vector3d, 3> row13 = Row(1, offset);
    std::array<Eigen::Vector3d, 5> cross;
    cross.fill(Eigen::Vector3d::Zero());
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) cross[i + j] += row12[i].cross(row13[j]);
    }
    return cross;
  }

  // cx^2 + cy^2 - cz^2 (degree 8) divided by its exact factor 1 + t^2: the sextic of derivations.md
  // section 5.4.
  std::array<double, 7> Sextic(const Offset& offset) const {
    const std::array<Eigen::Vector3d, 5> cross = Cross(offset);
    std::array<double, 9> g{};
    for (int i = 0; i < 5; ++i) {
      for (int j = 0; j < 5; ++j) {
        g[i + j] +=
            cross[i].x() * cross[j].x() + cross[i].y() * cross[j].y() - cross[i].z() * cross[j].z();
      }
    }
    std::array<double, 7> h{};
    for (int d = 8; d >= 2; --d) {
      h[d - 2] = g[d];
      g[d - 2] -= g[d];
    }
    return h;
  }

 private:
  // [pair][point a or b]: (alpha, beta, gamma) of f_2n and f_3n.
  Eigen::Vector3d view2_[2][2], view3_[2][2];
};

int SolveSexticAligned(const Rays& x1,
                       const Rays& x2,
                       const Rays& x3,
                       std::vector<ThreeViewPose>* solutions) {
  const SexticSystem system(x1, x2, x3);
  std::array<double, 7> sextic = system.Sextic(kOffsets[0]);
  auto max_abs = [](const std::array<double, 7>& h) {
    double largest = 0.0;
    for (const double value : h) largest = std::max(largest, std::abs(value));
    return largest;
  };
  const double scale = max_abs(sextic);
  if (!(scale > 0.0) || !std::isfinite(scale)) return 0;
  const Offset* offset = &kOffsets[0];
  if (std::abs(sextic[6]) < kMinRelativeLeading * scale) {
    // The leading coefficient is the value of the sextic's trigonometric form at theta_0 + pi.
    offset = &ChooseOffset(kMinRelativeLeading, scale, [&](const Offset& theta0) {
      const std::array<double, 7> h = system.Sextic(theta0);
      return h[6] * scale / std::max(max_abs(h), 1e-300);
    });
    if (offset != &kOffsets[0]) sextic = system.Sextic(*offset);
  }

  std::array<double, 6> t;
  const int num_t = internal::SolveSexticReal(sextic, &t);

  struct Candidate {
    double score;
    ThreeViewPose pose;
  };
  std::array<Candidate, 6> candidates;
  int count = 0;
  const std::array<Eigen::Vector3d, 5> cross = system.Cross(*offset);
  for (int i = 0; i < num_t; ++i) {
    const Yaw yaw2 = YawFromCayley(t[i], *offset);
    // (cos theta_3, sin theta_3, 1) ~ row_12 x row_13 at this t.
    Eigen::Vector3d direction = cross[4];
    for (int d = 3; d >= 0; --d) direction = direction * t[i] + cross[d];
    if (!direction.allFinite() || !(direction.z() != 0.0) ||
        (direction.x() == 0.0 && direction.y() == 0.0)) {
      continue;
    }
    const double sign = direction.z() > 0.0 ? 1.0 : -1.0;
    const Yaw yaw3 = Yaw::FromDirection(sign * direction.x(), sign * direction.y());

    // Centres: null vector of the 12x6 translation system with the yaws fixed (derivations.md
    // section 3.4).
    const Eigen::Matrix3d R2 = yaw2.Matrix(), R3 = yaw3.Matrix();
    Eigen::Matrix<double, 12, 6> F;
    for (std::size_t n = 0; n < kNumTriplets; ++n) {
      F.middleRows<4>(4 * n) = internal::TranslationRows(x1[n], x2[n], x3[n], R2, R3);
    }
    if (!F.allFinite()) continue;
    const Eigen::Matrix<double, 6, 6> R_F = internal::TriangularFactor(F);
    const Vector6d centers = internal::SmallestRightSingularVectorOfTriangular<6>(R_F);
    const double sigma_max = LargestSingularValue(R_F);
    if (!(sigma_max > 0.0)) continue;
    const double score = R_F.lazyProduct(centers).norm() / sigma_max;

    Candidate& candidate = candidates[count];
    if (!internal::OrientScaleAndMakePose(x1, x2, x3, yaw2, centers.head<3>(), yaw3,
                                          centers.tail<3>(), &candidate.pose) ||
        !PointsInFront(x1, x2, candidate.pose.cam2_from_cam1) ||
        !PointsInFront(x1, x3, candidate.pose.cam3_from_cam1) || !std::isfinite(score)) {
      continue;
    }
    candidate.score = score;
    ++count;
  }
  SortByKey(
      count, [](const Candidate& c) { return c.score; }, &candidates);
  for (int i = 0; i < count; ++i) solutions->push_back(candidates[i].pose);
  return count;
}

}  // namespace

int SolveTrifocal3pt(const Rays& x1,
                     const Rays& x2,
                     const Rays& x3,
                     std::vector<ThreeViewPose>* solutions) {
  internal::CheckTriplets("SolveTrifocal3pt", kNumTriplets, kNumTriplets, x1, x2, x3, solutions);
  DecoupledSolution solution;
  SolveDecoupledAligned({x1[0], x1[1], x1[2]}, {x2[0], x2[1], x2[2]}, {x3[0], x3[1], x3[2]},
                        &solution);
  // Each candidate's poses straight from its roots (cheaper than staging them per root).
  return WriteCandidates(
      solution,
      [&solution](int camera, int index, double scale, CameraPose* pose) {
        const PairRoot& root = camera == 1 ? solution.roots2[index] : solution.roots3[index];
        pose->R = root.yaw.Matrix();
        pose->t = -scale * root.epipole;
      },
      solutions);
}

// Aligns the rays into fixed storage and maps each root back in closed form from its yaw
// (GravityFrames, derivations.md section 2.2): no heap allocation, no 3x3 products per candidate.
int SolveTrifocal3pt(const Rays& x1,
                     const Rays& x2,
                     const Rays& x3,
                     const Eigen::Vector3d& gravity_in_cam1,
                     const Eigen::Vector3d& gravity_in_cam2,
                     const Eigen::Vector3d& gravity_in_cam3,
                     std::vector<ThreeViewPose>* solutions) {
  const internal::GravityFrames frames("SolveTrifocal3pt", gravity_in_cam1, gravity_in_cam2,
                                       gravity_in_cam3);
  internal::CheckTriplets("SolveTrifocal3pt", kNumTriplets, kNumTriplets, x1, x2, x3, solutions);
  std::array<MinimalRays, 3> aligned;
  for (std::size_t n = 0; n < kNumTriplets; ++n) {
    aligned[0][n] = frames.alignment(0) * x1[n];
    aligned[1][n] = frames.alignment(1) * x2[n];
    aligned[2][n] = frames.alignment(2) * x3[n];
  }
  DecoupledSolution solution;
  SolveDecoupledAligned(aligned[0], aligned[1], aligned[2], &solution);
  // Each root mapped back once (candidates share roots; t is linear in the scale), in plain Eigen
  // storage left uninitialised.
  std::array<std::array<Eigen::Matrix3d, 4>, 2> R;
  std::array<std::array<Eigen::Vector3d, 4>, 2> t;
  for (int camera = 1; camera <= 2; ++camera) {
    const int count = camera == 1 ? solution.count2 : solution.count3;
    for (int i = 0; i < count; ++i) {
      const PairRoot& root = camera == 1 ? solution.roots2[i] : solution.roots3[i];
      const CameraPose pose = frames.UnalignYawPose(camera, root.yaw.c, root.yaw.s, -root.epipole);
      R[camera - 1][i] = pose.R;
      t[camera - 1][i] = pose.t;
    }
  }
  return WriteCandidates(
      solution,
      [&R, &t](int camera, int index, double scale, CameraPose* pose) {
        pose->R = R[camera - 1][index];
        pose->t = scale * t[camera - 1][index];
      },
      solutions);
}

int SolveTrifocal3ptSextic(const Rays& x1,
                           const Rays& x2,
                           const Rays& x3,
                           std::vector<ThreeViewPose>* solutions) {
  internal::CheckTriplets("SolveTrifocal3ptSextic", kNumTriplets, kNumTriplets, x1, x2, x3,
                          solutions);
  solutions->clear();
  if (internal::PairExplainedByYaw(x1, x2)) return 0;  // as in SolveTrifocal3pt
  return SolveSexticAligned(x1, x2, x3, solutions);
}

int SolveTrifocal3ptSextic(const Rays& x1,
                           const Rays& x2,
                           const Rays& x3,
                           const Eigen::Vector3d& gravity_in_cam1,
                           const Eigen::Vector3d& gravity_in_cam2,
                           const Eigen::Vector3d& gravity_in_cam3,
                           std::vector<ThreeViewPose>* solutions) {
  return internal::SolveWithGravity(
      "SolveTrifocal3ptSextic", x1, x2, x3, gravity_in_cam1, gravity_in_cam2, gravity_in_cam3,
      solutions,
      [](const Rays& y1, const Rays& y2, const Rays& y3, std::vector<ThreeViewPose>* out) {
        return SolveTrifocal3ptSextic(y1, y2, y3, out);
      });
}

}  // namespace trigrav
