// A caller's stop request (RansacOptions::stop_requested, ThreeViewBundleAdjustmentOptions::
// stop_requested) ends each stage early and never gives a success: RANSAC, the robust estimate
// and its verdict, and every refinement engine inside InitializeAndRefine.

#include <gtest/gtest.h>

#include <atomic>
#include <random>

#include "trigrav/ba/initialize_and_refine.h"
#include "trigrav/evaluation/synthetic_scene.h"
#include "trigrav/initializers/robust_three_view.h"

namespace trigrav {
namespace {

using Engine = ThreeViewBundleAdjustmentOptions::Engine;

ThreeViewObservations Scene() {
  SyntheticSceneOptions options;
  options.num_points = 200;
  std::mt19937_64 rng(7);
  return ToObservations(GenerateSyntheticScene(options, &rng));
}

TEST(StopRequestTest, RansacStopsAfterTheRequestAndFails) {
  const ThreeViewObservations observations = Scene();
  RobustThreeViewOptions options;
  options.ransac.min_iterations = 200;
  int calls = 0;
  options.ransac.stop_requested = [&] { return ++calls > 5; };
  const RobustThreeViewEstimate estimate = EstimateThreeViewPoseRobust(observations, options);
  EXPECT_FALSE(estimate.success);
  EXPECT_EQ(estimate.cause, FailureCause::kStopped);
  EXPECT_NE(estimate.message.find("stopped on request"), std::string::npos);
  EXPECT_LE(calls, 8);  // checked before each sample, and once after the run
}

TEST(StopRequestTest, AStopDuringTheVerdictIsNoSuccess) {
  // The request comes after RANSAC's samples, while the verdict compares with the gravity-free
  // estimate: the answer is still a failure.
  const ThreeViewObservations observations = Scene();
  RobustThreeViewOptions options;
  options.check_gravity_after_success = true;
  RobustThreeViewEstimate reference = EstimateThreeViewPoseRobust(observations, options);
  ASSERT_TRUE(reference.success) << reference.message;
  int calls = 0;
  const int samples = reference.ransac.iterations;
  options.ransac.stop_requested = [&] { return ++calls > samples + 1; };
  const RobustThreeViewEstimate estimate = EstimateThreeViewPoseRobust(observations, options);
  EXPECT_FALSE(estimate.success);
  EXPECT_EQ(estimate.cause, FailureCause::kStopped);
}

TEST(StopRequestTest, EveryRefinementEngineStopsAndInitializeAndRefineFails) {
  const ThreeViewObservations observations = Scene();
  for (const Engine engine : {Engine::kCeres, Engine::kCeresPointsEliminated}) {
    InitializeAndRefineOptions options;
    options.bundle_adjustment.engine = engine;
    ASSERT_TRUE(InitializeAndRefine(observations, options).success);
    int calls = 0;
    options.bundle_adjustment.stop_requested = [&] { return ++calls > 1; };
    const ThreeViewEstimate estimate = InitializeAndRefine(observations, options);
    EXPECT_FALSE(estimate.success) << EngineName(engine);
    EXPECT_EQ(estimate.cause, FailureCause::kStopped) << EngineName(engine);
    // Ceres calls back at iteration 0 too; then Solve() and InitializeAndRefine ask once more.
    EXPECT_LE(calls, 4) << EngineName(engine);
  }
}

}  // namespace
}  // namespace trigrav
