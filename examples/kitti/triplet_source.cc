#include "triplet_source.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <utility>

namespace trigrav::kitti {
namespace {

double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

TripletSource::TripletSource(const KittiSequence& sequence,
                             const std::vector<Eigen::Vector3d>& gravity_in_cam,
                             const std::string& cache_dir,
                             const SiftOptions& sift_options,
                             const MatchOptions& match_options)
    : sequence_(sequence),
      gravity_in_cam_(gravity_in_cam),
      cache_dir_(cache_dir),
      sift_options_(sift_options),
      match_options_(match_options) {}

std::string TripletSource::CacheFile(int frame, const std::string& tail) const {
  if (cache_dir_.empty()) return "";
  char name[32];
  std::snprintf(name, sizeof(name), "%06d_", frame);
  return (std::filesystem::path(cache_dir_) / (sequence_.sequence + "_" + name + tail)).string();
}

std::string TripletSource::CachePath(int frame) const {
  return CacheFile(frame, sift_options_.CacheTag() + ".sift");
}

std::string TripletSource::MatchCachePath(int frame) const {
  return CacheFile(frame, sift_options_.CacheTag() + "_" + match_options_.CacheTag() + ".match");
}

bool TripletSource::CacheFrame(int frame, bool* detected, std::string* error) const {
  FrameFeatures features;
  return Load(frame, &features, detected, error);
}

bool TripletSource::Load(int frame,
                         FrameFeatures* features,
                         bool* detected,
                         std::string* error) const {
  if (!cache_dir_.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(cache_dir_, ec);
    if (ec) {
      *error = "cannot create the feature cache folder " + cache_dir_ + ": " + ec.message();
      return false;
    }
  }
  return LoadOrDetectFeatures(sequence_.ImagePath(frame), CachePath(frame), sift_options_, features,
                              detected, error);
}

bool TripletSource::Get(int frame, TripletData* triplet, std::string* error) {
  triplet->frame = frame;
  auto start = std::chrono::steady_clock::now();
  std::vector<int> match01;
  bool detected = false;
  if (frame == window_frame_ + 1) {
    window_[0] = std::move(window_[1]);
    window_[1] = std::move(window_[2]);
    match01 = std::move(last_pair_match_);
    window_frame_ = -10;  // invalid until the new frame is in
    if (!Load(frame + 2, &window_[2], &detected, error)) return false;
    triplet->features_s = SecondsSince(start);
  } else {
    window_frame_ = -10;
    for (int k = 0; k < 3; ++k) {
      if (!Load(frame + k, &window_[k], &detected, error)) return false;
    }
    triplet->features_s = SecondsSince(start);
    start = std::chrono::steady_clock::now();
    if (!LoadOrMatchFeatures(window_[0], window_[1], match_options_, MatchCachePath(frame),
                             &match01, error)) {
      return false;
    }
    triplet->matching_s = SecondsSince(start);
  }
  start = std::chrono::steady_clock::now();
  if (!LoadOrMatchFeatures(window_[1], window_[2], match_options_, MatchCachePath(frame + 1),
                           &last_pair_match_, error)) {
    return false;
  }
  triplet->matching_s += SecondsSince(start);
  window_frame_ = frame;
  triplet->tracks = ChainTracks(match01, last_pair_match_);
  const int index = frame - sequence_.first_frame;
  triplet->observations = TrackObservations(
      {&window_[0], &window_[1], &window_[2]}, triplet->tracks, sequence_.camera,
      {gravity_in_cam_[index], gravity_in_cam_[index + 1], gravity_in_cam_[index + 2]});
  return true;
}

}  // namespace trigrav::kitti
