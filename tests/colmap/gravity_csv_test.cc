// The gravity CSV: round trip, the accepted variations (comments, blank lines, CRLF, spaces), and
// every bad input with its file and line.
#include "trigrav/colmap/gravity_csv.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "colmap_test_utils.h"

namespace trigrav {
namespace colmap {
namespace {

using ::testing::HasSubstr;
using ::testing::ThrowsMessage;
using testing_utils::ScratchFolder;
using testing_utils::WriteText;

constexpr char kHeader[] = "image_name,gravity_x,gravity_y,gravity_z\n";

TEST(GravityCsv, RoundTripsEveryBit) {
  const GravityByImageName gravity = {
      {"000001.png", Eigen::Vector3d(0.1 / 3.0, 0.9994, -std::sqrt(2.0) / 100.0)},
      {"dir/000000.png", Eigen::Vector3d(1e-300, 2.5, -7.25e10)}};
  const std::string path = ScratchFolder() + "/gravity.csv";
  WriteGravityCsv(gravity, path);
  EXPECT_EQ(ReadGravityCsv(path), gravity);
}

TEST(GravityCsv, ReadsCommentsBlankLinesCrlfAndSpaces) {
  const std::string path = ScratchFolder() + "/gravity.csv";
  WriteText(path,
            "# gravity of KITTI 00\r\n\r\nimage_name,gravity_x,gravity_y,gravity_z\r\n"
            "000000.png,0.0123,0.9998,-0.0141\r\n# a comment\n  b.png , 0 , 1 , 0  \n");
  const GravityByImageName gravity = ReadGravityCsv(path);
  ASSERT_EQ(gravity.size(), 2u);
  EXPECT_EQ(gravity.at("000000.png"), Eigen::Vector3d(0.0123, 0.9998, -0.0141));
  EXPECT_EQ(gravity.at("b.png"), Eigen::Vector3d(0, 1, 0));
}

TEST(GravityCsv, BadFilesNameFileAndLine) {
  const std::string folder = ScratchFolder();
  const std::string path = folder + "/gravity.csv";
  EXPECT_THAT([&] { ReadGravityCsv(folder + "/missing.csv"); },
              ThrowsMessage<std::runtime_error>(HasSubstr("missing.csv: no such file")));
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"", "gravity.csv: empty (expected the header"},
      {"000000.png,0,1,0\n", "gravity.csv:1: expected the header"},
      {std::string(kHeader) + "a.png,nan,1,0\n", "gravity.csv:2: the gravity of a.png is zero"},
      {std::string(kHeader) + "a.png,0,inf,0\n", "gravity.csv:2: the gravity of a.png is zero"},
      {std::string(kHeader) + "a.png,0,0,0\n", "gravity.csv:2: the gravity of a.png is zero"},
      {std::string(kHeader) + "a.png,0,1\n", "gravity.csv:2: expected image_name,gravity_x"},
      {std::string(kHeader) + ",0,1,0\n", "gravity.csv:2: expected image_name,gravity_x"},
      {std::string(kHeader) + "a.png,0,1,0,4\n", "gravity.csv:2: expected image_name"},
      {std::string(kHeader) + "a.png,0,1x,0\n", "gravity.csv:2: gravity_y is not a number"},
      {std::string(kHeader) + "a.png,0,1,0\n\na.png,0,1,0\n", "gravity.csv:4: a.png appears twice"},
  };
  for (const auto& [contents, message] : cases) {
    WriteText(path, contents);
    EXPECT_THAT([&] { ReadGravityCsv(path); },
                ThrowsMessage<std::runtime_error>(HasSubstr(message)))
        << contents;
  }
}

TEST(GravityCsv, AFailedWriteWritesNothing) {
  const std::string folder = ScratchFolder();
  const std::string path = folder + "/gravity.csv";
  const std::vector<std::pair<GravityByImageName, std::string>> cases = {
      {{{"a.png", Eigen::Vector3d(0, NAN, 1)}}, "the gravity of a.png is zero or not finite"},
      {{{"a.png", Eigen::Vector3d::Zero()}}, "the gravity of a.png is zero or not finite"},
      {{{"a,b.png", Eigen::Vector3d::UnitY()}}, "image name \"a,b.png\" cannot be written"},
      {{{"#a.png", Eigen::Vector3d::UnitY()}}, "cannot be written"},
      {{{" a.png", Eigen::Vector3d::UnitY()}}, "cannot be written"},
  };
  for (const auto& [gravity, message] : cases) {
    EXPECT_THAT([&] { WriteGravityCsv(gravity, path); },
                ThrowsMessage<std::runtime_error>(HasSubstr(message)));
    EXPECT_TRUE(std::filesystem::is_empty(folder)) << message;
  }
  EXPECT_THAT(
      [&] {
        WriteGravityCsv({{"a.png", Eigen::Vector3d::UnitY()}}, folder + "/no/g.csv");
      },
      ThrowsMessage<std::runtime_error>(HasSubstr("cannot be written")));
}

TEST(GravityCsv, GravityOfImagesListsTheMissingNames) {
  const GravityByImageName gravity = {{"a.png", Eigen::Vector3d::UnitY()},
                                      {"b.png", Eigen::Vector3d(0, 2, 1)}};
  const std::vector<Eigen::Vector3d> found = GravityOfImages(gravity, {"b.png", "a.png"});
  ASSERT_EQ(found.size(), 2u);
  EXPECT_EQ(found[0], Eigen::Vector3d(0, 2, 1));
  EXPECT_EQ(found[1], Eigen::Vector3d::UnitY());
  EXPECT_THAT(
      [&] {
        GravityOfImages(gravity, {"a.png", "c.png"});
      },
      ThrowsMessage<std::runtime_error>(HasSubstr("no gravity for 1 of 2 images: c.png")));
  const std::vector<std::string> many = {"1", "2", "3", "4", "5", "6", "7", "a.png"};
  EXPECT_THAT([&] { GravityOfImages(gravity, many); },
              ThrowsMessage<std::runtime_error>(
                  HasSubstr("no gravity for 7 of 8 images: 1, 2, 3, 4, 5, ...")));
}

}  // namespace
}  // namespace colmap
}  // namespace trigrav
