// Tests of trigrav::factors and trigrav::ba: derivatives, manifolds, refinement accuracy, bad
// input.
#include <ceres/gradient_checker.h>
#include <ceres/manifold.h>
#include <ceres/manifold_test_utils.h>
#include <ceres/sphere_manifold.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

#include "driving_scene.h"
#include "trigrav/ba/initialize_and_refine.h"
#include "trigrav/ba/three_view_bundle_adjustment.h"
#include "trigrav/factors/angle_manifold.h"
#include "trigrav/factors/reprojection_factors.h"
#include "trigrav/initializers/gravity.h"
#include "trigrav/initializers/pose_metrics.h"
#include "trigrav/initializers/synthetic_scene.h"

namespace trigrav {
namespace {

using RotationModel = ThreeViewBundleAdjustmentOptions::RotationModel;

PinholeCamera TestCamera() {
  PinholeCamera camera;
  camera.fx = 500.0;
  camera.fy = 510.0;
  camera.cx = 320.0;
  camera.cy = 240.0;
  return camera;
}

// Probes a cost function at the given parameters; expects analytic == numeric derivatives.
void ExpectGradientsMatch(const ceres::CostFunction& cost,
                          const std::vector<const ceres::Manifold*>& manifolds,
                          const std::vector<const double*>& parameters) {
  ceres::NumericDiffOptions numeric_options;
  ceres::GradientChecker checker(&cost, &manifolds, numeric_options);
  ceres::GradientChecker::ProbeResults results;
  EXPECT_TRUE(checker.Probe(parameters.data(), 1e-7, &results)) << results.error_log;
  EXPECT_TRUE(results.return_value);
  EXPECT_LT(results.maximum_relative_error, 1e-7);
}

TEST(FactorsTest, YawOnlyReprojectionGradient) {
  const Eigen::Matrix3d a_cam = GravityAlignmentFromPitchRoll(0.1, -0.05);
  const Eigen::Matrix3d a_ref = GravityAlignmentFromPitchRoll(-0.07, 0.12);
  std::unique_ptr<ceres::CostFunction> cost(
      YawOnlyReprojectionError::Create(TestCamera(), a_cam, a_ref, Eigen::Vector2d(300.0, 250.0)));
  const double yaw = 0.3;
  const double center[3] = {0.5, -0.2, 0.1};
  const double point[3] = {1.0, 0.5, 12.0};
  YawManifold yaw_manifold;
  ExpectGradientsMatch(*cost, {&yaw_manifold, nullptr, nullptr}, {&yaw, center, point});
}

TEST(FactorsTest, YawOnlyReprojectionMatchesPoseProjection) {
  const Eigen::Matrix3d a_cam = GravityAlignmentFromPitchRoll(0.1, -0.05);
  const Eigen::Matrix3d a_ref = GravityAlignmentFromPitchRoll(-0.07, 0.12);
  const double yaw = 0.3;
  const Eigen::Vector3d center(0.5, -0.2, 0.1), point(1.0, 0.5, 12.0);
  const Eigen::Matrix3d R = a_cam.transpose() * RotationAboutY(yaw) * a_ref;
  const Eigen::Vector3d x = R * (point - center);
  const PinholeCamera camera = TestCamera();
  const Eigen::Vector2d pixel(camera.fx * x.x() / x.z() + camera.cx,
                              camera.fy * x.y() / x.z() + camera.cy);
  const YawOnlyReprojectionError functor(camera, a_cam, a_ref, pixel);
  double residuals[2];
  ASSERT_TRUE(functor(&yaw, center.data(), point.data(), residuals));
  EXPECT_NEAR(residuals[0], 0.0, 1e-9);
  EXPECT_NEAR(residuals[1], 0.0, 1e-9);
}

TEST(FactorsTest, ReprojectionGradient) {
  std::unique_ptr<ceres::CostFunction> cost(
      ReprojectionError::Create(TestCamera(), Eigen::Vector2d(310.0, 230.0)));
  Eigen::Quaterniond q(Eigen::AngleAxisd(0.2, Eigen::Vector3d(0.3, 1.0, -0.2).normalized()));
  const double quaternion[4] = {q.w(), q.x(), q.y(), q.z()};
  const double center[3] = {-0.4, 0.3, 0.2};
  const double point[3] = {-1.0, 0.8, 15.0};
  ceres::QuaternionManifold quaternion_manifold;
  ExpectGradientsMatch(*cost, {&quaternion_manifold, nullptr, nullptr},
                       {quaternion, center, point});
  ExpectGradientsMatch(*cost, {nullptr, nullptr, nullptr}, {quaternion, center, point});
}

TEST(FactorsTest, ReferenceReprojectionGradient) {
  std::unique_ptr<ceres::CostFunction> cost(
      ReferenceReprojectionError::Create(TestCamera(), Eigen::Vector2d(310.0, 230.0)));
  const double point[3] = {-1.0, 0.8, 15.0};
  ExpectGradientsMatch(*cost, {nullptr}, {point});
}

TEST(FactorsTest, GravityPriorGradientAndValue) {
  const Eigen::Vector3d g_ref = Eigen::Vector3d(0.05, 1.0, -0.1);
  const Eigen::Quaterniond q(Eigen::AngleAxisd(0.3, Eigen::Vector3d(0.2, 1.0, 0.4).normalized()));
  // Measured gravity 2 degrees away from the predicted one.
  const Eigen::Vector3d predicted = q * g_ref.normalized();
  const Eigen::Vector3d axis = predicted.cross(Eigen::Vector3d(0.3, -0.5, 0.8)).normalized();
  const double angle = 2.0 * M_PI / 180.0;
  const Eigen::Vector3d g_cam = 3.0 * (Eigen::AngleAxisd(angle, axis) * predicted);
  std::unique_ptr<ceres::CostFunction> cost(GravityPriorError::Create(g_ref, g_cam));
  const double quaternion[4] = {q.w(), q.x(), q.y(), q.z()};
  ceres::QuaternionManifold quaternion_manifold;
  ExpectGradientsMatch(*cost, {&quaternion_manifold}, {quaternion});
  ExpectGradientsMatch(*cost, {nullptr}, {quaternion});

  const GravityPriorError functor(g_ref, g_cam);
  double residuals[2];
  ASSERT_TRUE(functor(quaternion, residuals));
  EXPECT_NEAR(std::hypot(residuals[0], residuals[1]), angle, 1e-12);
  // Zero at an exact match, with finite derivatives there.
  const GravityPriorError exact(g_ref, predicted);
  ASSERT_TRUE(exact(quaternion, residuals));
  EXPECT_NEAR(residuals[0], 0.0, 1e-15);
  EXPECT_NEAR(residuals[1], 0.0, 1e-15);
  std::unique_ptr<ceres::CostFunction> exact_cost(GravityPriorError::Create(g_ref, predicted));
  ExpectGradientsMatch(*exact_cost, {&quaternion_manifold}, {quaternion});
  EXPECT_THROW(GravityPriorError(Eigen::Vector3d::Zero(), g_cam), std::invalid_argument);
}

TEST(FactorsTest, YawManifoldInvariants) {
  using Vector = Eigen::VectorXd;
  using namespace ceres;  // the matchers of manifold_test_utils.h
  const YawManifold manifold;
  const double values[][3] = {
      {0.3, 0.2, -2.0}, {3.0, 0.3, -3.0}, {-3.1, -0.2, 2.9}, {0.0, 1.5, 1.0}, {-1.0, -2.5, 3.1}};
  for (const auto& v : values) {
    const Vector x = Vector::Constant(1, v[0]);
    const Vector delta = Vector::Constant(1, v[1]);
    const Vector y = Vector::Constant(1, v[2]);
    EXPECT_THAT_MANIFOLD_INVARIANTS_HOLD(manifold, x, delta, y, 1e-9);
  }
  double wrapped = 0.0;
  const double x = 3.0, delta = 0.5;
  ASSERT_TRUE(manifold.Plus(&x, &delta, &wrapped));
  EXPECT_NEAR(wrapped, 3.5 - 2.0 * M_PI, 1e-15);
  EXPECT_GE(NormalizeAngle(M_PI), -M_PI);
  EXPECT_LT(NormalizeAngle(M_PI), M_PI);
}

// ------------------------------------------------------------------------------------------------
// Synthetic refinement.

struct RunErrors {
  std::vector<double> raw_rotation, raw_translation, refined_rotation, refined_translation;
  std::vector<double> ba_time_s, ba_points;
  int failures = 0;
};

SyntheticSceneOptions SceneOptions(double imu_noise_deg) {
  SyntheticSceneOptions options;
  options.num_points = 100;
  options.pixel_noise_px = 1.0;
  options.outlier_ratio = 0.2;
  options.imu_pitch_noise_deg = imu_noise_deg;
  options.imu_roll_noise_deg = imu_noise_deg;
  return options;
}

// Runs InitializeAndRefine on `num_problems` scenes; optionally checks gravity consistency.
RunErrors RunSynthetic(int num_problems,
                       double imu_noise_deg,
                       RotationModel model,
                       InitialSolver solver,
                       std::uint64_t seed,
                       double* max_gravity_error_deg,
                       bool local_optimization = true) {
  std::mt19937_64 rng(seed);
  RunErrors out;
  InitializeAndRefineOptions options;
  options.solver = solver;
  options.ransac.local_optimization = local_optimization;
  options.bundle_adjustment.rotation_model = model;
  options.bundle_adjustment.gravity_sigma_deg = std::max(imu_noise_deg, 0.01);
  if (max_gravity_error_deg) *max_gravity_error_deg = 0.0;
  for (int p = 0; p < num_problems; ++p) {
    const SyntheticScene scene = GenerateSyntheticScene(SceneOptions(imu_noise_deg), &rng);
    const ThreeViewObservations observations = ToObservations(scene);
    options.seed = static_cast<std::uint64_t>(p);
    const ThreeViewEstimate estimate = InitializeAndRefine(observations, options);
    if (!estimate.success || !estimate.refinement_ran) {
      ++out.failures;
      continue;
    }
    EXPECT_TRUE(estimate.refined.IsFinite());
    const ThreeViewPoseErrors raw =
        ComputeThreeViewPoseErrors(scene.ground_truth, estimate.initial);
    const ThreeViewPoseErrors refined =
        ComputeThreeViewPoseErrors(scene.ground_truth, estimate.refined);
    out.raw_rotation.push_back(raw.MaxRotationDeg());
    out.raw_translation.push_back(raw.MaxTranslationDeg());
    out.refined_rotation.push_back(refined.MaxRotationDeg());
    out.refined_translation.push_back(refined.MaxTranslationDeg());
    out.ba_time_s.push_back(estimate.ba_time_s);
    out.ba_points.push_back(estimate.ba_num_points);
    if (max_gravity_error_deg) {
      const Eigen::Vector3d g1 = observations.gravity_in_cam[0].normalized();
      const CameraPose* poses[2] = {&estimate.refined.cam2_from_cam1,
                                    &estimate.refined.cam3_from_cam1};
      for (int j = 0; j < 2; ++j) {
        *max_gravity_error_deg = std::max(
            *max_gravity_error_deg,
            DirectionErrorDeg(observations.gravity_in_cam[j + 1].normalized(), poses[j]->R * g1));
      }
    }
  }
  return out;
}

void Print(const char* name, const RunErrors& e) {
  std::cout << name << ": problems " << e.raw_rotation.size() << " (failures " << e.failures
            << ")  median rotation raw " << Median(e.raw_rotation) << " refined "
            << Median(e.refined_rotation) << " deg; translation raw " << Median(e.raw_translation)
            << " refined " << Median(e.refined_translation) << " deg; BA "
            << 1e3 * Median(e.ba_time_s) << " ms median over " << Median(e.ba_points)
            << " points\n";
}

// "Raw" is the minimal-solver estimate: RANSAC without local optimisation, so the initial pose is
// the 3-point solution of the best minimal sample. (With local optimisation the RANSAC winner is
// already a non-minimal least-squares estimate on the inliers; see the next test.)
TEST(InitializeAndRefineTest, RefinementHalvesTheMinimalSolverError) {
  double max_gravity_error_deg = 0.0;
  const RunErrors e = RunSynthetic(200, 0.0, RotationModel::kYawOnly, InitialSolver::kTrifocal3pt,
                                   1, &max_gravity_error_deg, /*local_optimization=*/false);
  Print("yaw-only, exact IMU, RANSAC without LO", e);
  ASSERT_GE(e.raw_rotation.size(), 190u);
  EXPECT_LE(Median(e.refined_rotation), 0.5 * Median(e.raw_rotation));
  EXPECT_LE(Median(e.refined_translation), 0.5 * Median(e.raw_translation));
  EXPECT_LT(max_gravity_error_deg, 1e-9);
}

// With local optimisation (the default) the raw pose is near the optimum already: refinement must
// still not make it worse.
TEST(InitializeAndRefineTest, RefinementImprovesTheLocallyOptimisedEstimate) {
  const RunErrors e = RunSynthetic(200, 0.0, RotationModel::kYawOnly, InitialSolver::kTrifocal3pt,
                                   1, nullptr, /*local_optimization=*/true);
  Print("yaw-only, exact IMU, RANSAC with LO", e);
  ASSERT_GE(e.raw_rotation.size(), 190u);
  EXPECT_LT(Median(e.refined_rotation), Median(e.raw_rotation));
  EXPECT_LT(Median(e.refined_translation), Median(e.raw_translation));
}

TEST(InitializeAndRefineTest, YawOnlyKeepsPitchAndRollFromGravity) {
  double max_gravity_error_deg = 1.0;
  const RunErrors e = RunSynthetic(20, 0.5, RotationModel::kYawOnly, InitialSolver::kTrifocal3pt, 2,
                                   &max_gravity_error_deg);
  ASSERT_FALSE(e.raw_rotation.empty());
  // R_k g_1 == g_k to rounding: the refined pitch and roll are exactly the measured ones.
  EXPECT_LT(max_gravity_error_deg, 1e-9);
}

TEST(InitializeAndRefineTest, GravityPriorBeatsYawOnlyWithImuNoise) {
  const RunErrors yaw_only =
      RunSynthetic(50, 0.5, RotationModel::kYawOnly, InitialSolver::kTrifocal3pt, 3, nullptr);
  const RunErrors prior =
      RunSynthetic(50, 0.5, RotationModel::kGravityPrior, InitialSolver::kTrifocal3pt, 3, nullptr);
  Print("yaw-only, 0.5 deg IMU", yaw_only);
  Print("gravity prior, 0.5 deg IMU", prior);
  ASSERT_GE(prior.refined_translation.size(), 40u);
  EXPECT_LT(Median(prior.refined_translation), Median(yaw_only.refined_translation));
}

// KITTI-like driving with 0.1 deg of IMU noise, 1.5 px threshold: the gravity-prior model corrects
// the tilt already in RANSAC (correct_tilt_in_ransac), so the refinement starts from the true
// motion and wins the IMU's error back; from upright RANSAC models it often cannot.
TEST(InitializeAndRefineTest, GravityPriorWinsBackImuTiltOnDrivingTriplets) {
  InitializeAndRefineOptions options;
  options.inlier_threshold_px = 1.5;
  options.ransac.min_iterations = 100;
  options.bundle_adjustment.rotation_model = RotationModel::kGravityPrior;
  options.bundle_adjustment.gravity_sigma_deg = 0.1;
  options.bundle_adjustment.pixel_sigma_px = 0.5;
  options.bundle_adjustment.loss_scale_px = 1.0;
  for (const bool correct_tilt : {false, true}) {
    options.correct_tilt_in_ransac = correct_tilt;
    std::vector<double> rotation;
    int gross = 0;
    for (std::uint64_t seed = 1; seed <= 60; ++seed) {
      const testing_utils::DrivingScene scene = testing_utils::MakeDrivingScene(0.1, seed);
      options.seed = seed;
      const ThreeViewEstimate estimate = InitializeAndRefine(scene.observations, options);
      ASSERT_TRUE(estimate.success) << estimate.message;
      const ThreeViewPoseErrors e =
          ComputeThreeViewPoseErrors(scene.ground_truth, estimate.refined);
      rotation.push_back(e.MaxRotationDeg());
      gross += e.MaxTranslationDeg() > 10.0;
    }
    std::printf(
        "gravity prior, 0.1 deg IMU, 60 driving triplets, correct_tilt_in_ransac %d: %d with "
        "translation error > 10 deg, median rotation error %.4f deg\n",
        correct_tilt, gross, Median(rotation));
    if (correct_tilt) {
      EXPECT_LE(gross, 8);
      EXPECT_LT(Median(rotation), 0.05);  // the IMU's relative tilt error alone is 0.14 deg
    } else {
      EXPECT_GE(gross, 10) << "the scenes no longer show the failure of upright RANSAC";
    }
  }
}

TEST(InitializeAndRefineTest, RefineFalseKeepsTheInitialPose) {
  std::mt19937_64 rng(4);
  const SyntheticScene scene = GenerateSyntheticScene(SceneOptions(0.0), &rng);
  InitializeAndRefineOptions options;
  options.refine = false;
  const ThreeViewEstimate estimate = InitializeAndRefine(ToObservations(scene), options);
  ASSERT_TRUE(estimate.success) << estimate.message;
  EXPECT_FALSE(estimate.refinement_ran);
  EXPECT_EQ(estimate.refined.cam2_from_cam1.R, estimate.initial.cam2_from_cam1.R);
  EXPECT_EQ(estimate.refined.cam3_from_cam1.t, estimate.initial.cam3_from_cam1.t);
}

// A triplet with ~300 inliers (the size of the 10 ms timing target, measured in the README with
// refine_synthetic_triplets, not here): noise-free, both rotation models converge to the truth.
TEST(InitializeAndRefineTest, RefinesThreeHundredInliersToTheTruth) {
  std::mt19937_64 rng(5);
  SyntheticSceneOptions scene_options = SceneOptions(0.0);
  scene_options.num_points = 375;  // 20 % outliers: 300 inliers
  scene_options.pixel_noise_px = 0.0;
  for (const RotationModel model : {RotationModel::kYawOnly, RotationModel::kGravityPrior}) {
    for (int p = 0; p < 5; ++p) {
      const SyntheticScene scene = GenerateSyntheticScene(scene_options, &rng);
      InitializeAndRefineOptions options;
      options.bundle_adjustment.rotation_model = model;
      const ThreeViewEstimate estimate = InitializeAndRefine(ToObservations(scene), options);
      ASSERT_TRUE(estimate.refinement_ran) << estimate.message;
      EXPECT_GE(estimate.ba_num_points, 280);
      const ThreeViewPoseErrors e = ComputeThreeViewPoseErrors(scene.ground_truth, estimate.refined);
      EXPECT_LT(e.MaxRotationDeg(), 1e-6);
      EXPECT_LT(e.MaxTranslationDeg(), 1e-6);
      EXPECT_LT(e.relative_scale, 1e-6);
    }
  }
}

// ------------------------------------------------------------------------------------------------
// Bad input.

ThreeViewObservations ValidObservations() {
  std::mt19937_64 rng(6);
  SyntheticSceneOptions options;
  options.num_points = 30;
  return ToObservations(GenerateSyntheticScene(options, &rng));
}

// Bad input must give success == false with a message or std::invalid_argument, never a crash.
void ExpectRejected(const ThreeViewObservations& observations,
                    const InitializeAndRefineOptions& options) {
  try {
    const ThreeViewEstimate estimate = InitializeAndRefine(observations, options);
    EXPECT_FALSE(estimate.success);
    EXPECT_FALSE(estimate.message.empty());
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()), "");
  }
}

TEST(InitializeAndRefineTest, BadInput) {
  const InitializeAndRefineOptions options;
  ExpectRejected(ThreeViewObservations(), options);  // empty
  {
    ThreeViewObservations o = ValidObservations();
    o.pixels[2].pop_back();  // mismatched sizes
    EXPECT_THROW(InitializeAndRefine(o, options), std::invalid_argument);
  }
  {
    ThreeViewObservations o = ValidObservations();
    o.pixels[1][3].x() = std::numeric_limits<double>::quiet_NaN();
    EXPECT_THROW(InitializeAndRefine(o, options), std::invalid_argument);
  }
  {
    ThreeViewObservations o = ValidObservations();
    o.gravity_in_cam[1] = Eigen::Vector3d(std::numeric_limits<double>::quiet_NaN(), 1.0, 0.0);
    EXPECT_THROW(InitializeAndRefine(o, options), std::invalid_argument);
  }
  for (const double focal : {0.0, -500.0}) {
    ThreeViewObservations o = ValidObservations();
    o.cameras[2].fx = focal;
    EXPECT_THROW(InitializeAndRefine(o, options), std::invalid_argument);
  }
  {
    ThreeViewObservations o = ValidObservations();
    for (auto& view : o.pixels) view.resize(2);  // fewer than a minimal sample
    ExpectRejected(o, options);
  }
  {
    InitializeAndRefineOptions bad = options;
    bad.inlier_threshold_px = -1.0;
    EXPECT_THROW(InitializeAndRefine(ValidObservations(), bad), std::invalid_argument);
    bad = options;
    bad.bundle_adjustment.loss_scale_px = 0.0;
    EXPECT_THROW(InitializeAndRefine(ValidObservations(), bad), std::invalid_argument);
  }
}

TEST(ThreeViewBundleAdjusterTest, RejectsNonFiniteInitialPose) {
  const ThreeViewObservations o = ValidObservations();
  ThreeViewBundleAdjuster adjuster(o, ThreeViewBundleAdjustmentConfig(),
                                   ThreeViewBundleAdjustmentOptions());
  ThreeViewPose pose;
  pose.cam2_from_cam1.t.x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(adjuster.Build(pose));
  EXPECT_FALSE(adjuster.message().empty());
  pose.cam2_from_cam1.t.setZero();  // |C2| = 0
  EXPECT_FALSE(adjuster.Build(pose));
  const ThreeViewBundleAdjustmentSummary summary = adjuster.Solve();
  EXPECT_FALSE(summary.success);
  EXPECT_TRUE(summary.pose.IsFinite());
}

}  // namespace
}  // namespace trigrav
