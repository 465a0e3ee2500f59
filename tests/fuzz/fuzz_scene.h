// Fuzz problems that start from a valid synthetic scene (synthetic_scene.h), so that the fuzzer
// reaches the solvers' numerical code, and then break it with a few decoded edits:
// NaN/Inf/huge/tiny entries, duplicate triplets, collinear points, identical views, mismatched
// sizes, bad gravity.
#ifndef TRIGRAV_TESTS_FUZZ_FUZZ_SCENE_H_
#define TRIGRAV_TESTS_FUZZ_FUZZ_SCENE_H_

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <optional>
#include <random>
#include <stdexcept>
#include <vector>

#include "fuzz_input.h"
#include "trigrav/evaluation/synthetic_scene.h"

namespace trigrav {
namespace fuzz {

// One byte of option flags, one of size and four of seed. Every option set is valid, so nullopt
// (GenerateSyntheticScene's std::runtime_error) means only that no scene could be drawn.
inline std::optional<SyntheticScene> DecodeSyntheticScene(FuzzInput* input,
                                                          int min_points,
                                                          int max_points) {
  const std::uint8_t flags = input->Byte();
  SyntheticSceneOptions options;
  options.num_points = min_points + input->Index(max_points - min_points + 1);
  constexpr double kMaxYawDeg[] = {10.0, 90.0, 180.0, 0.0};
  options.max_yaw_deg = kMaxYawDeg[flags & 3];
  if (flags & 4) options.max_center_m = 0.0;  // zero baseline: pure rotation
  if (flags & 8) options.pixel_noise_px = 1.0;
  if (flags & 16) options.outlier_ratio = 0.3;
  if (flags & 32) options.imu_pitch_noise_deg = options.imu_roll_noise_deg = 1.0;
  if (flags & 64) options.focal_px = 50.0;  // 162 deg wide
  if (flags & 128) options.max_tilt_deg = 45.0;
  std::mt19937_64 rng(input->Uint32());
  try {
    return GenerateSyntheticScene(options, &rng);
  } catch (const std::runtime_error&) {
    return std::nullopt;
  }
}

// Applies up to 8 decoded edits to the per-view points (rays or pixels) and the gravity vectors.
// Returns the number of edits applied.
template <int D>
int ApplyEdits(FuzzInput* input,
               std::array<std::vector<Eigen::Matrix<double, D, 1>>, 3>* views,
               std::array<Eigen::Vector3d, 3>* gravity) {
  using Point = Eigen::Matrix<double, D, 1>;
  const int num_edits = input->Index(9);
  for (int edit = 0; edit < num_edits; ++edit) {
    const int operation = input->Index(8);
    const int k = input->Index(3);
    std::vector<Point>& view = (*views)[k];
    const std::size_t common =
        std::min({(*views)[0].size(), (*views)[1].size(), (*views)[2].size()});
    switch (operation) {
      case 0:  // one entry of a point
        if (!view.empty()) {
          view[input->Index(static_cast<int>(view.size()))][input->Index(D)] = input->Double();
        }
        break;
      case 1:  // one entry of a gravity vector
        (*gravity)[k][input->Index(3)] = input->Double();
        break;
      case 2:  // duplicate triplet: b := a in every view
        if (common > 0) {
          const int a = input->Index(static_cast<int>(common));
          const int b = input->Index(static_cast<int>(common));
          for (auto& v : *views) v[b] = v[a];
        }
        break;
      case 3:  // one view loses its last point
        if (!view.empty()) view.pop_back();
        break;
      case 4:  // one view gains a point
        view.push_back(Point::NullaryExpr([input](Eigen::Index) { return input->Double(); }));
        break;
      case 5:  // scale a point (negative: behind the camera; huge or tiny)
        if (!view.empty()) view[input->Index(static_cast<int>(view.size()))] *= input->Double();
        break;
      case 6:  // identical views: view k := view j
        (*views)[k] = (*views)[input->Index(3)];
        break;
      default:  // collinear: b := a + s (c - a) in every view
        if (common > 0) {
          const int a = input->Index(static_cast<int>(common));
          const int b = input->Index(static_cast<int>(common));
          const int c = input->Index(static_cast<int>(common));
          const double s = input->Double();
          for (auto& v : *views) v[b] = v[a] + s * (v[c] - v[a]);
        }
        break;
    }
  }
  return num_edits;
}

}  // namespace fuzz
}  // namespace trigrav

#endif  // TRIGRAV_TESTS_FUZZ_FUZZ_SCENE_H_
