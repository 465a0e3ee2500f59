#ifndef TRIGRAV_INITIALIZERS_THREE_VIEW_OBSERVATIONS_H_
#define TRIGRAV_INITIALIZERS_THREE_VIEW_OBSERVATIONS_H_

#include <Eigen/Core>
#include <array>
#include <vector>

namespace trigrav {

// Pinhole intrinsics without distortion: u = fx x/z + cx, v = fy y/z + cy.
struct PinholeCamera {
  double fx = 1.0, fy = 1.0, cx = 0.0, cy = 0.0;

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

// What a pipeline has for three views: intrinsics, each camera's gravity direction (down, in its
// own frame, any positive length) and the pixels of N point triplets.
struct ThreeViewObservations {
  std::array<PinholeCamera, 3> cameras;
  std::array<Eigen::Vector3d, 3> gravity_in_cam = {
      Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitY()};
  std::array<std::vector<Eigen::Vector2d>, 3> pixels;  // pixels[k][n]: triplet n seen in view k

  std::size_t size() const { return pixels[0].size(); }
  // Throws std::invalid_argument naming the problem: sizes differ, bad intrinsics, non-finite
  // pixels, pixels whose ray K^-1 [u v 1]^T overflows, zero or non-finite gravity.
  void Check() const;
};

}  // namespace trigrav

#endif  // TRIGRAV_INITIALIZERS_THREE_VIEW_OBSERVATIONS_H_
