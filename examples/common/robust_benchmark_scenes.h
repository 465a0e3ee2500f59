#ifndef TRIGRAV_EXAMPLES_COMMON_ROBUST_BENCHMARK_SCENES_H_
#define TRIGRAV_EXAMPLES_COMMON_ROBUST_BENCHMARK_SCENES_H_

// The scene set of the robust benchmark (examples/benchmarks/robust_benchmark), on which
// peer_comparison times the peers too: 20 scenes from seed 2026 of 500 triplets with 30 % outliers
// and 0.5 px image noise (the other SyntheticSceneOptions at their defaults: f = 500 px, 640 x 480,
// exact IMU), inlier threshold 1.5 px (3 sigma). Header only, not part of the installed library.

#include <cstdint>
#include <random>
#include <vector>

#include "trigrav/evaluation/synthetic_scene.h"

namespace trigrav {

inline constexpr int kRobustBenchmarkScenes = 20;
inline constexpr std::uint64_t kRobustBenchmarkSeed = 2026;
inline constexpr double kRobustBenchmarkThresholdPx = 1.5;  // 3 sigma at 0.5 px

inline SyntheticSceneOptions RobustBenchmarkSceneOptions() {
  SyntheticSceneOptions options;
  options.num_points = 500;
  options.pixel_noise_px = 0.5;
  options.outlier_ratio = 0.3;
  return options;
}

// `count` scenes drawn one after the other from one generator seeded with `seed`.
inline std::vector<SyntheticScene> RobustBenchmarkScenes(
    int count = kRobustBenchmarkScenes, std::uint64_t seed = kRobustBenchmarkSeed) {
  const SyntheticSceneOptions options = RobustBenchmarkSceneOptions();
  std::mt19937_64 rng(seed);
  std::vector<SyntheticScene> scenes;
  for (int i = 0; i < count; ++i) scenes.push_back(GenerateSyntheticScene(options, &rng));
  return scenes;
}

}  // namespace trigrav

#endif  // TRIGRAV_EXAMPLES_COMMON_ROBUST_BENCHMARK_SCENES_H_
