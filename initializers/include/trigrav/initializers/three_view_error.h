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

  // A pose with what the error needs precomputed (rotations, centres).
  struct PreparedPose {
    std::array<Eigen::Matrix3d, 3> cam_from_ref;
    std::array<Eigen::Vector3d, 3> center_in_ref;
  };
  static PreparedPose Prepare(const ThreeViewPose& pose);

  // Largest reprojection error of triplet n (pixels, or degrees for bearings).
  double operator()(const PreparedPose& pose, std::size_t n) const;
  // The residual norm of triplet n's observation in view k (0, 1, 2) of a point given in camera
  // k's frame; +inf if the observation cannot see it.
  double ObservationError(int k, std::size_t n, const Eigen::Vector3d& point_in_cam) const;
  std::size_t size() const { return unit_rays_[0].size(); }
  // Each view's ray of each triplet in its camera's frame: the unprojected pixel (z = 1) or the
  // bearing (unit length).
  const std::array<std::vector<Eigen::Vector3d>, 3>& rays() const { return rays_; }

 private:
  bool bearings_;
  std::array<Camera, 3> cameras_;
  std::array<std::vector<Eigen::Vector2d>, 3> pixels_;          // pixel observations
  std::array<std::vector<BearingResidual>, 3> bearing_errors_;  // bearing observations
  std::array<std::vector<Eigen::Vector3d>, 3> rays_;
  std::array<std::vector<Eigen::Vector3d>, 3> unit_rays_;  // rays_, normalised
};

}  // namespace trigrav

#endif  // TRIGRAV_INITIALIZERS_THREE_VIEW_ERROR_H_
