// Internal polynomial toolkit of the minimal solvers, for univariate polynomials: arithmetic,
// evaluation with derivatives (Horner), guarded Newton polishing, and real roots in closed form
// (cubic, quartic) or by Sturm sequences (sextic, degree <= 10). Not
// installed; not part of the public API. Coefficients are stored lowest degree first: c[0] + c[1] t
// + ... + c[N] t^N. Everything works on fixed-size arrays: no heap allocation.
#ifndef TRIGRAV_INITIALIZERS_SRC_POLYNOMIAL_H_
#define TRIGRAV_INITIALIZERS_SRC_POLYNOMIAL_H_

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>

namespace trigrav {
namespace internal {

// Coefficients of a polynomial of the given degree.
template <int Degree>
using Polynomial = std::array<double, Degree + 1>;

// The product a b.
template <std::size_t M, std::size_t N>
std::array<double, M + N - 1> MultiplyPolynomials(const std::array<double, M>& a,
                                                  const std::array<double, N>& b) {
  std::array<double, M + N - 1> product{};
  for (std::size_t i = 0; i < M; ++i) {
    for (std::size_t j = 0; j < N; ++j) product[i + j] += a[i] * b[j];
  }
  return product;
}

// The difference a - b.
template <std::size_t M>
std::array<double, M> SubtractPolynomials(const std::array<double, M>& a,
                                          const std::array<double, M>& b) {
  std::array<double, M> difference;
  for (std::size_t i = 0; i < M; ++i) difference[i] = a[i] - b[i];
  return difference;
}

// Value of c[0] + ... + c[degree] t^degree at t and, if D > 0, its first D derivatives at t in
// derivatives[0..D-1] (Horner's scheme, carried along for the derivatives).
template <int D = 0>
double EvaluatePolynomial(const double* c, int degree, double t, double* derivatives = nullptr) {
  std::array<double, D + 1> horner{};  // horner[k]: the k-th derivative / k!
  horner[0] = c[degree];
  for (int i = degree - 1; i >= 0; --i) {
    for (int k = D; k > 0; --k) horner[k] = horner[k] * t + horner[k - 1];
    horner[0] = horner[0] * t + c[i];
  }
  double factorial = 1.0;
  for (int k = 1; k <= D; ++k) {
    factorial *= k;
    derivatives[k - 1] = factorial * horner[k];
  }
  return horner[0];
}

// Value of the polynomial at t.
template <std::size_t M>
double EvaluatePolynomial(const std::array<double, M>& c, double t) {
  return EvaluatePolynomial(c.data(), static_cast<int>(M) - 1, t);
}

// Up to `steps` Newton steps on the polynomial from *t. A step is kept only if it lowers |p(t)|, so
// a root estimate is never made worse (flat points near double roots stay where they are), except
// that a step below 1e-10 max(1, |t|) is taken unchecked and ends the polish: the iteration is then
// converging quadratically, the next step would be below rounding, and checking would cost one more
// evaluation per root.
template <std::size_t M>
void PolishRootNewton(const std::array<double, M>& c, int steps, double* t) {
  constexpr int kDegree = static_cast<int>(M) - 1;
  constexpr double kConvergedStep = 1e-10;
  double slope = 0.0;
  double value = EvaluatePolynomial<1>(c.data(), kDegree, *t, &slope);
  for (int step = 0; step < steps && value != 0.0; ++step) {
    if (!(slope != 0.0)) break;
    const double next = *t - value / slope;
    if (std::abs(next - *t) <= kConvergedStep * std::max(1.0, std::abs(*t))) {
      *t = next;
      return;
    }
    double next_slope = 0.0;
    const double next_value = EvaluatePolynomial<1>(c.data(), kDegree, next, &next_slope);
    if (!(std::abs(next_value) < std::abs(value))) break;
    *t = next;
    value = next_value;
    slope = next_slope;
  }
}

// Largest real root of the monic cubic x^3 + a x^2 + b x + c, in closed form (Cardano when there is
// one real root, polished by two guarded Newton steps; the trigonometric form when there are three,
// with cos(acos(.)/3) from an interpolant and a Halley step, accurate to rounding without polish).
double LargestRealCubicRoot(double a, double b, double c);

// Real roots of a quartic c[0] + ... + c[4] t^4 with c[4] != 0 (the caller makes sure it is not
// tiny relative to the other coefficients), in closed form: Ferrari's method (the quartic as a
// product of two quadratics through the largest root of the resolvent cubic), then up to
// `newton_steps` guarded Newton steps per root on the quartic itself (PolishRootNewton; usually
// the first is already converged and the only one). A quadratic factor whose
// roots are complex with |Im t| <= max_imag (1 + (Re t)^2) (or only by rounding) contributes its
// real part once: for a half-angle tangent t = tan(phi/2) that bounds the imaginary part of phi by
// about 2 max_imag wherever the root lies. Returns the count (<= 4); order unspecified.
int SolveQuarticReal(const std::array<double, 5>& c,
                     std::array<double, 4>* roots,
                     int newton_steps = 6,
                     double max_imag = 0.0);

// Real roots of a sextic c[0] + ... + c[6] t^6 with c[6] not tiny relative to the other
// coefficients: SolveDegreeTenReal on the sextic (Sturm sequences). The 6x6 companion matrix's
// eigenvalues, used before, cost 1.4x the whole sextic solver and also kept near-double roots that
// rounding had made complex (imaginary part up to 1e-8 relative): noise-free, the sextic solver
// then found the truth in 96.30 % of 20,000 scenes, now in 96.29 %. Returns the count.
int SolveSexticReal(const std::array<double, 7>& c, std::array<double, 6>* roots);

// Real roots of c[0] + ... + c[10] z^10 (Nister's degree-10 polynomial of the five-point solver).
// Leading coefficients below 1e-14 of the largest are dropped (roots beyond ~1e14^(1/k)). The
// polynomial is made monic and balanced, z = s u with s = Fujiwara's bound 2 max_i |a_(n-i)|^(1/i)
// (|a_0 / 2| for i = n), so all roots u lie in [-1, 1] and the coefficients are O(1), then solved
// by Sturm sequences: without the balancing the Sturm chain gave wrong roots in about 2 % of
// noise-free scenes, with it in about 0.005 %, which the consistency checks send to the robust but
// three times slower root search through the derivatives. Returns the count.
int SolveDegreeTenReal(const Polynomial<10>& c, std::array<double, 10>* roots);

}  // namespace internal
}  // namespace trigrav

#endif  // TRIGRAV_INITIALIZERS_SRC_POLYNOMIAL_H_
