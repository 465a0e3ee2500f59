// Synthetic three-view scenes with outliers through InitializeAndRefine: RANSAC over a minimal
// solver, then three-view bundle adjustment on the inliers. Prints raw vs refined errors per trial,
// the Ceres summary line, and medians.
//
//   refine_synthetic_triplets --solver=3pt --points=100 --noise_px=1 --outlier_ratio=0.2
//   --trials=20 refine_synthetic_triplets --imu_noise_deg=0.5 --rotation_model=gravity-prior

#include <gflags/gflags.h>
#include <glog/logging.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "pooled_errors.h"
#include "require_flag.h"
#include "trigrav/ba/initialize_and_refine.h"
#include "trigrav/initializers/pose_metrics.h"
#include "trigrav/initializers/synthetic_scene.h"

DEFINE_string(solver, "3pt", "Initial solver: 3pt, 3pt-sextic, 4pt, 7pt-linear, 5pt, 8pt.");
DEFINE_string(rotation_model,
              "yaw-only",
              "Bundle adjustment rotation model: yaw-only, gravity-prior.");
DEFINE_string(loss, "huber", "Robust loss on the pixel residuals: huber, cauchy, none.");
DEFINE_double(loss_scale_px, 2.0, "Scale of the robust loss in pixels.");
DEFINE_double(gravity_sigma_deg, 0.5, "IMU angular sigma of the gravity prior in degrees.");
DEFINE_double(threshold_px, 2.0, "RANSAC inlier threshold in pixels.");
DEFINE_double(noise_px, 1.0, "Image noise sigma in pixels (all three views).");
DEFINE_double(imu_noise_deg, 0.0, "IMU noise sigma in degrees on each view's pitch and roll.");
DEFINE_double(outlier_ratio, 0.2, "Fraction of outlier triplets.");
DEFINE_int32(points, 100, "Triplets per scene.");
DEFINE_int32(trials, 20, "Number of scenes.");
DEFINE_int32(print_trials, 5, "Print per-trial errors and the Ceres summary of this many trials.");
DEFINE_int32(max_iterations, 50, "Ceres iterations.");
DEFINE_bool(local_optimization,
            true,
            "RANSAC local optimisation (the raw pose is then already a non-minimal estimate).");
DEFINE_int32(reclassification_rounds,
             1,
             "Re-classify inliers after a refinement and refine again.");
DEFINE_uint64(seed, 1, "Random seed; the same seed gives the same output.");

namespace {

using trigrav::examples::RequireFlag;

bool PositiveFinite(double value) { return value > 0.0 && std::isfinite(value); }
bool NonNegativeFinite(double value) { return value >= 0.0 && std::isfinite(value); }

trigrav::InitializeAndRefineOptions MakeOptions() {
  trigrav::InitializeAndRefineOptions options;
  RequireFlag(trigrav::ParseInitialSolver(FLAGS_solver, &options.solver),
              "unknown --solver=" + FLAGS_solver + " (3pt, 3pt-sextic, 4pt, 7pt-linear, 5pt, 8pt)");
  using Options = trigrav::ThreeViewBundleAdjustmentOptions;
  Options& ba = options.bundle_adjustment;
  if (FLAGS_rotation_model == "yaw-only") {
    ba.rotation_model = Options::RotationModel::kYawOnly;
  } else {
    RequireFlag(FLAGS_rotation_model == "gravity-prior",
                "--rotation_model must be yaw-only or gravity-prior");
    ba.rotation_model = Options::RotationModel::kGravityPrior;
  }
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
  ba.loss_scale_px = FLAGS_loss_scale_px;
  ba.gravity_sigma_deg = FLAGS_gravity_sigma_deg;
  ba.pixel_sigma_px = std::max(FLAGS_noise_px, 0.1);
  ba.max_num_iterations = FLAGS_max_iterations;
  options.inlier_threshold_px = FLAGS_threshold_px;
  options.ransac.local_optimization = FLAGS_local_optimization;
  options.reclassification_rounds = FLAGS_reclassification_rounds;
  return options;
}

}  // namespace

int main(int argc, char** argv) {
  gflags::ParseCommandLineFlags(&argc, &argv, true);
  google::InitGoogleLogging(argv[0]);
  RequireFlag(FLAGS_trials > 0, "--trials must be positive");
  RequireFlag(FLAGS_print_trials >= 0, "--print_trials must be >= 0");
  RequireFlag(NonNegativeFinite(FLAGS_noise_px), "--noise_px must be finite and >= 0");
  RequireFlag(NonNegativeFinite(FLAGS_imu_noise_deg), "--imu_noise_deg must be finite and >= 0");
  RequireFlag(FLAGS_outlier_ratio >= 0.0 && FLAGS_outlier_ratio < 1.0,
              "--outlier_ratio must be in [0, 1)");
  trigrav::InitializeAndRefineOptions options = MakeOptions();
  RequireFlag(FLAGS_points >= trigrav::MinimalSampleSize(options.solver),
              "--points must be at least the minimal sample of --solver=" + FLAGS_solver + " (" +
                  std::to_string(trigrav::MinimalSampleSize(options.solver)) + ")");

  trigrav::SyntheticSceneOptions scene_options;
  scene_options.num_points = FLAGS_points;
  scene_options.pixel_noise_px = FLAGS_noise_px;
  scene_options.imu_pitch_noise_deg = FLAGS_imu_noise_deg;
  scene_options.imu_roll_noise_deg = FLAGS_imu_noise_deg;
  scene_options.outlier_ratio = FLAGS_outlier_ratio;

  std::mt19937_64 rng(FLAGS_seed);
  trigrav::examples::PooledErrors raw_errors, refined_errors;
  std::vector<double> ba_ms, ransac_ms;
  int failures = 0;
  for (int trial = 0; trial < FLAGS_trials; ++trial) {
    const trigrav::SyntheticScene scene = trigrav::GenerateSyntheticScene(scene_options, &rng);
    options.seed = static_cast<std::uint64_t>(trial);
    const trigrav::ThreeViewEstimate estimate =
        trigrav::InitializeAndRefine(trigrav::ToObservations(scene), options);
    if (!estimate.success) {
      ++failures;
      std::printf("trial %d: failed: %s\n", trial, estimate.message.c_str());
      continue;
    }
    const trigrav::ThreeViewPoseErrors raw =
        trigrav::ComputeThreeViewPoseErrors(scene.ground_truth, estimate.initial);
    const trigrav::ThreeViewPoseErrors refined =
        trigrav::ComputeThreeViewPoseErrors(scene.ground_truth, estimate.refined);
    raw_errors.Add(raw);
    refined_errors.Add(refined);
    ba_ms.push_back(1e3 * estimate.ba_time_s);
    ransac_ms.push_back(1e3 * estimate.ransac_time_s);
    if (trial < FLAGS_print_trials) {
      std::printf(
          "trial %d: %d inliers, worse view: rotation %.4f -> %.4f deg, translation %.4f -> %.4f "
          "deg, "
          "scale %.5f -> %.5f, BA %.2f ms%s%s\n  %s\n",
          trial, estimate.num_inliers, raw.MaxRotationDeg(), refined.MaxRotationDeg(),
          raw.MaxTranslationDeg(), refined.MaxTranslationDeg(), raw.relative_scale,
          refined.relative_scale, 1e3 * estimate.ba_time_s, estimate.message.empty() ? "" : ", ",
          estimate.message.c_str(), estimate.ceres_brief_report.c_str());
    }
  }
  std::printf(
      "median over %zu trials (%d failures), views 2 and 3 pooled: rotation %.4f -> %.4f deg, "
      "translation "
      "%.4f -> %.4f deg, scale %.5f -> %.5f; RANSAC %.2f ms, BA %.2f ms\n",
      refined_errors.relative_scale.size(), failures, trigrav::Median(raw_errors.rotation_deg),
      trigrav::Median(refined_errors.rotation_deg), trigrav::Median(raw_errors.translation_deg),
      trigrav::Median(refined_errors.translation_deg), trigrav::Median(raw_errors.relative_scale),
      trigrav::Median(refined_errors.relative_scale), trigrav::Median(ransac_ms),
      trigrav::Median(ba_ms));
  return 0;
}
