// One gravity-aware minimal solver, or a variant of the 4-point solver, on synthetic three-view
// scenes (derivations.md section 8.5): the raw rays and each camera's measured gravity in, per-view
// rotation and translation errors of its best-ranked candidate against the ground truth out, one
// line per trial and a summary line of medians. paper_experiments runs every method at the paper's
// fixed levels; this tool runs one solver at any noise, focal length and number of triplets, and
// the 4-point variants the experiments leave out.
//
//   minimal_solver_accuracy                                    # 4pt, 4 triplets, 1 px, 10 scenes
//   minimal_solver_accuracy --solver=3pt --points=3 --trials=1000 --print_trials=0
//   minimal_solver_accuracy --solver=4pt-closed-form --imu_noise_deg=0.1

#include <gflags/gflags.h>
#include <glog/logging.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "common/pooled_errors.h"
#include "common/require_flag.h"
#include "common/tool_flags.h"
#include "gravity_solver.h"
#include "trigrav/evaluation/pose_errors.h"
#include "trigrav/evaluation/statistics.h"
#include "trigrav/evaluation/synthetic_scene.h"
#include "trigrav/initializers/trifocal_3pt.h"
#include "trigrav/initializers/trifocal_4pt.h"

DEFINE_string(
    solver,
    "4pt",
    "Solver: 3pt (decoupled, best-ranked candidate), 3pt-sextic (the paper's system), "
    "4pt (trigrav's default pipeline: the least-squares read polished until converged), "
    "4pt-enforced (derivations.md section 4.3, the re-solve and one polish step: the default "
    "pipeline for more than 4 triplets), 4pt-enforced-converged (the same polished until "
    "converged: recovery = kEnforced), 4pt-unpolished (the same without the polish), "
    "4pt-paper (paper III-D: enforced with the tensor's epipoles, no translation re-solve, no "
    "polish), "
    "4pt-closed-form (paper eqs c8-c11, no enforcement), 4pt-least-squares (derivations.md "
    "section 4.2)");
DEFINE_double(noise_px, 1.0, "Image noise sigma in pixels (all three views).");
DEFINE_double(imu_noise_deg, 0.0, "IMU noise sigma in degrees on each view's pitch and roll.");
DEFINE_int32(points, 4, "Triplets per scene (the 3pt solvers need exactly 3).");
DEFINE_int32(trials, 10, "Number of scenes.");
DEFINE_int32(print_trials, 10, "Print per-view errors of this many trials.");
DEFINE_uint64(seed, 1, "Random seed; the same seed gives the same output.");
DEFINE_double(focal_px, 500.0, "Focal length in pixels (640 x 480 image).");

namespace {

using trigrav::ThreeViewPose;
using trigrav::testing_utils::GravitySolver;
using trigrav::testing_utils::Rays;

GravitySolver Trifocal4pt(const trigrav::Trifocal4ptOptions& options) {
  return [options](const Rays& x1, const Rays& x2, const Rays& x3, const Eigen::Vector3d& g1,
                   const Eigen::Vector3d& g2, const Eigen::Vector3d& g3,
                   std::vector<ThreeViewPose>* solutions) {
    return trigrav::SolveTrifocal4pt(x1, x2, x3, g1, g2, g3, options, solutions);
  };
}

// A variant of the 4-point pipeline (trifocal_4pt.h).
GravitySolver Trifocal4pt(trigrav::Trifocal4ptRecovery recovery,
                          bool resolve_translations,
                          int polish_iterations,
                          trigrav::Trifocal4ptEpipoles epipoles =
                              trigrav::Trifocal4ptEpipoles::kLeastSquaresReadIfMinimal) {
  trigrav::Trifocal4ptOptions options;
  options.recovery = recovery;
  options.epipoles = epipoles;
  options.resolve_translations = resolve_translations;
  options.polish_iterations = polish_iterations;
  return Trifocal4pt(options);
}

const std::map<std::string, GravitySolver>& Solvers() {
  using trigrav::Trifocal4ptRecovery;
  static const std::map<std::string, GravitySolver> solvers = {
      {"3pt",
       [](const Rays& x1, const Rays& x2, const Rays& x3, const Eigen::Vector3d& g1,
          const Eigen::Vector3d& g2, const Eigen::Vector3d& g3, std::vector<ThreeViewPose>* out) {
         return trigrav::SolveTrifocal3pt(x1, x2, x3, g1, g2, g3, out);
       }},
      {"3pt-sextic",
       [](const Rays& x1, const Rays& x2, const Rays& x3, const Eigen::Vector3d& g1,
          const Eigen::Vector3d& g2, const Eigen::Vector3d& g3, std::vector<ThreeViewPose>* out) {
         return trigrav::SolveTrifocal3ptSextic(x1, x2, x3, g1, g2, g3, out);
       }},
      {"4pt", Trifocal4pt(trigrav::Trifocal4ptOptions())},
      {"4pt-enforced", Trifocal4pt(Trifocal4ptRecovery::kEnforced, true, 1)},
      {"4pt-enforced-converged", Trifocal4pt(Trifocal4ptRecovery::kEnforced, true,
                                             trigrav::Trifocal4ptOptions().polish_iterations)},
      {"4pt-unpolished", Trifocal4pt(Trifocal4ptRecovery::kEnforced, true, 0)},
      {"4pt-paper", Trifocal4pt(Trifocal4ptRecovery::kEnforced, false, 0,
                                trigrav::Trifocal4ptEpipoles::kTensorNullVectors)},
      {"4pt-closed-form", Trifocal4pt(Trifocal4ptRecovery::kPaperClosedForm, false, 0)},
      {"4pt-least-squares", Trifocal4pt(Trifocal4ptRecovery::kLeastSquares, false, 0)},
  };
  return solvers;
}

}  // namespace

int main(int argc, char** argv) {
  trigrav::examples::ParseToolFlags("Runs a gravity-aware trifocal solver on synthetic triplets.",
                                    __FILE__, &argc, &argv);
  google::InitGoogleLogging(argv[0]);
  using trigrav::examples::RequireFlag;
  const auto solver = Solvers().find(FLAGS_solver);
  RequireFlag(solver != Solvers().end(), "unknown --solver=" + FLAGS_solver);
  RequireFlag(FLAGS_trials > 0, "--trials must be positive");
  RequireFlag(FLAGS_print_trials >= 0, "--print_trials must be >= 0");
  if (FLAGS_solver.rfind("3pt", 0) == 0) {
    RequireFlag(FLAGS_points == 3,
                "--solver=" + FLAGS_solver + " takes exactly 3 triplets: --points=3");
  } else {
    RequireFlag(FLAGS_points >= 4, "--solver=" + FLAGS_solver + " needs --points >= 4");
  }
  RequireFlag(FLAGS_noise_px >= 0.0 && std::isfinite(FLAGS_noise_px),
              "--noise_px must be finite and >= 0");
  RequireFlag(FLAGS_imu_noise_deg >= 0.0 && std::isfinite(FLAGS_imu_noise_deg),
              "--imu_noise_deg must be finite and >= 0");
  RequireFlag(FLAGS_focal_px > 0.0 && std::isfinite(FLAGS_focal_px),
              "--focal_px must be positive and finite");

  trigrav::SyntheticSceneOptions scene_options;
  scene_options.num_points = FLAGS_points;
  scene_options.pixel_noise_px = FLAGS_noise_px;
  scene_options.imu_pitch_noise_deg = FLAGS_imu_noise_deg;
  scene_options.imu_roll_noise_deg = FLAGS_imu_noise_deg;
  scene_options.focal_px = FLAGS_focal_px;
  scene_options.Check();

  std::mt19937_64 rng(FLAGS_seed);
  trigrav::PooledErrors errors;
  int failures = 0;
  std::printf("solver %s, %d triplets, %.2f px noise, %.2f deg IMU noise, seed %llu\n",
              FLAGS_solver.c_str(), FLAGS_points, FLAGS_noise_px, FLAGS_imu_noise_deg,
              static_cast<unsigned long long>(FLAGS_seed));
  std::printf("%6s %12s %12s %12s %12s %10s\n", "trial", "R2 err deg", "R3 err deg", "t2 err deg",
              "t3 err deg", "scale err");
  for (int trial = 0; trial < FLAGS_trials; ++trial) {
    const trigrav::SyntheticScene scene = trigrav::GenerateSyntheticScene(scene_options, &rng);
    std::vector<ThreeViewPose> solutions;
    const int count = solver->second(
        scene.rays[0], scene.rays[1], scene.rays[2], scene.gravity_in_cam_measured[0],
        scene.gravity_in_cam_measured[1], scene.gravity_in_cam_measured[2], &solutions);
    if (count == 0) {
      ++failures;
      if (trial < FLAGS_print_trials) std::printf("%6d   no solution\n", trial);
      continue;
    }
    // Solvers return candidates best first; the first is what a caller without ground truth takes.
    const trigrav::ThreeViewPoseErrors e =
        trigrav::ComputeThreeViewPoseErrors(scene.ground_truth, solutions[0]);
    errors.Add(e);
    if (trial < FLAGS_print_trials) {
      std::printf("%6d %12.3e %12.3e %12.3e %12.3e %10.3e\n", trial, e.rotation_deg[0],
                  e.rotation_deg[1], e.translation_deg[0], e.translation_deg[1], e.relative_scale);
    }
  }
  std::printf(
      "summary: %d trials, %d without solution, median rotation %.4g deg, median translation %.4g "
      "deg, median |log scale ratio| %.4g\n",
      FLAGS_trials, failures, trigrav::Median(errors.rotation_deg),
      trigrav::Median(errors.translation_deg), trigrav::Median(errors.relative_scale));
  return 0;
}
