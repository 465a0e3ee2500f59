#ifndef TRIGRAV_COLMAP_TRIPLET_CSV_H_
#define TRIGRAV_COLMAP_TRIPLET_CSV_H_

// The result of a triplet initialisation per triplet, the verdict that decides whether a triplet
// may seed a COLMAP model, and the per-triplet CSV (the file examples/colmap/triplet_initializer
// writes; its columns: examples/colmap/README.md, "The triplet CSV"). Poses are in the frame of
// the triplet's camera 1 (cam2_from_cam1, cam3_from_cam1, |C2| = 1), as ThreeViewEstimate gives
// them. Nothing is written or printed: the CSV is returned as text.

#include <array>
#include <string>
#include <vector>

#include "trigrav/ba/initialize_and_refine.h"
#include "trigrav/colmap/database.h"

namespace trigrav {
namespace colmap {

// One triplet: its database images (in the order of its tracks, image 1 the reference), its
// three-view tracks (ThreeViewTracks) and, when there were enough, InitializeAndRefine's estimate
// on them.
struct TripletResult {
  std::array<DatabaseImage, 3> images;
  int num_tracks = 0;
  bool estimated = false;  // InitializeAndRefine ran (enough tracks); `estimate` is its answer
  ThreeViewEstimate estimate;
};

// "trusted" when the estimate succeeded, its refinement succeeded and the refined pose has a
// covariance (a well-conditioned problem); else the first of "too_few_tracks", "failed",
// "unrefined", "no_covariance" that applies.
std::string TripletVerdict(const TripletResult& result);

// The CSV text of the results, one row each, after '#' lines documenting every column (README.md,
// "The triplet CSV"); the covariance columns follow the layout of `rotation_model`
// (three_view_covariance.h).
std::string FormatTripletCsv(const std::vector<TripletResult>& results,
                             ThreeViewBundleAdjustmentOptions::RotationModel rotation_model);

}  // namespace colmap
}  // namespace trigrav

#endif  // TRIGRAV_COLMAP_TRIPLET_CSV_H_
