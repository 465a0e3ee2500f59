#ifndef TRIGRAV_INITIALIZERS_SKEW_H_
#define TRIGRAV_INITIALIZERS_SKEW_H_

// The cross-product matrix [v]_x, with [v]_x w = v x w.

#include <Eigen/Core>

namespace trigrav {

inline Eigen::Matrix3d Skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return m;
}

}  // namespace trigrav

#endif  // TRIGRAV_INITIALIZERS_SKEW_H_
