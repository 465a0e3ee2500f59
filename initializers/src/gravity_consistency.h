#ifndef TRIGRAV_INITIALIZERS_SRC_GRAVITY_CONSISTENCY_H_
#define TRIGRAV_INITIALIZERS_SRC_GRAVITY_CONSISTENCY_H_

// How far each camera's gravity is from what the images say (derivations.md section 7.6): a
// gravity-free robust estimate compared with the given gravity.

#include "robust_triplet_data.h"
#include "trigrav/initializers/camera_pose.h"
#include "trigrav/initializers/ransac.h"
#include "trigrav/initializers/robust_three_view.h"

namespace trigrav {
namespace internal {

// Runs the five-point method (through the same RANSAC, with `ransac`) on the triplets and, if it
// succeeds, measures its rotations against the gravity of `data` and against `gravity_aware`
// (compared only when `has_gravity_aware_pose`). The gravity-free estimate itself goes to
// `gravity_free` when not null.
GravityConsistency MeasureGravityConsistency(const TripletData& data,
                                             const RansacOptions& ransac,
                                             const ThreeViewPose& gravity_aware,
                                             bool has_gravity_aware_pose,
                                             RobustThreeViewEstimate* gravity_free = nullptr);

}  // namespace internal
}  // namespace trigrav

#endif  // TRIGRAV_INITIALIZERS_SRC_GRAVITY_CONSISTENCY_H_
