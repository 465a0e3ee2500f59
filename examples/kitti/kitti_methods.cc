#include "kitti_methods.h"

#include <algorithm>
#include <chrono>
#include <utility>

#include "trigrav/ba/initialize_and_refine.h"
#include "trigrav/initializers/robust_three_view.h"

namespace trigrav::kitti {
namespace {

using RotationModel = ThreeViewBundleAdjustmentOptions::RotationModel;

MethodPose Refine(const ThreeViewObservations& observations,
                  const InitializeAndRefineOptions& options,
                  const char* stage) {
  const ThreeViewEstimate estimate = InitializeAndRefine(observations, options);
  MethodPose pose;
  pose.stage = stage;
  pose.success = estimate.success && estimate.refinement_ran;
  pose.pose = estimate.refined;
  pose.num_inliers = estimate.num_inliers;
  pose.time_s = estimate.total_time_s;
  return pose;
}

Method MakeMethod(InitialSolver solver, bool refine, const TrigravMethodSettings& settings) {
  Method method;
  method.name = InitialSolverName(solver);
  method.run = [solver, refine, settings](const ThreeViewObservations& observations,
                                          std::uint64_t seed) {
    std::vector<MethodPose> poses;
    RobustThreeViewOptions robust;
    robust.solver = solver;
    robust.ransac = settings.ransac;
    robust.ransac.seed = seed;
    const auto start = std::chrono::steady_clock::now();
    const RobustThreeViewEstimate estimate = EstimateThreeViewPoseRobust(observations, robust);
    MethodPose raw;
    raw.stage = kRawStage;
    raw.time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    raw.success = estimate.success;
    raw.pose = estimate.pose;
    raw.num_inliers = estimate.num_inliers;
    poses.push_back(raw);
    if (!refine) return poses;
    InitializeAndRefineOptions options;
    options.solver = solver;
    options.inlier_threshold_px = settings.ransac.max_error;
    options.seed = seed;
    options.ransac = settings.ransac;
    options.reclassification_rounds = settings.reclassification_rounds;
    options.bundle_adjustment = settings.bundle_adjustment;
    for (const auto& [model, stage] :
         {std::pair{RotationModel::kYawOnly, kYawOnlyStage},
          std::pair{RotationModel::kGravityPrior, kGravityPriorStage}}) {
      options.bundle_adjustment.rotation_model = model;
      if (raw.success) {
        poses.push_back(Refine(observations, options, stage));
      } else {
        MethodPose failed;
        failed.stage = stage;
        poses.push_back(failed);
      }
    }
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
