#ifndef TRIGRAV_COLMAP_NVIEW_CONVERSION_H_
#define TRIGRAV_COLMAP_NVIEW_CONVERSION_H_

// A COLMAP model with the images' gravity as the input of trigrav's N-view bundle adjustment
// (trigrav/ba/nview_bundle_adjustment.h, RefineWithGravity), and the refined poses and points back
// into the model. Poses are COLMAP's cam_from_world, points in COLMAP's world frame, gravity in
// each image's camera frame (gravity_csv.h); nothing is read, written or printed.

#include <vector>

#include "trigrav/ba/nview_bundle_adjustment.h"
#include "trigrav/colmap/gravity_csv.h"
#include "trigrav/colmap/reconstruction.h"

namespace trigrav {
namespace colmap {

// The N-view input and the COLMAP ids behind its indices.
struct NViewInput {
  NViewReconstruction reconstruction;
  std::vector<ImageId> image_ids;    // of reconstruction.images[i]
  std::vector<Point3DId> point_ids;  // of reconstruction.points_in_world[p]
};

// Cameras, images (increasing id) with their gravity by name, points (increasing id) and one
// observation per track element (the keypoint's pixel). Throws std::runtime_error listing the
// images without gravity (GravityOfImages).
NViewInput ToNView(const Reconstruction& model, const GravityByImageName& gravity);

// `model` with the poses and points of `refined` (ToNView's indices), each point's error the mean
// reprojection error of its track at the refined pose (pixels).
Reconstruction FromNView(const Reconstruction& model,
                         const NViewInput& input,
                         const NViewReconstruction& refined);

}  // namespace colmap
}  // namespace trigrav

#endif  // TRIGRAV_COLMAP_NVIEW_CONVERSION_H_
