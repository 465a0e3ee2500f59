#ifndef TRIGRAV_COLMAP_SRC_FILE_IO_H_
#define TRIGRAV_COLMAP_SRC_FILE_IO_H_

// Whole-file reads and durable writes. Errors throw std::runtime_error naming the path.

#include <functional>
#include <string>

namespace trigrav {
namespace colmap {
namespace internal {

bool FileExists(const std::string& path);
// The bytes of a file; throws std::runtime_error naming it when it cannot be read.
std::string ReadFileContents(const std::string& path);
// Creates `path` (which must not exist), writes `contents` and flushes it to the disk (fsync).
void WriteNewFileSynced(const std::string& path, const std::string& contents);
// Flushes a folder's entries (names created, renamed or removed in it) to the disk.
void SyncFolder(const std::string& folder);
// The folder a path is in ("." for a bare name).
std::string ParentFolder(const std::string& path);
// Creates "<prefix>XXXXXX" with six random letters and digits by `create(name)` (true: created;
// false with errno EEXIST: try another name) and returns the name; throws on another error.
std::string CreateUniquely(const std::string& prefix,
                           const std::function<bool(const char*)>& create);
// Replaces `path` by a file holding `contents`, all or nothing: the contents go to a new
// "<path>.tmp-XXXXXX" beside it, are flushed, then renamed onto `path` and the folder flushed.
// On an error the temporary file is removed and `path` is as it was.
void WriteFileAtomically(const std::string& path, const std::string& contents);

}  // namespace internal
}  // namespace colmap
}  // namespace trigrav

#endif  // TRIGRAV_COLMAP_SRC_FILE_IO_H_
