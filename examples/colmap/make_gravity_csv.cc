// The gravity CSV (trigrav/colmap/gravity_csv.h) of a folder of images from a ground-truth pose
// file, emulating an IMU's vertical direction as the KITTI README describes: each frame's gravity
// is the world's down axis seen from that frame's camera, optionally tilted by IMU-like noise.
//
//   make_gravity_csv --poses_path=kitti/poses/00.txt --image_path=images --output_path=g.csv
//
// Pose file: KITTI odometry's, line k = the 12 numbers of the row-major 3 x 4 [R_k | t_k] mapping
// frame k's camera coordinates into the world frame (camera-to-world). Images: every regular file
// under --image_path, named as COLMAP names them (the path relative to the folder, '/'
// separated), in sorted order; the k-th is frame k. World +y is down on KITTI (camera axes x right,
// y down, z forward, the world being frame 0's camera), so
//   gravity_in_cam_k = R_k^T e_y.
// "Exact" gravity (--noise_deg=0) is thus the ground-truth world's +y, i.e. frame 0's camera y
// axis: it carries frame 0's own tilt from true vertical (about a degree on KITTI), the same for
// every frame.
// With --noise_deg = sigma > 0 the vector is tilted by Exp(w) with w = a e1 + b e2, a, b ~ N(0,
// sigma^2) (radians), e1, e2 an orthonormal basis of the plane perpendicular to gravity: an IMU
// whose pitch and roll each err by about sigma (the tilt angle |w| is Rayleigh, mean 1.25 sigma).
// The random numbers come from std::mt19937_64(--seed) and std::normal_distribution, the same for
// one standard library.

#include <gflags/gflags.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/output_paths.h"
#include "common/require_flag.h"
#include "common/tool_flags.h"
#include "trigrav/colmap/gravity_csv.h"

DEFINE_string(poses_path,
              "",
              "KITTI-style pose file: line k = row-major 3x4 [R|t] camera-to-world of frame k "
              "(required).");
DEFINE_string(image_path,
              "",
              "Image folder (COLMAP's --image_path): the k-th file in sorted order is frame k "
              "(required).");
DEFINE_string(output_path, "", "Gravity CSV to write (required).");
DEFINE_double(noise_deg,
              0.0,
              "IMU noise: sigma (deg) of the tilt added to each frame's gravity, per axis of the "
              "plane perpendicular to it; 0 = exact gravity (the poses' world +y).");
DEFINE_uint64(seed, 1, "Seed of the noise.");

namespace {

namespace fs = std::filesystem;
using trigrav::examples::RequireFlag;

constexpr double kDegToRad = M_PI / 180.0;

// The rotations R_k (camera-to-world) of a KITTI pose file, one per non-blank line.
std::vector<Eigen::Matrix3d> ReadCameraToWorldRotations(const std::string& path) {
  std::ifstream file(path);
  if (!file) throw std::runtime_error("cannot read --poses_path=" + path);
  std::vector<Eigen::Matrix3d> rotations;
  std::string line;
  for (int line_number = 1; std::getline(file, line); ++line_number) {
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    std::istringstream stream(line);
    double values[12];
    for (double& value : values) stream >> value;
    std::string rest;
    if (!stream || (stream >> rest) ||
        !std::all_of(values, values + 12, [](double v) { return std::isfinite(v); })) {
      throw std::runtime_error(path + ":" + std::to_string(line_number) +
                               ": expected 12 finite numbers (row-major 3x4 [R|t])");
    }
    Eigen::Matrix3d R;
    R << values[0], values[1], values[2], values[4], values[5], values[6], values[8], values[9],
        values[10];
    if (!((R.transpose() * R - Eigen::Matrix3d::Identity()).norm() < 1e-3) ||
        !(R.determinant() > 0.0)) {
      throw std::runtime_error(path + ":" + std::to_string(line_number) +
                               ": the 3x3 block is not a rotation");
    }
    rotations.push_back(R);
  }
  return rotations;
}

// Every regular file under `folder` (symbolic links to files included, not resolved), as a path
// relative to it with '/' separators, sorted.
std::vector<std::string> ImageNames(const std::string& folder) {
  std::vector<std::string> names;
  for (const fs::directory_entry& entry : fs::recursive_directory_iterator(folder)) {
    if (entry.is_regular_file()) {
      names.push_back(entry.path().lexically_relative(folder).generic_string());
    }
  }
  std::sort(names.begin(), names.end());
  return names;
}

// `gravity` (unit) tilted by Exp(a e1 + b e2), a, b ~ N(0, sigma^2).
Eigen::Vector3d Tilt(const Eigen::Vector3d& gravity, double sigma_rad, std::mt19937_64* rng) {
  std::normal_distribution<double> normal(0.0, sigma_rad);
  const Eigen::Vector3d e1 = gravity.unitOrthogonal();
  const Eigen::Vector3d e2 = gravity.cross(e1);
  const Eigen::Vector3d w = normal(*rng) * e1 + normal(*rng) * e2;
  if (!(w.norm() > 0.0)) return gravity;
  return Eigen::AngleAxisd(w.norm(), w.normalized()) * gravity;
}

void Run() {
  const std::vector<Eigen::Matrix3d> cam_to_world = ReadCameraToWorldRotations(FLAGS_poses_path);
  const std::vector<std::string> names = ImageNames(FLAGS_image_path);
  if (names.empty()) throw std::runtime_error("no image in --image_path=" + FLAGS_image_path);
  if (cam_to_world.size() < names.size()) {
    throw std::runtime_error("--poses_path=" + FLAGS_poses_path + " has " +
                             std::to_string(cam_to_world.size()) + " poses for " +
                             std::to_string(names.size()) +
                             " images in --image_path=" + FLAGS_image_path);
  }
  std::mt19937_64 rng(FLAGS_seed);
  trigrav::colmap::GravityByImageName gravity;
  for (std::size_t k = 0; k < names.size(); ++k) {
    const Eigen::Vector3d exact = cam_to_world[k].transpose() * Eigen::Vector3d::UnitY();
    gravity[names[k]] =
        FLAGS_noise_deg > 0.0 ? Tilt(exact, FLAGS_noise_deg * kDegToRad, &rng) : exact;
  }
  trigrav::colmap::WriteGravityCsv(gravity, FLAGS_output_path);
  std::cout << "wrote the gravity of " << names.size() << " images (" << cam_to_world.size()
            << " poses, noise " << FLAGS_noise_deg << " deg) to " << FLAGS_output_path << "\n";
}

}  // namespace

int main(int argc, char** argv) {
  trigrav::examples::ParseToolFlags(
      "make_gravity_csv --poses_path=poses.txt --image_path=images --output_path=g.csv", __FILE__,
      &argc, &argv);
  RequireFlag(!FLAGS_poses_path.empty(), "--poses_path is required");
  RequireFlag(fs::is_regular_file(FLAGS_poses_path),
              "--poses_path=" + FLAGS_poses_path + " is not a file");
  RequireFlag(!FLAGS_image_path.empty(), "--image_path is required");
  RequireFlag(fs::is_directory(FLAGS_image_path),
              "--image_path=" + FLAGS_image_path + " is not a folder");
  RequireFlag(!FLAGS_output_path.empty(), "--output_path is required");
  RequireFlag(FLAGS_noise_deg >= 0.0 && std::isfinite(FLAGS_noise_deg),
              "--noise_deg must be finite and >= 0");
  using trigrav::examples::ToolPath;
  trigrav::examples::RequireOutputsApartFromInputs(
      {{"--poses_path", FLAGS_poses_path}, {"--image_path", FLAGS_image_path, ToolPath::kFolder}},
      {{"--output_path", FLAGS_output_path}});
  try {
    Run();
  } catch (const std::exception& error) {
    std::cerr << "error: " << error.what() << std::endl;
    return 1;
  }
  return 0;
}
