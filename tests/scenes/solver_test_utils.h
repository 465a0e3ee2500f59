// Helpers shared by the solver tests.
#ifndef TRIGRAV_TESTS_SOLVER_TEST_UTILS_H_
#define TRIGRAV_TESTS_SOLVER_TEST_UTILS_H_

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <vector>

#include "trigrav/evaluation/pose_errors.h"
#include "trigrav/evaluation/statistics.h"
#include "trigrav/evaluation/synthetic_scene.h"

namespace trigrav {
namespace testing_utils {

// Scenes unlike the default the solvers were developed on: other focal lengths, yaw well beyond
// +-10 deg (up to 170), tilts from 3 to 15 deg, deeper scenes. The caller sets num_points.
inline std::vector<SyntheticSceneOptions> UnseenSceneOptions() {
  struct Case {
    double focal_px, max_yaw_deg, max_tilt_deg;
  };
  std::vector<SyntheticSceneOptions> scenes;
  for (const Case c : {Case{300.0, 45.0, 5.0}, Case{1200.0, 90.0, 8.0}, Case{800.0, 170.0, 3.0},
                       Case{500.0, 30.0, 15.0}}) {
    SyntheticSceneOptions options;
    options.focal_px = c.focal_px;
    options.max_yaw_deg = c.max_yaw_deg;
    options.max_tilt_deg = c.max_tilt_deg;
    options.max_depth_m = 80.0;
    scenes.push_back(options);
  }
  return scenes;
}

// Median rotation error (deg, views 2 and 3 pooled) of the first (best-ranked) solution of
// solve(scene, &solutions) over num_scenes scenes drawn with `seed`; a scene without solution
// counts 180 deg for both views and is counted in *no_solution when given.
template <typename Solve>
double MedianFirstSolutionRotationErrorDeg(const SyntheticSceneOptions& options,
                                           std::uint64_t seed,
                                           int num_scenes,
                                           Solve solve,
                                           int* no_solution = nullptr) {
  std::mt19937_64 rng(seed);
  std::vector<double> errors;
  std::vector<ThreeViewPose> solutions;
  for (int trial = 0; trial < num_scenes; ++trial) {
    const SyntheticScene scene = GenerateSyntheticScene(options, &rng);
    if (solve(scene, &solutions) == 0) {
      if (no_solution != nullptr) ++*no_solution;
      errors.insert(errors.end(), {180.0, 180.0});
      continue;
    }
    EXPECT_TRUE(solutions[0].IsFinite());
    const ThreeViewPoseErrors e = ComputeThreeViewPoseErrors(scene.ground_truth, solutions[0]);
    errors.insert(errors.end(), {e.rotation_deg[0], e.rotation_deg[1]});
  }
  return Median(errors);
}

}  // namespace testing_utils
}  // namespace trigrav

#endif  // TRIGRAV_TESTS_SOLVER_TEST_UTILS_H_
