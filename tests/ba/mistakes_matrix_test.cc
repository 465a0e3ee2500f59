// Mistakes matrix: InitializeAndRefine at its defaults against each common input mistake of
// tests/scenes/input_mistakes.h (synthetic scenes of 600 triplets, 1 px noise, 10 %
// outliers, f = 1000 px), and against pure outliers. A mistake must give success == false with a
// message naming its likely cause (all but the short focal length, which the verdict does not
// see); correct input must still give the true pose. The figures per mistake:
// examples/experiments/README.md (verdict_matrix).

#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "input_mistakes.h"
#include "trigrav/ba/initialize_and_refine.h"
#include "trigrav/evaluation/pose_errors.h"
#include "trigrav/evaluation/synthetic_scene.h"

namespace trigrav {
namespace {

constexpr int kScenes = 2;

// `mild`: small tilts, yaws and baselines (within 2 deg, 3 deg, 2 m), where wrong intrinsics are
// partly absorbed by the pose.
std::vector<SyntheticScene> Scenes(bool mild = false, int count = kScenes) {
  SyntheticSceneOptions options;
  if (mild) {
    options.max_tilt_deg = 2.0;
    options.max_yaw_deg = 3.0;
    options.max_center_m = 2.0;
  }
  options.num_points = 600;
  options.focal_px = 1000.0;
  options.width_px = 1280.0;
  options.height_px = 720.0;
  options.pixel_noise_px = 1.0;
  options.outlier_ratio = 0.1;
  std::mt19937_64 rng(17);
  std::vector<SyntheticScene> scenes;
  for (int s = 0; s < count; ++s) scenes.push_back(GenerateSyntheticScene(options, &rng));
  return scenes;
}

ThreeViewEstimate Estimate(const ThreeViewObservations& observations, std::uint64_t seed) {
  InitializeAndRefineOptions options;
  options.robust.ransac.seed = seed;
  return InitializeAndRefine(observations, options);
}

bool Mentions(const std::string& message, const std::string& text) {
  return message.find(text) != std::string::npos;
}

TEST(MistakesMatrix, CorrectInputGivesTheTruePose) {
  const std::vector<SyntheticScene> scenes = Scenes();
  for (int s = 0; s < kScenes; ++s) {
    const ThreeViewEstimate estimate = Estimate(WithMistake(scenes[s], InputMistake::kNone), s);
    ASSERT_TRUE(estimate.success) << estimate.message;
    const ThreeViewPoseErrors errors =
        ComputeThreeViewPoseErrors(scenes[s].ground_truth, estimate.refined);
    EXPECT_LT(errors.MaxRotationDeg(), 0.2) << "scene " << s;
    EXPECT_LT(errors.MaxTranslationDeg(), 2.0) << "scene " << s;
    EXPECT_FALSE(estimate.robust.gravity.measured);  // no check after a success by default
  }
}

// Each mistake: a failure whose message (at most about 200 characters) names the cause. Not the
// short focal length, which the pose partly absorbs (examples/experiments/README.md,
// verdict_matrix).
TEST(MistakesMatrix, EveryMistakeFailsWithItsLikelyCause) {
  struct Case {
    InputMistake mistake;
    std::vector<std::string> named;  // every one must appear in the message
  };
  const std::vector<Case> cases = {
      {InputMistake::kGravitySignCamera2, {"gravity of camera 2", "wrong sign"}},
      {InputMistake::kWorldVerticalEveryCamera, {"gravity", "off the images"}},
      {InputMistake::kTransposedRotation, {"gravity", "off the images"}},
      {InputMistake::kHalfResolutionPixels, {"intrinsics", "resized image"}},
      {InputMistake::kRowColumnPixels, {"(row, column)"}},
      {InputMistake::kViews2And3PixelsSwapped, {"views 2 and 3 out of order"}},
      {InputMistake::kReadmeExampleIntrinsics, {"another camera's intrinsics"}},
  };
  const std::vector<SyntheticScene> scenes = Scenes();
  for (const Case& c : cases) {
    for (int s = 0; s < kScenes; ++s) {
      const ThreeViewEstimate estimate = Estimate(WithMistake(scenes[s], c.mistake), s);
      const char* name = InputMistakeName(c.mistake);
      EXPECT_FALSE(estimate.success) << name << " scene " << s;
      EXPECT_LE(estimate.message.size(), 210u) << estimate.message;
      for (const std::string& text : c.named) {
        EXPECT_TRUE(Mentions(estimate.message, text)) << name << ": " << estimate.message;
      }
    }
  }
}

// The flipped gravity is located: camera 2 in the two pairs beyond the bound, 180 deg off.
TEST(MistakesMatrix, FlippedGravityNamesTheCameraAndTheAngle) {
  const std::vector<SyntheticScene> scenes = Scenes();
  for (int s = 0; s < kScenes; ++s) {
    const ThreeViewEstimate estimate =
        Estimate(WithMistake(scenes[s], InputMistake::kGravitySignCamera2), s);
    ASSERT_TRUE(estimate.robust.gravity.measured) << estimate.message;
    EXPECT_EQ(estimate.robust.gravity.inconsistent_camera, 2);
    EXPECT_GT(estimate.robust.gravity.pair_inconsistency_deg[0], 175.0);  // pair (1,2)
    EXPECT_LT(estimate.robust.gravity.pair_inconsistency_deg[1], 1.0);    // pair (1,3)
    EXPECT_GT(estimate.robust.gravity.pair_inconsistency_deg[2], 175.0);  // pair (2,3)
    EXPECT_GT(estimate.robust.gravity.num_inliers, 300);                  // of 540 true inliers
  }
}

// With the comparison after a success (the default), correct input keeps its pose: no gravity-free
// model explains more triplets, or it agrees with the gravity.
TEST(MistakesMatrix, GravityCheckAfterSuccessKeepsCorrectInput) {
  const std::vector<SyntheticScene> scenes = Scenes();
  InitializeAndRefineOptions options;
  options.robust.check_gravity_after_success = true;
  for (int s = 0; s < kScenes; ++s) {
    options.robust.ransac.seed = s;
    const ThreeViewEstimate estimate =
        InitializeAndRefine(WithMistake(scenes[s], InputMistake::kNone), options);
    ASSERT_TRUE(estimate.success) << estimate.message;
    if (!estimate.robust.gravity.measured) continue;
    for (const double angle : estimate.robust.gravity.pair_inconsistency_deg) EXPECT_LT(angle, 2.8);
    for (const double angle : estimate.robust.gravity.rotation_disagreement_deg)
      EXPECT_LT(angle, 2.8);
  }
}

// Half-resolution pixels on mild geometry fit a pose with a wrong camera well (rotation errors of
// 1.5 deg median before the verdict checked the pixels against the intrinsics): every call now
// fails naming the resized image.
TEST(MistakesMatrix, HalfResolutionOnMildGeometryIsNamed) {
  const std::vector<SyntheticScene> scenes = Scenes(/*mild=*/true, 4);
  for (std::size_t s = 0; s < scenes.size(); ++s) {
    const ThreeViewEstimate estimate =
        Estimate(WithMistake(scenes[s], InputMistake::kHalfResolutionPixels), s);
    EXPECT_FALSE(estimate.success) << "scene " << s;
    EXPECT_TRUE(Mentions(estimate.message, "resized image")) << estimate.message;
  }
}

// Views 2 and 3 swapped entirely (pixels, gravity, intrinsics) are a valid problem: the pose of
// that order comes back.
TEST(MistakesMatrix, FullySwappedViewsGiveThePoseOfThatOrder) {
  const std::vector<SyntheticScene> scenes = Scenes();
  for (int s = 0; s < kScenes; ++s) {
    ThreeViewObservations observations = WithMistake(scenes[s], InputMistake::kNone);
    std::swap(observations.pixels[1], observations.pixels[2]);
    std::swap(observations.gravity_in_cam[1], observations.gravity_in_cam[2]);
    std::swap(observations.cameras[1], observations.cameras[2]);
    const ThreeViewEstimate estimate = Estimate(observations, s);
    ASSERT_TRUE(estimate.success) << estimate.message;
    const ThreeViewPose swapped_truth{scenes[s].ground_truth.cam3_from_cam1,
                                      scenes[s].ground_truth.cam2_from_cam1};
    const ThreeViewPoseErrors errors = ComputeThreeViewPoseErrors(swapped_truth, estimate.refined);
    EXPECT_LT(errors.MaxRotationDeg(), 0.2) << "scene " << s;
    EXPECT_LT(errors.MaxTranslationDeg(), 2.0) << "scene " << s;
  }
}

TEST(MistakesMatrix, PureOutliersFailWithAClearMessage) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(0.0, 1280.0), v(0.0, 720.0);
  ThreeViewObservations observations;
  for (int k = 0; k < 3; ++k) {
    observations.cameras[k] = PinholeCamera{1000.0, 1000.0, 640.0, 360.0};
    observations.gravity_in_cam[k] = Eigen::Vector3d::UnitY();
    for (int n = 0; n < 1000; ++n) observations.pixels[k].emplace_back(u(rng), v(rng));
  }
  const ThreeViewEstimate estimate = Estimate(observations, 1);
  EXPECT_FALSE(estimate.success);
  EXPECT_TRUE(Mentions(estimate.message, "of 1000 triplets fit")) << estimate.message;
  EXPECT_TRUE(Mentions(estimate.message, "matches?")) << estimate.message;
  EXPECT_FALSE(estimate.robust.gravity.measured);  // no gravity-free model either
  // Stopped at the floor's sample count, not at max_iterations (log(1e-4) / log(1 - 0.25^3)).
  EXPECT_EQ(estimate.robust.ransac.iterations, 585);
}

}  // namespace
}  // namespace trigrav
