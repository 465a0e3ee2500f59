#ifndef TRIGRAV_EXAMPLES_KITTI_TRIPLET_SOURCE_H_
#define TRIGRAV_EXAMPLES_KITTI_TRIPLET_SOURCE_H_

// Observations of the triplets (f, f+1, f+2) of a KITTI frame range: features and pair matches
// (both cached), and chained tracks. Consecutive triplets share two frames and one pair match,
// which a source keeps, so a worker walking through consecutive triplets detects / loads each frame
// and matches each pair once.

#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

#include "descriptor_matching.h"
#include "kitti_sequence.h"
#include "sift_features.h"
#include "trigrav/initializers/three_view_observations.h"
#include "triplet_tracks.h"

namespace trigrav::kitti {

struct TripletData {
  int frame = 0;  // first frame of the triplet
  ThreeViewObservations observations;
  std::vector<Track> tracks;
  double features_s = 0.0;  // loading / detecting the frames not shared with the previous triplet
  double matching_s = 0.0;  // the pair matches not shared with the previous triplet
};

class TripletSource {
 public:
  // gravity_in_cam: per frame of the sequence's range (ImuGravityInCameras). cache_dir: folder of
  // the feature and match cache files (created if missing); empty disables the cache. The
  // references must outlive the source.
  TripletSource(const KittiSequence& sequence,
                const std::vector<Eigen::Vector3d>& gravity_in_cam,
                const std::string& cache_dir,
                const SiftOptions& sift_options,
                const MatchOptions& match_options);

  // Triplet (frame, frame + 1, frame + 2), frame in [first_frame, last_frame - 2]. Returns false
  // with a message if an image cannot be read or the cache not written.
  bool Get(int frame, TripletData* triplet, std::string* error);

  // Makes sure a frame's features are in the cache (detecting them if not); *detected tells which.
  // Lets a caller fill the cache in parallel before walking through the triplets.
  bool CacheFrame(int frame, bool* detected, std::string* error) const;

  // Cache file of a frame's features ("" without a cache).
  std::string CachePath(int frame) const;

 private:
  // <cache_dir>/<sequence>_<frame, 6 digits>_<tail> ("" without a cache).
  std::string CacheFile(int frame, const std::string& tail) const;
  // Cache file of the match of frames (frame, frame + 1) ("" without a cache).
  std::string MatchCachePath(int frame) const;
  bool Load(int frame, FrameFeatures* features, bool* detected, std::string* error) const;

  const KittiSequence& sequence_;
  const std::vector<Eigen::Vector3d>& gravity_in_cam_;
  std::string cache_dir_;
  SiftOptions sift_options_;
  MatchOptions match_options_;
  // Sliding window of the last triplet: frames window_frame_ .. window_frame_ + 2 and the match of
  // its last pair.
  int window_frame_ = -10;
  std::array<FrameFeatures, 3> window_;
  std::vector<int> last_pair_match_;
};

}  // namespace trigrav::kitti

#endif  // TRIGRAV_EXAMPLES_KITTI_TRIPLET_SOURCE_H_
