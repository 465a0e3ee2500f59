#include "cache_file.h"

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

namespace trigrav::kitti {

bool WriteCacheFile(const std::string& path, const std::function<void(std::ostream&)>& write) {
  // Unique per process and thread.
  std::ostringstream suffix;
  suffix << ".tmp" << ::getpid() << "_" << std::this_thread::get_id();
  const std::string temporary = path + suffix.str();
  bool written = false;
  {
    std::ofstream file(temporary, std::ios::binary | std::ios::trunc);
    write(file);
    file.close();  // flushes: a full disk shows here
    written = static_cast<bool>(file);
  }
  std::error_code ec;
  if (written) std::filesystem::rename(temporary, path, ec);
  if (!written || ec) {
    std::remove(temporary.c_str());
    return false;
  }
  return true;
}

}  // namespace trigrav::kitti
