// Time of RefineWithGravity (nview_bundle_adjustment.h) on a synthetic driving sequence
// (tests/scenes/nview_scene.h) started from 1 deg / 5 % perturbed poses and 2 % perturbed points,
// per rotation model and linear solver (SPARSE_SCHUR, DENSE_SCHUR; ITERATIVE_SCHUR too with
// iterative=1), interleaved over repetitions; prints the medians and ranges of the CPU time of the
// whole call (std::clock: one thread, so the figure is the work, less sensitive to a loaded machine
// than the wall time) and of the covariance's wall time.
//   nview_bundle_adjustment_benchmark [num_images=300] [num_points=30000] [repetitions=3]
//                                     [covariance=0] [iterative=0]

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <string>
#include <vector>

#include "nview_scene.h"
#include "trigrav/ba/nview_bundle_adjustment.h"

int main(int argc, char** argv) {
  using trigrav::NViewBundleAdjustmentOptions;
  const int num_images = argc > 1 ? std::atoi(argv[1]) : 300;
  const int num_points = argc > 2 ? std::atoi(argv[2]) : 30000;
  const int repetitions = argc > 3 ? std::atoi(argv[3]) : 3;
  const bool covariance = argc > 4 && std::atoi(argv[4]) != 0;
  const bool iterative = argc > 5 && std::atoi(argv[5]) != 0;
  trigrav::testing_utils::NViewSceneOptions scene_options;
  scene_options.num_images = num_images;
  scene_options.num_points = num_points;
  scene_options.gravity_noise_deg = 0.1;
  const trigrav::NViewReconstruction truth =
      trigrav::testing_utils::MakeNViewScene(scene_options, 1).truth;
  const trigrav::NViewReconstruction start =
      trigrav::testing_utils::PerturbReconstruction(truth, 1.0, 0.05, 0.02, 2);
  std::printf("%d images, %zu points, %zu observations, covariance %d\n", num_images,
              truth.points_in_world.size(), truth.observations.size(), covariance ? 1 : 0);

  struct Variant {
    const char* name;
    NViewBundleAdjustmentOptions::RotationModel model;
    ceres::LinearSolverType solver;
    std::vector<double> solve_s, covariance_s;
    int iterations = 0;
    double final_cost = 0.0;
  };
  std::vector<Variant> variants;
  for (const auto model : {NViewBundleAdjustmentOptions::RotationModel::kYawOnly,
                           NViewBundleAdjustmentOptions::RotationModel::kGravityPrior}) {
    for (const auto solver : {ceres::SPARSE_SCHUR, ceres::DENSE_SCHUR, ceres::ITERATIVE_SCHUR}) {
      if (solver == ceres::ITERATIVE_SCHUR && !iterative) continue;
      const char* name = model == NViewBundleAdjustmentOptions::RotationModel::kYawOnly
                             ? "yaw_only"
                             : "gravity_prior";
      variants.push_back({name, model, solver, {}, {}});
    }
  }
  for (int r = 0; r < repetitions; ++r) {
    for (Variant& v : variants) {
      NViewBundleAdjustmentOptions options;
      options.rotation_model = v.model;
      options.linear_solver_type = v.solver;
      options.compute_covariance = covariance;
      trigrav::NViewReconstruction refined;
      const std::clock_t cpu_start = std::clock();
      const trigrav::NViewBundleAdjustmentSummary summary =
          trigrav::RefineWithGravity(start, {}, options, &refined);
      const double cpu_s = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
      if (!summary.success) {
        std::printf("%s %s failed: %s\n", v.name, ceres::LinearSolverTypeToString(v.solver),
                    summary.message.c_str());
        return 1;
      }
      v.solve_s.push_back(cpu_s);
      v.covariance_s.push_back(summary.covariance_s);
      v.iterations = summary.Iterations();
      v.final_cost = summary.FinalCost();
    }
  }
  auto median = [](std::vector<double> x) {
    std::sort(x.begin(), x.end());
    return x[x.size() / 2];
  };
  for (const Variant& v : variants) {
    std::printf(
        "%-14s %-16s call CPU median %.2f s (min %.2f, max %.2f), %d iterations, final cost "
        "%.6g, covariance wall median %.2f s\n",
        v.name, ceres::LinearSolverTypeToString(v.solver), median(v.solve_s),
        *std::min_element(v.solve_s.begin(), v.solve_s.end()),
        *std::max_element(v.solve_s.begin(), v.solve_s.end()), v.iterations, v.final_cost,
        median(v.covariance_s));
  }
  return 0;
}
