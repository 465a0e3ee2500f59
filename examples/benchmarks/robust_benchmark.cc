// Time of a whole robust estimate (EstimateThreeViewPoseRobust: RANSAC with local optimisation,
// every method scored by the same three-view reprojection error) of every solver of kInitialSolvers
// on the robust benchmark's scenes (robust_benchmark_scenes.h: 500 triplets with 30 % outliers and
// 0.5 px noise, f = 500 px, 1.5 px threshold, 20 scenes). Counters over the first pass through the
// scenes: median rotation / translation error (deg, views 2 and 3 pooled, a failure counting as
// 180 deg) and the median number of RANSAC iterations.
//
//   robust_benchmark

#include <benchmark/benchmark.h>

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

void BM_RobustEstimate(benchmark::State& state, trigrav::InitialSolver solver) {
  std::vector<trigrav::ThreeViewObservations> observations;
  for (const trigrav::SyntheticScene& scene : Scenes()) {
    observations.push_back(trigrav::ToObservations(scene));
  }
  trigrav::RobustThreeViewOptions options;
  options.solver = solver;
  options.ransac.max_error = trigrav::kRobustBenchmarkThresholdPx;
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
        errors.Add(trigrav::ComputeThreeViewPoseErrors(Scenes()[p].ground_truth, estimate.pose));
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
