// The tools' outputs: the model folder (examples/colmap/model_folder.h) leaves no folder behind
// when the write fails; the guard (examples/common/output_paths.h) relates paths as the file
// system resolves them. The tools themselves are run by output_guard_tests.cmake.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "common/output_paths.h"
#include "model_folder.h"

namespace trigrav::colmap_tools {
namespace {

namespace fs = std::filesystem;
using examples::IsWithin;
using examples::OutputConflict;
using examples::ToolPath;

std::string Scratch() {
  const fs::path folder =
      fs::path(::testing::TempDir()) /
      ("trigrav_tool_outputs_" +
       std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
  fs::remove_all(folder);
  fs::create_directories(folder);
  return folder.string();
}

colmap::Reconstruction OneImageModel(const std::string& name) {
  colmap::Reconstruction model;
  model.cameras[1] = {1, Camera::FromColmap("PINHOLE", {500, 500, 320, 240}), 640, 480};
  model.images[1].image_id = 1;
  model.images[1].name = name;
  model.images[1].camera_id = 1;
  return model;
}

TEST(ModelFolder, CreatesMissingParentsAndRemovesThemWhenTheWriteFails) {
  const std::string scratch = Scratch();
  WriteModelFolder(OneImageModel("a.png"), scratch + "/a/b/model", colmap::ModelFormat::kText);
  EXPECT_EQ(colmap::ReadModel(scratch + "/a/b/model").images.at(1).name, "a.png");
  // A name with a space cannot be written as text: no folder is left.
  EXPECT_THROW(WriteModelFolder(OneImageModel("a b.png"), scratch + "/c/d/model",
                                colmap::ModelFormat::kText),
               std::runtime_error);
  EXPECT_FALSE(fs::exists(scratch + "/c"));
  // A folder holding something else is not replaced.
  std::ofstream(scratch + "/a/b/model/notes.txt") << "mine";
  EXPECT_THROW(WriteModelFolder(OneImageModel("b.png"), scratch + "/a/b/model",
                                colmap::ModelFormat::kBinary),
               std::runtime_error);
  EXPECT_EQ(colmap::ReadModel(scratch + "/a/b/model").images.at(1).name, "a.png");
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
}  // namespace trigrav::colmap_tools
