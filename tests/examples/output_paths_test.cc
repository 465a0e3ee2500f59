// The tools' output guard (examples/common/output_paths.h) relates paths as the file system
// resolves them. The tools themselves are run by output_guard_tests.cmake.

#include "common/output_paths.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace trigrav::examples {
namespace {

namespace fs = std::filesystem;

std::string Scratch() {
  const fs::path folder =
      fs::path(::testing::TempDir()) /
      ("trigrav_output_paths_" +
       std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
  fs::remove_all(folder);
  fs::create_directories(folder);
  return folder.string();
}

TEST(OutputPaths, RelatesPathsAsTheFileSystemResolvesThem) {
  const std::string scratch = Scratch();
  fs::create_directories(scratch + "/in/sub");
  std::ofstream(scratch + "/in/db.db") << "db";
  fs::create_hard_link(scratch + "/in/db.db", scratch + "/hard.db");
  fs::create_directory_symlink(scratch + "/in", scratch + "/link");
  EXPECT_TRUE(IsWithin(scratch + "/link/sub/new.csv", scratch + "/in"));
  EXPECT_TRUE(IsWithin(scratch + "/in/./sub/../db.db", scratch + "/in/"));
  EXPECT_FALSE(IsWithin(scratch + "/in2/x", scratch + "/in"));
  EXPECT_FALSE(IsWithin(scratch + "/in", scratch + "/in/sub"));

  const std::vector<ToolPath> inputs = {{"--database_path", scratch + "/in/db.db"}};
  EXPECT_EQ(OutputConflict(inputs, {{"--out", scratch + "/out.csv"}}), "");
  EXPECT_NE(OutputConflict(inputs, {{"--out", scratch + "/hard.db"}}), "");
  EXPECT_NE(OutputConflict(inputs, {{"--out", scratch + "/link/db.db"}}), "");
  EXPECT_NE(OutputConflict(inputs, {{"--out", scratch + "/link", ToolPath::kFolder}}), "");
  // Two outputs that are one path, though neither exists.
  EXPECT_NE(OutputConflict({}, {{"--a", scratch + "/x/y"}, {"--b", scratch + "/x/../x/y"}}), "");
}

}  // namespace
}  // namespace trigrav::examples
