// What InitializeAndRefine says to common input mistakes (tests/scenes/input_mistakes.h) and to
// pure outliers: per mistake, over synthetic scenes, how many calls fail, the inlier ratio of the
// gravity-aware RANSAC, the gravity inconsistency angles and, for the calls that succeed, the
// rotation error against the ground truth and how many are more than 5 deg off; then the time to
// fail on pure outliers of EstimateThreeViewPoseRobust and InitializeAndRefine at their defaults.
// Commands: examples/experiments/README.md (verdict_matrix).

#include <gflags/gflags.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "common/require_flag.h"
#include "common/tool_flags.h"
#include "input_mistakes.h"
#include "trigrav/ba/initialize_and_refine.h"
#include "trigrav/evaluation/pose_errors.h"
#include "trigrav/evaluation/statistics.h"
#include "trigrav/evaluation/synthetic_scene.h"

DEFINE_int32(scenes, 30, "Synthetic scenes per mistake.");
DEFINE_int32(points, 600, "Triplets per scene.");
DEFINE_double(noise_px, 1.0, "Image noise sigma in pixels.");
DEFINE_double(outlier_ratio, 0.1, "Fraction of outlier triplets.");
DEFINE_double(imu_noise_deg, 0.0, "Sigma of each camera's pitch and roll error (deg).");
DEFINE_double(focal_px, 1000.0, "Focal length (px) of the 1280 x 720 images.");
DEFINE_double(max_tilt_deg, 10.0, "Pitch and roll of each camera within +-this (deg).");
DEFINE_double(max_yaw_deg, 10.0, "Yaw of each camera within +-this (deg).");
DEFINE_double(max_center_m, 10.0, "Centres of cameras 2 and 3 within +-this (m) per axis.");
DEFINE_double(min_inlier_ratio, 0.25, "robust.ransac.min_inlier_ratio.");
DEFINE_bool(gravity_check, true, "false: robust.max_gravity_inconsistency_deg = infinity.");
DEFINE_bool(gravity_prior,
            false,
            "Gravity-prior rotation model (tilt correction) instead of yaw-only.");
DEFINE_bool(check_gravity_after_success, true, "robust.check_gravity_after_success.");
DEFINE_string(mistakes, "all", "all, or one name of tests/scenes/input_mistakes.h.");
DEFINE_int32(outlier_triplets, 1000, "Triplets of the pure-outlier timing (0: skip it).");
DEFINE_int32(outlier_runs, 20, "Calls timed on pure outliers (median).");
DEFINE_uint64(seed, 1, "Seed of the scenes and of RANSAC.");

namespace {

using trigrav::InputMistake;

double Seconds(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

trigrav::InitializeAndRefineOptions Options(std::uint64_t seed) {
  trigrav::InitializeAndRefineOptions options;
  options.robust.ransac.seed = seed;
  options.robust.ransac.min_inlier_ratio = FLAGS_min_inlier_ratio;
  options.robust.check_gravity_after_success = FLAGS_check_gravity_after_success;
  if (FLAGS_gravity_prior) {
    options.bundle_adjustment.rotation_model =
        trigrav::ThreeViewBundleAdjustmentOptions::RotationModel::kGravityPrior;
  }
  if (!FLAGS_gravity_check) {
    options.robust.max_gravity_inconsistency_deg = std::numeric_limits<double>::infinity();
  }
  return options;
}

trigrav::SyntheticSceneOptions SceneOptions() {
  trigrav::SyntheticSceneOptions options;
  options.num_points = FLAGS_points;
  options.focal_px = FLAGS_focal_px;
  options.width_px = 1280.0;
  options.height_px = 720.0;
  options.max_tilt_deg = FLAGS_max_tilt_deg;
  options.max_yaw_deg = FLAGS_max_yaw_deg;
  options.max_center_m = FLAGS_max_center_m;
  options.pixel_noise_px = FLAGS_noise_px;
  options.outlier_ratio = FLAGS_outlier_ratio;
  options.imu_pitch_noise_deg = options.imu_roll_noise_deg = FLAGS_imu_noise_deg;
  return options;
}

// A success further off than this (deg, rotation or translation direction, view 2 or 3) is wrong.
constexpr double kWrongDeg = 5.0;

void PrintMistake(InputMistake mistake, const std::vector<trigrav::SyntheticScene>& scenes) {
  std::vector<double> ratio, max_pair_deg, rotation_error_deg, ms;
  int failures = 0, culprit_named = 0, wrong = 0;
  std::string message;
  for (std::size_t s = 0; s < scenes.size(); ++s) {
    const trigrav::ThreeViewObservations observations = WithMistake(scenes[s], mistake);
    const auto start = std::chrono::steady_clock::now();
    const trigrav::ThreeViewEstimate estimate =
        trigrav::InitializeAndRefine(observations, Options(FLAGS_seed + s));
    ms.push_back(1e3 * Seconds(start));
    ratio.push_back(static_cast<double>(estimate.robust.ransac.num_inliers) / observations.size());
    if (estimate.robust.gravity.measured) {
      const auto& angle = estimate.robust.gravity.pair_inconsistency_deg;
      max_pair_deg.push_back(*std::max_element(angle.begin(), angle.end()));
    }
    culprit_named += estimate.robust.gravity.inconsistent_camera != 0;
    if (!estimate.success) {
      ++failures;
      if (message.empty()) message = estimate.message;
      continue;
    }
    const trigrav::ThreeViewPoseErrors errors =
        trigrav::ComputeThreeViewPoseErrors(scenes[s].ground_truth, estimate.refined);
    rotation_error_deg.push_back(errors.MaxRotationDeg());
    wrong += std::max(errors.MaxRotationDeg(), errors.MaxTranslationDeg()) > kWrongDeg;
  }
  std::printf("%-29s %4d/%-4zu %6.3f %6.3f %8.2f %8.2f %6d %8.3f %8.3f %5d %7.1f\n",
              trigrav::InputMistakeName(mistake), failures, scenes.size(),
              trigrav::Quantile(ratio, 0.0), trigrav::Median(ratio), trigrav::Median(max_pair_deg),
              trigrav::Quantile(max_pair_deg, 1.0), culprit_named,
              trigrav::Median(rotation_error_deg), trigrav::Quantile(rotation_error_deg, 1.0),
              wrong, trigrav::Median(ms));
  if (!message.empty()) std::printf("    first message: %s\n", message.c_str());
}

// Uniform random pixels in all three views: no pose explains them.
void PrintPureOutliers() {
  std::mt19937_64 rng(FLAGS_seed);
  std::uniform_real_distribution<double> u(0.0, 1280.0), v(0.0, 720.0);
  trigrav::ThreeViewObservations observations;
  for (int k = 0; k < 3; ++k) {
    observations.cameras[k] = trigrav::PinholeCamera{FLAGS_focal_px, FLAGS_focal_px, 640.0, 360.0};
    observations.gravity_in_cam[k] = Eigen::Vector3d::UnitY();
    for (int n = 0; n < FLAGS_outlier_triplets; ++n) {
      observations.pixels[k].emplace_back(u(rng), v(rng));
    }
  }
  std::vector<double> robust_ms, refine_ms;
  int robust_successes = 0, refine_successes = 0;
  std::string message;
  for (int run = 0; run < FLAGS_outlier_runs; ++run) {
    trigrav::RobustThreeViewOptions robust;
    robust.ransac = Options(FLAGS_seed + run).robust.ransac;
    auto start = std::chrono::steady_clock::now();
    robust_successes += trigrav::EstimateThreeViewPoseRobust(observations, robust).success;
    robust_ms.push_back(1e3 * Seconds(start));
    start = std::chrono::steady_clock::now();
    const trigrav::ThreeViewEstimate estimate =
        trigrav::InitializeAndRefine(observations, Options(FLAGS_seed + run));
    refine_ms.push_back(1e3 * Seconds(start));
    refine_successes += estimate.success;
    message = estimate.message;
  }
  std::printf(
      "pure outliers, %d triplets, %d runs: EstimateThreeViewPoseRobust %d successes, median "
      "%.1f ms (max %.1f); InitializeAndRefine %d successes, median %.1f ms (max %.1f)\n"
      "    message: %s\n",
      FLAGS_outlier_triplets, FLAGS_outlier_runs, robust_successes, trigrav::Median(robust_ms),
      trigrav::Quantile(robust_ms, 1.0), refine_successes, trigrav::Median(refine_ms),
      trigrav::Quantile(refine_ms, 1.0), message.c_str());
}

}  // namespace

int main(int argc, char** argv) {
  trigrav::examples::ParseToolFlags("What InitializeAndRefine says to common input mistakes.",
                                    __FILE__, &argc, &argv);
  using trigrav::examples::RequireFlag;
  RequireFlag(FLAGS_scenes > 0, "--scenes must be positive");
  RequireFlag(FLAGS_points >= 20, "--points must be >= 20");
  RequireFlag(FLAGS_outlier_triplets >= 0, "--outlier_triplets must be >= 0");
  RequireFlag(FLAGS_outlier_runs > 0, "--outlier_runs must be positive");
  RequireFlag(FLAGS_min_inlier_ratio >= 0.0 && FLAGS_min_inlier_ratio < 1.0,
              "--min_inlier_ratio must be in [0, 1)");
  std::vector<InputMistake> mistakes;
  for (const InputMistake mistake : trigrav::kInputMistakes) {
    if (FLAGS_mistakes == "all" || FLAGS_mistakes == trigrav::InputMistakeName(mistake)) {
      mistakes.push_back(mistake);
    }
  }
  RequireFlag(!mistakes.empty(), "--mistakes must be all or a mistake's name");
  RequireFlag(FLAGS_noise_px >= 0.0 && std::isfinite(FLAGS_noise_px),
              "--noise_px must be finite and >= 0");
  RequireFlag(FLAGS_imu_noise_deg >= 0.0 && std::isfinite(FLAGS_imu_noise_deg),
              "--imu_noise_deg must be finite and >= 0");
  RequireFlag(FLAGS_outlier_ratio >= 0.0 && FLAGS_outlier_ratio < 1.0,
              "--outlier_ratio must be in [0, 1)");
  RequireFlag(FLAGS_focal_px > 0.0 && std::isfinite(FLAGS_focal_px),
              "--focal_px must be positive and finite");
  for (const double value : {FLAGS_max_tilt_deg, FLAGS_max_yaw_deg, FLAGS_max_center_m}) {
    RequireFlag(value >= 0.0 && std::isfinite(value),
                "--max_tilt_deg, --max_yaw_deg and --max_center_m must be finite and >= 0");
  }
  const trigrav::SyntheticSceneOptions scene_options = SceneOptions();

  std::mt19937_64 rng(FLAGS_seed);
  std::vector<trigrav::SyntheticScene> scenes;
  for (int s = 0; s < FLAGS_scenes; ++s) {
    scenes.push_back(trigrav::GenerateSyntheticScene(scene_options, &rng));
  }
  std::printf(
      "%d scenes of %d triplets, f = %g px (1280 x 720), %g px noise, %g %% outliers, IMU noise "
      "%g deg; InitializeAndRefine defaults, min_inlier_ratio %.3f\n",
      FLAGS_scenes, FLAGS_points, FLAGS_focal_px, FLAGS_noise_px, 100.0 * FLAGS_outlier_ratio,
      FLAGS_imu_noise_deg, FLAGS_min_inlier_ratio);
  std::printf("%-29s %9s %6s %6s %8s %8s %6s %8s %8s %5s %7s\n", "mistake", "failed", "ratio",
              "median", "pair med", "pair max", "named", "rot med", "rot max", "wrong", "ms");
  for (const InputMistake mistake : mistakes) PrintMistake(mistake, scenes);
  if (FLAGS_outlier_triplets > 0) PrintPureOutliers();
  return 0;
}
