#ifndef TRIGRAV_EXAMPLES_COLMAP_NVIEW_CONVERSION_H_
#define TRIGRAV_EXAMPLES_COLMAP_NVIEW_CONVERSION_H_

// A COLMAP model with the images' gravity as the input of trigrav's N-view bundle adjustment
// (trigrav/ba/nview_bundle_adjustment.h), and the refined poses and points back into the model.

#include <vector>

#include "trigrav/ba/nview_bundle_adjustment.h"
#include "trigrav/colmap/gravity_csv.h"
#include "trigrav/colmap/reconstruction.h"

namespace trigrav::colmap_tools {

// The N-view input and the COLMAP ids behind its indices.
struct NViewInput {
  NViewReconstruction reconstruction;
  std::vector<colmap::ImageId> image_ids;    // of reconstruction.images[i]
  std::vector<colmap::Point3DId> point_ids;  // of reconstruction.points_in_world[p]
};

// Cameras, images (increasing id) with their gravity by name, points (increasing id) and one
// observation per track element (the keypoint's pixel). Throws std::runtime_error listing the
// images without gravity (GravityOfImages).
NViewInput ToNView(const colmap::Reconstruction& model, const colmap::GravityByImageName& gravity);

// `model` with the poses and points of `refined` (ToNView's indices), each point's error the mean
// reprojection error of its track at the refined pose (pixels).
colmap::Reconstruction FromNView(const colmap::Reconstruction& model,
                                 const NViewInput& input,
                                 const NViewReconstruction& refined);

}  // namespace trigrav::colmap_tools

#endif  // TRIGRAV_EXAMPLES_COLMAP_NVIEW_CONVERSION_H_
