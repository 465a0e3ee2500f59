#ifndef TRIGRAV_INITIALIZERS_SRC_PARALLAX_CHECK_H_
#define TRIGRAV_INITIALIZERS_SRC_PARALLAX_CHECK_H_

// The robust estimator's rejection of data without parallax between views 1 and 2, whose camera 2
// centre (the scale |C2| = 1) is then not observable.

#include "robust_triplet_data.h"
#include "trigrav/initializers/robust_three_view.h"

namespace trigrav {
namespace internal {

// Turns a successful estimate into a failure with the reason if its inliers show no parallax
// between views 1 and 2 (robust_three_view.h), whatever the method: if a camera 2 without baseline
// explains more than 80 % of them within `max_error` (pixels, or degrees for
// bearings).
void RejectWithoutParallax(const TripletData& data,
                           double max_error,
                           RobustThreeViewEstimate* estimate);

}  // namespace internal
}  // namespace trigrav

#endif  // TRIGRAV_INITIALIZERS_SRC_PARALLAX_CHECK_H_
