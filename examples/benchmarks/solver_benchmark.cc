// Time per call of the minimal solvers on pre-generated noise-free scenes (aligned rays, so only the
// solver is timed). Counter "found" = fraction of the scenes whose best-ranked solution is within
// 1e-6 deg of the truth. Built with a peer library (examples/peers/), it also times OpenGV's
// five-point solvers (BM_Peer/<name>) on the same kind of scenes; their counter "truth_found" is the
// fraction of scenes with the true essential matrix among the solutions (they return essential
// matrices, not poses). Run: ./build/examples/solver_benchmark

#include <algorithm>
#include <random>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#ifdef TRIGRAV_WITH_PEERS
#include "peer_estimators.h"
#endif

#include "trigrav/initializers/essential_5pt.h"
#include "trigrav/initializers/essential_8pt.h"
#include "trigrav/initializers/gravity.h"
#include "trigrav/evaluation/pose_errors.h"
#include "trigrav/evaluation/synthetic_scene.h"
#include "trigrav/initializers/trifocal_3pt.h"
#include "trigrav/initializers/trifocal_4pt.h"
#include "trigrav/initializers/trifocal_linear.h"

namespace {

using trigrav::ThreeViewPose;

// A scene's rays in gravity-aligned frames and its ground truth in the same frames.
struct AlignedProblem {
  std::vector<Eigen::Vector3d> x1, x2, x3;
  ThreeViewPose ground_truth;
};

std::vector<AlignedProblem> MakeProblems(int num_points, int count) {
  std::mt19937_64 rng(2026);
  trigrav::SyntheticSceneOptions options;
  options.num_points = num_points;
  std::vector<AlignedProblem> problems;
  for (int i = 0; i < count; ++i) {
    const trigrav::SyntheticScene scene = trigrav::GenerateSyntheticScene(options, &rng);
    const auto& align = scene.gravity_alignment_true;
    AlignedProblem problem;
    problem.x1 = trigrav::AlignRays(align[0], scene.rays[0]);
    problem.x2 = trigrav::AlignRays(align[1], scene.rays[1]);
    problem.x3 = trigrav::AlignRays(align[2], scene.rays[2]);
    // Aligned ground truth: R = A_k R~ A_1^T, t = A_k t~ (the inverse of UnalignPose).
    problem.ground_truth = trigrav::UnalignThreeViewPose(scene.ground_truth, align[0].transpose(),
                                                         align[1].transpose(), align[2].transpose());
    problems.push_back(problem);
  }
  return problems;
}

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

void BM_Trifocal4pt(benchmark::State& state) {
  RunSolverBenchmark(state, 4,
                     [](const auto& x1, const auto& x2, const auto& x3, auto* solutions) {
                       return trigrav::SolveTrifocal4pt(x1, x2, x3, solutions);
                     });
}
BENCHMARK(BM_Trifocal4pt);

// The math note's recommended pipeline: trigrav's default without the polish step.
void BM_Trifocal4ptNoPolish(benchmark::State& state) {
  trigrav::Trifocal4ptOptions options;
  options.polish_iterations = 0;
  RunSolverBenchmark(state, 4,
                     [&options](const auto& x1, const auto& x2, const auto& x3, auto* solutions) {
                       return trigrav::SolveTrifocal4pt(x1, x2, x3, options, solutions);
                     });
}
BENCHMARK(BM_Trifocal4ptNoPolish);

// The paper's own 4-point variant: no enforcement, eqs c8-c11, no translation re-solve.
void BM_Trifocal4ptPaper(benchmark::State& state) {
  trigrav::Trifocal4ptOptions options;
  options.recovery = trigrav::Trifocal4ptRecovery::kPaperClosedForm;
  options.resolve_translations = false;
  options.polish_iterations = 0;
  RunSolverBenchmark(state, 4,
                     [&options](const auto& x1, const auto& x2, const auto& x3, auto* solutions) {
                       return trigrav::SolveTrifocal4pt(x1, x2, x3, options, solutions);
                     });
}
BENCHMARK(BM_Trifocal4ptPaper);

// The default 3-point solver (decoupled, math note 4.4); all candidates, best first.
void BM_Trifocal3pt(benchmark::State& state) {
  RunSolverBenchmark(state, 3,
                     [](const auto& x1, const auto& x2, const auto& x3, auto* solutions) {
                       return trigrav::SolveTrifocal3pt(x1, x2, x3, solutions);
                     });
}
BENCHMARK(BM_Trifocal3pt);

// The paper's joint 3-point system (cores C_12 = C_13 = 0, a sextic; math note 4.3).
void BM_Trifocal3ptSextic(benchmark::State& state) {
  RunSolverBenchmark(state, 3,
                     [](const auto& x1, const auto& x2, const auto& x3, auto* solutions) {
                       return trigrav::SolveTrifocal3ptSextic(x1, x2, x3, solutions);
                     });
}
BENCHMARK(BM_Trifocal3ptSextic);

// Two-view counterpart of RunSolverBenchmark: raw rays of views 1 and 2 (no gravity alignment);
// "found" = fraction of the scenes with the truth (1e-6 deg) among the solutions (they are not ranked).
template <typename Solver>
void RunTwoViewSolverBenchmark(benchmark::State& state, int num_points, Solver solve) {
  std::mt19937_64 rng(2026);
  trigrav::SyntheticSceneOptions options;
  options.num_points = num_points;
  std::vector<trigrav::SyntheticScene> scenes;
  for (int i = 0; i < 100; ++i) scenes.push_back(trigrav::GenerateSyntheticScene(options, &rng));
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

void BM_Essential5pt(benchmark::State& state) {
  RunTwoViewSolverBenchmark(state, 5, [](const auto& x1, const auto& x2, auto* solutions) {
    return trigrav::SolveEssential5pt(x1, x2, solutions);
  });
}
BENCHMARK(BM_Essential5pt);

// Normalised 8-point with 8 and with 20 correspondences.
void BM_Essential8pt(benchmark::State& state) {
  RunTwoViewSolverBenchmark(state, static_cast<int>(state.range(0)),
                            [](const auto& x1, const auto& x2, auto* solutions) {
                              return trigrav::SolveEssential8pt(x1, x2, solutions);
                            });
}
BENCHMARK(BM_Essential8pt)->Arg(8)->Arg(20);

// Normalised linear trifocal tensor (general rotations) with 7 and with 20 triplets.
void BM_TrifocalLinear(benchmark::State& state) {
  RunSolverBenchmark(state, static_cast<int>(state.range(0)),
                     [](const auto& x1, const auto& x2, const auto& x3, auto* solutions) {
                       return trigrav::SolveTrifocalLinear(x1, x2, x3, solutions);
                     });
}
BENCHMARK(BM_TrifocalLinear)->Arg(7)->Arg(20);

#ifdef TRIGRAV_WITH_PEERS
// One benchmark per peer minimal solver, on 100 scenes of 5 triplets (seed 2026, like the others).
void RegisterPeerBenchmarks() {
  static const std::vector<trigrav::peers::MinimalProblem> problems =
      trigrav::peers::MakeMinimalProblems(100, 2026);
  for (const trigrav::peers::NamedMinimalSolver& solver : trigrav::peers::PeerMinimalSolvers()) {
    std::string name = "BM_Peer/" + solver.name;  // "BM_Peer/opengv_fivept_stewenius"
    std::replace(name.begin(), name.end(), ' ', '_');
    benchmark::RegisterBenchmark(name.c_str(),
                                 [solver](benchmark::State& state) {
                                   const trigrav::peers::PreparedMinimalSolver prepared =
                                       solver.prepare(problems);
                                   int found = 0;
                                   for (std::size_t i = 0; i < problems.size(); ++i)
                                     found += prepared.truth_found(i);
                                   std::size_t i = 0;
                                   for (auto _ : state)
                                     benchmark::DoNotOptimize(prepared.solve(i++ % problems.size()));
                                   state.counters["truth_found"] =
                                       static_cast<double>(found) / problems.size();
                                 });
  }
}
#endif

}  // namespace

int main(int argc, char** argv) {
#ifdef TRIGRAV_WITH_PEERS
  RegisterPeerBenchmarks();
#endif
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
