#include "track_mistakes.h"

#include <utility>

namespace trigrav::kitti {

const std::vector<std::pair<TrackMistake, std::string>>& TrackMistakeNames() {
  static const std::vector<std::pair<TrackMistake, std::string>> names = {
      {TrackMistake::kNone, "none"},
      {TrackMistake::kViews2And3Swapped, "views-2-3-swapped"},
      {TrackMistake::kOtherIntrinsics, "other-intrinsics"},
      {TrackMistake::kHalfResolution, "half-resolution"},
      {TrackMistake::kRowColumn, "row-column"},
      {TrackMistake::kFiveTracks, "five-tracks"},
      {TrackMistake::kGravitySignCamera2, "gravity-sign-camera-2"}};
  return names;
}

bool ParseTrackMistake(const std::string& name, TrackMistake* mistake) {
  for (const auto& [value, value_name] : TrackMistakeNames()) {
    if (value_name == name) {
      *mistake = value;
      return true;
    }
  }
  return false;
}

void ApplyTrackMistake(TrackMistake mistake, ThreeViewObservations* observations) {
  auto& pixels = observations->pixels;
  switch (mistake) {
    case TrackMistake::kNone:
      return;
    case TrackMistake::kViews2And3Swapped:
      std::swap(pixels[1], pixels[2]);
      return;
    case TrackMistake::kOtherIntrinsics:
      for (Camera& camera : observations->cameras) {
        camera = Camera::FromPinhole(PinholeCamera{500.0, 500.0, 320.0, 240.0});
      }
      return;
    case TrackMistake::kHalfResolution:
      for (auto& view : pixels) {
        for (Eigen::Vector2d& pixel : view) pixel *= 0.5;
      }
      return;
    case TrackMistake::kRowColumn:
      for (auto& view : pixels) {
        for (Eigen::Vector2d& pixel : view) pixel = Eigen::Vector2d(pixel.y(), pixel.x());
      }
      return;
    case TrackMistake::kFiveTracks:
      for (auto& view : pixels) view.resize(std::min<std::size_t>(view.size(), 5));
      return;
    case TrackMistake::kGravitySignCamera2:
      observations->gravity_in_cam[1] = -observations->gravity_in_cam[1];
      return;
  }
}

}  // namespace trigrav::kitti
