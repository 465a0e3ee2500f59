#ifndef TRIGRAV_INITIALIZERS_SRC_VERDICT_H_
#define TRIGRAV_INITIALIZERS_SRC_VERDICT_H_

// The robust estimator's verdict on a RANSAC result (derivations.md sections 7.5-7.7): a winner is
// a success only if its consensus could not arise by chance, its inliers pin the pose down and no
// gravity-free model explains clearly more triplets; a failure's message names the likely cause
// first.

#include <array>

#include "robust_triplet_data.h"
#include "trigrav/initializers/ransac.h"
#include "trigrav/initializers/robust_three_view.h"
#include "trigrav/initializers/three_view_observations.h"

namespace trigrav {
namespace internal {

// What the verdict needs to know of the method and the options.
struct VerdictSettings {
  int sample_size = 0;
  int max_models_per_sample = 1;
  bool uses_gravity = false;
  bool tilt_correcting = false;              // RobustThreeViewOptions::max_tilt_correction_deg > 0
  double max_gravity_inconsistency_deg = 0;  // resolved; +inf: no gravity-free comparison
  bool check_gravity_after_success = false;
  double max_pose_sigma_deg = 0;
  bool judge_offset = false;  // !refined_afterwards: the pose's offset from its optimum counts
  int min_inliers = 0;
};

// `estimate` is the RANSAC result of the method under `ransac` on `data` (made of `observations`).
// Fills estimate->evidence and, where the comparison runs, estimate->gravity; turns a success the
// evidence does not support into a failure, and gives a failure below the floor its likely cause.
void JudgeEstimate(const TripletData& data,
                   const ThreeViewObservations& observations,
                   const RansacOptions& ransac,
                   const VerdictSettings& settings,
                   RobustThreeViewEstimate* estimate);

}  // namespace internal
}  // namespace trigrav

#endif  // TRIGRAV_INITIALIZERS_SRC_VERDICT_H_
