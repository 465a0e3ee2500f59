// A synthetic driving sequence for the N-view bundle adjustment (its tests and its timing program).
#ifndef TRIGRAV_TESTS_NVIEW_SCENE_H_
#define TRIGRAV_TESTS_NVIEW_SCENE_H_

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "trigrav/ba/nview_bundle_adjustment.h"

namespace trigrav {
namespace testing_utils {

struct NViewSceneOptions {
  int num_images = 20;
  int num_points = 400;
  int max_track_length = 8;  // each point is seen by 2..max_track_length consecutive images
  double pixel_noise_px = 1.0;
  double gravity_noise_deg = 0.0;  // per-image pitch and roll error of the measured gravity
  // Distance between consecutive images along the road (m); the weave's amplitude scales with it.
  // Below 1: a slow car, low parallax (examples/experiments/gravity_pays.cc).
  double step_m = 1.0;
};

struct NViewScene {
  // True poses and points; pixels with noise; gravity as measured.
  NViewReconstruction truth;
};

// KITTI-like driving (f = 719 px, 1241 x 376): image k step_m (1 m) further along the road, with a
// slow left-right weave (yaw 5 deg sin(k / 15)) and a 1 deg pitch; points 4-60 m in front of a
// random image, seen by the next images while in view. The world frame is then moved by a random
// rotation and translation, so that gravity is not an axis of it.
inline NViewScene MakeNViewScene(const NViewSceneOptions& options, std::uint64_t seed) {
  constexpr double kDegToRad = M_PI / 180.0;
  constexpr double f = 719.0, cx = 607.0, cy = 185.0, width = 1241.0, height = 376.0;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::normal_distribution<double> normal(0.0, 1.0);
  NViewScene scene;
  NViewReconstruction& r = scene.truth;
  r.cameras.push_back(PinholeCamera{f, f, cx, cy});

  // world_from_aligned: the random frame change (aligned: y along gravity).
  const Eigen::Matrix3d world_from_aligned =
      Eigen::Quaterniond(Eigen::Vector4d(normal(rng), normal(rng), normal(rng), normal(rng)))
          .normalized()
          .toRotationMatrix();
  const Eigen::Vector3d world_offset(10.0 * normal(rng), 10.0 * normal(rng), 10.0 * normal(rng));
  for (int k = 0; k < options.num_images; ++k) {
    const double yaw = 5.0 * kDegToRad * std::sin(k / 15.0);
    const Eigen::Matrix3d cam_from_aligned =
        (Eigen::AngleAxisd(1.0 * kDegToRad, Eigen::Vector3d::UnitX()) *
         Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitY()))
            .toRotationMatrix();
    const Eigen::Vector3d center_aligned(3.0 * options.step_m * std::sin(k / 25.0), 0.0,
                                         options.step_m * k);
    NViewImage image;
    image.camera_index = 0;
    image.cam_from_world.R = cam_from_aligned * world_from_aligned.transpose();
    image.cam_from_world.t =
        -image.cam_from_world.R * (world_from_aligned * center_aligned + world_offset);
    const double sigma = options.gravity_noise_deg * kDegToRad;
    const Eigen::Matrix3d imu_error =
        (Eigen::AngleAxisd(sigma * normal(rng), Eigen::Vector3d::UnitX()) *
         Eigen::AngleAxisd(sigma * normal(rng), Eigen::Vector3d::UnitZ()))
            .toRotationMatrix();
    image.gravity_in_cam = imu_error * cam_from_aligned * Eigen::Vector3d::UnitY() * 9.81;
    r.images.push_back(image);
  }
  auto project = [&](int k, const Eigen::Vector3d& point_in_world, Eigen::Vector2d* pixel) {
    const Eigen::Vector3d x = r.images[k].cam_from_world.Apply(point_in_world);
    if (!(x.z() > 1.0)) return false;
    *pixel = Eigen::Vector2d(f * x.x() / x.z() + cx, f * x.y() / x.z() + cy);
    return pixel->x() >= 0.0 && pixel->x() < width && pixel->y() >= 0.0 && pixel->y() < height;
  };
  while (static_cast<int>(r.points_in_world.size()) < options.num_points) {
    const int anchor = static_cast<int>(uniform(rng) * (options.num_images - 1));
    const double depth = 4.0 + 56.0 * uniform(rng);
    const Eigen::Vector3d ray((uniform(rng) * width - cx) / f, (uniform(rng) * height - cy) / f,
                              1.0);
    const Eigen::Vector3d point = r.images[anchor].cam_from_world.Inverse().Apply(depth * ray);
    const int length = 2 + static_cast<int>(uniform(rng) * (options.max_track_length - 1));
    std::vector<NViewObservation> track;
    for (int k = anchor; k < options.num_images && k < anchor + length; ++k) {
      Eigen::Vector2d pixel;
      if (!project(k, point, &pixel)) break;
      pixel += options.pixel_noise_px * Eigen::Vector2d(normal(rng), normal(rng));
      track.push_back({k, static_cast<int>(r.points_in_world.size()), pixel});
    }
    if (track.size() < 2) continue;
    r.points_in_world.push_back(point);
    r.observations.insert(r.observations.end(), track.begin(), track.end());
  }
  return scene;
}

// The reconstruction with each rotation turned by N(0, rotation_deg^2) per axis, each centre moved
// by N(0, (center_fraction * 1 m)^2) per axis (1 m: the step between images) and each point moved
// by N(0, (point_fraction * its distance to the first image seeing it)^2) per axis.
inline NViewReconstruction PerturbReconstruction(const NViewReconstruction& input,
                                                 double rotation_deg,
                                                 double center_fraction,
                                                 double point_fraction,
                                                 std::uint64_t seed) {
  constexpr double kDegToRad = M_PI / 180.0;
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  NViewReconstruction out = input;
  for (NViewImage& image : out.images) {
    const Eigen::Vector3d center =
        image.cam_from_world.Center() +
        center_fraction * Eigen::Vector3d(normal(rng), normal(rng), normal(rng));
    const Eigen::Vector3d omega =
        rotation_deg * kDegToRad * Eigen::Vector3d(normal(rng), normal(rng), normal(rng));
    if (omega.norm() > 0.0) {
      image.cam_from_world.R =
          Eigen::AngleAxisd(omega.norm(), omega.normalized()).toRotationMatrix() *
          image.cam_from_world.R;
    }
    image.cam_from_world.t = -image.cam_from_world.R * center;
  }
  std::vector<double> distance(out.points_in_world.size(), -1.0);
  for (const NViewObservation& o : input.observations) {
    if (distance[o.point_index] < 0.0) {
      distance[o.point_index] = (input.points_in_world[o.point_index] -
                                 input.images[o.image_index].cam_from_world.Center())
                                    .norm();
    }
  }
  for (std::size_t p = 0; p < out.points_in_world.size(); ++p) {
    out.points_in_world[p] += point_fraction * std::max(distance[p], 0.0) *
                              Eigen::Vector3d(normal(rng), normal(rng), normal(rng));
  }
  return out;
}

}  // namespace testing_utils
}  // namespace trigrav

#endif  // TRIGRAV_TESTS_NVIEW_SCENE_H_
