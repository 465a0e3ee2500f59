#ifndef TRIGRAV_TESTS_SCENES_GRAVITY_SOLVER_H_
#define TRIGRAV_TESTS_SCENES_GRAVITY_SOLVER_H_

// One gravity-aware minimal solver held as a value, so that a test or an experiment runs several
// on the same scenes: the gravity overloads of trifocal_3pt.h and trifocal_4pt.h (options bound)
// share this signature. Used by tests/initializers/trifocal_3pt_test.cc and by
// examples/experiments/ (minimal_solver_accuracy, solver_stability), which have tests/scenes on
// their include path.

#include <Eigen/Core>
#include <functional>
#include <vector>

#include "trigrav/initializers/camera_pose.h"

namespace trigrav {
namespace testing_utils {

// Rays of one view (K^-1 [u v 1]^T), one per triplet.
using Rays = std::vector<Eigen::Vector3d>;

// solve(x1, x2, x3, gravity_in_cam1, gravity_in_cam2, gravity_in_cam3, &solutions), each gravity
// the view's down direction in its own frame: clears solutions, appends every candidate pose in the
// original camera frames (best-ranked first) and returns their count.
using GravitySolver = std::function<int(const Rays&,
                                        const Rays&,
                                        const Rays&,
                                        const Eigen::Vector3d&,
                                        const Eigen::Vector3d&,
                                        const Eigen::Vector3d&,
                                        std::vector<ThreeViewPose>*)>;

}  // namespace testing_utils
}  // namespace trigrav

#endif  // TRIGRAV_TESTS_SCENES_GRAVITY_SOLVER_H_
