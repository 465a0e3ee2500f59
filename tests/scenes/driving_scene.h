// A KITTI-like driving triplet for the tests of gravity from an IMU (robust and ba tests).
#ifndef TRIGRAV_TESTS_DRIVING_SCENE_H_
#define TRIGRAV_TESTS_DRIVING_SCENE_H_

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <cstdint>
#include <random>

#include "trigrav/initializers/camera_pose.h"
#include "trigrav/initializers/three_view_observations.h"

namespace trigrav {
namespace testing_utils {

struct DrivingScene {
  ThreeViewObservations observations;  // gravity as the IMU reports it
  ThreeViewPose ground_truth;
};

// Straight driving as on KITTI: f = 719 px on 1241 x 376 images, camera k at (0.02 k, 0, k) m
// yawed by 0.5 k deg, 300 triplets of points 5-80 m ahead with N(0, 0.5^2) pixel noise, 20 % of
// them outliers (view 3 moved 20-60 px right and 0-20 px down). Each camera's gravity is tilted
// by pitch and roll errors N(0, imu_sigma_deg^2), as from an IMU.
inline DrivingScene MakeDrivingScene(double imu_sigma_deg, std::uint64_t seed) {
  constexpr double kDegToRad = M_PI / 180.0;
  constexpr double f = 719.0, cx = 607.0, cy = 185.0, width = 1241.0, height = 376.0;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> x(-15.0, 15.0), y(-3.0, 1.5), z(5.0, 80.0), u(0.0, 1.0);
  std::normal_distribution<double> pixel_noise(0.0, 0.5), imu_noise(0.0, imu_sigma_deg * kDegToRad);
  DrivingScene scene;
  std::array<Eigen::Matrix3d, 3> cam_from_world;
  std::array<Eigen::Vector3d, 3> center;
  for (int k = 0; k < 3; ++k) {
    cam_from_world[k] =
        Eigen::AngleAxisd(0.5 * k * kDegToRad, Eigen::Vector3d::UnitY()).toRotationMatrix();
    center[k] = Eigen::Vector3d(0.02 * k, 0.0, k);
    scene.observations.cameras[k] = PinholeCamera{f, f, cx, cy};
    const Eigen::Matrix3d imu_error = (Eigen::AngleAxisd(imu_noise(rng), Eigen::Vector3d::UnitX()) *
                                       Eigen::AngleAxisd(imu_noise(rng), Eigen::Vector3d::UnitZ()))
                                          .toRotationMatrix();
    scene.observations.gravity_in_cam[k] = imu_error * cam_from_world[k] * Eigen::Vector3d::UnitY();
  }
  for (int k = 1; k < 3; ++k) {
    CameraPose& pose =
        k == 1 ? scene.ground_truth.cam2_from_cam1 : scene.ground_truth.cam3_from_cam1;
    pose.R = cam_from_world[k] * cam_from_world[0].transpose();
    pose.t = cam_from_world[k] * (center[0] - center[k]);
  }
  while (scene.observations.size() < 300) {
    const Eigen::Vector3d point(x(rng), y(rng), z(rng));
    std::array<Eigen::Vector2d, 3> pixels;
    bool visible = true;
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d p = cam_from_world[k] * (point - center[k]);
      pixels[k] = Eigen::Vector2d(f * p.x() / p.z() + cx + pixel_noise(rng),
                                  f * p.y() / p.z() + cy + pixel_noise(rng));
      visible = visible && p.z() > 1.0 && pixels[k].x() >= 0.0 && pixels[k].x() < width &&
                pixels[k].y() >= 0.0 && pixels[k].y() < height;
    }
    if (!visible) continue;
    if (u(rng) < 0.2) pixels[2] += Eigen::Vector2d(20.0 + 40.0 * u(rng), 20.0 * u(rng));
    for (int k = 0; k < 3; ++k) scene.observations.pixels[k].push_back(pixels[k]);
  }
  return scene;
}

}  // namespace testing_utils
}  // namespace trigrav

#endif  // TRIGRAV_TESTS_DRIVING_SCENE_H_
