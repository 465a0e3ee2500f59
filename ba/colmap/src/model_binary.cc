// COLMAP's binary model (https://colmap.github.io/format.html#binary-file-format; COLMAP 3.8
// src/base/reconstruction.cc), every number little-endian:
//   cameras.bin   uint64 count; per camera: uint32 camera_id, int32 model_id, uint64 width,
//                 uint64 height, double params[NumCameraParams(model)]
//   images.bin    uint64 count; per image: uint32 image_id, double qw qx qy qz tx ty tz,
//                 uint32 camera_id, name bytes + '\0', uint64 num_points2D, per point2D:
//                 double x, double y, uint64 point3D_id (2^64 - 1 for none)
//   points3D.bin  uint64 count; per point: uint64 point3D_id, double x y z, uint8 r g b,
//                 double error, uint64 track_length, per element: uint32 image_id,
//                 uint32 point2D_idx
#include <cstdint>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <type_traits>

#include "colmap_camera_models.h"
#include "model_formats.h"

namespace trigrav {
namespace colmap {
namespace internal {
namespace {

// Little-endian values from a file's bytes; reading past the end throws std::runtime_error naming
// the file, the record and what was being read.
class ByteReader {
 public:
  ByteReader(const std::string& bytes, const std::string& path) : bytes_(bytes), path_(path) {}

  template <typename T>
  T Read(const char* what) {
    static_assert(std::is_arithmetic_v<T>);
    Require(sizeof(T), what);
    std::uint64_t bits = 0;
    for (std::size_t i = 0; i < sizeof(T); ++i) {
      bits |= static_cast<std::uint64_t>(static_cast<unsigned char>(bytes_[position_ + i]))
              << (8 * i);
    }
    position_ += sizeof(T);
    if constexpr (std::is_floating_point_v<T>) {
      T value;
      std::memcpy(&value, &bits, sizeof(T));
      return value;
    } else {
      return static_cast<T>(bits);
    }
  }
  // A '\0'-terminated string.
  std::string ReadString(const char* what) {
    const std::size_t end = bytes_.find('\0', position_);
    if (end == std::string::npos) Require(bytes_.size() - position_ + 1, what);
    std::string value = bytes_.substr(position_, end - position_);
    position_ = end + 1;
    return value;
  }
  // A count of records of at least `min_record_bytes` each; more than the rest of the file can
  // hold throws (a corrupt count never reaches an allocation).
  std::uint64_t ReadCount(const char* what, std::size_t min_record_bytes) {
    const auto count = Read<std::uint64_t>(what);
    if (count > (bytes_.size() - position_) / min_record_bytes) {
      throw std::runtime_error(Where() + ": " + what + " " + std::to_string(count) +
                               " exceeds what the rest of the file holds (truncated or corrupt)");
    }
    return count;
  }
  void SetRecord(const std::string& record) { record_ = record; }
  std::string Where() const { return path_ + (record_.empty() ? "" : ", " + record_); }
  bool AtEnd() const { return position_ == bytes_.size(); }

 private:
  void Require(std::size_t size, const char* what) const {
    if (bytes_.size() - position_ < size) {
      throw std::runtime_error(Where() + ": the file ends while reading " + what + " (truncated)");
    }
  }

  const std::string& bytes_;
  const std::string& path_;
  std::size_t position_ = 0;
  std::string record_;
};

class ByteWriter {
 public:
  template <typename T>
  void Write(T value) {
    static_assert(std::is_arithmetic_v<T>);
    std::uint64_t bits = 0;
    if constexpr (std::is_floating_point_v<T>) {
      std::memcpy(&bits, &value, sizeof(T));
    } else {
      bits = static_cast<std::uint64_t>(value);
    }
    for (std::size_t i = 0; i < sizeof(T); ++i) {
      bytes_.push_back(static_cast<char>((bits >> (8 * i)) & 0xff));
    }
  }
  void WriteString(const std::string& value) { bytes_.append(value.c_str(), value.size() + 1); }
  std::string Take() { return std::move(bytes_); }

 private:
  std::string bytes_;
};

void CheckEnd(const ByteReader& reader) {
  if (!reader.AtEnd()) throw std::runtime_error(reader.Where() + ": unexpected bytes at the end");
}

void ParseCameras(const std::string& bytes, const std::string& path, Reconstruction* model) {
  ByteReader reader(bytes, path);
  const std::uint64_t count = reader.ReadCount("the number of cameras", 24);
  for (std::uint64_t i = 0; i < count; ++i) {
    reader.SetRecord("camera record " + std::to_string(i));
    ColmapCamera camera;
    camera.camera_id = reader.Read<std::uint32_t>("camera_id");
    reader.SetRecord("camera " + std::to_string(camera.camera_id));
    const CameraModel camera_model =
        ModelOfColmapId(reader.Read<std::int32_t>("model_id"), reader.Where());
    const auto width = reader.Read<std::uint64_t>("width");
    const auto height = reader.Read<std::uint64_t>("height");
    const auto max_size = static_cast<std::uint64_t>(std::numeric_limits<int>::max());
    if (width > max_size || height > max_size) {
      throw std::runtime_error(reader.Where() + ": width or height out of range");
    }
    camera.width = static_cast<int>(width);
    camera.height = static_cast<int>(height);
    std::vector<double> params(NumCameraParams(camera_model));
    for (double& param : params) param = reader.Read<double>("params");
    camera.camera = CameraFromColmap(CameraModelName(camera_model), params, reader.Where());
    if (!model->cameras.emplace(camera.camera_id, camera).second) {
      throw std::runtime_error(reader.Where() + " appears twice");
    }
  }
  CheckEnd(reader);
}

void ParseImages(const std::string& bytes, const std::string& path, Reconstruction* model) {
  ByteReader reader(bytes, path);
  const std::uint64_t count = reader.ReadCount("the number of images", 73);
  for (std::uint64_t i = 0; i < count; ++i) {
    reader.SetRecord("image record " + std::to_string(i));
    ColmapImage image;
    image.image_id = reader.Read<std::uint32_t>("image_id");
    reader.SetRecord("image " + std::to_string(image.image_id));
    double pose[7];
    for (double& value : pose) value = reader.Read<double>("the pose");
    image.cam_from_world.R = RotationOfQuaternion(pose, reader.Where());
    image.cam_from_world.t = Eigen::Vector3d(pose[4], pose[5], pose[6]);
    image.camera_id = reader.Read<std::uint32_t>("camera_id");
    image.name = reader.ReadString("the name");
    const std::uint64_t num_points2D = reader.ReadCount("num_points2D", 24);
    image.points2D.reserve(num_points2D);
    image.point3D_ids.reserve(num_points2D);
    for (std::uint64_t k = 0; k < num_points2D; ++k) {
      const double x = reader.Read<double>("points2D");
      const double y = reader.Read<double>("points2D");
      image.points2D.emplace_back(x, y);
      image.point3D_ids.push_back(reader.Read<std::uint64_t>("points2D"));
    }
    const ImageId image_id = image.image_id;
    if (!model->images.emplace(image_id, std::move(image)).second) {
      throw std::runtime_error(reader.Where() + " appears twice");
    }
  }
  CheckEnd(reader);
}

void ParsePoints3D(const std::string& bytes, const std::string& path, Reconstruction* model) {
  ByteReader reader(bytes, path);
  const std::uint64_t count = reader.ReadCount("the number of points3D", 51);
  for (std::uint64_t i = 0; i < count; ++i) {
    reader.SetRecord("point3D record " + std::to_string(i));
    const auto point3D_id = reader.Read<std::uint64_t>("point3D_id");
    reader.SetRecord("point3D " + std::to_string(point3D_id));
    ColmapPoint3D point;
    for (int k = 0; k < 3; ++k) point.xyz[k] = reader.Read<double>("xyz");
    for (int k = 0; k < 3; ++k) point.color[k] = reader.Read<std::uint8_t>("rgb");
    point.error = reader.Read<double>("error");
    const std::uint64_t track_length = reader.ReadCount("track_length", 8);
    point.track.resize(track_length);
    for (TrackElement& element : point.track) {
      element.image_id = reader.Read<std::uint32_t>("the track");
      element.point2D_idx = reader.Read<std::uint32_t>("the track");
    }
    if (!model->points3D.emplace(point3D_id, std::move(point)).second) {
      throw std::runtime_error(reader.Where() + " appears twice");
    }
  }
  CheckEnd(reader);
}

}  // namespace

Reconstruction ParseBinaryModel(const ModelFiles& contents, const ModelFiles& paths) {
  Reconstruction model;
  ParseCameras(contents.cameras, paths.cameras, &model);
  ParseImages(contents.images, paths.images, &model);
  ParsePoints3D(contents.points3D, paths.points3D, &model);
  return model;
}

ModelFiles FormatBinaryModel(const Reconstruction& reconstruction) {
  ModelFiles files;
  ByteWriter cameras;
  cameras.Write<std::uint64_t>(reconstruction.cameras.size());
  for (const auto& [camera_id, camera] : reconstruction.cameras) {
    cameras.Write<std::uint32_t>(camera_id);
    cameras.Write<std::int32_t>(ColmapModelId(camera.camera.model));
    cameras.Write<std::uint64_t>(camera.width);
    cameras.Write<std::uint64_t>(camera.height);
    for (int i = 0; i < NumCameraParams(camera.camera.model); ++i) {
      cameras.Write<double>(camera.camera.params[i]);
    }
  }
  files.cameras = cameras.Take();

  ByteWriter images;
  images.Write<std::uint64_t>(reconstruction.images.size());
  for (const auto& [image_id, image] : reconstruction.images) {
    images.Write<std::uint32_t>(image_id);
    double q_wxyz[4];
    QuaternionOfRotation(image.cam_from_world.R, q_wxyz);
    for (const double value : q_wxyz) images.Write<double>(value);
    for (int i = 0; i < 3; ++i) images.Write<double>(image.cam_from_world.t[i]);
    images.Write<std::uint32_t>(image.camera_id);
    images.WriteString(image.name);
    images.Write<std::uint64_t>(image.points2D.size());
    for (std::size_t i = 0; i < image.points2D.size(); ++i) {
      images.Write<double>(image.points2D[i].x());
      images.Write<double>(image.points2D[i].y());
      images.Write<std::uint64_t>(image.point3D_ids[i]);
    }
  }
  files.images = images.Take();

  ByteWriter points;
  points.Write<std::uint64_t>(reconstruction.points3D.size());
  for (const auto& [point3D_id, point] : reconstruction.points3D) {
    points.Write<std::uint64_t>(point3D_id);
    for (int i = 0; i < 3; ++i) points.Write<double>(point.xyz[i]);
    for (int i = 0; i < 3; ++i) points.Write<std::uint8_t>(point.color[i]);
    points.Write<double>(point.error);
    points.Write<std::uint64_t>(point.track.size());
    for (const TrackElement& element : point.track) {
      points.Write<std::uint32_t>(element.image_id);
      points.Write<std::uint32_t>(element.point2D_idx);
    }
  }
  files.points3D = points.Take();
  return files;
}

}  // namespace internal
}  // namespace colmap
}  // namespace trigrav
