#include "trigrav/colmap/reconstruction.h"

#include <Eigen/Core>
#include <Eigen/LU>
#include <cmath>
#include <set>
#include <stdexcept>
#include <utility>

namespace trigrav {
namespace colmap {
namespace {

[[noreturn]] void Fail(const std::string& message) {
  throw std::invalid_argument("trigrav::colmap: Reconstruction: " + message);
}

// R^T R = I and det R = 1 to 1e-9: cam_from_world.R is written as a unit quaternion.
bool IsRotation(const Eigen::Matrix3d& R) {
  return (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() < 1e-9 &&
         std::abs(R.determinant() - 1.0) < 1e-9;
}

void CheckCamera(CameraId key, const ColmapCamera& camera) {
  const std::string name = "camera " + std::to_string(key);
  if (camera.camera_id != key) Fail(name + " has camera_id " + std::to_string(camera.camera_id));
  if (camera.width <= 0 || camera.height <= 0) Fail(name + ": width and height must be positive");
  try {
    camera.camera.Check();
  } catch (const std::invalid_argument& error) {
    Fail(name + ": " + error.what());
  }
}

void CheckImage(ImageId key, const ColmapImage& image, const Reconstruction& reconstruction) {
  const std::string name = "image " + std::to_string(key);
  if (image.image_id != key) Fail(name + " has image_id " + std::to_string(image.image_id));
  if (image.name.empty()) Fail(name + " has no name");
  if (image.name.find_first_of(std::string("\n\r\0", 3)) != std::string::npos) {
    Fail(name + ": the name contains a line break or a NUL character");
  }
  if (reconstruction.cameras.count(image.camera_id) == 0) {
    Fail(name + " refers to unknown camera " + std::to_string(image.camera_id));
  }
  if (!image.cam_from_world.IsFinite()) Fail(name + ": cam_from_world is not finite");
  if (!IsRotation(image.cam_from_world.R)) Fail(name + ": cam_from_world.R is not a rotation");
  if (image.points2D.size() != image.point3D_ids.size()) {
    Fail(name + ": points2D has " + std::to_string(image.points2D.size()) +
         " entries but point3D_ids " + std::to_string(image.point3D_ids.size()));
  }
  for (std::size_t i = 0; i < image.points2D.size(); ++i) {
    if (!image.points2D[i].allFinite()) {
      Fail(name + ": point2D " + std::to_string(i) + " is not finite");
    }
    const Point3DId point3D_id = image.point3D_ids[i];
    if (point3D_id != kInvalidPoint3DId && reconstruction.points3D.count(point3D_id) == 0) {
      Fail(name + ": point2D " + std::to_string(i) + " observes unknown point3D " +
           std::to_string(point3D_id));
    }
  }
}

}  // namespace

void Reconstruction::Check() const {
  for (const auto& [camera_id, camera] : cameras) CheckCamera(camera_id, camera);
  std::size_t num_observations = 0;  // keypoints with a 3D point
  for (const auto& [image_id, image] : images) {
    CheckImage(image_id, image, *this);
    for (const Point3DId point3D_id : image.point3D_ids) {
      num_observations += point3D_id != kInvalidPoint3DId;
    }
  }
  // Every track element names a distinct keypoint that names the point back; with as many track
  // elements as keypoints naming a point, the two agree everywhere.
  std::set<std::pair<ImageId, std::uint32_t>> track_elements;
  for (const auto& [point3D_id, point] : points3D) {
    const std::string name = "point3D " + std::to_string(point3D_id);
    if (point3D_id == kInvalidPoint3DId) Fail("point3D id -1 is reserved for \"no point\"");
    if (!point.xyz.allFinite()) Fail(name + ": xyz is not finite");
    if (!std::isfinite(point.error)) Fail(name + ": error is not finite");
    for (const TrackElement& element : point.track) {
      const std::string element_name = name + ": track element (image " +
                                       std::to_string(element.image_id) + ", point2D " +
                                       std::to_string(element.point2D_idx) + ")";
      const auto image = images.find(element.image_id);
      if (image == images.end()) Fail(element_name + " refers to an unknown image");
      if (element.point2D_idx >= image->second.points2D.size()) {
        Fail(element_name + " refers to a point2D beyond the image's " +
             std::to_string(image->second.points2D.size()));
      }
      if (image->second.point3D_ids[element.point2D_idx] != point3D_id) {
        Fail(element_name + ": that point2D observes point3D " +
             std::to_string(
                 static_cast<std::int64_t>(image->second.point3D_ids[element.point2D_idx])));
      }
      if (!track_elements.emplace(element.image_id, element.point2D_idx).second) {
        Fail(element_name + " appears twice");
      }
    }
  }
  if (track_elements.size() == num_observations) return;
  for (const auto& [image_id, image] : images) {
    for (std::uint32_t i = 0; i < image.point3D_ids.size(); ++i) {
      if (image.point3D_ids[i] != kInvalidPoint3DId && track_elements.count({image_id, i}) == 0) {
        Fail("image " + std::to_string(image_id) + ": point2D " + std::to_string(i) +
             " observes point3D " + std::to_string(image.point3D_ids[i]) +
             " whose track does not contain it");
      }
    }
  }
}

}  // namespace colmap
}  // namespace trigrav
