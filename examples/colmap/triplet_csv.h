#ifndef TRIGRAV_EXAMPLES_COLMAP_TRIPLET_CSV_H_
#define TRIGRAV_EXAMPLES_COLMAP_TRIPLET_CSV_H_

// The per-triplet CSV of triplet_initializer and the verdict that decides which triplet seeds the
// COLMAP model.

#include <array>
#include <string>
#include <vector>

#include "trigrav/ba/initialize_and_refine.h"
#include "trigrav/colmap/database.h"

namespace trigrav::colmap_tools {

struct TripletResult {
  std::array<colmap::DatabaseImage, 3> images;
  int num_tracks = 0;
  bool estimated = false;  // InitializeAndRefine ran (enough tracks)
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

}  // namespace trigrav::colmap_tools

#endif  // TRIGRAV_EXAMPLES_COLMAP_TRIPLET_CSV_H_
