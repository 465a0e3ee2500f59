#include "staged_file.h"

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <system_error>

namespace trigrav::colmap_tools {

StagedFile::StagedFile(const std::string& path, const std::string& contents) : path_(path) {
  std::ofstream out(path_ + ".tmp", std::ios::binary);
  out << contents;
  out.close();
  if (!out) {
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
}

}  // namespace trigrav::colmap_tools
