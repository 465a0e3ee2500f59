#ifndef TRIGRAV_EXAMPLES_PEERS_PAIRWISE_ESTIMATOR_H_
#define TRIGRAV_EXAMPLES_PEERS_PAIRWISE_ESTIMATOR_H_

// A two-view robust estimator run on the view pairs (1,2) and (1,3), turned into a three-view
// estimate, the way a user without a three-view method combines them.

#include <functional>
#include <string>
#include <vector>

#include "peer_estimators.h"
#include "trigrav/initializers/camera_pose.h"
#include "trigrav/initializers/three_view_observations.h"

namespace trigrav::peers {

// Result of a two-view robust estimate of view k against view 1 (k = 1 or 2, 0-based).
struct PairEstimate {
  bool success = false;
  std::string message;        // why not, when !success
  CameraPose cam_from_cam1;   // x_k = R x_1 + t, any positive scale
  std::vector<char> inliers;  // per triplet: inlier of this pair
};

// Estimates view `view` (1 or 2) against view 0 from observations.pixels[0] and pixels[view].
using PairEstimator = std::function<PairEstimate(
    const ThreeViewObservations& observations, int view, double threshold_px)>;

// Runs pair_estimator on pairs (1,2) and (1,3) and combines the two poses with
// trigrav::CombineTwoViewPairs on the triplets that are inliers of both pairs (relative scale from
// the view-1 depths, derivations.md section 7); camera 2 is scaled to |centre| = 1. If the scale
// cannot be found (no common inlier, kappa <= 0), camera 3 keeps |centre| = 1 and the message says
// so: the rotation and translation-direction errors do not depend on it. time_s covers both pairs
// and the combination. Throws std::invalid_argument for invalid observations
// (ThreeViewObservations::Check) or a threshold that is not positive and finite.
Estimator PairwiseEstimator(PairEstimator pair_estimator);

}  // namespace trigrav::peers

#endif  // TRIGRAV_EXAMPLES_PEERS_PAIRWISE_ESTIMATOR_H_
