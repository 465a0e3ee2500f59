#include "trigrav/evaluation/synthetic_scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>

#include "trigrav/evaluation/pose_errors.h"
#include "trigrav/initializers/gravity.h"

namespace trigrav {
namespace {

TEST(SyntheticScene, NoiseFreeSceneIsConsistent) {
  std::mt19937_64 rng(1);
  SyntheticSceneOptions options;
  options.num_points = 10;
  for (int trial = 0; trial < 200; ++trial) {
    const SyntheticScene scene = GenerateSyntheticScene(options, &rng);
    ASSERT_EQ(scene.points_in_world.size(), 10u);
    const CameraPose* poses[3] = {nullptr, &scene.ground_truth.cam2_from_cam1,
                                  &scene.ground_truth.cam3_from_cam1};
    for (int n = 0; n < 10; ++n) {
      const Eigen::Vector3d point_in_cam1 =
          scene.cam_from_world[0] * (scene.points_in_world[n] - scene.center_in_world[0]);
      EXPECT_GT(point_in_cam1.z(), options.min_depth_m - 1e-9);
      EXPECT_LT(point_in_cam1.z(), options.max_depth_m + 1e-9);
      for (int k = 0; k < 3; ++k) {
        const Eigen::Vector2d& pixel = scene.pixels[k][n];
        EXPECT_GE(pixel.x(), 0.0);
        EXPECT_LE(pixel.x(), options.width_px);
        EXPECT_GE(pixel.y(), 0.0);
        EXPECT_LE(pixel.y(), options.height_px);
        // Ray of view k points at the point, through the ground-truth relative pose.
        const Eigen::Vector3d point_in_cam =
            k == 0 ? point_in_cam1 : poses[k]->Apply(point_in_cam1);
        EXPECT_GT(point_in_cam.z(), options.min_depth_all_views_m);
        EXPECT_NEAR((point_in_cam / point_in_cam.z() - scene.rays[k][n]).norm(), 0.0, 1e-12);
      }
    }
    for (int k = 0; k < 3; ++k) {
      // Without IMU noise the measured gravity is the true one, and it is the world y axis.
      EXPECT_NEAR((scene.gravity_in_cam_measured[k] - scene.cam_from_world[k].col(1)).norm(), 0.0,
                  1e-14);
      EXPECT_LE(std::abs(scene.yaw_rad[k]), options.max_yaw_deg * M_PI / 180.0);
      EXPECT_LE(std::abs(scene.pitch_rad[k]), options.max_tilt_deg * M_PI / 180.0);
      // Aligned relative rotations are pure yaw.
      const Eigen::Matrix3d aligned_R = scene.gravity_alignment_true[k] * scene.cam_from_world[k] *
                                        scene.cam_from_world[0].transpose() *
                                        scene.gravity_alignment_true[0].transpose();
      EXPECT_NEAR((aligned_R - RotationAboutY(scene.yaw_rad[k] - scene.yaw_rad[0])).norm(), 0.0,
                  1e-13);
    }
    EXPECT_NEAR(scene.center_in_world[0].norm(), 0.0, 0.0);
  }
}

TEST(SyntheticScene, NoiseHasTheRequestedSpread) {
  std::mt19937_64 noise_free_rng(2), noisy_rng(2);
  SyntheticSceneOptions options;
  options.num_points = 50;
  SyntheticSceneOptions noisy = options;
  noisy.pixel_noise_px = 1.5;
  noisy.imu_pitch_noise_deg = 0.5;
  double sum_squares = 0.0, tilt_sum_squares = 0.0;
  int count = 0, tilt_count = 0;
  for (int trial = 0; trial < 100; ++trial) {
    // Same seed: the same cameras and points, so the difference is the noise. Noise is drawn after
    // the point is accepted, so both generators stay in step.
    const SyntheticScene clean = GenerateSyntheticScene(options, &noise_free_rng);
    const SyntheticScene dirty = GenerateSyntheticScene(noisy, &noisy_rng);
    (void)clean;
    for (int k = 0; k < 3; ++k) {
      const double tilt =
          RotationErrorDeg(dirty.gravity_alignment_true[k], dirty.gravity_alignment_measured[k]);
      tilt_sum_squares += tilt * tilt;
      ++tilt_count;
      for (std::size_t n = 0; n < dirty.points_in_world.size(); ++n) {
        const Eigen::Vector3d p =
            dirty.cam_from_world[k] * (dirty.points_in_world[n] - dirty.center_in_world[k]);
        const Eigen::Vector2d exact(noisy.focal_px * p.x() / p.z() + 320.0,
                                    noisy.focal_px * p.y() / p.z() + 240.0);
        sum_squares += (dirty.pixels[k][n] - exact).squaredNorm();
        count += 2;
      }
    }
  }
  EXPECT_NEAR(std::sqrt(sum_squares / count), 1.5, 0.05);
  EXPECT_NEAR(std::sqrt(tilt_sum_squares / tilt_count), 0.5, 0.06);
}

TEST(SyntheticScene, OutliersAreFarFromTheTruthAndCounted) {
  std::mt19937_64 noisy_rng(3), clean_rng(3);
  SyntheticSceneOptions options;
  options.num_points = 100;
  SyntheticSceneOptions with_outliers = options;
  with_outliers.outlier_ratio = 0.3;
  const SyntheticScene clean = GenerateSyntheticScene(options, &clean_rng);
  const SyntheticScene dirty = GenerateSyntheticScene(with_outliers, &noisy_rng);
  int outliers = 0;
  for (int n = 0; n < 100; ++n) {
    int views_changed = 0;
    for (int k = 0; k < 3; ++k) {
      const double shift = (dirty.pixels[k][n] - clean.pixels[k][n]).norm();
      views_changed += shift > 0.0;
      if (shift > 0.0) {
        EXPECT_GE(shift, 20.0);
      }
      Eigen::Vector3d ray;
      ASSERT_TRUE(dirty.camera.Unproject(dirty.pixels[k][n], &ray));
      EXPECT_NEAR((ray - dirty.rays[k][n]).norm(), 0.0, 1e-15);
    }
    EXPECT_EQ(views_changed, dirty.is_inlier[n] ? 0 : 1);
    outliers += !dirty.is_inlier[n];
  }
  EXPECT_EQ(outliers, 30);
  const ThreeViewObservations observations = ToObservations(dirty);
  EXPECT_NO_THROW(observations.Check());
  EXPECT_EQ(observations.pixels[2][7], dirty.pixels[2][7]);
  EXPECT_EQ(observations.cameras[1].params[0], 500.0);
}

TEST(SyntheticScene, SameSeedSameScene) {
  std::mt19937_64 a(7), b(7);
  SyntheticSceneOptions options;
  options.pixel_noise_px = 1.0;
  const SyntheticScene sa = GenerateSyntheticScene(options, &a);
  const SyntheticScene sb = GenerateSyntheticScene(options, &b);
  for (int k = 0; k < 3; ++k) {
    for (std::size_t n = 0; n < sa.rays[k].size(); ++n) EXPECT_EQ(sa.rays[k][n], sb.rays[k][n]);
  }
}

TEST(SyntheticScene, BadOptionsThrow) {
  std::mt19937_64 rng(1);
  SyntheticSceneOptions options;
  options.num_points = 0;
  EXPECT_THROW(GenerateSyntheticScene(options, &rng), std::invalid_argument);
  options = SyntheticSceneOptions();
  options.focal_px = NAN;
  EXPECT_THROW(GenerateSyntheticScene(options, &rng), std::invalid_argument);
  options = SyntheticSceneOptions();
  options.pixel_noise_px = -1.0;
  EXPECT_THROW(GenerateSyntheticScene(options, &rng), std::invalid_argument);
  EXPECT_THROW(GenerateSyntheticScene(SyntheticSceneOptions(), nullptr), std::invalid_argument);
}

}  // namespace
}  // namespace trigrav
