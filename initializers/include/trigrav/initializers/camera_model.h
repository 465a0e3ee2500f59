#ifndef TRIGRAV_INITIALIZERS_CAMERA_MODEL_H_
#define TRIGRAV_INITIALIZERS_CAMERA_MODEL_H_

// Camera models with COLMAP's names and parameter order, so that a line of COLMAP's cameras.txt
// ("MODEL WIDTH HEIGHT PARAMS...") maps one to one (Schoenberger and Frahm, "Structure-from-Motion
// Revisited", CVPR 2016; the models are defined in COLMAP's src/colmap/sensor/models.h). A point
// (X, Y, Z) in the camera frame, Z > 0, has normalised coordinates (u, v) = (X / Z, Y / Z); the
// model distorts them to (u_d, v_d) and maps those to pixels by the focal lengths and principal
// point. Distortion (u_d, v_d) = (u, v) + d(u, v), with r^2 = u^2 + v^2:
//   SIMPLE_PINHOLE  f, cx, cy                         d = 0, fx = fy = f
//   PINHOLE         fx, fy, cx, cy                    d = 0
//   SIMPLE_RADIAL   f, cx, cy, k                      d = (u, v) k r^2
//   RADIAL          f, cx, cy, k1, k2                 d = (u, v) (k1 r^2 + k2 r^4)
//   OPENCV          fx, fy, cx, cy, k1, k2, p1, p2    d = (u, v) (k1 r^2 + k2 r^4)
//                                                       + (2 p1 u v + p2 (r^2 + 2 u^2),
//                                                          2 p2 u v + p1 (r^2 + 2 v^2))
//   OPENCV_FISHEYE  fx, fy, cx, cy, k1, k2, k3, k4    (u_d, v_d) = (u, v) theta_d / r with
//                                                       theta = atan(r), theta_d = theta (1 +
//                                                       k1 theta^2 + k2 theta^4 + k3 theta^6 +
//                                                       k4 theta^8)
// Pixels follow COLMAP's convention: the centre of the top-left pixel is (0.5, 0.5). Derivations:
// derivations.md section 11.1 (models) and 11.2 (unprojection).

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace trigrav {

// Pinhole intrinsics without distortion: u = fx x/z + cx, v = fy y/z + cy. The default (all 0) is
// unset: ThreeViewObservations::Check() rejects it.
struct PinholeCamera {
  double fx = 0.0, fy = 0.0, cx = 0.0, cy = 0.0;

  // K^-1 [u v 1]^T: the ray through a pixel, z = 1.
  Eigen::Vector3d Ray(const Eigen::Vector2d& pixel) const {
    return Eigen::Vector3d((pixel.x() - cx) / fx, (pixel.y() - cy) / fy, 1.0);
  }
  // The pixel of a point (or direction) in camera coordinates, z != 0.
  Eigen::Vector2d Project(const Eigen::Vector3d& point_in_cam) const {
    return Eigen::Vector2d(fx * point_in_cam.x() / point_in_cam.z() + cx,
                           fy * point_in_cam.y() / point_in_cam.z() + cy);
  }
  // True when fx, fy are positive and finite and cx, cy finite.
  bool IsValid() const;
};

enum class CameraModel {
  kSimplePinhole,
  kPinhole,
  kSimpleRadial,
  kRadial,
  kOpenCV,
  kOpenCVFisheye,
};

// Every model, in the order above.
inline constexpr std::array<CameraModel, 6> kCameraModels = {
    CameraModel::kSimplePinhole, CameraModel::kPinhole, CameraModel::kSimpleRadial,
    CameraModel::kRadial,        CameraModel::kOpenCV,  CameraModel::kOpenCVFisheye};

// COLMAP's name ("SIMPLE_PINHOLE", ..., "OPENCV_FISHEYE"); throws std::invalid_argument for a value
// outside the enum.
const char* CameraModelName(CameraModel model);
// Inverse of CameraModelName; false (and *model untouched) for an unknown name.
bool ParseCameraModel(const std::string& name, CameraModel* model);
// Parameters of the model, in COLMAP's order (3, 4, 4, 5, 8, 8).
int NumCameraParams(CameraModel model);

// The largest parameter count of any model.
inline constexpr int kMaxCameraParams = 8;

// A camera of one of the models above. Fixed-size storage: copying one never allocates. The default
// (PINHOLE, all parameters 0) is unset: Check() rejects it.
struct Camera {
  CameraModel model = CameraModel::kPinhole;
  // COLMAP's parameters of `model`, the first NumCameraParams(model) entries; the rest are 0.
  std::array<double, kMaxCameraParams> params{};

  Camera() = default;
  Camera(CameraModel model, const std::array<double, kMaxCameraParams>& params)
      : model(model), params(params) {}
  // Implicit, so that a PinholeCamera can be given wherever a Camera is expected
  // (observations.cameras[k] = PinholeCamera{...}): the PINHOLE camera of the same intrinsics.
  Camera(const PinholeCamera& pinhole)  // NOLINT(google-explicit-constructor)
      : Camera(FromPinhole(pinhole)) {}

  // From COLMAP's model name and parameter list (a cameras.txt line without width and height).
  // Throws std::invalid_argument naming the problem: unknown model, wrong parameter count, or
  // parameters Check() rejects.
  static Camera FromColmap(const std::string& model_name, const std::vector<double>& params);
  // The PINHOLE camera of the given intrinsics.
  static Camera FromPinhole(const PinholeCamera& pinhole);

  // Throws std::invalid_argument naming the problem: a value outside the enum, non-finite
  // parameters, focal lengths that are not positive (0, the default, says "not set").
  void Check() const;
  // True when the model has no distortion (SIMPLE_PINHOLE, PINHOLE).
  bool IsPinhole() const;

  double FocalX() const;
  double FocalY() const;

  // Pixel of a point in the camera frame (templated for Ceres' automatic differentiation). Returns
  // false for a point not in front of the camera (Z <= 0); the pixel is then not written.
  template <typename T>
  bool Project(const T* point_in_cam, T* pixel) const;
  // Project() for doubles; the point must have Z > 0 (NaN pixel otherwise).
  Eigen::Vector2d Project(const Eigen::Vector3d& point_in_cam) const;

  // The ray (u, v, 1) whose projection is the pixel, by Newton's method on the distortion,
  // converged until the reprojection of the ray is within 1e-10 px of the pixel (pinhole models:
  // K^-1 [u v 1]^T directly, as PinholeCamera::Ray). Returns false if
  // the pixel is not finite or the iteration does not converge (a pixel outside the model's image
  // of the front hemisphere, e.g. beyond a radial model's fold).
  bool Unproject(const Eigen::Vector2d& pixel, Eigen::Vector3d* ray) const;
};

// ---------------------------------------------------------------------------------------------
// Implementation.

namespace internal {

// Distorted normalised coordinates of (u, v) under the model's distortion parameters.
template <typename T>
void Distort(CameraModel model, const double* distortion, const T& u, const T& v, T* u_d, T* v_d) {
  using std::atan;
  using std::sqrt;
  const T r2 = u * u + v * v;
  switch (model) {
    case CameraModel::kSimplePinhole:
    case CameraModel::kPinhole:
      *u_d = u;
      *v_d = v;
      return;
    case CameraModel::kSimpleRadial: {
      const T radial = T(distortion[0]) * r2;
      *u_d = u + u * radial;
      *v_d = v + v * radial;
      return;
    }
    case CameraModel::kRadial: {
      const T radial = T(distortion[0]) * r2 + T(distortion[1]) * r2 * r2;
      *u_d = u + u * radial;
      *v_d = v + v * radial;
      return;
    }
    case CameraModel::kOpenCV: {
      const T radial = T(distortion[0]) * r2 + T(distortion[1]) * r2 * r2;
      const T uv = u * v;
      const T p1(distortion[2]), p2(distortion[3]);
      *u_d = u + u * radial + T(2) * p1 * uv + p2 * (r2 + T(2) * u * u);
      *v_d = v + v * radial + T(2) * p2 * uv + p1 * (r2 + T(2) * v * v);
      return;
    }
    case CameraModel::kOpenCVFisheye: {
      // theta_d / r -> 1 as r -> 0; below the threshold the first-order value avoids 0 / 0.
      if (!(r2 > T(1e-30))) {
        *u_d = u;
        *v_d = v;
        return;
      }
      const T r = sqrt(r2);
      const T theta = atan(r);
      const T theta2 = theta * theta;
      const T theta_d =
          theta *
          (T(1) + theta2 * (T(distortion[0]) +
                            theta2 * (T(distortion[1]) +
                                      theta2 * (T(distortion[2]) + theta2 * T(distortion[3])))));
      *u_d = u * theta_d / r;
      *v_d = v * theta_d / r;
      return;
    }
  }
  *u_d = u;
  *v_d = v;
}

// Where the focal lengths, principal point and distortion parameters of a model sit in params.
struct CameraParamLayout {
  int fx, fy, cx, cy, distortion;
};
inline CameraParamLayout ParamLayout(CameraModel model) {
  switch (model) {
    case CameraModel::kSimplePinhole:
    case CameraModel::kSimpleRadial:
    case CameraModel::kRadial:
      return {0, 0, 1, 2, 3};
    case CameraModel::kPinhole:
    case CameraModel::kOpenCV:
    case CameraModel::kOpenCVFisheye:
      return {0, 1, 2, 3, 4};
  }
  return {0, 1, 2, 3, 4};
}

}  // namespace internal

// Inline: the bundle adjustment's analytic Jacobians ask once per observation and evaluation.
inline bool Camera::IsPinhole() const {
  return model == CameraModel::kSimplePinhole || model == CameraModel::kPinhole;
}

inline double Camera::FocalX() const { return params[internal::ParamLayout(model).fx]; }

inline double Camera::FocalY() const { return params[internal::ParamLayout(model).fy]; }

template <typename T>
bool Camera::Project(const T* point_in_cam, T* pixel) const {
  if (!(point_in_cam[2] > T(0))) return false;
  const internal::CameraParamLayout layout = internal::ParamLayout(model);
  if (model == CameraModel::kSimplePinhole || model == CameraModel::kPinhole) {
    // PinholeCamera::Project's arithmetic, to the last bit.
    pixel[0] = T(params[layout.fx]) * point_in_cam[0] / point_in_cam[2] + T(params[layout.cx]);
    pixel[1] = T(params[layout.fy]) * point_in_cam[1] / point_in_cam[2] + T(params[layout.cy]);
    return true;
  }
  const T u = point_in_cam[0] / point_in_cam[2];
  const T v = point_in_cam[1] / point_in_cam[2];
  T u_d, v_d;
  internal::Distort(model, params.data() + layout.distortion, u, v, &u_d, &v_d);
  pixel[0] = T(params[layout.fx]) * u_d + T(params[layout.cx]);
  pixel[1] = T(params[layout.fy]) * v_d + T(params[layout.cy]);
  return true;
}

}  // namespace trigrav

#endif  // TRIGRAV_INITIALIZERS_CAMERA_MODEL_H_
