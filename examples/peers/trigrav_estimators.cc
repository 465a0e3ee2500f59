// trigrav's own entries of the comparison: robust estimates, refined estimates, minimal solvers.

#include <chrono>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "peer_estimators.h"
#include "trigrav/ba/initialize_and_refine.h"
#include "trigrav/evaluation/pose_errors.h"
#include "trigrav/initializers/essential_5pt.h"
#include "trigrav/initializers/robust_three_view.h"
#include "trigrav/initializers/trifocal_3pt.h"
#include "trigrav/initializers/trifocal_4pt.h"

namespace trigrav::peers {
namespace {

constexpr double kTruthDeg = 1e-6;

double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

EstimatorResult RobustEstimate(const ThreeViewObservations& observations,
                               const RobustThreeViewOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  EstimatorResult result;
  static_cast<RobustThreeViewEstimate&>(result) =
      EstimateThreeViewPoseRobust(observations, options);
  result.time_s = SecondsSince(start);
  return result;
}

// The refined pose of InitializeAndRefine with its inliers (ransac.num_inliers counting them).
EstimatorResult RefinedEstimate(const ThreeViewObservations& observations,
                                const InitializeAndRefineOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const ThreeViewEstimate estimate = InitializeAndRefine(observations, options);
  EstimatorResult result;
  result.time_s = SecondsSince(start);
  result.success = estimate.success;
  result.message = estimate.message;
  result.pose = estimate.refined;
  result.inliers = estimate.inliers;
  result.ransac = estimate.robust.ransac;
  result.ransac.num_inliers = estimate.num_inliers;
  return result;
}

std::string RansacDescription(InitialSolver solver) {
  const RansacOptions defaults;
  char settings[160];
  std::snprintf(settings, sizeof(settings), "MSAC + LO, confidence %g, %d-%d iterations, seed 0",
                defaults.confidence, defaults.min_iterations, defaults.max_iterations);
  return std::string("trigrav::EstimateThreeViewPoseRobust, InitialSolver ") +
         InitialSolverName(solver) + (UsesGravity(solver) ? " (with gravity)" : " (no gravity)") +
         "; inlier iff the largest reprojection error over the 3 views of the midpoint-"
         "triangulated triplet <= threshold; " +
         settings;
}

// The first `count` triplets of a problem.
std::vector<Eigen::Vector3d> Head(const std::vector<Eigen::Vector3d>& rays, std::size_t count) {
  return std::vector<Eigen::Vector3d>(rays.begin(), rays.begin() + count);
}

// A three-view minimal solver with gravity on the first `sample` triplets of every problem.
template <typename Solve>
NamedMinimalSolver GravityMinimalSolver(std::string name,
                                        std::string description,
                                        std::size_t sample,
                                        Solve solve) {
  NamedMinimalSolver entry{std::move(name), std::move(description), nullptr};
  entry.prepare = [sample, solve](const std::vector<MinimalProblem>& problems) {
    struct Data {
      std::vector<std::vector<Eigen::Vector3d>> x1, x2, x3;
      std::vector<ThreeViewPose> solutions;
    };
    auto data = std::make_shared<Data>();
    for (const MinimalProblem& p : problems) {
      data->x1.push_back(Head(p.x1, sample));
      data->x2.push_back(Head(p.x2, sample));
      data->x3.push_back(Head(p.x3, sample));
    }
    data->solutions.reserve(64);
    const auto solve_one = [data, &problems, solve](std::size_t i) {
      const MinimalProblem& p = problems[i];
      return solve(data->x1[i], data->x2[i], data->x3[i], p.gravity_in_cam1, p.gravity_in_cam2,
                   p.gravity_in_cam3, &data->solutions);
    };
    PreparedMinimalSolver prepared;
    prepared.solve = solve_one;
    prepared.truth_found = [data, &problems, solve_one](std::size_t i) {
      solve_one(i);
      for (const ThreeViewPose& pose : data->solutions) {
        if (ComputeThreeViewPoseErrors(problems[i].ground_truth, pose).MaxAngleDeg() < kTruthDeg)
          return true;
      }
      return false;
    };
    return prepared;
  };
  return entry;
}

NamedMinimalSolver Essential5ptMinimalSolver() {
  NamedMinimalSolver entry{
      "5pt",
      "SolveEssential5pt: Nister five-point on pair (1,2), 5 rays; decomposes every E and "
      "keeps the cheirality-consistent poses",
      nullptr};
  entry.prepare = [](const std::vector<MinimalProblem>& problems) {
    struct Data {
      std::vector<std::vector<Eigen::Vector3d>> x1, x2;
      std::vector<CameraPose> solutions;
    };
    auto data = std::make_shared<Data>();
    for (const MinimalProblem& p : problems) {
      data->x1.push_back(Head(p.x1, 5));
      data->x2.push_back(Head(p.x2, 5));
    }
    data->solutions.reserve(16);
    const auto solve_one = [data](std::size_t i) {
      return SolveEssential5pt(data->x1[i], data->x2[i], &data->solutions);
    };
    PreparedMinimalSolver prepared;
    prepared.solve = solve_one;
    prepared.truth_found = [data, &problems, solve_one](std::size_t i) {
      solve_one(i);
      const CameraPose& truth = problems[i].ground_truth.cam2_from_cam1;
      for (const CameraPose& pose : data->solutions) {
        if (RotationErrorDeg(truth.R, pose.R) < kTruthDeg &&
            DirectionErrorDeg(truth.Center(), pose.Center()) < kTruthDeg)
          return true;
      }
      return false;
    };
    return prepared;
  };
  return entry;
}

}  // namespace

std::vector<NamedEstimator> TrigravRobustEstimators() {
  std::vector<NamedEstimator> estimators;
  for (const InitialSolver solver : kInitialSolvers) {
    estimators.push_back({InitialSolverName(solver), "raw", RansacDescription(solver),
                          [solver](const ThreeViewObservations& observations, double threshold_px) {
                            RobustThreeViewOptions options;
                            options.solver = solver;
                            options.ransac.max_error = threshold_px;
                            return RobustEstimate(observations, options);
                          }});
  }
  return estimators;
}

std::vector<NamedEstimator> TrigravRefinedEstimators() {
  std::vector<NamedEstimator> estimators;
  for (const InitialSolver solver : kInitialSolvers) {
    estimators.push_back(
        {InitialSolverName(solver), "yaw-only",
         RansacDescription(solver) +
             "; then trigrav::InitializeAndRefine: yaw-only bundle adjustment on the inliers "
             "(Huber 2 px), one re-classification round, 1 thread",
         [solver](const ThreeViewObservations& observations, double threshold_px) {
           InitializeAndRefineOptions options;
           options.robust.solver = solver;
           options.robust.ransac.max_error = threshold_px;
           return RefinedEstimate(observations, options);
         }});
  }
  return estimators;
}

std::vector<NamedMinimalSolver> TrigravMinimalSolvers() {
  using Rays = std::vector<Eigen::Vector3d>;
  return {
      GravityMinimalSolver("3pt",
                           "SolveTrifocal3pt: 3 triplets + each camera's gravity; aligns the rays, "
                           "returns every cheirality-consistent three-view pose, best first",
                           3,
                           [](const Rays& x1, const Rays& x2, const Rays& x3,
                              const Eigen::Vector3d& g1, const Eigen::Vector3d& g2,
                              const Eigen::Vector3d& g3, std::vector<ThreeViewPose>* solutions) {
                             return SolveTrifocal3pt(x1, x2, x3, g1, g2, g3, solutions);
                           }),
      GravityMinimalSolver("4pt",
                           "SolveTrifocal4pt: 4 triplets + each camera's gravity; aligns the rays, "
                           "one three-view pose (linear trifocal + polish)",
                           4,
                           [](const Rays& x1, const Rays& x2, const Rays& x3,
                              const Eigen::Vector3d& g1, const Eigen::Vector3d& g2,
                              const Eigen::Vector3d& g3, std::vector<ThreeViewPose>* solutions) {
                             return SolveTrifocal4pt(x1, x2, x3, g1, g2, g3, solutions);
                           }),
      Essential5ptMinimalSolver(),
  };
}

}  // namespace trigrav::peers
