#include "trigrav/initializers/three_view_error.h"

#include <cmath>
#include <limits>

#include <Eigen/LU>

namespace trigrav {

bool TriangulateMidpoint(const std::array<Eigen::Vector3d, 3>& centers_in_ref,
                         const std::array<Eigen::Vector3d, 3>& directions_in_ref,
                         Eigen::Vector3d* point_in_ref) {
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  for (int k = 0; k < 3; ++k) {
    const Eigen::Matrix3d projector =
        Eigen::Matrix3d::Identity() - directions_in_ref[k] * directions_in_ref[k].transpose();
    A += projector;
    b += projector * centers_in_ref[k];
  }
  // Parallel rays make A rank 2 (det 0); demand a clearly invertible system.
  const double determinant = A.determinant();
  if (!(std::abs(determinant) > 1e-12)) return false;
  *point_in_ref = A.inverse() * b;
  return point_in_ref->allFinite();
}

ThreeViewReprojectionError::ThreeViewReprojectionError(const ThreeViewObservations& observations)
    : cameras_(observations.cameras), pixels_(observations.pixels) {
  for (int k = 0; k < 3; ++k) {
    unit_rays_[k].reserve(pixels_[k].size());
    for (const Eigen::Vector2d& pixel : pixels_[k]) {
      unit_rays_[k].push_back(cameras_[k].Ray(pixel).normalized());
    }
  }
}

ThreeViewReprojectionError::PreparedPose ThreeViewReprojectionError::Prepare(
    const ThreeViewPose& pose) {
  PreparedPose prepared;
  prepared.cam_from_ref = {Eigen::Matrix3d::Identity(), pose.cam2_from_cam1.R, pose.cam3_from_cam1.R};
  prepared.center_in_ref = {Eigen::Vector3d::Zero(), pose.cam2_from_cam1.Center(),
                            pose.cam3_from_cam1.Center()};
  return prepared;
}

double ThreeViewReprojectionError::operator()(const PreparedPose& pose, std::size_t n) const {
  constexpr double kInfinity = std::numeric_limits<double>::infinity();
  std::array<Eigen::Vector3d, 3> directions;
  for (int k = 0; k < 3; ++k) directions[k] = pose.cam_from_ref[k].transpose() * unit_rays_[k][n];
  Eigen::Vector3d point;
  if (!TriangulateMidpoint(pose.center_in_ref, directions, &point)) return kInfinity;
  double largest_squared = 0.0;
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d p = pose.cam_from_ref[k] * (point - pose.center_in_ref[k]);
    if (!(p.z() > 0.0)) return kInfinity;
    const PinholeCamera& camera = cameras_[k];
    const double du = camera.fx * p.x() / p.z() + camera.cx - pixels_[k][n].x();
    const double dv = camera.fy * p.y() / p.z() + camera.cy - pixels_[k][n].y();
    largest_squared = std::max(largest_squared, du * du + dv * dv);
  }
  const double error = std::sqrt(largest_squared);
  return std::isfinite(error) ? error : kInfinity;
}

}  // namespace trigrav
