// Internal real-root finders for the small univariate polynomials of the minimal solvers. Not
// installed; not part of the public API. Coefficients are stored lowest degree first: c[0] + c[1] t
// + ... + c[N] t^N. Everything works on fixed-size arrays: no heap allocation.
#ifndef TRIGRAV_INITIALIZERS_SRC_POLYNOMIAL_H_
#define TRIGRAV_INITIALIZERS_SRC_POLYNOMIAL_H_

#include <array>
#include <cmath>
#include <cstddef>

namespace trigrav {
namespace internal {

// Value of the polynomial at t (Horner).
template <std::size_t M>
double EvaluatePolynomial(const std::array<double, M>& c, double t) {
  double value = c[M - 1];
  for (std::size_t i = M - 1; i-- > 0;) value = value * t + c[i];
  return value;
}

// Up to `steps` Newton steps on the polynomial from *t. A step is kept only if it lowers |p(t)|, so
// a root estimate is never made worse (flat points near double roots stay where they are). Returns
// |p(t)|.
template <std::size_t M>
double PolishRootNewton(const std::array<double, M>& c, int steps, double* t) {
  auto value_and_derivative = [&c](double x, double* derivative) {
    double value = c[M - 1];
    double slope = 0.0;
    for (std::size_t i = M - 1; i-- > 0;) {
      slope = slope * x + value;
      value = value * x + c[i];
    }
    *derivative = slope;
    return value;
  };
  double slope = 0.0;
  double value = value_and_derivative(*t, &slope);
  for (int step = 0; step < steps && value != 0.0; ++step) {
    if (!(slope != 0.0)) break;
    const double next = *t - value / slope;
    double next_slope = 0.0;
    const double next_value = value_and_derivative(next, &next_slope);
    if (!(std::abs(next_value) < std::abs(value))) break;
    *t = next;
    value = next_value;
    slope = next_slope;
  }
  return std::abs(value);
}

// Largest real root of the monic cubic x^3 + a x^2 + b x + c, in closed form (Cardano when there is
// one real root, the trigonometric form when there are three), polished by two guarded Newton
// steps.
double LargestRealCubicRoot(double a, double b, double c);

// Real roots of a quartic c[0] + ... + c[4] t^4 with c[4] != 0 (the caller makes sure it is not
// tiny relative to the other coefficients), in closed form: Ferrari's method (the quartic as a
// product of two quadratics through the largest root of the resolvent cubic), then up to
// `newton_steps` guarded Newton steps per root on the quartic itself (they stop once a step no
// longer lowers |q(t)|; one or two suffice except near double roots). A quadratic factor whose
// roots are complex with imaginary part at most max_imag (or only by rounding) contributes its real
// part once. Returns the count (<= 4); order unspecified.
int SolveQuarticReal(const std::array<double, 5>& c, std::array<double, 4>* roots,
                     int newton_steps = 6, double max_imag = 0.0);

// Real roots of a sextic c[0] + ... + c[6] t^6 with c[6] != 0: eigenvalues of the 6x6 companion
// matrix (Eigen::EigenSolver on a fixed-size matrix), kept when the imaginary part is below
// max_relative_imag * (1 + |re|), each then polished by guarded Newton steps. Returns the count.
int SolveSexticReal(const std::array<double, 7>& c, std::array<double, 6>* roots,
                    double max_relative_imag = 1e-8, int newton_steps = 3);

}  // namespace internal
}  // namespace trigrav

#endif  // TRIGRAV_INITIALIZERS_SRC_POLYNOMIAL_H_
