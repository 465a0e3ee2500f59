#include "trigrav/initializers/camera_pose.h"

namespace trigrav {

Eigen::Vector3d CameraPose::Center() const { return -R.transpose() * t; }

bool CameraPose::IsFinite() const { return R.allFinite() && t.allFinite(); }

}  // namespace trigrav
