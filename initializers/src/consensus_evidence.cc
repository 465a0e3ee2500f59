#include "consensus_evidence.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>

namespace trigrav {
namespace internal {
namespace {

constexpr double kDegPerRad = 180.0 / M_PI;

// Area and diagonal of the domain one view's observations cover, in the threshold's unit.
struct Domain {
  double area = 0.0;
  double diagonal = 0.0;
};

Domain PixelDomain(const std::vector<Eigen::Vector2d>& pixels, double threshold) {
  const PixelBox box = PixelBoundingBox(pixels);
  // No narrower than the fit regions themselves: a degenerate box would make every fit "unlikely".
  const Eigen::Vector2d size =
      (box.high - box.low).cwiseMax(Eigen::Vector2d::Constant(4.0 * threshold));
  return {size.x() * size.y(), size.norm()};
}

Domain BearingDomain(const std::vector<Eigen::Vector3d>& bearings, double threshold_deg) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& bearing : bearings) mean += bearing.normalized();
  double max_angle = M_PI;  // bearings all around: the whole sphere
  if (mean.norm() > 1e-9) {
    mean.normalize();
    max_angle = 0.0;
    for (const Eigen::Vector3d& bearing : bearings) {
      const Eigen::Vector3d unit = bearing.normalized();
      max_angle = std::max(max_angle, std::atan2(unit.cross(mean).norm(), unit.dot(mean)));
    }
  }
  max_angle = std::max(max_angle, 2.0 * threshold_deg / kDegPerRad);
  // Spherical cap of half-angle max_angle, in square degrees.
  return {2.0 * M_PI * (1.0 - std::cos(max_angle)) * kDegPerRad * kDegPerRad,
          2.0 * max_angle * kDegPerRad};
}

Eigen::Matrix3d Skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d s;
  s << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return s;
}

// Two unit vectors completing v / |v| to an orthonormal basis.
Eigen::Matrix<double, 3, 2> TangentBasis(const Eigen::Vector3d& v) {
  const Eigen::Vector3d unit = v.normalized();
  const Eigen::Vector3d helper =
      std::abs(unit.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  Eigen::Matrix<double, 3, 2> basis;
  basis.col(0) = unit.cross(helper).normalized();
  basis.col(1) = unit.cross(basis.col(0));
  return basis;
}

double LargestEigenvalue(const Eigen::Matrix3d& symmetric) {
  return Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(symmetric, Eigen::EigenvaluesOnly)
      .eigenvalues()
      .maxCoeff();
}

// kRotation parameters (1 per view: the yaw about camera 1's vertical; or 3 per view), then the two
// tangent directions of C_2 and the three of C_3.
template <int kRotation>
PosePrecision Predict(const TripletData& data,
                      const ThreeViewPose& pose,
                      const std::vector<char>& inliers,
                      const std::array<double, 3>& units_per_radian,
                      double sigma) {
  constexpr int kParams = 2 * kRotation + 5;
  using PoseJacobian = Eigen::Matrix<double, 6, kParams>;
  const std::array<Eigen::Matrix3d, 3> R = {Eigen::Matrix3d::Identity(), pose.cam2_from_cam1.R,
                                            pose.cam3_from_cam1.R};
  const std::array<Eigen::Vector3d, 3> C = {Eigen::Vector3d::Zero(), pose.cam2_from_cam1.Center(),
                                            pose.cam3_from_cam1.Center()};
  // g_1 = A_1^T e_y, the vertical in camera 1 (and reference) coordinates.
  const Eigen::Vector3d vertical = data.alignment[0].row(1).transpose();
  const Eigen::Matrix<double, 3, 2> center2_tangent = TangentBasis(C[1]);
  Eigen::Matrix<double, kParams, kParams> information =
      Eigen::Matrix<double, kParams, kParams>::Zero();
  Eigen::Matrix<double, kParams, 1> gradient = Eigen::Matrix<double, kParams, 1>::Zero();
  for (std::size_t n = 0; n < inliers.size(); ++n) {
    if (!inliers[n]) continue;
    // Midpoint triangulation (section 7.1) of the unit rays in reference coordinates.
    std::array<Eigen::Vector3d, 3> ray;
    Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();
    Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k) {
      ray[k] = data.raw[k][n].normalized();
      const Eigen::Vector3d direction = R[k].transpose() * ray[k];
      const Eigen::Matrix3d projector =
          Eigen::Matrix3d::Identity() - direction * direction.transpose();
      normal += projector;
      rhs += projector * C[k];
    }
    if (!(normal.determinant() > 1e-12)) continue;
    const Eigen::Vector3d point = normal.inverse() * rhs;
    PoseJacobian pose_jacobian = PoseJacobian::Zero();
    Eigen::Matrix<double, 6, 3> point_jacobian;
    Eigen::Matrix<double, 6, 1> residual;
    bool visible = true;
    for (int k = 0; k < 3 && visible; ++k) {
      const Eigen::Vector3d in_cam = R[k] * (point - C[k]);
      const double depth = ray[k].dot(in_cam);
      visible = depth > 0.0;
      // Tangent-plane residual B^T p / (d^T p) at p ~ d, weighted to unit variance.
      const Eigen::Matrix<double, 2, 3> residual_from_point =
          (units_per_radian[k] / (sigma * depth)) * TangentBasis(ray[k]).transpose();
      point_jacobian.middleRows<2>(2 * k) = residual_from_point * R[k];
      residual.segment<2>(2 * k) = residual_from_point * in_cam;
      if (k == 0) continue;
      // p = R_k (X - C_k) with R_k <- R_k Exp(omega): dp/domega = -R_k [X - C_k]_x.
      const Eigen::Matrix3d from_rotation = -R[k] * Skew(point - C[k]);
      if constexpr (kRotation == 1) {
        pose_jacobian.template block<2, 1>(2 * k, k - 1) =
            residual_from_point * from_rotation * vertical;
      } else {
        pose_jacobian.template block<2, 3>(2 * k, 3 * (k - 1)) =
            residual_from_point * from_rotation;
      }
      if (k == 1) {
        pose_jacobian.template block<2, 2>(2, 2 * kRotation) =
            -residual_from_point * R[1] * center2_tangent;
      } else {
        pose_jacobian.template block<2, 3>(4, 2 * kRotation + 2) = -residual_from_point * R[2];
      }
    }
    if (!visible) continue;
    // Eliminate the point: J_p^T J_p - J_p^T J_X (J_X^T J_X)^-1 J_X^T J_p.
    const Eigen::Matrix3d point_information = point_jacobian.transpose() * point_jacobian;
    const Eigen::Matrix<double, 3, kParams> cross = point_jacobian.transpose() * pose_jacobian;
    Eigen::LDLT<Eigen::Matrix3d> point_ldlt(point_information);
    if (point_ldlt.info() != Eigen::Success || !(point_information.determinant() > 0.0)) continue;
    information.noalias() += pose_jacobian.transpose() * pose_jacobian;
    information.noalias() -= cross.transpose() * point_ldlt.solve(cross);
    gradient.noalias() += pose_jacobian.transpose() * residual;
    gradient.noalias() -=
        cross.transpose() * point_ldlt.solve(point_jacobian.transpose() * residual);
  }
  PosePrecision precision;
  const Eigen::LLT<Eigen::Matrix<double, kParams, kParams>> llt(information);
  if (llt.info() != Eigen::Success) return precision;
  const Eigen::Matrix<double, kParams, kParams> covariance =
      llt.solve(Eigen::Matrix<double, kParams, kParams>::Identity());
  if (!covariance.allFinite() || !(covariance.diagonal().minCoeff() > 0.0)) return precision;
  double rotation_variance = 0.0;
  for (int view = 0; view < 2; ++view) {
    if constexpr (kRotation == 1) {
      rotation_variance = std::max(rotation_variance, covariance(view, view));
    } else {
      rotation_variance =
          std::max(rotation_variance,
                   LargestEigenvalue(covariance.template block<3, 3>(3 * view, 3 * view)));
    }
  }
  // |C_2| = 1: its tangent variance is the direction's. C_3: the part normal to C_3, over |C_3|^2.
  const Eigen::Matrix2d center2 = covariance.template block<2, 2>(2 * kRotation, 2 * kRotation);
  const double center2_variance =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(center2, Eigen::EigenvaluesOnly)
          .eigenvalues()
          .maxCoeff();
  const Eigen::Vector3d center3_unit = C[2].normalized();
  const Eigen::Matrix3d normal_part =
      Eigen::Matrix3d::Identity() - center3_unit * center3_unit.transpose();
  const double center3_variance =
      LargestEigenvalue(normal_part *
                        covariance.template block<3, 3>(2 * kRotation + 2, 2 * kRotation + 2) *
                        normal_part) /
      C[2].squaredNorm();
  // The Gauss-Newton step to the inliers' least-squares optimum: its size in degrees.
  const Eigen::Matrix<double, kParams, 1> step = -covariance * gradient;
  double step_rotation = 0.0;
  for (int view = 0; view < 2; ++view) {
    step_rotation =
        std::max(step_rotation, step.template segment<kRotation>(kRotation * view).norm());
  }
  const double step_center2 = step.template segment<2>(2 * kRotation).norm();
  const double step_center3 =
      (normal_part * step.template segment<3>(2 * kRotation + 2)).norm() / C[2].norm();
  precision.rotation_offset_deg = kDegPerRad * step_rotation;
  precision.direction_offset_deg = kDegPerRad * std::max(step_center2, step_center3);
  precision.determined = true;
  precision.rotation_sigma_deg = kDegPerRad * std::sqrt(rotation_variance);
  precision.direction_sigma_deg =
      kDegPerRad * std::sqrt(std::max(center2_variance, center3_variance));
  if (!std::isfinite(precision.direction_sigma_deg)) precision.determined = false;
  return precision;
}

}  // namespace

PixelBox PixelBoundingBox(const std::vector<Eigen::Vector2d>& pixels) {
  PixelBox box{pixels.front(), pixels.front()};
  for (const Eigen::Vector2d& pixel : pixels) {
    box.low = box.low.cwiseMin(pixel);
    box.high = box.high.cwiseMax(pixel);
  }
  return box;
}

std::array<double, 3> ThresholdUnitsPerRadian(const ThreeViewObservations& observations) {
  std::array<double, 3> units;
  for (int k = 0; k < 3; ++k) {
    units[k] = observations.HasBearings()
                   ? kDegPerRad
                   : 0.5 * (observations.cameras[k].FocalX() + observations.cameras[k].FocalY());
  }
  return units;
}

double ChanceFitProbability(const ThreeViewObservations& observations, double threshold) {
  std::array<Domain, 3> domain;
  for (int k = 0; k < 3; ++k) {
    domain[k] = observations.HasBearings() ? BearingDomain(observations.bearings[k], threshold)
                                           : PixelDomain(observations.pixels[k], threshold);
  }
  const double tolerance = 2.0 * threshold;
  auto band = [&](int k) { return 2.0 * tolerance * domain[k].diagonal / domain[k].area; };
  auto disc = [&](int k) { return M_PI * tolerance * tolerance / domain[k].area; };
  return std::min(1.0, std::max(band(1) * disc(2), band(2) * disc(1)));
}

double Log10NumberOfFalseAlarms(int n, int k, int sample_size, int max_models, double alpha) {
  // Fewer than a minimal sample fit any pose: never evidence.
  if (k < sample_size) return std::numeric_limits<double>::infinity();
  auto log10_choose = [](int a, int b) {
    return (std::lgamma(a + 1.0) - std::lgamma(b + 1.0) - std::lgamma(a - b + 1.0)) / M_LN10;
  };
  return std::log10(static_cast<double>(max_models) * std::max(1, n - sample_size)) +
         log10_choose(n, k) + log10_choose(k, sample_size) + (k - sample_size) * std::log10(alpha);
}

PosePrecision PredictPosePrecision(const TripletData& data,
                                   const ThreeViewPose& pose,
                                   const std::vector<char>& inliers,
                                   const std::array<double, 3>& units_per_radian,
                                   double sigma,
                                   bool yaw_only) {
  return yaw_only ? Predict<1>(data, pose, inliers, units_per_radian, sigma)
                  : Predict<3>(data, pose, inliers, units_per_radian, sigma);
}

}  // namespace internal
}  // namespace trigrav
