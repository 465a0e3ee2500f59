#ifndef TRIGRAV_INITIALIZERS_SRC_ROBUST_TRIPLET_DATA_H_
#define TRIGRAV_INITIALIZERS_SRC_ROBUST_TRIPLET_DATA_H_

// What the robust estimator prepares once per call (EstimateThreeViewPoseRobust): each view's rays,
// raw and gravity-aligned, the alignments and the common inlier error; and the solvers' reused
// output storage.

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <vector>

#include "trigrav/initializers/camera_pose.h"
#include "trigrav/initializers/gravity.h"
#include "trigrav/initializers/three_view_error.h"
#include "trigrav/initializers/three_view_observations.h"

namespace trigrav {
namespace internal {

using Rays = std::vector<Eigen::Vector3d>;
using ViewRays = std::array<Rays, 3>;

// What every method's estimator shares: the rays of each view, raw (unprojected pixels with z = 1,
// or unit bearings) and gravity-aligned, and the common inlier error.
struct TripletData {
  TripletData(const ThreeViewObservations& observations, double max_tilt_correction_deg)
      : min_cos_tilt_correction(std::cos(max_tilt_correction_deg * M_PI / 180.0)),
        error(observations) {
    for (int k = 0; k < 3; ++k) {
      alignment[k] = GravityAlignmentFromGravity(observations.gravity_in_cam[k]);
      raw[k] = error.rays()[k];
      aligned[k] = AlignRays(alignment[k], raw[k]);
    }
  }
  ViewRays raw, aligned;
  std::array<Eigen::Matrix3d, 3> alignment;
  double min_cos_tilt_correction;  // cos(RobustThreeViewOptions::max_tilt_correction_deg)
  ThreeViewReprojectionError error;
};

// Reused storage of the solvers' outputs, so the RANSAC loop does not allocate once warm.
struct Workspace {
  std::vector<ThreeViewPose> three_view;
  std::vector<CameraPose> pair12, pair13;
  ViewRays corrected;  // tilt-corrected aligned rays (TiltCorrectingRefinement)
};

// A method's solver (robust_methods.h): appends three-view poses in the original frames computed
// from the given rays of the selected triplets.
using SolveFunction = void (*)(const TripletData&,
                               const ViewRays&,
                               Workspace*,
                               std::vector<ThreeViewPose>*);

}  // namespace internal
}  // namespace trigrav

#endif  // TRIGRAV_INITIALIZERS_SRC_ROBUST_TRIPLET_DATA_H_
