#include "trigrav/initializers/two_view_to_three_view.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "trigrav/evaluation/pose_errors.h"
#include "trigrav/evaluation/synthetic_scene.h"
#include "trigrav/initializers/essential_5pt.h"

namespace trigrav {
namespace {

// Ground-truth pairs give the true relative scale with a rounding-level residual.
TEST(CombineTwoViewPairs, TruePairsGiveTrueScale) {
  SyntheticSceneOptions options;
  options.num_points = 6;
  std::mt19937_64 rng(3);
  for (int trial = 0; trial < 20; ++trial) {
    const SyntheticScene scene = GenerateSyntheticScene(options, &rng);
    CameraPose cam2 = scene.ground_truth.cam2_from_cam1, cam3 = scene.ground_truth.cam3_from_cam1;
    const double norm2 = cam2.Center().norm();
    cam2.t /= norm2;
    cam3.t /= cam3.Center().norm();  // the pair (1,3) alone knows no scale
    std::vector<ThreeViewPose> poses;
    std::vector<double> residuals;
    CombineTwoViewPairs(scene.rays[0], scene.rays[1], scene.rays[2], {cam2}, {cam3}, &poses,
                        &residuals);
    ASSERT_EQ(poses.size(), 1u);
    ASSERT_EQ(residuals.size(), 1u);
    EXPECT_LT(residuals[0], 1e-12);
    const ThreeViewPoseErrors e = ComputeThreeViewPoseErrors(scene.ground_truth, poses[0]);
    EXPECT_LT(e.relative_scale, 1e-12);
    EXPECT_LT(e.MaxTranslationDeg(), 1e-10);
  }
}

// Among all 5-point combinations, the smallest depth-ratio residual picks the true one
// (noise-free), and the residual list stays parallel to the poses; no residual without request.
TEST(CombineTwoViewPairs, SmallestResidualIsTruePoseNoiseFree) {
  SyntheticSceneOptions options;
  options.num_points = 5;
  std::mt19937_64 rng(5);
  for (int trial = 0; trial < 50; ++trial) {
    const SyntheticScene scene = GenerateSyntheticScene(options, &rng);
    std::vector<CameraPose> pair12, pair13;
    SolveEssential5pt(scene.rays[0], scene.rays[1], &pair12);
    SolveEssential5pt(scene.rays[0], scene.rays[2], &pair13);
    std::vector<ThreeViewPose> poses, plain;
    std::vector<double> residuals;
    CombineTwoViewPairs(scene.rays[0], scene.rays[1], scene.rays[2], pair12, pair13, &poses,
                        &residuals);
    CombineTwoViewPairs(scene.rays[0], scene.rays[1], scene.rays[2], pair12, pair13, &plain);
    ASSERT_EQ(poses.size(), residuals.size());
    ASSERT_EQ(poses.size(), plain.size());
    ASSERT_FALSE(poses.empty());
    const std::size_t best =
        std::min_element(residuals.begin(), residuals.end()) - residuals.begin();
    const ThreeViewPoseErrors e = ComputeThreeViewPoseErrors(scene.ground_truth, poses[best]);
    EXPECT_LT(e.MaxRotationDeg(), 1e-6) << "trial " << trial;
    EXPECT_LT(e.relative_scale, 1e-6) << "trial " << trial;
  }
}

}  // namespace
}  // namespace trigrav
