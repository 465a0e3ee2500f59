#include "trigrav/initializers/three_view_error.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "observation_rays.h"

namespace trigrav {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// The fields of ThreeViewReprojectionError::fields_.
enum Field {
  kA00,
  kA01,
  kA02,
  kA11,
  kA12,
  kA22,
  kB0,
  kB1,
  kB2,  // camera 1's part of the midpoint sums
  kRay2X,
  kRay2Y,
  kRay2Z,
  kRay3X,
  kRay3Y,
  kRay3Z,  // unit rays of cameras 2 and 3
  kPixel1U,
  kPixel1V,
  kPixel2U,
  kPixel2V,
  kPixel3U,
  kPixel3V,
  kNumFields
};

// R^T x and R (x - c) for a column-major R, summed in the order of the former Eigen expressions
// (R.transpose() * x, R * (x - c)), so that the errors are bit-identical to theirs.
inline void RotateTransposed(const double* R, const double* x, double* out) {
  for (int i = 0; i < 3; ++i)
    out[i] = (R[3 * i] * x[0] + R[3 * i + 1] * x[1]) + R[3 * i + 2] * x[2];
}
inline void ToCamera(const double* R, const double* c, const double* x, double* out) {
  const double w0 = x[0] - c[0], w1 = x[1] - c[1], w2 = x[2] - c[2];
  out[0] = (R[0] * w0 + R[3] * w1) + R[6] * w2;
  out[1] = (R[1] * w0 + R[4] * w1) + R[7] * w2;
  out[2] = R[2] * w0 + (R[5] * w1 + R[8] * w2);
}

// Squared residual norm of a pinhole observation (Camera::Project's arithmetic); +inf behind the
// camera or when not finite.
inline double PinholeSquaredError(const PinholeCamera& camera,
                                  const double* p,
                                  double u,
                                  double v) {
  const double du = (camera.fx * p[0] / p[2] + camera.cx) - u;
  const double dv = (camera.fy * p[1] / p[2] + camera.cy) - v;
  const double squared = du * du + dv * dv;
  return (p[2] > 0.0) & (squared <= std::numeric_limits<double>::max()) ? squared : kInfinity;
}

}  // namespace

bool TriangulateMidpoint(const std::array<Eigen::Vector3d, 3>& centers_in_ref,
                         const std::array<Eigen::Vector3d, 3>& directions_in_ref,
                         Eigen::Vector3d* point_in_ref) {
  if (point_in_ref == nullptr) {
    throw std::invalid_argument("trigrav: TriangulateMidpoint: point_in_ref is null");
  }
  internal::MidpointSums sums;
  for (int k = 0; k < 3; ++k) {
    if (!sums.Add(centers_in_ref[k].data(), directions_in_ref[k].data())) return false;
  }
  Eigen::Vector3d point;
  if (!sums.Solve(point.data())) return false;
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
  if (!bearings_ && cameras_[0].IsPinhole() && cameras_[1].IsPinhole() && cameras_[2].IsPinhole()) {
    for (const Camera& camera : cameras_) {
      const internal::CameraParamLayout layout = internal::ParamLayout(camera.model);
      pinhole_.push_back({camera.params[layout.fx], camera.params[layout.fy],
                          camera.params[layout.cx], camera.params[layout.cy]});
    }
  }
  const std::size_t n = size();
  fields_.assign(kNumFields * n, 0.0);
  auto field = [&](int f, std::size_t i) -> double& { return fields_[f * n + i]; };
  for (std::size_t i = 0; i < n; ++i) {
    internal::MidpointSums sums;
    const double origin[3] = {0.0, 0.0, 0.0};
    if (!sums.Add(origin, unit_rays_[0][i].data())) sums.a00 = std::nan("");  // Solve fails
    const double values[] = {sums.a00, sums.a01, sums.a02, sums.a11, sums.a12,
                             sums.a22, sums.b0,  sums.b1,  sums.b2};
    for (int f = kA00; f <= kB2; ++f) field(f, i) = values[f - kA00];
    for (int c = 0; c < 3; ++c) {
      field(kRay2X + c, i) = unit_rays_[1][i][c];
      field(kRay3X + c, i) = unit_rays_[2][i][c];
    }
    if (!bearings_) {
      for (int k = 0; k < 3; ++k) {
        field(kPixel1U + 2 * k, i) = pixels_[k][i].x();
        field(kPixel1V + 2 * k, i) = pixels_[k][i].y();
      }
    }
  }
}

inline double ThreeViewReprojectionError::PixelError(int k,
                                                     std::size_t n,
                                                     const Eigen::Vector3d& point_in_cam) const {
  Eigen::Vector2d residual;
  if (!PixelResidual{cameras_[k], pixels_[k][n]}(point_in_cam.data(), residual.data())) {
    return kInfinity;
  }
  const double error = residual.norm();
  return std::isfinite(error) ? error : kInfinity;
}

inline double ThreeViewReprojectionError::BearingError(int k,
                                                       std::size_t n,
                                                       const Eigen::Vector3d& point_in_cam) const {
  Eigen::Vector2d residual;
  if (!bearing_errors_[k][n](point_in_cam.data(), residual.data())) return kInfinity;
  const double error = residual.norm();
  return std::isfinite(error) ? error : kInfinity;
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
  // Camera 1 is the reference (identity rotation, centre at the origin): its part of the midpoint
  // sums is precomputed; the rays of cameras 2 and 3 in its frame are d_k = R_k^T x_k.
  internal::MidpointSums sums{Field(kA00, n), Field(kA01, n), Field(kA02, n),
                              Field(kA11, n), Field(kA12, n), Field(kA22, n),
                              Field(kB0, n),  Field(kB1, n),  Field(kB2, n)};
  double direction[3];
  for (int k = 1; k < 3; ++k) {
    RotateTransposed(pose.cam_from_ref[k].data(), unit_rays_[k][n].data(), direction);
    if (!sums.Add(pose.center_in_ref[k].data(), direction)) return kInfinity;
  }
  Eigen::Vector3d point;
  if (!sums.Solve(point.data())) return kInfinity;
  double largest = 0.0;
  for (int k = 0; k < 3; ++k) {
    Eigen::Vector3d p = point;
    if (k > 0)
      ToCamera(pose.cam_from_ref[k].data(), pose.center_in_ref[k].data(), point.data(), p.data());
    const double error = observation_error(k, n, p);
    if (error > cap) return error;  // the largest is beyond the cap too
    largest = std::max(largest, error);
  }
  return largest;
}

void ThreeViewReprojectionError::PinholeErrors(const PreparedPose& pose,
                                               std::size_t begin,
                                               std::size_t end,
                                               double* errors) const {
  // LargestError's arithmetic for pinhole cameras, without branches so that the loop vectorises
  // over triplets: the largest squared residual norm, whose square root is the largest norm.
  std::array<PinholeCamera, 3> camera = {pinhole_[0], pinhole_[1], pinhole_[2]};
  double rotation[2][9], center[2][3];
  for (int k = 0; k < 2; ++k) {
    for (int i = 0; i < 9; ++i) rotation[k][i] = pose.cam_from_ref[k + 1].data()[i];
    for (int i = 0; i < 3; ++i) center[k][i] = pose.center_in_ref[k + 1][i];
  }
  const std::size_t size = this->size();
  const double* f = fields_.data();
  // Chunks through a local buffer, which the compiler knows aliases none of the fields.
  constexpr std::size_t kChunk = 32;
  double largest_squared[kChunk];
  for (std::size_t first = begin; first < end; first += kChunk) {
    const std::size_t count = std::min(kChunk, end - first);
    for (std::size_t i = 0; i < count; ++i) {
      const std::size_t n = first + i;
      internal::MidpointSums sums{f[kA00 * size + n], f[kA01 * size + n], f[kA02 * size + n],
                                  f[kA11 * size + n], f[kA12 * size + n], f[kA22 * size + n],
                                  f[kB0 * size + n],  f[kB1 * size + n],  f[kB2 * size + n]};
      const double ray2[3] = {f[kRay2X * size + n], f[kRay2Y * size + n], f[kRay2Z * size + n]};
      const double ray3[3] = {f[kRay3X * size + n], f[kRay3Y * size + n], f[kRay3Z * size + n]};
      double direction2[3], direction3[3], point[3], point2[3], point3[3];
      RotateTransposed(rotation[0], ray2, direction2);
      RotateTransposed(rotation[1], ray3, direction3);
      bool valid = sums.Add(center[0], direction2);
      valid &= sums.Add(center[1], direction3);
      valid &= sums.Solve(point);
      ToCamera(rotation[0], center[0], point, point2);
      ToCamera(rotation[1], center[1], point, point3);
      double largest =
          PinholeSquaredError(camera[0], point, f[kPixel1U * size + n], f[kPixel1V * size + n]);
      largest = std::max(largest, PinholeSquaredError(camera[1], point2, f[kPixel2U * size + n],
                                                      f[kPixel2V * size + n]));
      largest = std::max(largest, PinholeSquaredError(camera[2], point3, f[kPixel3U * size + n],
                                                      f[kPixel3V * size + n]));
      largest_squared[i] = valid ? largest : kInfinity;
    }
    for (std::size_t i = 0; i < count; ++i)
      errors[first - begin + i] = std::sqrt(largest_squared[i]);
  }
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
  if (!pinhole_.empty()) {
    PinholeErrors(pose, begin, end, errors);
    return;
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
  Errors(pose, n, n + 1, kInfinity, &error);
  return error;
}

}  // namespace trigrav
