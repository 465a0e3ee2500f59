#ifndef TRIGRAV_EXAMPLES_BENCHMARKS_SOLVER_BENCHMARK_SCENES_H_
#define TRIGRAV_EXAMPLES_BENCHMARKS_SOLVER_BENCHMARK_SCENES_H_

// The minimal solvers' benchmark scenes (solver_benchmark and its PoseLib rows): `count`
// noise-free scenes of `num_points` triplets from SyntheticSceneOptions' defaults (f = 500 px,
// exact gravity), drawn one after the other from one generator seeded with 2026.

#include <Eigen/Core>
#include <array>
#include <random>
#include <vector>

#include "trigrav/evaluation/synthetic_scene.h"
#include "trigrav/initializers/camera_pose.h"
#include "trigrav/initializers/gravity.h"

namespace trigrav::benchmarks {

// A scene's rays in gravity-aligned frames (gravity = the y axis) and its ground truth in the
// same frames.
struct AlignedProblem {
  std::vector<Eigen::Vector3d> x1, x2, x3;
  ThreeViewPose ground_truth;
};

// The same scene as a gravity overload sees it: raw rays, each camera's gravity, the original
// frames' ground truth.
struct RawProblem {
  std::array<std::vector<Eigen::Vector3d>, 3> rays;
  std::array<Eigen::Vector3d, 3> gravity_in_cam;
  ThreeViewPose ground_truth;
};

inline std::vector<SyntheticScene> MakeScenes(int num_points, int count) {
  std::mt19937_64 rng(2026);
  SyntheticSceneOptions options;
  options.num_points = num_points;
  std::vector<SyntheticScene> scenes;
  for (int i = 0; i < count; ++i) scenes.push_back(GenerateSyntheticScene(options, &rng));
  return scenes;
}

inline std::vector<AlignedProblem> MakeProblems(int num_points, int count) {
  std::vector<AlignedProblem> problems;
  for (const SyntheticScene& scene : MakeScenes(num_points, count)) {
    const auto& align = scene.gravity_alignment_true;
    AlignedProblem problem;
    problem.x1 = AlignRays(align[0], scene.rays[0]);
    problem.x2 = AlignRays(align[1], scene.rays[1]);
    problem.x3 = AlignRays(align[2], scene.rays[2]);
    // Aligned ground truth: R = A_k R~ A_1^T, t = A_k t~ (the inverse of UnalignPose).
    problem.ground_truth = UnalignThreeViewPose(scene.ground_truth, align[0].transpose(),
                                                align[1].transpose(), align[2].transpose());
    problems.push_back(problem);
  }
  return problems;
}

inline std::vector<RawProblem> MakeRawProblems(int num_points, int count) {
  std::vector<RawProblem> problems;
  for (const SyntheticScene& scene : MakeScenes(num_points, count)) {
    problems.push_back({scene.rays, scene.gravity_in_cam_measured, scene.ground_truth});
  }
  return problems;
}

}  // namespace trigrav::benchmarks

#endif  // TRIGRAV_EXAMPLES_BENCHMARKS_SOLVER_BENCHMARK_SCENES_H_
