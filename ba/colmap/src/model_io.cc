#include "trigrav/colmap/model_io.h"

#include <sys/stat.h>

#include <Eigen/Geometry>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>

#include "file_io.h"
#include "model_formats.h"

namespace trigrav {
namespace colmap {
namespace internal {

void QuaternionOfRotation(const Eigen::Matrix3d& R, double q_wxyz[4]) {
  Eigen::Quaterniond q(R);
  q.normalize();
  const double sign = q.w() < 0.0 ? -1.0 : 1.0;
  q_wxyz[0] = sign * q.w();
  q_wxyz[1] = sign * q.x();
  q_wxyz[2] = sign * q.y();
  q_wxyz[3] = sign * q.z();
}

Eigen::Matrix3d RotationOfQuaternion(const double q_wxyz[4], const std::string& where) {
  const Eigen::Quaterniond q(q_wxyz[0], q_wxyz[1], q_wxyz[2], q_wxyz[3]);
  const double norm = q.norm();
  if (!std::isfinite(norm) || !(norm > 0.0)) {
    throw std::runtime_error(where + ": the quaternion is zero or not finite");
  }
  return q.normalized().toRotationMatrix();
}

}  // namespace internal

namespace {

internal::ModelFiles ModelPaths(const std::string& folder, ModelFormat format) {
  const std::string extension = format == ModelFormat::kBinary ? ".bin" : ".txt";
  return {folder + "/cameras" + extension, folder + "/images" + extension,
          folder + "/points3D" + extension};
}

}  // namespace

Reconstruction ReadModel(const std::string& folder) {
  const internal::ModelFiles binary = ModelPaths(folder, ModelFormat::kBinary);
  const bool is_binary = internal::FileExists(binary.cameras) &&
                         internal::FileExists(binary.images) &&
                         internal::FileExists(binary.points3D);
  return ReadModel(folder, is_binary ? ModelFormat::kBinary : ModelFormat::kText);
}

Reconstruction ReadModel(const std::string& folder, ModelFormat format) {
  const internal::ModelFiles paths = ModelPaths(folder, format);
  const internal::ModelFiles contents = {internal::ReadFileContents(paths.cameras),
                                         internal::ReadFileContents(paths.images),
                                         internal::ReadFileContents(paths.points3D)};
  Reconstruction reconstruction = format == ModelFormat::kBinary
                                      ? internal::ParseBinaryModel(contents, paths)
                                      : internal::ParseTextModel(contents, paths);
  try {
    reconstruction.Check();
  } catch (const std::invalid_argument& error) {
    throw std::runtime_error(folder + ": " + error.what());
  }
  return reconstruction;
}

void WriteModel(const Reconstruction& reconstruction,
                const std::string& folder,
                ModelFormat format) {
  reconstruction.Check();
  struct stat info;
  if (::stat(folder.c_str(), &info) != 0 || !S_ISDIR(info.st_mode)) {
    throw std::runtime_error(folder + ": no such folder");
  }
  const internal::ModelFiles contents = format == ModelFormat::kBinary
                                            ? internal::FormatBinaryModel(reconstruction)
                                            : internal::FormatTextModel(reconstruction);
  const internal::ModelFiles paths = ModelPaths(folder, format);
  internal::WriteFilesAtomically({{paths.cameras, contents.cameras},
                                  {paths.images, contents.images},
                                  {paths.points3D, contents.points3D}});
  // The other format's files would be a stale model (ReadModel(folder) prefers .bin).
  const internal::ModelFiles stale = ModelPaths(
      folder, format == ModelFormat::kBinary ? ModelFormat::kText : ModelFormat::kBinary);
  for (const std::string* path : {&stale.cameras, &stale.images, &stale.points3D}) {
    if (internal::FileExists(*path) && std::remove(path->c_str()) != 0) {
      throw std::runtime_error(*path +
                               ": the model is written, but this stale file cannot be "
                               "removed (" +
                               std::strerror(errno) + ")");
    }
  }
}

}  // namespace colmap
}  // namespace trigrav
