#ifndef TRIGRAV_COLMAP_RECONSTRUCTION_H_
#define TRIGRAV_COLMAP_RECONSTRUCTION_H_

// A COLMAP 3.8 sparse model in memory: cameras, images and 3D points with the fields of COLMAP's
// cameras.txt / images.txt / points3D.txt (and their binary twins), keyed by COLMAP's ids. Poses
// are COLMAP's: cam_from_world maps world coordinates into the camera (x_cam = R x_world + t), the
// camera models are trigrav's Camera (camera_model.h, COLMAP's names and parameter order; COLMAP
// models trigrav does not have are rejected when reading). Pixels use COLMAP's convention: the
// centre of the top-left pixel is (0.5, 0.5).

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "trigrav/initializers/camera_model.h"
#include "trigrav/initializers/camera_pose.h"

namespace trigrav {
namespace colmap {

using CameraId = std::uint32_t;
using ImageId = std::uint32_t;
using Point3DId = std::uint64_t;
// COLMAP's "no 3D point" (kInvalidPoint3DId, written as -1 in images.txt).
inline constexpr Point3DId kInvalidPoint3DId = static_cast<Point3DId>(-1);

struct ColmapCamera {
  CameraId camera_id = 0;
  Camera camera;
  int width = 0;
  int height = 0;
};

struct ColmapImage {
  ImageId image_id = 0;
  std::string name;  // path relative to the image folder, as COLMAP stores it
  CameraId camera_id = 0;
  CameraPose cam_from_world;
  // Keypoints of the image (pixels) and, per keypoint, the 3D point it observes or
  // kInvalidPoint3DId.
  std::vector<Eigen::Vector2d> points2D;
  std::vector<Point3DId> point3D_ids;
};

struct TrackElement {
  ImageId image_id = 0;
  std::uint32_t point2D_idx = 0;  // index into that image's points2D
};

struct ColmapPoint3D {
  Eigen::Vector3d xyz = Eigen::Vector3d::Zero();  // point_in_world
  std::array<std::uint8_t, 3> color{};
  double error = -1.0;  // mean reprojection error in pixels; -1 when unknown
  std::vector<TrackElement> track;
};

struct Reconstruction {
  std::map<CameraId, ColmapCamera> cameras;
  std::map<ImageId, ColmapImage> images;  // the registered images
  std::map<Point3DId, ColmapPoint3D> points3D;

  // Throws std::invalid_argument naming the first inconsistency: an image of an unknown camera, a
  // track element of an unknown image or keypoint, a keypoint whose point3D id disagrees with the
  // track that names it, sizes of points2D and point3D_ids that differ, non-finite poses or points,
  // a cam_from_world.R that is not a rotation (to 1e-9), a map key that differs from the record's
  // id, an invalid camera, an empty image name or one with a line break or NUL.
  void Check() const;
};

}  // namespace colmap
}  // namespace trigrav

#endif  // TRIGRAV_COLMAP_RECONSTRUCTION_H_
