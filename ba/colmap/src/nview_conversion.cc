#include "trigrav/colmap/nview_conversion.h"

#include <map>
#include <string>

namespace trigrav {
namespace colmap {

NViewInput ToNView(const Reconstruction& model, const GravityByImageName& gravity) {
  NViewInput input;
  NViewReconstruction& nview = input.reconstruction;
  std::map<CameraId, int> camera_index;
  for (const auto& [id, camera] : model.cameras) {
    camera_index[id] = static_cast<int>(nview.cameras.size());
    nview.cameras.push_back(camera.camera);
  }
  std::vector<std::string> names;
  for (const auto& [id, image] : model.images) names.push_back(image.name);
  const std::vector<Eigen::Vector3d> gravity_of_image = GravityOfImages(gravity, names);
  std::map<ImageId, int> image_index;
  for (const auto& [id, image] : model.images) {
    image_index[id] = static_cast<int>(nview.images.size());
    NViewImage& nview_image = nview.images.emplace_back();
    nview_image.camera_index = camera_index.at(image.camera_id);
    nview_image.cam_from_world = image.cam_from_world;
    nview_image.gravity_in_cam = gravity_of_image[image_index[id]];
    input.image_ids.push_back(id);
  }
  for (const auto& [id, point] : model.points3D) {
    const int point_index = static_cast<int>(nview.points_in_world.size());
    nview.points_in_world.push_back(point.xyz);
    input.point_ids.push_back(id);
    for (const TrackElement& element : point.track) {
      nview.observations.push_back(
          {image_index.at(element.image_id), point_index,
           model.images.at(element.image_id).points2D[element.point2D_idx]});
    }
  }
  return input;
}

Reconstruction FromNView(const Reconstruction& model,
                         const NViewInput& input,
                         const NViewReconstruction& refined) {
  Reconstruction result = model;
  for (std::size_t i = 0; i < input.image_ids.size(); ++i) {
    result.images.at(input.image_ids[i]).cam_from_world = refined.images[i].cam_from_world;
  }
  for (std::size_t p = 0; p < input.point_ids.size(); ++p) {
    ColmapPoint3D& point = result.points3D.at(input.point_ids[p]);
    point.xyz = refined.points_in_world[p];
    double sum = 0.0;
    int count = 0;
    for (const TrackElement& element : point.track) {
      const ColmapImage& image = result.images.at(element.image_id);
      const Eigen::Vector3d point_in_cam = image.cam_from_world.Apply(point.xyz);
      if (!(point_in_cam.z() > 0.0)) continue;
      const Camera& camera = result.cameras.at(image.camera_id).camera;
      sum += (camera.Project(point_in_cam) - image.points2D[element.point2D_idx]).norm();
      ++count;
    }
    point.error = count > 0 ? sum / count : -1.0;
  }
  return result;
}

}  // namespace colmap
}  // namespace trigrav
