// Time per call of the minimal solvers on 100 pre-generated noise-free scenes (seed 2026).
//   BM_Solver/<method>    every solver of kInitialSolvers at its minimal sample: the gravity-aware
//                         and trifocal ones on rays already in gravity-aligned frames (only the
//                         solver is timed), the two-view ones (5pt, 8pt) on pair (1,2) alone;
//   BM_Solver/3pt-gravity the gravity overload of the 3-point solver on the same scenes' raw rays
//                         and gravity directions (alignment and back-transform timed too);
//   BM_Solver/<method>/20 the linear solvers (7pt-linear, 8pt) with 20 triplets;
//   BM_Solver/4pt-unpolished, BM_Solver/4pt-closed-form  4-point variants (derivations.md
//   section 4.3 without the
//                         polish; the paper's closed forms c8-c11), as in minimal_solver_accuracy.
// Counter "found": the fraction of the scenes whose best-ranked solution is within 1e-6 deg of the
// truth (two-view solvers, whose solutions are not ranked: with the truth among the solutions).
// Built with OpenGV (examples/peers/), BM_Peer/<name> times its five-point solvers on the same kind
// of scenes; their counter "truth_found" is the fraction of scenes with the true essential matrix
// among the solutions (they return essential matrices, not poses). Built with PoseLib,
// BM_Peer/poselib_<solver> times its upright 3-point solver on the pairs (1,2) and (1,3) of the
// same scenes as BM_Solver/3pt (and its gravity wrapper on BM_Solver/3pt-gravity's) and its
// five-point solver on BM_Solver/5pt's pair (poselib_benchmarks.h).
//
//   solver_benchmark --benchmark_repetitions=5 --benchmark_report_aggregates_only=true

#include <benchmark/benchmark.h>

#include <algorithm>
#include <array>
#include <string>
#include <vector>

#ifdef TRIGRAV_WITH_PEERS
#include "peer_estimators.h"
#endif

#include "poselib_benchmarks.h"
#include "solver_benchmark_scenes.h"
#include "trigrav/evaluation/pose_errors.h"
#include "trigrav/evaluation/synthetic_scene.h"
#include "trigrav/initializers/essential_5pt.h"
#include "trigrav/initializers/essential_8pt.h"
#include "trigrav/initializers/initial_solver.h"
#include "trigrav/initializers/trifocal_3pt.h"
#include "trigrav/initializers/trifocal_4pt.h"
#include "trigrav/initializers/trifocal_linear.h"

namespace {

using trigrav::ThreeViewPose;

using trigrav::benchmarks::AlignedProblem;
using trigrav::benchmarks::MakeProblems;
using trigrav::benchmarks::MakeRawProblems;
using trigrav::benchmarks::MakeScenes;
using trigrav::benchmarks::RawProblem;

// Runs `solve` over the problem pool; reports how often the first solution is the truth.
template <typename Solver>
void RunSolverBenchmark(benchmark::State& state, int num_points, Solver solve) {
  const std::vector<AlignedProblem> problems = MakeProblems(num_points, 100);
  std::vector<ThreeViewPose> solutions;
  solutions.reserve(64);
  int found = 0;
  for (const AlignedProblem& p : problems) {
    if (solve(p.x1, p.x2, p.x3, &solutions) > 0) {
      const trigrav::ThreeViewPoseErrors e =
          trigrav::ComputeThreeViewPoseErrors(p.ground_truth, solutions[0]);
      found += e.MaxAngleDeg() < 1e-6;
    }
  }
  std::size_t i = 0;
  for (auto _ : state) {
    const AlignedProblem& p = problems[i++ % problems.size()];
    benchmark::DoNotOptimize(solve(p.x1, p.x2, p.x3, &solutions));
    benchmark::ClobberMemory();
  }
  state.counters["found"] = static_cast<double>(found) / problems.size();
}

// RunSolverBenchmark for a gravity overload: raw rays and each camera's gravity of the same scenes.
template <typename Solver>
void RunGravitySolverBenchmark(benchmark::State& state, int num_points, Solver solve) {
  const std::vector<RawProblem> problems = MakeRawProblems(num_points, 100);
  std::vector<ThreeViewPose> solutions;
  solutions.reserve(64);
  auto run = [&](const RawProblem& p) {
    return solve(p.rays[0], p.rays[1], p.rays[2], p.gravity_in_cam[0], p.gravity_in_cam[1],
                 p.gravity_in_cam[2], &solutions);
  };
  int found = 0;
  for (const RawProblem& p : problems) {
    if (run(p) > 0) {
      const trigrav::ThreeViewPoseErrors e =
          trigrav::ComputeThreeViewPoseErrors(p.ground_truth, solutions[0]);
      found += e.MaxAngleDeg() < 1e-6;
    }
  }
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(run(problems[i++ % problems.size()]));
    benchmark::ClobberMemory();
  }
  state.counters["found"] = static_cast<double>(found) / problems.size();
}

// Two-view counterpart of RunSolverBenchmark: raw rays of views 1 and 2 (no gravity alignment);
// "found" = fraction of the scenes with the truth (1e-6 deg) among the solutions (they are not
// ranked).
template <typename Solver>
void RunTwoViewSolverBenchmark(benchmark::State& state, int num_points, Solver solve) {
  const std::vector<trigrav::SyntheticScene> scenes = MakeScenes(num_points, 100);
  std::vector<trigrav::CameraPose> solutions;
  solutions.reserve(16);
  int found = 0;
  for (const trigrav::SyntheticScene& scene : scenes) {
    solve(scene.rays[0], scene.rays[1], &solutions);
    const trigrav::CameraPose& truth = scene.ground_truth.cam2_from_cam1;
    for (const trigrav::CameraPose& pose : solutions) {
      if (trigrav::RotationErrorDeg(truth.R, pose.R) < 1e-6 &&
          trigrav::DirectionErrorDeg(truth.Center(), pose.Center()) < 1e-6) {
        ++found;
        break;
      }
    }
  }
  std::size_t i = 0;
  for (auto _ : state) {
    const trigrav::SyntheticScene& scene = scenes[i++ % scenes.size()];
    benchmark::DoNotOptimize(solve(scene.rays[0], scene.rays[1], &solutions));
    benchmark::ClobberMemory();
  }
  state.counters["found"] = static_cast<double>(found) / scenes.size();
}

// Gravity-aware and trifocal solvers on aligned rays.
template <typename Solver>
void RegisterSolver(const std::string& name, int num_points, Solver solve) {
  benchmark::RegisterBenchmark(("BM_Solver/" + name).c_str(),
                               [num_points, solve](benchmark::State& state) {
                                 RunSolverBenchmark(state, num_points, solve);
                               });
}

// Gravity overloads on raw rays.
template <typename Solver>
void RegisterGravitySolver(const std::string& name, int num_points, Solver solve) {
  benchmark::RegisterBenchmark(("BM_Solver/" + name).c_str(),
                               [num_points, solve](benchmark::State& state) {
                                 RunGravitySolverBenchmark(state, num_points, solve);
                               });
}

// Two-view solvers on pair (1,2).
template <typename Solver>
void RegisterTwoViewSolver(const std::string& name, int num_points, Solver solve) {
  benchmark::RegisterBenchmark(("BM_Solver/" + name).c_str(),
                               [num_points, solve](benchmark::State& state) {
                                 RunTwoViewSolverBenchmark(state, num_points, solve);
                               });
}

void RegisterSolverBenchmarks() {
  using trigrav::InitialSolver;
  const auto trifocal_3pt = [](const auto& x1, const auto& x2, const auto& x3, auto* solutions) {
    return trigrav::SolveTrifocal3pt(x1, x2, x3, solutions);
  };
  const auto trifocal_3pt_gravity = [](const auto& x1, const auto& x2, const auto& x3,
                                       const auto& g1, const auto& g2, const auto& g3,
                                       auto* solutions) {
    return trigrav::SolveTrifocal3pt(x1, x2, x3, g1, g2, g3, solutions);
  };
  const auto trifocal_3pt_sextic = [](const auto& x1, const auto& x2, const auto& x3,
                                      auto* solutions) {
    return trigrav::SolveTrifocal3ptSextic(x1, x2, x3, solutions);
  };
  const auto trifocal_4pt = [](const auto& x1, const auto& x2, const auto& x3, auto* solutions) {
    return trigrav::SolveTrifocal4pt(x1, x2, x3, solutions);
  };
  const auto trifocal_linear = [](const auto& x1, const auto& x2, const auto& x3, auto* solutions) {
    return trigrav::SolveTrifocalLinear(x1, x2, x3, solutions);
  };
  const auto essential_5pt = [](const auto& x1, const auto& x2, auto* solutions) {
    return trigrav::SolveEssential5pt(x1, x2, solutions);
  };
  const auto essential_8pt = [](const auto& x1, const auto& x2, auto* solutions) {
    return trigrav::SolveEssential8pt(x1, x2, solutions);
  };
  for (const InitialSolver solver : trigrav::kInitialSolvers) {
    const std::string name = trigrav::InitialSolverName(solver);
    const int n = trigrav::MinimalSampleSize(solver);
    switch (solver) {
      case InitialSolver::kTrifocal3pt:
        RegisterSolver(name, n, trifocal_3pt);
        RegisterGravitySolver(name + "-gravity", n, trifocal_3pt_gravity);
        break;
      case InitialSolver::kTrifocal3ptSextic:
        RegisterSolver(name, n, trifocal_3pt_sextic);
        break;
      case InitialSolver::kTrifocal4pt:
        RegisterSolver(name, n, trifocal_4pt);
        break;
      case InitialSolver::kTrifocalLinear:
        RegisterSolver(name, n, trifocal_linear);
        RegisterSolver(name + "/20", 20, trifocal_linear);
        break;
      case InitialSolver::kEssential5pt:
        RegisterTwoViewSolver(name, n, essential_5pt);
        break;
      case InitialSolver::kEssential8pt:
        RegisterTwoViewSolver(name, n, essential_8pt);
        RegisterTwoViewSolver(name + "/20", 20, essential_8pt);
        break;
    }
  }
  // 4-point variants: the enforcement with the re-solve and one polish step (derivations.md
  // sections 4.3-4.5, the default's pipeline for more than 4 triplets), the same without the
  // polish, and the paper's closed forms (no enforcement, eqs c8-c11, no translation re-solve).
  trigrav::Trifocal4ptOptions enforced;
  enforced.recovery = trigrav::Trifocal4ptRecovery::kEnforced;
  enforced.polish_iterations = 1;
  trigrav::Trifocal4ptOptions unpolished = enforced;
  unpolished.polish_iterations = 0;
  for (const auto& [name, options] :
       {std::pair{"4pt-enforced", enforced}, std::pair{"4pt-unpolished", unpolished}}) {
    RegisterSolver(name, 4,
                   [options](const auto& x1, const auto& x2, const auto& x3, auto* solutions) {
                     return trigrav::SolveTrifocal4pt(x1, x2, x3, options, solutions);
                   });
  }
  trigrav::Trifocal4ptOptions closed_form;
  closed_form.recovery = trigrav::Trifocal4ptRecovery::kPaperClosedForm;
  closed_form.resolve_translations = false;
  closed_form.polish_iterations = 0;
  RegisterSolver("4pt-closed-form", 4,
                 [closed_form](const auto& x1, const auto& x2, const auto& x3, auto* solutions) {
                   return trigrav::SolveTrifocal4pt(x1, x2, x3, closed_form, solutions);
                 });
}

#ifdef TRIGRAV_WITH_PEERS
// One benchmark per peer minimal solver, on 100 scenes of 5 triplets (seed 2026, like the others).
void RegisterPeerBenchmarks() {
  static const std::vector<trigrav::peers::MinimalProblem> problems =
      trigrav::peers::MakeMinimalProblems(100, 2026);
  for (const trigrav::peers::NamedMinimalSolver& solver : trigrav::peers::PeerMinimalSolvers()) {
    std::string name = "BM_Peer/" + solver.name;  // "BM_Peer/opengv_fivept_stewenius"
    std::replace(name.begin(), name.end(), ' ', '_');
    benchmark::RegisterBenchmark(name.c_str(), [solver](benchmark::State& state) {
      const trigrav::peers::PreparedMinimalSolver prepared = solver.prepare(problems);
      int found = 0;
      for (std::size_t i = 0; i < problems.size(); ++i) found += prepared.truth_found(i);
      std::size_t i = 0;
      for (auto _ : state) benchmark::DoNotOptimize(prepared.solve(i++ % problems.size()));
      state.counters["truth_found"] = static_cast<double>(found) / problems.size();
    });
  }
}
#endif

}  // namespace

int main(int argc, char** argv) {
  RegisterSolverBenchmarks();
#ifdef TRIGRAV_WITH_PEERS
  RegisterPeerBenchmarks();
#endif
#ifdef TRIGRAV_WITH_POSELIB
  trigrav::benchmarks::RegisterPoseLibSolverBenchmarks();
#endif
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
