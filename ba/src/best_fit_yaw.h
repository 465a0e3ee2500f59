#ifndef TRIGRAV_BA_SRC_BEST_FIT_YAW_H_
#define TRIGRAV_BA_SRC_BEST_FIT_YAW_H_

// The yaw of a rotation that should be R_y(yaw) (derivations.md section 2.3), shared by the three-
// and N-view bundle adjustments to start their yaw-only parameters.

#include <Eigen/Core>
#include <cmath>

namespace trigrav {
namespace internal {

// argmin_yaw |R_y(yaw) - m|_F = atan2(m02 - m20, m00 + m22).
inline double BestFitYaw(const Eigen::Matrix3d& m) {
  return std::atan2(m(0, 2) - m(2, 0), m(0, 0) + m(2, 2));
}

}  // namespace internal
}  // namespace trigrav

#endif  // TRIGRAV_BA_SRC_BEST_FIT_YAW_H_
