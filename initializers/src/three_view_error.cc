#include "trigrav/initializers/three_view_error.h"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "observation_rays.h"

namespace trigrav {

bool TriangulateMidpoint(const std::array<Eigen::Vector3d, 3>& centers_in_ref,
                         const std::array<Eigen::Vector3d, 3>& directions_in_ref,
                         Eigen::Vector3d* point_in_ref) {
  if (point_in_ref == nullptr) {
    throw std::invalid_argument("trigrav: TriangulateMidpoint: point_in_ref is null");
  }
  // A = sum_k (I - d_k d_k^T) = 3 I - sum_k d_k d_k^T for unit d_k, b = sum_k (c_k - d_k (d_k .
  // c_k)); only the 6 distinct entries of the symmetric A are accumulated.
  double a00 = 0.0, a01 = 0.0, a02 = 0.0, a11 = 0.0, a12 = 0.0, a22 = 0.0;
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d& d = directions_in_ref[k];
    const double squared = d.squaredNorm();
    if (!(squared > 0.0) || !std::isfinite(squared)) return false;  // zero, overflowing or NaN
    const Eigen::Vector3d u = d / squared;  // (I - d d^T / |d|^2) also accepts non-unit directions
    a00 += 1.0 - u[0] * d[0];
    a01 -= u[0] * d[1];
    a02 -= u[0] * d[2];
    a11 += 1.0 - u[1] * d[1];
    a12 -= u[1] * d[2];
    a22 += 1.0 - u[2] * d[2];
    b += centers_in_ref[k] - u * d.dot(centers_in_ref[k]);
  }
  Eigen::Matrix3d A;
  A << a00, a01, a02, a01, a11, a12, a02, a12, a22;
  // A is symmetric: solve by its cofactors. Parallel rays make A rank 2 (det 0); demand a clearly
  // invertible system (A's eigenvalues lie in [0, 3]).
  const double c00 = A(1, 1) * A(2, 2) - A(1, 2) * A(1, 2);
  const double c01 = A(0, 2) * A(1, 2) - A(0, 1) * A(2, 2);
  const double c02 = A(0, 1) * A(1, 2) - A(0, 2) * A(1, 1);
  const double determinant = A(0, 0) * c00 + A(0, 1) * c01 + A(0, 2) * c02;
  if (!(std::abs(determinant) > 1e-12)) return false;
  const double c11 = A(0, 0) * A(2, 2) - A(0, 2) * A(0, 2);
  const double c12 = A(0, 1) * A(0, 2) - A(0, 0) * A(1, 2);
  const double c22 = A(0, 0) * A(1, 1) - A(0, 1) * A(0, 1);
  const Eigen::Vector3d point =
      Eigen::Vector3d(c00 * b[0] + c01 * b[1] + c02 * b[2], c01 * b[0] + c11 * b[1] + c12 * b[2],
                      c02 * b[0] + c12 * b[1] + c22 * b[2]) /
      determinant;
  if (!point.allFinite()) return false;
  *point_in_ref = point;
  return true;
}

ThreeViewReprojectionError::ThreeViewReprojectionError(const ThreeViewObservations& observations)
    : bearings_(observations.HasBearings()), cameras_(observations.cameras) {
  internal::CheckAndUnproject(observations, &rays_);  // one unprojection per pixel
  for (int k = 0; k < 3; ++k) {
    if (bearings_) {
      bearing_errors_[k].reserve(rays_[k].size());
      for (const Eigen::Vector3d& ray : rays_[k]) bearing_errors_[k].emplace_back(ray);
    } else {
      pixels_[k] = observations.pixels[k];
    }
    unit_rays_[k].reserve(rays_[k].size());
    for (const Eigen::Vector3d& ray : rays_[k]) unit_rays_[k].push_back(ray.normalized());
  }
}

double ThreeViewReprojectionError::ObservationError(int k,
                                                    std::size_t n,
                                                    const Eigen::Vector3d& point_in_cam) const {
  Eigen::Vector2d residual;
  const bool seen =
      bearings_ ? bearing_errors_[k][n](point_in_cam.data(), residual.data())
                : PixelResidual{cameras_[k], pixels_[k][n]}(point_in_cam.data(), residual.data());
  if (!seen) return std::numeric_limits<double>::infinity();
  const double error = residual.norm();
  return std::isfinite(error) ? error : std::numeric_limits<double>::infinity();
}

ThreeViewReprojectionError::PreparedPose ThreeViewReprojectionError::Prepare(
    const ThreeViewPose& pose) {
  PreparedPose prepared;
  prepared.cam_from_ref = {Eigen::Matrix3d::Identity(), pose.cam2_from_cam1.R,
                           pose.cam3_from_cam1.R};
  prepared.center_in_ref = {Eigen::Vector3d::Zero(), pose.cam2_from_cam1.Center(),
                            pose.cam3_from_cam1.Center()};
  return prepared;
}

double ThreeViewReprojectionError::operator()(const PreparedPose& pose, std::size_t n) const {
  constexpr double kInfinity = std::numeric_limits<double>::infinity();
  // Camera 1 is the reference: identity rotation, centre at the origin.
  const std::array<Eigen::Vector3d, 3> directions = {
      unit_rays_[0][n], pose.cam_from_ref[1].transpose() * unit_rays_[1][n],
      pose.cam_from_ref[2].transpose() * unit_rays_[2][n]};
  Eigen::Vector3d point;
  if (!TriangulateMidpoint(pose.center_in_ref, directions, &point)) return kInfinity;
  double largest = 0.0;
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d p =
        k == 0 ? point : pose.cam_from_ref[k] * (point - pose.center_in_ref[k]);
    largest = std::max(largest, ObservationError(k, n, p));
  }
  return largest;
}

}  // namespace trigrav
