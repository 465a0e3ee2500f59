// trigrav::colmap model I/O: a hand-written COLMAP text model read field by field; synthetic
// models through text and binary round trips (binary bit-exact but for the rotation, which passes
// through a quaternion; 17-digit text; text and binary reads identical); every bad input gives a
// clear error and leaves nothing half-written.
#include "trigrav/colmap/model_io.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <filesystem>
#include <functional>
#include <limits>
#include <random>

#include "colmap_test_utils.h"

namespace trigrav {
namespace colmap {
namespace {

using ::testing::HasSubstr;
using ::testing::ThrowsMessage;
using testing_utils::ReadBytes;
using testing_utils::ScratchFolder;
using testing_utils::WriteText;

// COLMAP's own layout, with a camera and an image without 3D points.
constexpr char kCamerasTxt[] =
    "# Camera list with one line of data per camera:\n"
    "#   CAMERA_ID, MODEL, WIDTH, HEIGHT, PARAMS[]\n"
    "1 PINHOLE 1241 376 718.856 718.856 607.1928 185.2157\n"
    "2 SIMPLE_RADIAL 640 480 500 320 240 0.01\n";
// Image 2: a rotation of 0.1 rad about y, q = (cos 0.05, 0, sin 0.05, 0).
constexpr char kImagesTxt[] =
    "# Image list with two lines of data per image:\n"
    "1 1 0 0 0 0 0 0 1 000000.png\n"
    "100 200 -1 300.5 100.25 7\n"
    "\n"
    "2 0.99875026039496628 0 0.049979169270678331 0 -0.5 0 0.1 1 000001.png\n"
    "310 90 7\n"
    "3 1 0 0 0 1 2 3 2 other.jpg\n"
    "\n";
constexpr char kPoints3DTxt[] =
    "# 3D point list with one line of data per point:\n"
    "7 0.5 -0.25 4 128 64 32 0.5 1 1 2 0\n";

void WriteTextModel(const std::string& folder,
                    const std::string& cameras,
                    const std::string& images,
                    const std::string& points3D) {
  WriteText(folder + "/cameras.txt", cameras);
  WriteText(folder + "/images.txt", images);
  WriteText(folder + "/points3D.txt", points3D);
}

TEST(ModelIo, ReadsAHandWrittenTextModel) {
  const std::string folder = ScratchFolder();
  WriteTextModel(folder, kCamerasTxt, kImagesTxt, kPoints3DTxt);
  const Reconstruction model = ReadModel(folder);

  ASSERT_EQ(model.cameras.size(), 2u);
  const ColmapCamera& camera1 = model.cameras.at(1);
  EXPECT_EQ(camera1.camera.model, CameraModel::kPinhole);
  EXPECT_EQ(camera1.width, 1241);
  EXPECT_EQ(camera1.height, 376);
  EXPECT_EQ(camera1.camera.params[2], 607.1928);
  EXPECT_EQ(model.cameras.at(2).camera.model, CameraModel::kSimpleRadial);
  EXPECT_EQ(model.cameras.at(2).camera.params[3], 0.01);

  ASSERT_EQ(model.images.size(), 3u);
  const ColmapImage& image1 = model.images.at(1);
  EXPECT_EQ(image1.name, "000000.png");
  EXPECT_EQ(image1.camera_id, 1u);
  EXPECT_EQ(image1.cam_from_world.R, Eigen::Matrix3d::Identity());
  ASSERT_EQ(image1.points2D.size(), 2u);
  EXPECT_EQ(image1.points2D[1], Eigen::Vector2d(300.5, 100.25));
  EXPECT_EQ(image1.point3D_ids[0], kInvalidPoint3DId);
  EXPECT_EQ(image1.point3D_ids[1], 7u);
  const ColmapImage& image2 = model.images.at(2);
  const Eigen::Matrix3d R_expected = Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitY()).matrix();
  EXPECT_LT((image2.cam_from_world.R - R_expected).norm(), 1e-15);
  EXPECT_EQ(image2.cam_from_world.t, Eigen::Vector3d(-0.5, 0, 0.1));
  EXPECT_TRUE(model.images.at(3).points2D.empty());
  EXPECT_EQ(model.images.at(3).name, "other.jpg");

  ASSERT_EQ(model.points3D.size(), 1u);
  const ColmapPoint3D& point = model.points3D.at(7);
  EXPECT_EQ(point.xyz, Eigen::Vector3d(0.5, -0.25, 4));
  EXPECT_EQ(point.color, (std::array<std::uint8_t, 3>{128, 64, 32}));
  EXPECT_EQ(point.error, 0.5);
  ASSERT_EQ(point.track.size(), 2u);
  EXPECT_EQ(point.track[0].image_id, 1u);
  EXPECT_EQ(point.track[0].point2D_idx, 1u);
  EXPECT_EQ(point.track[1].image_id, 2u);
  EXPECT_EQ(point.track[1].point2D_idx, 0u);
}

// Two cameras of distorted models, four images, 40 points seen by two to four images, extra
// keypoints without a point; every double drawn at random (all 53 bits of mantissa in use).
Reconstruction SyntheticModel() {
  std::mt19937 rng(19);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  Reconstruction model;
  model.cameras[3] = {
      3,
      Camera::FromColmap("OPENCV", {700 + uniform(rng), 705 + uniform(rng), 320 + uniform(rng),
                                    240 + uniform(rng), 0.01 * uniform(rng), 0.001 * uniform(rng),
                                    1e-4 * uniform(rng), 1e-4 * uniform(rng)}),
      640, 480};
  model.cameras[8] = {8,
                      Camera::FromColmap("SIMPLE_RADIAL", {500 + uniform(rng), 300 + uniform(rng),
                                                           200 + uniform(rng), 0.1 * uniform(rng)}),
                      600, 400};
  for (ImageId image_id = 1; image_id <= 4; ++image_id) {
    ColmapImage& image = model.images[image_id * 10];
    image.image_id = image_id * 10;
    image.name = "seq/" + std::to_string(image_id) + ".png";
    image.camera_id = image_id == 4 ? 8 : 3;
    image.cam_from_world.R =
        Eigen::Quaterniond(uniform(rng), uniform(rng), uniform(rng), uniform(rng))
            .normalized()
            .toRotationMatrix();
    image.cam_from_world.t = Eigen::Vector3d(uniform(rng), uniform(rng), uniform(rng));
    for (int k = 0; k < 5; ++k) {
      image.points2D.emplace_back(300 + 300 * uniform(rng), 200 + 200 * uniform(rng));
      image.point3D_ids.push_back(kInvalidPoint3DId);
    }
  }
  for (Point3DId point3D_id = 100; point3D_id < 140; ++point3D_id) {
    ColmapPoint3D& point = model.points3D[point3D_id * 1000003];
    point.xyz = Eigen::Vector3d(uniform(rng), uniform(rng), 5 + uniform(rng));
    point.color = {static_cast<std::uint8_t>(point3D_id), 0, 255};
    point.error = 0.5 + uniform(rng);
    for (auto& [image_id, image] : model.images) {
      if ((point3D_id + image_id) % 3 == 0 && !point.track.empty()) continue;
      point.track.push_back({image_id, static_cast<std::uint32_t>(image.points2D.size())});
      image.points2D.emplace_back(300 + 300 * uniform(rng), 200 + 200 * uniform(rng));
      image.point3D_ids.push_back(point3D_id * 1000003);
    }
  }
  model.Check();
  return model;
}

// Equal models; rotations to `rotation_tolerance` (max entry), everything else bit-exact.
void ExpectEqualModels(const Reconstruction& a,
                       const Reconstruction& b,
                       double rotation_tolerance) {
  ASSERT_EQ(a.cameras.size(), b.cameras.size());
  for (const auto& [camera_id, camera] : a.cameras) {
    const ColmapCamera& other = b.cameras.at(camera_id);
    EXPECT_EQ(camera.camera_id, other.camera_id);
    EXPECT_EQ(camera.camera.model, other.camera.model);
    EXPECT_EQ(camera.camera.params, other.camera.params);
    EXPECT_EQ(camera.width, other.width);
    EXPECT_EQ(camera.height, other.height);
  }
  ASSERT_EQ(a.images.size(), b.images.size());
  for (const auto& [image_id, image] : a.images) {
    const ColmapImage& other = b.images.at(image_id);
    EXPECT_EQ(image.image_id, other.image_id);
    EXPECT_EQ(image.name, other.name);
    EXPECT_EQ(image.camera_id, other.camera_id);
    EXPECT_LE((image.cam_from_world.R - other.cam_from_world.R).cwiseAbs().maxCoeff(),
              rotation_tolerance);
    EXPECT_EQ(image.cam_from_world.t, other.cam_from_world.t);
    EXPECT_EQ(image.points2D, other.points2D);
    EXPECT_EQ(image.point3D_ids, other.point3D_ids);
  }
  ASSERT_EQ(a.points3D.size(), b.points3D.size());
  for (const auto& [point3D_id, point] : a.points3D) {
    const ColmapPoint3D& other = b.points3D.at(point3D_id);
    EXPECT_EQ(point.xyz, other.xyz);
    EXPECT_EQ(point.color, other.color);
    EXPECT_EQ(point.error, other.error);
    ASSERT_EQ(point.track.size(), other.track.size());
    for (std::size_t i = 0; i < point.track.size(); ++i) {
      EXPECT_EQ(point.track[i].image_id, other.track[i].image_id);
      EXPECT_EQ(point.track[i].point2D_idx, other.track[i].point2D_idx);
    }
  }
}

TEST(ModelIo, RoundTripsTextAndBinary) {
  const Reconstruction model = SyntheticModel();
  const std::string text = ScratchFolder("_text"), binary = ScratchFolder("_binary");
  WriteModel(model, text, ModelFormat::kText);
  WriteModel(model, binary, ModelFormat::kBinary);
  EXPECT_FALSE(std::filesystem::exists(text + "/cameras.bin"));
  EXPECT_FALSE(std::filesystem::exists(binary + "/cameras.txt"));
  const Reconstruction from_text = ReadModel(text);
  const Reconstruction from_binary = ReadModel(binary);
  // The rotation passes through a unit quaternion: a few units in the last place.
  ExpectEqualModels(model, from_text, 1e-15);
  ExpectEqualModels(model, from_binary, 1e-15);
  // 17 significant digits: the text holds every double of the binary exactly.
  ExpectEqualModels(from_text, from_binary, 0.0);

  // A model read back and written again converts between the formats: the binary written from
  // the text model is the binary written from the binary model, byte for byte.
  const std::string again_from_text = ScratchFolder("_again_text");
  const std::string again_from_binary = ScratchFolder("_again_binary");
  WriteModel(from_text, again_from_text, ModelFormat::kBinary);
  WriteModel(from_binary, again_from_binary, ModelFormat::kBinary);
  for (const char* file : {"/cameras.bin", "/images.bin", "/points3D.bin"}) {
    EXPECT_EQ(ReadBytes(again_from_text + file), ReadBytes(again_from_binary + file)) << file;
  }
  // Cameras and points carry no rotation: their binary files are identical to the first write.
  EXPECT_EQ(ReadBytes(again_from_binary + "/cameras.bin"), ReadBytes(binary + "/cameras.bin"));
  EXPECT_EQ(ReadBytes(again_from_binary + "/points3D.bin"), ReadBytes(binary + "/points3D.bin"));
}

TEST(ModelIo, ReadsTheFormatAskedFor) {
  const Reconstruction model = SyntheticModel();
  const std::string folder = ScratchFolder();
  WriteModel(model, folder, ModelFormat::kText);
  EXPECT_EQ(ReadModel(folder, ModelFormat::kText).points3D.size(), model.points3D.size());
  EXPECT_THAT([&] { ReadModel(folder, ModelFormat::kBinary); },
              ThrowsMessage<std::runtime_error>(HasSubstr("cameras.bin: no such file")));
}

// Writing one format removes the other's files: ReadModel(folder), which prefers .bin, reads the
// model written last.
TEST(ModelIo, WritingRemovesTheOtherFormat) {
  const Reconstruction model = SyntheticModel();
  Reconstruction renamed = model;
  renamed.images.begin()->second.name = "renamed.png";
  const std::string folder = ScratchFolder();
  WriteModel(model, folder, ModelFormat::kBinary);
  WriteModel(renamed, folder, ModelFormat::kText);
  for (const char* file : {"/cameras.bin", "/images.bin", "/points3D.bin"}) {
    EXPECT_FALSE(std::filesystem::exists(folder + file)) << file;
  }
  EXPECT_EQ(ReadModel(folder).images.begin()->second.name, "renamed.png");
  WriteModel(model, folder, ModelFormat::kBinary);
  for (const char* file : {"/cameras.txt", "/images.txt", "/points3D.txt"}) {
    EXPECT_FALSE(std::filesystem::exists(folder + file)) << file;
  }
  EXPECT_EQ(ReadModel(folder).images.begin()->second.name, model.images.begin()->second.name);
}

TEST(ModelIo, MissingFilesAndFolders) {
  const std::string folder = ScratchFolder();
  EXPECT_THAT([&] { ReadModel(folder + "/nowhere"); },
              ThrowsMessage<std::runtime_error>(HasSubstr("cameras.txt: no such file")));
  WriteText(folder + "/cameras.txt", kCamerasTxt);
  WriteText(folder + "/images.txt", kImagesTxt);
  EXPECT_THAT([&] { ReadModel(folder); },
              ThrowsMessage<std::runtime_error>(HasSubstr("points3D.txt: no such file")));
  EXPECT_THAT([&] { WriteModel(SyntheticModel(), folder + "/no/where", ModelFormat::kBinary); },
              ThrowsMessage<std::runtime_error>(HasSubstr("no/where: no such folder")));
  // A missing folder whose parent exists is created.
  WriteModel(SyntheticModel(), folder + "/new", ModelFormat::kBinary);
  EXPECT_EQ(ReadModel(folder + "/new").images.size(), 4u);
}

TEST(ModelIo, TruncatedBinaryFilesAreRejected) {
  const std::string folder = ScratchFolder();
  WriteModel(SyntheticModel(), folder, ModelFormat::kBinary);
  for (const char* file : {"/cameras.bin", "/images.bin", "/points3D.bin"}) {
    const std::string path = folder + file;
    const std::string bytes = ReadBytes(path);
    // Every cut within the counts and the first records, then every 11th byte.
    for (std::size_t size = 0; size < bytes.size(); size += size < 128 ? 1 : 11) {
      WriteText(path, bytes.substr(0, size));
      EXPECT_THAT([&] { ReadModel(folder); },
                  ThrowsMessage<std::runtime_error>(HasSubstr("truncated")))
          << file << " cut to " << size << " bytes";
    }
    WriteText(path, bytes + "x");
    EXPECT_THAT([&] { ReadModel(folder); },
                ThrowsMessage<std::runtime_error>(HasSubstr("unexpected bytes at the end")));
    WriteText(path, bytes);
  }
  EXPECT_EQ(ReadModel(folder).images.size(), 4u);
}

TEST(ModelIo, CorruptBinaryCountsDoNotAllocate) {
  const std::string folder = ScratchFolder();
  WriteModel(SyntheticModel(), folder, ModelFormat::kBinary);
  std::string bytes = ReadBytes(folder + "/points3D.bin");
  bytes[7] = '\x7f';  // the point count's most significant byte
  WriteText(folder + "/points3D.bin", bytes);
  EXPECT_THAT([&] { ReadModel(folder); },
              ThrowsMessage<std::runtime_error>(HasSubstr("exceeds what the rest of the file")));
}

TEST(ModelIo, UnsupportedCameraModelsAreNamed) {
  const std::string folder = ScratchFolder();
  WriteTextModel(folder, "1 FULL_OPENCV 640 480 500 500 320 240 0 0 0 0 0 0 0 0\n", "", "");
  EXPECT_THAT([&] { ReadModel(folder); },
              ThrowsMessage<std::runtime_error>(HasSubstr("\"FULL_OPENCV\"")));

  // cameras.bin of one camera: id 1, model id 6 (FULL_OPENCV, 12 parameters), 640 x 480.
  const auto binary_camera = [](std::int32_t model_id) {
    std::string bytes;
    const auto append = [&bytes](std::uint64_t value, int size) {
      for (int i = 0; i < size; ++i) bytes.push_back(static_cast<char>((value >> (8 * i)) & 255));
    };
    append(1, 8);
    append(1, 4);
    append(static_cast<std::uint32_t>(model_id), 4);
    append(640, 8);
    append(480, 8);
    bytes.append(12 * sizeof(double), '\0');
    return bytes;
  };
  const std::string binary = ScratchFolder("_binary");
  WriteText(binary + "/images.bin", std::string(8, '\0'));
  WriteText(binary + "/points3D.bin", std::string(8, '\0'));
  WriteText(binary + "/cameras.bin", binary_camera(6));
  EXPECT_THAT([&] { ReadModel(binary); },
              ThrowsMessage<std::runtime_error>(
                  HasSubstr("camera 1: COLMAP camera model FULL_OPENCV (id 6) is not supported")));
  WriteText(binary + "/cameras.bin", binary_camera(10));
  EXPECT_THAT([&] { ReadModel(binary); },
              ThrowsMessage<std::runtime_error>(HasSubstr("THIN_PRISM_FISHEYE (id 10)")));
  WriteText(binary + "/cameras.bin", binary_camera(-3));
  EXPECT_THAT([&] { ReadModel(binary); },
              ThrowsMessage<std::runtime_error>(HasSubstr("unknown COLMAP camera model id -3")));
}

// Each bad variant of the hand-written model, and the expected message.
TEST(ModelIo, MalformedTextIsRejectedWithFileAndLine) {
  const std::string folder = ScratchFolder();
  struct Case {
    std::string cameras, images, points3D, message;
  };
  const std::string image2 =
      "2 0.99875026039496628 0 0.049979169270678331 0 -0.5 0 0.1 1 000001.png\n";
  const std::vector<Case> cases = {
      {"1 PINHOLE 1241 376 718.856 718.856 607.1928\n", kImagesTxt, kPoints3DTxt,
       "cameras.txt:1: trigrav: Camera: PINHOLE takes 4 parameters, not 3"},
      {"1 PINHOLE 1241 376 718.856 abc 607.1928 185.2157\n", kImagesTxt, kPoints3DTxt,
       "cameras.txt:1: PARAMS[1] is not a number: \"abc\""},
      {"1 PINHOLE -5 376 718.856 718.856 607.1928 185.2157\n", kImagesTxt, kPoints3DTxt,
       "cameras.txt:1: WIDTH is not a non-negative integer"},
      {std::string(kCamerasTxt) + "1 PINHOLE 1 1 1 1 1 1\n", kImagesTxt, kPoints3DTxt,
       "cameras.txt:5: camera 1 appears twice"},
      {kCamerasTxt, "1 1 0 0 0 0 0 0 1 000000.png\n", kPoints3DTxt,
       "images.txt:1: the line of POINTS2D of image 1 is missing"},
      {kCamerasTxt, "1 1 0 0 0 0 0 0 1 000000.png\n100 200\n", "",
       "images.txt:2: expected POINTS2D[] as (X Y POINT3D_ID), got 2 numbers"},
      {kCamerasTxt, "1 0 0 0 0 0 0 0 1 000000.png\n\n", "",
       "images.txt:1: the quaternion is zero or not finite"},
      {kCamerasTxt, "1 1 0 0 0 nan 0 0 1 000000.png\n\n", "", "cam_from_world is not finite"},
      {kCamerasTxt, "1 1 0 0 0 0 0 0 1\n\n", "", "images.txt:1: expected IMAGE_ID QW QX"},
      {kCamerasTxt, "1 1 0 0 0 0 0 0 5 a.png\n\n", "", "image 1 refers to unknown camera 5"},
      {kCamerasTxt, kImagesTxt, "7 nan -0.25 4 128 64 32 0.5 1 1 2 0\n",
       "point3D 7: xyz is not finite"},
      {kCamerasTxt, kImagesTxt, "7 0.5 -0.25 4 300 64 32 0.5 1 1 2 0\n",
       "points3D.txt:1: R 300 is out of range (at most 255)"},
      {kCamerasTxt, kImagesTxt, "7 0.5 -0.25 4 128 64 32 0.5 1 1 2\n",
       "points3D.txt:1: expected POINT3D_ID X Y Z R G B ERROR TRACK[]"},
      // Inconsistent tracks: an element of an unknown image, one beyond the keypoints, one whose
      // keypoint has no point, a keypoint missing from the track, an element twice.
      {kCamerasTxt, kImagesTxt, "7 0.5 -0.25 4 128 64 32 0.5 1 1 9 0\n",
       "point3D 7: track element (image 9, point2D 0) refers to an unknown image"},
      {kCamerasTxt, kImagesTxt, "7 0.5 -0.25 4 128 64 32 0.5 1 1 2 1\n",
       "track element (image 2, point2D 1) refers to a point2D beyond the image's 1"},
      {kCamerasTxt, kImagesTxt, "7 0.5 -0.25 4 128 64 32 0.5 1 0 1 1 2 0\n",
       "track element (image 1, point2D 0): that point2D observes point3D -1"},
      {kCamerasTxt, kImagesTxt, "7 0.5 -0.25 4 128 64 32 0.5 1 1\n",
       "image 2: point2D 0 observes point3D 7 whose track does not contain it"},
      {kCamerasTxt, kImagesTxt, "7 0.5 -0.25 4 128 64 32 0.5 1 1 2 0 1 1\n",
       "track element (image 1, point2D 1) appears twice"},
      {kCamerasTxt, "1 1 0 0 0 0 0 0 1 000000.png\n100 200 8\n", "",
       "image 1: point2D 0 observes unknown point3D 8"},
      {kCamerasTxt, std::string(kImagesTxt) + image2 + "\n", kPoints3DTxt, "image 2 appears twice"},
  };
  for (const Case& bad : cases) {
    WriteTextModel(folder, bad.cameras, bad.images, bad.points3D);
    EXPECT_THAT([&] { ReadModel(folder); },
                ThrowsMessage<std::runtime_error>(HasSubstr(bad.message)))
        << bad.cameras << "---\n"
        << bad.images << "---\n"
        << bad.points3D;
  }
}

TEST(ModelIo, CheckNamesTheInconsistency) {
  const Reconstruction good = SyntheticModel();
  EXPECT_NO_THROW(good.Check());
  struct Case {
    std::function<void(Reconstruction*)> spoil;
    std::string message;
  };
  const std::vector<Case> cases = {
      {[](Reconstruction* m) { m->cameras.at(3).camera_id = 4; }, "camera 3 has camera_id 4"},
      {[](Reconstruction* m) { m->cameras.at(3).width = 0; }, "width and height must be positive"},
      {[](Reconstruction* m) { m->cameras.at(8).camera.params[0] = 0; }, "camera 8: trigrav:"},
      {[](Reconstruction* m) { m->images.at(10).name = ""; }, "image 10 has no name"},
      {[](Reconstruction* m) { m->images.at(10).name = "a\nb"; }, "line break"},
      {[](Reconstruction* m) { m->images.at(10).cam_from_world.R(0, 0) += 1e-6; },
       "cam_from_world.R is not a rotation"},
      {[](Reconstruction* m) { m->images.at(20).cam_from_world.t.x() = NAN; },
       "image 20: cam_from_world is not finite"},
      {[](Reconstruction* m) { m->images.at(20).point3D_ids.pop_back(); },
       "image 20: points2D has"},
      {[](Reconstruction* m) { m->images.at(20).points2D[0].y() = INFINITY; },
       "image 20: point2D 0 is not finite"},
      {[](Reconstruction* m) { m->points3D.begin()->second.error = NAN; }, "error is not finite"},
      {[](Reconstruction* m) { m->points3D[kInvalidPoint3DId]; }, "-1 is reserved"},
  };
  for (const Case& bad : cases) {
    Reconstruction model = good;
    bad.spoil(&model);
    EXPECT_THAT([&] { model.Check(); },
                ThrowsMessage<std::invalid_argument>(HasSubstr(bad.message)))
        << bad.message;
    EXPECT_THAT([&] { WriteModel(model, ScratchFolder(), ModelFormat::kBinary); },
                ThrowsMessage<std::invalid_argument>(HasSubstr(bad.message)));
  }
}

TEST(ModelIo, AFailedWriteLeavesTheModelAsItWas) {
  const std::string folder = ScratchFolder();
  const Reconstruction model = SyntheticModel();
  WriteModel(model, folder, ModelFormat::kText);
  const std::string images_before = ReadBytes(folder + "/images.txt");

  Reconstruction spaced = model;
  spaced.images.rbegin()->second.name = "with space.png";
  EXPECT_THAT([&] { WriteModel(spaced, folder, ModelFormat::kText); },
              ThrowsMessage<std::runtime_error>(HasSubstr("cannot hold a name with whitespace")));
  Reconstruction broken = model;
  broken.points3D.begin()->second.xyz.x() = NAN;
  EXPECT_THROW(WriteModel(broken, folder, ModelFormat::kText), std::invalid_argument);

  EXPECT_EQ(ReadBytes(folder + "/images.txt"), images_before);
  std::vector<std::string> files;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    files.push_back(entry.path().filename().string());
  }
  EXPECT_THAT(files, ::testing::UnorderedElementsAre("cameras.txt", "images.txt", "points3D.txt",
                                                     "trigrav_model_set.txt"));
  // Binary keeps names with spaces (they end at '\0').
  const std::string binary = ScratchFolder("_binary");
  WriteModel(spaced, binary, ModelFormat::kBinary);
  EXPECT_EQ(ReadModel(binary).images.rbegin()->second.name, "with space.png");
}

// WriteModelCreatingParents creates the missing folders above the model and removes them again
// when the write fails.
TEST(ModelIo, CreatingParentsLeavesNoFolderWhenTheWriteFails) {
  const std::string scratch = ScratchFolder();
  const auto one_image_model = [](const std::string& name) {
    Reconstruction model;
    model.cameras[1] = {1, Camera::FromColmap("PINHOLE", {500, 500, 320, 240}), 640, 480};
    model.images[1].image_id = 1;
    model.images[1].name = name;
    model.images[1].camera_id = 1;
    return model;
  };
  WriteModelCreatingParents(one_image_model("a.png"), scratch + "/a/b/model", ModelFormat::kText);
  EXPECT_EQ(ReadModel(scratch + "/a/b/model").images.at(1).name, "a.png");
  // A name with a space cannot be written as text: no folder is left.
  EXPECT_THROW(WriteModelCreatingParents(one_image_model("a b.png"), scratch + "/c/d/model",
                                         ModelFormat::kText),
               std::runtime_error);
  EXPECT_FALSE(std::filesystem::exists(scratch + "/c"));
  // A folder holding something else is not replaced.
  WriteText(scratch + "/a/b/model/notes.txt", "mine");
  EXPECT_THROW(WriteModelCreatingParents(one_image_model("b.png"), scratch + "/a/b/model",
                                         ModelFormat::kBinary),
               std::runtime_error);
  EXPECT_EQ(ReadModel(scratch + "/a/b/model").images.at(1).name, "a.png");
}

}  // namespace
}  // namespace colmap
}  // namespace trigrav
