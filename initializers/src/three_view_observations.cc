#include "trigrav/initializers/three_view_observations.h"

#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

#include "input_checks.h"
#include "observation_rays.h"

namespace trigrav {

namespace {

[[noreturn]] void Fail(const std::string& what) {
  throw std::invalid_argument("trigrav: ThreeViewObservations: " + what);
}

std::string Entry(const char* name, int k, std::size_t n) {
  return std::string(name) + "[" + std::to_string(k) + "][" + std::to_string(n) + "]";
}

void CheckCamera(const Camera& camera, int k) {
  if (camera.FocalX() == 0.0 && camera.FocalY() == 0.0) {
    Fail(
        "camera " + std::to_string(k + 1) +
        " is not set (focal length 0): give each view's intrinsics, or bearings instead of pixels");
  }
  try {
    camera.Check();
  } catch (const std::invalid_argument& error) {
    Fail("camera " + std::to_string(k + 1) +
         " needs positive, finite focal lengths and finite parameters (" + error.what() + ")");
  }
}

void CheckGravityDirection(const Eigen::Vector3d& gravity, int k) {
  if (internal::IsUsableDirection(gravity)) return;
  const std::string unset = "not set (zero): give the direction of gravity (down) in camera " +
                            std::to_string(k + 1) + "'s own frame";
  Fail("gravity_in_cam[" + std::to_string(k) + "] is " +
       internal::DirectionProblem(gravity, unset));
}

// Unprojects the pixels into *rays (when not null), throwing for one that cannot be.
void CheckPixels(const Camera& camera,
                 const std::vector<Eigen::Vector2d>& pixels,
                 int k,
                 std::vector<Eigen::Vector3d>* rays) {
  for (std::size_t n = 0; n < pixels.size(); ++n) {
    if (!pixels[n].allFinite()) Fail(Entry("pixels", k, n) + " is not finite");
    // Pinhole rays have z = 1, so they are usable unless a finite pixel far from the principal
    // point (or a focal length near the smallest double) overflows the ray or its squared length
    // (found by tests/fuzz).
    Eigen::Vector3d ray;
    if (camera.Unproject(pixels[n], &ray) && internal::IsUsableDirection(ray)) {
      if (rays != nullptr) rays->push_back(ray);
      continue;
    }
    Fail(Entry("pixels", k, n) +
         (camera.IsPinhole()
              ? " is too far from the principal point for the focal length (its ray overflows)"
              : std::string(" cannot be unprojected by the ") + CameraModelName(camera.model) +
                    " camera (beyond the distortion's fold, or its ray overflows)"));
  }
}

void CheckBearings(const std::vector<Eigen::Vector3d>& bearings, int k) {
  for (std::size_t n = 0; n < bearings.size(); ++n) {
    if (internal::IsUsableDirection(bearings[n])) continue;
    Fail(Entry("bearings", k, n) + " is " + internal::DirectionProblem(bearings[n], "zero"));
  }
}

}  // namespace

Eigen::Vector3d ThreeViewObservations::Ray(int k, std::size_t n) const {
  if (HasBearings()) return bearings[k][n];
  Eigen::Vector3d ray;
  if (!cameras[k].Unproject(pixels[k][n], &ray)) {
    ray.setConstant(std::numeric_limits<double>::quiet_NaN());
  }
  return ray;
}

void ThreeViewObservations::Check() const { internal::CheckAndUnproject(*this, nullptr); }

namespace internal {

void CheckAndUnproject(const ThreeViewObservations& observations,
                       std::array<std::vector<Eigen::Vector3d>, 3>* rays) {
  const auto& [cameras, gravity_in_cam, pixels, bearings] = observations;
  const bool bearing_input = observations.HasBearings();
  for (int k = 0; k < 3; ++k) {
    CheckGravityDirection(gravity_in_cam[k], k);
    if (bearing_input && !pixels[k].empty()) {
      Fail("both pixels and bearings are given: give one of them");
    }
    const std::size_t size_k = bearing_input ? bearings[k].size() : pixels[k].size();
    if (size_k != observations.size()) {
      const auto& sizes = [&](auto& v) {
        std::ostringstream message;
        message << (bearing_input ? "bearings" : "pixels") << " of the three views differ in size ("
                << v[0].size() << ", " << v[1].size() << ", " << v[2].size() << ")";
        return message.str();
      };
      Fail(bearing_input ? sizes(bearings) : sizes(pixels));
    }
    std::vector<Eigen::Vector3d>* rays_k = rays != nullptr ? &(*rays)[k] : nullptr;
    if (rays_k != nullptr) {
      rays_k->clear();
      rays_k->reserve(size_k);
    }
    if (bearing_input) {
      CheckBearings(bearings[k], k);
      if (rays_k != nullptr) {
        for (const Eigen::Vector3d& b : bearings[k]) rays_k->push_back(b.normalized());
      }
    } else {
      CheckCamera(cameras[k], k);
      CheckPixels(cameras[k], pixels[k], k, rays_k);
    }
  }
}

}  // namespace internal

}  // namespace trigrav
