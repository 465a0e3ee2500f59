// Time of a whole robust estimate (RANSAC + local optimisation, every method scored by the same
// three-view reprojection error) on 500 triplets with 30 % outliers and 0.5 px noise, f = 500 px.
// Counters: median rotation / translation error (deg, pooled over views 2 and 3) and the median
// number of RANSAC iterations over a pool of 20 problems. Run: ./build/examples/robust_benchmark

#include <benchmark/benchmark.h>

#include <vector>

#include "pooled_errors.h"
#include "robust_benchmark_problems.h"
#include "trigrav/evaluation/pose_errors.h"
#include "trigrav/evaluation/statistics.h"
#include "trigrav/initializers/robust_three_view.h"
#include "trigrav/evaluation/synthetic_scene.h"

namespace {

const std::vector<trigrav::SyntheticScene>& Problems() {
  static const std::vector<trigrav::SyntheticScene> problems =
      trigrav::examples::RobustBenchmarkScenes();
  return problems;
}

void BM_RobustEstimate(benchmark::State& state, trigrav::InitialSolver solver) {
  std::vector<trigrav::ThreeViewObservations> observations;
  for (const trigrav::SyntheticScene& scene : Problems()) {
    observations.push_back(trigrav::ToObservations(scene));
  }
  trigrav::RobustThreeViewOptions options;
  options.solver = solver;
  options.ransac.max_error = trigrav::examples::kRobustBenchmarkThresholdPx;
  trigrav::examples::PooledErrors errors;  // of the first pass over the problems
  std::vector<double> iterations;
  std::size_t i = 0;
  for (auto _ : state) {
    const std::size_t p = i++ % observations.size();
    const trigrav::RobustThreeViewEstimate estimate =
        trigrav::EstimateThreeViewPoseRobust(observations[p], options);
    benchmark::DoNotOptimize(estimate.num_inliers);
    if (iterations.size() < observations.size()) {
      if (estimate.success) {
        errors.Add(trigrav::ComputeThreeViewPoseErrors(Problems()[p].ground_truth, estimate.pose));
      } else {
        errors.AddFailure();
      }
      iterations.push_back(estimate.iterations);
    }
  }
  state.counters["rot_deg"] = trigrav::Median(errors.rotation_deg);
  state.counters["trans_deg"] = trigrav::Median(errors.translation_deg);
  state.counters["iterations"] = trigrav::Median(iterations);
}

}  // namespace

BENCHMARK_CAPTURE(BM_RobustEstimate, 3pt, trigrav::InitialSolver::kTrifocal3pt)
    ->Unit(benchmark::kMillisecond)
    ->MinTime(1.0);
BENCHMARK_CAPTURE(BM_RobustEstimate, 3pt_sextic, trigrav::InitialSolver::kTrifocal3ptSextic)
    ->Unit(benchmark::kMillisecond)
    ->MinTime(1.0);
BENCHMARK_CAPTURE(BM_RobustEstimate, 4pt, trigrav::InitialSolver::kTrifocal4pt)
    ->Unit(benchmark::kMillisecond)
    ->MinTime(1.0);
BENCHMARK_CAPTURE(BM_RobustEstimate, 7pt_linear, trigrav::InitialSolver::kTrifocalLinear)
    ->Unit(benchmark::kMillisecond)
    ->MinTime(1.0);
BENCHMARK_CAPTURE(BM_RobustEstimate, 5pt, trigrav::InitialSolver::kEssential5pt)
    ->Unit(benchmark::kMillisecond)
    ->MinTime(1.0);
BENCHMARK_CAPTURE(BM_RobustEstimate, 8pt, trigrav::InitialSolver::kEssential8pt)
    ->Unit(benchmark::kMillisecond)
    ->MinTime(1.0);

BENCHMARK_MAIN();
