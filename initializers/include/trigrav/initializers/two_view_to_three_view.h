#ifndef TRIGRAV_INITIALIZERS_TWO_VIEW_TO_THREE_VIEW_H_
#define TRIGRAV_INITIALIZERS_TWO_VIEW_TO_THREE_VIEW_H_

#include <Eigen/Core>
#include <vector>

#include "trigrav/initializers/camera_pose.h"

namespace trigrav {

// Three-view poses from the solutions of a two-view method (5-point or 8-point) on the view pairs
// (1,2) and (1,3) (derivations.md sections 5.6 and 6.3): every combination of a (1,2) solution and
// a (1,3) solution, with the centre of camera 3 rescaled by kappa = <l2, l3> / <l3, l3>, l_k the
// view-1 depths of the triplets triangulated from pair (1,k) alone. Combinations with kappa <= 0
// (or not finite) are inconsistent and skipped. Camera 2 keeps its scale (|Center()| = 1 for
// trigrav's two-view solvers).
//
// x1, x2, x3: the rays of the triplets (the same ones the pair solutions came from, or more).
// Appends to *poses (not cleared). If residuals is not null, appends for each pose the depth-ratio
// residual |l2 - kappa l3| / |l2| (about 1e-15 for the true combination without noise), so that a
// caller can rank the combinations without ground truth. Without triplets there is no depth, so
// nothing is appended. Throws std::invalid_argument on misuse: x1, x2, x3 differ in size,
// non-finite numbers or zero-length rays, a non-finite pair pose, poses null.
void CombineTwoViewPairs(const std::vector<Eigen::Vector3d>& x1,
                         const std::vector<Eigen::Vector3d>& x2,
                         const std::vector<Eigen::Vector3d>& x3,
                         const std::vector<CameraPose>& pair12,
                         const std::vector<CameraPose>& pair13,
                         std::vector<ThreeViewPose>* poses,
                         std::vector<double>* residuals = nullptr);

}  // namespace trigrav

#endif  // TRIGRAV_INITIALIZERS_TWO_VIEW_TO_THREE_VIEW_H_
