// The real-root finders of the polynomial toolkit (polynomial.h).
#include "polynomial.h"

#include <algorithm>
#include <limits>

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

// p' / degree for p of the given degree (<= 10): monic if p is, a constant factor that moves no
// root.
Polynomial<10> ScaledDerivative(const Polynomial<10>& p, int degree) {
  Polynomial<10> derivative{};
  for (int i = 1; i <= degree; ++i) derivative[i - 1] = i * p[i] / degree;
  return derivative;
}

// The root of the polynomial (degree n) in [lo, hi], which holds exactly one root and across which
// the polynomial changes sign, by Laguerre's method safeguarded with bisection (a step leaving the
// current bracket is replaced by its midpoint). Laguerre's step
// n / (G +- sqrt((n - 1)(n H - G^2))), G = p'/p, H = G^2 - p''/p, is exact for (t - r)^n and
// converges cubically to a simple root, so it also comes in quickly from a distant start, where
// Newton crawls by factors (1 - 1/n); Newton's step is used if the square root is not real. Starts
// from the secant of the bracket (regula falsi); stops once a step is below
// tolerance * max(1, |x|).
double RootInBracket(const double* c,
                     int degree,
                     double lo,
                     double hi,
                     double value_lo,
                     double value_hi,
                     double tolerance) {
  const bool increasing = value_lo < 0.0;
  double x = lo - value_lo * (hi - lo) / (value_hi - value_lo);
  if (!(x > lo && x < hi)) x = 0.5 * (lo + hi);
  const double n = degree;
  for (int iteration = 0; iteration < 100; ++iteration) {
    double derivatives[2];
    const double value = EvaluatePolynomial<2>(c, degree, x, derivatives);
    const double first = derivatives[0], second = derivatives[1];
    if (value == 0.0) return x;
    if ((value < 0.0) == increasing) {
      lo = x;
    } else {
      hi = x;
    }
    const double G = first / value;
    const double H = G * G - second / value;
    const double discriminant = (n - 1.0) * (n * H - G * G);
    double next = x - value / first;
    if (discriminant >= 0.0) {
      const double root = std::sqrt(discriminant);
      const double denominator = G >= 0.0 ? G + root : G - root;
      if (denominator != 0.0) next = x - n / denominator;
    }
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    const double step = std::abs(next - x);
    x = next;
    if (step <= tolerance * std::max(1.0, std::abs(x))) break;
  }
  return x;
}

constexpr double kRootTolerance = 1e-15;

// Real roots in [-1, 1] of the monic polynomial p of degree n whose roots all lie in [-1, 1], by
// Sturm sequences as in Nister (2004): p_0 = p, p_1 = p', p_{k+1} = -(p_{k-1} mod p_k); the number
// of roots in (a, b] is the drop in sign changes along the sequence from a to b. Bisection isolates
// them, RootInBracket refines them. The remainder chain can lose precision; the result is flagged
// inconsistent (*consistent = false, to be redone by DerivativeRoots) if an isolated interval shows
// no sign change of p, a cluster cannot be separated, or the count has not the parity of n (complex
// roots come in pairs).
int SturmRoots(const Polynomial<10>& p, int n, std::array<double, 10>* roots, bool* consistent) {
  *consistent = false;
  // The chain, every member scaled to a leading coefficient of +-1 (signs unchanged).
  std::array<Polynomial<10>, 11> chain;
  std::array<int, 11> degree{};
  chain[0] = p;
  degree[0] = n;
  chain[1] = ScaledDerivative(p, n);
  degree[1] = n - 1;
  int length = 2;
  while (degree[length - 1] > 0) {
    const int k = length - 1;
    Polynomial<10> remainder = chain[k - 1];
    double scale = 0.0;
    for (int i = 0; i <= degree[k - 1]; ++i) scale = std::max(scale, std::abs(remainder[i]));
    for (int i = degree[k - 1]; i >= degree[k]; --i) {
      const double factor = remainder[i] / chain[k][degree[k]];
      for (int j = 0; j <= degree[k]; ++j) remainder[i - degree[k] + j] -= factor * chain[k][j];
      remainder[i] = 0.0;
    }
    int d = degree[k] - 1;
    while (d >= 0 && !(std::abs(remainder[d]) > 1e-14 * scale)) --d;
    if (d < 0) break;  // p and p' share a factor (a multiple root): the chain ends here
    const double factor = -1.0 / std::abs(remainder[d]);
    chain[length] = Polynomial<10>{};
    for (int i = 0; i <= d; ++i) chain[length][i] = factor * remainder[i];
    degree[length] = d;
    ++length;
  }
  auto sign_changes = [&](double t) {
    int changes = 0;
    double previous = 0.0;
    for (int k = 0; k < length; ++k) {
      const double value = EvaluatePolynomial(chain[k].data(), degree[k], t);
      if (value == 0.0) continue;
      if (previous != 0.0 && (value < 0.0) != (previous < 0.0)) ++changes;
      previous = value;
    }
    return changes;
  };

  struct Interval {
    double a, b;
    int changes_a, changes_b;
  };
  std::array<Interval, 64> stack;
  int stack_size = 0;
  stack[stack_size++] = {-1.0, 1.0, sign_changes(-1.0), sign_changes(1.0)};
  int count = 0;
  while (stack_size > 0) {
    const Interval interval = stack[--stack_size];
    const int inside = interval.changes_a - interval.changes_b;
    if (inside <= 0) continue;
    if (inside == 1) {
      const double value_a = EvaluatePolynomial(p.data(), n, interval.a);
      const double value_b = EvaluatePolynomial(p.data(), n, interval.b);
      if (value_b == 0.0) {
        (*roots)[count++] = interval.b;
      } else if ((value_a < 0.0) != (value_b < 0.0) && value_a != 0.0) {
        (*roots)[count++] =
            RootInBracket(p.data(), n, interval.a, interval.b, value_a, value_b, kRootTolerance);
      } else {
        return count;  // the chain's count disagrees with p itself
      }
    } else {
      const double middle = 0.5 * (interval.a + interval.b);
      if (interval.b - interval.a < 1e-13 || stack_size + 2 > static_cast<int>(stack.size())) {
        return count;  // a cluster bisection cannot separate
      }
      const int changes_middle = sign_changes(middle);
      stack[stack_size++] = {interval.a, middle, interval.changes_a, changes_middle};
      stack[stack_size++] = {middle, interval.b, changes_middle, interval.changes_b};
    }
    if (count == n) break;
  }
  *consistent = count % 2 == n % 2;
  return count;
}

// Real roots in [-1, 1] of the monic polynomial p of degree n whose roots all lie in [-1, 1],
// without a derived sequence (slower than SturmRoots, robust): the real roots of p^(k+1) split
// [-1, 1] into intervals on which p^(k) is monotone, so each interval holds a root of p^(k) exactly
// when p^(k) changes sign across it; from the linear p^(n-1) down to p (by Gauss-Lucas all these
// roots lie in [-1, 1] too). A double root without a sign change is missed.
int DerivativeRoots(const Polynomial<10>& p, int n, std::array<double, 10>* roots) {
  // derivatives[k] = p^(k), scaled to be monic (a constant factor does not move roots).
  std::array<Polynomial<10>, 10> derivatives;
  derivatives[0] = p;
  for (int k = 1; k < n; ++k) derivatives[k] = ScaledDerivative(derivatives[k - 1], n - k + 1);
  std::array<double, 10> current;  // real roots of p^(k+1), increasing
  int count = 0;
  for (int k = n - 1; k >= 0; --k) {
    const double* q = derivatives[k].data();
    const int d = n - k;
    std::array<double, 10> next;
    int next_count = 0;
    double lo = -1.0;
    double value_lo = EvaluatePolynomial(q, d, lo);
    for (int interval = 0; interval <= count; ++interval) {
      const double hi = interval < count ? current[interval] : 1.0;
      const double value_hi = EvaluatePolynomial(q, d, hi);
      if (value_lo == 0.0) {
        if (next_count == 0 || next[next_count - 1] != lo) next[next_count++] = lo;
      } else if ((value_lo < 0.0) != (value_hi < 0.0) && value_hi != 0.0) {
        // Roots of the derivatives only separate those of p: 1e-10 is plenty for them.
        next[next_count++] =
            RootInBracket(q, d, lo, hi, value_lo, value_hi, k == 0 ? kRootTolerance : 1e-10);
      }
      lo = hi;
      value_lo = value_hi;
    }
    if (value_lo == 0.0 && (next_count == 0 || next[next_count - 1] != lo)) next[next_count++] = lo;
    current = next;
    count = next_count;
  }
  *roots = current;
  return count;
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
  if (discriminant <= 0.0) {
    // Three real roots (P <= 0): z = 2 r k with r = sqrt(-P/3) and k the largest root of
    // 4 k^3 - 3 k = cos(phi) := -Q / (2 r^3), i.e. k = cos(phi / 3) in [1/2, 1], without
    // trigonometric calls: with u = sqrt((1 + cos(phi)) / 2) = cos(phi / 2), k = cos(2/3 acos(u)),
    // smooth on [0, 1]; a degree-4 interpolant at Chebyshev nodes (within 1.1e-5) and one Halley
    // step on 4 k^3 - 3 k - cos(phi) give it to rounding, so no Newton polish follows.
    const double r = std::sqrt(std::max(-third_P, 0.0));
    const double cosine = r > 0.0 ? std::clamp(-half_Q / (r * r * r), -1.0, 1.0) : 0.0;
    const double u = std::sqrt(0.5 + 0.5 * cosine);
    double k =
        0.5000106084908351 +
        u * (0.5768124795415822 +
             u * (-0.10649398677496211 + u * (0.038352908445762925 - u * 0.008688352074050488)));
    const double h = (4.0 * k * k - 3.0) * k - cosine, slope = 12.0 * k * k - 3.0;
    const double denominator = 2.0 * slope * slope - 24.0 * h * k;
    if (denominator > 0.0) k -= 2.0 * h * slope / denominator;
    return 2.0 * r * k - shift;
  }
  // One real root (Cardano), u^3 = -Q/2 - sign(Q) sqrt(discriminant) to avoid cancellation.
  const double u = std::cbrt(-half_Q - std::copysign(std::sqrt(discriminant), half_Q));
  double x = (u != 0.0 ? u - third_P / u : 0.0) - shift;
  PolishRootNewton(std::array<double, 4>{c, b, a, 1.0}, 2, &x);
  return x;
}

int SolveQuarticReal(const std::array<double, 5>& c,
                     std::array<double, 4>* roots,
                     int newton_steps,
                     double max_imag) {
  // Monic t^4 + b t^3 + cc t^2 + d t + e, depressed by t = y - b/4: y^4 + p y^2 + q y + r.
  const double inverse_leading = 1.0 / c[4];
  const double b = c[3] * inverse_leading, cc = c[2] * inverse_leading, d = c[1] * inverse_leading,
               e = c[0] * inverse_leading;
  const double shift = 0.25 * b;
  const double b2 = b * b;
  const double p = cc - 0.375 * b2;
  const double q = d - 0.5 * b * cc + 0.125 * b2 * b;
  const double r = e - 0.25 * b * d + 0.0625 * b2 * cc - (3.0 / 256.0) * b2 * b2;
  if (!std::isfinite(p) || !std::isfinite(q) || !std::isfinite(r)) return 0;

  // Ferrari: (y^2 + p/2 + m)^2 = 2m (y - q/(4m))^2 when m solves the resolvent cubic
  // m^3 + p m^2 + (p^2/4 - r) m - q^2/8 = 0; the largest root is the best conditioned choice.
  const double m = LargestRealCubicRoot(p, 0.25 * p * p - r, -0.125 * q * q);
  // The size of the depressed quartic's terms, max(|p|, |r|^(1/2), |q|^(1/3)), is compared with m
  // in powers (no cube root): m > tol * scale iff m > tol |p|, m^2 > tol^2 |r| and m^3 > tol^3 |q|.
  constexpr double kTolerance = 64.0 * kEps;
  const bool m_significant = m > kTolerance * std::max(std::abs(p), 1e-300) &&
                             m * m > kTolerance * kTolerance * std::abs(r) &&
                             m * m * m > kTolerance * kTolerance * kTolerance * std::abs(q);

  std::array<double, 4> y;
  // Real parts of near-real complex pairs are not roots: Newton could walk them onto a neighbouring
  // real root and duplicate it, so they are left as they are.
  std::array<bool, 4> approximate = {false, false, false, false};
  int count = 0;
  if (m_significant) {
    // y^2 -/+ s y + (p/2 + m +/- q/(2s)) = 0 with s = sqrt(2m).
    const double s = std::sqrt(2.0 * m);
    const double offset = 0.5 * q / s;
    const double real_plus = 0.5 * s - shift, real_minus = -0.5 * s - shift;
    count += SolveMonicQuadratic(-s, 0.5 * p + m + offset, max_imag * (1.0 + real_plus * real_plus),
                                 &y[count], &approximate[count]);
    count +=
        SolveMonicQuadratic(s, 0.5 * p + m - offset, max_imag * (1.0 + real_minus * real_minus),
                            &y[count], &approximate[count]);
  } else {
    // q ~ 0: biquadratic y^4 + p y^2 + r, y^2 = z with z^2 + p z + r = 0.
    const double scale =
        std::max({std::abs(p), std::sqrt(std::abs(r)), std::cbrt(std::abs(q)), 1e-300});
    double z[2];
    bool unused;
    const int z_count = SolveMonicQuadratic(p, r, 0.0, z, &unused);
    for (int i = 0; i < z_count; ++i) {
      if (z[i] < 0.0) {
        if (z[i] < -kTolerance * scale * scale) continue;
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

int SolveDegreeTenReal(const Polynomial<10>& c, std::array<double, 10>* roots) {
  double largest = 0.0;
  for (const double value : c) largest = std::max(largest, std::abs(value));
  if (!(largest > 0.0) || !std::isfinite(largest)) return 0;
  int n = 10;
  while (n > 0 && !(std::abs(c[n]) > 1e-14 * largest)) --n;
  if (n == 0) return 0;
  double bound = 0.0;
  for (int i = 1; i <= n; ++i) {
    const double a = std::abs(c[n - i] / c[n]) * (i == n ? 0.5 : 1.0);
    bound = std::max(bound, i == 1 ? a : std::pow(a, 1.0 / i));
  }
  // Slightly widened against rounding; floored so that the balancing cannot overflow.
  const double s = std::max(2.0 * bound * (1.0 + 1e-6), 1e-30);
  Polynomial<10> balanced{};  // u^n + ... with u = z / s: coefficient i is (c_i / c_n) s^(i - n)
  double factor = 1.0 / c[n];
  for (int i = n; i >= 0; --i) {
    balanced[i] = c[i] * factor;
    factor /= s;
  }
  bool consistent = false;
  int count = SturmRoots(balanced, n, roots, &consistent);
  if (!consistent) count = DerivativeRoots(balanced, n, roots);
  for (int i = 0; i < count; ++i) (*roots)[i] *= s;
  return count;
}

int SolveSexticReal(const std::array<double, 7>& c, std::array<double, 6>* roots) {
  Polynomial<10> padded{};
  std::copy(c.begin(), c.end(), padded.begin());
  std::array<double, 10> all;
  const int count = SolveDegreeTenReal(padded, &all);
  std::copy(all.begin(), all.begin() + count, roots->begin());
  return count;
}

}  // namespace internal
}  // namespace trigrav
