#include "trigrav/evaluation/synthetic_scene.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "trigrav/initializers/gravity.h"

namespace trigrav {
namespace {

constexpr double kDegToRad = EIGEN_PI / 180.0;
constexpr int kMaxPointDraws = 200;
constexpr int kMaxSceneDraws = 1000;

void CheckField(bool ok, const char* what) {
  if (!ok) throw std::invalid_argument(std::string("trigrav: SyntheticSceneOptions: ") + what);
}

// World-to-camera rotation R_x(pitch) R_z(roll) R_y(yaw), derivations.md section 8.5.
Eigen::Matrix3d CamFromWorld(double pitch, double roll, double yaw) {
  return (Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitX()) *
          Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitY()))
      .toRotationMatrix();
}

// Draws the cameras of a scene (everything but the points).
void DrawCameras(const SyntheticSceneOptions& options,
                 std::mt19937_64* rng,
                 SyntheticScene* scene) {
  std::uniform_real_distribution<double> yaw(-options.max_yaw_deg, options.max_yaw_deg);
  std::uniform_real_distribution<double> tilt(-options.max_tilt_deg, options.max_tilt_deg);
  std::uniform_real_distribution<double> center(-options.max_center_m, options.max_center_m);
  std::normal_distribution<double> unit_normal(0.0, 1.0);
  for (int k = 0; k < 3; ++k) {
    scene->yaw_rad[k] = yaw(*rng) * kDegToRad;
    scene->pitch_rad[k] = tilt(*rng) * kDegToRad;
    scene->roll_rad[k] = tilt(*rng) * kDegToRad;
    scene->cam_from_world[k] =
        CamFromWorld(scene->pitch_rad[k], scene->roll_rad[k], scene->yaw_rad[k]);
    scene->center_in_world[k] = k == 0 ? Eigen::Vector3d::Zero()
                                       : Eigen::Vector3d(center(*rng), center(*rng), center(*rng));
    scene->gravity_alignment_true[k] =
        GravityAlignmentFromPitchRoll(scene->pitch_rad[k], scene->roll_rad[k]);
    const double pitch_noise = options.imu_pitch_noise_deg * kDegToRad * unit_normal(*rng);
    const double roll_noise = options.imu_roll_noise_deg * kDegToRad * unit_normal(*rng);
    scene->gravity_alignment_measured[k] = GravityAlignmentFromPitchRoll(
        scene->pitch_rad[k] + pitch_noise, scene->roll_rad[k] + roll_noise);
    scene->gravity_in_cam_measured[k] = GravityInCamera(scene->gravity_alignment_measured[k]);
  }
  // Ground truth in the original frames: R~_k = W_k W_1^T, centre t~_k = W_1 (C_k - C_1).
  CameraPose* poses[2] = {&scene->ground_truth.cam2_from_cam1, &scene->ground_truth.cam3_from_cam1};
  for (int k = 1; k < 3; ++k) {
    const Eigen::Matrix3d R = scene->cam_from_world[k] * scene->cam_from_world[0].transpose();
    const Eigen::Vector3d center_in_cam1 =
        scene->cam_from_world[0] * (scene->center_in_world[k] - scene->center_in_world[0]);
    poses[k - 1]->R = R;
    poses[k - 1]->t = -R * center_in_cam1;
  }
}

// Projection of a world point into view k; false if not at least min_depth in front or not
// visible through the lens.
bool Project(const SyntheticScene& scene,
             int k,
             const Eigen::Vector3d& point_in_world,
             const SyntheticSceneOptions& options,
             Eigen::Vector2d* pixel) {
  const Eigen::Vector3d p = scene.cam_from_world[k] * (point_in_world - scene.center_in_world[k]);
  if (!(p.z() > options.min_depth_all_views_m)) return false;
  *pixel = scene.camera.Project(p);
  // Beyond the fold of a radial distortion a direction lands back inside the image, on the pixel
  // of another direction: no lens sees it. Keep the directions the pixel unprojects to.
  Eigen::Vector3d ray;
  if (!scene.camera.Unproject(*pixel, &ray) || !((ray - p / p.z()).norm() < 1e-6)) return false;
  return pixel->x() >= 0.0 && pixel->x() <= options.width_px && pixel->y() >= 0.0 &&
         pixel->y() <= options.height_px;
}

// Tries to draw all points of the scene; false if kMaxPointDraws draws in a row fail.
bool DrawPoints(const SyntheticSceneOptions& options, std::mt19937_64* rng, SyntheticScene* scene) {
  std::uniform_real_distribution<double> u(0.0, options.width_px);
  std::uniform_real_distribution<double> v(0.0, options.height_px);
  std::uniform_real_distribution<double> depth(options.min_depth_m, options.max_depth_m);
  std::normal_distribution<double> noise(0.0, 1.0);
  scene->points_in_world.clear();
  for (auto& p : scene->pixels) p.clear();
  for (auto& r : scene->rays) r.clear();
  while (static_cast<int>(scene->points_in_world.size()) < options.num_points) {
    bool found = false;
    for (int draw = 0; draw < kMaxPointDraws && !found; ++draw) {
      Eigen::Vector3d ray1;
      if (!scene->camera.Unproject(Eigen::Vector2d(u(*rng), v(*rng)), &ray1)) continue;
      const Eigen::Vector3d point =
          scene->center_in_world[0] + scene->cam_from_world[0].transpose() * (depth(*rng) * ray1);
      std::array<Eigen::Vector2d, 3> pixels;
      found = Project(*scene, 0, point, options, &pixels[0]) &&
              Project(*scene, 1, point, options, &pixels[1]) &&
              Project(*scene, 2, point, options, &pixels[2]);
      if (!found) continue;
      std::array<Eigen::Vector2d, 3> noisy;
      std::array<Eigen::Vector3d, 3> rays;
      for (int k = 0; k < 3; ++k) {
        noisy[k] = pixels[k] + options.pixel_noise_px * Eigen::Vector2d(noise(*rng), noise(*rng));
        found = found && scene->camera.Unproject(noisy[k], &rays[k]);
      }
      if (!found) continue;  // noise pushed a pixel beyond the distortion's fold
      scene->points_in_world.push_back(point);
      for (int k = 0; k < 3; ++k) {
        scene->pixels[k].push_back(noisy[k]);
        scene->rays[k].push_back(rays[k]);
      }
    }
    if (!found) return false;
  }
  return true;
}

// Replaces one random view's pixel of a random outlier_ratio fraction of the triplets.
void InjectOutliers(const SyntheticSceneOptions& options,
                    std::mt19937_64* rng,
                    SyntheticScene* scene) {
  const int n = static_cast<int>(scene->points_in_world.size());
  scene->is_inlier.assign(n, 1);
  if (options.outlier_ratio <= 0.0) return;
  std::vector<int> order(n);
  for (int i = 0; i < n; ++i) order[i] = i;
  std::shuffle(order.begin(), order.end(), *rng);
  const int num_outliers = static_cast<int>(std::lround(options.outlier_ratio * n));
  std::uniform_int_distribution<int> view(0, 2);
  std::uniform_real_distribution<double> u(0.0, options.width_px), v(0.0, options.height_px);
  constexpr double kMinShiftPx = 20.0;
  for (int j = 0; j < num_outliers; ++j) {
    const int i = order[j];
    const int k = view(*rng);
    Eigen::Vector2d replacement;
    do {
      replacement = Eigen::Vector2d(u(*rng), v(*rng));
    } while ((replacement - scene->pixels[k][i]).norm() < kMinShiftPx ||
             !scene->camera.Unproject(replacement, &scene->rays[k][i]));
    scene->pixels[k][i] = replacement;
    scene->is_inlier[i] = 0;
  }
}

}  // namespace

ThreeViewObservations ToObservations(const SyntheticScene& scene) {
  ThreeViewObservations observations;
  for (int k = 0; k < 3; ++k) {
    observations.cameras[k] = scene.camera;
    observations.gravity_in_cam[k] = scene.gravity_in_cam_measured[k];
    observations.pixels[k] = scene.pixels[k];
  }
  return observations;
}

ThreeViewObservations ToBearingObservations(const SyntheticScene& scene) {
  ThreeViewObservations observations;
  for (int k = 0; k < 3; ++k) {
    observations.gravity_in_cam[k] = scene.gravity_in_cam_measured[k];
    observations.bearings[k].reserve(scene.rays[k].size());
    for (const Eigen::Vector3d& ray : scene.rays[k]) {
      observations.bearings[k].push_back(ray.normalized());
    }
  }
  return observations;
}

void SyntheticSceneOptions::Check() const {
  CheckField(num_points >= 1, "num_points must be >= 1");
  CheckField(focal_px > 0.0 && std::isfinite(focal_px), "focal_px must be positive and finite");
  CheckField(
      width_px > 0.0 && height_px > 0.0 && std::isfinite(width_px) && std::isfinite(height_px),
      "image size must be positive and finite");
  CheckField(max_yaw_deg >= 0.0 && max_yaw_deg <= 180.0, "max_yaw_deg must be in [0, 180]");
  CheckField(max_tilt_deg >= 0.0 && max_tilt_deg < 90.0, "max_tilt_deg must be in [0, 90)");
  CheckField(max_center_m >= 0.0 && std::isfinite(max_center_m), "max_center_m must be >= 0");
  CheckField(min_depth_m > 0.0 && max_depth_m >= min_depth_m && std::isfinite(max_depth_m),
             "depths must satisfy 0 < min_depth_m <= max_depth_m < inf");
  CheckField(min_depth_all_views_m >= 0.0, "min_depth_all_views_m must be >= 0");
  CheckField(pixel_noise_px >= 0.0 && std::isfinite(pixel_noise_px), "pixel_noise_px must be >= 0");
  CheckField(imu_pitch_noise_deg >= 0.0 && std::isfinite(imu_pitch_noise_deg),
             "imu_pitch_noise_deg must be >= 0");
  CheckField(imu_roll_noise_deg >= 0.0 && std::isfinite(imu_roll_noise_deg),
             "imu_roll_noise_deg must be >= 0");
  for (const double d : opencv_distortion) {
    CheckField(std::isfinite(d), "opencv_distortion must be finite");
  }
  CheckField(outlier_ratio >= 0.0 && outlier_ratio <= 1.0, "outlier_ratio must be in [0, 1]");
}

SyntheticScene GenerateSyntheticScene(const SyntheticSceneOptions& options, std::mt19937_64* rng) {
  options.Check();
  if (rng == nullptr) throw std::invalid_argument("trigrav: GenerateSyntheticScene: rng is null");
  SyntheticScene scene;
  const double f = options.focal_px, cx = 0.5 * options.width_px, cy = 0.5 * options.height_px;
  const std::array<double, 4>& d = options.opencv_distortion;
  scene.camera = d == std::array<double, 4>{0.0, 0.0, 0.0, 0.0}
                     ? Camera(PinholeCamera{f, f, cx, cy})
                     : Camera(CameraModel::kOpenCV, {f, f, cx, cy, d[0], d[1], d[2], d[3]});
  for (int attempt = 0; attempt < kMaxSceneDraws; ++attempt) {
    DrawCameras(options, rng, &scene);
    if (DrawPoints(options, rng, &scene)) {
      InjectOutliers(options, rng, &scene);
      return scene;
    }
  }
  throw std::runtime_error("trigrav: GenerateSyntheticScene: no scene with all points visible");
}

}  // namespace trigrav
