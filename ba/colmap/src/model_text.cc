// COLMAP's text model (https://colmap.github.io/format.html#text-format):
//   cameras.txt   CAMERA_ID MODEL WIDTH HEIGHT PARAMS[]
//   images.txt    IMAGE_ID QW QX QY QZ TX TY TZ CAMERA_ID NAME, then a line of POINTS2D[] as
//                 (X Y POINT3D_ID), POINT3D_ID -1 for none (the line may be empty)
//   points3D.txt  POINT3D_ID X Y Z R G B ERROR TRACK[] as (IMAGE_ID POINT2D_IDX)
// Lines starting with '#' and blank lines are skipped, except the line of points2D that follows
// each image line.
#include <cstdint>
#include <limits>
#include <locale>
#include <sstream>
#include <stdexcept>
#include <string_view>
#include <vector>

#include "colmap_camera_models.h"
#include "model_formats.h"
#include "text_io.h"

namespace trigrav {
namespace colmap {
namespace internal {
namespace {

constexpr std::uint64_t kMaxUint32 = std::numeric_limits<std::uint32_t>::max();

// Lines of a file with their 1-based numbers.
class LineReader {
 public:
  LineReader(const std::string& contents, const std::string& path)
      : contents_(contents), path_(path) {}

  // The next line, or false at the end.
  bool NextLine(std::string_view* line) {
    if (position_ >= contents_.size()) return false;
    std::size_t end = contents_.find('\n', position_);
    if (end == std::string::npos) end = contents_.size();
    *line = std::string_view(contents_).substr(position_, end - position_);
    position_ = end + 1;
    ++line_number_;
    return true;
  }
  // The next line that is neither blank nor a comment, or false at the end.
  bool NextDataLine(std::string_view* line) {
    while (NextLine(line)) {
      const std::string_view trimmed = Trim(*line);
      if (!trimmed.empty() && trimmed.front() != '#') return true;
    }
    return false;
  }
  std::string Where() const { return path_ + ":" + std::to_string(line_number_); }

 private:
  const std::string& contents_;
  const std::string& path_;
  std::size_t position_ = 0;
  int line_number_ = 0;
};

void ParseCameras(const std::string& contents, const std::string& path, Reconstruction* model) {
  LineReader reader(contents, path);
  std::string_view line;
  while (reader.NextDataLine(&line)) {
    const std::string where = reader.Where();
    const std::vector<std::string_view> tokens = SplitWhitespace(line);
    if (tokens.size() < 4) {
      throw std::runtime_error(where + ": expected CAMERA_ID MODEL WIDTH HEIGHT PARAMS[]");
    }
    ColmapCamera camera;
    camera.camera_id = ParseUintAtMost(tokens[0], kMaxUint32, "CAMERA_ID", where);
    const auto max_size = static_cast<std::uint64_t>(std::numeric_limits<int>::max());
    camera.width = static_cast<int>(ParseUintAtMost(tokens[2], max_size, "WIDTH", where));
    camera.height = static_cast<int>(ParseUintAtMost(tokens[3], max_size, "HEIGHT", where));
    std::vector<double> params;
    for (std::size_t i = 4; i < tokens.size(); ++i) {
      params.push_back(ParseDouble(tokens[i], "PARAMS[" + std::to_string(i - 4) + "]", where));
    }
    camera.camera = CameraFromColmap(std::string(tokens[1]), params, where);
    if (!model->cameras.emplace(camera.camera_id, camera).second) {
      throw std::runtime_error(where + ": camera " + std::to_string(camera.camera_id) +
                               " appears twice");
    }
  }
}

void ParsePoints2D(std::string_view line, const std::string& where, ColmapImage* image) {
  const std::vector<std::string_view> tokens = SplitWhitespace(line);
  if (tokens.size() % 3 != 0) {
    throw std::runtime_error(where + ": expected POINTS2D[] as (X Y POINT3D_ID), got " +
                             std::to_string(tokens.size()) + " numbers");
  }
  for (std::size_t i = 0; i < tokens.size(); i += 3) {
    const std::string what = "POINTS2D[" + std::to_string(i / 3) + "]";
    image->points2D.emplace_back(ParseDouble(tokens[i], what + " X", where),
                                 ParseDouble(tokens[i + 1], what + " Y", where));
    image->point3D_ids.push_back(tokens[i + 2] == "-1"
                                     ? kInvalidPoint3DId
                                     : ParseUint(tokens[i + 2], what + " POINT3D_ID", where));
  }
}

void ParseImages(const std::string& contents, const std::string& path, Reconstruction* model) {
  LineReader reader(contents, path);
  std::string_view line;
  while (reader.NextDataLine(&line)) {
    const std::string where = reader.Where();
    const std::vector<std::string_view> tokens = SplitWhitespace(line);
    if (tokens.size() < 10) {
      throw std::runtime_error(where + ": expected IMAGE_ID QW QX QY QZ TX TY TZ CAMERA_ID NAME");
    }
    ColmapImage image;
    image.image_id = ParseUintAtMost(tokens[0], kMaxUint32, "IMAGE_ID", where);
    static const char* const kPoseNames[7] = {"QW", "QX", "QY", "QZ", "TX", "TY", "TZ"};
    double pose[7];
    for (int i = 0; i < 7; ++i) pose[i] = ParseDouble(tokens[1 + i], kPoseNames[i], where);
    image.cam_from_world.R = RotationOfQuaternion(pose, where);
    image.cam_from_world.t = Eigen::Vector3d(pose[4], pose[5], pose[6]);
    image.camera_id = ParseUintAtMost(tokens[8], kMaxUint32, "CAMERA_ID", where);
    // The name is the rest of the line (COLMAP writes it last).
    image.name = std::string(Trim(line.substr(tokens[9].data() - line.data())));
    if (!reader.NextLine(&line)) {
      throw std::runtime_error(where + ": the line of POINTS2D of image " +
                               std::to_string(image.image_id) + " is missing");
    }
    ParsePoints2D(line, reader.Where(), &image);
    const ImageId image_id = image.image_id;
    if (!model->images.emplace(image_id, std::move(image)).second) {
      throw std::runtime_error(where + ": image " + std::to_string(image_id) + " appears twice");
    }
  }
}

void ParsePoints3D(const std::string& contents, const std::string& path, Reconstruction* model) {
  LineReader reader(contents, path);
  std::string_view line;
  while (reader.NextDataLine(&line)) {
    const std::string where = reader.Where();
    const std::vector<std::string_view> tokens = SplitWhitespace(line);
    if (tokens.size() < 8 || tokens.size() % 2 != 0) {
      throw std::runtime_error(
          where + ": expected POINT3D_ID X Y Z R G B ERROR TRACK[] as (IMAGE_ID POINT2D_IDX)");
    }
    const Point3DId point3D_id = ParseUint(tokens[0], "POINT3D_ID", where);
    ColmapPoint3D point;
    point.xyz =
        Eigen::Vector3d(ParseDouble(tokens[1], "X", where), ParseDouble(tokens[2], "Y", where),
                        ParseDouble(tokens[3], "Z", where));
    static const char* const kColorNames[3] = {"R", "G", "B"};
    for (int i = 0; i < 3; ++i) {
      point.color[i] =
          static_cast<std::uint8_t>(ParseUintAtMost(tokens[4 + i], 255, kColorNames[i], where));
    }
    point.error = ParseDouble(tokens[7], "ERROR", where);
    for (std::size_t i = 8; i < tokens.size(); i += 2) {
      const std::string what = "TRACK[" + std::to_string((i - 8) / 2) + "]";
      TrackElement element;
      element.image_id = ParseUintAtMost(tokens[i], kMaxUint32, what + " IMAGE_ID", where);
      element.point2D_idx =
          ParseUintAtMost(tokens[i + 1], kMaxUint32, what + " POINT2D_IDX", where);
      point.track.push_back(element);
    }
    if (!model->points3D.emplace(point3D_id, std::move(point)).second) {
      throw std::runtime_error(where + ": point3D " + std::to_string(point3D_id) +
                               " appears twice");
    }
  }
}

}  // namespace

Reconstruction ParseTextModel(const ModelFiles& contents, const ModelFiles& paths) {
  Reconstruction model;
  ParseCameras(contents.cameras, paths.cameras, &model);
  ParseImages(contents.images, paths.images, &model);
  ParsePoints3D(contents.points3D, paths.points3D, &model);
  return model;
}

ModelFiles FormatTextModel(const Reconstruction& reconstruction) {
  ModelFiles files;
  // The classic locale, whatever the global one: no digit grouping in the integers.
  std::ostringstream cameras, images, points;
  for (std::ostringstream* stream : {&cameras, &images, &points}) {
    stream->imbue(std::locale::classic());
  }
  cameras << "# Camera list with one line of data per camera:\n"
          << "#   CAMERA_ID, MODEL, WIDTH, HEIGHT, PARAMS[]\n"
          << "# Number of cameras: " << reconstruction.cameras.size() << "\n";
  for (const auto& [camera_id, camera] : reconstruction.cameras) {
    cameras << camera_id << ' ' << CameraModelName(camera.camera.model) << ' ' << camera.width
            << ' ' << camera.height;
    for (int i = 0; i < NumCameraParams(camera.camera.model); ++i) {
      cameras << ' ' << FormatDouble(camera.camera.params[i]);
    }
    cameras << '\n';
  }
  files.cameras = cameras.str();

  images << "# Image list with two lines of data per image:\n"
         << "#   IMAGE_ID, QW, QX, QY, QZ, TX, TY, TZ, CAMERA_ID, NAME\n"
         << "#   POINTS2D[] as (X, Y, POINT3D_ID)\n"
         << "# Number of images: " << reconstruction.images.size() << "\n";
  for (const auto& [image_id, image] : reconstruction.images) {
    if (image.name.find_first_of(" \t") != std::string::npos) {
      throw std::runtime_error("image " + std::to_string(image_id) + " \"" + image.name +
                               "\": COLMAP's text format cannot hold a name with whitespace");
    }
    double pose[7];
    QuaternionOfRotation(image.cam_from_world.R, pose);
    for (int i = 0; i < 3; ++i) pose[4 + i] = image.cam_from_world.t[i];
    images << image_id;
    for (const double value : pose) images << ' ' << FormatDouble(value);
    images << ' ' << image.camera_id << ' ' << image.name << '\n';
    for (std::size_t i = 0; i < image.points2D.size(); ++i) {
      if (i > 0) images << ' ';
      images << FormatDouble(image.points2D[i].x()) << ' ' << FormatDouble(image.points2D[i].y())
             << ' ';
      if (image.point3D_ids[i] == kInvalidPoint3DId) {
        images << -1;
      } else {
        images << image.point3D_ids[i];
      }
    }
    images << '\n';
  }
  files.images = images.str();

  points << "# 3D point list with one line of data per point:\n"
         << "#   POINT3D_ID, X, Y, Z, R, G, B, ERROR, TRACK[] as (IMAGE_ID, POINT2D_IDX)\n"
         << "# Number of points: " << reconstruction.points3D.size() << "\n";
  for (const auto& [point3D_id, point] : reconstruction.points3D) {
    points << point3D_id;
    for (int i = 0; i < 3; ++i) points << ' ' << FormatDouble(point.xyz[i]);
    for (int i = 0; i < 3; ++i) points << ' ' << static_cast<int>(point.color[i]);
    points << ' ' << FormatDouble(point.error);
    for (const TrackElement& element : point.track) {
      points << ' ' << element.image_id << ' ' << element.point2D_idx;
    }
    points << '\n';
  }
  files.points3D = points.str();
  return files;
}

}  // namespace internal
}  // namespace colmap
}  // namespace trigrav
