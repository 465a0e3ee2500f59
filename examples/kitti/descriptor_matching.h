#ifndef TRIGRAV_EXAMPLES_KITTI_DESCRIPTOR_MATCHING_H_
#define TRIGRAV_EXAMPLES_KITTI_DESCRIPTOR_MATCHING_H_

// Nearest-neighbour matching of SIFT descriptors between two frames with Lowe's ratio test, a
// mutual (both-ways) check and a search window on the image displacement, with a per-pair cache
// file so that reruns skip matching.

#include <string>
#include <vector>

#include "sift_features.h"

namespace trigrav::kitti {

struct MatchOptions {
  // Lowe's ratio test on Euclidean descriptor distances: best < ratio * second best (both among the
  // candidates inside the window).
  double ratio = 0.8;
  // Candidates of a feature at (x, y) are those of the other frame within |dx| <= window_x_px and
  // |dy| <= window_y_px. Between consecutive KITTI frames (10 Hz, <= 1.5 m, <= 4 deg of yaw) points
  // move far less than the defaults; the window cuts matching time and removes distant look-alikes.
  double window_x_px = 250.0;
  double window_y_px = 120.0;
  // Keep a -> b only if a is also b's nearest neighbour among its candidates.
  bool mutual = true;

  // Part of the cache file name, so that other settings never read a stale match, e.g.
  // "r0.8_x250_y120_m1".
  std::string CacheTag() const;
};

// b_index_of_a[i]: the feature of b matched to feature i of a, or -1.
std::vector<int> MatchFeatures(const FrameFeatures& a,
                               const FrameFeatures& b,
                               const MatchOptions& options);

// Binary cache of a match: a header (magic, the two frames' feature counts and a hash of their
// pixels, so that re-detected features never read a stale match) then b_index_of_a. Read returns
// false for a missing, truncated or foreign file, other features or an index out of range; Write
// goes through a temporary file and a rename (cache_file.h).
bool ReadMatchCache(const std::string& path,
                    const FrameFeatures& a,
                    const FrameFeatures& b,
                    std::vector<int>* b_index_of_a);
bool WriteMatchCache(const std::string& path,
                     const FrameFeatures& a,
                     const FrameFeatures& b,
                     const std::vector<int>& b_index_of_a);

// MatchFeatures(a, b, options), from cache_path when it holds a valid cache of the pair, otherwise
// matched (and written to cache_path; an empty cache_path disables the cache). The path's name
// must tell the features' and the options' tags. Returns false with a message if the cache cannot
// be written.
bool LoadOrMatchFeatures(const FrameFeatures& a,
                         const FrameFeatures& b,
                         const MatchOptions& options,
                         const std::string& cache_path,
                         std::vector<int>* b_index_of_a,
                         std::string* error);

}  // namespace trigrav::kitti

#endif  // TRIGRAV_EXAMPLES_KITTI_DESCRIPTOR_MATCHING_H_
