#include "trigrav/initializers/pose_metrics.h"

#include <cmath>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

namespace trigrav {
namespace {

TEST(PoseMetrics, RotationErrorIsTheAngleEvenWhenTiny) {
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  for (const double angle_deg : {1e-12, 1e-6, 0.5, 30.0, 179.0}) {
    const Eigen::Matrix3d delta =
        Eigen::AngleAxisd(angle_deg * M_PI / 180.0, Eigen::Vector3d(0.3, -1, 0.2).normalized())
            .toRotationMatrix();
    EXPECT_NEAR(RotationErrorDeg(delta * R, R), angle_deg, 1e-12 + 1e-9 * angle_deg);
  }
}

TEST(PoseMetrics, DirectionErrorIgnoresLength) {
  EXPECT_NEAR(DirectionErrorDeg(Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(5, 5, 0)), 45.0, 1e-12);
  EXPECT_NEAR(DirectionErrorDeg(Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(-2, 0, 0)), 180.0, 1e-12);
  EXPECT_EQ(DirectionErrorDeg(Eigen::Vector3d(1, 0, 0), Eigen::Vector3d::Zero()), 180.0);
  EXPECT_NEAR(DirectionErrorDeg(Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(1, 1e-13, 0)),
              1e-13 * 180.0 / M_PI, 1e-20);
}

TEST(PoseMetrics, ThreeViewErrorsUseCentresAndScale) {
  ThreeViewPose truth;
  truth.cam2_from_cam1.R = Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitY()).toRotationMatrix();
  truth.cam2_from_cam1.t = -truth.cam2_from_cam1.R * Eigen::Vector3d(1, 0, 0);
  truth.cam3_from_cam1.t = -Eigen::Vector3d(0, 0, 2);
  ThreeViewPose estimate = truth;
  estimate.cam3_from_cam1.t *= 3.0;  // relative scale off by a factor 3, directions exact
  const ThreeViewPoseErrors e = ComputeThreeViewPoseErrors(truth, estimate);
  EXPECT_NEAR(e.rotation_deg[0], 0.0, 1e-12);
  EXPECT_NEAR(e.translation_deg[1], 0.0, 1e-12);
  EXPECT_NEAR(e.relative_scale, std::log(3.0), 1e-12);
  // A wrong rotation with the right centre: translation error stays zero (centres, not t).
  estimate = truth;
  estimate.cam2_from_cam1.R = Eigen::Matrix3d::Identity();
  estimate.cam2_from_cam1.t = -Eigen::Vector3d(1, 0, 0);
  const ThreeViewPoseErrors f = ComputeThreeViewPoseErrors(truth, estimate);
  EXPECT_NEAR(f.rotation_deg[0], 0.1 * 180.0 / M_PI, 1e-12);
  EXPECT_NEAR(f.translation_deg[0], 0.0, 1e-12);
}

}  // namespace
}  // namespace trigrav
