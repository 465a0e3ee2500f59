#include "solver_utils.h"

#include <sstream>
#include <stdexcept>

namespace trigrav {
namespace internal {
namespace {

void CheckRays(const char* solver, const char* name, const std::vector<Eigen::Vector3d>& rays) {
  for (std::size_t n = 0; n < rays.size(); ++n) {
    // One comparison per ray on the hot path (every solver call): NaN fails both, an infinite entry
    // or an overflowing length the second; the reason is worked out only on failure.
    if (!IsUsableDirection(rays[n])) {
      const double norm = rays[n].norm();
      std::ostringstream message;
      message << "trigrav: " << solver << ": " << name << "[" << n << "] is "
              << (!rays[n].allFinite() ? "not finite"
                  : norm > 0.0         ? "too long (its squared length overflows)"
                                       : "a zero-length ray");
      throw std::invalid_argument(message.str());
    }
  }
}

}  // namespace

void CheckTriplets(const char* solver, std::size_t min_triplets, std::size_t max_triplets,
                   const std::vector<Eigen::Vector3d>& x1, const std::vector<Eigen::Vector3d>& x2,
                   const std::vector<Eigen::Vector3d>& x3, const void* solutions) {
  // The message is built only on failure: this runs on every solver call (the RANSAC hot path).
  auto fail = [solver](const std::string& what) {
    throw std::invalid_argument(std::string("trigrav: ") + solver + ": " + what);
  };
  if (solutions == nullptr) fail("solutions is null");
  if (x1.size() != x2.size() || x1.size() != x3.size()) {
    fail("x1, x2, x3 differ in size (" + std::to_string(x1.size()) + ", " +
         std::to_string(x2.size()) + ", " + std::to_string(x3.size()) + ")");
  }
  if (x1.size() < min_triplets || x1.size() > max_triplets) {
    fail(std::string("needs ") + (min_triplets == max_triplets ? "exactly " : "at least ") +
         std::to_string(min_triplets) + " triplets, got " + std::to_string(x1.size()));
  }
  CheckRays(solver, "x1", x1);
  CheckRays(solver, "x2", x2);
  CheckRays(solver, "x3", x3);
}

void CheckPairs(const char* solver, std::size_t min_pairs, std::size_t max_pairs,
                const std::vector<Eigen::Vector3d>& x1, const std::vector<Eigen::Vector3d>& x2,
                const void* solutions) {
  // As CheckTriplets: the message is built only on failure.
  auto fail = [solver](const std::string& what) {
    throw std::invalid_argument(std::string("trigrav: ") + solver + ": " + what);
  };
  if (solutions == nullptr) fail("solutions is null");
  if (x1.size() != x2.size()) {
    fail("x1, x2 differ in size (" + std::to_string(x1.size()) + ", " + std::to_string(x2.size()) +
         ")");
  }
  if (x1.size() < min_pairs || x1.size() > max_pairs) {
    fail(std::string("needs ") + (min_pairs == max_pairs ? "exactly " : "at least ") +
         std::to_string(min_pairs) + " correspondences, got " + std::to_string(x1.size()));
  }
  CheckRays(solver, "x1", x1);
  CheckRays(solver, "x2", x2);
}

void CheckGravity(const char* solver, const char* name, const Eigen::Vector3d& gravity) {
  if (!IsUsableDirection(gravity)) {
    const double norm = gravity.norm();
    std::ostringstream message;
    message << "trigrav: " << solver << ": " << name << " is "
            << (!gravity.allFinite() ? "not finite"
                : norm > 0.0         ? "too long (its squared length overflows)"
                                     : "zero");
    throw std::invalid_argument(message.str());
  }
}

void CheckPoses(const char* solver, const char* name, const std::vector<CameraPose>& poses) {
  for (std::size_t i = 0; i < poses.size(); ++i) {
    if (!poses[i].IsFinite()) {
      throw std::invalid_argument(std::string("trigrav: ") + solver + ": " + name + "[" +
                                  std::to_string(i) + "] is not finite");
    }
  }
}

Eigen::Vector3d NullVector3(const Eigen::Matrix3d& M) {
  const double scale = M.cwiseAbs().maxCoeff();
  if (!(scale > 0.0) || !std::isfinite(scale)) return Eigen::Vector3d::Zero();
  const Eigen::Matrix3d A = M / scale;
  // adj(A) has columns r_j x r_k of the rows of A; for rank 2 every non-zero column spans the null space.
  Eigen::Matrix3d adjugate;
  adjugate.col(0) = A.row(1).cross(A.row(2)).transpose();
  adjugate.col(1) = A.row(2).cross(A.row(0)).transpose();
  adjugate.col(2) = A.row(0).cross(A.row(1)).transpose();
  Eigen::Index best = 0;
  const double largest = adjugate.colwise().squaredNorm().maxCoeff(&best);
  if (!(largest > 0.0)) return Eigen::Vector3d::Zero();
  Eigen::Vector3d x = adjugate.col(best).normalized();
  // Inverse iteration: (A^T A)^-1 is proportional to adj(A) adj(A)^T.
  // Each step shrinks the error by (sigma_3 / sigma_2)^2; stop at convergence or at the rounding floor.
  constexpr int kMaxIterations = 50;
  double previous_change = std::numeric_limits<double>::infinity();
  for (int iteration = 0; iteration < kMaxIterations; ++iteration) {
    Eigen::Vector3d next = adjugate * (adjugate.transpose() * x);
    const double norm = next.norm();
    if (!(norm > 0.0)) break;
    next /= norm;
    if (next.dot(x) < 0.0) next = -next;
    const double change = (next - x).squaredNorm();
    x = next;
    if (change < 1e-30 || (change < 1e-20 && change > 0.25 * previous_change)) break;
    previous_change = change;
  }
  return x;
}


Eigen::Matrix<double, 4, 6> TranslationRows(const Eigen::Vector3d& x1, const Eigen::Vector3d& x2,
                                            const Eigen::Vector3d& x3, const Eigen::Matrix3d& R2,
                                            const Eigen::Matrix3d& R3) {
  Eigen::Vector3d p[2], r[2];
  PerpendicularBasis(x2, &p[0], &p[1]);
  PerpendicularBasis(x3, &r[0], &r[1]);
  const Eigen::Vector3d u = x2.cross(R2 * x1);
  const Eigen::Vector3d z = (R3 * x1).cross(x3);
  Eigen::Matrix<double, 4, 6> rows;
  for (int a = 0; a < 2; ++a) {
    for (int b = 0; b < 2; ++b) {
      rows.block<1, 3>(2 * a + b, 0) = z.dot(r[b]) * (p[a].cross(x2)).transpose() * R2;
      rows.block<1, 3>(2 * a + b, 3) = p[a].dot(u) * (r[b].cross(x3)).transpose() * R3;
    }
  }
  return rows;
}

namespace {

// d R_y(theta) / d theta.
Eigen::Matrix3d RotationAboutYDerivative(double theta) {
  const double c = std::cos(theta), s = std::sin(theta);
  Eigen::Matrix3d D;
  D << -s, 0.0, c, 0.0, 0.0, 0.0, -c, 0.0, -s;
  return D;
}

}  // namespace

void RefineYawsAndCenters(const std::vector<Eigen::Vector3d>& x1,
                          const std::vector<Eigen::Vector3d>& x2,
                          const std::vector<Eigen::Vector3d>& x3, double* theta2, double* theta3,
                          Eigen::Vector3d* center2, Eigen::Vector3d* center3) {
  const Eigen::Matrix3d R2 = RotationAboutY(*theta2), dR2 = RotationAboutYDerivative(*theta2);
  const Eigen::Matrix3d R3 = RotationAboutY(*theta3), dR3 = RotationAboutYDerivative(*theta3);
  Eigen::Matrix<double, 6, 1> centers;
  centers << *center2, *center3;
  const double norm = centers.norm();
  if (!(norm > 0.0)) return;
  centers /= norm;
  const Eigen::Vector3d R2c2 = R2 * centers.head<3>(), dR2c2 = dR2 * centers.head<3>();
  const Eigen::Vector3d R3c3 = R3 * centers.tail<3>(), dR3c3 = dR3 * centers.tail<3>();
  // Normal equations of the 4N x 8 Jacobian [dr/dtheta2, dr/dtheta3, F], accumulated per triplet.
  Eigen::Matrix<double, 8, 8> JtJ = Eigen::Matrix<double, 8, 8>::Zero();
  Eigen::Matrix<double, 8, 1> Jtr = Eigen::Matrix<double, 8, 1>::Zero();
  for (std::size_t n = 0; n < x1.size(); ++n) {
    Eigen::Vector3d p[2], r[2];
    PerpendicularBasis(x2[n], &p[0], &p[1]);
    PerpendicularBasis(x3[n], &r[0], &r[1]);
    // Row (a, b): (z . r_b) (p_a x x2) . R2 c2 + (p_a . u) (r_b x x3) . R3 c3, u = x2 x R2 x1,
    // z = R3 x1 x x3 (math note 4.1); u and z carry the cross-dependence on the other yaw.
    const Eigen::Vector3d u = x2[n].cross(R2 * x1[n]), du = x2[n].cross(dR2 * x1[n]);
    const Eigen::Vector3d z = (R3 * x1[n]).cross(x3[n]), dz = (dR3 * x1[n]).cross(x3[n]);
    // Everything that depends on a alone or on b alone, then the 4 rows from products of the two.
    double left_R2c2[2], left_dR2c2[2], pu[2], pdu[2], right_R3c3[2], right_dR3c3[2], zr[2], dzr[2];
    Eigen::Vector3d left_R2[2], right_R3[2];
    for (int i = 0; i < 2; ++i) {
      const Eigen::Vector3d left = p[i].cross(x2[n]);
      const Eigen::Vector3d right = r[i].cross(x3[n]);
      left_R2c2[i] = left.dot(R2c2);
      left_dR2c2[i] = left.dot(dR2c2);
      left_R2[i] = R2.transpose() * left;
      pu[i] = p[i].dot(u);
      pdu[i] = p[i].dot(du);
      right_R3c3[i] = right.dot(R3c3);
      right_dR3c3[i] = right.dot(dR3c3);
      right_R3[i] = R3.transpose() * right;
      zr[i] = z.dot(r[i]);
      dzr[i] = dz.dot(r[i]);
    }
    for (int a = 0; a < 2; ++a) {
      for (int b = 0; b < 2; ++b) {
        Eigen::Matrix<double, 8, 1> row;
        row[0] = zr[b] * left_dR2c2[a] + pdu[a] * right_R3c3[b];
        row[1] = dzr[b] * left_R2c2[a] + pu[a] * right_dR3c3[b];
        row.segment<3>(2) = zr[b] * left_R2[a];
        row.segment<3>(5) = pu[a] * right_R3[b];
        const double residual = zr[b] * left_R2c2[a] + pu[a] * right_R3c3[b];
        JtJ.noalias() += row * row.transpose();
        Jtr += residual * row;
      }
    }
  }
  // Gauge: the step keeps c . delta_c = 0, weighted like an average row.
  Eigen::Matrix<double, 8, 1> gauge = Eigen::Matrix<double, 8, 1>::Zero();
  gauge.tail<6>() = centers;
  JtJ.noalias() += (JtJ.trace() / 8.0) * gauge * gauge.transpose();
  const Eigen::Matrix<double, 8, 1> step = -JtJ.ldlt().solve(Jtr);
  if (!step.allFinite()) return;
  *theta2 += step[0];
  *theta3 += step[1];
  centers += step.tail<6>();
  *center2 = norm * centers.head<3>();
  *center3 = norm * centers.tail<3>();
}

bool OrientScaleAndMakePose(const std::vector<Eigen::Vector3d>& x1,
                            const std::vector<Eigen::Vector3d>& x2,
                            const std::vector<Eigen::Vector3d>& x3, double theta2,
                            Eigen::Vector3d center2, double theta3, Eigen::Vector3d center3,
                            ThreeViewPose* pose) {
  if (!std::isfinite(theta2) || !std::isfinite(theta3) || !center2.allFinite() ||
      !center3.allFinite()) {
    return false;
  }
  const Eigen::Matrix3d R2 = RotationAboutY(theta2);
  const Eigen::Matrix3d R3 = RotationAboutY(theta3);
  int votes = 0;
  for (std::size_t n = 0; n < x1.size(); ++n) {
    for (const double depth : {ViewOneDepth(x1[n], x2[n], R2, center2),
                               ViewOneDepth(x1[n], x3[n], R3, center3)}) {
      votes += (depth > 0.0) - (depth < 0.0);
    }
  }
  const double scale = center2.norm();
  constexpr double kMinScale = 1e-12;
  if (!(scale > kMinScale * std::max(1.0, center3.norm()))) return false;
  const double factor = (votes < 0 ? -1.0 : 1.0) / scale;
  center2 *= factor;
  center3 *= factor;
  pose->cam2_from_cam1 = PoseFromYawAndCenter(theta2, center2);
  pose->cam3_from_cam1 = PoseFromYawAndCenter(theta3, center3);
  return pose->IsFinite();
}

}  // namespace internal
}  // namespace trigrav
