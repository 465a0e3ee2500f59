#ifndef TRIGRAV_EVALUATION_SYNTHETIC_SCENE_H_
#define TRIGRAV_EVALUATION_SYNTHETIC_SCENE_H_

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <random>
#include <vector>

#include "trigrav/initializers/camera_pose.h"
#include "trigrav/initializers/three_view_observations.h"

namespace trigrav {

// Synthetic three-view scenes following the protocol of the paper's Section IV as made explicit in
// derivations.md section 8.5. Defaults are that section's values (f = 500 px, 640 x 480, +-10 deg,
// +-10 m). The world y axis is gravity (down); camera k has world-to-camera rotation W_k =
// R_x(pitch_k) R_z(roll_k) R_y(yaw_k) and centre C_k (C_1 = 0).
struct SyntheticSceneOptions {
  int num_points = 4;
  double focal_px = 500.0;
  // OPENCV distortion (k1, k2, p1, p2) of all three cameras; all 0 (the default) gives PINHOLE.
  std::array<double, 4> opencv_distortion = {0.0, 0.0, 0.0, 0.0};
  double width_px = 640.0;
  double height_px = 480.0;
  double max_yaw_deg = 10.0;   // yaw_k ~ U(-max, max), independently per view
  double max_tilt_deg = 10.0;  // pitch_k, roll_k ~ U(-max, max)
  double max_center_m = 10.0;  // C_2, C_3 ~ U(-max, max)^3
  double min_depth_m = 10.0;   // view-1 depth of the points ~ U(min, max)
  double max_depth_m = 40.0;
  double min_depth_all_views_m = 1.0;  // a point is kept only if deeper than this in every view
  double pixel_noise_px = 0.0;         // N(0, sigma^2) on u and v in all three views
  double imu_pitch_noise_deg = 0.0;    // N(0, sigma^2) on the pitch seen by the solver, per view
  double imu_roll_noise_deg = 0.0;     // N(0, sigma^2) on the roll seen by the solver, per view
  // Fraction of triplets made outliers: one view's pixel (chosen at random) is replaced by a
  // uniform random pixel at least 20 px from the true one. With 0 no extra random numbers are
  // drawn.
  double outlier_ratio = 0.0;

  // Throws std::invalid_argument naming the first bad field.
  void Check() const;
};

struct SyntheticScene {
  ThreeViewPose ground_truth;                      // original (unaligned) camera frames
  std::array<Eigen::Matrix3d, 3> cam_from_world;   // W_k
  std::array<Eigen::Vector3d, 3> center_in_world;  // C_k
  std::array<double, 3> pitch_rad{}, roll_rad{}, yaw_rad{};
  std::vector<Eigen::Vector3d> points_in_world;
  std::array<std::vector<Eigen::Vector2d>, 3> pixels;  // noisy pixels of each view
  std::array<std::vector<Eigen::Vector3d>, 3> rays;    // unprojected noisy pixels (z = 1)
  std::array<Eigen::Matrix3d, 3> gravity_alignment_true;
  std::array<Eigen::Matrix3d, 3> gravity_alignment_measured;  // with IMU noise
  std::array<Eigen::Vector3d, 3> gravity_in_cam_measured;     // unit, down, with IMU noise
  Camera camera;                                              // the same for all three views
  std::vector<char> is_inlier;                                // per triplet
};

// The scene as a pipeline sees it: intrinsics, measured gravity and (noisy, outlier-ridden) pixels.
ThreeViewObservations ToObservations(const SyntheticScene& scene);
// The same as bearings: the unit rays of the pixels, no cameras.
ThreeViewObservations ToBearingObservations(const SyntheticScene& scene);

// Draws one scene. Points are drawn as uniform pixels in view 1 at a uniform view-1 depth and kept
// if they are in front of and inside all three images; the scene is redrawn if 200 draws in a row
// fail. Throws std::invalid_argument for bad options, std::runtime_error if no scene can be made.
SyntheticScene GenerateSyntheticScene(const SyntheticSceneOptions& options, std::mt19937_64* rng);

}  // namespace trigrav

#endif  // TRIGRAV_EVALUATION_SYNTHETIC_SCENE_H_
