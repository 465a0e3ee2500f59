// PoseLib's robust relative pose and its Levenberg-Marquardt refinement on robust_benchmark's issue
// scenes (poselib_benchmarks.h). PoseLib's cameras take COLMAP's model names and parameter order,
// like trigrav's; its threshold is a Sampson error in pixels. A pair's pose is cam_from_cam1 with
// |centre| = 1, which the errors of ComputeThreeViewPoseErrors (rotations, centre directions) do
// not depend on; the relative scale is not estimated and not reported.

#include <PoseLib/misc/camera_models.h>
#include <PoseLib/robust.h>
#include <PoseLib/robust/bundle.h>
#include <benchmark/benchmark.h>

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "common/pooled_errors.h"
#include "issue_scenes.h"
#include "poselib_benchmarks.h"
#include "trigrav/evaluation/pose_errors.h"
#include "trigrav/evaluation/statistics.h"
#include "trigrav/initializers/ransac.h"
#include "trigrav/initializers/robust_three_view.h"
#include "trigrav/initializers/three_view_observations.h"

namespace trigrav::benchmarks {
namespace {

poselib::Camera ToPoseLib(const Camera& camera) {
  const int num_params = NumCameraParams(camera.model);
  return poselib::Camera(
      CameraModelName(camera.model),
      std::vector<double>(camera.params.begin(), camera.params.begin() + num_params));
}

CameraPose FromPoseLib(const poselib::CameraPose& pose) { return {pose.R(), pose.t}; }

// One scene as PoseLib takes it: each view's pixels and camera.
struct PoseLibScene {
  std::vector<poselib::Point2D> pixels[3];
  poselib::Camera cameras[3];
  ThreeViewPose ground_truth;
};

std::vector<PoseLibScene> ToPoseLibScenes(int num_points) {
  std::vector<PoseLibScene> result;
  for (const SyntheticScene& scene : IssueScenes(num_points)) {
    const ThreeViewObservations observations = ToObservations(scene);
    PoseLibScene converted;
    for (int k = 0; k < 3; ++k) {
      converted.pixels[k] = observations.pixels[k];
      converted.cameras[k] = ToPoseLib(observations.cameras[k]);
    }
    converted.ground_truth = scene.ground_truth;
    result.push_back(converted);
  }
  return result;
}

// The stopping rules of the rows. kTrigravRule is trigrav's (RobustThreeViewOptions' RansacOptions,
// ransac.h): stop after max(min_iterations, k) samples, at most max_iterations, with k = log(1 -
// confidence) / log(1 - w^s) for the best model's inlier ratio w, i.e. PoseLib's rule with
// dyn_num_trials_mult = 1 (PoseLib draws w^s without replacement, and its loop takes one sample
// more: it stops once the count exceeds both bounds). kPoseLibDefaults: PoseLib's RansacOptions.
enum class StoppingRule { kTrigravRule, kPoseLibDefaults };

// RelativePoseOptions at the issue scenes' threshold with a stopping rule; final_refinement = false
// skips estimate_relative_pose's refinement after its RANSAC (bundle.max_iterations = 0).
poselib::RelativePoseOptions Options(StoppingRule rule, bool final_refinement) {
  poselib::RelativePoseOptions options;
  options.max_error = kIssueScenesThresholdPx;
  if (rule == StoppingRule::kTrigravRule) {
    const RansacOptions trigrav = RobustThreeViewOptions().ransac;
    options.ransac.success_prob = trigrav.confidence;
    options.ransac.min_iterations = static_cast<std::size_t>(trigrav.min_iterations);
    options.ransac.max_iterations = static_cast<std::size_t>(trigrav.max_iterations);
    options.ransac.dyn_num_trials_mult = 1.0;
  }
  if (!final_refinement) options.bundle.max_iterations = 0;
  return options;
}

// estimate_relative_pose on pair (1, view) of a scene.
poselib::RansacStats EstimatePair(const PoseLibScene& scene,
                                  int view,
                                  const poselib::RelativePoseOptions& options,
                                  poselib::CameraPose* cam_from_cam1,
                                  std::vector<char>* inliers) {
  return poselib::estimate_relative_pose(scene.pixels[0], scene.pixels[view], scene.cameras[0],
                                         scene.cameras[view], options, cam_from_cam1, inliers);
}

// Both pairs of each scene in turn, one call each. The counters come from one pass over all the
// scenes before the timing (a row of the defaults runs fewer calls than there are scenes).
void BM_EstimateRelativePose(benchmark::State& state, StoppingRule rule, bool final_refinement) {
  const std::vector<PoseLibScene> scenes = ToPoseLibScenes(static_cast<int>(state.range(0)));
  const poselib::RelativePoseOptions options = Options(rule, final_refinement);
  poselib::CameraPose cam2_from_cam1, cam3_from_cam1;
  std::vector<char> inliers12, inliers13;
  PooledErrors errors;
  std::vector<double> iterations, inliers;
  for (const PoseLibScene& scene : scenes) {
    const poselib::RansacStats stats12 =
        EstimatePair(scene, 1, options, &cam2_from_cam1, &inliers12);
    const poselib::RansacStats stats13 =
        EstimatePair(scene, 2, options, &cam3_from_cam1, &inliers13);
    if (stats12.num_inliers >= 5 && stats13.num_inliers >= 5) {
      errors.Add(ComputeThreeViewPoseErrors(
          scene.ground_truth, {FromPoseLib(cam2_from_cam1), FromPoseLib(cam3_from_cam1)}));
    } else {
      errors.AddFailure();
    }
    for (const poselib::RansacStats& stats : {stats12, stats13}) {
      iterations.push_back(static_cast<double>(stats.iterations));
      inliers.push_back(static_cast<double>(stats.num_inliers));
    }
  }
  std::size_t i = 0;
  for (auto _ : state) {
    const PoseLibScene& scene = scenes[i++ % scenes.size()];
    benchmark::DoNotOptimize(EstimatePair(scene, 1, options, &cam2_from_cam1, &inliers12));
    benchmark::DoNotOptimize(EstimatePair(scene, 2, options, &cam3_from_cam1, &inliers13));
  }
  state.counters["rot_deg"] = Median(errors.rotation_deg);
  state.counters["trans_deg"] = Median(errors.translation_deg);
  state.counters["ransac_iterations"] = Median(iterations);
  state.counters["inliers"] = Median(inliers);
}

// One pair's inliers in normalised coordinates and the pose to refine: the RANSAC's model at
// trigrav's stopping rule before estimate_relative_pose's own final refinement
// (bundle.max_iterations = 0), as trigrav's bundle adjustment starts from its RANSAC's estimate.
struct RefinementProblem {
  std::vector<poselib::Point2D> x1, x2;
  poselib::CameraPose cam_from_cam1;
};

RefinementProblem MakeRefinementProblem(const PoseLibScene& scene, int view) {
  RefinementProblem problem;
  std::vector<char> inliers;
  EstimatePair(scene, view, Options(StoppingRule::kTrigravRule, false), &problem.cam_from_cam1,
               &inliers);
  for (std::size_t n = 0; n < inliers.size(); ++n) {
    if (!inliers[n]) continue;
    poselib::Point2D x1, x2;
    scene.cameras[0].unproject(scene.pixels[0][n], &x1);
    scene.cameras[view].unproject(scene.pixels[view][n], &x2);
    problem.x1.push_back(x1);
    problem.x2.push_back(x2);
  }
  return problem;
}

// PoseLib's refine_relpose (Sampson error, its default Cauchy loss at 1 px) as
// estimate_relative_pose calls it, on pairs (1,2) and (1,3) of each scene in turn.
void BM_RefineRelposeTwoPairs(benchmark::State& state) {
  const std::vector<PoseLibScene> scenes = ToPoseLibScenes(static_cast<int>(state.range(0)));
  std::vector<std::pair<RefinementProblem, RefinementProblem>> problems;
  for (const PoseLibScene& scene : scenes) {
    problems.emplace_back(MakeRefinementProblem(scene, 1), MakeRefinementProblem(scene, 2));
  }
  // estimate_relative_pose scales the loss from pixels to normalised coordinates by the mean of
  // 1 / focal length of the two cameras (every camera of the issue scenes has the same focal).
  poselib::BundleOptions bundle;
  bundle.loss_scale *=
      0.5 * (1.0 / scenes[0].cameras[0].focal() + 1.0 / scenes[0].cameras[1].focal());
  PooledErrors errors;
  std::vector<double> iterations, inliers;
  for (std::size_t p = 0; p < problems.size(); ++p) {
    poselib::CameraPose cam2_from_cam1 = problems[p].first.cam_from_cam1;
    poselib::CameraPose cam3_from_cam1 = problems[p].second.cam_from_cam1;
    const poselib::BundleStats stats12 = poselib::refine_relpose(
        problems[p].first.x1, problems[p].first.x2, &cam2_from_cam1, bundle);
    const poselib::BundleStats stats13 = poselib::refine_relpose(
        problems[p].second.x1, problems[p].second.x2, &cam3_from_cam1, bundle);
    errors.Add(ComputeThreeViewPoseErrors(
        scenes[p].ground_truth, {FromPoseLib(cam2_from_cam1), FromPoseLib(cam3_from_cam1)}));
    iterations.push_back(stats12.iterations);
    iterations.push_back(stats13.iterations);
    inliers.push_back(static_cast<double>(problems[p].first.x1.size()));
    inliers.push_back(static_cast<double>(problems[p].second.x1.size()));
  }
  std::size_t i = 0;
  for (auto _ : state) {
    const auto& [pair12, pair13] = problems[i++ % problems.size()];
    poselib::CameraPose cam2_from_cam1 = pair12.cam_from_cam1;
    poselib::CameraPose cam3_from_cam1 = pair13.cam_from_cam1;
    benchmark::DoNotOptimize(
        poselib::refine_relpose(pair12.x1, pair12.x2, &cam2_from_cam1, bundle).cost);
    benchmark::DoNotOptimize(
        poselib::refine_relpose(pair13.x1, pair13.x2, &cam3_from_cam1, bundle).cost);
  }
  state.counters["rot_deg"] = Median(errors.rotation_deg);
  state.counters["trans_deg"] = Median(errors.translation_deg);
  state.counters["lm_iterations"] = Median(iterations);
  state.counters["inliers"] = Median(inliers);
}

}  // namespace

void RegisterPoseLibRobustBenchmarks() {
  struct Row {
    const char* name;
    StoppingRule rule;
    bool final_refinement;
  };
  for (const Row& row : {Row{"trigrav_rule", StoppingRule::kTrigravRule, true},
                         Row{"trigrav_rule_ransac_only", StoppingRule::kTrigravRule, false},
                         Row{"defaults", StoppingRule::kPoseLibDefaults, true}}) {
    benchmark::RegisterBenchmark(
        (std::string("BM_PoseLib/estimate_relative_pose/") + row.name).c_str(),
        [row](benchmark::State& state) {
          BM_EstimateRelativePose(state, row.rule, row.final_refinement);
        })
        ->Arg(375)
        ->Arg(875)
        ->Unit(benchmark::kMillisecond)
        ->MinTime(1.0);
  }
  benchmark::RegisterBenchmark("BM_PoseLib/refine_relpose_two_pairs", BM_RefineRelposeTwoPairs)
      ->Arg(375)
      ->Arg(875)
      ->Unit(benchmark::kMillisecond)
      ->MinTime(1.0);
}

}  // namespace trigrav::benchmarks
