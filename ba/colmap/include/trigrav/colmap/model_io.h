#ifndef TRIGRAV_COLMAP_MODEL_IO_H_
#define TRIGRAV_COLMAP_MODEL_IO_H_

// Reading and writing COLMAP 3.8 sparse models: a folder with cameras, images and points3D, either
// as text (.txt) or binary (.bin), in COLMAP's documented formats
// (https://colmap.github.io/format.html). Own implementation of those formats.

#include <string>

#include "trigrav/colmap/reconstruction.h"

namespace trigrav {
namespace colmap {

enum class ModelFormat { kText, kBinary };

// Reads the model in `folder`: binary when cameras.bin, images.bin and points3D.bin exist, else
// text. Throws std::runtime_error naming the file and line (or record) for a missing file, a
// malformed or truncated record, or a COLMAP camera model trigrav does not have (its COLMAP name
// is given); the result passes Reconstruction::Check().
Reconstruction ReadModel(const std::string& folder);
Reconstruction ReadModel(const std::string& folder, ModelFormat format);

// Writes `reconstruction` (which must pass Check(); std::invalid_argument otherwise) into
// `folder`, which must exist. The three files are written under temporary names and renamed
// into place only when all three are complete, so a failure leaves no half-written model. Then
// the other format's three files, if in `folder`, are removed, so that ReadModel(folder) reads
// this model. Throws std::runtime_error on an I/O error.
void WriteModel(const Reconstruction& reconstruction,
                const std::string& folder,
                ModelFormat format);

}  // namespace colmap
}  // namespace trigrav

#endif  // TRIGRAV_COLMAP_MODEL_IO_H_
