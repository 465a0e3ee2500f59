#include "cache_file.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

namespace trigrav::kitti {

bool WriteCacheFile(const std::string& path, const std::function<void(std::ostream&)>& write) {
  std::ostringstream suffix;
  suffix << ".tmp" << std::this_thread::get_id();
  const std::string temporary = path + suffix.str();
  {
    std::ofstream file(temporary, std::ios::binary | std::ios::trunc);
    write(file);
    if (!file) {
      std::remove(temporary.c_str());
      return false;
    }
  }
  std::error_code ec;
  std::filesystem::rename(temporary, path, ec);
  return !ec;
}

}  // namespace trigrav::kitti
