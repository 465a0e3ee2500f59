#ifndef TRIGRAV_COLMAP_SRC_COLMAP_CAMERA_MODELS_H_
#define TRIGRAV_COLMAP_SRC_COLMAP_CAMERA_MODELS_H_

// COLMAP 3.8's camera model ids (src/base/camera_models.h there): 0 SIMPLE_PINHOLE, 1 PINHOLE,
// 2 SIMPLE_RADIAL, 3 RADIAL, 4 OPENCV, 5 OPENCV_FISHEYE are trigrav's CameraModel in the same
// order; 6 FULL_OPENCV, 7 FOV, 8 SIMPLE_RADIAL_FISHEYE, 9 RADIAL_FISHEYE, 10 THIN_PRISM_FISHEYE
// are COLMAP models trigrav does not have.

#include <string>
#include <vector>

#include "trigrav/initializers/camera_model.h"

namespace trigrav {
namespace colmap {
namespace internal {

int ColmapModelId(CameraModel model);
// The model of a COLMAP id; throws std::runtime_error "<where>: COLMAP camera model <NAME> (id N)
// is not supported (...)" for ids 6-10 and "unknown COLMAP camera model id N" for others.
CameraModel ModelOfColmapId(long long model_id, const std::string& where);
// Camera::FromColmap with its std::invalid_argument turned into std::runtime_error prefixed by
// `where` (a file and line, or a database row).
Camera CameraFromColmap(const std::string& model_name,
                        const std::vector<double>& params,
                        const std::string& where);

}  // namespace internal
}  // namespace colmap
}  // namespace trigrav

#endif  // TRIGRAV_COLMAP_SRC_COLMAP_CAMERA_MODELS_H_
