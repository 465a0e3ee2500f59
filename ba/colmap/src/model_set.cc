#include "model_set.h"

#include <dirent.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cinttypes>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <sstream>
#include <stdexcept>

#include "file_io.h"

namespace trigrav {
namespace colmap {
namespace internal {
namespace {

std::runtime_error ErrnoError(const std::string& what) {
  return std::runtime_error(what + " (" + std::strerror(errno) + ")");
}

std::uint64_t Fnv1a64(const std::string& bytes) {
  std::uint64_t hash = 14695981039346656037ull;
  for (const char byte : bytes) {
    hash ^= static_cast<unsigned char>(byte);
    hash *= 1099511628211ull;
  }
  return hash;
}

// The modification time of a file in nanoseconds; throws when it cannot be read.
std::int64_t ModificationTime(const std::string& path) {
  struct stat info;
  if (::stat(path.c_str(), &info) != 0) throw ErrnoError(path + ": cannot be read");
  return static_cast<std::int64_t>(info.st_mtim.tv_sec) * 1000000000 + info.st_mtim.tv_nsec;
}

// A file of a set as the marker lists it.
struct Listing {
  std::uint64_t size = 0, hash = 0;
  std::int64_t mtime_ns = 0;
};

// The marker of `files` as written in `folder`.
std::string FormatMarker(const std::string& folder, const std::vector<NamedFile>& files) {
  std::string marker =
      "# trigrav::colmap::WriteModel: the files written together as one model "
      "(name, bytes, FNV-1a 64-bit hash, modification time in ns)\n";
  for (const auto& [name, contents] : files) {
    char hash[17];
    std::snprintf(hash, sizeof(hash), "%016" PRIx64, Fnv1a64(contents));
    marker += name + " " + std::to_string(contents.size()) + " " + hash + " " +
              std::to_string(ModificationTime(folder + "/" + name)) + "\n";
  }
  return marker;
}

std::map<std::string, Listing> ParseMarker(const std::string& path) {
  std::istringstream lines(ReadFileContents(path));
  std::map<std::string, Listing> listed;
  std::string line;
  for (int number = 1; std::getline(lines, line); ++number) {
    if (line.empty() || line.front() == '#') continue;
    std::istringstream fields(line);
    std::string name, hash, rest;
    Listing listing;
    if (!(fields >> name >> listing.size >> hash >> listing.mtime_ns) || (fields >> rest) ||
        hash.size() != 16 || hash.find_first_not_of("0123456789abcdef") != std::string::npos) {
      throw std::runtime_error(path + ":" + std::to_string(number) +
                               ": expected NAME BYTES HASH (16 hexadecimal digits) MTIME_NS");
    }
    listing.hash = std::stoull(hash, nullptr, 16);
    listed[name] = listing;
  }
  return listed;
}

// The names a model folder may hold: the files of both formats, the marker, and these + ".tmp".
bool IsModelEntry(const std::string& name) {
  std::string base = name;
  if (base.size() > 4 && base.compare(base.size() - 4, 4, ".tmp") == 0)
    base.resize(base.size() - 4);
  for (const char* file : {"cameras", "images", "points3D"}) {
    if (base == std::string(file) + ".bin" || base == std::string(file) + ".txt") return true;
  }
  return base == kModelSetMarker;
}

std::vector<std::string> FolderEntries(const std::string& folder) {
  DIR* directory = ::opendir(folder.c_str());
  if (directory == nullptr) throw ErrnoError(folder + ": cannot be listed");
  std::vector<std::string> names;
  while (const dirent* entry = ::readdir(directory)) {
    const std::string name = entry->d_name;
    if (name != "." && name != "..") names.push_back(name);
  }
  ::closedir(directory);
  return names;
}

// Removes a folder of model entries; what cannot be removed stays (a sibling no read looks at).
void RemoveModelFolder(const std::string& folder) {
  for (const std::string& name : FolderEntries(folder)) {
    if (IsModelEntry(name)) ::unlink((folder + "/" + name).c_str());
  }
  ::rmdir(folder.c_str());
}

std::string RealPath(const std::string& path) {
  char* real = ::realpath(path.c_str(), nullptr);
  if (real == nullptr) throw ErrnoError(path + ": cannot be resolved");
  std::string result = real;
  std::free(real);
  return result;
}

bool SameEntry(const struct stat& a, const struct stat& b) {
  return a.st_dev == b.st_dev && a.st_ino == b.st_ino;
}

}  // namespace

void WriteModelSet(const std::string& folder, const std::vector<NamedFile>& files) {
  // `target`: the folder's path with symbolic links resolved, where the new set goes.
  std::string target;
  struct stat info;
  bool has_entries = false;
  const bool exists = ::stat(folder.c_str(), &info) == 0;
  const int stat_errno = errno;
  if (exists) {
    if (!S_ISDIR(info.st_mode)) throw std::runtime_error(folder + ": not a folder");
    struct stat current;
    if (::stat(".", &current) == 0 && SameEntry(info, current)) {
      throw std::runtime_error(folder + ": the current folder cannot be replaced by a model");
    }
    target = RealPath(folder);
    for (const std::string& name : FolderEntries(target)) {
      if (!IsModelEntry(name)) {
        throw std::runtime_error(folder + ": holds " + name +
                                 ", which is not part of a COLMAP model; a model replaces its "
                                 "folder as a whole, so write it to a new or model-only folder");
      }
      has_entries = true;
    }
  } else {
    const std::string parent = ParentFolder(folder);
    struct stat parent_info;
    if (stat_errno != ENOENT || ::stat(parent.c_str(), &parent_info) != 0 ||
        !S_ISDIR(parent_info.st_mode)) {
      throw std::runtime_error(folder + ": no such folder, nor a parent folder to create it in");
    }
    std::string name = folder;
    while (name.size() > 1 && name.back() == '/') name.pop_back();
    target = RealPath(parent) + "/" + name.substr(name.rfind('/') + 1);
  }

  const std::string temporary =
      CreateUniquely(target + ".tmp-", [](const char* name) { return ::mkdir(name, 0777) == 0; });
  try {
    if (has_entries) ::chmod(temporary.c_str(), info.st_mode & 07777);  // the old folder's mode
    for (const auto& [name, contents] : files) {
      WriteNewFileSynced(temporary + "/" + name, contents);
    }
    WriteNewFileSynced(temporary + "/" + kModelSetMarker, FormatMarker(temporary, files));
    SyncFolder(temporary);
    if (!has_entries) {
      // Creates `target`, or replaces it when it is an empty folder.
      if (std::rename(temporary.c_str(), target.c_str()) != 0) {
        throw ErrnoError(folder + ": cannot be created");
      }
    } else if (::renameat2(AT_FDCWD, temporary.c_str(), AT_FDCWD, target.c_str(),
                           RENAME_EXCHANGE) != 0) {
      throw ErrnoError(folder + ": the file system cannot replace the model in one step " +
                       "(renameat2 RENAME_EXCHANGE); write to a new folder");
    }
  } catch (...) {
    RemoveModelFolder(temporary);
    throw;
  }
  // The old set, swapped to the temporary name, is removed also when the flush fails.
  try {
    SyncFolder(ParentFolder(target));
  } catch (...) {
    if (has_entries) RemoveModelFolder(temporary);
    throw;
  }
  if (has_entries) RemoveModelFolder(temporary);
}

void CheckModelSet(const std::string& folder, const std::vector<NamedFile>& files) {
  const std::string marker = folder + "/" + kModelSetMarker;
  if (!FileExists(marker)) return;
  const std::map<std::string, Listing> listed = ParseMarker(marker);
  // Untouched: as listed, modification time included. Different: other bytes than listed.
  std::string untouched, different;
  for (const auto& [name, contents] : files) {
    const auto entry = listed.find(name);
    const bool same_bytes = entry != listed.end() && entry->second.size == contents.size() &&
                            entry->second.hash == Fnv1a64(contents);
    if (!same_bytes) {
      different += (different.empty() ? "" : ", ") + name;
    } else if (entry->second.mtime_ns == ModificationTime(folder + "/" + name)) {
      untouched += (untouched.empty() ? "" : ", ") + name;
    }
  }
  if (!untouched.empty() && !different.empty()) {
    throw std::runtime_error(folder + ": " + different + " changed since the write of " +
                             untouched + " (by " + kModelSetMarker +
                             "): the folder mixes files of different writes");
  }
}

}  // namespace internal
}  // namespace colmap
}  // namespace trigrav
