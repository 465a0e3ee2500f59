#include "trigrav/initializers/essential_5pt.h"

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>

#include "essential_decomposition.h"
#include "input_checks.h"
#include "polynomial.h"

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
      tables.linear_linear[i][j] =
          MonomialIndex(a[0] + b[0], a[1] + b[1], a[2] + b[2]) - kFirstQuadratic;
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

// Nister's hidden-variable form (Nister 2004, section 3.2): after Gauss-Jordan elimination of the
// monomials below, each pair (x^2 z, x^2), (y^2 z, y^2), (x y z, x y) gives <row with z> - z <row
// without z>, an equation [x, y, 1] . (b_x(z), b_y(z), b_1(z)) = 0 with degrees 3, 3, 4. The three
// form the 3 x 3 matrix B(z); det B(z) = 0 is the degree-10 polynomial in z, and (x, y, 1) spans
// the null space of B(z) at each root.
// Columns of the 10 x 20 system, eliminated monomials first (x^3, y^3, x^2y, xy^2, x^2z, x^2, y^2z,
// y^2, xyz, xy), then (xz^2, xz, x, yz^2, yz, y, z^3, z^2, z, 1), as indices into kMonomials.
constexpr std::array<int, 20> kNisterOrder = {0, 6,  1,  3, 2,  10, 7, 13, 4,  11,
                                              5, 12, 16, 8, 14, 17, 9, 15, 18, 19};

struct HiddenVariableMatrix {
  internal::Polynomial<3> bx[3], by[3];
  internal::Polynomial<4> b1[3];

  Eigen::Matrix3d Evaluate(double z) const {
    Eigen::Matrix3d B;
    for (int r = 0; r < 3; ++r) {
      B(r, 0) = internal::EvaluatePolynomial(bx[r], z);
      B(r, 1) = internal::EvaluatePolynomial(by[r], z);
      B(r, 2) = internal::EvaluatePolynomial(b1[r], z);
    }
    return B;
  }

  // det B(z), expanded along the third column.
  internal::Polynomial<10> Determinant() const {
    internal::Polynomial<10> det{};
    for (int r = 0; r < 3; ++r) {
      const int a = (r + 1) % 3, b = (r + 2) % 3;
      const internal::Polynomial<6> minor = internal::SubtractPolynomials(
          internal::MultiplyPolynomials(bx[a], by[b]), internal::MultiplyPolynomials(bx[b], by[a]));
      const internal::Polynomial<10> term = internal::MultiplyPolynomials(b1[r], minor);
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
    const bool again =
        iteration + 1 < max_iterations && step.norm() > 1e-9 * std::max(1.0, candidate.norm());
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
  const int num_roots = internal::SolveDegreeTenReal(B.Determinant(), &roots);
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
                      const std::vector<Eigen::Vector3d>& x2,
                      std::vector<CameraPose>* solutions) {
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
