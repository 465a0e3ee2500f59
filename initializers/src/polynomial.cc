#include "polynomial.h"

#include <algorithm>
#include <complex>
#include <limits>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>

namespace trigrav {
namespace internal {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

// Real roots of the monic quadratic y^2 + b y + c, written to roots. A discriminant that is
// negative only by rounding (relative to the size of its terms) gives the double root -b/2 once;
// complex roots with imaginary part <= max_imag give their real part -b/2 once, flagged in
// *approximate.
int SolveMonicQuadratic(double b, double c, double max_imag, double* roots, bool* approximate) {
  const double half_b = 0.5 * b;
  const double discriminant = half_b * half_b - c;
  *approximate = false;
  if (discriminant < 0.0) {
    const bool rounding = discriminant >= -64.0 * kEps * (half_b * half_b + std::abs(c));
    if (!rounding && !(-discriminant <= max_imag * max_imag)) return 0;
    roots[0] = -half_b;
    *approximate = !rounding;
    return 1;
  }
  // Stable form: the larger-magnitude root first, the other from the product c.
  const double root = -(half_b + std::copysign(std::sqrt(discriminant), half_b));
  roots[0] = root;
  roots[1] = root != 0.0 ? c / root : 0.0;
  return 2;
}

}  // namespace

double LargestRealCubicRoot(double a, double b, double c) {
  // x = z - a/3: z^3 + P z + Q = 0.
  const double shift = a / 3.0;
  const double P = b - a * shift;
  const double Q = (2.0 / 27.0) * a * a * a - b * shift + c;
  const double half_Q = 0.5 * Q;
  const double third_P = P / 3.0;
  const double discriminant = half_Q * half_Q + third_P * third_P * third_P;
  double x;
  if (discriminant > 0.0) {
    // One real root (Cardano), u^3 = -Q/2 - sign(Q) sqrt(discriminant) to avoid cancellation.
    const double u = std::cbrt(-half_Q - std::copysign(std::sqrt(discriminant), half_Q));
    x = (u != 0.0 ? u - third_P / u : 0.0) - shift;
  } else {
    // Three real roots (trigonometric form, P <= 0); the largest is 2 r cos(phi / 3).
    const double r = std::sqrt(std::max(-third_P, 0.0));
    const double cosine = r > 0.0 ? std::clamp(-half_Q / (r * r * r), -1.0, 1.0) : 0.0;
    x = 2.0 * r * std::cos(std::acos(cosine) / 3.0) - shift;
  }
  PolishRootNewton(std::array<double, 4>{c, b, a, 1.0}, 2, &x);
  return x;
}

int SolveQuarticReal(const std::array<double, 5>& c, std::array<double, 4>* roots,
                     int newton_steps, double max_imag) {
  // Monic t^4 + b t^3 + cc t^2 + d t + e, depressed by t = y - b/4: y^4 + p y^2 + q y + r.
  const double b = c[3] / c[4], cc = c[2] / c[4], d = c[1] / c[4], e = c[0] / c[4];
  const double shift = 0.25 * b;
  const double b2 = b * b;
  const double p = cc - 0.375 * b2;
  const double q = d - 0.5 * b * cc + 0.125 * b2 * b;
  const double r = e - 0.25 * b * d + 0.0625 * b2 * cc - (3.0 / 256.0) * b2 * b2;
  if (!std::isfinite(p) || !std::isfinite(q) || !std::isfinite(r)) return 0;

  // Ferrari: (y^2 + p/2 + m)^2 = 2m (y - q/(4m))^2 when m solves the resolvent cubic
  // m^3 + p m^2 + (p^2/4 - r) m - q^2/8 = 0; the largest root is the best conditioned choice.
  const double m = LargestRealCubicRoot(p, 0.25 * p * p - r, -0.125 * q * q);
  const double scale =
      std::max({std::abs(p), std::sqrt(std::abs(r)), std::cbrt(std::abs(q)), 1e-300});

  std::array<double, 4> y;
  // Real parts of near-real complex pairs are not roots: Newton could walk them onto a neighbouring
  // real root and duplicate it, so they are left as they are.
  std::array<bool, 4> approximate = {false, false, false, false};
  int count = 0;
  if (m > 64.0 * kEps * scale) {
    // y^2 -/+ s y + (p/2 + m +/- q/(2s)) = 0 with s = sqrt(2m).
    const double s = std::sqrt(2.0 * m);
    const double offset = 0.5 * q / s;
    count +=
        SolveMonicQuadratic(-s, 0.5 * p + m + offset, max_imag, &y[count], &approximate[count]);
    count += SolveMonicQuadratic(s, 0.5 * p + m - offset, max_imag, &y[count], &approximate[count]);
  } else {
    // q ~ 0: biquadratic y^4 + p y^2 + r, y^2 = z with z^2 + p z + r = 0.
    double z[2];
    bool unused;
    const int z_count = SolveMonicQuadratic(p, r, 0.0, z, &unused);
    for (int i = 0; i < z_count; ++i) {
      if (z[i] < 0.0) {
        if (z[i] < -64.0 * kEps * scale * scale) continue;
        y[count++] = 0.0;
        continue;
      }
      const double root = std::sqrt(z[i]);
      y[count++] = root;
      y[count++] = -root;
    }
  }
  for (int i = 0; i < count; ++i) {
    (*roots)[i] = y[i] - shift;
    if (!approximate[i]) PolishRootNewton(c, newton_steps, &(*roots)[i]);
  }
  return count;
}

int SolveSexticReal(const std::array<double, 7>& c, std::array<double, 6>* roots,
                    double max_relative_imag, int newton_steps) {
  // Companion matrix of the monic polynomial: ones on the subdiagonal, -c[i]/c[6] in the last
  // column.
  Eigen::Matrix<double, 6, 6> companion = Eigen::Matrix<double, 6, 6>::Zero();
  for (int i = 0; i < 5; ++i) companion(i + 1, i) = 1.0;
  for (int i = 0; i < 6; ++i) companion(i, 5) = -c[i] / c[6];
  if (!companion.allFinite()) return 0;
  const Eigen::EigenSolver<Eigen::Matrix<double, 6, 6>> solver(companion, false);
  if (solver.info() != Eigen::Success) return 0;
  int count = 0;
  for (int i = 0; i < 6; ++i) {
    const std::complex<double> eigenvalue = solver.eigenvalues()[i];
    if (std::abs(eigenvalue.imag()) > max_relative_imag * (1.0 + std::abs(eigenvalue.real()))) {
      continue;
    }
    double t = eigenvalue.real();
    PolishRootNewton(c, newton_steps, &t);
    (*roots)[count++] = t;
  }
  return count;
}

}  // namespace internal
}  // namespace trigrav
