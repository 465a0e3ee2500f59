// examples/kitti (trigrav_kitti): trajectory chaining and ATE on constructed poses, and sanity
// checks on real KITTI frames (sequence 00, frames 20-29) when the data is present: calibration and
// poses read right, every triplet has enough tracks, the feature cache round-trips, and the 3-point
// method's errors against ground truth are in the range the full evaluation reports. The data
// folder is $TRIGRAV_KITTI_DIR, else TRIGRAV_KITTI_DEFAULT_DIR (../shared/data/kitti next to the
// repository); without it the real-data tests are skipped. Feature caches go to a temporary folder.

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "kitti_methods.h"
#include "kitti_report.h"
#include "kitti_sequence.h"
#include "sift_features.h"
#include "trajectory.h"
#include "trigrav/evaluation/pose_errors.h"
#include "triplet_source.h"

namespace trigrav::kitti {
namespace {

namespace fs = std::filesystem;

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

TEST(KittiTrajectory, ChainingExactTripletsReproducesTheDriveWithZeroAte) {
  const std::vector<CameraPose> truth = CurvedDrive(12);
  std::vector<ThreeViewPose> triplets;
  for (int f = 0; f + 2 < 12; ++f) {
    ThreeViewPose pose{RelativePose(truth[f], truth[f + 1]), RelativePose(truth[f], truth[f + 2])};
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

TEST(KittiTrajectory, AteAlignsARigidMotionAndMeasuresWhatIsLeft) {
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

TEST(KittiTrajectory, AFailedStepRepeatsThePreviousOne) {
  const std::vector<CameraPose> truth = CurvedDrive(6);
  TrajectorySteps steps;
  for (int f = 0; f < 5; ++f) {
    steps.next_from_current.push_back(RelativePose(truth[f], truth[f + 1]));
    steps.valid.push_back(f == 3 ? 0 : 1);
  }
  steps.next_from_current[3].t = Eigen::Vector3d(100, 0, 0);  // garbage that must not be used
  const std::vector<double> lengths(5, 2.0);
  const std::vector<CameraPose> chained = ChainTrajectory(truth[0], steps, lengths);
  const CameraPose step3_from_2 = RelativePose(chained[2], chained[3]);
  const CameraPose step4_from_3 = RelativePose(chained[3], chained[4]);
  EXPECT_LT(RotationErrorDeg(step3_from_2.R, step4_from_3.R), 1e-9);
  EXPECT_LT((step3_from_2.t - step4_from_3.t).norm(), 1e-9);
  EXPECT_NEAR(step4_from_3.Center().norm(), 2.0, 1e-9);
}

std::string KittiDir() {
  const char* from_env = std::getenv("TRIGRAV_KITTI_DIR");
  return from_env != nullptr && *from_env != '\0' ? from_env : TRIGRAV_KITTI_DEFAULT_DIR;
}

constexpr int kFirstFrame = 20;
constexpr int kLastFrame = 29;

// Sequence 00, frames 20-29, and its 8 triplets, read once for all tests (features cached in a
// temporary folder removed at the end).
class KittiRealData : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    std::string error;
    if (!LoadKittiSequence(KittiDir(), "00", kFirstFrame, kLastFrame, &sequence_, &error)) {
      skip_reason_ = "KITTI odometry data not found (" + error +
                     "); set TRIGRAV_KITTI_DIR to a folder with sequences/00 and poses/00.txt";
      return;
    }
    cache_dir_ = fs::temp_directory_path() /
                 ("trigrav_kitti_test_" +
                  std::to_string(std::chrono::steady_clock::now().time_since_epoch().count()));
    gravity_ = ImuGravityInCameras(sequence_, 0.0, 1);
    TripletSource source(sequence_, gravity_, cache_dir_.string(), SiftOptions(), MatchOptions());
    for (int frame = kFirstFrame; frame + 2 <= kLastFrame; ++frame) {
      TripletData triplet;
      if (!source.Get(frame, &triplet, &error)) {
        load_error_ = error;
        return;
      }
      triplets_.push_back(std::move(triplet));
    }
  }
  static void TearDownTestSuite() {
    if (!cache_dir_.empty()) fs::remove_all(cache_dir_);
  }
  void SetUp() override {
    if (!skip_reason_.empty()) GTEST_SKIP() << skip_reason_;
    ASSERT_TRUE(load_error_.empty()) << load_error_;
  }

  // 3pt raw, yaw-only and gravity-prior summaries of the 8 triplets, each camera's gravity taken
  // from `gravity_in_frames` (per frame of the range) and the prior's sigma `gravity_sigma_deg`.
  // The errors are measured about the exact gravity.
  static std::vector<MethodSummary> RunThreePoint(
      const std::vector<Eigen::Vector3d>& gravity_in_frames, double gravity_sigma_deg) {
    TrigravMethodSettings settings;
    settings.ransac.max_error = 1.5;
    settings.ransac.min_iterations = 100;
    settings.refined_methods = {"3pt"};
    settings.bundle_adjustment.gravity_sigma_deg = gravity_sigma_deg;
    std::vector<Method> methods;
    std::string error;
    EXPECT_TRUE(MakeTrigravMethods({"3pt"}, settings, &methods, &error)) << error;
    std::vector<PoseRecord> records;
    for (const TripletData& triplet : triplets_) {
      const int i = triplet.frame - kFirstFrame;
      ThreeViewObservations observations = triplet.observations;
      for (int k = 0; k < 3; ++k) observations.gravity_in_cam[k] = gravity_in_frames[i + k];
      for (const MethodPose& pose : methods.at(0).run(observations, triplet.frame)) {
        records.push_back(EvaluatePose(triplet.frame, "3pt", pose, triplet.tracks.size(),
                                       sequence_.GroundTruthTriplet(triplet.frame), gravity_[i + 1],
                                       gravity_[i + 2]));
      }
    }
    return Summarize(sequence_, records);
  }

  static inline KittiSequence sequence_;
  static inline std::vector<Eigen::Vector3d> gravity_;
  static inline fs::path cache_dir_;
  static inline std::vector<TripletData> triplets_;
  static inline std::string skip_reason_, load_error_;
};

TEST_F(KittiRealData, ReadsCalibrationAndPoses) {
  EXPECT_DOUBLE_EQ(sequence_.camera.fx, 718.856);
  EXPECT_DOUBLE_EQ(sequence_.camera.fy, 718.856);
  EXPECT_DOUBLE_EQ(sequence_.camera.cx, 607.1928);
  EXPECT_DOUBLE_EQ(sequence_.camera.cy, 185.2157);
  ASSERT_EQ(sequence_.num_frames(), 10);
  for (int frame = kFirstFrame; frame + 2 <= kLastFrame; ++frame) {
    // 10 Hz, about 0.8 m per frame on 00, a camera looking along its motion.
    const Eigen::Vector3d step = sequence_.GroundTruthTriplet(frame).cam2_from_cam1.Center();
    EXPECT_GT(step.norm(), 0.3);
    EXPECT_LT(step.norm(), 1.5);
    EXPECT_GT(step.z(), 0.99 * step.norm()) << "camera 2 is not ahead of camera 1";
  }
  // Gravity (world y) is within 5 deg of each camera's y axis.
  for (const Eigen::Vector3d& g : gravity_) EXPECT_GT(g.y(), std::cos(5.0 * M_PI / 180.0));
}

TEST_F(KittiRealData, EveryTripletHasEnoughTracks) {
  ASSERT_EQ(triplets_.size(), 8u);
  for (const TripletData& triplet : triplets_) {
    EXPECT_GE(triplet.tracks.size(), 300u) << "triplet " << triplet.frame;
    EXPECT_EQ(triplet.observations.size(), triplet.tracks.size());
  }
}

TEST_F(KittiRealData, FeatureCacheRoundTrips) {
  const TripletSource source(sequence_, gravity_, cache_dir_.string(), SiftOptions(),
                             MatchOptions());
  FrameFeatures cached, detected;
  bool was_detected = true;
  std::string error;
  ASSERT_TRUE(LoadOrDetectFeatures(sequence_.ImagePath(kFirstFrame), source.CachePath(kFirstFrame),
                                   SiftOptions(), &cached, &was_detected, &error))
      << error;
  EXPECT_FALSE(was_detected) << "frame " << kFirstFrame << " should come from the cache";
  ASSERT_TRUE(LoadOrDetectFeatures(sequence_.ImagePath(kFirstFrame), "", SiftOptions(), &detected,
                                   &was_detected, &error))
      << error;
  EXPECT_TRUE(was_detected);
  ASSERT_EQ(cached.size(), detected.size());
  ASSERT_GT(cached.size(), 1000);
  for (int i = 0; i < cached.size(); i += 97) {
    EXPECT_EQ(cached.pixels[i], detected.pixels[i]);
    EXPECT_EQ(cv::norm(cached.descriptors.row(i), detected.descriptors.row(i), cv::NORM_L1), 0.0);
  }
  // A cache of another image (other byte size) is not used.
  FrameFeatures stale;
  EXPECT_FALSE(ReadFeatureCache(source.CachePath(kFirstFrame), 12345, &stale));
}

TEST_F(KittiRealData, ThreePointErrorsAreSane) {
  const std::vector<MethodSummary> summaries = RunThreePoint(gravity_, 0.03);
  ASSERT_EQ(summaries.size(), 3u);  // raw, yaw-only, gravity-prior
  for (const MethodSummary& s : summaries) {
    SCOPED_TRACE(s.stage);
    EXPECT_EQ(s.num_failures, 0);
    EXPECT_EQ(s.num_gross, 0);
    EXPECT_LT(s.rotation_deg, 0.1);
    EXPECT_LT(s.translation_deg, 3.0);
    EXPECT_GT(s.median_inliers, 0.8 * s.median_tracks);
    EXPECT_LT(s.trajectory.ate_rmse_m, 0.5);  // 8 m of driving
  }
  // Exact gravity: the upright estimate has no tilt error, only yaw.
  EXPECT_EQ(summaries[0].stage, kRawStage);
  EXPECT_LT(summaries[0].tilt_deg, 1e-6);
  EXPECT_NEAR(summaries[0].yaw_deg, summaries[0].rotation_deg, 1e-6);
}

// The same triplets with 0.1 deg of IMU noise on each frame's pitch and roll (the README's
// --imu_noise_deg=0.1): upright estimates inherit the IMU's tilt error, and the gravity-prior
// refinement, whose RANSAC corrects the tilt, wins it back.
TEST_F(KittiRealData, GravityPriorWinsBackImuNoise) {
  const std::vector<MethodSummary> summaries =
      RunThreePoint(ImuGravityInCameras(sequence_, 0.1, 1), 0.1);
  ASSERT_EQ(summaries.size(), 3u);  // raw, yaw-only, gravity-prior
  for (const MethodSummary& s : summaries) {
    std::printf("0.1 deg IMU, 3pt %s: rotation %.4f (tilt %.4f), translation %.3f deg, %d gross\n",
                s.stage.c_str(), s.rotation_deg, s.tilt_deg, s.translation_deg, s.num_gross);
  }
  EXPECT_EQ(summaries[2].stage, kGravityPriorStage);
  EXPECT_GT(summaries[0].tilt_deg, 0.05);  // raw: the IMU's relative tilt error
  EXPECT_EQ(summaries[2].num_gross, 0);
  EXPECT_LT(summaries[2].rotation_deg, 0.08);
  EXPECT_LT(summaries[2].tilt_deg, 0.5 * summaries[0].tilt_deg);
  EXPECT_LT(summaries[2].translation_deg, 3.0);
}

}  // namespace
}  // namespace trigrav::kitti
