#include "kitti_methods.h"

#include <algorithm>

#include "trigrav/ba/initialize_and_refine.h"
#include "trigrav/initializers/robust_three_view.h"

namespace trigrav::kitti {
namespace {

using RotationModel = ThreeViewBundleAdjustmentOptions::RotationModel;

// The refined stage of an InitializeAndRefine estimate; its time includes the RANSAC.
MethodPose RefinedStage(const char* stage, const ThreeViewEstimate& estimate) {
  return {stage, estimate.success && estimate.refinement_ran, estimate.refined,
          estimate.num_inliers, estimate.total_time_s};
}

Method MakeMethod(InitialSolver solver, bool refine, const TrigravMethodSettings& settings) {
  InitializeAndRefineOptions options;
  options.solver = solver;
  options.inlier_threshold_px = settings.ransac.max_error;
  options.ransac = settings.ransac;
  options.refine = refine;
  options.reclassification_rounds = settings.reclassification_rounds;
  options.bundle_adjustment = settings.bundle_adjustment;
  options.bundle_adjustment.rotation_model = RotationModel::kYawOnly;
  Method method;
  method.name = InitialSolverName(solver);
  method.run = [options](const ThreeViewObservations& observations, std::uint64_t seed) {
    InitializeAndRefineOptions run_options = options;
    run_options.seed = seed;
    // One call gives the raw stage (its RANSAC estimate) and the yaw-only refinement of it.
    const ThreeViewEstimate yaw_only = InitializeAndRefine(observations, run_options);
    // initial_inliers is filled only when the estimate was refined.
    std::vector<MethodPose> poses = {
        {kRawStage, yaw_only.success, yaw_only.initial,
         run_options.refine ? yaw_only.num_initial_inliers : yaw_only.num_inliers,
         yaw_only.ransac_time_s}};
    if (!run_options.refine) return poses;
    poses.push_back(RefinedStage(kYawOnlyStage, yaw_only));
    if (!yaw_only.success) {  // no RANSAC estimate: the gravity-prior stage fails alike
      poses.push_back(RefinedStage(kGravityPriorStage, yaw_only));
      return poses;
    }
    // Same seed, other rotation model. Its RANSAC differs from the yaw-only one: with the
    // gravity-prior model the local optimisation frees the tilt (initialize_and_refine.h).
    run_options.bundle_adjustment.rotation_model = RotationModel::kGravityPrior;
    poses.push_back(
        RefinedStage(kGravityPriorStage, InitializeAndRefine(observations, run_options)));
    return poses;
  };
  return method;
}

}  // namespace

bool MakeTrigravMethods(const std::vector<std::string>& names,
                        const TrigravMethodSettings& settings,
                        std::vector<Method>* methods,
                        std::string* error) {
  for (const std::string& name : names) {
    InitialSolver solver;
    if (!ParseInitialSolver(name, &solver)) {
      *error =
          "unknown method \"" + name + "\" (expected 8pt, 5pt, 7pt-linear, 3pt, 3pt-sextic, 4pt)";
      return false;
    }
    const bool refine = std::find(settings.refined_methods.begin(), settings.refined_methods.end(),
                                  name) != settings.refined_methods.end();
    methods->push_back(MakeMethod(solver, refine, settings));
  }
  return true;
}

}  // namespace trigrav::kitti
