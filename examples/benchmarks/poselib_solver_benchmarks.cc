// PoseLib's minimal relative-pose solvers on solver_benchmark's scenes (poselib_benchmarks.h).
// PoseLib's CameraPose is cam2_from_cam1 like trigrav's (x_2 ~ R x_1 + t), and its upright solver
// rotates about the y axis, which is gravity in trigrav's aligned frames (conventions.md), so the
// aligned rays go in unchanged.

#include <PoseLib/solvers/relpose_5pt.h>
#include <PoseLib/solvers/relpose_upright_3pt.h>
#include <benchmark/benchmark.h>

#include <array>
#include <string>
#include <vector>

#include "poselib_benchmarks.h"
#include "solver_benchmark_scenes.h"
#include "trigrav/evaluation/pose_errors.h"

namespace trigrav::benchmarks {
namespace {

// True when `truth` is among the solutions (rotation and centre direction within 1e-6 deg).
bool TruthAmong(const CameraPose& truth, const poselib::CameraPoseVector& solutions) {
  for (const poselib::CameraPose& pose : solutions) {
    if (RotationErrorDeg(truth.R, pose.R()) < 1e-6 &&
        DirectionErrorDeg(truth.Center(), pose.center()) < 1e-6) {
      return true;
    }
  }
  return false;
}

// Whether both pairs' true poses are among their solutions.
bool TruthAmongBothPairs(const ThreeViewPose& truth,
                         const poselib::CameraPoseVector& solutions12,
                         const poselib::CameraPoseVector& solutions13) {
  return TruthAmong(truth.cam2_from_cam1, solutions12) &&
         TruthAmong(truth.cam3_from_cam1, solutions13);
}

// Times solve(i, &solutions12, &solutions13) over problems 0..count-1 in turn; truth_found(i, ...)
// says whether problem i's truth is among both pairs' solutions.
template <typename Solve, typename TruthFound>
void RunPairSolverBenchmark(benchmark::State& state,
                            std::size_t count,
                            Solve solve,
                            TruthFound truth_found) {
  poselib::CameraPoseVector solutions12, solutions13;
  solutions12.reserve(16);
  solutions13.reserve(16);
  int found = 0;
  for (std::size_t i = 0; i < count; ++i) {
    solve(i, &solutions12, &solutions13);
    found += truth_found(i, solutions12, solutions13);
  }
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(solve(i++ % count, &solutions12, &solutions13));
    benchmark::ClobberMemory();
  }
  state.counters["truth_found"] = static_cast<double>(found) / count;
}

void BM_Upright3ptTwoPairs(benchmark::State& state) {
  const std::vector<AlignedProblem> problems = MakeProblems(3, 100);
  RunPairSolverBenchmark(
      state, problems.size(),
      [&](std::size_t i, poselib::CameraPoseVector* s12, poselib::CameraPoseVector* s13) {
        const AlignedProblem& p = problems[i];
        return poselib::relpose_upright_3pt(p.x1, p.x2, s12) +
               poselib::relpose_upright_3pt(p.x1, p.x3, s13);
      },
      [&](std::size_t i, const poselib::CameraPoseVector& s12,
          const poselib::CameraPoseVector& s13) {
        return TruthAmongBothPairs(problems[i].ground_truth, s12, s13);
      });
}

void BM_Upright3ptGravityTwoPairs(benchmark::State& state) {
  const std::vector<RawProblem> problems = MakeRawProblems(3, 100);
  RunPairSolverBenchmark(
      state, problems.size(),
      [&](std::size_t i, poselib::CameraPoseVector* s12, poselib::CameraPoseVector* s13) {
        const RawProblem& p = problems[i];
        const auto& g = p.gravity_in_cam;
        return poselib::relpose_upright_3pt(p.rays[0], p.rays[1], g[0], g[1], s12) +
               poselib::relpose_upright_3pt(p.rays[0], p.rays[2], g[0], g[2], s13);
      },
      [&](std::size_t i, const poselib::CameraPoseVector& s12,
          const poselib::CameraPoseVector& s13) {
        return TruthAmongBothPairs(problems[i].ground_truth, s12, s13);
      });
}

// One pair: only `solutions12` is used. relpose_5pt needs unit bearings (with BM_Solver/5pt's
// z = 1 rays it misses the truth in about 40 % of these scenes), so the rays are normalised once,
// outside the timing.
void BM_FivePoint(benchmark::State& state) {
  const std::vector<SyntheticScene> scenes = MakeScenes(5, 100);
  std::vector<std::array<std::vector<Eigen::Vector3d>, 2>> bearings;
  for (const SyntheticScene& scene : scenes) {
    bearings.push_back({scene.rays[0], scene.rays[1]});
    for (std::vector<Eigen::Vector3d>& view : bearings.back()) {
      for (Eigen::Vector3d& ray : view) ray.normalize();
    }
  }
  RunPairSolverBenchmark(
      state, scenes.size(),
      [&](std::size_t i, poselib::CameraPoseVector* s12, poselib::CameraPoseVector*) {
        return poselib::relpose_5pt(bearings[i][0], bearings[i][1], s12);
      },
      [&](std::size_t i, const poselib::CameraPoseVector& s12, const poselib::CameraPoseVector&) {
        return TruthAmong(scenes[i].ground_truth.cam2_from_cam1, s12);
      });
}

}  // namespace

void RegisterPoseLibSolverBenchmarks() {
  benchmark::RegisterBenchmark("BM_Peer/poselib_upright_3pt_two_pairs", BM_Upright3ptTwoPairs);
  benchmark::RegisterBenchmark("BM_Peer/poselib_upright_3pt_gravity_two_pairs",
                               BM_Upright3ptGravityTwoPairs);
  benchmark::RegisterBenchmark("BM_Peer/poselib_5pt", BM_FivePoint);
}

}  // namespace trigrav::benchmarks
