// The pieces the trifocal solvers share (trifocal_common.h).
#include "trifocal_common.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <cstddef>

#include "null_space.h"
#include "trigrav/initializers/gravity.h"
#include "two_view_geometry.h"

namespace trigrav {
namespace internal {

Eigen::Matrix<double, 4, 6> TranslationRows(const Eigen::Vector3d& x1,
                                            const Eigen::Vector3d& x2,
                                            const Eigen::Vector3d& x3,
                                            const Eigen::Matrix3d& R2,
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

bool EpipolesFromTensor(const std::array<Eigen::Matrix3d, 3>& T,
                        Eigen::Vector3d* epipole2,
                        Eigen::Vector3d* epipole3) {
  Eigen::Matrix3d left_null_vectors, right_null_vectors;
  for (int i = 0; i < 3; ++i) {
    left_null_vectors.col(i) = NullVector3(T[i].transpose());
    right_null_vectors.col(i) = NullVector3(T[i]);
  }
  *epipole2 = NullVector3(left_null_vectors.transpose());
  *epipole3 = NullVector3(right_null_vectors.transpose());
  return !epipole2->isZero() && !epipole3->isZero();
}

namespace {

// d R_y(theta) / d theta from R = R_y(theta) (cos = R(0,0), sin = R(0,2)): no second sincos.
Eigen::Matrix3d RotationAboutYDerivative(const Eigen::Matrix3d& R) {
  const double c = R(0, 0), s = R(0, 2);
  Eigen::Matrix3d D;
  D << -s, 0.0, c, 0.0, 0.0, 0.0, -c, 0.0, -s;
  return D;
}

// Pose of camera k in the aligned frames from its yaw rotation R = R_y(theta) and its centre:
// t = -R c.
CameraPose PoseFromYawAndCenter(const Eigen::Matrix3d& R, const Eigen::Vector3d& center) {
  CameraPose pose;
  pose.R = R;
  pose.t = -R * center;
  return pose;
}

}  // namespace

void RefineYawsAndCenters(const std::vector<Eigen::Vector3d>& x1,
                          const std::vector<Eigen::Vector3d>& x2,
                          const std::vector<Eigen::Vector3d>& x3,
                          double* theta2,
                          double* theta3,
                          Eigen::Vector3d* center2,
                          Eigen::Vector3d* center3) {
  const Eigen::Matrix3d R2 = RotationAboutY(*theta2), dR2 = RotationAboutYDerivative(R2);
  const Eigen::Matrix3d R3 = RotationAboutY(*theta3), dR3 = RotationAboutYDerivative(R3);
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
    // z = R3 x1 x x3 (derivations.md section 3.4); u and z carry the cross-dependence on the other
    // yaw.
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
  // With the gauge row JtJ is positive definite unless the data are degenerate: Cholesky (several
  // times cheaper than pivoted LDLT at 8x8), LDLT only where Cholesky fails.
  const Eigen::LLT<Eigen::Matrix<double, 8, 8>> cholesky(JtJ);
  const Eigen::Matrix<double, 8, 1> step =
      cholesky.info() == Eigen::Success ? Eigen::Matrix<double, 8, 1>(-cholesky.solve(Jtr))
                                        : Eigen::Matrix<double, 8, 1>(-JtJ.ldlt().solve(Jtr));
  if (!step.allFinite()) return;
  *theta2 += step[0];
  *theta3 += step[1];
  centers += step.tail<6>();
  *center2 = norm * centers.head<3>();
  *center3 = norm * centers.tail<3>();
}

bool OrientScaleAndMakePose(const std::vector<Eigen::Vector3d>& x1,
                            const std::vector<Eigen::Vector3d>& x2,
                            const std::vector<Eigen::Vector3d>& x3,
                            double theta2,
                            Eigen::Vector3d center2,
                            double theta3,
                            Eigen::Vector3d center3,
                            ThreeViewPose* pose) {
  if (!std::isfinite(theta2) || !std::isfinite(theta3) || !center2.allFinite() ||
      !center3.allFinite()) {
    return false;
  }
  const Eigen::Matrix3d R2 = RotationAboutY(theta2);
  const Eigen::Matrix3d R3 = RotationAboutY(theta3);
  int votes = 0;
  for (std::size_t n = 0; n < x1.size(); ++n) {
    for (const double depth :
         {ViewOneDepth(x1[n], x2[n], R2, center2), ViewOneDepth(x1[n], x3[n], R3, center3)}) {
      votes += (depth > 0.0) - (depth < 0.0);
    }
  }
  const double scale = center2.norm();
  constexpr double kMinScale = 1e-12;
  if (!(scale > kMinScale * std::max(1.0, center3.norm()))) return false;
  const double factor = (votes < 0 ? -1.0 : 1.0) / scale;
  center2 *= factor;
  center3 *= factor;
  pose->cam2_from_cam1 = PoseFromYawAndCenter(R2, center2);
  pose->cam3_from_cam1 = PoseFromYawAndCenter(R3, center3);
  return pose->IsFinite();
}

}  // namespace internal
}  // namespace trigrav
