#include "trigrav/colmap/model_io.h"

#include <Eigen/Geometry>
#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <system_error>
#include <vector>

#include "file_io.h"
#include "model_formats.h"
#include "model_set.h"

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

// The file names of a model in `format`.
internal::ModelFiles ModelFileNames(ModelFormat format) {
  const std::string extension = format == ModelFormat::kBinary ? ".bin" : ".txt";
  return {"cameras" + extension, "images" + extension, "points3D" + extension};
}

internal::ModelFiles ModelPaths(const std::string& folder, ModelFormat format) {
  const internal::ModelFiles names = ModelFileNames(format);
  return {folder + "/" + names.cameras, folder + "/" + names.images, folder + "/" + names.points3D};
}

// (name, contents) of the three files.
std::vector<internal::NamedFile> NamedFiles(const internal::ModelFiles& names,
                                            const internal::ModelFiles& contents) {
  return {{names.cameras, contents.cameras},
          {names.images, contents.images},
          {names.points3D, contents.points3D}};
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
  // After the parse, whose errors name the record: files that parse may still not belong together.
  internal::CheckModelSet(folder, NamedFiles(ModelFileNames(format), contents));
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
  const internal::ModelFiles contents = format == ModelFormat::kBinary
                                            ? internal::FormatBinaryModel(reconstruction)
                                            : internal::FormatTextModel(reconstruction);
  internal::WriteModelSet(folder, NamedFiles(ModelFileNames(format), contents));
}

void WriteModelCreatingParents(const Reconstruction& reconstruction,
                               const std::string& folder,
                               ModelFormat format) {
  namespace fs = std::filesystem;
  // The missing folders above `folder`, deepest first.
  std::vector<fs::path> missing;
  for (fs::path above = fs::path(folder).lexically_normal().parent_path();
       !above.empty() && !fs::exists(above) && above != above.parent_path();
       above = above.parent_path()) {
    missing.push_back(above);
  }
  std::vector<fs::path> created;
  try {
    for (auto above = missing.rbegin(); above != missing.rend(); ++above) {
      fs::create_directory(*above);
      created.push_back(*above);
    }
    WriteModel(reconstruction, folder, format);
  } catch (...) {
    std::error_code ignored;
    for (auto above = created.rbegin(); above != created.rend(); ++above) {
      fs::remove(*above, ignored);  // only an empty folder is removed
    }
    throw;
  }
}

}  // namespace colmap
}  // namespace trigrav
