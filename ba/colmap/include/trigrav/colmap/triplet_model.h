#ifndef TRIGRAV_COLMAP_TRIPLET_MODEL_H_
#define TRIGRAV_COLMAP_TRIPLET_MODEL_H_

// The COLMAP sparse model of one initialised triplet (InitializeAndRefine on the tracks of
// ThreeViewTracks), the seed `colmap mapper --input_path` continues from. Write it with
// WriteModel or WriteModelCreatingParents (model_io.h).

#include <Eigen/Core>
#include <array>
#include <vector>

#include "trigrav/ba/initialize_and_refine.h"
#include "trigrav/colmap/database.h"
#include "trigrav/colmap/match_graph.h"
#include "trigrav/colmap/reconstruction.h"

namespace trigrav {
namespace colmap {

// The model of a triplet whose refinement succeeded (estimate.refinement.summary.success):
//  - cameras: every camera of the database (`cameras`);
//  - images: the triplet's three database images (id, name, camera), camera 1 being the world
//    (identity pose), cameras 2 and 3 at the refined cam2_from_cam1, cam3_from_cam1 (|C2| = 1);
//    each with all its database keypoints as points2D, in the database's order, so that COLMAP's
//    check of the keypoint count against the database passes;
//  - points3D: the refined points (ThreeViewRefinement::points_in_cam1) of the triangulated inlier
//    tracks, ids 1, 2, ..., each with its track of three observations, its mean residual norm as
//    the error and a grey colour; the keypoints of a point carry its id, the others none.
// Throws std::invalid_argument if the refinement did not succeed, a camera id is unknown or a
// track names a keypoint the image does not have.
Reconstruction TripletModel(const std::vector<ColmapCamera>& cameras,
                            const std::array<DatabaseImage, 3>& images,
                            const std::array<std::vector<Eigen::Vector2d>, 3>& keypoints,
                            const std::vector<ThreeViewTrack>& tracks,
                            const ThreeViewEstimate& estimate);

}  // namespace colmap
}  // namespace trigrav

#endif  // TRIGRAV_COLMAP_TRIPLET_MODEL_H_
