// trigrav side by side with OpenCV's and OpenGV's five-point RANSAC, in one run on the same
// instances and with the same error metrics (trigrav::ComputeThreeViewPoseErrors: rotation and
// camera-centre direction of views 2 and 3, pooled; a failed estimate counts as 180 deg):
//   (a) minimal-solver time per call (noise-free scenes; median over timed passes, one thread),
//   (b) robust estimates on robust_benchmark's problems: 500 triplets, 30 % outliers, 0.5 px noise,
//       1.5 px threshold, f = 500 px (time: median over problems of the median over repetitions,
//       one thread),
//   (c) accuracy at 1 px: scenes of 100 triplets with 30 % outliers, every trigrav method raw and
//       refined (InitializeAndRefine, yaw-only) against each peer (on --threads threads; no times
//       reported).
// Each comparison is also printed as ratios trigrav / peer (< 1: trigrav faster or more accurate).
// Tables are markdown. The KITTI rows of the peers come from kitti_triplets --peers
// (examples/kitti/).
//
//   peer_comparison   # the README's run
//   peer_comparison --solver_problems=100 --robust_repetitions=1 --accuracy_scenes=10  # smoke test

#include <gflags/gflags.h>
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <iostream>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "../common/thread_note.h"
#include "common/pooled_errors.h"
#include "common/require_flag.h"
#include "common/robust_benchmark_scenes.h"
#include "common/tool_flags.h"
#include "peer_estimators.h"
#include "trigrav/evaluation/pose_errors.h"
#include "trigrav/evaluation/statistics.h"
#include "trigrav/evaluation/synthetic_scene.h"
#include "trigrav/initializers/parallel_for.h"

DEFINE_int32(solver_problems, 1000, "(a) Noise-free problems for the minimal solvers.");
DEFINE_int32(solver_passes, 21, "(a) Timed passes over the problems; the median pass counts.");
DEFINE_int32(robust_problems,
             trigrav::kRobustBenchmarkScenes,
             "(b) Problems (the default: robust_benchmark's).");
DEFINE_int32(robust_repetitions, 5, "(b) Timed runs of each estimate; the median counts.");
DEFINE_uint64(robust_seed,
              trigrav::kRobustBenchmarkSeed,
              "(b) Seed of the problems (the default: robust_benchmark's).");
DEFINE_int32(accuracy_scenes, 300, "(c) Scenes.");
DEFINE_int32(accuracy_points, 100, "(c) Triplets per scene.");
DEFINE_double(accuracy_noise_px, 1.0, "(c) Image noise sigma in pixels.");
DEFINE_double(accuracy_outlier_ratio, 0.3, "(c) Fraction of outlier triplets.");
DEFINE_double(accuracy_threshold_px, 3.0, "(c) Inlier threshold in pixels (3 sigma).");
DEFINE_uint64(seed, 1, "Seed of the (a) and (c) scenes (the same scenes for every estimator).");
DEFINE_int32(threads, 2, "(c) Worker threads; (a) and (b) always time on one thread.");

namespace {

using trigrav::peers::EstimatorResult;
using trigrav::peers::MinimalProblem;
using trigrav::peers::NamedEstimator;
using trigrav::peers::NamedMinimalSolver;

double NowSeconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// CPU time of the whole process: on a shared machine it counts only the work done, not the time
// waiting for a core, and it includes any thread a peer might start.
double ProcessCpuSeconds() {
  timespec time;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &time);
  return time.tv_sec + 1e-9 * time.tv_nsec;
}

// CPU and wall time of one timed stretch.
struct Stopwatch {
  double cpu_start = ProcessCpuSeconds();
  double wall_start = NowSeconds();
  double CpuSeconds() const { return ProcessCpuSeconds() - cpu_start; }
  double WallSeconds() const { return NowSeconds() - wall_start; }
};

// The 1-minute load average, to report how busy the machine was while timing.
std::string LoadAverage() {
  std::ifstream file("/proc/loadavg");
  std::string one_minute;
  file >> one_minute;
  return one_minute.empty() ? "unknown" : one_minute;
}

// Prints a markdown table of ratios: one row per trigrav entry, one column per peer.
void PrintRatios(const std::string& title,
                 const std::vector<std::string>& rows,
                 const std::vector<std::string>& columns,
                 const std::function<std::string(std::size_t, std::size_t)>& cell) {
  std::printf("\n%s\n\n| trigrav \\ peer |", title.c_str());
  for (const std::string& column : columns) std::printf(" %s |", column.c_str());
  std::printf("\n|---|");
  for (std::size_t c = 0; c < columns.size(); ++c) std::printf("---|");
  std::printf("\n");
  for (std::size_t r = 0; r < rows.size(); ++r) {
    std::printf("| %s |", rows[r].c_str());
    for (std::size_t c = 0; c < columns.size(); ++c) std::printf(" %s |", cell(r, c).c_str());
    std::printf("\n");
  }
}

std::string Format(const char* format, double a, double b = 0.0, double c = 0.0) {
  char text[64];
  std::snprintf(text, sizeof(text), format, a, b, c);
  return text;
}

// "<name> <stage>" of each estimator, e.g. "3pt yaw-only", "opencv-ransac raw".
std::vector<std::string> Names(const std::vector<NamedEstimator>& estimators) {
  std::vector<std::string> names;
  for (const NamedEstimator& e : estimators) names.push_back(e.name + " " + e.stage);
  return names;
}

void PrintDescriptions(const std::vector<NamedEstimator>& estimators) {
  for (const NamedEstimator& e : estimators) {
    std::printf("- `%s` %s: %s\n", e.name.c_str(), e.stage.c_str(), e.description.c_str());
  }
}

// ---------------------------------------------------------------------------------------------
// (a) Minimal solvers.

struct SolverTiming {
  double cpu_ns_per_call = 0.0;  // medians over the passes
  double wall_ns_per_call = 0.0;
  double truth_found = 0.0;  // fraction of problems
  double solutions = 0.0;    // mean number of solutions
};

std::vector<SolverTiming> TimeMinimalSolvers(const std::vector<NamedMinimalSolver>& solvers,
                                             const std::vector<MinimalProblem>& problems) {
  std::vector<trigrav::peers::PreparedMinimalSolver> prepared;
  std::vector<SolverTiming> timings(solvers.size());
  for (std::size_t s = 0; s < solvers.size(); ++s) {
    prepared.push_back(solvers[s].prepare(problems));
    int found = 0;
    long solutions = 0;
    for (std::size_t i = 0; i < problems.size(); ++i) {
      found += prepared[s].truth_found(i) ? 1 : 0;
      solutions += prepared[s].solve(i);
    }
    timings[s].truth_found = static_cast<double>(found) / problems.size();
    timings[s].solutions = static_cast<double>(solutions) / problems.size();
  }
  // Passes interleave the solvers, so that a burst of load hits all of them alike.
  std::vector<std::vector<double>> cpu_ns(solvers.size()), wall_ns(solvers.size());
  static volatile long sink = 0;  // keeps the calls observable
  for (int pass = 0; pass < FLAGS_solver_passes; ++pass) {
    for (std::size_t s = 0; s < solvers.size(); ++s) {
      const Stopwatch stopwatch;
      for (std::size_t i = 0; i < problems.size(); ++i) sink += prepared[s].solve(i);
      cpu_ns[s].push_back(stopwatch.CpuSeconds() * 1e9 / problems.size());
      wall_ns[s].push_back(stopwatch.WallSeconds() * 1e9 / problems.size());
    }
  }
  for (std::size_t s = 0; s < solvers.size(); ++s) {
    timings[s].cpu_ns_per_call = trigrav::Median(cpu_ns[s]);
    timings[s].wall_ns_per_call = trigrav::Median(wall_ns[s]);
  }
  return timings;
}

void RunMinimalSolvers() {
  const std::vector<NamedMinimalSolver> trigrav_solvers = trigrav::peers::TrigravMinimalSolvers();
  const std::vector<NamedMinimalSolver> peer_solvers = trigrav::peers::PeerMinimalSolvers();
  std::vector<NamedMinimalSolver> all = trigrav_solvers;
  all.insert(all.end(), peer_solvers.begin(), peer_solvers.end());
  const std::vector<MinimalProblem> problems =
      trigrav::peers::MakeMinimalProblems(FLAGS_solver_problems, FLAGS_seed);
  const std::string load_before = LoadAverage();
  const std::vector<SolverTiming> timings = TimeMinimalSolvers(all, problems);
  std::printf(
      "\n## (a) Minimal solvers: time per call\n\n%d noise-free scenes, %d passes, median "
      "pass; one thread; CPU time of the process (wall time for reference); load average %s "
      "before, %s after. \"truth found\": share of "
      "scenes with the true pose (or essential matrix) among the solutions. OpenCV has no "
      "public minimal-solver call.\n\n",
      FLAGS_solver_problems, FLAGS_solver_passes, load_before.c_str(), LoadAverage().c_str());
  std::printf(
      "| method | CPU ns per call | wall ns per call | solutions (mean) | truth found | one call "
      "computes |\n|---|---|---|---|---|---|\n");
  for (std::size_t s = 0; s < all.size(); ++s) {
    std::printf("| %s | %.0f | %.0f | %.2f | %.1f %% | %s |\n", all[s].name.c_str(),
                timings[s].cpu_ns_per_call, timings[s].wall_ns_per_call, timings[s].solutions,
                100.0 * timings[s].truth_found, all[s].description.c_str());
  }
  if (peer_solvers.empty()) return;
  std::vector<std::string> rows, columns;
  for (const NamedMinimalSolver& s : trigrav_solvers) rows.push_back(s.name);
  for (const NamedMinimalSolver& s : peer_solvers) columns.push_back(s.name);
  PrintRatios(
      "CPU time ratio trigrav / peer (per call; a three-view estimate from pairs needs two "
      "five-point calls, one per pair):",
      rows, columns, [&](std::size_t r, std::size_t c) {
        return Format("%.2f", timings[r].cpu_ns_per_call /
                                  timings[trigrav_solvers.size() + c].cpu_ns_per_call);
      });
}

// ---------------------------------------------------------------------------------------------
// Errors of one estimator over many problems.

struct Errors {
  // 180 deg and scale error +inf for a failure; scale error +inf when the scale is unknown.
  trigrav::PooledErrors pooled;
  std::vector<double> inliers;
  std::vector<double> cpu_seconds, wall_seconds;  // per problem, when timed
  int failures = 0;

  void Add(const trigrav::ThreeViewPose& truth, const EstimatorResult& result) {
    inliers.push_back(result.ransac.num_inliers);
    if (!result.success) {
      ++failures;
      pooled.AddFailure();
      return;
    }
    trigrav::ThreeViewPoseErrors e = trigrav::ComputeThreeViewPoseErrors(truth, result.pose);
    if (!result.relative_scale_known) e.relative_scale = std::numeric_limits<double>::infinity();
    pooled.Add(e);
  }
};

void PrintErrorTable(const std::vector<NamedEstimator>& estimators,
                     const std::vector<Errors>& errors,
                     bool with_time) {
  std::printf(
      "\n| method | stage |%s rotation (deg) | translation (deg) | \\|log scale\\| | inliers | "
      "failures |\n|---|---|%s---|---|---|---|---|\n",
      with_time ? " CPU ms per estimate | wall ms |" : "", with_time ? "---|---|" : "");
  for (std::size_t e = 0; e < estimators.size(); ++e) {
    std::printf("| %s | %s |", estimators[e].name.c_str(), estimators[e].stage.c_str());
    if (with_time) {
      std::printf(" %.2f | %.2f |", 1e3 * trigrav::Median(errors[e].cpu_seconds),
                  1e3 * trigrav::Median(errors[e].wall_seconds));
    }
    const trigrav::PooledErrors& pooled = errors[e].pooled;
    std::printf(" %.4f | %.4f | %.4f | %.0f | %d |\n", trigrav::Median(pooled.rotation_deg),
                trigrav::Median(pooled.translation_deg), trigrav::Median(pooled.relative_scale),
                trigrav::Median(errors[e].inliers), errors[e].failures);
  }
}

// ---------------------------------------------------------------------------------------------
// (b) Robust estimates, timed.

void RunRobust() {
  const std::vector<trigrav::SyntheticScene> scenes =
      trigrav::RobustBenchmarkScenes(FLAGS_robust_problems, FLAGS_robust_seed);
  std::vector<trigrav::ThreeViewObservations> observations;
  for (const trigrav::SyntheticScene& scene : scenes)
    observations.push_back(trigrav::ToObservations(scene));
  const trigrav::SyntheticSceneOptions options = trigrav::RobustBenchmarkSceneOptions();
  constexpr double kThresholdPx = trigrav::kRobustBenchmarkThresholdPx;
  const std::vector<NamedEstimator> trigrav_estimators = trigrav::peers::TrigravRobustEstimators();
  const std::vector<NamedEstimator> peers = trigrav::peers::PeerEstimators();
  std::vector<NamedEstimator> all = trigrav_estimators;
  all.insert(all.end(), peers.begin(), peers.end());

  // Repetitions interleave the estimators and problems; errors come from the first repetition
  // (every estimator is deterministic).
  const std::string load_before = LoadAverage();
  using Runs = std::vector<std::vector<std::vector<double>>>;  // [estimator][problem][run]
  Runs cpu(all.size(), std::vector<std::vector<double>>(scenes.size()));
  Runs wall = cpu;
  std::vector<Errors> errors(all.size());
  for (int rep = 0; rep < FLAGS_robust_repetitions; ++rep) {
    for (std::size_t p = 0; p < scenes.size(); ++p) {
      for (std::size_t e = 0; e < all.size(); ++e) {
        const Stopwatch stopwatch;
        const EstimatorResult result = all[e].estimate(observations[p], kThresholdPx);
        cpu[e][p].push_back(stopwatch.CpuSeconds());
        wall[e][p].push_back(stopwatch.WallSeconds());
        if (rep == 0) errors[e].Add(scenes[p].ground_truth, result);
      }
    }
  }
  for (std::size_t e = 0; e < all.size(); ++e) {
    for (std::size_t p = 0; p < scenes.size(); ++p) {
      errors[e].cpu_seconds.push_back(trigrav::Median(cpu[e][p]));
      errors[e].wall_seconds.push_back(trigrav::Median(wall[e][p]));
    }
  }
  std::printf(
      "\n## (b) Robust estimates: %d triplets, %.0f %% outliers, %g px\n\n%d problems "
      "(robust_benchmark's, seed %llu), threshold %.1f px, f = %g px; time: median over "
      "the problems of the median of %d runs, one thread, CPU time of the process (wall time "
      "for reference); load average %s before, %s "
      "after. Errors: medians, views 2 and 3 pooled.\n",
      options.num_points, 100.0 * options.outlier_ratio, options.pixel_noise_px,
      FLAGS_robust_problems, static_cast<unsigned long long>(FLAGS_robust_seed), kThresholdPx,
      options.focal_px, FLAGS_robust_repetitions, load_before.c_str(), LoadAverage().c_str());
  PrintErrorTable(all, errors, /*with_time=*/true);
  const std::size_t n = trigrav_estimators.size();
  PrintRatios(
      "Ratios trigrav / peer: CPU time / rotation error / translation error:",
      Names(trigrav_estimators), Names(peers), [&](std::size_t r, std::size_t c) {
        const Errors& a = errors[r];
        const Errors& b = errors[n + c];
        return Format(
            "%.2f / %.2f / %.2f", trigrav::Median(a.cpu_seconds) / trigrav::Median(b.cpu_seconds),
            trigrav::Median(a.pooled.rotation_deg) / trigrav::Median(b.pooled.rotation_deg),
            trigrav::Median(a.pooled.translation_deg) / trigrav::Median(b.pooled.translation_deg));
      });
}

// ---------------------------------------------------------------------------------------------
// (c) Accuracy, raw and refined, on worker threads.

void RunAccuracy() {
  std::mt19937_64 rng(FLAGS_seed + 1);
  trigrav::SyntheticSceneOptions options;
  options.num_points = FLAGS_accuracy_points;
  options.pixel_noise_px = FLAGS_accuracy_noise_px;
  options.outlier_ratio = FLAGS_accuracy_outlier_ratio;
  std::vector<trigrav::SyntheticScene> scenes;
  for (int i = 0; i < FLAGS_accuracy_scenes; ++i)
    scenes.push_back(trigrav::GenerateSyntheticScene(options, &rng));
  std::vector<NamedEstimator> trigrav_estimators = trigrav::peers::TrigravRobustEstimators();
  for (NamedEstimator& e : trigrav::peers::TrigravRefinedEstimators())
    trigrav_estimators.push_back(std::move(e));
  const std::vector<NamedEstimator> peers = trigrav::peers::PeerEstimators();
  std::vector<NamedEstimator> all = trigrav_estimators;
  all.insert(all.end(), peers.begin(), peers.end());

  std::vector<std::vector<EstimatorResult>> results(scenes.size());
  trigrav::examples::NoteFewerThreads(
      trigrav::ParallelFor(scenes.size(), FLAGS_threads, [&](std::size_t s) {
        const trigrav::ThreeViewObservations observations = trigrav::ToObservations(scenes[s]);
        for (const NamedEstimator& e : all)
          results[s].push_back(e.estimate(observations, FLAGS_accuracy_threshold_px));
      }));
  std::vector<Errors> errors(all.size());
  for (std::size_t s = 0; s < scenes.size(); ++s) {
    for (std::size_t e = 0; e < all.size(); ++e)
      errors[e].Add(scenes[s].ground_truth, results[s][e]);
  }

  std::printf(
      "\n## (c) Accuracy: %d triplets, %.0f %% outliers, %g px\n\n%d scenes (seed %llu), "
      "threshold %g px, f = %g px; medians, views 2 and 3 pooled; stage \"yaw-only\": "
      "trigrav::InitializeAndRefine (yaw-only bundle adjustment).\n",
      FLAGS_accuracy_points, 100.0 * FLAGS_accuracy_outlier_ratio, FLAGS_accuracy_noise_px,
      FLAGS_accuracy_scenes, static_cast<unsigned long long>(FLAGS_seed + 1),
      FLAGS_accuracy_threshold_px, options.focal_px);
  PrintErrorTable(all, errors, /*with_time=*/false);
  const std::size_t n = trigrav_estimators.size();
  PrintRatios(
      "Ratios trigrav / peer: rotation error / translation error:", Names(trigrav_estimators),
      Names(peers), [&](std::size_t r, std::size_t c) {
        const trigrav::PooledErrors& a = errors[r].pooled;
        const trigrav::PooledErrors& b = errors[n + c].pooled;
        return Format("%.2f / %.2f",
                      trigrav::Median(a.rotation_deg) / trigrav::Median(b.rotation_deg),
                      trigrav::Median(a.translation_deg) / trigrav::Median(b.translation_deg));
      });
}

}  // namespace

int main(int argc, char** argv) {
  trigrav::examples::ParseToolFlags(
      "trigrav against OpenCV's and OpenGV's five-point RANSAC, one run.", __FILE__, &argc, &argv);
  using trigrav::examples::RequireFlag;
  RequireFlag(FLAGS_solver_problems > 0, "--solver_problems must be positive");
  RequireFlag(FLAGS_solver_passes > 0, "--solver_passes must be positive");
  RequireFlag(FLAGS_robust_problems > 0, "--robust_problems must be positive");
  RequireFlag(FLAGS_robust_repetitions > 0, "--robust_repetitions must be positive");
  RequireFlag(FLAGS_accuracy_scenes > 0, "--accuracy_scenes must be positive");
  RequireFlag(FLAGS_accuracy_points >= 8, "--accuracy_points must be >= 8");
  RequireFlag(FLAGS_accuracy_noise_px >= 0.0 && std::isfinite(FLAGS_accuracy_noise_px),
              "--accuracy_noise_px must be finite and >= 0");
  RequireFlag(FLAGS_accuracy_outlier_ratio >= 0.0 && FLAGS_accuracy_outlier_ratio < 0.5,
              "--accuracy_outlier_ratio must be in [0, 0.5)");
  RequireFlag(FLAGS_accuracy_threshold_px > 0.0 && std::isfinite(FLAGS_accuracy_threshold_px),
              "--accuracy_threshold_px must be positive and finite");
  RequireFlag(FLAGS_threads > 0, "--threads must be positive");
  trigrav::peers::RunPeersSingleThreaded();

  const double start = NowSeconds();
  std::printf(
      "# trigrav vs OpenCV / OpenGV five-point RANSAC\n\nEstimators (the threshold is in "
      "pixels for everyone; what it bounds differs):\n\n");
  std::vector<NamedEstimator> all = trigrav::peers::TrigravRobustEstimators();
  for (NamedEstimator& e : trigrav::peers::TrigravRefinedEstimators()) all.push_back(std::move(e));
  for (NamedEstimator& e : trigrav::peers::PeerEstimators()) all.push_back(std::move(e));
  PrintDescriptions(all);
  RunMinimalSolvers();
  RunRobust();
  RunAccuracy();
  std::printf("\nTotal run time %.0f s.\n", NowSeconds() - start);
  return 0;
}
