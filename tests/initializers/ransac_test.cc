#include "trigrav/initializers/ransac.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace trigrav {
namespace {

// Robust 1-D location: the model is a number, one datum is a minimal sample, refinement takes the
// mean of the inliers. Small enough to check the loop itself exactly.
class LocationEstimator {
 public:
  using Model = double;
  static constexpr int kSampleSize = 1;
  explicit LocationEstimator(std::vector<double> data) : data_(std::move(data)) {}
  std::size_t num_data() const { return data_.size(); }
  void generate_models(const std::array<int, 1>& sample, std::vector<Model>* models) const {
    models->push_back(data_[sample[0]]);
  }
  // Exact errors; with `beyond_cap`, each error above the cap is replaced by the smallest double
  // above it, as the Estimator concept allows.
  void errors(
      const Model& model, std::size_t begin, std::size_t end, double cap, double* errors) const {
    for (std::size_t i = begin; i < end; ++i) {
      const double e = std::abs(data_[i] - model);
      errors[i - begin] =
          beyond_cap_ && e > cap ? std::nextafter(cap, std::numeric_limits<double>::infinity()) : e;
    }
  }
  void set_beyond_cap(bool beyond_cap) { beyond_cap_ = beyond_cap; }
  bool refine_model(const std::vector<int>& inliers, Model* model) const {
    double sum = 0.0;
    for (const int i : inliers) sum += data_[i];
    *model = sum / inliers.size();
    return true;
  }

 private:
  std::vector<double> data_;
  bool beyond_cap_ = false;
};

std::vector<double> Data(int inliers, int outliers, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(5.0, 0.1);
  std::uniform_real_distribution<double> uniform(-100.0, 100.0);
  std::vector<double> data;
  for (int i = 0; i < inliers; ++i) data.push_back(noise(rng));
  for (int i = 0; i < outliers; ++i) data.push_back(uniform(rng));
  return data;
}

// Errors above the cap (the largest local-optimisation threshold) are not needed exactly: the
// smallest values above it give the same report, bit for bit, as the exact errors.
TEST(Ransac, ErrorsAboveTheCapChangeNothing) {
  for (const double multiplier : {1.0, 3.0}) {
    LocationEstimator estimator(Data(300, 700, 2));
    RansacOptions options;
    options.max_error = 0.5;
    options.local_optimization_threshold_multiplier = multiplier;
    options.min_iterations = 50;
    const RansacReport<double> exact = Ransac(estimator, options);
    estimator.set_beyond_cap(true);
    const RansacReport<double> capped = Ransac(estimator, options);
    ASSERT_TRUE(exact.success);
    EXPECT_GT(exact.statistics.num_local_optimizations, 0);
    EXPECT_EQ(capped.model, exact.model);
    EXPECT_EQ(capped.inlier_mask, exact.inlier_mask);
    EXPECT_EQ(capped.statistics.msac_cost, exact.statistics.msac_cost);
    EXPECT_EQ(capped.statistics.num_models_scored, exact.statistics.num_models_scored);
    EXPECT_EQ(capped.statistics.num_local_optimizations, exact.statistics.num_local_optimizations);
    EXPECT_EQ(capped.statistics.iterations, exact.statistics.iterations);
  }
}

TEST(Ransac, FindsTheInlierModelAndMask) {
  const LocationEstimator estimator(Data(300, 700, 1));
  RansacOptions options;
  options.max_error = 0.5;
  const RansacReport<double> report = Ransac(estimator, options);
  ASSERT_TRUE(report.success) << report.message;
  EXPECT_NEAR(report.model, 5.0, 0.03);
  int true_inliers_found = 0, false_inliers = 0;
  for (int i = 0; i < 1000; ++i) {
    true_inliers_found += i < 300 && report.inlier_mask[i];
    false_inliers += i >= 300 && report.inlier_mask[i];
  }
  EXPECT_GE(true_inliers_found, 295);
  EXPECT_LE(false_inliers, 5);
  EXPECT_EQ(report.statistics.num_inliers, true_inliers_found + false_inliers);
  EXPECT_GT(report.statistics.num_local_optimizations, 0);
}

TEST(Ransac, StopsAdaptively) {
  RansacOptions options;
  options.max_error = 0.5;
  options.min_iterations = 0;
  // 90 % inliers, s = 1: log(1e-4) / log(0.1) = 4 samples suffice; 30 % need 26.
  const RansacReport<double> easy = Ransac(LocationEstimator(Data(900, 100, 2)), options);
  const RansacReport<double> hard = Ransac(LocationEstimator(Data(300, 700, 2)), options);
  EXPECT_LE(easy.statistics.iterations, 8);
  EXPECT_GE(hard.statistics.iterations, 20);
  EXPECT_LE(hard.statistics.iterations, 60);
  options.min_iterations = 50;
  EXPECT_EQ(Ransac(LocationEstimator(Data(900, 100, 2)), options).statistics.iterations, 50);
  options.max_iterations = 60;
  options.max_error = 1e-9;  // nothing agrees: without the floor, runs to the cap
  options.min_inlier_ratio = 0.0;
  EXPECT_EQ(Ransac(LocationEstimator(Data(300, 700, 2)), options).statistics.iterations, 60);
}

TEST(Ransac, RequiredIterationsIsSafeForTinyInlierRatios) {
  EXPECT_EQ(internal::RequiredIterations(1.0, 8, 0.99), 0);
  EXPECT_EQ(internal::RequiredIterations(0.0, 3, 0.99), std::numeric_limits<int>::max());
  // 1 inlier of 200 with an 8-point sample: w^s = 4e-19 must not round to "no iterations needed".
  EXPECT_EQ(internal::RequiredIterations(0.005, 8, 0.9999), std::numeric_limits<int>::max());
  EXPECT_EQ(internal::RequiredIterations(0.5, 3, 0.99), 35);  // log(0.01) / log(7/8) = 34.5
}

TEST(Ransac, SameSeedSameResultOtherSeedOtherSamples) {
  const LocationEstimator estimator(Data(300, 700, 3));
  RansacOptions options;
  options.max_error = 0.5;
  options.local_optimization = false;
  options.seed = 7;
  const RansacReport<double> a = Ransac(estimator, options);
  const RansacReport<double> b = Ransac(estimator, options);
  EXPECT_EQ(a.model, b.model);
  EXPECT_EQ(a.inlier_mask, b.inlier_mask);
  EXPECT_EQ(a.statistics.iterations, b.statistics.iterations);
  options.seed = 8;
  EXPECT_NE(Ransac(estimator, options).model, a.model);
}

// Below the floor: a failure, after the samples that would have found a model at the floor (s = 1:
// log(1e-4) / log(3/4) = 32.02, so 33 > min_iterations) instead of max_iterations.
TEST(Ransac, InlierRatioFloorFailsAndStopsEarly) {
  RansacOptions options;
  options.max_error = 0.5;
  for (const auto& [inliers, outliers] : {std::pair{200, 800}, std::pair{0, 1000}}) {
    const RansacReport<double> report =
        Ransac(LocationEstimator(Data(inliers, outliers, 5)), options);
    EXPECT_FALSE(report.success);
    EXPECT_NE(report.message.find("min_inlier_ratio"), std::string::npos) << report.message;
    EXPECT_EQ(report.statistics.iterations, 33);
    EXPECT_TRUE(report.inlier_mask.empty());
    EXPECT_LT(report.statistics.num_inliers, 250);
  }
  EXPECT_EQ(internal::RequiredIterations(0.25, 1, 0.9999), 33);
  // The floor off: the same data run until the few chance agreements of uniform data end the
  // adaptive stop (pure outliers), or succeed (20 %).
  options.min_inlier_ratio = 0.0;
  EXPECT_GT(Ransac(LocationEstimator(Data(0, 1000, 5)), options).statistics.iterations, 300);
  EXPECT_TRUE(Ransac(LocationEstimator(Data(200, 800, 5)), options).success);
}

// Above the floor the adaptive stop comes first, so the floor changes nothing.
TEST(Ransac, InlierRatioFloorLeavesDataAboveItUnchanged) {
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    const LocationEstimator estimator(Data(500, 500, seed));
    RansacOptions with_floor, without_floor;
    with_floor.max_error = without_floor.max_error = 0.5;
    with_floor.seed = without_floor.seed = seed;
    without_floor.min_inlier_ratio = 0.0;
    const RansacReport<double> a = Ransac(estimator, with_floor);
    const RansacReport<double> b = Ransac(estimator, without_floor);
    ASSERT_TRUE(a.success);
    EXPECT_EQ(a.model, b.model);
    EXPECT_EQ(a.inlier_mask, b.inlier_mask);
    EXPECT_EQ(a.statistics.iterations, b.statistics.iterations);
    EXPECT_EQ(a.statistics.num_models_scored, b.statistics.num_models_scored);
  }
}

TEST(Ransac, TooFewDataIsAFailureNotAnException) {
  const RansacReport<double> report = Ransac(LocationEstimator({}), RansacOptions());
  EXPECT_FALSE(report.success);
  EXPECT_FALSE(report.message.empty());
}

TEST(Ransac, BadOptionsThrow) {
  const LocationEstimator estimator(Data(10, 0, 4));
  for (auto mutate : std::vector<void (*)(RansacOptions*)>{
           [](RansacOptions* o) { o->max_error = 0.0; },
           [](RansacOptions* o) { o->max_error = NAN; },
           [](RansacOptions* o) { o->confidence = 1.0; },
           [](RansacOptions* o) { o->min_iterations = -1; },
           [](RansacOptions* o) { o->max_iterations = 0; },
           [](RansacOptions* o) { o->min_inlier_ratio = -0.1; },
           [](RansacOptions* o) { o->min_inlier_ratio = 1.0; },
           [](RansacOptions* o) { o->min_inlier_ratio = NAN; },
           [](RansacOptions* o) { o->min_iterations = 10, o->max_iterations = 5; }}) {
    RansacOptions options;
    mutate(&options);
    EXPECT_THROW(Ransac(estimator, options), std::invalid_argument);
  }
}

}  // namespace
}  // namespace trigrav
