#include "file_io.h"

#include <sys/stat.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace trigrav {
namespace colmap {
namespace internal {

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

void WriteFilesAtomically(const std::vector<std::pair<std::string, std::string>>& files) {
  std::vector<std::string> temporaries;
  const auto remove_temporaries = [&temporaries] {
    for (const std::string& temporary : temporaries) std::remove(temporary.c_str());
  };
  for (const auto& [path, contents] : files) {
    const std::string temporary = path + ".tmp";
    temporaries.push_back(temporary);
    std::ofstream file(temporary, std::ios::binary | std::ios::trunc);
    file.write(contents.data(), static_cast<std::streamsize>(contents.size()));
    file.close();
    if (!file) {
      remove_temporaries();
      throw std::runtime_error(temporary + ": cannot be written");
    }
  }
  for (std::size_t i = 0; i < files.size(); ++i) {
    if (std::rename(temporaries[i].c_str(), files[i].first.c_str()) != 0) {
      const std::string reason = std::strerror(errno);
      remove_temporaries();
      throw std::runtime_error(files[i].first + ": cannot be renamed into place (" + reason + ")");
    }
  }
}

}  // namespace internal
}  // namespace colmap
}  // namespace trigrav
