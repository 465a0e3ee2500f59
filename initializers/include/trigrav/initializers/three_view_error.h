#ifndef TRIGRAV_INITIALIZERS_THREE_VIEW_ERROR_H_
#define TRIGRAV_INITIALIZERS_THREE_VIEW_ERROR_H_

#include <Eigen/Core>
#include <array>
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
// symmetric A are kept.
struct MidpointSums {
  double a00 = 0.0, a01 = 0.0, a02 = 0.0, a11 = 0.0, a12 = 0.0, a22 = 0.0;
  Eigen::Vector3d b = Eigen::Vector3d::Zero();

  // Adds the ray from `center` along d; false (sums untouched) if d is zero, not finite or so long
  // that its squared length overflows.
  bool Add(const Eigen::Vector3d& center, const Eigen::Vector3d& d);
  // X = A^-1 b; false (X untouched) unless A is clearly invertible and X finite.
  bool Solve(Eigen::Vector3d* point) const;
};

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
  double PixelError(int k, std::size_t n, const Eigen::Vector3d& point_in_cam) const;
  double BearingError(int k, std::size_t n, const Eigen::Vector3d& point_in_cam) const;

  bool bearings_;
  std::array<Camera, 3> cameras_;
  std::array<std::vector<Eigen::Vector2d>, 3> pixels_;          // pixel observations
  std::array<std::vector<BearingResidual>, 3> bearing_errors_;  // bearing observations
  std::array<std::vector<Eigen::Vector3d>, 3> rays_;
  std::array<std::vector<Eigen::Vector3d>, 3> unit_rays_;  // rays_, normalised
  // Camera 1's part of each triplet's midpoint system, which no pose changes, and whether its ray
  // could be added (MidpointSums::Add).
  std::vector<internal::MidpointSums> reference_sums_;
  std::vector<char> reference_added_;
};

}  // namespace trigrav

#endif  // TRIGRAV_INITIALIZERS_THREE_VIEW_ERROR_H_
