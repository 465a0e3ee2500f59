#ifndef TRIGRAV_COLMAP_SRC_MODEL_SET_H_
#define TRIGRAV_COLMAP_SRC_MODEL_SET_H_

// A model folder written as one set, and the check that a folder's files are one set.
//
// The rule: a write never changes a file inside an existing model folder. It writes the new files
// and a marker listing them into a new sibling folder "<folder>.tmp-XXXXXX", flushes each file and
// that folder to the disk (fsync), then puts it in place with one rename: rename(2) when `folder`
// does not exist or is empty, else renameat2(RENAME_EXCHANGE), which swaps the two folders' names
// at once; then it flushes the parent folder and removes the old set (now the sibling). At every
// instant `folder` holds the complete old set or the complete new one: a crash leaves at most a
// "<folder>.tmp-XXXXXX" sibling, which no read looks at. A file system that cannot swap folders
// gets an error, not a weaker write, when `folder` already holds a model.
// The old folder is removed as a whole, so it must hold model files only (cameras, images,
// points3D in either format, the marker, and these names + ".tmp", left by older writers):
// anything else is refused before anything is written. A symbolic link to a folder stays in place
// and points at the new set.
//
// The marker, kModelSetMarker, lists each file of the set with its size, FNV-1a 64-bit hash and
// modification time. A folder in which a file has other bytes than listed while another is
// untouched (bytes and time as listed) mixes two writes (a file copied in, or a writer that
// renamed file by file was interrupted), and reading it fails. When no file is untouched, another
// program (COLMAP) has rewritten the whole model and the marker is stale: it is ignored.

#include <string>
#include <utility>
#include <vector>

namespace trigrav {
namespace colmap {
namespace internal {

inline constexpr char kModelSetMarker[] = "trigrav_model_set.txt";

// (file name, contents) of one file of a set.
using NamedFile = std::pair<std::string, std::string>;

// Writes `files` as the set in `folder` (see above); `folder` need not exist, its parent must.
// Throws std::runtime_error naming the folder or file; nothing changes in `folder` then, and no
// temporary folder is left.
void WriteModelSet(const std::string& folder, const std::vector<NamedFile>& files);

// Throws std::runtime_error when `folder` has a marker by which `files` (as read from it) mix two
// writes; nothing without a marker or with a stale one.
void CheckModelSet(const std::string& folder, const std::vector<NamedFile>& files);

}  // namespace internal
}  // namespace colmap
}  // namespace trigrav

#endif  // TRIGRAV_COLMAP_SRC_MODEL_SET_H_
