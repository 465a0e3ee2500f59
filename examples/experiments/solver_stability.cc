// Numerical stability of the gravity-aware minimal solvers on noise-free synthetic scenes (math
// derivations.md sections 9, 8.1 and 8.5): SolveTrifocal3pt (decoupled), SolveTrifocal3ptSextic
// (the paper's system) and SolveTrifocal4pt on the same scenes. Scenes have 4 points; the 3-point
// solvers get the first 3. Errors are in the original camera frames (gravity overloads), in
// degrees, pooled over views 2 and 3; for the 3-point solvers both the best-ranked candidate (what
// a caller gets) and the oracle-best candidate are reported.
//
//   solver_stability --trials=5000 --seed=1

#include <gflags/gflags.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "common/require_flag.h"
#include "common/tool_flags.h"
#include "gravity_solver.h"
#include "trigrav/evaluation/pose_errors.h"
#include "trigrav/evaluation/statistics.h"
#include "trigrav/evaluation/synthetic_scene.h"
#include "trigrav/initializers/trifocal_3pt.h"
#include "trigrav/initializers/trifocal_4pt.h"

DEFINE_int32(trials, 5000, "Number of synthetic scenes.");
DEFINE_uint64(seed, 1, "Random seed; the same seed gives the same output.");
DEFINE_double(noise_px, 0.0, "Image noise sigma in pixels (0: the stability experiment).");
DEFINE_double(found_deg,
              1e-6,
              "A candidate counts as the truth if its rotation and translation errors (both views) "
              "are below this many degrees.");

namespace {

using trigrav::ThreeViewPose;
using trigrav::testing_utils::GravitySolver;
using trigrav::testing_utils::Rays;

constexpr double kNoSolutionDeg = 180.0;

struct Statistics {
  std::string name;
  int num_points = 0;
  GravitySolver solve;
  std::vector<double> rotation_first, translation_first, rotation_oracle, translation_oracle;
  int found = 0, found_first = 0, no_solution = 0;
  long long candidates = 0;
};

Rays FirstN(const Rays& rays, int n) { return Rays(rays.begin(), rays.begin() + n); }

void AddErrors(const trigrav::ThreeViewPoseErrors& e,
               std::vector<double>* rotation,
               std::vector<double>* translation) {
  for (int k = 0; k < 2; ++k) {
    rotation->push_back(trigrav::Log10Error(e.rotation_deg[k]));
    translation->push_back(trigrav::Log10Error(e.translation_deg[k]));
  }
}

void RunScene(const trigrav::SyntheticScene& scene, Statistics* stats) {
  std::vector<ThreeViewPose> solutions;
  const int count = stats->solve(
      FirstN(scene.rays[0], stats->num_points), FirstN(scene.rays[1], stats->num_points),
      FirstN(scene.rays[2], stats->num_points), scene.gravity_in_cam_measured[0],
      scene.gravity_in_cam_measured[1], scene.gravity_in_cam_measured[2], &solutions);
  stats->candidates += count;
  if (count == 0) {
    ++stats->no_solution;
    trigrav::ThreeViewPoseErrors failure;
    failure.rotation_deg[0] = failure.rotation_deg[1] = kNoSolutionDeg;
    failure.translation_deg[0] = failure.translation_deg[1] = kNoSolutionDeg;
    AddErrors(failure, &stats->rotation_first, &stats->translation_first);
    AddErrors(failure, &stats->rotation_oracle, &stats->translation_oracle);
    return;
  }
  const trigrav::ThreeViewPoseErrors first =
      trigrav::ComputeThreeViewPoseErrors(scene.ground_truth, solutions[0]);
  trigrav::ThreeViewPoseErrors oracle = first;
  for (const ThreeViewPose& pose : solutions) {
    const trigrav::ThreeViewPoseErrors e =
        trigrav::ComputeThreeViewPoseErrors(scene.ground_truth, pose);
    if (e.MaxAngleDeg() < oracle.MaxAngleDeg()) oracle = e;
  }
  AddErrors(first, &stats->rotation_first, &stats->translation_first);
  AddErrors(oracle, &stats->rotation_oracle, &stats->translation_oracle);
  stats->found += oracle.MaxAngleDeg() < FLAGS_found_deg;
  stats->found_first += first.MaxAngleDeg() < FLAGS_found_deg;
}

}  // namespace

int main(int argc, char** argv) {
  trigrav::examples::ParseToolFlags(
      "Noise-free stability of the 3-point and 4-point trifocal solvers.", __FILE__, &argc, &argv);
  using trigrav::examples::RequireFlag;
  RequireFlag(FLAGS_trials > 0, "--trials must be positive");
  RequireFlag(FLAGS_noise_px >= 0.0 && std::isfinite(FLAGS_noise_px),
              "--noise_px must be finite and >= 0");
  RequireFlag(FLAGS_found_deg > 0.0 && std::isfinite(FLAGS_found_deg),
              "--found_deg must be positive and finite");

  std::vector<Statistics> all(3);
  all[0].name = "3pt";
  all[0].num_points = 3;
  all[0].solve = [](const Rays& x1, const Rays& x2, const Rays& x3, const Eigen::Vector3d& g1,
                    const Eigen::Vector3d& g2, const Eigen::Vector3d& g3,
                    std::vector<ThreeViewPose>* out) {
    return trigrav::SolveTrifocal3pt(x1, x2, x3, g1, g2, g3, out);
  };
  all[1].name = "3pt-sextic";
  all[1].num_points = 3;
  all[1].solve = [](const Rays& x1, const Rays& x2, const Rays& x3, const Eigen::Vector3d& g1,
                    const Eigen::Vector3d& g2, const Eigen::Vector3d& g3,
                    std::vector<ThreeViewPose>* out) {
    return trigrav::SolveTrifocal3ptSextic(x1, x2, x3, g1, g2, g3, out);
  };
  all[2].name = "4pt";
  all[2].num_points = 4;
  all[2].solve = [](const Rays& x1, const Rays& x2, const Rays& x3, const Eigen::Vector3d& g1,
                    const Eigen::Vector3d& g2, const Eigen::Vector3d& g3,
                    std::vector<ThreeViewPose>* out) {
    return trigrav::SolveTrifocal4pt(x1, x2, x3, g1, g2, g3, out);
  };

  trigrav::SyntheticSceneOptions scene_options;
  scene_options.num_points = 4;
  scene_options.pixel_noise_px = FLAGS_noise_px;
  std::mt19937_64 rng(FLAGS_seed);
  for (int trial = 0; trial < FLAGS_trials; ++trial) {
    const trigrav::SyntheticScene scene = trigrav::GenerateSyntheticScene(scene_options, &rng);
    for (Statistics& stats : all) RunScene(scene, &stats);
  }

  std::printf(
      "%d scenes, seed %llu, %.2f px noise; log10 of errors in deg, views 2 and 3 pooled;\n"
      "found = some candidate within %.0e deg (rotation and translation, both views)\n\n",
      FLAGS_trials, static_cast<unsigned long long>(FLAGS_seed), FLAGS_noise_px, FLAGS_found_deg);
  std::printf("%-15s %-7s %9s %9s %9s %9s %9s %9s %9s\n", "solver", "pick", "rot med", "rot p99",
              "tra med", "tra p99", "found", "no sol", "cands");
  for (const Statistics& stats : all) {
    const bool has_candidates = stats.num_points == 3;
    for (const bool oracle : {false, true}) {
      if (oracle && !has_candidates) continue;
      const auto& rotation = oracle ? stats.rotation_oracle : stats.rotation_first;
      const auto& translation = oracle ? stats.translation_oracle : stats.translation_first;
      std::printf("%-15s %-7s %9.2f %9.2f %9.2f %9.2f %9.4f %9.4f %9.2f\n", stats.name.c_str(),
                  oracle ? "oracle" : "ranked", trigrav::Quantile(rotation, 0.5),
                  trigrav::Quantile(rotation, 0.99), trigrav::Quantile(translation, 0.5),
                  trigrav::Quantile(translation, 0.99),
                  static_cast<double>(oracle ? stats.found : stats.found_first) / FLAGS_trials,
                  static_cast<double>(stats.no_solution) / FLAGS_trials,
                  static_cast<double>(stats.candidates) / FLAGS_trials);
    }
  }
  return 0;
}
