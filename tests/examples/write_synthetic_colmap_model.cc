// Writes a small synthetic COLMAP model with noisy poses and points, and its gravity CSV, for the
// end-to-end test of gravity_bundle_adjuster (check_colmap_tools.cmake):
//   write_synthetic_colmap_model <folder>
// creates <folder>/model (binary: 5 images of one PINHOLE camera driving forward, 150 points seen
// in every image, 0.5 px pixel noise, poses and points perturbed) and <folder>/gravity.csv (exact
// gravity: the world's +y axis seen from each camera).

#include <Eigen/Geometry>
#include <filesystem>
#include <iostream>
#include <random>
#include <string>

#include "trigrav/colmap/gravity_csv.h"
#include "trigrav/colmap/model_io.h"

namespace {

namespace colmap = trigrav::colmap;

constexpr int kNumImages = 5;
constexpr int kNumPoints = 150;

Eigen::Matrix3d SmallRotation(double sigma_rad, std::mt19937_64* rng) {
  std::normal_distribution<double> normal(0.0, sigma_rad);
  const Eigen::Vector3d w(normal(*rng), normal(*rng), normal(*rng));
  return Eigen::AngleAxisd(w.norm(), w.normalized()).toRotationMatrix();
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: write_synthetic_colmap_model <folder>\n";
    return 2;
  }
  const std::string folder = argv[1];
  std::mt19937_64 rng(7);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);

  colmap::Reconstruction model;
  colmap::ColmapCamera& camera = model.cameras[1];
  camera.camera_id = 1;
  camera.camera = trigrav::Camera::FromColmap("PINHOLE", {500.0, 500.0, 320.0, 240.0});
  camera.width = 640;
  camera.height = 480;

  // True poses: forward along z, 1 m apart, a few degrees of yaw, pitch and roll.
  std::vector<trigrav::CameraPose> truth(kNumImages);
  colmap::GravityByImageName gravity;
  for (int k = 0; k < kNumImages; ++k) {
    const Eigen::Matrix3d R = (Eigen::AngleAxisd(0.02 * k, Eigen::Vector3d::UnitY()) *
                               Eigen::AngleAxisd(0.01 * uniform(rng), Eigen::Vector3d::UnitX()) *
                               Eigen::AngleAxisd(0.01 * uniform(rng), Eigen::Vector3d::UnitZ()))
                                  .toRotationMatrix();
    const Eigen::Vector3d center(0.1 * k, 0.0, 1.0 * k);
    truth[k].R = R;
    truth[k].t = -R * center;
    colmap::ColmapImage& image = model.images[k + 1];
    image.image_id = k + 1;
    image.name = "frame" + std::to_string(k) + ".png";
    image.camera_id = 1;
    image.cam_from_world.R = SmallRotation(0.005, &rng) * R;
    image.cam_from_world.t = -image.cam_from_world.R * (center + 0.05 * Eigen::Vector3d::Random());
    gravity[image.name] = R * Eigen::Vector3d::UnitY();
  }
  // Points seen in every image; each image also has one keypoint without a point.
  for (colmap::Point3DId id = 1; model.points3D.size() < kNumPoints;) {
    const Eigen::Vector3d point(8.0 * uniform(rng), 3.0 * uniform(rng), 19.0 + 11.0 * uniform(rng));
    bool visible = true;
    std::vector<Eigen::Vector2d> pixels;
    for (int k = 0; k < kNumImages; ++k) {
      const Eigen::Vector3d in_cam = truth[k].Apply(point);
      const Eigen::Vector2d pixel = camera.camera.Project(in_cam);
      visible = visible && in_cam.z() > 1.0 && pixel.x() > 0 && pixel.x() < 640 && pixel.y() > 0 &&
                pixel.y() < 480;
      pixels.push_back(pixel + 0.5 * Eigen::Vector2d(normal(rng), normal(rng)));
    }
    if (!visible) continue;
    colmap::ColmapPoint3D& model_point = model.points3D[id];
    model_point.xyz = point + 0.05 * Eigen::Vector3d(normal(rng), normal(rng), normal(rng));
    for (int k = 0; k < kNumImages; ++k) {
      colmap::ColmapImage& image = model.images[k + 1];
      model_point.track.push_back({image.image_id, std::uint32_t(image.points2D.size())});
      image.points2D.push_back(pixels[k]);
      image.point3D_ids.push_back(id);
    }
    ++id;
  }
  for (auto& [id, image] : model.images) {
    image.points2D.emplace_back(10.0, 10.0);
    image.point3D_ids.push_back(colmap::kInvalidPoint3DId);
  }
  std::filesystem::create_directories(folder + "/model");
  colmap::WriteModel(model, folder + "/model", colmap::ModelFormat::kBinary);
  colmap::WriteGravityCsv(gravity, folder + "/gravity.csv");
  std::cout << "wrote " << folder << "/model and " << folder << "/gravity.csv\n";
  return 0;
}
