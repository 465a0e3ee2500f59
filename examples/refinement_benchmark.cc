// Refined vs raw: for every initial solver, image noise level (0-2 px, exact IMU) and IMU noise
// level (0-1 deg on pitch and roll, 1 px), the median rotation, translation and relative-scale
// errors of the RANSAC estimate ("raw") and of its bundle adjustment ("refined"), for the yaw-only
// and the gravity-prior rotation models. Writes one CSV row per setting; plot with
// examples/plot_refinement.py.
//
//   refinement_benchmark --trials=50 --output=refinement.csv

#include <gflags/gflags.h>
#include <glog/logging.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "parallel_for.h"
#include "pooled_errors.h"
#include "require_flag.h"
#include "trigrav/ba/initialize_and_refine.h"
#include "trigrav/evaluation/pose_errors.h"
#include "trigrav/evaluation/statistics.h"
#include "trigrav/evaluation/synthetic_scene.h"

DEFINE_int32(trials, 50, "Scenes per setting.");
DEFINE_int32(points, 100, "Triplets per scene.");
DEFINE_double(outlier_ratio, 0.2, "Fraction of outlier triplets.");
DEFINE_double(threshold_sigmas,
              3.0,
              "RANSAC inlier threshold in units of the image noise sigma (at least 0.5 px).");
DEFINE_uint64(seed, 1, "Seed of the scenes (the same for every solver and model).");
DEFINE_int32(threads, 2, "Worker threads.");
DEFINE_string(output, "refinement.csv", "CSV file to write.");
DEFINE_bool(quick, false, "Three settings and 5 trials: a smoke test.");

namespace {

using RotationModel = trigrav::ThreeViewBundleAdjustmentOptions::RotationModel;

struct Setting {
  trigrav::InitialSolver solver;
  RotationModel model;
  double noise_px, imu_deg;
};

struct Medians {
  double rotation = 0.0, translation = 0.0, scale = 0.0;
};

Medians MediansOf(const trigrav::examples::PooledErrors& errors) {
  return {trigrav::Median(errors.rotation_deg), trigrav::Median(errors.translation_deg),
          trigrav::Median(errors.relative_scale)};
}

struct Result {
  Setting setting;
  Medians raw, refined;
  int failures = 0;
  double ba_ms = 0.0;  // median bundle-adjustment time
};

Result Run(const Setting& setting) {
  trigrav::SyntheticSceneOptions scene_options;
  scene_options.num_points = FLAGS_points;
  scene_options.pixel_noise_px = setting.noise_px;
  scene_options.imu_pitch_noise_deg = setting.imu_deg;
  scene_options.imu_roll_noise_deg = setting.imu_deg;
  scene_options.outlier_ratio = FLAGS_outlier_ratio;
  trigrav::InitializeAndRefineOptions options;
  options.solver = setting.solver;
  options.inlier_threshold_px = FLAGS_threshold_sigmas * std::max(setting.noise_px, 0.5);
  options.bundle_adjustment.rotation_model = setting.model;
  options.bundle_adjustment.gravity_sigma_deg = std::max(setting.imu_deg, 0.1);
  std::mt19937_64 rng(FLAGS_seed);
  trigrav::examples::PooledErrors raw, refined;
  std::vector<double> ba_ms;
  Result result{setting, {}, {}, 0, 0.0};
  for (int trial = 0; trial < FLAGS_trials; ++trial) {
    const trigrav::SyntheticScene scene = trigrav::GenerateSyntheticScene(scene_options, &rng);
    options.seed = trial;
    const trigrav::ThreeViewEstimate estimate =
        trigrav::InitializeAndRefine(trigrav::ToObservations(scene), options);
    if (!estimate.success) {
      ++result.failures;
      continue;
    }
    raw.Add(trigrav::ComputeThreeViewPoseErrors(scene.ground_truth, estimate.initial));
    refined.Add(trigrav::ComputeThreeViewPoseErrors(scene.ground_truth, estimate.refined));
    ba_ms.push_back(1e3 * estimate.ba_time_s);
  }
  result.raw = MediansOf(raw);
  result.refined = MediansOf(refined);
  result.ba_ms = trigrav::Median(ba_ms);
  return result;
}

std::vector<Setting> Settings() {
  using trigrav::InitialSolver;
  const std::vector<InitialSolver> solvers = {
      InitialSolver::kTrifocal3pt,  InitialSolver::kTrifocal3ptSextic,
      InitialSolver::kTrifocal4pt,  InitialSolver::kTrifocalLinear,
      InitialSolver::kEssential5pt, InitialSolver::kEssential8pt};
  std::vector<Setting> settings;
  if (FLAGS_quick) {
    settings.push_back({InitialSolver::kTrifocal3pt, RotationModel::kYawOnly, 0.0, 0.0});
    settings.push_back({InitialSolver::kTrifocal3pt, RotationModel::kYawOnly, 1.0, 0.0});
    settings.push_back({InitialSolver::kEssential5pt, RotationModel::kGravityPrior, 1.0, 0.5});
    return settings;
  }
  for (const InitialSolver solver : solvers) {
    for (const RotationModel model : {RotationModel::kYawOnly, RotationModel::kGravityPrior}) {
      for (const double noise : {0.0, 0.5, 1.0, 1.5, 2.0})
        settings.push_back({solver, model, noise, 0.0});
      for (const double imu : {0.25, 0.5, 0.75, 1.0}) settings.push_back({solver, model, 1.0, imu});
    }
  }
  return settings;
}

}  // namespace

int main(int argc, char** argv) {
  gflags::SetUsageMessage("Refined vs raw three-view errors for every solver; writes a CSV.");
  gflags::ParseCommandLineFlags(&argc, &argv, true);
  google::InitGoogleLogging(argv[0]);
  using trigrav::examples::RequireFlag;
  RequireFlag(FLAGS_trials > 0, "--trials must be positive");
  RequireFlag(FLAGS_points >= 8, "--points must be >= 8 (the eight-point baseline's sample)");
  RequireFlag(FLAGS_outlier_ratio >= 0.0 && FLAGS_outlier_ratio < 1.0,
              "--outlier_ratio must be in [0, 1)");
  RequireFlag(FLAGS_threads >= 1 && FLAGS_threads <= 256, "--threads must be in [1, 256]");
  RequireFlag(FLAGS_threshold_sigmas > 0.0 && std::isfinite(FLAGS_threshold_sigmas),
              "--threshold_sigmas must be positive and finite");
  // Opened before the run, so that an unwritable path fails at once, not after the benchmark.
  std::ofstream csv(FLAGS_output);
  RequireFlag(static_cast<bool>(csv), "cannot write --output=" + FLAGS_output);
  if (FLAGS_quick) FLAGS_trials = std::min(FLAGS_trials, 5);

  const std::vector<Setting> settings = Settings();
  std::vector<Result> results(settings.size());
  std::atomic<std::size_t> done{0};
  trigrav::examples::ParallelFor(settings.size(), FLAGS_threads, [&](std::size_t i) {
    results[i] = Run(settings[i]);
    std::fprintf(stderr, "\r%zu / %zu settings", ++done, settings.size());
  });
  std::fprintf(stderr, "\n");

  csv << "solver,model,noise_px,imu_deg,trials,failures,raw_rotation_deg,raw_translation_deg,"
         "raw_scale,refined_rotation_deg,refined_translation_deg,refined_scale,ba_ms\n";
  for (const Result& r : results) {
    csv << trigrav::InitialSolverName(r.setting.solver) << ','
        << (r.setting.model == RotationModel::kYawOnly ? "yaw-only" : "gravity-prior") << ','
        << r.setting.noise_px << ',' << r.setting.imu_deg << ',' << FLAGS_trials << ','
        << r.failures << ',' << r.raw.rotation << ',' << r.raw.translation << ',' << r.raw.scale
        << ',' << r.refined.rotation << ',' << r.refined.translation << ',' << r.refined.scale
        << ',' << r.ba_ms << '\n';
  }
  std::printf("wrote %zu settings x %d trials to %s\n", results.size(), FLAGS_trials,
              FLAGS_output.c_str());
  return 0;
}
