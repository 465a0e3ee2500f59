#ifndef TRIGRAV_BA_SRC_THREE_VIEW_LM_SOLVER_H_
#define TRIGRAV_BA_SRC_THREE_VIEW_LM_SOLVER_H_

// The dedicated engine of ThreeViewBundleAdjuster (ThreeViewBundleAdjustmentOptions::Engine::
// kDedicated): Levenberg-Marquardt on the adjuster's problem with each point's 3 x 3 block
// eliminated and a fixed-size reduced system of the pose, following Ceres' trust-region rules
// but on a warm start (point steps first, the last candidate kept at the function tolerance)
// (ba/derivations.md section 13). Internal to trigrav::ba.

#include <ceres/solver.h>

#include <Eigen/Core>
#include <vector>

#include "trigrav/ba/three_view_bundle_adjustment.h"

namespace trigrav {
namespace internal {

// Largest pose dimension (kGravityPrior).
inline constexpr int kMaxThreeViewPoseSize = 11;

// The Gauss-Newton information J^T J of the adjuster's residuals through their losses (Ceres'
// corrector), by blocks, in Ceres' tangent coordinates of the pose blocks ordered as
// ThreeViewCovarianceLayout (rotation 2, rotation 3, C2, C3): pose-pose, per point the point-point
// block and the pose-point coupling. No point blocks when the points are constant.
struct ThreeViewInformation {
  Eigen::Matrix<double,
                Eigen::Dynamic,
                Eigen::Dynamic,
                0,
                kMaxThreeViewPoseSize,
                kMaxThreeViewPoseSize>
      pose;
  std::vector<Eigen::Matrix3d> point;
  std::vector<Eigen::Matrix<double, kMaxThreeViewPoseSize, 3>> coupling;
};

// Minimises the built adjuster's problem in place (its rotation, centre and point blocks) and
// fills the fields of *summary that ThreeViewBundleAdjustmentSummary documents for this engine.
void SolveThreeViewLm(ThreeViewBundleAdjuster* adjuster, ceres::Solver::Summary* summary);

// The information at the adjuster's current parameters; false if a residual cannot be evaluated.
bool EvaluateThreeViewInformation(ThreeViewBundleAdjuster* adjuster,
                                  ThreeViewInformation* information);

}  // namespace internal
}  // namespace trigrav

#endif  // TRIGRAV_BA_SRC_THREE_VIEW_LM_SOLVER_H_
