#ifndef TRIGRAV_INITIALIZERS_THREE_VIEW_OBSERVATIONS_H_
#define TRIGRAV_INITIALIZERS_THREE_VIEW_OBSERVATIONS_H_

#include <Eigen/Core>
#include <array>
#include <vector>

#include "trigrav/initializers/camera_model.h"

namespace trigrav {

// What a pipeline has for three views: each camera's gravity direction (down, in its own frame,
// any length whose square is a positive finite double, about 2e-162 to 1e154) and N point
// triplets, given either as
//  - pixels with a camera model per view (camera_model.h; a PinholeCamera converts), or
//  - bearings: unit (any length, as for gravity) directions in each camera's frame, for users
//    with a camera model of their own. `cameras` are then unused; the errors, thresholds and losses
//    are angles (observation_residual.h) instead of pixels.
// Nothing has a usable default: Check() rejects unset cameras (focal length 0) and unset gravity
// (zero), also for the methods that ignore gravity.
struct ThreeViewObservations {
  std::array<Camera, 3> cameras;
  std::array<Eigen::Vector3d, 3> gravity_in_cam = {Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(),
                                                   Eigen::Vector3d::Zero()};
  std::array<std::vector<Eigen::Vector2d>, 3> pixels;  // pixels[k][n]: triplet n seen in view k
  // Instead of pixels: bearings[k][n], the direction of triplet n in camera k's frame.
  std::array<std::vector<Eigen::Vector3d>, 3> bearings;

  // True when the triplets are given as bearings (any view has bearings).
  bool HasBearings() const {
    return !bearings[0].empty() || !bearings[1].empty() || !bearings[2].empty();
  }
  std::size_t size() const { return HasBearings() ? bearings[0].size() : pixels[0].size(); }
  // The ray of triplet n in view k's frame: the unprojected pixel (Camera::Unproject, z = 1), or
  // the bearing as given. For observations that pass Check(); NaN if the pixel cannot be
  // unprojected.
  Eigen::Vector3d Ray(int k, std::size_t n) const;
  // Throws std::invalid_argument naming the problem: sizes differ, pixels and bearings both given,
  // unset or bad camera parameters, non-finite pixels, pixels the camera cannot unproject (beyond
  // a distortion's fold, or so far out that the ray overflows), zero or non-finite bearings, unset
  // (zero) or non-finite gravity, bearings or gravity too short or too long to normalise.
  void Check() const;
};

}  // namespace trigrav

#endif  // TRIGRAV_INITIALIZERS_THREE_VIEW_OBSERVATIONS_H_
