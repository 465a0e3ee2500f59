#ifndef TRIGRAV_EXAMPLES_KITTI_DESCRIPTOR_MATCHING_H_
#define TRIGRAV_EXAMPLES_KITTI_DESCRIPTOR_MATCHING_H_

// Nearest-neighbour matching of SIFT descriptors between two frames with Lowe's ratio test, a
// mutual (both-ways) check and a search window on the image displacement.

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
};

// b_index_of_a[i]: the feature of b matched to feature i of a, or -1.
std::vector<int> MatchFeatures(const FrameFeatures& a,
                               const FrameFeatures& b,
                               const MatchOptions& options);

}  // namespace trigrav::kitti

#endif  // TRIGRAV_EXAMPLES_KITTI_DESCRIPTOR_MATCHING_H_
