// trigrav::evaluation trajectories (trajectory.h): steps from triplet estimates, chaining with
// ground-truth step lengths, constant velocity over failed steps, and the ATE's rigid alignment, on
// constructed poses.

#include "trigrav/evaluation/trajectory.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <vector>

#include "trigrav/evaluation/pose_errors.h"

namespace trigrav {
namespace {

// A curved drive: camera f at angle 0.02 f about y, centres along a circle of radius 40 m.
std::vector<CameraPose> CurvedDrive(int num_frames) {
  std::vector<CameraPose> cam_from_world;
  for (int f = 0; f < num_frames; ++f) {
    const double yaw = 0.02 * f;
    const Eigen::Matrix3d world_from_cam =
        (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitY()) *
         Eigen::AngleAxisd(0.01 * std::sin(0.3 * f), Eigen::Vector3d::UnitX()))
            .toRotationMatrix();
    const Eigen::Vector3d center(40.0 * (1.0 - std::cos(yaw)), 0.05 * std::sin(0.2 * f),
                                 40.0 * std::sin(yaw));
    CameraPose pose;
    pose.R = world_from_cam.transpose();
    pose.t = -pose.R * center;
    cam_from_world.push_back(pose);
  }
  return cam_from_world;
}

TEST(Trajectory, ChainingExactTripletsReproducesTheDriveWithZeroAte) {
  const std::vector<CameraPose> truth = CurvedDrive(12);
  std::vector<ThreeViewPose> triplets;
  for (int f = 0; f + 2 < 12; ++f) {
    ThreeViewPose pose{truth[f + 1] * truth[f].Inverse(), truth[f + 2] * truth[f].Inverse()};
    // Solvers return |C2| = 1: the chaining must restore the length.
    const double scale = pose.cam2_from_cam1.Center().norm();
    pose.cam2_from_cam1.t /= scale;
    pose.cam3_from_cam1.t /= scale;
    triplets.push_back(pose);
  }
  const TrajectorySteps steps = StepsFromTriplets(triplets, std::vector<char>(triplets.size(), 1));
  ASSERT_EQ(steps.next_from_current.size(), 11u);
  std::vector<double> lengths;
  std::vector<Eigen::Vector3d> truth_centers = {truth[0].Center()};
  for (int f = 1; f < 12; ++f) {
    truth_centers.push_back(truth[f].Center());
    lengths.push_back((truth[f].Center() - truth[f - 1].Center()).norm());
  }
  const std::vector<CameraPose> chained = ChainTrajectory(truth[0], steps, lengths);
  ASSERT_EQ(chained.size(), 12u);
  std::vector<Eigen::Vector3d> centers;
  // Frame 11 checks the last step, which comes from the last triplet's cam3_from_cam2.
  for (int f = 0; f < 12; ++f) {
    centers.push_back(chained[f].Center());
    EXPECT_LT((chained[f].Center() - truth[f].Center()).norm(), 1e-9) << f;
    EXPECT_LT(RotationErrorDeg(truth[f].R, chained[f].R), 1e-9) << f;
  }
  EXPECT_LT(ComputeAbsoluteTrajectoryError(centers, truth_centers).rmse_m, 1e-9);
}

TEST(Trajectory, AteAlignsARigidMotionAndMeasuresWhatIsLeft) {
  const std::vector<CameraPose> truth = CurvedDrive(20);
  std::vector<Eigen::Vector3d> truth_centers, moved;
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  for (const CameraPose& pose : truth) {
    truth_centers.push_back(pose.Center());
    moved.push_back(R * pose.Center() + Eigen::Vector3d(5, -2, 9));
  }
  EXPECT_LT(ComputeAbsoluteTrajectoryError(moved, truth_centers).rmse_m, 1e-9);
  // One centre off by 2 m (after any alignment some error remains): RMSE between 0 and 2/sqrt(n).
  moved[10] += R * Eigen::Vector3d(0, 2, 0);
  const AbsoluteTrajectoryError ate = ComputeAbsoluteTrajectoryError(moved, truth_centers);
  EXPECT_GT(ate.rmse_m, 0.2);
  EXPECT_LE(ate.rmse_m, 2.0 / std::sqrt(20.0) + 1e-9);
  EXPECT_GT(ate.error_m[10], 1.5);
}

TEST(Trajectory, AFailedStepRepeatsThePreviousOne) {
  const std::vector<CameraPose> truth = CurvedDrive(6);
  TrajectorySteps steps;
  for (int f = 0; f < 5; ++f) {
    steps.next_from_current.push_back(truth[f + 1] * truth[f].Inverse());
    steps.valid.push_back(f == 3 ? 0 : 1);
  }
  steps.next_from_current[3].t = Eigen::Vector3d(100, 0, 0);  // garbage that must not be used
  const std::vector<double> lengths(5, 2.0);
  const std::vector<CameraPose> chained = ChainTrajectory(truth[0], steps, lengths);
  const CameraPose step3_from_2 = chained[3] * chained[2].Inverse();
  const CameraPose step4_from_3 = chained[4] * chained[3].Inverse();
  EXPECT_LT(RotationErrorDeg(step3_from_2.R, step4_from_3.R), 1e-9);
  EXPECT_LT((step3_from_2.t - step4_from_3.t).norm(), 1e-9);
  EXPECT_NEAR(step4_from_3.Center().norm(), 2.0, 1e-9);
}

}  // namespace
}  // namespace trigrav
