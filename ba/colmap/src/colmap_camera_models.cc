#include "colmap_camera_models.h"

#include <array>
#include <stdexcept>

namespace trigrav {
namespace colmap {
namespace internal {
namespace {

// COLMAP 3.8's models by id; the first kCameraModels.size() are trigrav's.
constexpr std::array<const char*, 11> kColmapModelNames = {"SIMPLE_PINHOLE",
                                                           "PINHOLE",
                                                           "SIMPLE_RADIAL",
                                                           "RADIAL",
                                                           "OPENCV",
                                                           "OPENCV_FISHEYE",
                                                           "FULL_OPENCV",
                                                           "FOV",
                                                           "SIMPLE_RADIAL_FISHEYE",
                                                           "RADIAL_FISHEYE",
                                                           "THIN_PRISM_FISHEYE"};

}  // namespace

int ColmapModelId(CameraModel model) {
  for (std::size_t id = 0; id < kCameraModels.size(); ++id) {
    if (kCameraModels[id] == model) return static_cast<int>(id);
  }
  throw std::invalid_argument("trigrav::colmap: camera model outside the enum");
}

CameraModel ModelOfColmapId(long long model_id, const std::string& where) {
  if (model_id >= 0 && model_id < static_cast<long long>(kCameraModels.size())) {
    return kCameraModels[static_cast<std::size_t>(model_id)];
  }
  if (model_id >= 0 && model_id < static_cast<long long>(kColmapModelNames.size())) {
    throw std::runtime_error(where + ": COLMAP camera model " +
                             kColmapModelNames[static_cast<std::size_t>(model_id)] + " (id " +
                             std::to_string(model_id) +
                             ") is not supported (SIMPLE_PINHOLE, PINHOLE, SIMPLE_RADIAL, RADIAL, "
                             "OPENCV and OPENCV_FISHEYE are)");
  }
  throw std::runtime_error(where + ": unknown COLMAP camera model id " + std::to_string(model_id));
}

Camera CameraFromColmap(const std::string& model_name,
                        const std::vector<double>& params,
                        const std::string& where) {
  try {
    return Camera::FromColmap(model_name, params);
  } catch (const std::invalid_argument& error) {
    throw std::runtime_error(where + ": " + error.what());
  }
}

}  // namespace internal
}  // namespace colmap
}  // namespace trigrav
