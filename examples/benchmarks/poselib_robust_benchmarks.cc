// PoseLib's robust relative pose and its Levenberg-Marquardt refinement on robust_benchmark's issue
// scenes (poselib_benchmarks.h). PoseLib's cameras take COLMAP's model names and parameter order,
// like trigrav's; its threshold is a Sampson error in pixels. A pair's pose is cam_from_cam1 with
// |centre| = 1, which the errors of ComputeThreeViewPoseErrors (rotations, centre directions) do
// not depend on; the relative scale is not estimated and not reported.

#include <PoseLib/misc/camera_models.h>
#include <PoseLib/robust.h>
#include <PoseLib/robust/bundle.h>
#include <benchmark/benchmark.h>

#include <string>
#include <utility>
#include <vector>

#include "common/pooled_errors.h"
#include "issue_scenes.h"
#include "poselib_benchmarks.h"
#include "trigrav/evaluation/pose_errors.h"
#include "trigrav/evaluation/statistics.h"
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

// RelativePoseOptions at the issue scenes' threshold; min_iterations = 0 keeps PoseLib's default.
poselib::RelativePoseOptions Options(std::size_t min_iterations) {
  poselib::RelativePoseOptions options;
  options.max_error = kIssueScenesThresholdPx;
  if (min_iterations > 0) options.ransac.min_iterations = min_iterations;
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
void BM_EstimateRelativePose(benchmark::State& state, std::size_t min_iterations) {
  const std::vector<PoseLibScene> scenes = ToPoseLibScenes(static_cast<int>(state.range(0)));
  const poselib::RelativePoseOptions options = Options(min_iterations);
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
      iterations.push_back(stats.iterations);
      inliers.push_back(stats.num_inliers);
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
  state.counters["iterations"] = Median(iterations);
  state.counters["inliers"] = Median(inliers);
}

// Pair (1,2)'s inliers in normalised coordinates and the pose to refine: the RANSAC's model before
// estimate_relative_pose's own final refinement (bundle.max_iterations = 0), as trigrav's bundle
// adjustment starts from its RANSAC's estimate.
struct RefinementProblem {
  std::vector<poselib::Point2D> x1, x2;
  poselib::CameraPose cam2_from_cam1;
  ThreeViewPose ground_truth;
};

// PoseLib's refine_relpose (Sampson error, its default Cauchy loss at 1 px) as
// estimate_relative_pose calls it, on pair (1,2)'s inliers of each scene in turn.
void BM_RefineRelpose(benchmark::State& state) {
  const std::vector<PoseLibScene> scenes = ToPoseLibScenes(static_cast<int>(state.range(0)));
  poselib::RelativePoseOptions options = Options(20);
  options.bundle.max_iterations = 0;
  std::vector<RefinementProblem> problems;
  for (const PoseLibScene& scene : scenes) {
    RefinementProblem problem;
    std::vector<char> inliers;
    EstimatePair(scene, 1, options, &problem.cam2_from_cam1, &inliers);
    for (std::size_t n = 0; n < inliers.size(); ++n) {
      if (!inliers[n]) continue;
      poselib::Point2D x1, x2;
      scene.cameras[0].unproject(scene.pixels[0][n], &x1);
      scene.cameras[1].unproject(scene.pixels[1][n], &x2);
      problem.x1.push_back(x1);
      problem.x2.push_back(x2);
    }
    problem.ground_truth = scene.ground_truth;
    problems.push_back(problem);
  }
  // estimate_relative_pose scales the loss from pixels to normalised coordinates by the mean of
  // 1 / focal length of the two cameras.
  poselib::BundleOptions bundle;
  bundle.loss_scale *=
      0.5 * (1.0 / scenes[0].cameras[0].focal() + 1.0 / scenes[0].cameras[1].focal());
  std::vector<double> iterations, inliers, rotation_deg, translation_deg;
  for (const RefinementProblem& problem : problems) {
    poselib::CameraPose cam2_from_cam1 = problem.cam2_from_cam1;
    const poselib::BundleStats stats =
        poselib::refine_relpose(problem.x1, problem.x2, &cam2_from_cam1, bundle);
    const CameraPose& truth = problem.ground_truth.cam2_from_cam1;
    rotation_deg.push_back(RotationErrorDeg(truth.R, cam2_from_cam1.R()));
    translation_deg.push_back(DirectionErrorDeg(truth.Center(), cam2_from_cam1.center()));
    iterations.push_back(stats.iterations);
    inliers.push_back(problem.x1.size());
  }
  std::size_t i = 0;
  for (auto _ : state) {
    const RefinementProblem& problem = problems[i++ % problems.size()];
    poselib::CameraPose cam2_from_cam1 = problem.cam2_from_cam1;
    benchmark::DoNotOptimize(
        poselib::refine_relpose(problem.x1, problem.x2, &cam2_from_cam1, bundle).cost);
  }
  state.counters["rot_deg"] = Median(rotation_deg);
  state.counters["trans_deg"] = Median(translation_deg);
  state.counters["iterations"] = Median(iterations);
  state.counters["inliers"] = Median(inliers);
}

}  // namespace

void RegisterPoseLibRobustBenchmarks() {
  for (const auto& [name, min_iterations] :
       {std::pair<const char*, std::size_t>{"min_iterations_20", 20}, {"defaults", 0}}) {
    benchmark::RegisterBenchmark((std::string("BM_PoseLib/estimate_relative_pose/") + name).c_str(),
                                 [min_iterations = min_iterations](benchmark::State& state) {
                                   BM_EstimateRelativePose(state, min_iterations);
                                 })
        ->Arg(375)
        ->Arg(875)
        ->Unit(benchmark::kMillisecond)
        ->MinTime(1.0);
  }
  benchmark::RegisterBenchmark("BM_PoseLib/refine_relpose", BM_RefineRelpose)
      ->Arg(375)
      ->Arg(875)
      ->Unit(benchmark::kMillisecond)
      ->MinTime(1.0);
}

}  // namespace trigrav::benchmarks
