#include "trigrav/initializers/gravity.h"

#include <Eigen/Geometry>
#include <cmath>
#include <stdexcept>
#include <string>

#include "gravity_alignment.h"
#include "input_checks.h"

namespace trigrav {

Eigen::Matrix3d RotationAboutY(double theta_rad) {
  const double c = std::cos(theta_rad);
  const double s = std::sin(theta_rad);
  Eigen::Matrix3d R;
  R << c, 0.0, s, 0.0, 1.0, 0.0, -s, 0.0, c;
  return R;
}

Eigen::Matrix3d GravityAlignmentFromGravity(const Eigen::Vector3d& gravity_in_cam) {
  if (!internal::IsUsableDirection(gravity_in_cam)) {
    throw std::invalid_argument("trigrav: gravity direction is " +
                                internal::DirectionProblem(gravity_in_cam, "zero"));
  }
  return internal::AlignmentFromUsableGravity(gravity_in_cam, gravity_in_cam.norm());
}

Eigen::Matrix3d GravityAlignmentFromPitchRoll(double pitch_rad, double roll_rad) {
  if (!std::isfinite(pitch_rad) || !std::isfinite(roll_rad)) {
    throw std::invalid_argument("trigrav: pitch or roll is not finite");
  }
  const Eigen::Matrix3d tilt = (Eigen::AngleAxisd(pitch_rad, Eigen::Vector3d::UnitX()) *
                                Eigen::AngleAxisd(roll_rad, Eigen::Vector3d::UnitZ()))
                                   .toRotationMatrix();
  return tilt.transpose();
}

Eigen::Vector3d GravityInCamera(const Eigen::Matrix3d& gravity_alignment) {
  return gravity_alignment.row(1).transpose();
}

std::vector<Eigen::Vector3d> AlignRays(const Eigen::Matrix3d& gravity_alignment,
                                       const std::vector<Eigen::Vector3d>& rays_in_cam) {
  std::vector<Eigen::Vector3d> aligned;
  aligned.reserve(rays_in_cam.size());
  for (const Eigen::Vector3d& ray : rays_in_cam) aligned.push_back(gravity_alignment * ray);
  return aligned;
}

CameraPose UnalignPose(const CameraPose& aligned_cam_from_aligned_ref,
                       const Eigen::Matrix3d& gravity_alignment_ref,
                       const Eigen::Matrix3d& gravity_alignment_cam) {
  CameraPose pose;
  pose.R =
      gravity_alignment_cam.transpose() * aligned_cam_from_aligned_ref.R * gravity_alignment_ref;
  pose.t = gravity_alignment_cam.transpose() * aligned_cam_from_aligned_ref.t;
  return pose;
}

ThreeViewPose UnalignThreeViewPose(const ThreeViewPose& aligned,
                                   const Eigen::Matrix3d& gravity_alignment1,
                                   const Eigen::Matrix3d& gravity_alignment2,
                                   const Eigen::Matrix3d& gravity_alignment3) {
  ThreeViewPose pose;
  pose.cam2_from_cam1 = UnalignPose(aligned.cam2_from_cam1, gravity_alignment1, gravity_alignment2);
  pose.cam3_from_cam1 = UnalignPose(aligned.cam3_from_cam1, gravity_alignment1, gravity_alignment3);
  return pose;
}

}  // namespace trigrav
