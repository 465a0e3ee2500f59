// The pieces the trifocal solvers share (trifocal_common.h).
#include "trifocal_common.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "null_space.h"
#include "two_view_geometry.h"

namespace trigrav {
namespace internal {

bool EpipolesFromTensor(const TensorSlices& T,
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

// Pose of camera k in the aligned frames from its yaw rotation R = R_y(theta) and its centre:
// t = -R c.
CameraPose PoseFromYawAndCenter(const Eigen::Matrix3d& R, const Eigen::Vector3d& center) {
  CameraPose pose;
  pose.R = R;
  pose.t = -R * center;
  return pose;
}

}  // namespace

bool OrientScaleAndMakePose(const std::vector<Eigen::Vector3d>& x1,
                            const std::vector<Eigen::Vector3d>& x2,
                            const std::vector<Eigen::Vector3d>& x3,
                            const Yaw& yaw2,
                            Eigen::Vector3d center2,
                            const Yaw& yaw3,
                            Eigen::Vector3d center3,
                            ThreeViewPose* pose) {
  if (!yaw2.IsFinite() || !yaw3.IsFinite() || !center2.allFinite() || !center3.allFinite()) {
    return false;
  }
  const Eigen::Matrix3d R2 = yaw2.Matrix();
  const Eigen::Matrix3d R3 = yaw3.Matrix();
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
