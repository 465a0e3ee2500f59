#include "kitti_sequence.h"

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

namespace trigrav::kitti {
namespace {

namespace fs = std::filesystem;

bool ReadCameraP0(const fs::path& calib_path, PinholeCamera* camera, std::string* error) {
  std::ifstream file(calib_path);
  if (!file) {
    *error = "cannot read " + calib_path.string();
    return false;
  }
  std::string line;
  while (std::getline(file, line)) {
    std::istringstream row(line);
    std::string name;
    row >> name;
    if (name != "P0:") continue;
    double p[12];
    for (double& v : p) row >> v;
    if (!row) break;
    // P0 = K [I | 0] for the rectified left camera: fx = P(0,0), fy = P(1,1), cx = P(0,2), cy =
    // P(1,2).
    camera->fx = p[0];
    camera->fy = p[5];
    camera->cx = p[2];
    camera->cy = p[6];
    if (!camera->IsValid()) break;
    return true;
  }
  *error = calib_path.string() + " has no valid row \"P0:\" with 12 numbers";
  return false;
}

// Reads rows 0..last_frame of a poses file: world_from_cam [R | t], stored as cam_from_world.
bool ReadPoses(const fs::path& poses_path,
               int last_frame,
               std::vector<CameraPose>* cam_from_world,
               std::string* error) {
  std::ifstream file(poses_path);
  if (!file) {
    *error = "cannot read " + poses_path.string();
    return false;
  }
  cam_from_world->clear();
  std::string line;
  while (static_cast<int>(cam_from_world->size()) <= last_frame && std::getline(file, line)) {
    std::istringstream row(line);
    Eigen::Matrix<double, 3, 4, Eigen::RowMajor> world_from_cam;
    for (int i = 0; i < 12; ++i) row >> world_from_cam.data()[i];
    if (!row || !world_from_cam.allFinite()) {
      *error = poses_path.string() + ": line " + std::to_string(cam_from_world->size() + 1) +
               " is not 12 finite numbers";
      return false;
    }
    CameraPose pose;
    pose.R = world_from_cam.leftCols<3>().transpose();
    pose.t = -pose.R * world_from_cam.col(3);
    cam_from_world->push_back(pose);
  }
  if (static_cast<int>(cam_from_world->size()) <= last_frame) {
    *error = poses_path.string() + " has poses of frames 0.." +
             std::to_string(static_cast<int>(cam_from_world->size()) - 1) + ", not up to frame " +
             std::to_string(last_frame);
    return false;
  }
  return true;
}

}  // namespace

ThreeViewPose KittiSequence::GroundTruthTriplet(int frame) const {
  ThreeViewPose pose;
  const CameraPose world_from_cam1 = CamFromWorld(frame).Inverse();
  pose.cam2_from_cam1 = CamFromWorld(frame + 1) * world_from_cam1;
  pose.cam3_from_cam1 = CamFromWorld(frame + 2) * world_from_cam1;
  return pose;
}

bool LoadKittiSequence(const std::string& kitti_dir,
                       const std::string& sequence,
                       int first_frame,
                       int last_frame,
                       KittiSequence* out,
                       std::string* error) {
  if (first_frame < 0 || last_frame < first_frame) {
    *error = "frame range " + std::to_string(first_frame) + ".." + std::to_string(last_frame) +
             " is empty or negative";
    return false;
  }
  const fs::path root(kitti_dir);
  const fs::path sequence_dir = root / "sequences" / sequence;
  if (!fs::is_directory(sequence_dir / "image_0")) {
    *error = "no folder " + (sequence_dir / "image_0").string() +
             " (expected the KITTI odometry layout sequences/XX/image_0)";
    return false;
  }
  KittiSequence result;
  result.sequence = sequence;
  result.first_frame = first_frame;
  result.last_frame = last_frame;
  if (!ReadCameraP0(sequence_dir / "calib.txt", &result.camera, error)) return false;
  std::vector<CameraPose> all_poses;
  if (!ReadPoses(root / "poses" / (sequence + ".txt"), last_frame, &all_poses, error)) return false;
  result.cam_from_world.assign(all_poses.begin() + first_frame, all_poses.end());
  for (int frame = first_frame; frame <= last_frame; ++frame) {
    char name[32];
    std::snprintf(name, sizeof(name), "%06d.png", frame);
    const fs::path image = sequence_dir / "image_0" / name;
    if (!fs::is_regular_file(image)) {
      *error = "frame " + std::to_string(frame) + " is missing: no " + image.string();
      return false;
    }
    result.image_paths.push_back(image.string());
  }
  *out = std::move(result);
  return true;
}

std::vector<Eigen::Vector3d> ImuGravityInCameras(const KittiSequence& sequence,
                                                 double imu_noise_deg,
                                                 std::uint64_t seed) {
  std::vector<Eigen::Vector3d> gravity;
  gravity.reserve(sequence.num_frames());
  for (int frame = sequence.first_frame; frame <= sequence.last_frame; ++frame) {
    Eigen::Vector3d g = sequence.CamFromWorld(frame).R * Eigen::Vector3d::UnitY();
    if (imu_noise_deg > 0.0) {
      std::seed_seq seeds{static_cast<std::uint32_t>(seed), static_cast<std::uint32_t>(seed >> 32),
                          static_cast<std::uint32_t>(frame)};
      std::mt19937_64 rng(seeds);
      std::normal_distribution<double> angle(0.0, imu_noise_deg * M_PI / 180.0);
      const double pitch = angle(rng);
      const double roll = angle(rng);
      g = Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitX()) *
          (Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitZ()) * g);
    }
    gravity.push_back(g);
  }
  return gravity;
}

}  // namespace trigrav::kitti
