#include "trigrav/colmap/triplet_model.h"

#include <stdexcept>
#include <string>

namespace trigrav {
namespace colmap {

Reconstruction TripletModel(const std::vector<ColmapCamera>& cameras,
                            const std::array<DatabaseImage, 3>& images,
                            const std::array<std::vector<Eigen::Vector2d>, 3>& keypoints,
                            const std::vector<ThreeViewTrack>& tracks,
                            const ThreeViewEstimate& estimate) {
  const ThreeViewRefinement& refinement = estimate.refinement;
  if (!refinement.summary.success) {
    throw std::invalid_argument("TripletModel: the triplet's refinement did not succeed");
  }
  Reconstruction model;
  for (const ColmapCamera& camera : cameras) model.cameras[camera.camera_id] = camera;
  const std::array<CameraPose, 3> cam_from_world = {CameraPose(), refinement.pose.cam2_from_cam1,
                                                    refinement.pose.cam3_from_cam1};
  for (int k = 0; k < 3; ++k) {
    if (model.cameras.count(images[k].camera_id) == 0) {
      throw std::invalid_argument("TripletModel: image " + images[k].name + " has camera id " +
                                  std::to_string(images[k].camera_id) +
                                  ", which the database does not have");
    }
    ColmapImage& image = model.images[images[k].image_id];
    image.image_id = images[k].image_id;
    image.name = images[k].name;
    image.camera_id = images[k].camera_id;
    image.cam_from_world = cam_from_world[k];
    image.points2D = keypoints[k];
    image.point3D_ids.assign(keypoints[k].size(), kInvalidPoint3DId);
  }
  for (std::size_t p = 0; p < refinement.triplets.size(); ++p) {
    const Point3DId point_id = p + 1;
    const ThreeViewTrack& track = tracks.at(refinement.triplets[p]);
    ColmapPoint3D& point = model.points3D[point_id];
    point.xyz = refinement.points_in_cam1[p];
    point.color = {128, 128, 128};
    point.error = refinement.residual_norms[p].mean();
    for (int k = 0; k < 3; ++k) {
      ColmapImage& image = model.images[images[k].image_id];
      if (track[k] >= image.points2D.size()) {
        throw std::invalid_argument("TripletModel: keypoint " + std::to_string(track[k]) +
                                    " of image " + image.name + " does not exist");
      }
      image.point3D_ids[track[k]] = point_id;
      point.track.push_back({image.image_id, track[k]});
    }
  }
  model.Check();
  return model;
}

}  // namespace colmap
}  // namespace trigrav
