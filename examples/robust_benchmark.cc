// Time of a whole robust estimate (RANSAC + local optimisation, every method scored by the same
// three-view reprojection error) on 500 triplets with 30 % outliers and 0.5 px noise, f = 500 px.
// Counters: median rotation / translation error (deg, pooled over views 2 and 3) and the median
// number of RANSAC iterations over a pool of 20 problems. Run: ./build/examples/robust_benchmark

#include <benchmark/benchmark.h>

#include <algorithm>
#include <random>
#include <vector>

#include "trigrav/initializers/pose_metrics.h"
#include "trigrav/initializers/robust_three_view.h"
#include "trigrav/initializers/synthetic_scene.h"

namespace {

constexpr int kNumProblems = 20;
constexpr double kThresholdPx = 1.5;  // 3 sigma at 0.5 px

const std::vector<trigrav::SyntheticScene>& Problems() {
  static const std::vector<trigrav::SyntheticScene> problems = [] {
    std::mt19937_64 rng(2026);
    trigrav::SyntheticSceneOptions options;
    options.num_points = 500;
    options.pixel_noise_px = 0.5;
    options.outlier_ratio = 0.3;
    std::vector<trigrav::SyntheticScene> scenes;
    for (int i = 0; i < kNumProblems; ++i)
      scenes.push_back(trigrav::GenerateSyntheticScene(options, &rng));
    return scenes;
  }();
  return problems;
}

void BM_RobustEstimate(benchmark::State& state, trigrav::InitialSolver solver) {
  std::vector<trigrav::ThreeViewObservations> observations;
  for (const trigrav::SyntheticScene& scene : Problems()) {
    observations.push_back(trigrav::ToObservations(scene));
  }
  trigrav::RobustThreeViewOptions options;
  options.solver = solver;
  options.ransac.max_error = kThresholdPx;
  std::vector<double> rotation_errors, translation_errors, iterations;
  std::size_t i = 0;
  for (auto _ : state) {
    const std::size_t p = i++ % observations.size();
    const trigrav::RobustThreeViewEstimate estimate =
        trigrav::EstimateThreeViewPoseRobust(observations[p], options);
    benchmark::DoNotOptimize(estimate.num_inliers);
    if (rotation_errors.size() < 2 * observations.size()) {
      const trigrav::ThreeViewPoseErrors e =
          trigrav::ComputeThreeViewPoseErrors(Problems()[p].ground_truth, estimate.pose);
      for (int k = 0; k < 2; ++k) {
        rotation_errors.push_back(estimate.success ? e.rotation_deg[k] : 180.0);
        translation_errors.push_back(estimate.success ? e.translation_deg[k] : 180.0);
      }
      iterations.push_back(estimate.iterations);
    }
  }
  state.counters["rot_deg"] = trigrav::Median(rotation_errors);
  state.counters["trans_deg"] = trigrav::Median(translation_errors);
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
