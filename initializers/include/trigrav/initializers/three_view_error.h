#ifndef TRIGRAV_INITIALIZERS_THREE_VIEW_ERROR_H_
#define TRIGRAV_INITIALIZERS_THREE_VIEW_ERROR_H_

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "trigrav/initializers/camera_pose.h"
#include "trigrav/initializers/observation_residual.h"
#include "trigrav/initializers/three_view_observations.h"

namespace trigrav {

// Multi-view midpoint: the point closest (least squares) to the rays from the centres c_k along the
// directions d_k (any non-zero length), all in reference (camera 1) coordinates (derivations.md
// section 7):
//   X = (sum_k (I - d_k d_k^T))^-1 sum_k (I - d_k d_k^T) c_k.
// Returns false (X untouched) if the rays are parallel (singular system), a direction is zero,
// not finite or so long that its squared length overflows, or the point is not finite. Throws
// std::invalid_argument if point_in_ref is null.
bool TriangulateMidpoint(const std::array<Eigen::Vector3d, 3>& centers_in_ref,
                         const std::array<Eigen::Vector3d, 3>& directions_in_ref,
                         Eigen::Vector3d* point_in_ref);

namespace internal {

// The midpoint system A X = b above, summed ray by ray: A = sum_k (I - d_k d_k^T) = 3 I - sum_k d_k
// d_k^T for unit d_k, b = sum_k (c_k - d_k (d_k . c_k)); only the 6 distinct entries of the
// symmetric A are kept. Branch-free, so that a loop over many triplets vectorises.
struct MidpointSums {
  double a00 = 0.0, a01 = 0.0, a02 = 0.0, a11 = 0.0, a12 = 0.0, a22 = 0.0;
  double b0 = 0.0, b1 = 0.0, b2 = 0.0;

  // Adds the ray from c along d (any non-zero length). False if d is zero, not finite or so long
  // that its squared length overflows; the sums are then meaningless. A NaN sum makes Solve fail.
  bool Add(const double* c, const double* d);
  // X = A^-1 b by A's cofactors. False unless A is clearly invertible (parallel rays make it rank
  // 2; its eigenvalues lie in [0, 3]) and X finite; X is then meaningless.
  bool Solve(double* x) const;
};

inline bool MidpointSums::Add(const double* c, const double* d) {
  // Sums in the order of the former Eigen expressions (d.squaredNorm(), d.dot(c)): bit-identical.
  const double squared = (d[0] * d[0] + d[1] * d[1]) + d[2] * d[2];
  // (I - d d^T / |d|^2) also accepts non-unit directions.
  const double u0 = d[0] / squared, u1 = d[1] / squared, u2 = d[2] / squared;
  a00 += 1.0 - u0 * d[0];
  a01 -= u0 * d[1];
  a02 -= u0 * d[2];
  a11 += 1.0 - u1 * d[1];
  a12 -= u1 * d[2];
  a22 += 1.0 - u2 * d[2];
  const double along = (d[0] * c[0] + d[1] * c[1]) + d[2] * c[2];
  b0 += c[0] - u0 * along;
  b1 += c[1] - u1 * along;
  b2 += c[2] - u2 * along;
  // Zero, overflowing or NaN fail (NaN compares false).
  return (squared > 0.0) & (squared <= std::numeric_limits<double>::max());
}

inline bool MidpointSums::Solve(double* x) const {
  const double c00 = a11 * a22 - a12 * a12;
  const double c01 = a02 * a12 - a01 * a22;
  const double c02 = a01 * a12 - a02 * a11;
  const double determinant = a00 * c00 + a01 * c01 + a02 * c02;
  const double c11 = a00 * a22 - a02 * a02;
  const double c12 = a01 * a02 - a00 * a12;
  const double c22 = a00 * a11 - a01 * a01;
  x[0] = (c00 * b0 + c01 * b1 + c02 * b2) / determinant;
  x[1] = (c01 * b0 + c11 * b1 + c12 * b2) / determinant;
  x[2] = (c02 * b0 + c12 * b1 + c22 * b2) / determinant;
  constexpr double kLargest = std::numeric_limits<double>::max();
  return (std::abs(determinant) > 1e-12) & (std::abs(x[0]) <= kLargest) &
         (std::abs(x[1]) <= kLargest) & (std::abs(x[2]) <= kLargest);
}

}  // namespace internal

// The inlier error every trigrav robust estimator uses, whatever the method (derivations.md section
// 7): triangulate the triplet by the multi-view midpoint in the original (unaligned) frames,
// reproject into all three views and take the largest residual norm (observation_residual.h): in
// pixels of the real camera for pixel observations, in degrees for bearings; +inf if the point is
// behind any camera or cannot be triangulated. Unlike the largest pairwise Sampson error, it sees
// an outlier that slides along its epipolar line when the three centres are collinear (straight
// driving).
class ThreeViewReprojectionError {
 public:
  // Throws std::invalid_argument if the observations fail ThreeViewObservations::Check().
  explicit ThreeViewReprojectionError(const ThreeViewObservations& observations);

  // A pose with what the error needs precomputed (rotations, centres). Camera 1 is the reference:
  // entries 0 are the identity and the origin.
  struct PreparedPose {
    std::array<Eigen::Matrix3d, 3> cam_from_ref;
    std::array<Eigen::Vector3d, 3> center_in_ref;
  };
  static PreparedPose Prepare(const ThreeViewPose& pose);

  // Largest reprojection error of triplet n (pixels, or degrees for bearings).
  double operator()(const PreparedPose& pose, std::size_t n) const;
  // The errors of triplets [begin, end) into errors[0, end - begin): operator()'s value, to the
  // last bit, where it is <= cap; some value > cap where it is > cap (a triplet's remaining views
  // are skipped once one is beyond the cap). Scoring for RANSAC, which needs no more. Throws
  // std::invalid_argument unless begin <= end <= size() and errors is not null.
  void Errors(const PreparedPose& pose,
              std::size_t begin,
              std::size_t end,
              double cap,
              double* errors) const;
  // The residual norm of triplet n's observation in view k (0, 1, 2) of a point given in camera
  // k's frame; +inf if the observation cannot see it.
  double ObservationError(int k, std::size_t n, const Eigen::Vector3d& point_in_cam) const;
  std::size_t size() const { return unit_rays_[0].size(); }
  // Each view's ray of each triplet in its camera's frame: the unprojected pixel (z = 1) or the
  // bearing (unit length).
  const std::array<std::vector<Eigen::Vector3d>, 3>& rays() const { return rays_; }

 private:
  template <typename ObservationErrorFn>
  double LargestError(const PreparedPose& pose,
                      std::size_t n,
                      double cap,
                      const ObservationErrorFn& observation_error) const;
  void PinholeErrors(const PreparedPose& pose,
                     std::size_t begin,
                     std::size_t end,
                     double* errors) const;
  double PixelError(int k, std::size_t n, const Eigen::Vector3d& point_in_cam) const;
  double BearingError(int k, std::size_t n, const Eigen::Vector3d& point_in_cam) const;
  double Field(int field, std::size_t n) const { return fields_[field * size() + n]; }

  bool bearings_;
  std::array<Camera, 3> cameras_;
  std::array<std::vector<Eigen::Vector2d>, 3> pixels_;          // pixel observations
  std::array<std::vector<BearingResidual>, 3> bearing_errors_;  // bearing observations
  std::array<std::vector<Eigen::Vector3d>, 3> rays_;
  std::array<std::vector<Eigen::Vector3d>, 3> unit_rays_;  // rays_, normalised
  // Pixel observations of three cameras without distortion: their intrinsics (else empty).
  std::vector<PinholeCamera> pinhole_;
  // Per triplet, field by field (fields_[field * size() + n], the fields of three_view_error.cc):
  // camera 1's part of the midpoint sums, which no pose changes, the unit rays of cameras 2 and 3
  // and the pixels; a layout that the scoring loop vectorises over.
  std::vector<double> fields_;
};

}  // namespace trigrav

#endif  // TRIGRAV_INITIALIZERS_THREE_VIEW_ERROR_H_
