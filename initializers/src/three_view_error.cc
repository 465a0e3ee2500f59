#include "trigrav/initializers/three_view_error.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "observation_rays.h"

namespace trigrav {

namespace internal {

bool MidpointSums::Add(const Eigen::Vector3d& center, const Eigen::Vector3d& d) {
  const double squared = d.squaredNorm();
  if (!(squared > 0.0) || !std::isfinite(squared)) return false;  // zero, overflowing or NaN
  const Eigen::Vector3d u = d / squared;  // (I - d d^T / |d|^2) also accepts non-unit directions
  a00 += 1.0 - u[0] * d[0];
  a01 -= u[0] * d[1];
  a02 -= u[0] * d[2];
  a11 += 1.0 - u[1] * d[1];
  a12 -= u[1] * d[2];
  a22 += 1.0 - u[2] * d[2];
  b += center - u * d.dot(center);
  return true;
}

bool MidpointSums::Solve(Eigen::Vector3d* point) const {
  // By A's cofactors. Parallel rays make A rank 2 (det 0); demand a clearly invertible system (A's
  // eigenvalues lie in [0, 3]).
  const double c00 = a11 * a22 - a12 * a12;
  const double c01 = a02 * a12 - a01 * a22;
  const double c02 = a01 * a12 - a02 * a11;
  const double determinant = a00 * c00 + a01 * c01 + a02 * c02;
  if (!(std::abs(determinant) > 1e-12)) return false;
  const double c11 = a00 * a22 - a02 * a02;
  const double c12 = a01 * a02 - a00 * a12;
  const double c22 = a00 * a11 - a01 * a01;
  const Eigen::Vector3d solution =
      Eigen::Vector3d(c00 * b[0] + c01 * b[1] + c02 * b[2], c01 * b[0] + c11 * b[1] + c12 * b[2],
                      c02 * b[0] + c12 * b[1] + c22 * b[2]) /
      determinant;
  if (!solution.allFinite()) return false;
  *point = solution;
  return true;
}

}  // namespace internal

bool TriangulateMidpoint(const std::array<Eigen::Vector3d, 3>& centers_in_ref,
                         const std::array<Eigen::Vector3d, 3>& directions_in_ref,
                         Eigen::Vector3d* point_in_ref) {
  if (point_in_ref == nullptr) {
    throw std::invalid_argument("trigrav: TriangulateMidpoint: point_in_ref is null");
  }
  internal::MidpointSums sums;
  for (int k = 0; k < 3; ++k) {
    if (!sums.Add(centers_in_ref[k], directions_in_ref[k])) return false;
  }
  return sums.Solve(point_in_ref);
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
  reference_sums_.resize(size());
  reference_added_.resize(size());
  for (std::size_t n = 0; n < size(); ++n) {
    reference_added_[n] = reference_sums_[n].Add(Eigen::Vector3d::Zero(), unit_rays_[0][n]);
  }
}

namespace {

// The norm of a residual, +inf if the observation cannot see the point or the norm is not finite.
double ResidualNorm(bool seen, const Eigen::Vector2d& residual) {
  if (!seen) return std::numeric_limits<double>::infinity();
  const double error = residual.norm();
  return std::isfinite(error) ? error : std::numeric_limits<double>::infinity();
}

}  // namespace

double ThreeViewReprojectionError::PixelError(int k,
                                              std::size_t n,
                                              const Eigen::Vector3d& point_in_cam) const {
  Eigen::Vector2d residual;
  return ResidualNorm(
      PixelResidual{cameras_[k], pixels_[k][n]}(point_in_cam.data(), residual.data()), residual);
}

double ThreeViewReprojectionError::BearingError(int k,
                                                std::size_t n,
                                                const Eigen::Vector3d& point_in_cam) const {
  Eigen::Vector2d residual;
  return ResidualNorm(bearing_errors_[k][n](point_in_cam.data(), residual.data()), residual);
}

double ThreeViewReprojectionError::ObservationError(int k,
                                                    std::size_t n,
                                                    const Eigen::Vector3d& point_in_cam) const {
  return bearings_ ? BearingError(k, n, point_in_cam) : PixelError(k, n, point_in_cam);
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

template <typename ObservationErrorFn>
double ThreeViewReprojectionError::LargestError(const PreparedPose& pose,
                                                std::size_t n,
                                                double cap,
                                                const ObservationErrorFn& observation_error) const {
  constexpr double kInfinity = std::numeric_limits<double>::infinity();
  // Camera 1 is the reference (identity rotation, centre at the origin): its part of the midpoint
  // sums is the precomputed one; the rays of cameras 2 and 3 in its frame are d_k = R_k^T x_k.
  if (!reference_added_[n]) return kInfinity;
  internal::MidpointSums sums = reference_sums_[n];
  Eigen::Vector3d point;
  if (!sums.Add(pose.center_in_ref[1], pose.cam_from_ref[1].transpose() * unit_rays_[1][n]) ||
      !sums.Add(pose.center_in_ref[2], pose.cam_from_ref[2].transpose() * unit_rays_[2][n]) ||
      !sums.Solve(&point)) {
    return kInfinity;
  }
  double largest = 0.0;
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d p =
        k == 0 ? point : pose.cam_from_ref[k] * (point - pose.center_in_ref[k]);
    const double error = observation_error(k, n, p);
    if (error > cap) return error;  // the largest is beyond the cap too
    largest = std::max(largest, error);
  }
  return largest;
}

void ThreeViewReprojectionError::Errors(const PreparedPose& pose,
                                        std::size_t begin,
                                        std::size_t end,
                                        double cap,
                                        double* errors) const {
  if (!(begin <= end && end <= size())) {
    throw std::invalid_argument(
        "trigrav: ThreeViewReprojectionError::Errors: [begin, end) must lie in [0, size())");
  }
  if (errors == nullptr && begin < end) {
    throw std::invalid_argument("trigrav: ThreeViewReprojectionError::Errors: errors is null");
  }
  // The observation model is chosen once for the whole range.
  auto fill = [&](const auto& observation_error) {
    for (std::size_t n = begin; n < end; ++n) {
      errors[n - begin] = LargestError(pose, n, cap, observation_error);
    }
  };
  if (bearings_) {
    fill([this](int k, std::size_t n, const Eigen::Vector3d& p) { return BearingError(k, n, p); });
  } else {
    fill([this](int k, std::size_t n, const Eigen::Vector3d& p) { return PixelError(k, n, p); });
  }
}

double ThreeViewReprojectionError::operator()(const PreparedPose& pose, std::size_t n) const {
  double error;
  Errors(pose, n, n + 1, std::numeric_limits<double>::infinity(), &error);
  return error;
}

}  // namespace trigrav
