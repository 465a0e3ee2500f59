// Tests of trigrav::ba: refinement accuracy on synthetic scenes, refine-only, bad input.
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
#include <memory>
#include <random>
#include <stdexcept>
#include <vector>

#include "driving_scene.h"
#include "trigrav/ba/initialize_and_refine.h"
#include "trigrav/ba/refine_three_view_pose.h"
#include "trigrav/ba/three_view_bundle_adjustment.h"
#include "trigrav/evaluation/pose_errors.h"
#include "trigrav/evaluation/statistics.h"
#include "trigrav/evaluation/synthetic_scene.h"
#include "trigrav/factors/angle_manifold.h"
#include "trigrav/factors/reprojection_factors.h"
#include "trigrav/initializers/gravity.h"

namespace trigrav {
namespace {

using RotationModel = ThreeViewBundleAdjustmentOptions::RotationModel;

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
  options.robust.solver = solver;
  options.robust.ransac.local_optimization = local_optimization;
  options.bundle_adjustment.rotation_model = model;
  options.bundle_adjustment.gravity_sigma_deg = std::max(imu_noise_deg, 0.01);
  if (max_gravity_error_deg) *max_gravity_error_deg = 0.0;
  for (int p = 0; p < num_problems; ++p) {
    const SyntheticScene scene = GenerateSyntheticScene(SceneOptions(imu_noise_deg), &rng);
    const ThreeViewObservations observations = ToObservations(scene);
    options.robust.ransac.seed = static_cast<std::uint64_t>(p);
    const ThreeViewEstimate estimate = InitializeAndRefine(observations, options);
    if (!estimate.success || estimate.refinement_runs == 0) {
      ++out.failures;
      continue;
    }
    EXPECT_TRUE(estimate.refined.IsFinite());
    const ThreeViewPoseErrors raw =
        ComputeThreeViewPoseErrors(scene.ground_truth, estimate.robust.pose);
    const ThreeViewPoseErrors refined =
        ComputeThreeViewPoseErrors(scene.ground_truth, estimate.refined);
    out.raw_rotation.push_back(raw.MaxRotationDeg());
    out.raw_translation.push_back(raw.MaxTranslationDeg());
    out.refined_rotation.push_back(refined.MaxRotationDeg());
    out.refined_translation.push_back(refined.MaxTranslationDeg());
    out.ba_time_s.push_back(estimate.timings.refinement_s);
    out.ba_points.push_back(estimate.refinement.summary.num_points);
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
// the tilt already in RANSAC (the automatic max_tilt_correction_deg), so the refinement starts from
// the true motion and wins the IMU's error back; from upright RANSAC models it often cannot. The
// verdict (robust_three_view.h) refuses most of those; it cannot see the rest, where the
// gravity-free five-point estimate is as far off (15-70 deg) and explains fewer triplets, and the
// predicted precision is 0.6-1.2 deg: the limit the README's robustness section states, and the
// reason to use the gravity-prior model with an IMU.
TEST(InitializeAndRefineStatisticalTest, GravityPriorWinsBackImuTiltOnDrivingTriplets) {
  InitializeAndRefineOptions options;
  options.robust.ransac.max_error = 1.5;
  options.robust.ransac.min_iterations = 100;
  options.bundle_adjustment.rotation_model = RotationModel::kGravityPrior;
  options.bundle_adjustment.gravity_sigma_deg = 0.1;
  options.bundle_adjustment.pixel_sigma_px = 0.5;
  options.bundle_adjustment.loss_scale_px = 1.0;
  for (const bool correct_tilt : {false, true}) {
    options.robust.max_tilt_correction_deg =
        correct_tilt ? RobustThreeViewOptions::kTiltCorrectionFromGravitySigma : 0.0;
    std::vector<double> rotation;
    int failures = 0, far_off = 0;
    for (std::uint64_t seed = 1; seed <= 60; ++seed) {
      const testing_utils::DrivingScene scene = testing_utils::MakeDrivingScene(0.1, seed);
      options.robust.ransac.seed = seed;
      const ThreeViewEstimate estimate = InitializeAndRefine(scene.observations, options);
      if (!estimate.success) {
        ++failures;
        EXPECT_FALSE(estimate.message.empty());
        continue;
      }
      const ThreeViewPoseErrors e =
          ComputeThreeViewPoseErrors(scene.ground_truth, estimate.refined);
      rotation.push_back(e.MaxRotationDeg());
      far_off += e.MaxTranslationDeg() > 10.0;
    }
    std::printf(
        "gravity prior, 0.1 deg IMU, 60 driving triplets, tilt correction %d: %d refused, %d "
        "successes with translation error > 10 deg, median rotation error %.4f deg\n",
        correct_tilt, failures, far_off, Median(rotation));
    if (correct_tilt) {
      EXPECT_LE(failures, 8);
      EXPECT_LE(far_off, 1);
      EXPECT_LT(Median(rotation), 0.05);  // the IMU's relative tilt error alone is 0.14 deg
    } else {
      EXPECT_GE(failures + far_off, 10)
          << "the scenes no longer show the failure of upright RANSAC";
      EXPECT_GE(failures, 2 * far_off);  // measured: 14 refused, 6 not
    }
  }
}

// A gravity-free (5pt) RANSAC pose refined with the yaw-only model under 0.1 deg of IMU noise: the
// exact gravity the refinement imposes can pull the verified pose far off (KITTI 00: 9 triplets
// more than 10 deg off before the check); such a refinement is a failure, never a success far off.
TEST(InitializeAndRefineStatisticalTest, YawOnlyRefinementThatLeavesTheVerifiedPoseFails) {
  InitializeAndRefineOptions options;
  options.robust.solver = InitialSolver::kEssential5pt;
  options.robust.ransac.max_error = 1.5;
  int shifted = 0, far_off = 0;
  for (std::uint64_t seed = 1; seed <= 60; ++seed) {
    const testing_utils::DrivingScene scene = testing_utils::MakeDrivingScene(0.1, seed);
    options.robust.ransac.seed = seed;
    const ThreeViewEstimate estimate = InitializeAndRefine(scene.observations, options);
    if (!estimate.success) {
      shifted += estimate.cause == FailureCause::kRefinementShift;
      continue;
    }
    far_off +=
        ComputeThreeViewPoseErrors(scene.ground_truth, estimate.refined).MaxTranslationDeg() > 10.0;
  }
  std::printf(
      "5pt, yaw-only, 0.1 deg IMU, 60 driving triplets: %d refinements refused, %d "
      "successes more than 10 deg off\n",
      shifted, far_off);
  // Measured: 22 refused, 2 left, whose five-point RANSAC pose is itself that far off (these weak
  // forward-motion scenes; a gravity-free method has no gravity-free estimate to be compared with).
  EXPECT_GE(shifted, 10);
  EXPECT_LE(far_off, 2);
}

TEST(InitializeAndRefineTest, RefineFalseKeepsTheInitialPose) {
  std::mt19937_64 rng(4);
  const SyntheticScene scene = GenerateSyntheticScene(SceneOptions(0.0), &rng);
  InitializeAndRefineOptions options;
  options.refine = false;
  const ThreeViewEstimate estimate = InitializeAndRefine(ToObservations(scene), options);
  ASSERT_TRUE(estimate.success) << estimate.message;
  EXPECT_EQ(estimate.refinement_runs, 0);
  EXPECT_FALSE(estimate.refinement.summary.success);
  EXPECT_EQ(estimate.refined.cam2_from_cam1.R, estimate.robust.pose.cam2_from_cam1.R);
  EXPECT_EQ(estimate.refined.cam3_from_cam1.t, estimate.robust.pose.cam3_from_cam1.t);
}

// A triplet with ~300 inliers: noise-free, both rotation models converge to the truth.
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
      ASSERT_GE(estimate.refinement_runs, 1) << estimate.message;
      EXPECT_GE(estimate.refinement.summary.num_points, 280);
      EXPECT_EQ(estimate.refinement.points_in_cam1.size(), estimate.refinement.triplets.size());
      const ThreeViewPoseErrors e =
          ComputeThreeViewPoseErrors(scene.ground_truth, estimate.refined);
      EXPECT_LT(e.MaxRotationDeg(), 1e-6);
      EXPECT_LT(e.MaxTranslationDeg(), 1e-6);
      EXPECT_LT(e.relative_scale, 1e-6);
    }
  }
}

// Refine-only: from a perturbed true pose on the true inliers, RefineThreeViewPose reaches the
// truth (noise-free), returns one refined point per triplet in the problem, each matching the
// scene's point in camera 1's frame, and equals the first bundle adjustment of InitializeAndRefine
// started from the same pose.
TEST(RefineThreeViewPoseTest, ReachesTheTruthAndReturnsThePoints) {
  std::mt19937_64 rng(7);
  SyntheticSceneOptions scene_options = SceneOptions(0.0);
  scene_options.num_points = 100;
  scene_options.pixel_noise_px = 0.0;
  const SyntheticScene scene = GenerateSyntheticScene(scene_options, &rng);
  const ThreeViewObservations observations = ToObservations(scene);
  ThreeViewPose start = scene.ground_truth;
  start.cam2_from_cam1.t += Eigen::Vector3d(0.02, -0.01, 0.03);
  start.cam3_from_cam1.t += Eigen::Vector3d(-0.03, 0.02, 0.01);
  ThreeViewBundleAdjustmentOptions options;
  options.rotation_model = RotationModel::kGravityPrior;
  const ThreeViewRefinement refinement =
      RefineThreeViewPose(observations, start, scene.is_inlier, options);
  ASSERT_TRUE(refinement.summary.success) << refinement.summary.message;
  const ThreeViewPoseErrors e = ComputeThreeViewPoseErrors(scene.ground_truth, refinement.pose);
  EXPECT_LT(e.MaxRotationDeg(), 1e-6);
  EXPECT_LT(e.MaxTranslationDeg(), 1e-6);
  EXPECT_NEAR(refinement.pose.cam2_from_cam1.Center().norm(), 1.0, 1e-12);
  ASSERT_EQ(refinement.points_in_cam1.size(), refinement.triplets.size());
  EXPECT_GE(refinement.triplets.size(), 70u);
  // Camera 1 is the world frame's camera 1 scaled so that |C2| = 1.
  const double scale = 1.0 / scene.ground_truth.cam2_from_cam1.Center().norm();
  for (std::size_t p = 0; p < refinement.triplets.size(); ++p) {
    const int i = refinement.triplets[p];
    ASSERT_TRUE(scene.is_inlier[i]);
    const Eigen::Vector3d truth =
        scale * (scene.cam_from_world[0] * (scene.points_in_world[i] - scene.center_in_world[0]));
    EXPECT_LT((refinement.points_in_cam1[p] - truth).norm(), 1e-6 * truth.norm()) << i;
  }
  EXPECT_LT(refinement.summary.FinalCost(), 1e-12);
  EXPECT_GT(refinement.summary.Iterations(), 0);
  EXPECT_FALSE(refinement.summary.BriefReport().empty());
}

TEST(RefineThreeViewPoseTest, BadInput) {
  std::mt19937_64 rng(8);
  const SyntheticScene scene = GenerateSyntheticScene(SceneOptions(0.0), &rng);
  const ThreeViewObservations observations = ToObservations(scene);
  const ThreeViewBundleAdjustmentOptions options;
  std::vector<char> short_mask(observations.size() - 1, 1);
  EXPECT_THROW(RefineThreeViewPose(observations, scene.ground_truth, short_mask, options),
               std::invalid_argument);
  const std::vector<char> no_inliers(observations.size(), 0);
  const ThreeViewRefinement none =
      RefineThreeViewPose(observations, scene.ground_truth, no_inliers, options);
  EXPECT_FALSE(none.summary.success);
  EXPECT_NE(none.summary.message.find("no inlier"), std::string::npos);
  ThreeViewPose nan_pose = scene.ground_truth;
  nan_pose.cam3_from_cam1.t.x() = std::numeric_limits<double>::quiet_NaN();
  const ThreeViewRefinement failed =
      RefineThreeViewPose(observations, nan_pose, scene.is_inlier, options);
  EXPECT_FALSE(failed.summary.success);
  EXPECT_FALSE(failed.summary.message.empty());
  EXPECT_TRUE(failed.points_in_cam1.empty());
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
    o.cameras[2].params[0] = focal;
    EXPECT_THROW(InitializeAndRefine(o, options), std::invalid_argument);
  }
  {
    ThreeViewObservations o = ValidObservations();
    for (auto& view : o.pixels) view.resize(2);  // fewer than a minimal sample
    ExpectRejected(o, options);
  }
  {
    InitializeAndRefineOptions bad = options;
    bad.robust.ransac.max_error = -1.0;
    EXPECT_THROW(InitializeAndRefine(ValidObservations(), bad), std::invalid_argument);
    bad = options;
    bad.bundle_adjustment.loss_scale_px = 0.0;
    EXPECT_THROW(InitializeAndRefine(ValidObservations(), bad), std::invalid_argument);
  }
}

// An adjuster given the observations' inlier error takes the same steps as one that builds its
// own; an error that is missing or of other observations is refused.
TEST(ThreeViewBundleAdjusterTest, SharedInlierErrorGivesTheSameRefinement) {
  std::mt19937_64 rng(9);
  const SyntheticScene scene = GenerateSyntheticScene(SceneOptions(0.0), &rng);
  const ThreeViewObservations o = ToObservations(scene);
  const ThreeViewBundleAdjustmentOptions options;
  ThreeViewPose initial = scene.ground_truth;
  initial.cam2_from_cam1.t += Eigen::Vector3d(0.02, -0.01, 0.01);
  ThreeViewBundleAdjuster own(o, {}, options);
  ThreeViewBundleAdjuster shared(o, std::make_shared<const ThreeViewReprojectionError>(o), {},
                                 options);
  ASSERT_TRUE(own.Build(initial));
  ASSERT_TRUE(shared.Build(initial));
  ASSERT_TRUE(own.Solve().success);
  ASSERT_TRUE(shared.Solve().success);
  EXPECT_EQ(own.CurrentPose().cam2_from_cam1.t, shared.CurrentPose().cam2_from_cam1.t);
  EXPECT_EQ(own.CurrentPose().cam3_from_cam1.R, shared.CurrentPose().cam3_from_cam1.R);
  EXPECT_EQ(own.points(), shared.points());

  EXPECT_THROW(ThreeViewBundleAdjuster(o, nullptr, {}, options), std::invalid_argument);
  const auto other = std::make_shared<const ThreeViewReprojectionError>(ValidObservations());
  ASSERT_NE(other->size(), o.size());
  EXPECT_THROW(ThreeViewBundleAdjuster(o, other, {}, options), std::invalid_argument);
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
  EXPECT_EQ(adjuster.message(),
            "initial pose has no baseline between cameras 1 and 2 (|C2| = 0, at most 1e-12)");
  const ThreeViewBundleAdjustmentSummary summary = adjuster.Solve();
  EXPECT_FALSE(summary.success);
  EXPECT_FALSE(summary.message.empty());
}

// The pose's scale is free: a translation of 1e300 refines as one of 1 (its |C2| does not overflow
// to a "zero" baseline). Only |C2| <= 1e-12, or a centre -R^T t that overflows, is refused, by
// name.
TEST(ThreeViewBundleAdjusterTest, TakesAnyFiniteBaselineAndNamesAMissingOne) {
  std::mt19937_64 rng(10);
  const SyntheticScene scene = GenerateSyntheticScene(SceneOptions(0.0), &rng);
  const ThreeViewObservations o = ToObservations(scene);
  const ThreeViewBundleAdjustmentOptions options;
  ThreeViewPose huge = scene.ground_truth;
  huge.cam2_from_cam1.t *= 1e300;
  huge.cam3_from_cam1.t *= 1e300;
  const ThreeViewRefinement unit =
      RefineThreeViewPose(o, scene.ground_truth, scene.is_inlier, options);
  const ThreeViewRefinement from_huge = RefineThreeViewPose(o, huge, scene.is_inlier, options);
  ASSERT_TRUE(unit.summary.success) << unit.summary.message;
  ASSERT_TRUE(from_huge.summary.success) << from_huge.summary.message;
  EXPECT_LT((from_huge.pose.cam3_from_cam1.t - unit.pose.cam3_from_cam1.t).norm(), 1e-12);
  EXPECT_LT((from_huge.pose.cam3_from_cam1.R - unit.pose.cam3_from_cam1.R).norm(), 1e-12);

  ThreeViewBundleAdjuster adjuster(o, {}, options);
  ThreeViewPose tiny = scene.ground_truth;
  tiny.cam2_from_cam1.t *= 1e-13 / tiny.cam2_from_cam1.Center().norm();
  EXPECT_FALSE(adjuster.Build(tiny));
  EXPECT_EQ(adjuster.message(),
            "initial pose has no baseline between cameras 1 and 2 (|C2| = 1e-13, at most 1e-12)");
  ThreeViewPose overflowing = scene.ground_truth;  // finite R and t, C2 = -R^T t is not
  overflowing.cam2_from_cam1.R = RotationAboutY(M_PI / 4.0);
  overflowing.cam2_from_cam1.t =
      Eigen::Vector3d(1.0, 0.0, 1.0) * std::numeric_limits<double>::max();
  EXPECT_FALSE(adjuster.Build(overflowing));
  EXPECT_EQ(adjuster.message(),
            "initial pose's camera 2 centre -R^T t overflows (t too large for doubles)");
}

}  // namespace
}  // namespace trigrav
