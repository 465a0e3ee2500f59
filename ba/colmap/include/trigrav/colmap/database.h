#ifndef TRIGRAV_COLMAP_DATABASE_H_
#define TRIGRAV_COLMAP_DATABASE_H_

// Read-only access to a COLMAP 3.8 database (SQLite; https://colmap.github.io/database.html):
// cameras, images, keypoints and the verified matches of two_view_geometries.

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "trigrav/colmap/reconstruction.h"

namespace trigrav {
namespace colmap {

// The inlier matches of one verified image pair, image_id1 < image_id2 as COLMAP stores them.
struct TwoViewGeometry {
  ImageId image_id1 = 0;
  ImageId image_id2 = 0;
  // COLMAP's TwoViewGeometry::ConfigurationType (2 CALIBRATED, 3 UNCALIBRATED, ...).
  int config = 0;
  // Keypoint indices (into image_id1's, image_id2's keypoints) of each inlier match.
  std::vector<std::array<std::uint32_t, 2>> matches;
};

// An image row of the database (name, camera); keypoints are read separately.
struct DatabaseImage {
  ImageId image_id = 0;
  std::string name;
  CameraId camera_id = 0;
};

class Database {
 public:
  // Opens `path` read-only. Throws std::runtime_error naming the file when it does not exist, is
  // not an SQLite database, or lacks the tables of a COLMAP database (cameras, images, keypoints,
  // two_view_geometries).
  explicit Database(const std::string& path);
  ~Database();
  Database(const Database&) = delete;
  Database& operator=(const Database&) = delete;

  // Every camera; a COLMAP model trigrav does not have, or a parameter blob of the wrong size,
  // throws std::runtime_error naming the camera id and the model.
  std::vector<ColmapCamera> ReadCameras() const;
  // Every image; one whose camera_id has no camera row throws std::runtime_error naming the image.
  std::vector<DatabaseImage> ReadImages() const;
  // Keypoint positions of an image (pixels, COLMAP's convention; the first two columns of
  // COLMAP's 2-, 4- or 6-column keypoint rows). An image without keypoints gives an empty vector;
  // an unknown image id, a malformed blob or a non-finite position throws std::runtime_error
  // naming the image (and the row).
  std::vector<Eigen::Vector2d> ReadKeypoints(ImageId image_id) const;
  // Every verified pair with at least one inlier match. A match index outside its image's keypoint
  // count throws std::runtime_error naming the pair.
  std::vector<TwoViewGeometry> ReadTwoViewGeometries() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// COLMAP's pair id of two images, and back (image_id1 < image_id2; PairId orders its arguments,
// as COLMAP's Database::ImagePairToPairId).
std::uint64_t PairId(ImageId image_id1, ImageId image_id2);
void ImagesOfPairId(std::uint64_t pair_id, ImageId* image_id1, ImageId* image_id2);

}  // namespace colmap
}  // namespace trigrav

#endif  // TRIGRAV_COLMAP_DATABASE_H_
