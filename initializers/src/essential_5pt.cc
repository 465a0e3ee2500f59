#include "trigrav/initializers/essential_5pt.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <Eigen/Cholesky>

#include "essential_decomposition.h"
#include "solver_utils.h"

namespace trigrav {
namespace {

constexpr int kNumPoints = 5;

// Monomials in (x, y, z) of degree <= 3 as exponent triples: the 10 cubic ones first, then the 10
// of degree <= 2, the quotient-ring basis (x^2, xy, xz, y^2, yz, z^2, x, y, z, 1). The last 4 are
// the linear monomials (x, y, z, 1), the last 10 the quadratic ones: a Linear or Quadratic below
// stores its coefficients in that order.
constexpr int kMonomials[20][3] = {
    {3, 0, 0}, {2, 1, 0}, {2, 0, 1}, {1, 2, 0}, {1, 1, 1}, {1, 0, 2}, {0, 3, 0},
    {0, 2, 1}, {0, 1, 2}, {0, 0, 3}, {2, 0, 0}, {1, 1, 0}, {1, 0, 1}, {0, 2, 0},
    {0, 1, 1}, {0, 0, 2}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, 0, 0},
};
constexpr int kFirstQuadratic = 10;
constexpr int kFirstLinear = 16;

using Linear = std::array<double, 4>;
using Quadratic = std::array<double, 10>;
using Cubic = std::array<double, 20>;

constexpr int MonomialIndex(int a, int b, int c) {
  for (int i = 0; i < 20; ++i) {
    if (kMonomials[i][0] == a && kMonomials[i][1] == b && kMonomials[i][2] == c) return i;
  }
  return -1;
}

// Where the product of two monomials lands: linear x linear -> quadratic, quadratic x linear ->
// cubic.
struct ProductTables {
  int linear_linear[4][4];
  int quadratic_linear[10][4];
};

constexpr ProductTables MakeProductTables() {
  ProductTables tables{};
  for (int j = 0; j < 4; ++j) {
    const int* b = kMonomials[kFirstLinear + j];
    for (int i = 0; i < 4; ++i) {
      const int* a = kMonomials[kFirstLinear + i];
      tables.linear_linear[i][j] = MonomialIndex(a[0] + b[0], a[1] + b[1], a[2] + b[2]) -
                                   kFirstQuadratic;
    }
    for (int i = 0; i < 10; ++i) {
      const int* a = kMonomials[kFirstQuadratic + i];
      tables.quadratic_linear[i][j] = MonomialIndex(a[0] + b[0], a[1] + b[1], a[2] + b[2]);
    }
  }
  return tables;
}
constexpr ProductTables kProducts = MakeProductTables();

Quadratic Multiply(const Linear& a, const Linear& b) {
  Quadratic product{};
#pragma GCC unroll 4
  for (int i = 0; i < 4; ++i) {
#pragma GCC unroll 4
    for (int j = 0; j < 4; ++j) product[kProducts.linear_linear[i][j]] += a[i] * b[j];
  }
  return product;
}

// sum += a * b.
void AddProduct(const Quadratic& a, const Linear& b, Cubic* sum) {
#pragma GCC unroll 10
  for (int i = 0; i < 10; ++i) {
#pragma GCC unroll 4
    for (int j = 0; j < 4; ++j) (*sum)[kProducts.quadratic_linear[i][j]] += a[i] * b[j];
  }
}

Quadratic Combine(double alpha, const Quadratic& a, double beta, const Quadratic& b) {
  Quadratic result;
  for (int i = 0; i < 10; ++i) result[i] = alpha * a[i] + beta * b[i];
  return result;
}

// Orthonormal basis (columns) of the null space of the 5 x 9 epipolar system: the last 4 columns of
// Q in A^T = Q R, by 5 Householder reflections (unblocked, fixed size, no allocation). Returns
// false (basis not written) if A has (numerically) rank < 5, e.g. coincident points: then the null
// space has more than 4 dimensions and E is not determined.
bool NullSpaceBasis(const Eigen::Matrix<double, kNumPoints, 9>& A,
                    Eigen::Matrix<double, 9, 4>* basis) {
  Eigen::Matrix<double, 9, kNumPoints> M = A.transpose();
  std::array<Eigen::Matrix<double, 9, 1>, kNumPoints> reflectors;
  std::array<double, kNumPoints> betas, diagonal;
  for (int j = 0; j < kNumPoints; ++j) {
    // H_j = I - beta v v^T maps column j (rows j..8) onto a multiple of e_j.
    Eigen::Matrix<double, 9, 1> v = M.col(j);
    v.head(j).setZero();
    const double x0 = v[j];
    const double norm = v.norm();
    diagonal[j] = norm;  // |R(j, j)|
    v[j] = x0 - (x0 <= 0.0 ? norm : -norm);
    const double v_squared = v.squaredNorm();
    const double beta = v_squared > 0.0 ? 2.0 / v_squared : 0.0;
    for (int k = j + 1; k < kNumPoints; ++k) M.col(k) -= (beta * v.dot(M.col(k))) * v;
    reflectors[j] = v;
    betas[j] = beta;
  }
  // A triangular R has at least as many zero diagonal entries as its rank deficiency, and
  // R(4, 4) = 0 already when the rows are merely dependent, so any tiny |R(j, j)| flags rank < 5.
  const double largest = *std::max_element(diagonal.begin(), diagonal.end());
  for (const double d : diagonal) {
    if (!(d > 1e-10 * largest)) return false;
  }
  // Q = H_0 ... H_4, applied to e_5..e_8.
  basis->setZero();
  basis->bottomRows<4>().setIdentity();
  for (int j = kNumPoints - 1; j >= 0; --j) {
    *basis -= (betas[j] * reflectors[j]) * (reflectors[j].transpose() * *basis);
  }
  return true;
}

// The 10 x 20 coefficient matrix of det(E) = 0 (row 0) and 2 E E^T E - tr(E E^T) E = 0 (rows 1-9)
// for E = x X + y Y + z Z + W, whose entries E_ij are the columns of `basis` at row 3 i + j.
Eigen::Matrix<double, 10, 20> ConstraintMatrix(const Eigen::Matrix<double, 9, 4>& basis) {
  Linear E[3][3];
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      for (int k = 0; k < 4; ++k) E[i][j][k] = basis(3 * i + j, k);
    }
  }
  Eigen::Matrix<double, 10, 20> C;
  // det E: expansion along the first row, the cofactors of row 0 being quadratics.
  Cubic row{};
  for (int j = 0; j < 3; ++j) {
    const int a = (j + 1) % 3, b = (j + 2) % 3;
    AddProduct(Combine(1.0, Multiply(E[1][a], E[2][b]), -1.0, Multiply(E[1][b], E[2][a])), E[0][j],
               &row);
  }
  C.row(0) = Eigen::Map<const Eigen::Matrix<double, 1, 20>>(row.data());
  // Lambda = 2 E E^T - tr(E E^T) I (quadratics, symmetric); the trace constraint is Lambda E = 0.
  Quadratic EEt[3][3];
  for (int i = 0; i < 3; ++i) {
    for (int k = i; k < 3; ++k) {
      EEt[i][k] = Multiply(E[i][0], E[k][0]);
      for (int j = 1; j < 3; ++j) {
        EEt[i][k] = Combine(1.0, EEt[i][k], 1.0, Multiply(E[i][j], E[k][j]));
      }
      EEt[k][i] = EEt[i][k];
    }
  }
  const Quadratic trace = Combine(1.0, Combine(1.0, EEt[0][0], 1.0, EEt[1][1]), 1.0, EEt[2][2]);
  Quadratic Lambda[3][3];
  for (int i = 0; i < 3; ++i) {
    for (int k = 0; k < 3; ++k) {
      Lambda[i][k] = Combine(2.0, EEt[i][k], i == k ? -1.0 : 0.0, trace);
    }
  }
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      Cubic entry{};
      for (int k = 0; k < 3; ++k) AddProduct(Lambda[i][k], E[k][j], &entry);
      C.row(1 + 3 * i + j) = Eigen::Map<const Eigen::Matrix<double, 1, 20>>(entry.data());
    }
  }
  return C;
}

// Polynomials in z, coefficients lowest degree first.
template <int Degree>
using PolynomialZ = std::array<double, Degree + 1>;

template <int DegreeA, int DegreeB>
PolynomialZ<DegreeA + DegreeB> MultiplyZ(const PolynomialZ<DegreeA>& a,
                                         const PolynomialZ<DegreeB>& b) {
  PolynomialZ<DegreeA + DegreeB> product{};
  for (int i = 0; i <= DegreeA; ++i) {
    for (int j = 0; j <= DegreeB; ++j) product[i + j] += a[i] * b[j];
  }
  return product;
}

template <int Degree>
PolynomialZ<Degree> SubtractZ(const PolynomialZ<Degree>& a, const PolynomialZ<Degree>& b) {
  PolynomialZ<Degree> difference;
  for (int i = 0; i <= Degree; ++i) difference[i] = a[i] - b[i];
  return difference;
}

// Nister's hidden-variable form (Nister 2004, section 3.2): after Gauss-Jordan elimination of the
// monomials below, each pair (x^2 z, x^2), (y^2 z, y^2), (x y z, x y) gives <row with z> - z <row
// without z>, an equation [x, y, 1] . (b_x(z), b_y(z), b_1(z)) = 0 with degrees 3, 3, 4. The three
// form the 3 x 3 matrix B(z); det B(z) = 0 is the degree-10 polynomial in z, and (x, y, 1) spans
// the null space of B(z) at each root.
// Columns of the 10 x 20 system, eliminated monomials first (x^3, y^3, x^2y, xy^2, x^2z, x^2, y^2z,
// y^2, xyz, xy), then (xz^2, xz, x, yz^2, yz, y, z^3, z^2, z, 1), as indices into kMonomials.
constexpr std::array<int, 20> kNisterOrder = {0,  6,  1,  3,  2,  10, 7,  13, 4,  11,
                                              5,  12, 16, 8,  14, 17, 9,  15, 18, 19};

struct HiddenVariableMatrix {
  PolynomialZ<3> bx[3], by[3];
  PolynomialZ<4> b1[3];

  Eigen::Matrix3d Evaluate(double z) const {
    Eigen::Matrix3d B;
    for (int r = 0; r < 3; ++r) {
      B(r, 0) = ((bx[r][3] * z + bx[r][2]) * z + bx[r][1]) * z + bx[r][0];
      B(r, 1) = ((by[r][3] * z + by[r][2]) * z + by[r][1]) * z + by[r][0];
      B(r, 2) = (((b1[r][4] * z + b1[r][3]) * z + b1[r][2]) * z + b1[r][1]) * z + b1[r][0];
    }
    return B;
  }

  // det B(z), expanded along the third column.
  PolynomialZ<10> Determinant() const {
    PolynomialZ<10> det{};
    for (int r = 0; r < 3; ++r) {
      const int a = (r + 1) % 3, b = (r + 2) % 3;
      const PolynomialZ<6> minor =
          SubtractZ<6>(MultiplyZ<3, 3>(bx[a], by[b]), MultiplyZ<3, 3>(bx[b], by[a]));
      const PolynomialZ<10> term = MultiplyZ<4, 6>(b1[r], minor);
      for (int i = 0; i <= 10; ++i) det[i] += term[i];
    }
    return det;
  }
};

// Gauss-Jordan elimination with partial pivoting of the 10 x 20 system in kNisterOrder, then the
// rows of the three pairs combined into B(z). Returns false if the eliminated block is singular.
bool MakeHiddenVariableMatrix(const Eigen::Matrix<double, 10, 20>& C, HiddenVariableMatrix* B) {
  std::array<std::array<double, 20>, 10> G;
  for (int r = 0; r < 10; ++r) {
    for (int c = 0; c < 20; ++c) G[r][c] = C(r, kNisterOrder[c]);
  }
  const double tiny = 1e-14 * C.cwiseAbs().maxCoeff();
  for (int k = 0; k < 10; ++k) {
    int pivot = k;
    for (int r = k + 1; r < 10; ++r) {
      if (std::abs(G[r][k]) > std::abs(G[pivot][k])) pivot = r;
    }
    if (!(std::abs(G[pivot][k]) > tiny)) return false;
    std::swap(G[k], G[pivot]);
    const double inverse = 1.0 / G[k][k];
    for (int c = k + 1; c < 20; ++c) G[k][c] *= inverse;
    G[k][k] = 1.0;
    for (int r = 0; r < 10; ++r) {
      if (r == k) continue;
      const double factor = G[r][k];
      for (int c = k + 1; c < 20; ++c) G[r][c] -= factor * G[k][c];
      G[r][k] = 0.0;
    }
  }
  // Row k now reads: eliminated monomial k + sum_j G[k][10 + j] rest_j = 0.
  for (int pair = 0; pair < 3; ++pair) {
    const double* p = &G[4 + 2 * pair][10];  // the row of x^2 z, y^2 z or xyz
    const double* q = &G[5 + 2 * pair][10];  // the row of x^2, y^2 or xy
    B->bx[pair] = {p[2], p[1] - q[2], p[0] - q[1], -q[0]};
    B->by[pair] = {p[5], p[4] - q[5], p[3] - q[4], -q[3]};
    B->b1[pair] = {p[9], p[8] - q[9], p[7] - q[8], p[6] - q[7], -q[6]};
  }
  return true;
}

// Polynomial of degree <= 10 in a single variable, lowest degree first.
using Coefficients = std::array<double, 11>;

// Value, first and second derivative of c[0] + ... + c[degree] t^degree at t (Horner).
double EvaluateWithDerivatives(const double* c, int degree, double t, double* first,
                               double* second) {
  double value = c[degree];
  double d1 = 0.0, d2 = 0.0;
  for (int i = degree - 1; i >= 0; --i) {
    d2 = d2 * t + d1;
    d1 = d1 * t + value;
    value = value * t + c[i];
  }
  *first = d1;
  *second = 2.0 * d2;
  return value;
}

double Evaluate(const double* c, int degree, double t) {
  double value = c[degree];
  for (int i = degree - 1; i >= 0; --i) value = value * t + c[i];
  return value;
}

// The root of the polynomial (degree n) in [lo, hi], which holds exactly one root and across which
// the polynomial changes sign, by Laguerre's method safeguarded with bisection (a step leaving the
// current bracket is replaced by its midpoint). Laguerre's step
// n / (G +- sqrt((n - 1)(n H - G^2))), G = p'/p, H = G^2 - p''/p, is exact for (t - r)^n and
// converges cubically to a simple root, so it also comes in quickly from a distant start, where
// Newton crawls by factors (1 - 1/n); Newton's step is used if the square root is not real. Starts
// from the secant of the bracket (regula falsi); stops once a step is below
// tolerance * max(1, |x|).
double RootInBracket(const double* c, int degree, double lo, double hi, double value_lo,
                     double value_hi, double tolerance) {
  const bool increasing = value_lo < 0.0;
  double x = lo - value_lo * (hi - lo) / (value_hi - value_lo);
  if (!(x > lo && x < hi)) x = 0.5 * (lo + hi);
  const double n = degree;
  for (int iteration = 0; iteration < 100; ++iteration) {
    double first = 0.0, second = 0.0;
    const double value = EvaluateWithDerivatives(c, degree, x, &first, &second);
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
int SturmRoots(const Coefficients& p, int n, std::array<double, 10>* roots, bool* consistent) {
  *consistent = false;
  // The chain, every member scaled to a leading coefficient of +-1 (signs unchanged).
  std::array<Coefficients, 11> chain;
  std::array<int, 11> degree{};
  chain[0] = p;
  degree[0] = n;
  chain[1] = Coefficients{};
  for (int i = 1; i <= n; ++i) chain[1][i - 1] = i * p[i] / n;
  degree[1] = n - 1;
  int length = 2;
  while (degree[length - 1] > 0) {
    const int k = length - 1;
    Coefficients remainder = chain[k - 1];
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
    chain[length] = Coefficients{};
    for (int i = 0; i <= d; ++i) chain[length][i] = factor * remainder[i];
    degree[length] = d;
    ++length;
  }
  auto sign_changes = [&](double t) {
    int changes = 0;
    double previous = 0.0;
    for (int k = 0; k < length; ++k) {
      const double value = Evaluate(chain[k].data(), degree[k], t);
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
      const double value_a = Evaluate(p.data(), n, interval.a);
      const double value_b = Evaluate(p.data(), n, interval.b);
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
int DerivativeRoots(const Coefficients& p, int n, std::array<double, 10>* roots) {
  // derivatives[k] = p^(k), scaled to be monic (a constant factor does not move roots).
  std::array<Coefficients, 10> derivatives;
  derivatives[0] = p;
  for (int k = 1; k < n; ++k) {
    const int d = n - k;  // degree of p^(k)
    for (int i = 0; i <= d; ++i) derivatives[k][i] = (i + 1) * derivatives[k - 1][i + 1] / (d + 1);
  }
  std::array<double, 10> current;  // real roots of p^(k+1), increasing
  int count = 0;
  for (int k = n - 1; k >= 0; --k) {
    const double* q = derivatives[k].data();
    const int d = n - k;
    std::array<double, 10> next;
    int next_count = 0;
    double lo = -1.0;
    double value_lo = Evaluate(q, d, lo);
    for (int interval = 0; interval <= count; ++interval) {
      const double hi = interval < count ? current[interval] : 1.0;
      const double value_hi = Evaluate(q, d, hi);
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

// Real roots of c[0] + ... + c[10] z^10 (Nister's degree-10 polynomial). Leading coefficients below
// 1e-14 of the largest are dropped (roots beyond ~1e14^(1/k)). The polynomial is made monic and
// balanced, z = s u with s = Fujiwara's bound 2 max_i |a_(n-i)|^(1/i) (|a_0 / 2| for i = n), so all
// roots u lie in [-1, 1] and the coefficients are O(1): without the balancing the Sturm chain gave
// wrong roots in about 2 % of noise-free scenes, with it in about 0.005 %, which the consistency
// checks send to the robust but three times slower DerivativeRoots. Returns the count.
int RealRootsDegreeTen(const PolynomialZ<10>& c, std::array<double, 10>* roots) {
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
  Coefficients balanced{};  // u^n + ... with u = z / s: coefficient i is (c_i / c_n) s^(i - n)
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

// Gauss-Newton on the 10 cubic constraints C m(x, y, z) = 0 (m the 20 monomials of kMonomials):
// polishes a root read from the degree-10 polynomial, whose coefficients and the null vector of
// B(z) lose precision when roots are close. A step is kept only if it lowers the residual; iterates
// (up to max_iterations) only while the steps are above 1e-9 relative, below which one step has
// already reached the rounding level (quadratic convergence).
void PolishRoot(const Eigen::Matrix<double, 10, 20>& C, int max_iterations, Eigen::Vector3d* xyz) {
  // Residual C m(v) and, if J is not null, its Jacobian C dm/dv.
  auto evaluate = [&C](const Eigen::Vector3d& v, Eigen::Matrix<double, 10, 3>* J) {
    double power[3][4];  // powers 0..3 of each variable
    for (int a = 0; a < 3; ++a) {
      power[a][0] = 1.0;
      for (int e = 1; e < 4; ++e) power[a][e] = power[a][e - 1] * v[a];
    }
    Eigen::Matrix<double, 20, 1> m;
    for (int i = 0; i < 20; ++i) {
      const int* e = kMonomials[i];
      m[i] = power[0][e[0]] * power[1][e[1]] * power[2][e[2]];
    }
    if (J != nullptr) {
      Eigen::Matrix<double, 20, 3> dm;
      for (int i = 0; i < 20; ++i) {
        const int* e = kMonomials[i];
        dm(i, 0) = e[0] > 0 ? e[0] * power[0][e[0] - 1] * power[1][e[1]] * power[2][e[2]] : 0.0;
        dm(i, 1) = e[1] > 0 ? e[1] * power[0][e[0]] * power[1][e[1] - 1] * power[2][e[2]] : 0.0;
        dm(i, 2) = e[2] > 0 ? e[2] * power[0][e[0]] * power[1][e[1]] * power[2][e[2] - 1] : 0.0;
      }
      // lazyProduct: coefficient-wise products, not Eigen's blocked GEMM path, at this size.
      *J = C.lazyProduct(dm);
    }
    return Eigen::Matrix<double, 10, 1>(C.lazyProduct(m));
  };
  Eigen::Matrix<double, 10, 3> J;
  Eigen::Matrix<double, 10, 1> r = evaluate(*xyz, nullptr);
  // Most roots arrive accurate: skip the Jacobian when the residual is already at the rounding
  // level of C m (1e-13 relative to |C| |m|, with |m| >= 1 since m contains the monomial 1).
  const double magnitude =
      C.cwiseAbs().maxCoeff() * std::max(1.0, xyz->squaredNorm() * xyz->norm());
  if (r.cwiseAbs().maxCoeff() < 1e-13 * magnitude) return;
  r = evaluate(*xyz, &J);
  for (int iteration = 0; iteration < max_iterations; ++iteration) {
    const Eigen::Vector3d step = (J.transpose() * J).ldlt().solve(-J.transpose() * r);
    if (!step.allFinite()) return;
    const Eigen::Vector3d candidate = *xyz + step;
    const bool again = iteration + 1 < max_iterations &&
                       step.norm() > 1e-9 * std::max(1.0, candidate.norm());
    const Eigen::Matrix<double, 10, 1> r_candidate = evaluate(candidate, again ? &J : nullptr);
    if (!(r_candidate.squaredNorm() < r.squaredNorm())) return;
    *xyz = candidate;
    r = r_candidate;
    if (!again) return;
  }
}

// Minimum relative gap between two real roots z below which the hidden-variable form is retried
// with the roles of x and z swapped (see EssentialCandidates).
constexpr double kCloseRootGap = 1e-4;

// The real solutions vec(E) = x X + y Y + z Z + W (X, Y, Z, W the columns of basis) of the 10
// constraints, through Nister's degree-10 polynomial in z. Sets *close_roots if two roots z are
// within kCloseRootGap (relative) of each other: two solutions that (nearly) share z make B(z)
// nearly rank 1 there, so the roots and their (x, y) lose most of their precision. Returns the
// count.
int EssentialCandidates(const Eigen::Matrix<double, 9, 4>& basis,
                        std::array<Eigen::Matrix<double, 9, 1>, 10>* essentials,
                        bool* close_roots) {
  *close_roots = false;
  const Eigen::Matrix<double, 10, 20> C = ConstraintMatrix(basis);
  if (!C.allFinite()) return 0;
  HiddenVariableMatrix B;
  if (!MakeHiddenVariableMatrix(C, &B)) return 0;
  std::array<double, 10> roots;
  const int num_roots = RealRootsDegreeTen(B.Determinant(), &roots);
  int count = 0;
  for (int i = 0; i < num_roots; ++i) {
    const double z = roots[i];
    for (int j = 0; j < i; ++j) {
      if (std::abs(z - roots[j]) < kCloseRootGap * std::max(1.0, std::abs(z))) *close_roots = true;
    }
    // (x, y, 1) spans the null space of B(z): the largest cross product of two of its rows.
    const Eigen::Matrix3d Bz = B.Evaluate(z);
    Eigen::Vector3d v = Bz.row(0).cross(Bz.row(1));
    for (const Eigen::Vector3d& candidate : {Eigen::Vector3d(Bz.row(0).cross(Bz.row(2))),
                                            Eigen::Vector3d(Bz.row(1).cross(Bz.row(2)))}) {
      if (candidate.squaredNorm() > v.squaredNorm()) v = candidate;
    }
    if (!(std::abs(v[2]) > 1e-12 * v.norm())) continue;  // no finite (x, y) for this root
    Eigen::Vector3d xyz(v[0] / v[2], v[1] / v[2], z);
    PolishRoot(C, 3, &xyz);
    (*essentials)[count++] =
        xyz[0] * basis.col(0) + xyz[1] * basis.col(1) + xyz[2] * basis.col(2) + basis.col(3);
  }
  return count;
}

}  // namespace

int SolveEssential5pt(const std::vector<Eigen::Vector3d>& x1,
                      const std::vector<Eigen::Vector3d>& x2, std::vector<CameraPose>* solutions) {
  internal::CheckPairs("SolveEssential5pt", kNumPoints, kNumPoints, x1, x2, solutions);
  solutions->clear();

  // Epipolar rows x2^T E x1 = kron(x2, x1)^T vec(E), E vectorised row by row; rays scaled to unit
  // length so that every row has unit norm.
  Eigen::Matrix<double, kNumPoints, 9> A;
  for (int n = 0; n < kNumPoints; ++n) {
    const Eigen::Vector3d a = x1[n].normalized();
    const Eigen::Vector3d b = x2[n].normalized();
    for (int i = 0; i < 3; ++i) A.block<1, 3>(n, 3 * i) = b[i] * a.transpose();
  }
  Eigen::Matrix<double, 9, 4> basis;
  if (!NullSpaceBasis(A, &basis)) return 0;
  std::array<Eigen::Matrix<double, 9, 1>, 10> essentials;
  bool close_roots = false;
  int count = EssentialCandidates(basis, &essentials, &close_roots);
  if (close_roots) {
    // Close roots in z are mostly an accident of the basis: swap the roles of x and z and keep the
    // retry unless its roots are close too.
    Eigen::Matrix<double, 9, 4> swapped = basis;
    swapped.col(0).swap(swapped.col(2));
    std::array<Eigen::Matrix<double, 9, 1>, 10> retry;
    bool retry_close_roots = false;
    const int retry_count = EssentialCandidates(swapped, &retry, &retry_close_roots);
    if (!retry_close_roots) {
      essentials = retry;
      count = retry_count;
    }
  }
  for (int i = 0; i < count; ++i) {
    const Eigen::Matrix3d E =
        Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(essentials[i].data());
    CameraPose pose;
    if (internal::PoseFromExactEssential(E, x1, x2, &pose) == kNumPoints) {
      solutions->push_back(pose);
    }
  }
  return static_cast<int>(solutions->size());
}

}  // namespace trigrav
