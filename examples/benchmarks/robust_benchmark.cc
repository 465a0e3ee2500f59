// Time of a whole robust estimate (EstimateThreeViewPoseRobust: RANSAC with local optimisation,
// every method scored by the same three-view reprojection error) of every solver of kInitialSolvers
// on the robust benchmark's scenes (robust_benchmark_scenes.h: 500 triplets with 30 % outliers and
// 0.5 px noise, f = 500 px, 1.5 px threshold, 20 scenes). Counters over the first pass through the
// scenes: median rotation / translation error (deg, views 2 and 3 pooled, a failure counting as
// 180 deg) and the median number of RANSAC iterations (ransac_iterations: a counter named
// iterations would replace Google Benchmark's own in its JSON output).
// On scenes like initialize_and_refine_synthetic's default (IssueScenes: 1 px noise, 20 % outliers,
// threshold 2 px, f = 500 px, 20 scenes from seed 2026, n = 375 and 875 triplets):
//  - BM_RobustEstimateIssueScenes/3pt/<n>: the 3-point robust estimate;
//    .../3pt_without_gravity_check/<n>: the same without the gravity-free comparison after a
//    success (RobustThreeViewOptions::check_gravity_after_success = false);
//  - BM_InitializeAndRefine/<raw|engine>/<n>: InitializeAndRefine (3pt RANSAC, yaw-only
//    refinement with one re-classification round): RANSAC only ("raw"), or refined by each engine
//    (EngineName: ceres, ceres_points_eliminated); counters are per-call medians of the
//    stages (ms, ThreeViewEstimateTimings, wall clock), of the inliers, of the refinement runs and
//    of the last run's iterations; ransac_cpu_ms and refinement_cpu_ms, in CPU time like the time
//    per call and means per call like it: each stage's wall-clock time scaled by the call's
//    process CPU time (std::clock) over its wall-clock time (exact when the process is not
//    preempted); rot_deg and trans_deg of the answer (`refined`), medians over the first pass
//    through the scenes as above.
// Built with PoseLib, BM_PoseLib/... times its two-pair estimate_relative_pose and its refinement
// on the same scenes (poselib_benchmarks.h).
//
//   robust_benchmark
//   robust_benchmark --benchmark_filter=InitializeAndRefine --benchmark_repetitions=5
//       --benchmark_enable_random_interleaving=true   (one line)

#include <benchmark/benchmark.h>

#include <chrono>
#include <ctime>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "common/pooled_errors.h"
#include "common/robust_benchmark_scenes.h"
#include "issue_scenes.h"
#include "poselib_benchmarks.h"
#include "trigrav/ba/initialize_and_refine.h"
#include "trigrav/evaluation/pose_errors.h"
#include "trigrav/evaluation/statistics.h"
#include "trigrav/evaluation/synthetic_scene.h"
#include "trigrav/initializers/initial_solver.h"
#include "trigrav/initializers/robust_three_view.h"

namespace {

const std::vector<trigrav::SyntheticScene>& Scenes() {
  static const std::vector<trigrav::SyntheticScene> scenes = trigrav::RobustBenchmarkScenes();
  return scenes;
}

using trigrav::benchmarks::IssueScenes;

// Times EstimateThreeViewPoseRobust over the scenes in turn at the inlier threshold.
void TimeRobustEstimate(benchmark::State& state,
                        const std::vector<trigrav::SyntheticScene>& scenes,
                        trigrav::InitialSolver solver,
                        double threshold_px,
                        bool check_gravity_after_success = true) {
  std::vector<trigrav::ThreeViewObservations> observations;
  for (const trigrav::SyntheticScene& scene : scenes) {
    observations.push_back(trigrav::ToObservations(scene));
  }
  trigrav::RobustThreeViewOptions options;
  options.solver = solver;
  options.ransac.max_error = threshold_px;
  options.check_gravity_after_success = check_gravity_after_success;
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
  state.counters["ransac_iterations"] = trigrav::Median(iterations);
}

void BM_RobustEstimate(benchmark::State& state, trigrav::InitialSolver solver) {
  TimeRobustEstimate(state, Scenes(), solver, trigrav::kRobustBenchmarkThresholdPx);
}

void BM_RobustEstimateIssueScenes(benchmark::State& state, bool check_gravity_after_success) {
  TimeRobustEstimate(state, IssueScenes(static_cast<int>(state.range(0))),
                     trigrav::InitialSolver::kTrifocal3pt,
                     trigrav::benchmarks::kIssueScenesThresholdPx, check_gravity_after_success);
}

BENCHMARK_CAPTURE(BM_RobustEstimateIssueScenes, 3pt, true)
    ->Arg(375)
    ->Arg(875)
    ->Unit(benchmark::kMillisecond)
    ->MinTime(1.0);
BENCHMARK_CAPTURE(BM_RobustEstimateIssueScenes, 3pt_without_gravity_check, false)
    ->Arg(375)
    ->Arg(875)
    ->Unit(benchmark::kMillisecond)
    ->MinTime(1.0);

// The refinement's engine; none for the raw stage.
using Refinement = std::optional<trigrav::ThreeViewBundleAdjustmentOptions::Engine>;

void BM_InitializeAndRefine(benchmark::State& state, Refinement refinement) {
  const std::vector<trigrav::SyntheticScene>& synthetic =
      IssueScenes(static_cast<int>(state.range(0)));
  std::vector<trigrav::ThreeViewObservations> scenes;
  for (const trigrav::SyntheticScene& scene : synthetic) {
    scenes.push_back(trigrav::ToObservations(scene));
  }
  trigrav::InitializeAndRefineOptions options;
  options.refine = refinement.has_value();
  if (refinement) options.bundle_adjustment.engine = *refinement;
  std::vector<double> ransac, build, solve, reclassification, refine, inliers, runs, iterations;
  trigrav::PooledErrors errors;                         // of the first pass over the scenes
  double ransac_cpu_ms = 0.0, refinement_cpu_ms = 0.0;  // sums over the calls
  std::size_t i = 0;
  for (auto _ : state) {
    const std::size_t p = i++ % scenes.size();
    options.robust.ransac.seed = p;
    const auto wall_start = std::chrono::steady_clock::now();
    const std::clock_t cpu_start = std::clock();
    const trigrav::ThreeViewEstimate estimate = trigrav::InitializeAndRefine(scenes[p], options);
    const double cpu_ms = 1e3 * static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
    const double wall_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
    benchmark::DoNotOptimize(estimate.num_inliers);
    const trigrav::ThreeViewEstimateTimings& t = estimate.timings;
    if (wall_s > 0.0) {  // each stage's wall-clock time at the call's CPU / wall ratio
      ransac_cpu_ms += cpu_ms * t.ransac_s / wall_s;
      refinement_cpu_ms += cpu_ms * t.refinement_s / wall_s;
    }
    ransac.push_back(1e3 * t.ransac_s);
    build.push_back(1e3 * t.build_s);
    solve.push_back(1e3 * t.solve_s);
    reclassification.push_back(1e3 * t.reclassification_s);
    refine.push_back(1e3 * t.refinement_s);
    inliers.push_back(estimate.num_inliers);
    runs.push_back(estimate.refinement_runs);
    iterations.push_back(estimate.refinement.summary.Iterations());
    if (i <= scenes.size()) {
      if (estimate.success) {
        errors.Add(
            trigrav::ComputeThreeViewPoseErrors(synthetic[p].ground_truth, estimate.refined));
      } else {
        errors.AddFailure();
      }
    }
  }
  state.counters["ransac_ms"] = trigrav::Median(ransac);
  state.counters["build_ms"] = trigrav::Median(build);
  state.counters["solve_ms"] = trigrav::Median(solve);
  state.counters["reclassify_ms"] = trigrav::Median(reclassification);
  state.counters["refinement_ms"] = trigrav::Median(refine);
  state.counters["ransac_cpu_ms"] =
      benchmark::Counter(ransac_cpu_ms, benchmark::Counter::kAvgIterations);
  state.counters["refinement_cpu_ms"] =
      benchmark::Counter(refinement_cpu_ms, benchmark::Counter::kAvgIterations);
  state.counters["inliers"] = trigrav::Median(inliers);
  state.counters["runs"] = trigrav::Median(runs);
  if (refinement) state.counters["last_run_iterations"] = trigrav::Median(iterations);
  state.counters["rot_deg"] = trigrav::Median(errors.rotation_deg);
  state.counters["trans_deg"] = trigrav::Median(errors.translation_deg);
}

}  // namespace

int main(int argc, char** argv) {
  using Engine = trigrav::ThreeViewBundleAdjustmentOptions::Engine;
  const std::pair<std::string, Refinement> refinements[] = {
      {"raw", std::nullopt},
      {trigrav::EngineName(Engine::kCeres), Engine::kCeres},
      {trigrav::EngineName(Engine::kCeresPointsEliminated), Engine::kCeresPointsEliminated}};
  for (const auto& [name, refinement] : refinements) {
    benchmark::RegisterBenchmark(("BM_InitializeAndRefine/" + name).c_str(),
                                 [refinement = refinement](benchmark::State& state) {
                                   BM_InitializeAndRefine(state, refinement);
                                 })
        ->Arg(375)
        ->Arg(875)
        ->Unit(benchmark::kMillisecond)
        ->MinTime(1.0);
  }
  for (const trigrav::InitialSolver solver : trigrav::kInitialSolvers) {
    benchmark::RegisterBenchmark(
        (std::string("BM_RobustEstimate/") + trigrav::InitialSolverName(solver)).c_str(),
        [solver](benchmark::State& state) { BM_RobustEstimate(state, solver); })
        ->Unit(benchmark::kMillisecond)
        ->MinTime(1.0);
  }
#ifdef TRIGRAV_WITH_POSELIB
  trigrav::benchmarks::RegisterPoseLibRobustBenchmarks();
#endif
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
