// Internal geometry of one view pair (1, k): the view-1 depth of a point from its two rays, and the
// test for a pair without parallax in gravity-aligned frames. Not installed; not part of the public
// API.
#ifndef TRIGRAV_INITIALIZERS_SRC_TWO_VIEW_GEOMETRY_H_
#define TRIGRAV_INITIALIZERS_SRC_TWO_VIEW_GEOMETRY_H_

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>
#include <cstddef>
#include <vector>

namespace trigrav {
namespace internal {

// View-1 depth of the point seen along x1 and xk, from the pair (1, k) alone, with
// xk ~ R (X - center): lambda = ((xk x R center) . (xk x R x1)) / |xk x R x1|^2 (derivations.md
// section 4.6). NaN-free: returns 0 when the rays are parallel after rotation.
inline double ViewOneDepth(const Eigen::Vector3d& x1,
                           const Eigen::Vector3d& xk,
                           const Eigen::Matrix3d& R,
                           const Eigen::Vector3d& center) {
  const Eigen::Vector3d a = xk.cross(R * x1);
  const double denominator = a.squaredNorm();
  if (!(denominator > 0.0)) return 0.0;
  return xk.cross(R * center).dot(a) / denominator;
}

// Sine of the angle below which the rays of a view pair count as parallel: baseline / depth below
// 1e-4, a twentieth of a pixel at f = 500 px.
constexpr double kMinPairParallax = 1e-4;

// True if one rotation about the y axis (gravity, in aligned frames) maps every ray x1_n onto xk_n
// to within kMinPairParallax: the pair (1,k) has no parallax (zero baseline, identical views,
// points at infinity) and the direction of camera k's centre is not determined. The yaw maximises
// sum_n xk_n . R_y(theta) x1_n (Wahba's problem about one axis, rays weighted by their lengths,
// which leaves an exact rotation exact). Cheap enough for every minimal solve: a yaw keeps the
// elevation of a ray, so a first triplet whose elevations differ settles it without the fit. Rays:
// any container of Eigen::Vector3d with size() and operator[].
template <typename Rays>
bool PairExplainedByYaw(const Rays& x1, const Rays& xk) {
  // Elevations y / |x| within kMinPairParallax of each other: a necessary condition, compared
  // squared (|a^2 - b^2| <= 2 |a - b| for |a|, |b| <= 1) with the signs, without division.
  const double y1 = x1[0].y(), yk = xk[0].y();
  const double n1 = x1[0].squaredNorm(), nk = xk[0].squaredNorm();
  constexpr double kTolerance2 = kMinPairParallax * kMinPairParallax;
  if (std::abs(y1 * y1 * nk - yk * yk * n1) > 2.0 * kMinPairParallax * n1 * nk ||
      (y1 * yk < 0.0 && (y1 * y1 > kTolerance2 * n1 || yk * yk > kTolerance2 * nk))) {
    return false;
  }
  double cosine = 0.0, sine = 0.0;
  for (std::size_t n = 0; n < x1.size(); ++n) {
    cosine += xk[n].x() * x1[n].x() + xk[n].z() * x1[n].z();
    sine += xk[n].x() * x1[n].z() - xk[n].z() * x1[n].x();
  }
  const double norm = std::sqrt(cosine * cosine + sine * sine);
  const double c = norm > 0.0 ? cosine / norm : 1.0, s = norm > 0.0 ? sine / norm : 0.0;
  for (std::size_t n = 0; n < x1.size(); ++n) {
    const Eigen::Vector3d rotated(c * x1[n].x() + s * x1[n].z(), x1[n].y(),
                                  c * x1[n].z() - s * x1[n].x());
    if (rotated.cross(xk[n]).squaredNorm() >=
        kMinPairParallax * kMinPairParallax * rotated.squaredNorm() * xk[n].squaredNorm()) {
      return false;
    }
  }
  return true;
}

}  // namespace internal
}  // namespace trigrav

#endif  // TRIGRAV_INITIALIZERS_SRC_TWO_VIEW_GEOMETRY_H_
