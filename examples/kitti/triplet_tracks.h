#ifndef TRIGRAV_EXAMPLES_KITTI_TRIPLET_TRACKS_H_
#define TRIGRAV_EXAMPLES_KITTI_TRIPLET_TRACKS_H_

// Three-view tracks of consecutive frames (i, i+1, i+2) chained from the pair matches (i, i+1) and
// (i+1, i+2), and the ThreeViewObservations a trigrav estimator takes.

#include <Eigen/Core>
#include <array>
#include <vector>

#include "sift_features.h"
#include "trigrav/initializers/three_view_observations.h"

namespace trigrav::kitti {

// Feature indices of one track in frames i, i+1, i+2.
using Track = std::array<int, 3>;

// Tracks (a, b, c) with b = b_of_a[a] >= 0 and c = c_of_b[b] >= 0 (match arrays as returned by
// MatchFeatures), in the order of a.
std::vector<Track> ChainTracks(const std::vector<int>& b_of_a, const std::vector<int>& c_of_b);

// Pixels of the tracks in the three frames, one camera for all three, and each frame's gravity
// (down, in its own camera frame).
ThreeViewObservations TrackObservations(const std::array<const FrameFeatures*, 3>& frames,
                                        const std::vector<Track>& tracks,
                                        const PinholeCamera& camera,
                                        const std::array<Eigen::Vector3d, 3>& gravity_in_cam);

}  // namespace trigrav::kitti

#endif  // TRIGRAV_EXAMPLES_KITTI_TRIPLET_TRACKS_H_
