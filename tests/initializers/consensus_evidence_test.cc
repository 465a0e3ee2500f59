// The verdict's Gauss-Newton offset (initializers/src/consensus_evidence.h, derivations.md 7.7
// step 4): zero at the least-squares optimum of noise-free data, and the size of a known
// perturbation of the pose, in the units of the sigmas.
#include "consensus_evidence.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>
#include <vector>

#include "robust_triplet_data.h"
#include "trigrav/evaluation/synthetic_scene.h"

namespace trigrav {
namespace internal {
namespace {

constexpr double kDegPerRad = 180.0 / M_PI;

struct NoiseFreeScene {
  ThreeViewObservations observations;
  ThreeViewPose truth;
};

NoiseFreeScene MakeScene() {
  SyntheticSceneOptions options;
  options.num_points = 200;
  options.pixel_noise_px = 0.0;
  options.outlier_ratio = 0.0;
  std::mt19937_64 rng(3);
  const SyntheticScene scene = GenerateSyntheticScene(options, &rng);
  return {ToObservations(scene), scene.ground_truth};
}

PosePrecision Precision(const NoiseFreeScene& scene, const ThreeViewPose& pose, bool yaw_only) {
  const TripletData data(scene.observations, 0.0);
  const std::vector<char> inliers(scene.observations.size(), 1);
  return PredictPosePrecision(data, pose, inliers, ThresholdUnitsPerRadian(scene.observations), 1.0,
                              yaw_only);
}

TEST(ConsensusEvidence, OffsetIsZeroAtTheOptimumAndTheSizeOfAPerturbation) {
  const NoiseFreeScene scene = MakeScene();
  for (const bool yaw_only : {true, false}) {
    SCOPED_TRACE(yaw_only);
    const PosePrecision at_truth = Precision(scene, scene.truth, yaw_only);
    ASSERT_TRUE(at_truth.determined);
    EXPECT_LT(at_truth.rotation_offset_deg, 1e-6);
    EXPECT_LT(at_truth.direction_offset_deg, 1e-6);

    // Camera 2 turned by 0.01 rad about camera 1's vertical (a yaw: both parameterisations hold
    // it): the step back is 0.573 deg of rotation.
    const Eigen::Vector3d vertical = scene.observations.gravity_in_cam[0].normalized();
    ThreeViewPose turned = scene.truth;
    CameraPose& pose2 = turned.cam2_from_cam1;
    const Eigen::Vector3d center2 = pose2.Center();
    pose2.R = pose2.R * Eigen::AngleAxisd(0.01, vertical).toRotationMatrix();
    pose2.t = -pose2.R * center2;
    EXPECT_NEAR(Precision(scene, turned, yaw_only).rotation_offset_deg, 0.01 * kDegPerRad,
                0.05 * 0.01 * kDegPerRad);

    // Camera 3's centre moved by 0.02 |C3| normal to it: the step back is 1.146 deg of direction.
    ThreeViewPose moved = scene.truth;
    CameraPose& pose3 = moved.cam3_from_cam1;
    const Eigen::Vector3d center3 = pose3.Center();
    const Eigen::Vector3d normal = center3.unitOrthogonal();
    pose3.t = -pose3.R * (center3 + 0.02 * center3.norm() * normal);
    EXPECT_NEAR(Precision(scene, moved, yaw_only).direction_offset_deg, 0.02 * kDegPerRad,
                0.05 * 0.02 * kDegPerRad);
  }
}

}  // namespace
}  // namespace internal
}  // namespace trigrav
