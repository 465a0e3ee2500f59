// WriteModel writes a model as one set (ba/colmap/src/model_set.h): a crash or an I/O error at
// any step of the write leaves the old model or the new one, never a mix, and no temporary folder
// after an error; ReadModel rejects a folder whose files come from different writes; leftovers of
// killed writes disturb neither reads nor writes; a folder holding other files is not replaced.
//
// The steps are the write's fsync, rename and renameat2 calls: this test program defines these
// functions itself (they take the place of the C library's, for trigrav_colmap too), counts the
// calls and, at a chosen one, ends the process (_exit, in a child process) or fails with EIO.
#include <fcntl.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <filesystem>
#include <string>
#include <vector>

#include "colmap_test_utils.h"
#include "trigrav/colmap/model_io.h"

namespace {

enum class Injection { kNone, kCrash, kFail };
Injection injection = Injection::kNone;
int injection_step = 0;  // 1-based: the call that crashes or fails
int steps_done = 0;
constexpr int kCrashExitCode = 42;

// False (errno EIO) for the call chosen to fail; ends the process for the one chosen to crash.
bool Proceed() {
  if (injection == Injection::kNone) return true;
  if (++steps_done != injection_step) return true;
  if (injection == Injection::kCrash) ::_exit(kCrashExitCode);
  errno = EIO;
  return false;
}

}  // namespace

extern "C" int fsync(int fd) {
  if (!Proceed()) return -1;
  return static_cast<int>(::syscall(SYS_fsync, fd));
}

extern "C" int rename(const char* from, const char* to) {
  if (!Proceed()) return -1;
  return static_cast<int>(::syscall(SYS_renameat2, AT_FDCWD, from, AT_FDCWD, to, 0));
}

extern "C" int renameat2(
    int from_dir, const char* from, int to_dir, const char* to, unsigned int flags) {
  if (!Proceed()) return -1;
  return static_cast<int>(::syscall(SYS_renameat2, from_dir, from, to_dir, to, flags));
}

namespace trigrav {
namespace colmap {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::ThrowsMessage;
using testing_utils::ReadBytes;
using testing_utils::ScratchFolder;
using testing_utils::WriteText;

// A small model whose image 2 sits at `x`: two writes differ in images.* only, at equal sizes.
Reconstruction ModelWithImageAt(double x) {
  Reconstruction model;
  model.cameras[1] = {1, Camera::FromColmap("PINHOLE", {500, 500, 320, 240}), 640, 480};
  for (ImageId id : {1u, 2u}) {
    ColmapImage& image = model.images[id];
    image.image_id = id;
    image.name = std::to_string(id) + ".png";
    image.camera_id = 1;
    image.cam_from_world.t = Eigen::Vector3d(id == 2 ? x : 0.0, 0.0, 0.0);
    image.points2D = {Eigen::Vector2d(300, 200)};
    image.point3D_ids = {7};
  }
  model.points3D[7].xyz = Eigen::Vector3d(0.1, 0.2, 5.0);
  model.points3D[7].track = {{1, 0}, {2, 0}};
  return model;
}

// Image 2's x of the model in `folder`.
double ImageX(const std::string& folder) {
  return ReadModel(folder).images.at(2).cam_from_world.t.x();
}

// The entries of `parent` whose names start with `prefix`.
std::vector<std::string> EntriesStartingWith(const std::string& parent, const std::string& prefix) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(parent)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind(prefix, 0) == 0) names.push_back(name);
  }
  return names;
}

// Runs WriteModel(model, folder) in a child process that ends at the `step`-th call; true when
// it ended there, false when the write finished before.
bool WriteCrashingAt(const Reconstruction& model, const std::string& folder, int step) {
  const pid_t child = ::fork();
  if (child == 0) {
    injection = Injection::kCrash;
    injection_step = step;
    try {
      WriteModel(model, folder, ModelFormat::kBinary);
    } catch (...) {
      ::_exit(1);
    }
    ::_exit(0);
  }
  int status = 0;
  ::waitpid(child, &status, 0);
  EXPECT_TRUE(WIFEXITED(status));
  const int code = WEXITSTATUS(status);
  EXPECT_TRUE(code == 0 || code == kCrashExitCode) << "step " << step << ": exit " << code;
  return code == kCrashExitCode;
}

TEST(ModelWriteSet, ACrashAtAnyStepLeavesTheOldOrTheNewModel) {
  const std::string parent = ScratchFolder();
  const std::string folder = parent + "/model";
  int old_reads = 0, new_reads = 0, step = 1;
  for (; step < 30; ++step) {
    WriteModel(ModelWithImageAt(1.0), folder, ModelFormat::kBinary);  // the old model
    const bool crashed = WriteCrashingAt(ModelWithImageAt(2.0), folder, step);
    const double x = ImageX(folder);
    EXPECT_TRUE(x == 1.0 || x == 2.0) << "step " << step;
    (x == 1.0 ? old_reads : new_reads) += 1;
    // Only the model's files are in the folder, whatever the leftovers beside it.
    for (const auto& entry : fs::directory_iterator(folder)) {
      EXPECT_THAT(
          entry.path().filename().string(),
          ::testing::AnyOf("cameras.bin", "images.bin", "points3D.bin", "trigrav_model_set.txt"));
    }
    // The next write succeeds despite any leftover.
    WriteModel(ModelWithImageAt(3.0), folder, ModelFormat::kBinary);
    EXPECT_EQ(ImageX(folder), 3.0);
    if (!crashed) break;
  }
  EXPECT_GT(step, 5) << "fewer steps than files and folders to flush";
  EXPECT_LT(step, 30);
  EXPECT_GT(old_reads, 0);
  EXPECT_GT(new_reads, 0);
}

TEST(ModelWriteSet, ACrashBeforeTheFirstModelLeavesNoFolder) {
  const std::string parent = ScratchFolder();
  const std::string folder = parent + "/model";
  for (int step = 1; step < 30; ++step) {
    const bool crashed = WriteCrashingAt(ModelWithImageAt(2.0), folder, step);
    // No folder, or the complete new model.
    if (fs::exists(folder)) {
      EXPECT_EQ(ImageX(folder), 2.0) << "step " << step;
    }
    if (!crashed) break;
    fs::remove_all(folder);
  }
}

TEST(ModelWriteSet, AnErrorAtAnyStepLeavesTheOldOrNewModelAndNoTemporaryFolder) {
  const std::string parent = ScratchFolder();
  const std::string folder = parent + "/model";
  bool failed = true;
  for (int step = 1; failed && step < 30; ++step) {
    WriteModel(ModelWithImageAt(1.0), folder, ModelFormat::kBinary);
    injection = Injection::kFail;
    injection_step = step;
    steps_done = 0;
    try {
      WriteModel(ModelWithImageAt(2.0), folder, ModelFormat::kBinary);
      failed = false;
    } catch (const std::runtime_error& error) {
      EXPECT_THAT(error.what(), HasSubstr("Input/output error")) << "step " << step;
    }
    injection = Injection::kNone;
    const double x = ImageX(folder);
    EXPECT_TRUE(x == 1.0 || x == 2.0) << "step " << step;
    EXPECT_THAT(EntriesStartingWith(parent, "model"), ::testing::ElementsAre("model"))
        << "step " << step;
  }
  EXPECT_FALSE(failed) << "the write never finished";

  // Into a new folder: an error leaves no folder.
  const std::string fresh = parent + "/fresh";
  injection = Injection::kFail;
  injection_step = 1;
  steps_done = 0;
  EXPECT_THROW(WriteModel(ModelWithImageAt(2.0), fresh, ModelFormat::kText), std::runtime_error);
  injection = Injection::kNone;
  EXPECT_TRUE(EntriesStartingWith(parent, "fresh").empty());
}

TEST(ModelWriteSet, AMixOfTwoWritesIsRejected) {
  const std::string old_model = ScratchFolder("_old"), new_model = ScratchFolder("_new");
  WriteModel(ModelWithImageAt(1.0), old_model, ModelFormat::kBinary);
  WriteModel(ModelWithImageAt(2.0), new_model, ModelFormat::kBinary);
  ASSERT_EQ(ReadBytes(old_model + "/images.bin").size(),
            ReadBytes(new_model + "/images.bin").size());
  // The new images.bin beside the old cameras.bin and points3D.bin.
  WriteText(old_model + "/images.bin", ReadBytes(new_model + "/images.bin"));
  EXPECT_THAT([&] { ReadModel(old_model); },
              ThrowsMessage<std::runtime_error>(
                  HasSubstr("images.bin changed since the write of cameras.bin, points3D.bin")));
  // Another program rewrites the other two files too (with the same bytes, as COLMAP may): the
  // marker is stale and the model reads.
  for (const char* file : {"/cameras.bin", "/points3D.bin"}) {
    const std::string path = old_model + file;
    WriteText(path, ReadBytes(path));
    fs::last_write_time(path, fs::last_write_time(path) + std::chrono::seconds(1));
  }
  EXPECT_EQ(ImageX(old_model), 2.0);
}

TEST(ModelWriteSet, LeftoversDisturbNeitherReadsNorWrites) {
  const std::string parent = ScratchFolder();
  const std::string folder = parent + "/model";
  WriteModel(ModelWithImageAt(1.0), folder, ModelFormat::kBinary);
  // A killed write of this scheme (a sibling) and of the former one (".tmp" files inside).
  fs::create_directories(folder + ".tmp-abc123");
  WriteText(folder + ".tmp-abc123/images.bin", "partial");
  WriteText(folder + "/images.bin.tmp", "partial");
  EXPECT_EQ(ImageX(folder), 1.0);
  WriteModel(ModelWithImageAt(2.0), folder, ModelFormat::kBinary);
  EXPECT_EQ(ImageX(folder), 2.0);
  EXPECT_FALSE(fs::exists(folder + "/images.bin.tmp"));
  EXPECT_THAT(EntriesStartingWith(parent, "model"),
              ::testing::UnorderedElementsAre("model", "model.tmp-abc123"));
}

TEST(ModelWriteSet, AFolderHoldingOtherFilesIsNotReplaced) {
  const std::string parent = ScratchFolder();
  const std::string folder = parent + "/model";
  WriteModel(ModelWithImageAt(1.0), folder, ModelFormat::kBinary);
  WriteText(folder + "/notes.txt", "mine");
  EXPECT_THAT([&] { WriteModel(ModelWithImageAt(2.0), folder, ModelFormat::kBinary); },
              ThrowsMessage<std::runtime_error>(HasSubstr("holds notes.txt")));
  EXPECT_EQ(ImageX(folder), 1.0);
  EXPECT_EQ(ReadBytes(folder + "/notes.txt"), "mine");
  EXPECT_THAT(EntriesStartingWith(parent, "model"), ::testing::ElementsAre("model"));
  EXPECT_THROW(WriteModel(ModelWithImageAt(2.0), folder + "/notes.txt", ModelFormat::kBinary),
               std::runtime_error);

  // Through a symbolic link: the link stays and shows the new model.
  const std::string target = parent + "/target", link = parent + "/link";
  WriteModel(ModelWithImageAt(1.0), target, ModelFormat::kBinary);
  fs::create_directory_symlink(target, link);
  WriteModel(ModelWithImageAt(2.0), link, ModelFormat::kText);
  EXPECT_TRUE(fs::is_symlink(link));
  EXPECT_EQ(ImageX(link), 2.0);
  EXPECT_FALSE(fs::exists(target + "/images.bin"));
}

}  // namespace
}  // namespace colmap
}  // namespace trigrav
