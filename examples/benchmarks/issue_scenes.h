#ifndef TRIGRAV_EXAMPLES_BENCHMARKS_ISSUE_SCENES_H_
#define TRIGRAV_EXAMPLES_BENCHMARKS_ISSUE_SCENES_H_

// robust_benchmark's issue-like scenes (its IssueScenes rows and its PoseLib rows), like
// initialize_and_refine_synthetic's default: 20 scenes from seed 2026 of `num_points` (375 or 875)
// triplets, f = 500 px, 1 px noise and 20 % outliers; benchmarked at a 2 px threshold.

#include <random>
#include <vector>

#include "common/robust_benchmark_scenes.h"
#include "trigrav/evaluation/synthetic_scene.h"

namespace trigrav::benchmarks {

constexpr double kIssueScenesThresholdPx = 2.0;

// Generated once per size (375 or 875) and kept.
inline const std::vector<SyntheticScene>& IssueScenes(int num_points) {
  static std::vector<std::vector<SyntheticScene>> cache(2);
  std::vector<SyntheticScene>& scenes = cache[num_points > 500 ? 1 : 0];
  if (scenes.empty()) {
    SyntheticSceneOptions options;
    options.num_points = num_points;
    options.pixel_noise_px = 1.0;
    options.outlier_ratio = 0.2;
    std::mt19937_64 rng(kRobustBenchmarkSeed);
    for (int i = 0; i < kRobustBenchmarkScenes; ++i) {
      scenes.push_back(GenerateSyntheticScene(options, &rng));
    }
  }
  return scenes;
}

}  // namespace trigrav::benchmarks

#endif  // TRIGRAV_EXAMPLES_BENCHMARKS_ISSUE_SCENES_H_
