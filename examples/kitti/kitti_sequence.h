#ifndef TRIGRAV_EXAMPLES_KITTI_KITTI_SEQUENCE_H_
#define TRIGRAV_EXAMPLES_KITTI_KITTI_SEQUENCE_H_

// A frame range of a KITTI odometry sequence (Geiger, Lenz, Urtasun, CVPR 2012) in the official
// layout: <kitti_dir>/sequences/XX/image_0/NNNNNN.png (left grayscale camera, rectified),
// <kitti_dir>/sequences/XX/calib.txt (row "P0:", 3x4 row-major) and <kitti_dir>/poses/XX.txt (one
// row-major 3x4 [R | t] per frame mapping camera-0 coordinates of that frame into the world frame,
// which is camera 0 at frame 0).

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "trigrav/initializers/camera_pose.h"
#include "trigrav/initializers/three_view_observations.h"

namespace trigrav::kitti {

struct KittiSequence {
  std::string sequence;  // "00"
  int first_frame = 0;   // frames first_frame..last_frame, both included
  int last_frame = 0;
  PinholeCamera camera;  // from P0 (rectified, no distortion)
  // Per frame of the range (index frame - first_frame): ground truth x_cam = R x_world + t and the
  // image file.
  std::vector<CameraPose> cam_from_world;
  std::vector<std::string> image_paths;

  int num_frames() const { return last_frame - first_frame + 1; }
  const CameraPose& CamFromWorld(int frame) const { return cam_from_world[frame - first_frame]; }
  const std::string& ImagePath(int frame) const { return image_paths[frame - first_frame]; }
  // Ground truth of the triplet (frame, frame + 1, frame + 2): cam2_from_cam1 =
  // CamFromWorld(frame + 1) * CamFromWorld(frame).Inverse(), likewise cam3_from_cam1; metric
  // translations.
  ThreeViewPose GroundTruthTriplet(int frame) const;
};

// Reads calibration, poses and image paths of frames first..last. Returns false with a message
// naming the missing or malformed file or frame (no exception: the message is for a command line).
bool LoadKittiSequence(const std::string& kitti_dir,
                       const std::string& sequence,
                       int first_frame,
                       int last_frame,
                       KittiSequence* out,
                       std::string* error);

// Gravity (down, unit) in each frame of the range as an IMU would report it. The world y axis is
// taken as down, as the paper does on KITTI (the world frame, camera 0 of frame 0, is itself
// tilted by about a degree; only relative tilts enter the pose): gravity_in_cam = R_cam_from_world
// e_y. With imu_noise_deg > 0, each frame's gravity is perturbed by a pitch error (about the
// camera x axis) and a roll error (about the camera z axis), each N(0, imu_noise_deg), drawn from a
// generator seeded by (seed, frame), so the noise of a frame does not depend on the frame range or
// on threads.
std::vector<Eigen::Vector3d> ImuGravityInCameras(const KittiSequence& sequence,
                                                 double imu_noise_deg,
                                                 std::uint64_t seed);

}  // namespace trigrav::kitti

#endif  // TRIGRAV_EXAMPLES_KITTI_KITTI_SEQUENCE_H_
