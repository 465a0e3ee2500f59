#include "kitti_methods.h"

namespace trigrav::kitti {
namespace {

using RotationModel = ThreeViewBundleAdjustmentOptions::RotationModel;

// The RANSAC stage of an InitializeAndRefine estimate: a success when the verdict accepted the
// RANSAC pose, whatever the refinement did with it afterwards.
MethodPose RawStage(const ThreeViewEstimate& estimate) {
  MethodPose pose;
  const bool refinement_refused = estimate.cause == FailureCause::kRefinementShift;
  pose.success = estimate.success || refinement_refused;
  pose.message = refinement_refused ? "" : estimate.message;
  pose.cause = refinement_refused ? FailureCause::kNone : estimate.cause;
  pose.pose = estimate.robust.pose;
  pose.inliers = estimate.robust.inliers;
  pose.ransac = estimate.robust.ransac;
  pose.gravity = estimate.robust.gravity;
  pose.evidence = estimate.robust.evidence;
  pose.stage = kRawStage;
  pose.time_s = estimate.timings.ransac_s;
  return pose;
}

// The refined stage of an InitializeAndRefine estimate; its time includes the RANSAC.
MethodPose RefinedStage(const char* stage, const ThreeViewEstimate& estimate) {
  MethodPose pose;
  pose.success = estimate.success && estimate.refinement_runs > 0;
  pose.message = estimate.message;
  pose.cause = estimate.cause;
  pose.pose = estimate.refined;
  pose.inliers = estimate.inliers;
  pose.ransac = estimate.robust.ransac;
  pose.ransac.num_inliers = estimate.num_inliers;
  pose.gravity = estimate.robust.gravity;
  pose.evidence = estimate.robust.evidence;
  pose.stage = stage;
  pose.time_s = estimate.timings.total_s;
  return pose;
}

}  // namespace

Method TrigravMethod(InitialSolver solver, bool refine, const InitializeAndRefineOptions& options) {
  InitializeAndRefineOptions method_options = options;
  method_options.robust.solver = solver;
  method_options.refine = refine;
  method_options.bundle_adjustment.rotation_model = RotationModel::kYawOnly;
  Method method;
  method.name = InitialSolverName(solver);
  method.run = [method_options](const ThreeViewObservations& observations, std::uint64_t seed) {
    InitializeAndRefineOptions run_options = method_options;
    run_options.robust.ransac.seed = seed;
    // One call gives the raw stage (its RANSAC estimate) and the yaw-only refinement of it.
    const ThreeViewEstimate yaw_only = InitializeAndRefine(observations, run_options);
    std::vector<MethodPose> poses = {RawStage(yaw_only)};
    if (!run_options.refine) return poses;
    poses.push_back(RefinedStage(kYawOnlyStage, yaw_only));
    // Same seed, other rotation model, run whatever the yaw-only call gave: its RANSAC differs
    // (the local optimisation may correct the tilt, initialize_and_refine.h) and so may its
    // verdict.
    run_options.bundle_adjustment.rotation_model = RotationModel::kGravityPrior;
    poses.push_back(
        RefinedStage(kGravityPriorStage, InitializeAndRefine(observations, run_options)));
    return poses;
  };
  return method;
}

}  // namespace trigrav::kitti
