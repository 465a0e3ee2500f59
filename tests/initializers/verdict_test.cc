// The robust estimator's verdict (derivations.md section 7.7): chance consensus, predicted
// precision and the gravity-free comparison, on synthetic scenes with known truth. The mistakes
// matrix on real KITTI tracks is tests/examples/check_kitti_mistakes.cmake.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "trigrav/evaluation/pose_errors.h"
#include "trigrav/evaluation/synthetic_scene.h"
#include "trigrav/initializers/robust_three_view.h"

namespace trigrav {
namespace {

SyntheticScene Scene(int num_points, double outlier_ratio, std::mt19937_64* rng) {
  SyntheticSceneOptions options;
  options.num_points = num_points;
  options.pixel_noise_px = 1.0;
  options.outlier_ratio = outlier_ratio;
  return GenerateSyntheticScene(options, rng);
}

double LargestErrorDeg(const SyntheticScene& scene, const ThreeViewPose& pose) {
  const ThreeViewPoseErrors errors = ComputeThreeViewPoseErrors(scene.ground_truth, pose);
  return std::max(errors.MaxRotationDeg(), errors.MaxTranslationDeg());
}

// The case: 3-6 triplets with 20 % outliers gave successes up to 176 deg off.
TEST(Verdict, FewTripletsWithOutliersNeverSucceedFarOff) {
  std::mt19937_64 rng(5);
  int successes = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const int n = 3 + trial % 4;
    const SyntheticScene scene = Scene(n, 0.2, &rng);
    RobustThreeViewOptions options;
    options.ransac.seed = trial;
    const RobustThreeViewEstimate estimate =
        EstimateThreeViewPoseRobust(ToObservations(scene), options);
    if (!estimate.success) {
      EXPECT_FALSE(estimate.message.empty());
      continue;
    }
    ++successes;
    EXPECT_LT(LargestErrorDeg(scene, estimate.pose), 5.0) << "trial " << trial << ", " << n;
  }
  // Fewer than min_inliers (15) triplets never pass.
  EXPECT_EQ(successes, 0);
}

TEST(Verdict, MinimalSampleIsNeverEvidence) {
  std::mt19937_64 rng(8);
  const SyntheticScene scene = Scene(3, 0.0, &rng);
  RobustThreeViewOptions options;
  options.min_inliers = 0;  // the number of false alarms alone
  const RobustThreeViewEstimate estimate =
      EstimateThreeViewPoseRobust(ToObservations(scene), options);
  ASSERT_FALSE(estimate.success);
  EXPECT_NE(estimate.message.find("by chance"), std::string::npos) << estimate.message;
  EXPECT_GE(estimate.evidence.log10_nfa, 0.0);
  EXPECT_LE(estimate.message.size(), 200u) << estimate.message;
}

// The predicted sigma matches the spread of the actual errors: over 60 scenes of 30 triplets,
// the RMS of (error / predicted sigma) of the yaws is near 1 (0.5-2).
TEST(Verdict, PredictedPrecisionMatchesActualErrors) {
  std::mt19937_64 rng(11);
  double sum_squared_ratio = 0.0;
  int count = 0;
  for (int trial = 0; trial < 60; ++trial) {
    const SyntheticScene scene = Scene(30, 0.0, &rng);
    RobustThreeViewOptions options;
    options.ransac.seed = trial;
    options.solver = InitialSolver::kTrifocal4pt;  // least squares on all inliers
    options.max_pose_sigma_deg = std::numeric_limits<double>::infinity();
    const RobustThreeViewEstimate estimate =
        EstimateThreeViewPoseRobust(ToObservations(scene), options);
    ASSERT_TRUE(estimate.success) << estimate.message;
    const ThreeViewPoseErrors errors =
        ComputeThreeViewPoseErrors(scene.ground_truth, estimate.pose);
    // Threshold 2 px: the prediction assumes sigma = 2 / 3 px; the scenes have 1 px.
    const double predicted = estimate.evidence.rotation_sigma_deg * 1.5;
    ASSERT_GT(predicted, 0.0);
    for (const double e : errors.rotation_deg) {
      sum_squared_ratio += (e / predicted) * (e / predicted);
      ++count;
    }
  }
  ASSERT_GT(count, 80);
  const double rms = std::sqrt(sum_squared_ratio / count);
  EXPECT_GT(rms, 0.5);
  EXPECT_LT(rms, 2.0);
}

TEST(Verdict, CorrectSceneHasOverwhelmingEvidence) {
  std::mt19937_64 rng(3);
  const SyntheticScene scene = Scene(300, 0.2, &rng);
  const RobustThreeViewEstimate estimate =
      EstimateThreeViewPoseRobust(ToObservations(scene), RobustThreeViewOptions());
  ASSERT_TRUE(estimate.success) << estimate.message;
  EXPECT_LT(estimate.evidence.log10_nfa, -100.0);
  EXPECT_LT(estimate.evidence.rotation_sigma_deg, 0.1);
  EXPECT_LT(estimate.evidence.direction_sigma_deg, 1.0);
  EXPECT_LT(LargestErrorDeg(scene, estimate.pose), 2.0);
}

// Pixels of views 2 and 3 swapped with the gravity in order: never a success far off, and a
// failure names the view order.
TEST(Verdict, SwappedViewsAreNamed) {
  std::mt19937_64 rng(21);
  for (int trial = 0; trial < 6; ++trial) {
    const SyntheticScene scene = Scene(300, 0.1, &rng);
    ThreeViewObservations observations = ToObservations(scene);
    std::swap(observations.pixels[1], observations.pixels[2]);
    RobustThreeViewOptions options;
    options.ransac.seed = trial;
    const RobustThreeViewEstimate estimate = EstimateThreeViewPoseRobust(observations, options);
    ASSERT_FALSE(estimate.success) << "trial " << trial;
    EXPECT_LE(estimate.message.size(), 240u) << estimate.message;
  }
}

TEST(Verdict, OptionsAreChecked) {
  RobustThreeViewOptions options;
  options.max_pose_sigma_deg = 0.0;
  EXPECT_THROW(options.Check(), std::invalid_argument);
  options.max_pose_sigma_deg = std::nan("");
  EXPECT_THROW(options.Check(), std::invalid_argument);
  options.max_pose_sigma_deg = std::numeric_limits<double>::infinity();
  EXPECT_NO_THROW(options.Check());
  options.min_inliers = -1;
  EXPECT_THROW(options.Check(), std::invalid_argument);
}

// Another camera's intrinsics, a resized image or (row, column) pixels: named before any pose.
TEST(Verdict, PixelsThatTheIntrinsicsCannotProduceAreNamed) {
  std::mt19937_64 rng(4);
  const SyntheticScene scene = Scene(200, 0.0, &rng);  // 640 x 480, principal point (320, 240)
  for (int mistake = 0; mistake < 3; ++mistake) {
    ThreeViewObservations observations = ToObservations(scene);
    for (auto& view : observations.pixels) {
      for (Eigen::Vector2d& pixel : view) {
        pixel = mistake == 0   ? Eigen::Vector2d(pixel * 2.0)  // double-resolution pixels
                : mistake == 1 ? Eigen::Vector2d(pixel * 0.5)  // half-resolution pixels
                               : Eigen::Vector2d(pixel.y(), pixel.x()) * 1.5;
      }
    }
    const RobustThreeViewEstimate estimate =
        EstimateThreeViewPoseRobust(observations, RobustThreeViewOptions());
    ASSERT_FALSE(estimate.success) << "mistake " << mistake;
    EXPECT_NE(estimate.message.find("intrinsics"), std::string::npos) << estimate.message;
    EXPECT_LE(estimate.message.size(), 200u) << estimate.message;
  }
}

// The image a principal point implies, with a tenth of it as margin (derivations.md 7.7): pixels
// stretched to 1.08 of the 640 x 480 image are judged by the other tests; to 1.12 (another
// camera's image, as KITTI's tracks with another camera's intrinsics) they are refused as such.
TEST(Verdict, PixelsBeyondATenthOfTheImageAreAnotherCamerasIntrinsics) {
  std::mt19937_64 rng(5);
  const SyntheticScene scene = Scene(200, 0.0, &rng);  // 640 x 480, principal point (320, 240)
  for (const double stretch : {1.08, 1.12}) {
    ThreeViewObservations observations = ToObservations(scene);
    for (auto& view : observations.pixels) {
      for (Eigen::Vector2d& pixel : view) pixel.x() *= stretch;
    }
    const RobustThreeViewEstimate estimate =
        EstimateThreeViewPoseRobust(observations, RobustThreeViewOptions());
    EXPECT_EQ(estimate.cause == FailureCause::kPixelsVsIntrinsics, stretch > 1.1)
        << stretch << ": " << estimate.message;
  }
}

// A repeated triplet (the same pixels in all three views, as duplicate keypoints give) adds no
// evidence: 4 distinct triplets given 15 times each are too few (counted 60 times, they pass
// 14 deg off), and 100 triplets given twice have the evidence of 100, not 200 (which would
// predict sigmas 0.71 times as large).
TEST(Verdict, RepeatedTripletsCountOnce) {
  std::mt19937_64 rng(6);
  const SyntheticScene scene = Scene(100, 0.0, &rng);
  const ThreeViewObservations once = ToObservations(scene);
  ThreeViewObservations four = once, twice = once;
  for (int k = 0; k < 3; ++k) {
    const std::vector<Eigen::Vector2d>& pixels = once.pixels[k];
    four.pixels[k].clear();
    for (int copy = 0; copy < 15; ++copy) {
      four.pixels[k].insert(four.pixels[k].end(), pixels.begin(), pixels.begin() + 4);
    }
    twice.pixels[k].insert(twice.pixels[k].end(), pixels.begin(), pixels.end());
  }
  const RobustThreeViewEstimate refused =
      EstimateThreeViewPoseRobust(four, RobustThreeViewOptions());
  ASSERT_FALSE(refused.success);
  EXPECT_EQ(refused.cause, FailureCause::kTooFewInliers);
  EXPECT_NE(
      refused.message.find("only 4 distinct triplets given (60 with repeats; min_inliers 15)"),
      std::string::npos)
      << refused.message;

  const RobustThreeViewEstimate single =
      EstimateThreeViewPoseRobust(once, RobustThreeViewOptions());
  const RobustThreeViewEstimate doubled =
      EstimateThreeViewPoseRobust(twice, RobustThreeViewOptions());
  ASSERT_TRUE(single.success) << single.message;
  ASSERT_TRUE(doubled.success) << doubled.message;
  EXPECT_NEAR(doubled.ransac.num_inliers, 2 * single.ransac.num_inliers, 4);
  EXPECT_NEAR(doubled.evidence.rotation_sigma_deg / single.evidence.rotation_sigma_deg, 1.0, 0.1);
  EXPECT_NEAR(doubled.evidence.direction_sigma_deg / single.evidence.direction_sigma_deg, 1.0, 0.1);
  // Each inlier adds about log10(alpha) = -5 (-400 in all); 200 would give about -800.
  EXPECT_NEAR(doubled.evidence.log10_nfa, single.evidence.log10_nfa, 15.0);
}

// Fewer triplets than min_inliers are named as such, whatever RANSAC made of them; a chance
// consensus under a threshold that lets most random triplets fit names the threshold.
TEST(Verdict, TooFewTripletsAndALooseThresholdAreNamed) {
  std::mt19937_64 rng(7);
  const SyntheticScene few = Scene(10, 0.0, &rng);
  const RobustThreeViewEstimate too_few =
      EstimateThreeViewPoseRobust(ToObservations(few), RobustThreeViewOptions());
  EXPECT_EQ(too_few.cause, FailureCause::kTooFewInliers);
  EXPECT_NE(too_few.message.find("only 10 triplets given (min_inliers 15)"), std::string::npos)
      << too_few.message;

  const SyntheticScene scene = Scene(40, 0.0, &rng);
  RobustThreeViewOptions loose;
  loose.ransac.max_error = 1e6;
  const RobustThreeViewEstimate chance = EstimateThreeViewPoseRobust(ToObservations(scene), loose);
  EXPECT_EQ(chance.cause, FailureCause::kChanceConsensus);
  EXPECT_NE(chance.message.find("the threshold 1e+06 lets a random triplet fit"), std::string::npos)
      << chance.message;
  EXPECT_LE(chance.message.size(), 200u) << chance.message;
}

}  // namespace
}  // namespace trigrav
