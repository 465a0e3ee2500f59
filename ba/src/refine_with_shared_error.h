#ifndef TRIGRAV_BA_SRC_REFINE_WITH_SHARED_ERROR_H_
#define TRIGRAV_BA_SRC_REFINE_WITH_SHARED_ERROR_H_

// RefineThreeViewPose with the observations' inlier error built once by the caller, for
// InitializeAndRefine's runs and re-classification. Not installed; not part of the public API.

#include <memory>
#include <vector>

#include "trigrav/ba/refine_three_view_pose.h"
#include "trigrav/initializers/three_view_error.h"

namespace trigrav {
namespace internal {

// RefineThreeViewPose(observations, initial, inliers, options[, *previous]) with `error` the
// inlier error of `observations` (nullptr: the adjuster builds its own), previous nullptr for the
// first overload.
ThreeViewRefinement RefineThreeViewPose(const ThreeViewObservations& observations,
                                        std::shared_ptr<const ThreeViewReprojectionError> error,
                                        const ThreeViewPose& initial,
                                        const std::vector<char>& inliers,
                                        const ThreeViewBundleAdjustmentOptions& options,
                                        const ThreeViewRefinement* previous);

}  // namespace internal
}  // namespace trigrav

#endif  // TRIGRAV_BA_SRC_REFINE_WITH_SHARED_ERROR_H_
