#ifndef TRIGRAV_TESTS_SCENES_TYPICAL_CAMERAS_H_
#define TRIGRAV_TESTS_SCENES_TYPICAL_CAMERAS_H_

#include <stdexcept>

#include "trigrav/initializers/camera_model.h"

namespace trigrav {

// A 1280 x 960 camera of each model with distortion like real lenses (COLMAP's order).
inline Camera TypicalCamera(CameraModel model) {
  switch (model) {
    case CameraModel::kSimplePinhole:
      return Camera::FromColmap("SIMPLE_PINHOLE", {1000.0, 640.0, 480.0});
    case CameraModel::kPinhole:
      return Camera::FromColmap("PINHOLE", {1000.0, 1010.0, 640.0, 480.0});
    case CameraModel::kSimpleRadial:
      return Camera::FromColmap("SIMPLE_RADIAL", {1000.0, 640.0, 480.0, -0.1});
    case CameraModel::kRadial:
      return Camera::FromColmap("RADIAL", {1000.0, 640.0, 480.0, -0.2, 0.05});
    case CameraModel::kOpenCV:
      return Camera::FromColmap("OPENCV", {1000.0, 1010.0, 640.0, 480.0, -0.3, 0.1, 1e-3, -5e-4});
    case CameraModel::kOpenCVFisheye:
      return Camera::FromColmap("OPENCV_FISHEYE",
                                {600.0, 600.0, 640.0, 480.0, 0.05, -0.01, 0.002, -0.0005});
  }
  throw std::logic_error("unreachable");
}

}  // namespace trigrav

#endif  // TRIGRAV_TESTS_SCENES_TYPICAL_CAMERAS_H_
