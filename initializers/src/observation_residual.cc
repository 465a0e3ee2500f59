#include "trigrav/initializers/observation_residual.h"

#include <Eigen/Geometry>

namespace trigrav {

BearingResidual::BearingResidual(const Eigen::Vector3d& bearing_in_cam) {
  const Eigen::Vector3d b = bearing_in_cam.normalized();
  // e1 perpendicular to b and to the coordinate axis least aligned with it (never parallel to b).
  int axis = 0;
  b.cwiseAbs().minCoeff(&axis);
  const Eigen::Vector3d e1 = b.cross(Eigen::Vector3d::Unit(axis)).normalized();
  frame_.row(0) = e1.transpose();
  frame_.row(1) = b.cross(e1).transpose();
  frame_.row(2) = b.transpose();
}

}  // namespace trigrav
