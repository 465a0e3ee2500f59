#ifndef TRIGRAV_EXAMPLES_KITTI_TRACK_MISTAKES_H_
#define TRIGRAV_EXAMPLES_KITTI_TRACK_MISTAKES_H_

// Mistakes users make in preparing real three-view tracks, applied to a triplet's observations
// (kitti_triplets --mistake): the mistakes matrix on real tracks (README, robustness). The ground
// truth stays the right answer.

#include <string>
#include <vector>

#include "trigrav/initializers/three_view_observations.h"

namespace trigrav::kitti {

enum class TrackMistake {
  kNone,
  kViews2And3Swapped,   // the pixels of views 2 and 3 swapped (gravity in order)
  kOtherIntrinsics,     // another camera's intrinsics: the README example's PINHOLE 500 500 320 240
  kHalfResolution,      // pixels of a half-resolution image, full-resolution intrinsics
  kRowColumn,           // pixels as (row, column)
  kFiveTracks,          // only the first 5 tracks
  kGravitySignCamera2,  // camera 2's gravity negated
};

// Names as --mistake takes them: none, views-2-3-swapped, other-intrinsics, half-resolution,
// row-column, five-tracks, gravity-sign-camera-2.
const std::vector<std::pair<TrackMistake, std::string>>& TrackMistakeNames();
bool ParseTrackMistake(const std::string& name, TrackMistake* mistake);

void ApplyTrackMistake(TrackMistake mistake, ThreeViewObservations* observations);

}  // namespace trigrav::kitti

#endif  // TRIGRAV_EXAMPLES_KITTI_TRACK_MISTAKES_H_
