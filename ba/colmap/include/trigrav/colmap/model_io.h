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
// is given), and for files that WriteModel's marker shows to come from different writes; the
// result passes Reconstruction::Check().
Reconstruction ReadModel(const std::string& folder);
Reconstruction ReadModel(const std::string& folder, ModelFormat format);

// Writes `reconstruction` (which must pass Check(); std::invalid_argument otherwise) as the model
// in `folder`, as one set: old model or new, never a mix, also after a crash. The three files
// and a marker file listing them (trigrav_model_set.txt: sizes, hashes, times) are written and
// flushed to the disk in a new sibling folder "<folder>.tmp-XXXXXX", which then takes the place
// of `folder` in one rename (an existing folder is swapped with it atomically, then removed).
// `folder` need not exist (its parent must); if it exists, it may hold model files only (either
// format, the marker, "*.tmp" of these names), since it is replaced as a whole: the other
// format's files go with it. Throws std::runtime_error naming the folder on an I/O error, a
// folder holding anything else, or a file system that cannot swap folders (renameat2
// RENAME_EXCHANGE); nothing has changed then and no temporary folder is left. A crash may leave
// a "<folder>.tmp-XXXXXX" sibling, which no read looks at.
void WriteModel(const Reconstruction& reconstruction,
                const std::string& folder,
                ModelFormat format);

// WriteModel into a `folder` whose missing parent folders are created first (top down) and removed
// again when the write fails, so that a failed write leaves no empty folder behind. Throws what
// WriteModel throws, or std::filesystem::filesystem_error when a parent folder cannot be created.
void WriteModelCreatingParents(const Reconstruction& reconstruction,
                               const std::string& folder,
                               ModelFormat format);

}  // namespace colmap
}  // namespace trigrav

#endif  // TRIGRAV_COLMAP_MODEL_IO_H_
