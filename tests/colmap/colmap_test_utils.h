#ifndef TRIGRAV_TESTS_COLMAP_COLMAP_TEST_UTILS_H_
#define TRIGRAV_TESTS_COLMAP_COLMAP_TEST_UTILS_H_

// Scratch folders and files for the trigrav::colmap tests.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace trigrav {
namespace colmap {
namespace testing_utils {

// A new empty folder under the test's temporary directory, named after the running test.
inline std::string ScratchFolder(const std::string& suffix = "") {
  const ::testing::TestInfo* test = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::filesystem::path folder =
      std::filesystem::path(::testing::TempDir()) /
      ("trigrav_colmap_" + std::string(test->test_suite_name()) + "_" + test->name() + suffix);
  std::filesystem::remove_all(folder);
  std::filesystem::create_directories(folder);
  return folder.string();
}

inline void WriteText(const std::string& path, const std::string& contents) {
  std::ofstream file(path, std::ios::binary | std::ios::trunc);
  file << contents;
}

inline std::string ReadBytes(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>());
}

}  // namespace testing_utils
}  // namespace colmap
}  // namespace trigrav

#endif  // TRIGRAV_TESTS_COLMAP_COLMAP_TEST_UTILS_H_
