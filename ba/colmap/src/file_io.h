#ifndef TRIGRAV_COLMAP_SRC_FILE_IO_H_
#define TRIGRAV_COLMAP_SRC_FILE_IO_H_

// Whole-file reads and all-or-nothing writes of several files.

#include <string>
#include <utility>
#include <vector>

namespace trigrav {
namespace colmap {
namespace internal {

bool FileExists(const std::string& path);
// The bytes of a file; throws std::runtime_error naming it when it cannot be read.
std::string ReadFileContents(const std::string& path);
// Writes each (path, contents) to "<path>.tmp", and only when every one is complete renames them
// into place; on an error, removes the temporary files and throws std::runtime_error naming the
// file (the targets are left as they were, unless a rename itself fails).
void WriteFilesAtomically(const std::vector<std::pair<std::string, std::string>>& files);

}  // namespace internal
}  // namespace colmap
}  // namespace trigrav

#endif  // TRIGRAV_COLMAP_SRC_FILE_IO_H_
