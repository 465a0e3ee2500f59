// Internal, unchecked core of GravityAlignmentFromGravity (gravity.h), inline so that the gravity
// overloads of the solvers, which check their inputs themselves, can interleave the three cameras'
// alignments. Not installed; not part of the public API.
#ifndef TRIGRAV_INITIALIZERS_SRC_GRAVITY_ALIGNMENT_H_
#define TRIGRAV_INITIALIZERS_SRC_GRAVITY_ALIGNMENT_H_

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>

namespace trigrav {
namespace internal {

// GravityAlignmentFromGravity for a finite g of length norm = |g| > 0 whose squared length does not
// overflow (IsUsableDirection). Rows of R: R g = e_y makes the middle row g^T; the first row is the
// camera axis least parallel to g (x, or z for a camera rolled by 90 deg) made orthogonal to g, the
// last completes a right-handed frame. Exact to rounding for any g, including g along -y; R = I
// when g = e_y. Written out so that the two square roots are independent: x - (x.d) d for
// d = g / |g| is (g_y^2 + g_z^2, -g_x g_y, -g_x g_z) / |g|^2, of length sqrt(g_y^2 + g_z^2) / |g|;
// for the z axis, d x (z - (z.d) d) = d x z, whose normalisation is (g_y, -g_x, 0) /
// sqrt(g_x^2 + g_y^2). Each squared length is at least half of |g|^2 by the choice of axis.
inline Eigen::Matrix3d AlignmentFromUsableGravity(const Eigen::Vector3d& gravity_in_cam,
                                                  double norm) {
  const double gx = gravity_in_cam.x(), gy = gravity_in_cam.y(), gz = gravity_in_cam.z();
  const Eigen::Vector3d down = gravity_in_cam * (1.0 / norm);
  Eigen::Vector3d first;
  if (std::abs(gx) < std::abs(gz)) {
    const double squared_length = gy * gy + gz * gz;
    const double factor = 1.0 / (norm * std::sqrt(squared_length));
    first = Eigen::Vector3d(squared_length * factor, -gx * gy * factor, -gx * gz * factor);
  } else {
    const double factor = 1.0 / std::sqrt(gx * gx + gy * gy);
    first = Eigen::Vector3d(gy * factor, -gx * factor, 0.0);
  }
  Eigen::Matrix3d R;
  R.row(0) = first.transpose();
  R.row(1) = down.transpose();
  R.row(2) = first.cross(down).transpose();
  return R;
}

}  // namespace internal
}  // namespace trigrav

#endif  // TRIGRAV_INITIALIZERS_SRC_GRAVITY_ALIGNMENT_H_
