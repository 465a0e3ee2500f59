// Determinism and thread safety: the same seed gives bit-identical results, in repeated calls and
// from several threads at once (no hidden global state: static RNGs, buffers or caches), and a
// different seed gives a different RANSAC trace.

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <cstring>
#include <random>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "trigrav/ba/initialize_and_refine.h"
#include "trigrav/evaluation/synthetic_scene.h"
#include "trigrav/initializers/ransac.h"
#include "trigrav/initializers/robust_three_view.h"

namespace trigrav {
namespace {

// 40 triplets with noise and outliers (by default 0.3 px and 20 %, where every method succeeds).
ThreeViewObservations MakeObservations(std::uint64_t seed,
                                       double noise_px = 0.3,
                                       double outlier_ratio = 0.2) {
  SyntheticSceneOptions options;
  options.num_points = 40;
  options.pixel_noise_px = noise_px;
  options.outlier_ratio = outlier_ratio;
  std::mt19937_64 rng(seed);
  return ToObservations(GenerateSyntheticScene(options, &rng));
}

// At most 200 samples keep the slow methods (7pt-linear, 8pt) fast under the sanitizers.
constexpr int kMaxIterations = 200;

RobustThreeViewOptions RobustOptions(InitialSolver solver, std::uint64_t seed) {
  RobustThreeViewOptions options;
  options.solver = solver;
  options.ransac.max_error = 3.0;
  options.ransac.max_iterations = kMaxIterations;
  options.ransac.seed = seed;
  return options;
}

InitializeAndRefineOptions RefineOptions(InitialSolver solver, std::uint64_t seed) {
  InitializeAndRefineOptions options;
  options.robust = RobustOptions(solver, seed);
  return options;
}

// The bytes of a pose: two poses with equal bytes are bit-identical.
std::string PoseBytes(const ThreeViewPose& pose) {
  std::string bytes;
  for (const CameraPose* camera : {&pose.cam2_from_cam1, &pose.cam3_from_cam1}) {
    bytes.append(reinterpret_cast<const char*>(camera->R.data()), sizeof(double) * 9);
    bytes.append(reinterpret_cast<const char*>(camera->t.data()), sizeof(double) * 3);
  }
  return bytes;
}

bool BitwiseEqual(const ThreeViewPose& a, const ThreeViewPose& b) {
  return PoseBytes(a) == PoseBytes(b);
}

bool BitwiseEqual(double a, double b) { return std::memcmp(&a, &b, sizeof(double)) == 0; }

// Every field of a robust estimate (all of them are deterministic).
bool SameStatistics(const RansacStatistics& a, const RansacStatistics& b) {
  return a.num_inliers == b.num_inliers && a.iterations == b.iterations &&
         a.num_models_scored == b.num_models_scored &&
         a.num_local_optimizations == b.num_local_optimizations &&
         BitwiseEqual(a.msac_cost, b.msac_cost);
}

bool SameEstimate(const RobustThreeViewEstimate& a, const RobustThreeViewEstimate& b) {
  return a.success == b.success && a.message == b.message && BitwiseEqual(a.pose, b.pose) &&
         a.inliers == b.inliers && SameStatistics(a.ransac, b.ransac);
}

bool SameRefinement(const ThreeViewRefinement& a, const ThreeViewRefinement& b) {
  bool same_points = a.points_in_cam1.size() == b.points_in_cam1.size();
  for (std::size_t i = 0; same_points && i < a.points_in_cam1.size(); ++i) {
    same_points = std::memcmp(a.points_in_cam1[i].data(), b.points_in_cam1[i].data(),
                              3 * sizeof(double)) == 0;
  }
  return same_points && BitwiseEqual(a.pose, b.pose) && a.triplets == b.triplets &&
         a.summary.success == b.summary.success && a.summary.message == b.summary.message &&
         a.summary.num_points == b.summary.num_points &&
         a.summary.num_residual_blocks == b.summary.num_residual_blocks &&
         BitwiseEqual(a.summary.InitialCost(), b.summary.InitialCost()) &&
         BitwiseEqual(a.summary.FinalCost(), b.summary.FinalCost()) &&
         a.summary.Iterations() == b.summary.Iterations();
}

// Everything of an initialise-and-refine estimate except the wall times.
bool SameEstimate(const ThreeViewEstimate& a, const ThreeViewEstimate& b) {
  return a.success == b.success && a.message == b.message &&
         BitwiseEqual(a.robust.pose, b.robust.pose) && BitwiseEqual(a.refined, b.refined) &&
         a.inliers == b.inliers && a.num_inliers == b.num_inliers &&
         a.robust.inliers == b.robust.inliers && SameStatistics(a.robust.ransac, b.robust.ransac) &&
         a.refinement_runs == b.refinement_runs && SameRefinement(a.refinement, b.refinement);
}

class DeterminismEveryMethod : public ::testing::TestWithParam<InitialSolver> {};

// Same seed, same data: bit-identical, also after calls with other data, methods and seeds in
// between (state left behind by one call would change the next).
TEST_P(DeterminismEveryMethod, SameSeedGivesBitIdenticalEstimates) {
  const ThreeViewObservations observations = MakeObservations(11);
  const RobustThreeViewOptions options = RobustOptions(GetParam(), 5);
  const RobustThreeViewEstimate first = EstimateThreeViewPoseRobust(observations, options);
  ASSERT_TRUE(first.success) << first.message;
  for (const InitialSolver other : kInitialSolvers) {
    EstimateThreeViewPoseRobust(MakeObservations(12), RobustOptions(other, 6));
    EXPECT_TRUE(SameEstimate(first, EstimateThreeViewPoseRobust(observations, options)))
        << "after a call with " << InitialSolverName(other);
  }
}

// A different seed draws different samples. Local optimisation re-estimates from the inliers alone,
// so with it every seed may end on the same bits; without it, and with 5 samples, the estimate is
// the best of 5 minimal models, which only the same samples reproduce: over 6 seeds at least 4
// distinct poses (equal samples from two seeds are rare). Fails if the seed is ignored. Without
// outliers and with 0.1 px noise every minimal model of every method explains its sample. A minimal
// model lies off its inliers' optimum, which the verdict weighs unless a refinement follows: here
// one is declared, so that every seed's pose is returned.
TEST_P(DeterminismEveryMethod, DifferentSeedsGiveDifferentTraces) {
  const ThreeViewObservations observations = MakeObservations(21, 0.1, 0.0);
  std::set<std::string> poses;
  for (std::uint64_t seed = 0; seed < 6; ++seed) {
    RobustThreeViewOptions options = RobustOptions(GetParam(), seed);
    options.refined_afterwards = true;
    options.ransac.local_optimization = false;
    options.ransac.min_iterations = options.ransac.max_iterations = 5;
    const RobustThreeViewEstimate estimate = EstimateThreeViewPoseRobust(observations, options);
    ASSERT_TRUE(estimate.success) << estimate.message;
    EXPECT_EQ(estimate.ransac.iterations, 5);
    poses.insert(PoseBytes(estimate.pose));
  }
  EXPECT_GE(poses.size(), 4u);
}

TEST_P(DeterminismEveryMethod, InitializeAndRefineIsBitIdentical) {
  const ThreeViewObservations observations = MakeObservations(31);
  const InitializeAndRefineOptions options = RefineOptions(GetParam(), 9);
  const ThreeViewEstimate first = InitializeAndRefine(observations, options);
  ASSERT_TRUE(first.success) << first.message;
  ASSERT_GE(first.refinement_runs, 1) << first.message;
  EXPECT_TRUE(SameEstimate(first, InitializeAndRefine(observations, options)));
}

INSTANTIATE_TEST_SUITE_P(AllSolvers,
                         DeterminismEveryMethod,
                         ::testing::ValuesIn(kInitialSolvers),
                         [](const ::testing::TestParamInfo<InitialSolver>& info) {
                           std::string name = InitialSolverName(info.param);
                           for (char& c : name) {
                             if (c == '-') c = '_';
                           }
                           return "m" + name;
                         });

// The RANSAC template itself: the sample sequence is a function of the seed alone.
struct RecordingEstimator {
  using Model = int;
  static constexpr int kSampleSize = 3;
  std::size_t num_data() const { return 50; }
  void generate_models(const std::array<int, kSampleSize>& sample,
                       std::vector<Model>* models) const {
    samples->push_back(sample);
    models->push_back(sample[0]);
  }
  void errors(const Model& model,
              std::size_t begin,
              std::size_t end,
              double /*cap*/,
              double* errors) const {
    for (std::size_t i = begin; i < end; ++i) {
      errors[i - begin] = static_cast<int>(i) % 5 == model % 5 ? 0.0 : 10.0;
    }
  }
  bool refine_model(const std::vector<int>&, Model*) const { return false; }
  std::vector<std::array<int, kSampleSize>>* samples;
};

std::vector<std::array<int, 3>> SamplesDrawn(std::uint64_t seed) {
  std::vector<std::array<int, 3>> samples;
  RansacOptions options;
  options.seed = seed;
  options.min_iterations = options.max_iterations = 40;
  Ransac(RecordingEstimator{&samples}, options);
  return samples;
}

TEST(RansacDeterminism, SampleSequenceDependsOnTheSeedOnly) {
  const std::vector<std::array<int, 3>> samples = SamplesDrawn(3);
  ASSERT_EQ(samples.size(), 40u);
  EXPECT_EQ(samples, SamplesDrawn(3));
  EXPECT_NE(samples, SamplesDrawn(4));
}

// Several threads at once, each with its own copy of the inputs, give exactly the serial results:
// every (scene, method) job of a robust estimate and of initialise-and-refine, run by 4 threads
// concurrently, each thread starting at a different job.
TEST(ThreadDeterminism, ConcurrentEstimatesEqualSerialOnes) {
  struct Job {
    ThreeViewObservations observations;
    InitializeAndRefineOptions options;
  };
  std::vector<Job> jobs;
  for (std::uint64_t scene = 0; scene < 2; ++scene) {
    for (const InitialSolver solver : kInitialSolvers) {
      jobs.push_back({MakeObservations(100 + scene), RefineOptions(solver, scene)});
    }
  }
  struct Result {
    RobustThreeViewEstimate robust;
    ThreeViewEstimate refined;
  };
  auto run = [](const Job& job) {
    const RobustThreeViewOptions robust = job.options.robust;
    return Result{EstimateThreeViewPoseRobust(job.observations, robust),
                  InitializeAndRefine(job.observations, job.options)};
  };
  std::vector<Result> serial;
  for (const Job& job : jobs) serial.push_back(run(job));

  constexpr int kThreads = 4;
  std::vector<std::vector<Result>> concurrent(kThreads, std::vector<Result>(jobs.size()));
  std::vector<std::thread> threads;
  for (int t = 0; t < kThreads; ++t) {
    threads.emplace_back([&, t] {
      const std::vector<Job> own_jobs = jobs;  // each thread its own inputs
      for (std::size_t i = 0; i < own_jobs.size(); ++i) {
        const std::size_t j = (i + t * own_jobs.size() / kThreads) % own_jobs.size();
        concurrent[t][j] = run(own_jobs[j]);
      }
    });
  }
  for (std::thread& thread : threads) thread.join();

  // Failures (the verdict refuses a few of the small jobs) must be equal too; most jobs succeed.
  int successes = 0;
  for (const Result& result : serial) successes += result.robust.success;
  EXPECT_GE(successes, static_cast<int>(3 * jobs.size() / 4));
  for (int t = 0; t < kThreads; ++t) {
    for (std::size_t j = 0; j < jobs.size(); ++j) {
      EXPECT_TRUE(SameEstimate(serial[j].robust, concurrent[t][j].robust))
          << "thread " << t << ", job " << j;
      EXPECT_TRUE(SameEstimate(serial[j].refined, concurrent[t][j].refined))
          << "thread " << t << ", job " << j;
    }
  }
}

}  // namespace
}  // namespace trigrav
