#include "trigrav/evaluation/pose_errors.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <stdexcept>

namespace trigrav {
namespace {

TEST(PoseMetrics, RotationErrorIsTheAngleEvenWhenTiny) {
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
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

// Error rotations E = R_gt R^T built from a known twist about gravity and a swing about an axis
// perpendicular to it: the split must return exactly those two angles.
TEST(PoseMetrics, SplitRotationErrorRecoversConstructedYawAndTilt) {
  const Eigen::Vector3d gravity_in_cam = Eigen::Vector3d(0.05, 1.0, -0.08) * 9.81;  // any length
  const Eigen::Vector3d g = gravity_in_cam.normalized();
  const Eigen::Vector3d perpendicular = g.cross(Eigen::Vector3d(0.3, 0.1, 1.0)).normalized();
  const Eigen::Matrix3d R_gt =
      Eigen::AngleAxisd(0.4, Eigen::Vector3d(-1, 2, 0.5).normalized()).toRotationMatrix();
  constexpr double kDeg = M_PI / 180.0;
  struct Case {
    double yaw_deg, tilt_deg;
  };
  for (const Case c : {Case{0.3, 0.0}, Case{0.0, 0.2}, Case{1.5, 0.7}, Case{-25.0, 12.0},
                       Case{1e-9, 3e-9}, Case{170.0, 5.0}}) {
    const Eigen::Matrix3d E =
        Eigen::AngleAxisd(c.tilt_deg * kDeg, perpendicular).toRotationMatrix() *
        Eigen::AngleAxisd(c.yaw_deg * kDeg, g).toRotationMatrix();
    const Eigen::Matrix3d R = E.transpose() * R_gt;  // so that R_gt R^T = E
    const YawTiltErrorDeg split = SplitRotationErrorDeg(R_gt, R, gravity_in_cam);
    const double tolerance = 1e-12 + 1e-10 * (std::abs(c.yaw_deg) + c.tilt_deg);
    EXPECT_NEAR(split.yaw_deg, std::abs(c.yaw_deg), tolerance) << c.yaw_deg << " " << c.tilt_deg;
    EXPECT_NEAR(split.tilt_deg, c.tilt_deg, tolerance) << c.yaw_deg << " " << c.tilt_deg;
  }
}

TEST(PoseMetrics, SplitRotationErrorTiltIsTheGravityDirectionError) {
  const Eigen::Vector3d g = Eigen::Vector3d(0.1, 1.0, 0.02).normalized();
  const Eigen::Matrix3d R_gt = Eigen::Matrix3d::Identity();
  const Eigen::Matrix3d E =
      Eigen::AngleAxisd(0.02, Eigen::Vector3d(0.4, -0.3, 1.0).normalized()).toRotationMatrix();
  const YawTiltErrorDeg split = SplitRotationErrorDeg(R_gt, E.transpose(), g);
  EXPECT_NEAR(split.tilt_deg, DirectionErrorDeg(g, E * g), 1e-12);
  EXPECT_GT(split.yaw_deg, 0.1);
  // Small errors: the parts add in quadrature to the whole rotation error.
  EXPECT_NEAR(std::hypot(split.yaw_deg, split.tilt_deg), RotationErrorDeg(R_gt, E.transpose()),
              1e-4);
}

TEST(PoseMetrics, SplitRotationErrorRejectsZeroGravity) {
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  EXPECT_THROW(SplitRotationErrorDeg(I, I, Eigen::Vector3d::Zero()), std::invalid_argument);
  EXPECT_THROW(SplitRotationErrorDeg(I, I, Eigen::Vector3d(NAN, 1, 0)), std::invalid_argument);
}

}  // namespace
}  // namespace trigrav
