#ifndef TRIGRAV_COLMAP_SRC_MODEL_FORMATS_H_
#define TRIGRAV_COLMAP_SRC_MODEL_FORMATS_H_

// The two file formats of a COLMAP sparse model (https://colmap.github.io/format.html), as the
// contents of its three files. Parsing throws std::runtime_error naming the file and line (text) or
// record (binary); it does not run Reconstruction::Check() (ReadModel does).

#include <string>

#include "trigrav/colmap/reconstruction.h"

namespace trigrav {
namespace colmap {
namespace internal {

// The three files of a model: their paths, or their contents.
struct ModelFiles {
  std::string cameras, images, points3D;
};

Reconstruction ParseTextModel(const ModelFiles& contents, const ModelFiles& paths);
// Throws std::runtime_error for an image name COLMAP's text format cannot hold (with whitespace).
ModelFiles FormatTextModel(const Reconstruction& reconstruction);

Reconstruction ParseBinaryModel(const ModelFiles& contents, const ModelFiles& paths);
ModelFiles FormatBinaryModel(const Reconstruction& reconstruction);

// The unit quaternion (w, x, y, z), w >= 0, of a rotation matrix, and the rotation matrix of a
// quaternion (normalised first; throws std::runtime_error with `where` for a zero or non-finite
// one).
void QuaternionOfRotation(const Eigen::Matrix3d& R, double q_wxyz[4]);
Eigen::Matrix3d RotationOfQuaternion(const double q_wxyz[4], const std::string& where);

}  // namespace internal
}  // namespace colmap
}  // namespace trigrav

#endif  // TRIGRAV_COLMAP_SRC_MODEL_FORMATS_H_
