// InitializeAndRefine on synthetic three-view scenes: RANSAC over a minimal solver, then three-view
// bundle adjustment on its inliers, compared with the ground truth. Three experiments:
//   single    (default) one setting, chosen by the flags: the median rotation, translation and
//             relative-scale errors of the RANSAC estimate ("raw") and of its refinement, the
//             inliers found against the true ones, and the time per call;
//   sweep     raw vs refined for every solver of kInitialSolvers, image noise 0-2 px (exact IMU)
//             and IMU pitch / roll noise 0.25-1 deg (1 px), with the yaw-only and the gravity-prior
//             rotation models: one CSV row per setting (plot_raw_vs_refined.py);
//   sample20  equal sample sizes (the paper protocol's last experiment): every method gets the same
//             20 triplets without outliers, 1000 scenes per level, image noise 0-2 px and IMU pitch
//             / roll noise 0.25-1 deg at 1 px, threshold 3 px x max(1, sigma / 1 px); raw and
//             refined from one InitializeAndRefine call, yaw-only without IMU noise, gravity prior
//             with sigma = the IMU noise otherwise, both from the paper's upright RANSAC. Built
//             with OpenCV / OpenGV (examples/peers), one more row per peer (--peers): its
//             five-point RANSAC on pairs (1,2), (1,3) of the same scenes at the same threshold,
//             without gravity. One CSV row per method, stage and level (plot_raw_vs_refined.py).
// Errors (pose_errors.h): rotation and translation-direction errors of views 2 and 3 pooled (deg),
// relative-scale error |log(s_est / s_gt)|, s = |C3| / |C2|; medians (statistics.h) over the
// estimates that returned a pose, failures counted apart.
//
//   initialize_and_refine_synthetic                       # 3pt, 1 px, 20 % outliers, 20 scenes
//   initialize_and_refine_synthetic --solver=5pt --imu_noise_deg=0.5 --rotation_model=gravity-prior
//   initialize_and_refine_synthetic --points=375 --engine=ceres
//   initialize_and_refine_synthetic --experiment=sweep --output=sweep.csv         # about 40 s
//   initialize_and_refine_synthetic --experiment=sample20 --output=sample20.csv   # about 5 min

#include <gflags/gflags.h>
#include <glog/logging.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <initializer_list>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "../common/thread_note.h"
#include "common/output_paths.h"
#include "common/paper_protocol.h"
#include "common/pooled_errors.h"
#include "common/require_flag.h"
#include "common/tool_flags.h"
#include "trigrav/ba/initialize_and_refine.h"
#include "trigrav/ba/three_view_bundle_adjustment.h"
#include "trigrav/evaluation/pose_errors.h"
#include "trigrav/evaluation/statistics.h"
#include "trigrav/evaluation/synthetic_scene.h"
#include "trigrav/initializers/parallel_for.h"

#ifdef TRIGRAV_WITH_PEERS
#include "peer_estimators.h"
constexpr bool kBuiltWithPeers = true;
#else
constexpr bool kBuiltWithPeers = false;
#endif

DEFINE_string(experiment, "single", "single (one setting, the flags below), sweep or sample20.");
DEFINE_string(solver, "3pt", "single: initial solver: 3pt, 3pt-sextic, 4pt, 7pt-linear, 5pt, 8pt.");
DEFINE_string(rotation_model,
              "yaw-only",
              "single: bundle adjustment rotation model: yaw-only, gravity-prior.");
DEFINE_string(
    engine,
    trigrav::EngineName(trigrav::ThreeViewBundleAdjustmentOptions().engine),
    "single: Bundle-adjustment engine (ThreeViewBundleAdjustmentOptions::Engine, the same "
    "optimum): ceres_points_eliminated (the library's default) or ceres (a block per point).");
DEFINE_string(loss, "huber", "single: robust loss on the pixel residuals: huber, cauchy, none.");
DEFINE_double(loss_scale_px, 2.0, "single: scale of the robust loss in pixels.");
DEFINE_double(gravity_sigma_deg, 0.5, "single: IMU angular sigma of the gravity prior in degrees.");
DEFINE_double(threshold_px, 2.0, "single: inlier threshold in pixels (RANSAC, re-classification).");
DEFINE_double(noise_px, 1.0, "single: image noise sigma in pixels (all three views).");
DEFINE_double(imu_noise_deg,
              0.0,
              "single: IMU noise sigma in degrees on each view's pitch and roll.");
DEFINE_double(outlier_ratio, 0.2, "single, sweep: fraction of outlier triplets.");
DEFINE_int32(points, 100, "Triplets per scene (sample20: default 20).");
DEFINE_int32(trials,
             20,
             "Scenes (single: default 20; sweep: per setting, default 50; sample20: per level, "
             "default 1000).");
DEFINE_int32(print_trials,
             0,
             "single: print the errors and the Ceres summary of this many trials.");
DEFINE_int32(max_iterations, 50, "single: Ceres iterations.");
DEFINE_bool(
    local_optimization,
    true,
    "single: RANSAC local optimisation (the raw pose is then already a non-minimal estimate).");
DEFINE_int32(reclassification_rounds,
             1,
             "single: re-classify the inliers after a refinement and refine again.");
DEFINE_double(threshold_sigmas,
              3.0,
              "sweep: inlier threshold in units of the image noise sigma (at least 0.5 px).");
DEFINE_uint64(seed, 1, "Seed of the scenes (the same for every solver and model).");
DEFINE_int32(threads, 2, "sweep, sample20: worker threads.");
DEFINE_string(output, "", "sweep, sample20: CSV file to write (default: sweep.csv, sample20.csv).");
DEFINE_bool(quick, false, "sweep, sample20: a few settings and trials, a smoke test.");
DEFINE_bool(
    peers,
    kBuiltWithPeers,
    "sample20: one more row per OpenCV / OpenGV five-point RANSAC (needs a build with them; "
    "default: on if built with them).");

namespace {

using trigrav::examples::RequireFlag;
using RotationModel = trigrav::ThreeViewBundleAdjustmentOptions::RotationModel;

enum class Experiment { kSingle, kSweep, kSample20 };

Experiment ParseExperiment() {
  if (FLAGS_experiment == "sweep") return Experiment::kSweep;
  if (FLAGS_experiment == "sample20") return Experiment::kSample20;
  RequireFlag(FLAGS_experiment == "single", "--experiment must be single, sweep or sample20");
  return Experiment::kSingle;
}

bool IsDefault(const char* flag) { return gflags::GetCommandLineFlagInfoOrDie(flag).is_default; }

// A flag that only some experiments read is an error for the others, not silently ignored.
void RequireOnlyFor(Experiment experiment,
                    std::initializer_list<Experiment> readers,
                    std::initializer_list<const char*> flags) {
  if (std::find(readers.begin(), readers.end(), experiment) != readers.end()) return;
  for (const char* flag : flags) {
    RequireFlag(IsDefault(flag),
                std::string("--") + flag + " does not apply to --experiment=" + FLAGS_experiment);
  }
}

bool PositiveFinite(double value) { return value > 0.0 && std::isfinite(value); }
bool NonNegativeFinite(double value) { return value >= 0.0 && std::isfinite(value); }

const char* ModelName(RotationModel model) {
  return model == RotationModel::kYawOnly ? "yaw-only" : "gravity-prior";
}

// ---------------------------------------------------------------------------------------------
// single: one setting.

trigrav::InitializeAndRefineOptions SingleOptions() {
  trigrav::InitializeAndRefineOptions options;
  RequireFlag(trigrav::ParseInitialSolver(FLAGS_solver, &options.robust.solver),
              "unknown --solver=" + FLAGS_solver + " (" + trigrav::InitialSolverNames() + ")");
  using Options = trigrav::ThreeViewBundleAdjustmentOptions;
  Options& ba = options.bundle_adjustment;
  if (FLAGS_rotation_model == "yaw-only") {
    ba.rotation_model = RotationModel::kYawOnly;
  } else {
    RequireFlag(FLAGS_rotation_model == "gravity-prior",
                "--rotation_model must be yaw-only or gravity-prior");
    ba.rotation_model = RotationModel::kGravityPrior;
  }
  RequireFlag(trigrav::ParseEngine(FLAGS_engine, &ba.engine),
              "--engine must be " + trigrav::EngineNames());
  if (FLAGS_loss == "huber") {
    ba.loss = Options::LossType::kHuber;
  } else if (FLAGS_loss == "cauchy") {
    ba.loss = Options::LossType::kCauchy;
  } else {
    RequireFlag(FLAGS_loss == "none", "--loss must be huber, cauchy or none");
    ba.loss = Options::LossType::kNone;
  }
  RequireFlag(PositiveFinite(FLAGS_loss_scale_px), "--loss_scale_px must be positive and finite");
  RequireFlag(PositiveFinite(FLAGS_gravity_sigma_deg),
              "--gravity_sigma_deg must be positive and finite");
  RequireFlag(PositiveFinite(FLAGS_threshold_px), "--threshold_px must be positive and finite");
  RequireFlag(FLAGS_max_iterations >= 0, "--max_iterations must be >= 0");
  RequireFlag(FLAGS_reclassification_rounds >= 0, "--reclassification_rounds must be >= 0");
  RequireFlag(FLAGS_print_trials >= 0, "--print_trials must be >= 0");
  RequireFlag(NonNegativeFinite(FLAGS_noise_px), "--noise_px must be finite and >= 0");
  RequireFlag(NonNegativeFinite(FLAGS_imu_noise_deg), "--imu_noise_deg must be finite and >= 0");
  const int sample = trigrav::MinimalSampleSize(options.robust.solver);
  RequireFlag(FLAGS_points >= sample, "--points must be at least the minimal sample of --solver=" +
                                          FLAGS_solver + " (" + std::to_string(sample) + ")");
  ba.loss_scale_px = FLAGS_loss_scale_px;
  ba.gravity_sigma_deg = FLAGS_gravity_sigma_deg;
  ba.pixel_sigma_px = std::max(FLAGS_noise_px, 0.1);
  ba.max_num_iterations = FLAGS_max_iterations;
  options.robust.ransac.max_error = FLAGS_threshold_px;
  options.robust.ransac.local_optimization = FLAGS_local_optimization;
  options.reclassification_rounds = FLAGS_reclassification_rounds;
  return options;
}

int CountSet(const std::vector<char>& mask) {
  return static_cast<int>(std::count(mask.begin(), mask.end(), 1));
}

// Inliers of `mask` that are true inliers of the scene.
int CountTrue(const std::vector<char>& mask, const std::vector<char>& is_inlier) {
  int count = 0;
  for (std::size_t i = 0; i < mask.size(); ++i) count += mask[i] && is_inlier[i];
  return count;
}

void RunSingle() {
  trigrav::InitializeAndRefineOptions options = SingleOptions();
  trigrav::SyntheticSceneOptions scene_options;
  scene_options.num_points = FLAGS_points;
  scene_options.pixel_noise_px = FLAGS_noise_px;
  scene_options.imu_pitch_noise_deg = FLAGS_imu_noise_deg;
  scene_options.imu_roll_noise_deg = FLAGS_imu_noise_deg;
  scene_options.outlier_ratio = FLAGS_outlier_ratio;

  std::printf(
      "InitializeAndRefine on %d synthetic scenes (seed %llu): %d triplets each, %.0f %% "
      "outliers, %g px image noise, ",
      FLAGS_trials, static_cast<unsigned long long>(FLAGS_seed), FLAGS_points,
      100.0 * FLAGS_outlier_ratio, FLAGS_noise_px);
  if (FLAGS_imu_noise_deg > 0.0) {
    std::printf("gravity off by %g deg (pitch and roll sigma)\n", FLAGS_imu_noise_deg);
  } else {
    std::printf("exact gravity\n");
  }
  std::printf(
      "%s RANSAC with a %g px threshold, then %s bundle adjustment (engine %s, %s loss)\n\n",
      FLAGS_solver.c_str(), FLAGS_threshold_px, FLAGS_rotation_model.c_str(), FLAGS_engine.c_str(),
      FLAGS_loss.c_str());

  std::mt19937_64 rng(FLAGS_seed);
  trigrav::PooledErrors raw_errors, refined_errors;
  std::vector<double> ransac_ms, refinement_ms;
  long long true_inliers = 0, ransac_found = 0, ransac_true = 0, refined_found = 0,
            refined_true = 0;
  int failures = 0;
  std::map<trigrav::FailureCause, int> failures_by_cause;
  for (int trial = 0; trial < FLAGS_trials; ++trial) {
    const trigrav::SyntheticScene scene = trigrav::GenerateSyntheticScene(scene_options, &rng);
    options.robust.ransac.seed = static_cast<std::uint64_t>(trial);
    const trigrav::ThreeViewEstimate estimate =
        trigrav::InitializeAndRefine(trigrav::ToObservations(scene), options);
    true_inliers += CountSet(scene.is_inlier);
    if (!estimate.success) {
      ++failures;
      ++failures_by_cause[estimate.cause];
      if (trial < FLAGS_print_trials) {
        std::printf("trial %d: failed: %s\n", trial, estimate.message.c_str());
      }
      continue;
    }
    const trigrav::ThreeViewPoseErrors raw =
        trigrav::ComputeThreeViewPoseErrors(scene.ground_truth, estimate.robust.pose);
    const trigrav::ThreeViewPoseErrors refined =
        trigrav::ComputeThreeViewPoseErrors(scene.ground_truth, estimate.refined);
    raw_errors.Add(raw);
    refined_errors.Add(refined);
    ransac_ms.push_back(1e3 * estimate.timings.ransac_s);
    refinement_ms.push_back(1e3 * estimate.timings.refinement_s);
    ransac_found += estimate.robust.ransac.num_inliers;
    ransac_true += CountTrue(estimate.robust.inliers, scene.is_inlier);
    refined_found += estimate.num_inliers;
    refined_true += CountTrue(estimate.inliers, scene.is_inlier);
    if (trial < FLAGS_print_trials) {
      std::printf(
          "trial %d: %d true inliers, RANSAC found %d, refinement kept %d; worse view: rotation "
          "%.4f -> %.4f deg, translation %.4f -> %.4f deg, scale %.5f -> %.5f; RANSAC %.2f ms, "
          "refinement %.2f ms%s%s\n  %s\n",
          trial, CountSet(scene.is_inlier), estimate.robust.ransac.num_inliers,
          estimate.num_inliers, raw.MaxRotationDeg(), refined.MaxRotationDeg(),
          raw.MaxTranslationDeg(), refined.MaxTranslationDeg(), raw.relative_scale,
          refined.relative_scale, 1e3 * estimate.timings.ransac_s,
          1e3 * estimate.timings.refinement_s, estimate.message.empty() ? "" : "; ",
          estimate.message.c_str(), estimate.refinement.summary.BriefReport().c_str());
    }
  }
  if (FLAGS_print_trials > 0) std::printf("\n");
  const int estimates = FLAGS_trials - failures;
  std::printf(
      "median error, views 2 and 3 pooled  rotation (deg)  translation (deg)  "
      "|log scale ratio|\n");
  std::printf("  RANSAC estimate (raw)             %14.4f  %17.4f  %17.5f\n",
              trigrav::Median(raw_errors.rotation_deg), trigrav::Median(raw_errors.translation_deg),
              trigrav::Median(raw_errors.relative_scale));
  std::printf("  refined                           %14.4f  %17.4f  %17.5f\n",
              trigrav::Median(refined_errors.rotation_deg),
              trigrav::Median(refined_errors.translation_deg),
              trigrav::Median(refined_errors.relative_scale));
  const double per_estimate = estimates > 0 ? 1.0 / estimates : 0.0;
  std::printf(
      "inliers per scene (mean): %.1f true; RANSAC found %.1f (%.1f true), refinement kept "
      "%.1f (%.1f true)\n",
      static_cast<double>(true_inliers) / FLAGS_trials, ransac_found * per_estimate,
      ransac_true * per_estimate, refined_found * per_estimate, refined_true * per_estimate);
  std::printf("time per call (median): RANSAC %.2f ms, refinement %.2f ms\n",
              trigrav::Median(ransac_ms), trigrav::Median(refinement_ms));
  std::printf("failures: %d of %d calls", failures, FLAGS_trials);
  for (const auto& [cause, count] : failures_by_cause) {
    std::printf("%s %s %d", cause == failures_by_cause.begin()->first ? " (" : ", ",
                trigrav::FailureCauseName(cause), count);
  }
  std::printf("%s\n", failures_by_cause.empty() ? "" : ")");
}

// ---------------------------------------------------------------------------------------------
// sweep: every solver x noise level x rotation model.

struct Setting {
  trigrav::InitialSolver solver;
  RotationModel model;
  double noise_px, imu_deg;
};

struct Medians {
  double rotation = 0.0, translation = 0.0, scale = 0.0;
};

Medians MediansOf(const trigrav::PooledErrors& errors) {
  return {trigrav::Median(errors.rotation_deg), trigrav::Median(errors.translation_deg),
          trigrav::Median(errors.relative_scale)};
}

struct SweepResult {
  Setting setting;
  Medians raw, refined;
  int failures = 0;
  double refinement_ms = 0.0;  // median
};

SweepResult RunSetting(const Setting& setting) {
  trigrav::SyntheticSceneOptions scene_options;
  scene_options.num_points = FLAGS_points;
  scene_options.pixel_noise_px = setting.noise_px;
  scene_options.imu_pitch_noise_deg = setting.imu_deg;
  scene_options.imu_roll_noise_deg = setting.imu_deg;
  scene_options.outlier_ratio = FLAGS_outlier_ratio;
  trigrav::InitializeAndRefineOptions options;
  options.robust.solver = setting.solver;
  options.robust.ransac.max_error = FLAGS_threshold_sigmas * std::max(setting.noise_px, 0.5);
  options.bundle_adjustment.rotation_model = setting.model;
  options.bundle_adjustment.gravity_sigma_deg = std::max(setting.imu_deg, 0.1);
  std::mt19937_64 rng(FLAGS_seed);
  trigrav::PooledErrors raw, refined;
  std::vector<double> refinement_ms;
  SweepResult result{setting, {}, {}, 0, 0.0};
  for (int trial = 0; trial < FLAGS_trials; ++trial) {
    const trigrav::SyntheticScene scene = trigrav::GenerateSyntheticScene(scene_options, &rng);
    options.robust.ransac.seed = static_cast<std::uint64_t>(trial);
    const trigrav::ThreeViewEstimate estimate =
        trigrav::InitializeAndRefine(trigrav::ToObservations(scene), options);
    if (!estimate.success) {
      ++result.failures;
      continue;
    }
    raw.Add(trigrav::ComputeThreeViewPoseErrors(scene.ground_truth, estimate.robust.pose));
    refined.Add(trigrav::ComputeThreeViewPoseErrors(scene.ground_truth, estimate.refined));
    refinement_ms.push_back(1e3 * estimate.timings.refinement_s);
  }
  result.raw = MediansOf(raw);
  result.refined = MediansOf(refined);
  result.refinement_ms = trigrav::Median(refinement_ms);
  return result;
}

std::vector<Setting> SweepSettings() {
  using trigrav::InitialSolver;
  std::vector<Setting> settings;
  if (FLAGS_quick) {
    settings.push_back({InitialSolver::kTrifocal3pt, RotationModel::kYawOnly, 0.0, 0.0});
    settings.push_back({InitialSolver::kTrifocal3pt, RotationModel::kYawOnly, 1.0, 0.0});
    settings.push_back({InitialSolver::kEssential5pt, RotationModel::kGravityPrior, 1.0, 0.5});
    return settings;
  }
  for (const InitialSolver solver : trigrav::kInitialSolvers) {
    for (const RotationModel model : {RotationModel::kYawOnly, RotationModel::kGravityPrior}) {
      for (const double noise : {0.0, 0.5, 1.0, 1.5, 2.0})
        settings.push_back({solver, model, noise, 0.0});
      for (const double imu : {0.25, 0.5, 0.75, 1.0}) settings.push_back({solver, model, 1.0, imu});
    }
  }
  return settings;
}

void RunSweep(std::ofstream* csv) {
  if (IsDefault("trials")) FLAGS_trials = 50;
  if (FLAGS_quick) FLAGS_trials = std::min(FLAGS_trials, 5);

  const std::vector<Setting> settings = SweepSettings();
  std::vector<SweepResult> results(settings.size());
  std::atomic<std::size_t> done{0};
  trigrav::examples::NoteFewerThreads(
      trigrav::ParallelFor(settings.size(), FLAGS_threads, [&](std::size_t i) {
        results[i] = RunSetting(settings[i]);
        std::fprintf(stderr, "\r%zu / %zu settings", ++done, settings.size());
      }));
  std::fprintf(stderr, "\n");

  *csv << "solver,model,noise_px,imu_deg,trials,failures,raw_rotation_deg,raw_translation_deg,"
          "raw_scale,refined_rotation_deg,refined_translation_deg,refined_scale,refinement_ms\n";
  for (const SweepResult& r : results) {
    *csv << trigrav::InitialSolverName(r.setting.solver) << ',' << ModelName(r.setting.model) << ','
         << r.setting.noise_px << ',' << r.setting.imu_deg << ',' << FLAGS_trials << ','
         << r.failures << ',' << r.raw.rotation << ',' << r.raw.translation << ',' << r.raw.scale
         << ',' << r.refined.rotation << ',' << r.refined.translation << ',' << r.refined.scale
         << ',' << r.refinement_ms << '\n';
  }
  std::printf("wrote %zu settings x %d trials to %s\n", results.size(), FLAGS_trials,
              FLAGS_output.c_str());
}

// ---------------------------------------------------------------------------------------------
// sample20: every method on the same 20 triplets (paper_protocol.h).

#ifdef TRIGRAV_WITH_PEERS
// The OpenCV / OpenGV robust estimates (examples/peers/peer_estimators.h), without gravity, at an
// inlier threshold in pixels; none without --peers.
const std::vector<trigrav::peers::NamedEstimator>& Peers() {
  static const std::vector<trigrav::peers::NamedEstimator> peers = [] {
    if (!FLAGS_peers) return std::vector<trigrav::peers::NamedEstimator>();
    trigrav::peers::RunPeersSingleThreaded();  // the worker threads are ours
    return trigrav::peers::PeerEstimators();
  }();
  return peers;
}
std::size_t NumPeers() { return Peers().size(); }
#else
std::size_t NumPeers() { return 0; }
#endif

// Rows of one level: per solver of kInitialSolvers raw and refined, then one per peer.
std::size_t NumRows() { return 2 * trigrav::kInitialSolvers.size() + NumPeers(); }

std::vector<trigrav::LevelErrors> RunSample20Chunk(const trigrav::PaperLevel& level,
                                                   int trials,
                                                   std::uint64_t seed) {
  std::vector<trigrav::LevelErrors> errors(NumRows());
  trigrav::SyntheticSceneOptions scene_options;
  scene_options.num_points = FLAGS_points;
  scene_options.pixel_noise_px = level.noise_px;
  scene_options.imu_pitch_noise_deg = level.pitch_deg;
  scene_options.imu_roll_noise_deg = level.roll_deg;
  const double imu_deg = std::max(level.pitch_deg, level.roll_deg);
  const double threshold_px = 3.0 * std::max(1.0, level.noise_px);
  std::mt19937_64 rng(seed);
  for (int trial = 0; trial < trials; ++trial) {
    const trigrav::SyntheticScene scene = trigrav::GenerateSyntheticScene(scene_options, &rng);
    const trigrav::ThreeViewObservations observations = trigrav::ToObservations(scene);
    for (std::size_t s = 0; s < trigrav::kInitialSolvers.size(); ++s) {
      trigrav::InitializeAndRefineOptions options;
      options.robust.solver = trigrav::kInitialSolvers[s];
      options.robust.ransac.max_error = threshold_px;
      options.robust.ransac.seed = seed + trial;
      if (imu_deg > 0.0) {
        options.bundle_adjustment.rotation_model = RotationModel::kGravityPrior;
        options.bundle_adjustment.gravity_sigma_deg = imu_deg;
        options.bundle_adjustment.pixel_sigma_px = std::max(level.noise_px, 0.1);
        // Both stages start from the paper's upright RANSAC: "refined" refines the raw row.
        options.robust.max_tilt_correction_deg = 0.0;
      }
      const trigrav::ThreeViewEstimate estimate =
          trigrav::InitializeAndRefine(observations, options);
      errors[2 * s].Add(scene.ground_truth, estimate.success, estimate.robust.pose);
      errors[2 * s + 1].Add(scene.ground_truth, estimate.success && estimate.refinement_runs > 0,
                            estimate.refined);
    }
#ifdef TRIGRAV_WITH_PEERS
    for (std::size_t p = 0; p < Peers().size(); ++p) {
      const trigrav::peers::EstimatorResult peer = Peers()[p].estimate(observations, threshold_px);
      errors[2 * trigrav::kInitialSolvers.size() + p].Add(scene.ground_truth, peer.success,
                                                          peer.pose, peer.relative_scale_known);
    }
#endif
  }
  return errors;
}

void RunSample20(std::ofstream* csv) {
#ifdef TRIGRAV_WITH_PEERS
  for (const trigrav::peers::NamedEstimator& peer : Peers()) {
    std::fprintf(stderr, "peer %s (no gravity): %s\n", peer.name.c_str(), peer.description.c_str());
  }
#endif
  // The sample20 levels of the paper protocol, with their place in it (and so their seeds).
  std::vector<trigrav::PaperLevel> levels = trigrav::PaperLevels(FLAGS_quick, 1.0);
  if (!IsDefault("trials")) {
    for (trigrav::PaperLevel& level : levels) level.trials = FLAGS_trials;
  }
  const std::vector<trigrav::PaperChunk> chunks =
      trigrav::PaperChunks(levels, {trigrav::PaperExperiment::kSample20}, FLAGS_seed);
  const auto start = std::chrono::steady_clock::now();
  const std::vector<std::vector<trigrav::LevelErrors>> results = trigrav::RunPaperChunks(
      levels, chunks, NumRows(), FLAGS_threads, RunSample20Chunk,
      [&](std::size_t done, std::size_t total) {
        const double s =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        std::fprintf(stderr, "\r%zu / %zu chunks, %.0f s", done, total, s);
      });
  std::fprintf(stderr, "\n");

  std::vector<std::string> methods, stages;
  for (const trigrav::InitialSolver solver : trigrav::kInitialSolvers) {
    for (const char* stage : {"raw", "refined"}) {
      methods.push_back(trigrav::InitialSolverName(solver));
      stages.push_back(stage);
    }
  }
#ifdef TRIGRAV_WITH_PEERS
  for (const trigrav::peers::NamedEstimator& peer : Peers()) {
    methods.push_back(peer.name);
    stages.push_back(peer.stage);
  }
#endif
  trigrav::WritePaperAccuracyHeader(/*with_stage=*/true, csv);
  int rows = 0;
  for (std::size_t r = 0; r < methods.size(); ++r) {
    for (std::size_t l = 0; l < levels.size(); ++l) {
      if (levels[l].experiment != trigrav::PaperExperiment::kSample20) continue;
      trigrav::WritePaperAccuracyRow(levels[l], methods[r], stages[r], FLAGS_points, results[l][r],
                                     csv);
      ++rows;
    }
  }
  std::printf("wrote %d rows (methods x stages x levels) to %s in %.1f s\n", rows,
              FLAGS_output.c_str(),
              std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
}

}  // namespace

int main(int argc, char** argv) {
  trigrav::examples::ParseToolFlags(
      "InitializeAndRefine on synthetic triplets: raw (RANSAC) vs refined errors, inliers, time.",
      __FILE__, &argc, &argv);
  google::InitGoogleLogging(argv[0]);
  const Experiment experiment = ParseExperiment();
  using E = Experiment;
  RequireOnlyFor(experiment, {E::kSingle},
                 {"solver", "rotation_model", "engine", "loss", "loss_scale_px",
                  "gravity_sigma_deg", "threshold_px", "noise_px", "imu_noise_deg", "print_trials",
                  "max_iterations", "local_optimization", "reclassification_rounds"});
  RequireOnlyFor(experiment, {E::kSingle, E::kSweep}, {"outlier_ratio"});
  RequireOnlyFor(experiment, {E::kSweep}, {"threshold_sigmas"});
  RequireOnlyFor(experiment, {E::kSweep, E::kSample20}, {"threads", "output", "quick"});
  RequireOnlyFor(experiment, {E::kSample20}, {"peers"});
  RequireFlag(FLAGS_trials > 0, "--trials must be positive");
  RequireFlag(FLAGS_outlier_ratio >= 0.0 && FLAGS_outlier_ratio < 1.0,
              "--outlier_ratio must be in [0, 1)");
  if (experiment == E::kSingle) {
    RunSingle();
    return 0;
  }

  if (experiment == E::kSample20 && IsDefault("points")) FLAGS_points = 20;
  RequireFlag(FLAGS_points >= 8, "--points must be >= 8 (the eight-point baseline's sample)");
  RequireFlag(FLAGS_threads >= 1 && FLAGS_threads <= 256, "--threads must be in [1, 256]");
  RequireFlag(FLAGS_threshold_sigmas > 0.0 && std::isfinite(FLAGS_threshold_sigmas),
              "--threshold_sigmas must be positive and finite");
  RequireFlag(!FLAGS_peers || kBuiltWithPeers, "--peers: built without OpenCV and OpenGV");
  if (FLAGS_output.empty()) FLAGS_output = FLAGS_experiment + ".csv";
  trigrav::examples::RequireOutputsApartFromInputs({}, {{"--output", FLAGS_output}});
  // Opened before the run, so that an unwritable path fails at once, not after the experiment.
  std::ofstream csv(FLAGS_output);
  RequireFlag(static_cast<bool>(csv), "cannot write --output=" + FLAGS_output);
  if (experiment == E::kSweep) {
    RunSweep(&csv);
  } else {
    RunSample20(&csv);
  }
  csv.close();
  RequireFlag(static_cast<bool>(csv), "cannot write --output=" + FLAGS_output);
  return 0;
}
