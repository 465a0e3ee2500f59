#include "staged_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <filesystem>
#include <stdexcept>
#include <system_error>

namespace trigrav::colmap_tools {
namespace {

// Writes all of `contents` to a new or truncated `path` and flushes it to the disk.
bool WriteSynced(const std::string& path, const std::string& contents) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (fd < 0) return false;
  std::size_t done = 0;
  while (done < contents.size()) {
    const ssize_t written = ::write(fd, contents.data() + done, contents.size() - done);
    if (written < 0 && errno == EINTR) continue;
    if (written <= 0) break;
    done += static_cast<std::size_t>(written);
  }
  const bool ok = done == contents.size() && ::fsync(fd) == 0;
  return ::close(fd) == 0 && ok;
}

}  // namespace

StagedFile::StagedFile(const std::string& path, const std::string& contents) : path_(path) {
  if (!WriteSynced(path_ + ".tmp", contents)) {
    std::error_code ignored;
    std::filesystem::remove(path_ + ".tmp", ignored);
    throw std::runtime_error("cannot write " + path_ + ".tmp");
  }
}

StagedFile::~StagedFile() {
  std::error_code ignored;
  if (!committed_) std::filesystem::remove(path_ + ".tmp", ignored);
}

void StagedFile::Commit() {
  std::error_code error;
  std::filesystem::rename(path_ + ".tmp", path_, error);
  if (error) throw std::runtime_error("cannot rename " + path_ + ".tmp: " + error.message());
  committed_ = true;
  // The rename itself reaches the disk with the folder's entries.
  const std::filesystem::path folder = std::filesystem::path(path_).parent_path();
  const int fd = ::open(folder.empty() ? "." : folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd >= 0) {
    ::fsync(fd);
    ::close(fd);
  }
}

}  // namespace trigrav::colmap_tools
