// CameraPose: centre, inverse and composition against hand-made transforms.
#include "trigrav/initializers/camera_pose.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

namespace trigrav {
namespace {

CameraPose MakePose(double angle, const Eigen::Vector3d& axis, const Eigen::Vector3d& t) {
  CameraPose pose;
  pose.R = Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
  pose.t = t;
  return pose;
}

TEST(CameraPose, InverseMapsPointsBack) {
  const CameraPose b_from_a = MakePose(0.7, Eigen::Vector3d(1, 2, 3), Eigen::Vector3d(4, -5, 6));
  const CameraPose a_from_b = b_from_a.Inverse();
  const Eigen::Vector3d x_a(0.3, -1.2, 7.5);
  EXPECT_LT((a_from_b.Apply(b_from_a.Apply(x_a)) - x_a).norm(), 1e-14);
  // The inverse's centre is the origin of a seen from b: b_from_a.t.
  EXPECT_LT((a_from_b.Center() - b_from_a.t).norm(), 1e-14);
  EXPECT_LT((b_from_a.Inverse().Inverse().R - b_from_a.R).norm(), 1e-15);
}

TEST(CameraPose, CompositionAppliesRightToLeft) {
  const CameraPose b_from_a = MakePose(0.4, Eigen::Vector3d(0, 1, 0), Eigen::Vector3d(1, 0, 2));
  const CameraPose c_from_b = MakePose(-1.1, Eigen::Vector3d(1, 0, 1), Eigen::Vector3d(0, 3, -1));
  const CameraPose c_from_a = c_from_b * b_from_a;
  const Eigen::Vector3d x_a(2.0, 0.5, -3.0);
  EXPECT_LT((c_from_a.Apply(x_a) - c_from_b.Apply(b_from_a.Apply(x_a))).norm(), 1e-14);
  const CameraPose identity = c_from_a * c_from_a.Inverse();
  EXPECT_LT((identity.R - Eigen::Matrix3d::Identity()).norm(), 1e-15);
  EXPECT_LT(identity.t.norm(), 1e-14);
}

TEST(ThreeViewPose, Cam3FromCam2ComposesThroughCameraOne) {
  ThreeViewPose pose;
  pose.cam2_from_cam1 = MakePose(0.2, Eigen::Vector3d(0, 1, 0), Eigen::Vector3d(1, 0, 0));
  pose.cam3_from_cam1 = MakePose(0.5, Eigen::Vector3d(0, 1, 0.1), Eigen::Vector3d(2, 0.1, 0));
  const Eigen::Vector3d x_cam1(0.5, 0.2, 9.0);
  const Eigen::Vector3d x_cam2 = pose.cam2_from_cam1.Apply(x_cam1);
  EXPECT_LT((pose.Cam3FromCam2().Apply(x_cam2) - pose.cam3_from_cam1.Apply(x_cam1)).norm(), 1e-14);
}

// A rotation, not any matrix: scaled, reflected or perturbed beyond 1e-6 matrices are refused
// (RefineThreeViewPose fails on such an initial pose, naming R).
TEST(CameraPose, HasRotationOnlyForRotations) {
  CameraPose pose;
  EXPECT_TRUE(pose.HasRotation());
  pose.R = Eigen::AngleAxisd(0.3, Eigen::Vector3d(1.0, 2.0, 3.0).normalized()).toRotationMatrix();
  EXPECT_TRUE(pose.HasRotation());
  const Eigen::Matrix3d rotation = pose.R;
  pose.R = 2.0 * rotation;
  EXPECT_FALSE(pose.HasRotation());
  pose.R = rotation * Eigen::Vector3d(1.0, 1.0, -1.0).asDiagonal();  // a reflection
  EXPECT_FALSE(pose.HasRotation());
  pose.R = rotation;
  pose.R(0, 1) += 1e-5;
  EXPECT_FALSE(pose.HasRotation());
  ThreeViewPose three;
  EXPECT_TRUE(three.HasRotations());
  three.cam3_from_cam1.R = 2.0 * rotation;
  EXPECT_FALSE(three.HasRotations());
}

}  // namespace
}  // namespace trigrav
