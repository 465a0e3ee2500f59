// Calibration of the refined pose's covariance (trigrav/ba/three_view_covariance.h): over synthetic
// scenes through InitializeAndRefine (defaults, compute_covariance on), the predicted standard
// deviation of each parameter (RMS of the predicted sigmas) against the empirical standard
// deviation of the refined-minus-true errors in the same parameterisation, their ratio, and the
// normalised error e^T Sigma^-1 e (mean ~ the dimension when the covariance is right). Then the
// cost of the covariance at 300 and 650 points, against ceres::Covariance (SPARSE_QR).
//
//   covariance_calibration                         # 500 scenes per case, 100 triplets, 1 px, 20 %
//   covariance_calibration --quick                 # 50 scenes, 3 timed problems (ctest)

#include <ceres/covariance.h>
#include <gflags/gflags.h>
#include <glog/logging.h>

#include <Eigen/Cholesky>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "common/require_flag.h"
#include "common/tool_flags.h"
#include "trigrav/ba/initialize_and_refine.h"
#include "trigrav/ba/three_view_covariance.h"
#include "trigrav/evaluation/statistics.h"
#include "trigrav/evaluation/synthetic_scene.h"

DEFINE_int32(scenes, 500, "Synthetic scenes per case.");
DEFINE_int32(points, 100, "Triplets per scene.");
DEFINE_double(noise_px, 1.0, "Image noise sigma (px); also the assumed pixel_sigma_px.");
DEFINE_double(outlier_ratio, 0.2, "Fraction of outlier triplets.");
DEFINE_double(imu_noise_deg,
              0.5,
              "Pitch and roll sigma of the IMU-noise case (deg); also its gravity_sigma_deg.");
DEFINE_double(threshold_px, 2.0, "robust.ransac.max_error, the inlier threshold (px).");
DEFINE_int32(cost_problems, 20, "Problems timed per point count (median).");
DEFINE_uint64(seed, 1, "Seed of the scenes; RANSAC's seed is the scene index.");
DEFINE_bool(quick, false, "Smoke test: 50 scenes per case, 3 timed problems.");

namespace {

using RotationModel = trigrav::ThreeViewBundleAdjustmentOptions::RotationModel;

// The exact-gravity cases still need a prior sigma (unused by yaw-only): one far below the images'
// tilt precision, so that the prior says what the (exact) IMU does.
constexpr double kExactGravitySigmaDeg = 0.001;

// sigma / median |e| of a normal distribution.
constexpr double kMadToSigma = 1.4826;

struct Case {
  std::string name;
  RotationModel model;
  double imu_noise_deg;
  double gravity_sigma_deg;
};

std::string Format(double value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.2f deg", value);
  return text;
}

double Seconds(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

trigrav::SyntheticSceneOptions SceneOptions(int num_points, double imu_noise_deg) {
  trigrav::SyntheticSceneOptions options;
  options.num_points = num_points;
  options.pixel_noise_px = FLAGS_noise_px;
  options.outlier_ratio = FLAGS_outlier_ratio;
  options.imu_pitch_noise_deg = imu_noise_deg;
  options.imu_roll_noise_deg = imu_noise_deg;
  return options;
}

std::vector<std::string> ParameterNames(RotationModel model) {
  if (model == RotationModel::kYawOnly) {
    return {"yaw2 (rad)", "yaw3 (rad)", "u2.1", "u2.2", "C3.x", "C3.y", "C3.z"};
  }
  return {"omega2.x (rad)",
          "omega2.y (rad)",
          "omega2.z (rad)",
          "omega3.x (rad)",
          "omega3.y (rad)",
          "omega3.z (rad)",
          "u2.1",
          "u2.2",
          "C3.x",
          "C3.y",
          "C3.z"};
}

// One case over FLAGS_scenes scenes: the table of predicted against empirical sigmas.
void Calibrate(const Case& c, int num_scenes) {
  const trigrav::ThreeViewCovarianceLayout layout =
      trigrav::ThreeViewCovarianceLayout::For(c.model);
  const int n = layout.Size();
  trigrav::InitializeAndRefineOptions options;
  options.bundle_adjustment.rotation_model = c.model;
  options.bundle_adjustment.gravity_sigma_deg = c.gravity_sigma_deg;
  options.bundle_adjustment.pixel_sigma_px = FLAGS_noise_px;
  options.bundle_adjustment.compute_covariance = true;
  options.robust.ransac.max_error = FLAGS_threshold_px;
  const trigrav::SyntheticSceneOptions scene_options = SceneOptions(FLAGS_points, c.imu_noise_deg);
  std::mt19937_64 rng(FLAGS_seed);
  Eigen::VectorXd sum_error = Eigen::VectorXd::Zero(n),
                  sum_squared_error = Eigen::VectorXd::Zero(n);
  Eigen::VectorXd sum_variance = Eigen::VectorXd::Zero(n);
  std::vector<std::vector<double>> z(n);  // per parameter: e / sigma of each scene
  std::vector<double> normalised;
  int failures = 0;
  for (int s = 0; s < num_scenes; ++s) {
    const trigrav::SyntheticScene scene = trigrav::GenerateSyntheticScene(scene_options, &rng);
    const trigrav::ThreeViewObservations observations = trigrav::ToObservations(scene);
    options.robust.ransac.seed = static_cast<std::uint64_t>(s);
    const trigrav::ThreeViewEstimate estimate = trigrav::InitializeAndRefine(observations, options);
    const Eigen::MatrixXd& covariance = estimate.refinement.covariance;
    if (!estimate.success || estimate.refinement_runs == 0 || covariance.rows() != n) {
      ++failures;
      continue;
    }
    const Eigen::VectorXd error = trigrav::ThreeViewPoseDifference(
        c.model, estimate.refined, scene.ground_truth, observations.gravity_in_cam);
    sum_error += error;
    sum_squared_error += error.cwiseAbs2();
    sum_variance += covariance.diagonal();
    for (int i = 0; i < n; ++i) z[i].push_back(std::abs(error[i]) / std::sqrt(covariance(i, i)));
    normalised.push_back(error.dot(covariance.ldlt().solve(error)));
  }
  const double count = static_cast<double>(normalised.size());
  std::printf("\n%s, gravity_sigma_deg %g: %d scenes, %d without a covariance\n", c.name.c_str(),
              c.gravity_sigma_deg, num_scenes, failures);
  std::printf("%-16s %15s %14s %14s %8s %10s %10s\n", "parameter", "predicted sigma",
              "empirical std", "empirical mean", "ratio", "RMS e/sig", "1.48 MAD");
  const std::vector<std::string> names = ParameterNames(c.model);
  for (int i = 0; i < n; ++i) {
    const double mean = sum_error[i] / count;
    const double std_dev = std::sqrt(sum_squared_error[i] / count - mean * mean);
    const double predicted = std::sqrt(sum_variance[i] / count);
    double z_squares = 0.0;
    for (const double value : z[i]) z_squares += value * value;
    std::printf("%-16s %15.3e %14.3e %14.3e %8.3f %10.3f %10.3f\n", names[i].c_str(), predicted,
                std_dev, mean, predicted / std_dev, std::sqrt(z_squares / count),
                kMadToSigma * trigrav::Median(z[i]));
  }
  std::printf("normalised error e^T Sigma^-1 e: mean %.2f, median %.2f (dimension %d)\n",
              trigrav::Mean(normalised), trigrav::Median(normalised), n);
}

// Median time of ComputeThreeViewPoseCovariance and of ceres::Covariance (SPARSE_QR, the pose
// blocks in Ceres' tangent coordinates) on refined problems of num_points inlier triplets, and of
// building and solving them.
void TimeCovariance(RotationModel model, int num_points, int num_problems) {
  trigrav::SyntheticSceneOptions scene_options = SceneOptions(num_points, 0.0);
  scene_options.outlier_ratio = 0.0;
  trigrav::ThreeViewBundleAdjustmentOptions options;
  options.rotation_model = model;
  options.gravity_sigma_deg = kExactGravitySigmaDeg;
  std::mt19937_64 rng(FLAGS_seed);
  std::vector<double> solve_s, ours_s, ceres_s;
  for (int p = 0; p < num_problems; ++p) {
    const trigrav::SyntheticScene scene = trigrav::GenerateSyntheticScene(scene_options, &rng);
    const trigrav::ThreeViewObservations observations = trigrav::ToObservations(scene);
    trigrav::ThreeViewBundleAdjuster adjuster(observations, {}, options);
    auto start = std::chrono::steady_clock::now();
    if (!adjuster.Build(scene.ground_truth) || !adjuster.Solve().success) continue;
    solve_s.push_back(Seconds(start));
    Eigen::MatrixXd covariance;
    std::string message;
    start = std::chrono::steady_clock::now();
    const bool ours = trigrav::ComputeThreeViewPoseCovariance(
        &adjuster, options.ObservationSigma(observations), &covariance, &message);
    ours_s.push_back(Seconds(start));
    ceres::Covariance::Options ceres_options;
    ceres_options.algorithm_type = ceres::SPARSE_QR;
    ceres::Covariance ceres_covariance(ceres_options);
    const std::vector<const double*> blocks = {adjuster.RotationBlock(2), adjuster.RotationBlock(3),
                                               adjuster.CenterBlock(2), adjuster.CenterBlock(3)};
    Eigen::MatrixXd tangent(covariance.rows(), covariance.cols());
    start = std::chrono::steady_clock::now();
    const bool theirs = ceres_covariance.Compute(blocks, adjuster.problem()) &&
                        ceres_covariance.GetCovarianceMatrixInTangentSpace(blocks, tangent.data());
    ceres_s.push_back(Seconds(start));
    CHECK(ours && theirs) << "covariance failed on a well-posed problem: " << message;
  }
  std::printf(
      "%-14s %4d points: build + refinement from the truth %6.2f ms, "
      "ComputeThreeViewPoseCovariance %6.3f ms, ceres::Covariance SPARSE_QR %6.2f ms\n",
      model == RotationModel::kYawOnly ? "yaw-only" : "gravity-prior", num_points,
      1e3 * trigrav::Median(solve_s), 1e3 * trigrav::Median(ours_s),
      1e3 * trigrav::Median(ceres_s));
}

}  // namespace

int main(int argc, char** argv) {
  trigrav::examples::ParseToolFlags("Predicted against empirical sigmas of the refined pose.",
                                    __FILE__, &argc, &argv);
  using trigrav::examples::RequireFlag;
  RequireFlag(FLAGS_scenes > 0, "--scenes must be positive");
  RequireFlag(FLAGS_points >= 20, "--points must be >= 20");
  RequireFlag(FLAGS_noise_px > 0.0 && std::isfinite(FLAGS_noise_px),
              "--noise_px must be positive and finite");
  RequireFlag(FLAGS_imu_noise_deg > 0.0 && std::isfinite(FLAGS_imu_noise_deg),
              "--imu_noise_deg must be positive and finite");
  RequireFlag(FLAGS_outlier_ratio >= 0.0 && FLAGS_outlier_ratio < 1.0,
              "--outlier_ratio must be in [0, 1)");
  RequireFlag(FLAGS_threshold_px > 0.0 && std::isfinite(FLAGS_threshold_px),
              "--threshold_px must be positive and finite");
  RequireFlag(FLAGS_cost_problems >= 0, "--cost_problems must be >= 0");
  const int num_scenes = FLAGS_quick ? 50 : FLAGS_scenes;
  const int cost_problems = FLAGS_quick ? 3 : FLAGS_cost_problems;

  std::printf(
      "Covariance calibration (seed %llu): %d triplets, %.2f px noise, %.0f %% outliers, "
      "InitializeAndRefine defaults, pixel_sigma_px = noise\n",
      static_cast<unsigned long long>(FLAGS_seed), FLAGS_points, FLAGS_noise_px,
      100.0 * FLAGS_outlier_ratio);
  std::vector<Case> cases = {
      {"yaw-only, exact gravity", RotationModel::kYawOnly, 0.0, kExactGravitySigmaDeg},
      {"gravity-prior, exact gravity", RotationModel::kGravityPrior, 0.0, kExactGravitySigmaDeg}};
  // The IMU's sigma, as gravity_sigma_deg is documented; and sqrt(2) times it, the sigma of the
  // prior's residual when camera 1's gravity is as noisy as the others'.
  for (const double factor : {1.0, std::sqrt(2.0)}) {
    cases.push_back({"gravity-prior, IMU pitch / roll noise " + Format(FLAGS_imu_noise_deg),
                     RotationModel::kGravityPrior, FLAGS_imu_noise_deg,
                     factor * FLAGS_imu_noise_deg});
  }
  for (const Case& c : cases) Calibrate(c, num_scenes);

  if (cost_problems > 0) {
    std::printf("\ncost, median of %d problems (no outliers, one thread):\n", cost_problems);
    for (const RotationModel model : {RotationModel::kYawOnly, RotationModel::kGravityPrior}) {
      for (const int num_points : {300, 650}) TimeCovariance(model, num_points, cost_problems);
    }
  }
  return 0;
}
