// Time of a whole robust estimate (EstimateThreeViewPoseRobust: RANSAC with local optimisation,
// every method scored by the same three-view reprojection error) of every solver of kInitialSolvers
// on the robust benchmark's scenes (robust_benchmark_scenes.h: 500 triplets with 30 % outliers and
// 0.5 px noise, f = 500 px, 1.5 px threshold, 20 scenes). Counters over the first pass through the
// scenes: median rotation / translation error (deg, views 2 and 3 pooled, a failure counting as
// 180 deg) and the median number of RANSAC iterations. BM_RobustEstimateIssueScenes/3pt/<n>: the
// 3-point method on scenes like initialize_and_refine_synthetic's default (1 px noise, 20 %
// outliers, threshold 2 px, f = 500 px, 20 scenes from seed 2026) with n = 375 and 875 triplets.
//
//   robust_benchmark

#include <benchmark/benchmark.h>

#include <random>
#include <string>
#include <vector>

#include "trigrav/evaluation/pooled_errors.h"
#include "trigrav/evaluation/pose_errors.h"
#include "trigrav/evaluation/robust_benchmark_scenes.h"
#include "trigrav/evaluation/statistics.h"
#include "trigrav/evaluation/synthetic_scene.h"
#include "trigrav/initializers/initial_solver.h"
#include "trigrav/initializers/robust_three_view.h"

namespace {

const std::vector<trigrav::SyntheticScene>& Scenes() {
  static const std::vector<trigrav::SyntheticScene> scenes = trigrav::RobustBenchmarkScenes();
  return scenes;
}

// 20 scenes from seed 2026 of `num_points` triplets, 1 px noise and 20 % outliers.
std::vector<trigrav::SyntheticScene> IssueScenes(int num_points) {
  trigrav::SyntheticSceneOptions options;
  options.num_points = num_points;
  options.pixel_noise_px = 1.0;
  options.outlier_ratio = 0.2;
  std::mt19937_64 rng(trigrav::kRobustBenchmarkSeed);
  std::vector<trigrav::SyntheticScene> scenes;
  for (int i = 0; i < trigrav::kRobustBenchmarkScenes; ++i) {
    scenes.push_back(trigrav::GenerateSyntheticScene(options, &rng));
  }
  return scenes;
}

// Times EstimateThreeViewPoseRobust over the scenes in turn at the inlier threshold.
void TimeRobustEstimate(benchmark::State& state,
                        const std::vector<trigrav::SyntheticScene>& scenes,
                        trigrav::InitialSolver solver,
                        double threshold_px) {
  std::vector<trigrav::ThreeViewObservations> observations;
  for (const trigrav::SyntheticScene& scene : scenes) {
    observations.push_back(trigrav::ToObservations(scene));
  }
  trigrav::RobustThreeViewOptions options;
  options.solver = solver;
  options.ransac.max_error = threshold_px;
  trigrav::PooledErrors errors;  // of the first pass over the scenes
  std::vector<double> iterations;
  std::size_t i = 0;
  for (auto _ : state) {
    const std::size_t p = i++ % observations.size();
    const trigrav::RobustThreeViewEstimate estimate =
        trigrav::EstimateThreeViewPoseRobust(observations[p], options);
    benchmark::DoNotOptimize(estimate.ransac.num_inliers);
    if (iterations.size() < observations.size()) {
      if (estimate.success) {
        errors.Add(trigrav::ComputeThreeViewPoseErrors(scenes[p].ground_truth, estimate.pose));
      } else {
        errors.AddFailure();
      }
      iterations.push_back(estimate.ransac.iterations);
    }
  }
  state.counters["rot_deg"] = trigrav::Median(errors.rotation_deg);
  state.counters["trans_deg"] = trigrav::Median(errors.translation_deg);
  state.counters["iterations"] = trigrav::Median(iterations);
}

void BM_RobustEstimate(benchmark::State& state, trigrav::InitialSolver solver) {
  TimeRobustEstimate(state, Scenes(), solver, trigrav::kRobustBenchmarkThresholdPx);
}

void BM_RobustEstimateIssueScenes(benchmark::State& state) {
  TimeRobustEstimate(state, IssueScenes(static_cast<int>(state.range(0))),
                     trigrav::InitialSolver::kTrifocal3pt, 2.0);
}

BENCHMARK(BM_RobustEstimateIssueScenes)
    ->Name("BM_RobustEstimateIssueScenes/3pt")
    ->Arg(375)
    ->Arg(875)
    ->Unit(benchmark::kMillisecond)
    ->MinTime(1.0);

}  // namespace

int main(int argc, char** argv) {
  for (const trigrav::InitialSolver solver : trigrav::kInitialSolvers) {
    benchmark::RegisterBenchmark(
        (std::string("BM_RobustEstimate/") + trigrav::InitialSolverName(solver)).c_str(),
        [solver](benchmark::State& state) { BM_RobustEstimate(state, solver); })
        ->Unit(benchmark::kMillisecond)
        ->MinTime(1.0);
  }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
