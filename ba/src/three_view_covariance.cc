#include "trigrav/ba/three_view_covariance.h"

#include <ceres/crs_matrix.h>
#include <ceres/sphere_manifold.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "pseudo_inverse.h"

namespace trigrav {
namespace {

using RotationModel = ThreeViewBundleAdjustmentOptions::RotationModel;

// Largest pose dimension (kGravityPrior); matrices of the pose use fixed-size storage.
constexpr int kMaxPoseSize = 11;
using PoseMatrix =
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxPoseSize, kMaxPoseSize>;
using PoseVector = Eigen::Matrix<double, kMaxPoseSize, 1>;
using PosePointMatrix = Eigen::Matrix<double, kMaxPoseSize, 3>;

// The Gauss-Newton information J^T J of the adjuster's residuals through their losses (Ceres'
// corrector), by blocks, in Ceres' tangent coordinates of the pose blocks ordered as
// ThreeViewCovarianceLayout (rotation 2, rotation 3, C2, C3): pose-pose, per point the point-point
// block and the pose-point coupling. No point blocks when the points are constant.
struct ThreeViewInformation {
  PoseMatrix pose;
  std::vector<Eigen::Matrix3d> point;
  std::vector<PosePointMatrix> coupling;
};

// Eigenvalues below this fraction of the largest make a matrix rank-deficient.
constexpr double kMinRelativeEigenvalue = 1e-12;

// Left-perturbation rotation vector of R_a R_b^T.
Eigen::Vector3d RotationDifference(const Eigen::Matrix3d& R_a, const Eigen::Matrix3d& R_b) {
  const Eigen::AngleAxisd angle_axis(Eigen::Matrix3d(R_a * R_b.transpose()));
  return angle_axis.angle() * angle_axis.axis();
}

// d(layout coordinates) / d(Ceres tangent coordinates) of the pose blocks: 1 for a yaw, 2 I for a
// quaternion (QuaternionManifold rotates by 2 |delta|), B^T P for C2 with P the sphere's Plus
// Jacobian, I for C3.
PoseMatrix TangentToLayout(const ThreeViewCovarianceLayout& layout,
                           const Eigen::Vector3d& center2) {
  PoseMatrix T = PoseMatrix::Identity(layout.Size(), layout.Size());
  T.topLeftCorner(2 * layout.rotation_size, 2 * layout.rotation_size) *=
      layout.rotation_size == 3 ? 2.0 : 1.0;
  Eigen::Matrix<double, 3, 2, Eigen::RowMajor> plus_jacobian;
  ceres::SphereManifold<3>().PlusJacobian(center2.data(), plus_jacobian.data());
  T.block<2, 2>(layout.Center2(), layout.Center2()) =
      CenterTangentBasis(center2).transpose() * plus_jacobian;
  return T;
}

// The pose rescaled to |C2| = 1.
ThreeViewPose UnitBaseline(const ThreeViewPose& pose) {
  ThreeViewPose out = pose;
  const double scale = pose.cam2_from_cam1.Center().norm();
  out.cam2_from_cam1.t /= scale;
  out.cam3_from_cam1.t /= scale;
  return out;
}

// The information blocks from the Ceres problem's Jacobian (Problem::Evaluate through the losses);
// n is the pose's tangent size.
bool CeresInformation(ThreeViewBundleAdjuster* adjuster,
                      int n,
                      ThreeViewInformation* information,
                      std::string* message) {
  ceres::Problem* problem = adjuster->problem();
  // Jacobian columns: pose blocks in the layout's order (Ceres tangent coordinates), then the
  // points unless they are constant.
  ceres::Problem::EvaluateOptions evaluate;
  evaluate.parameter_blocks = {adjuster->RotationBlock(2), adjuster->RotationBlock(3),
                               adjuster->CenterBlock(2), adjuster->CenterBlock(3)};
  const int num_points = static_cast<int>(adjuster->points().size());
  const bool free_points =
      num_points > 0 && !problem->IsParameterBlockConstant(adjuster->PointBlock(0));
  const int num_free_points = free_points ? num_points : 0;
  for (int p = 0; p < num_free_points; ++p) {
    evaluate.parameter_blocks.push_back(adjuster->PointBlock(p));
  }
  evaluate.apply_loss_function = true;
  ceres::CRSMatrix jacobian;
  if (!problem->Evaluate(evaluate, nullptr, nullptr, nullptr, &jacobian) ||
      jacobian.num_cols != n + 3 * num_free_points) {
    *message = "covariance: the Jacobian could not be evaluated";
    return false;
  }

  // Information J^T J by blocks: pose-pose, point-point and pose-point. Each residual block
  // involves at most one point.
  information->pose = PoseMatrix::Zero(n, n);
  information->point.assign(num_free_points, Eigen::Matrix3d::Zero());
  information->coupling.assign(num_free_points, PosePointMatrix::Zero());
  for (int row = 0; row < jacobian.num_rows; ++row) {
    PoseVector pose_row = PoseVector::Zero();
    Eigen::Vector3d point_row = Eigen::Vector3d::Zero();
    int point = -1;
    for (int i = jacobian.rows[row]; i < jacobian.rows[row + 1]; ++i) {
      const int col = jacobian.cols[i];
      if (col < n) {
        pose_row[col] = jacobian.values[i];
        continue;
      }
      const int col_point = (col - n) / 3;
      if (point >= 0 && col_point != point) {
        *message = "covariance: a residual involves two points (use ceres::Covariance)";
        return false;
      }
      point = col_point;
      point_row[(col - n) % 3] = jacobian.values[i];
    }
    information->pose += pose_row.head(n) * pose_row.head(n).transpose();
    if (point >= 0) {
      information->point[point] += point_row * point_row.transpose();
      information->coupling[point] += pose_row * point_row.transpose();
    }
  }
  return true;
}

}  // namespace

ThreeViewCovarianceLayout ThreeViewCovarianceLayout::For(RotationModel model) {
  ThreeViewCovarianceLayout layout;
  layout.rotation_size = model == RotationModel::kYawOnly ? 1 : 3;
  return layout;
}

Eigen::Matrix<double, 3, 2> CenterTangentBasis(const Eigen::Vector3d& c) {
  const Eigen::Vector3d unit = c.normalized();
  int axis = 0;
  unit.cwiseAbs().minCoeff(&axis);
  const Eigen::Vector3d e1 = Eigen::Vector3d::Unit(axis).cross(unit).normalized();
  Eigen::Matrix<double, 3, 2> basis;
  basis << e1, unit.cross(e1);
  return basis;
}

Eigen::VectorXd ThreeViewPoseDifference(RotationModel model,
                                        const ThreeViewPose& pose,
                                        const ThreeViewPose& reference,
                                        const std::array<Eigen::Vector3d, 3>& gravity_in_cam) {
  const ThreeViewCovarianceLayout layout = ThreeViewCovarianceLayout::For(model);
  const ThreeViewPose a = UnitBaseline(pose);
  const ThreeViewPose b = UnitBaseline(reference);
  const CameraPose* poses_a[2] = {&a.cam2_from_cam1, &a.cam3_from_cam1};
  const CameraPose* poses_b[2] = {&b.cam2_from_cam1, &b.cam3_from_cam1};
  Eigen::VectorXd difference(layout.Size());
  for (int view = 2; view <= 3; ++view) {
    const Eigen::Vector3d omega = RotationDifference(poses_a[view - 2]->R, poses_b[view - 2]->R);
    if (model == RotationModel::kYawOnly) {
      difference[layout.Rotation(view)] = gravity_in_cam[view - 1].normalized().dot(omega);
    } else {
      difference.segment<3>(layout.Rotation(view)) = omega;
    }
  }
  const Eigen::Vector3d center2 = a.cam2_from_cam1.Center();
  difference.segment<2>(layout.Center2()) =
      CenterTangentBasis(center2).transpose() * (center2 - b.cam2_from_cam1.Center());
  difference.segment<3>(layout.Center3()) = a.cam3_from_cam1.Center() - b.cam3_from_cam1.Center();
  return difference;
}

bool ComputeThreeViewPoseCovariance(ThreeViewBundleAdjuster* adjuster,
                                    double observation_sigma,
                                    Eigen::MatrixXd* covariance,
                                    std::string* message) {
  if (adjuster == nullptr || covariance == nullptr || message == nullptr) {
    throw std::invalid_argument("trigrav: ComputeThreeViewPoseCovariance: null argument");
  }
  if (!(observation_sigma > 0.0) || !std::isfinite(observation_sigma)) {
    throw std::invalid_argument(
        "trigrav: ComputeThreeViewPoseCovariance: observation_sigma must be positive and finite");
  }
  covariance->resize(0, 0);
  message->clear();
  if (!adjuster->built()) {
    *message = "covariance: the adjuster has no problem (Build() failed or was not called)";
    return false;
  }
  const ThreeViewCovarianceLayout layout =
      ThreeViewCovarianceLayout::For(adjuster->options().rotation_model);
  const int n = layout.Size();  // also the pose blocks' tangent size in Ceres
  ThreeViewInformation information;
  if (!CeresInformation(adjuster, n, &information, message)) return false;
  PoseMatrix pose_information = information.pose;
  // Schur complement: the pose's information with the points marginalised.
  for (std::size_t p = 0; p < information.point.size(); ++p) {
    const Eigen::Matrix<double, Eigen::Dynamic, 3, 0, kMaxPoseSize, 3> c =
        information.coupling[p].topRows(n);
    pose_information -=
        c * internal::PseudoInverse(information.point[p], kMinRelativeEigenvalue) * c.transpose();
  }

  const Eigen::SelfAdjointEigenSolver<PoseMatrix> eigen(pose_information);
  const auto& values = eigen.eigenvalues();
  if (eigen.info() != Eigen::Success || !values.allFinite() ||
      !(values.minCoeff() > kMinRelativeEigenvalue * values.maxCoeff())) {
    *message = "covariance: the information matrix is rank-deficient (no covariance)";
    return false;
  }
  const PoseMatrix tangent_covariance =
      eigen.eigenvectors() * values.cwiseInverse().asDiagonal() * eigen.eigenvectors().transpose();
  const Eigen::Vector3d center2 = Eigen::Map<const Eigen::Vector3d>(adjuster->CenterBlock(2));
  const PoseMatrix T = TangentToLayout(layout, center2);
  PoseMatrix result =
      observation_sigma * observation_sigma * T * tangent_covariance * T.transpose();
  result = 0.5 * (result + result.transpose()).eval();
  if (!result.allFinite()) {
    *message = "covariance: not finite";
    return false;
  }
  *covariance = result;
  return true;
}

}  // namespace trigrav
