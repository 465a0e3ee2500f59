#include "trigrav/initializers/gravity.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>
#include <stdexcept>

#include "trigrav/evaluation/pose_errors.h"

namespace trigrav {
namespace {

Eigen::Matrix3d RandomRotation(std::mt19937_64* rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  return Eigen::Quaterniond(n(*rng), n(*rng), n(*rng), n(*rng)).normalized().toRotationMatrix();
}

TEST(Gravity, AlignmentFromGravityMapsGravityToY) {
  std::mt19937_64 rng(1);
  std::normal_distribution<double> n(0.0, 1.0);
  for (int trial = 0; trial < 1000; ++trial) {
    const Eigen::Vector3d gravity(n(rng), n(rng), n(rng));
    const Eigen::Matrix3d R = GravityAlignmentFromGravity(3.7 * gravity);
    EXPECT_NEAR((R * gravity.normalized() - Eigen::Vector3d::UnitY()).norm(), 0.0, 1e-14);
    EXPECT_NEAR((R * R.transpose() - Eigen::Matrix3d::Identity()).norm(), 0.0, 1e-14);
    EXPECT_NEAR(R.determinant(), 1.0, 1e-14);
    EXPECT_NEAR((GravityInCamera(R) - gravity.normalized()).norm(), 0.0, 1e-14);
  }
  // Gravity opposite to the camera y axis (camera upside down) and along it.
  for (const Eigen::Vector3d& g : {Eigen::Vector3d(0, -1, 0), Eigen::Vector3d(0, 2, 0)}) {
    const Eigen::Matrix3d R = GravityAlignmentFromGravity(g);
    EXPECT_TRUE(R.allFinite());
    EXPECT_NEAR((R * g.normalized() - Eigen::Vector3d::UnitY()).norm(), 0.0, 1e-14);
  }
}

TEST(Gravity, PitchRollAlignmentAgreesWithGravityUpToYaw) {
  std::mt19937_64 rng(2);
  std::uniform_real_distribution<double> angle(-0.5, 0.5);
  for (int trial = 0; trial < 1000; ++trial) {
    const Eigen::Matrix3d from_angles = GravityAlignmentFromPitchRoll(angle(rng), angle(rng));
    const Eigen::Matrix3d from_gravity = GravityAlignmentFromGravity(GravityInCamera(from_angles));
    // The two differ by a left rotation about y only.
    const Eigen::Matrix3d difference = from_gravity * from_angles.transpose();
    EXPECT_NEAR((difference * Eigen::Vector3d::UnitY() - Eigen::Vector3d::UnitY()).norm(), 0.0,
                1e-14);
  }
}

TEST(Gravity, UnalignInvertsAlignment) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 1000; ++trial) {
    const Eigen::Matrix3d align_ref = RandomRotation(&rng), align_cam = RandomRotation(&rng);
    CameraPose original;
    original.R = RandomRotation(&rng);
    original.t = Eigen::Vector3d(u(rng), u(rng), u(rng));
    // Into the aligned frames and back: x_al_cam = A_cam x_cam, x_al_ref = A_ref x_ref.
    CameraPose aligned;
    aligned.R = align_cam * original.R * align_ref.transpose();
    aligned.t = align_cam * original.t;
    const CameraPose back = UnalignPose(aligned, align_ref, align_cam);
    EXPECT_NEAR((back.R - original.R).norm(), 0.0, 1e-14);
    EXPECT_NEAR((back.t - original.t).norm(), 0.0, 1e-14);
    // The centre maps with the reference alignment (the corrected eq. b4), not the camera's.
    EXPECT_NEAR((back.Center() - align_ref.transpose() * aligned.Center()).norm(), 0.0, 1e-13);
    // A point seen by both: aligned projection equals the aligned original projection.
    const Eigen::Vector3d point_in_ref(u(rng), u(rng), 5.0);
    EXPECT_NEAR(
        (align_cam * original.Apply(point_in_ref) - aligned.Apply(align_ref * point_in_ref)).norm(),
        0.0, 1e-13);
  }
}

TEST(Gravity, AlignRaysKeepsDirectionAndSign) {
  const Eigen::Matrix3d R = GravityAlignmentFromPitchRoll(0.3, -0.2);
  const std::vector<Eigen::Vector3d> rays = {Eigen::Vector3d(0.1, 0.2, 1.0),
                                             Eigen::Vector3d(0, 0, -1)};
  const std::vector<Eigen::Vector3d> aligned = AlignRays(R, rays);
  ASSERT_EQ(aligned.size(), 2u);
  EXPECT_NEAR((aligned[1] - R * rays[1]).norm(), 0.0, 0.0);
  EXPECT_NEAR(aligned[0].norm(), rays[0].norm(), 1e-15);
}

TEST(Gravity, RotationAboutYMatchesConvention) {
  const Eigen::Matrix3d R = RotationAboutY(0.4);
  EXPECT_NEAR((R - Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitY()).toRotationMatrix()).norm(), 0.0,
              1e-15);
  EXPECT_NEAR(R(0, 2), std::sin(0.4), 1e-15);
}

TEST(Gravity, MisuseThrows) {
  EXPECT_THROW(GravityAlignmentFromGravity(Eigen::Vector3d::Zero()), std::invalid_argument);
  EXPECT_THROW(GravityAlignmentFromGravity(Eigen::Vector3d(0, NAN, 1)), std::invalid_argument);
  EXPECT_THROW(GravityAlignmentFromGravity(Eigen::Vector3d(0, INFINITY, 0)), std::invalid_argument);
  EXPECT_THROW(GravityAlignmentFromPitchRoll(NAN, 0.0), std::invalid_argument);
  EXPECT_THROW(GravityAlignmentFromPitchRoll(0.0, INFINITY), std::invalid_argument);
}

}  // namespace
}  // namespace trigrav
