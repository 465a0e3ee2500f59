#include "trigrav/initializers/camera_model.h"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace trigrav {
namespace {

struct ModelInfo {
  CameraModel model;
  const char* name;
  int num_params;
};

constexpr std::array<ModelInfo, 6> kModels = {{
    {CameraModel::kSimplePinhole, "SIMPLE_PINHOLE", 3},
    {CameraModel::kPinhole, "PINHOLE", 4},
    {CameraModel::kSimpleRadial, "SIMPLE_RADIAL", 4},
    {CameraModel::kRadial, "RADIAL", 5},
    {CameraModel::kOpenCV, "OPENCV", 8},
    {CameraModel::kOpenCVFisheye, "OPENCV_FISHEYE", 8},
}};

constexpr bool TableFollowsModelList() {
  for (std::size_t i = 0; i < kModels.size(); ++i) {
    if (kModels[i].model != kCameraModels[i]) return false;
  }
  return kModels.size() == kCameraModels.size();
}
static_assert(TableFollowsModelList(), "kModels must follow kCameraModels");

const ModelInfo& Info(CameraModel model) {
  for (const ModelInfo& info : kModels) {
    if (info.model == model) return info;
  }
  throw std::invalid_argument("trigrav: unknown CameraModel value");
}

// Newton's method stops when the distorted coordinates are this close to the target, in pixels.
constexpr double kUnprojectTolerancePx = 1e-11;
constexpr int kMaxUnprojectIterations = 100;

}  // namespace

bool PinholeCamera::IsValid() const {
  return fx > 0.0 && fy > 0.0 && std::isfinite(fx) && std::isfinite(fy) && std::isfinite(cx) &&
         std::isfinite(cy);
}

const char* CameraModelName(CameraModel model) { return Info(model).name; }

int NumCameraParams(CameraModel model) { return Info(model).num_params; }

bool ParseCameraModel(const std::string& name, CameraModel* model) {
  for (const ModelInfo& info : kModels) {
    if (name == info.name) {
      *model = info.model;
      return true;
    }
  }
  return false;
}

Camera Camera::FromColmap(const std::string& model_name, const std::vector<double>& params) {
  Camera camera;
  if (!ParseCameraModel(model_name, &camera.model)) {
    throw std::invalid_argument("trigrav: Camera: unknown camera model \"" + model_name +
                                "\" (SIMPLE_PINHOLE, PINHOLE, SIMPLE_RADIAL, RADIAL, OPENCV and "
                                "OPENCV_FISHEYE are supported)");
  }
  const int expected = NumCameraParams(camera.model);
  if (static_cast<int>(params.size()) != expected) {
    throw std::invalid_argument("trigrav: Camera: " + model_name + " takes " +
                                std::to_string(expected) + " parameters, not " +
                                std::to_string(params.size()));
  }
  std::copy(params.begin(), params.end(), camera.params.begin());
  camera.Check();
  return camera;
}

Camera Camera::FromPinhole(const PinholeCamera& pinhole) {
  Camera camera;
  camera.model = CameraModel::kPinhole;
  camera.params = {pinhole.fx, pinhole.fy, pinhole.cx, pinhole.cy, 0.0, 0.0, 0.0, 0.0};
  return camera;
}

void Camera::Check() const {
  const int n = NumCameraParams(model);  // throws for a value outside the enum
  for (int i = 0; i < n; ++i) {
    if (!std::isfinite(params[i])) {
      throw std::invalid_argument(std::string("trigrav: Camera: ") + CameraModelName(model) +
                                  " parameter " + std::to_string(i) + " is not finite");
    }
  }
  if (!(FocalX() > 0.0) || !(FocalY() > 0.0)) {
    throw std::invalid_argument(std::string("trigrav: Camera: ") + CameraModelName(model) +
                                " needs positive focal lengths");
  }
}

Eigen::Vector2d Camera::Project(const Eigen::Vector3d& point_in_cam) const {
  Eigen::Vector2d pixel;
  if (!Project(point_in_cam.data(), pixel.data())) {
    pixel.setConstant(std::numeric_limits<double>::quiet_NaN());
  }
  return pixel;
}

bool Camera::Unproject(const Eigen::Vector2d& pixel, Eigen::Vector3d* ray) const {
  if (!pixel.allFinite()) return false;
  const internal::CameraParamLayout layout = internal::ParamLayout(model);
  const double fx = params[layout.fx], fy = params[layout.fy];
  const Eigen::Vector2d target((pixel.x() - params[layout.cx]) / fx,
                               (pixel.y() - params[layout.cy]) / fy);
  if (IsPinhole()) {
    *ray = Eigen::Vector3d(target.x(), target.y(), 1.0);
    return true;
  }
  const double* distortion = params.data() + layout.distortion;
  auto distort = [&](const Eigen::Vector2d& x) {
    Eigen::Vector2d d;
    internal::Distort(model, distortion, x.x(), x.y(), &d.x(), &d.y());
    return d;
  };
  auto jacobian = [&](const Eigen::Vector2d& x) {
    Eigen::Matrix2d j;
    for (int c = 0; c < 2; ++c) {
      const double h = 1e-7 * std::max(1.0, std::abs(x[c]));
      Eigen::Vector2d plus = x, minus = x;
      plus[c] += h;
      minus[c] -= h;
      j.col(c) = (distort(plus) - distort(minus)) / (2.0 * h);
    }
    return j;
  };
  // Newton on distort(x) = target from x = target, with a central-difference Jacobian.
  Eigen::Vector2d x = target;
  bool converged = false;
  for (int iteration = 0; iteration < kMaxUnprojectIterations; ++iteration) {
    const Eigen::Vector2d residual = distort(x) - target;
    if (!residual.allFinite()) return false;
    if (std::abs(residual.x()) * fx <= kUnprojectTolerancePx &&
        std::abs(residual.y()) * fy <= kUnprojectTolerancePx) {
      converged = true;
      break;
    }
    const Eigen::Matrix2d j = jacobian(x);
    if (!(std::abs(j.determinant()) > 1e-12)) return false;  // at a fold of the distortion
    x -= j.inverse() * residual;
  }
  // Beyond the fold of a radial model Newton may converge to a second, folded-back solution: keep
  // only the branch through the image centre, where the distortion keeps the identity's
  // orientation (positive Jacobian determinant).
  if (!converged || !x.allFinite() || !(jacobian(x).determinant() > 0.0)) return false;
  *ray = Eigen::Vector3d(x.x(), x.y(), 1.0);
  return true;
}

}  // namespace trigrav
