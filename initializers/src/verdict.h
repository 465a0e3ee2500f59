#ifndef TRIGRAV_INITIALIZERS_SRC_VERDICT_H_
#define TRIGRAV_INITIALIZERS_SRC_VERDICT_H_

// The robust estimator's verdict on a RANSAC result (derivations.md sections 7.5 and 7.6): a best
// model below the inlier-ratio floor gets a message with the likely causes, and a gravity-aware
// estimate is checked against a gravity-free one.

#include "robust_triplet_data.h"
#include "trigrav/initializers/ransac.h"
#include "trigrav/initializers/robust_three_view.h"

namespace trigrav {
namespace internal {

// `estimate` is the RANSAC result of a method with minimal sample `sample_size` under `ransac`.
// For a gravity-aware method and a finite `max_gravity_inconsistency_deg`, after a failure (and
// after a success if `check_gravity_after_success`), fills estimate->gravity
// (gravity_consistency.h) and fails the estimate, with the camera, the angle and the likely cause,
// when the images contradict the gravity (robust_three_view.h). Below the floor, rewrites the
// message with the inlier figures and the likely causes.
void JudgeEstimate(const TripletData& data,
                   const RansacOptions& ransac,
                   int sample_size,
                   bool uses_gravity,
                   double max_gravity_inconsistency_deg,
                   bool check_gravity_after_success,
                   RobustThreeViewEstimate* estimate);

}  // namespace internal
}  // namespace trigrav

#endif  // TRIGRAV_INITIALIZERS_SRC_VERDICT_H_
