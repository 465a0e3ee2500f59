#include "trigrav/initializers/camera_pose.h"

#include <Eigen/LU>

namespace trigrav {

Eigen::Vector3d CameraPose::Center() const { return -R.transpose() * t; }

bool CameraPose::IsFinite() const { return R.allFinite() && t.allFinite(); }

bool CameraPose::HasRotation() const {
  return (R.transpose() * R - Eigen::Matrix3d::Identity()).norm() < 1e-6 && R.determinant() > 0.0;
}

CameraPose CameraPose::Inverse() const {
  CameraPose inverse;
  inverse.R = R.transpose();
  inverse.t = -(inverse.R * t);
  return inverse;
}

CameraPose operator*(const CameraPose& c_from_b, const CameraPose& b_from_a) {
  CameraPose c_from_a;
  c_from_a.R = c_from_b.R * b_from_a.R;
  c_from_a.t = c_from_b.R * b_from_a.t + c_from_b.t;
  return c_from_a;
}

}  // namespace trigrav
