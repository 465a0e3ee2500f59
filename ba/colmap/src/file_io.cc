#include "file_io.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <random>
#include <sstream>
#include <stdexcept>

namespace trigrav {
namespace colmap {
namespace internal {
namespace {

std::runtime_error ErrnoError(const std::string& path, const std::string& what) {
  return std::runtime_error(path + ": " + what + " (" + std::strerror(errno) + ")");
}

// Writes all of `contents` to `fd` and flushes it; false with errno set on an error.
bool WriteAllAndSync(int fd, const std::string& contents) {
  std::size_t done = 0;
  while (done < contents.size()) {
    const ssize_t written = ::write(fd, contents.data() + done, contents.size() - done);
    if (written < 0 && errno == EINTR) continue;
    if (written <= 0) return false;
    done += static_cast<std::size_t>(written);
  }
  return ::fsync(fd) == 0;
}

}  // namespace

bool FileExists(const std::string& path) {
  struct stat info;
  return ::stat(path.c_str(), &info) == 0 && S_ISREG(info.st_mode);
}

std::string ReadFileContents(const std::string& path) {
  if (!FileExists(path)) throw std::runtime_error(path + ": no such file");
  std::ifstream file(path, std::ios::binary);
  std::ostringstream contents;
  contents << file.rdbuf();
  if (!file) throw std::runtime_error(path + ": cannot be read");
  return contents.str();
}

void WriteNewFileSynced(const std::string& path, const std::string& contents) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
  if (fd < 0) throw ErrnoError(path, "cannot be written");
  const bool ok = WriteAllAndSync(fd, contents);
  const int saved_errno = errno;
  if (::close(fd) != 0 || !ok) {
    if (!ok) errno = saved_errno;
    throw ErrnoError(path, "cannot be written");
  }
}

void SyncFolder(const std::string& folder) {
  const int fd = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) throw ErrnoError(folder, "cannot be opened to flush it");
  const bool ok = ::fsync(fd) == 0;
  const int saved_errno = errno;
  ::close(fd);
  errno = saved_errno;
  if (!ok) throw ErrnoError(folder, "cannot be flushed");
}

std::string ParentFolder(const std::string& path) {
  std::string trimmed = path;
  while (trimmed.size() > 1 && trimmed.back() == '/') trimmed.pop_back();
  const std::size_t slash = trimmed.rfind('/');
  if (slash == std::string::npos) return ".";
  return slash == 0 ? "/" : trimmed.substr(0, slash);
}

std::string CreateUniquely(const std::string& prefix,
                           const std::function<bool(const char*)>& create) {
  static constexpr char kLetters[] = "abcdefghijklmnopqrstuvwxyz0123456789";
  static std::atomic<unsigned> counter{0};
  std::mt19937 random(std::random_device{}() ^ (static_cast<unsigned>(::getpid()) << 8) ^
                      counter.fetch_add(1));
  for (int attempt = 0; attempt < 100; ++attempt) {
    std::string name = prefix;
    for (int i = 0; i < 6; ++i) name += kLetters[random() % (sizeof(kLetters) - 1)];
    if (create(name.c_str())) return name;
    if (errno != EEXIST) break;
  }
  throw ErrnoError(prefix + "XXXXXX", "cannot be created");
}

void WriteFileAtomically(const std::string& path, const std::string& contents) {
  int fd = -1;
  std::string temporary;
  try {
    temporary = CreateUniquely(path + ".tmp-", [&fd](const char* name) {
      fd = ::open(name, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
      return fd >= 0;
    });
  } catch (const std::runtime_error&) {
    throw ErrnoError(path, "cannot be written");
  }
  bool ok = WriteAllAndSync(fd, contents);
  ok = ::close(fd) == 0 && ok;
  ok = ok && std::rename(temporary.c_str(), path.c_str()) == 0;
  if (!ok) {
    const int saved_errno = errno;
    std::remove(temporary.c_str());
    errno = saved_errno;
    throw ErrnoError(path, "cannot be written");
  }
  SyncFolder(ParentFolder(path));
}

}  // namespace internal
}  // namespace colmap
}  // namespace trigrav
