#ifndef TRIGRAV_INITIALIZERS_RANSAC_H_
#define TRIGRAV_INITIALIZERS_RANSAC_H_

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace trigrav {

// Options of the generic RANSAC loop. Errors are in the estimator's unit (pixels for trigrav's
// three-view estimators).
struct RansacOptions {
  double max_error = 2.0;      // inlier threshold; MSAC truncates squared errors at its square
  double confidence = 0.9999;  // probability of drawing at least one all-inlier sample
  int min_iterations = 20;
  int max_iterations = 10000;
  std::uint64_t seed = 0;  // same seed, same data: bit-identical result
  // Inlier-ratio floor: a best model explaining fewer than this share of the data is a failure
  // (success = false), and the loop stops once a model of at least this ratio, had it existed,
  // would have been found with the confidence: after max(min_iterations, log(1 - confidence) /
  // log(1 - min_inlier_ratio^s)) samples (585 for s = 3 at the defaults) instead of
  // max_iterations. Data with a model above the floor stop earlier anyway, so their result does not
  // depend on it. 0 turns both off. Rule behind the default, 0.25: a floor well below the inlier
  // ratios of legitimate three-view data, also with IMU noise and many outliers, so that it only
  // shortens the search on data without a motion (the ratios measured on KITTI and synthetic
  // scenes: derivations.md section 7.5).
  double min_inlier_ratio = 0.25;
  // Local optimisation whenever a better model appears: `local_optimization_rounds` re-estimates,
  // each from the inliers of the previous one, at a threshold shrinking linearly from max_error *
  // local_optimization_threshold_multiplier to max_error (Lebeda, Matas, Chum, "Fixing the locally
  // optimized RANSAC", BMVC 2012). Every result is scored at max_error.
  bool local_optimization = true;
  int local_optimization_rounds = 3;
  double local_optimization_threshold_multiplier = 3.0;
  // When set, called before each sample (from the calling thread); true ends the run as a failure
  // ("stopped on request"). For a caller that must cancel a long run from another thread, e.g. on
  // Python's Ctrl-C. It must be cheap and must not throw.
  std::function<bool()> stop_requested;

  // Throws std::invalid_argument naming the first bad field.
  void Check() const;
};

// What a RANSAC run did: the one statistics struct of every robust estimate in trigrav.
struct RansacStatistics {
  int num_inliers = 0;  // of the returned model (on a failure: of the best one)
  int iterations = 0;   // samples drawn
  int num_models_scored = 0;
  int num_local_optimizations = 0;
  double msac_cost = std::numeric_limits<double>::infinity();  // sum_i min(e_i^2, max_error^2)
};

template <typename Model>
struct RansacReport {
  bool success = false;
  std::string message;  // why not, when !success
  Model model{};
  std::vector<char> inlier_mask;  // inlier_mask[i] != 0 iff error(model, i) <= max_error
  RansacStatistics statistics;
};

// Generic RANSAC with MSAC scoring, adaptive stopping and local optimisation (Chum, Matas, Kittler,
// "Locally optimized RANSAC", 2003; Torr and Zisserman's MSAC, 2000).
//
// Estimator concept (no virtual calls; everything is resolved at compile time):
//   using Model = ...;                                   // copyable
//   static constexpr int kSampleSize = s;                // minimal sample
//   std::size_t num_data() const;
//   // Models of a minimal sample (indices into the data, distinct); append to *models.
//   void generate_models(const std::array<int, kSampleSize>& sample, std::vector<Model>* models)
//   const;
//   // Errors of data [begin, end) under a model into errors[0, end - begin), in the unit of
//   // RansacOptions::max_error; +inf for a datum it cannot explain (e.g. behind a camera); never
//   // NaN. Only errors <= cap must be exact: one beyond it may be any value beyond it.
//   void errors(const Model& model, std::size_t begin, std::size_t end, double cap,
//               double* errors) const;
//   // Local optimisation: a better model from the inlier indices (e.g. a non-minimal solver).
//   // Returns false to keep the current one.
//   bool refine_model(const std::vector<int>& inliers, Model* model) const;
//
// The loop draws distinct random samples (std::mt19937_64 seeded with options.seed), scores each
// model by the MSAC cost, stopping a model's scoring as soon as its partial cost exceeds the best
// one (the cost only grows, so this changes no result), and stops after max(min_iterations, k)
// samples with k = log(1 - confidence) / log(1 - w^s) for the best inlier ratio w so far, or at
// max_iterations; the inlier-ratio floor (RansacOptions::min_inlier_ratio) caps k at its value for
// w = min_inlier_ratio and makes a best model below the floor a failure.
template <typename Estimator>
RansacReport<typename Estimator::Model> Ransac(const Estimator& estimator,
                                               const RansacOptions& options);

// ---------------------------------------------------------------------------------------------
// Implementation.

namespace internal {

// Distinct uniform indices in [0, n), n >= S (Floyd's algorithm would need a set; for S <= 8 a
// rejection loop over the few already drawn is simplest and allocation-free).
template <int S>
void DrawSample(int n, std::mt19937_64* rng, std::array<int, S>* sample) {
  std::uniform_int_distribution<int> index(0, n - 1);
  for (int i = 0; i < S; ++i) {
    bool repeated = true;
    while (repeated) {
      (*sample)[i] = index(*rng);
      repeated =
          std::find(sample->begin(), sample->begin() + i, (*sample)[i]) != sample->begin() + i;
    }
  }
}

// Samples needed for the confidence with inlier ratio w and sample size s.
inline int RequiredIterations(double inlier_ratio, int sample_size, double confidence) {
  const double all_inliers = std::pow(inlier_ratio, sample_size);
  if (all_inliers >= 1.0) return 0;
  // log1p keeps tiny probabilities (w^s = 1e-19 would round 1 - w^s to 1 and give k = -inf).
  const double denominator = std::log1p(-all_inliers);
  if (!(denominator < 0.0)) return std::numeric_limits<int>::max();
  const double k = std::log1p(-confidence) / denominator;
  return k >= static_cast<double>(std::numeric_limits<int>::max()) ? std::numeric_limits<int>::max()
                                                                   : static_cast<int>(std::ceil(k));
}

// Data whose errors are computed at once before their MSAC terms are summed: a bound exceeded
// mid-block wastes at most a block, and the estimator's per-call work is amortised.
inline constexpr std::size_t kScoringBlock = 32;

// MSAC cost of a model, abandoned (returning +inf) once it exceeds `bound`, the terms summed in
// the order of the data whatever the blocks. Writes each datum's error into *errors as it goes
// (exact up to `cap`, see the Estimator concept), so a completed pass also gives the inliers of
// any threshold <= cap without a second pass.
template <typename Estimator>
double MsacCost(const Estimator& estimator,
                const typename Estimator::Model& model,
                double squared_threshold,
                double cap,
                double bound,
                std::vector<double>* errors) {
  double cost = 0.0;
  const std::size_t n = estimator.num_data();
  for (std::size_t begin = 0; begin < n; begin += kScoringBlock) {
    const std::size_t end = std::min(n, begin + kScoringBlock);
    estimator.errors(model, begin, end, cap, errors->data() + begin);
    for (std::size_t i = begin; i < end; ++i) {
      const double e = (*errors)[i];
      cost += std::min(e * e, squared_threshold);
      if (cost > bound) return std::numeric_limits<double>::infinity();
    }
  }
  return cost;
}

inline int CollectInliers(const std::vector<double>& errors,
                          double threshold,
                          std::vector<int>* inliers) {
  inliers->clear();
  for (std::size_t i = 0; i < errors.size(); ++i) {
    if (errors[i] <= threshold) inliers->push_back(static_cast<int>(i));
  }
  return static_cast<int>(inliers->size());
}

}  // namespace internal

inline void RansacOptions::Check() const {
  auto require = [](bool ok, const char* what) {
    if (!ok) throw std::invalid_argument(std::string("trigrav: RansacOptions: ") + what);
  };
  require(max_error > 0.0 && std::isfinite(max_error), "max_error must be positive and finite");
  require(confidence > 0.0 && confidence < 1.0, "confidence must be in (0, 1)");
  require(min_iterations >= 0, "min_iterations must be >= 0");
  require(max_iterations >= 1 && max_iterations >= min_iterations,
          "max_iterations must be >= max(1, min_iterations)");
  require(min_inlier_ratio >= 0.0 && min_inlier_ratio < 1.0, "min_inlier_ratio must be in [0, 1)");
  require(local_optimization_rounds >= 0, "local_optimization_rounds must be >= 0");
  require(local_optimization_threshold_multiplier >= 1.0 &&
              std::isfinite(local_optimization_threshold_multiplier),
          "local_optimization_threshold_multiplier must be >= 1 and finite");
}

template <typename Estimator>
RansacReport<typename Estimator::Model> Ransac(const Estimator& estimator,
                                               const RansacOptions& options) {
  using Model = typename Estimator::Model;
  constexpr int kSampleSize = Estimator::kSampleSize;
  options.Check();
  RansacReport<Model> report;
  const std::size_t n = estimator.num_data();
  if (n < static_cast<std::size_t>(kSampleSize)) {
    report.message = "fewer data (" + std::to_string(n) + ") than the minimal sample (" +
                     std::to_string(kSampleSize) + ")";
    return report;
  }
  const double squared_threshold = options.max_error * options.max_error;
  // The largest threshold any error is compared with: max_error, or the first local-optimisation
  // round's. Errors beyond it need not be exact; min(e^2, squared_threshold) and every inlier set
  // are the same for any of them.
  const double cap =
      options.max_error *
      (options.local_optimization ? options.local_optimization_threshold_multiplier : 1.0);
  std::mt19937_64 rng(options.seed);
  std::array<int, kSampleSize> sample;
  std::vector<Model> models;
  std::vector<int> inliers, local_inliers;
  inliers.reserve(n);
  local_inliers.reserve(n);
  // Errors of the best model and of the last candidate (complete unless its scoring was abandoned).
  std::vector<double> best_errors(n), candidate_errors(n);
  bool candidate_errors_complete = false;
  double best_cost = std::numeric_limits<double>::infinity();
  int best_inliers = 0;
  // Samples after which a model with inlier ratio >= min_inlier_ratio would have been found with
  // the confidence: the most ever needed, since a best model above the floor needs fewer.
  const int enough_for_floor =
      options.min_inlier_ratio > 0.0
          ? std::max(options.min_iterations,
                     internal::RequiredIterations(options.min_inlier_ratio, kSampleSize,
                                                  options.confidence))
          : options.max_iterations;
  int required = std::min(options.max_iterations, enough_for_floor);

  // Scores a candidate; on improvement keeps it and updates the stopping criterion.
  auto consider = [&](const Model& model) {
    ++report.statistics.num_models_scored;
    const double cost =
        internal::MsacCost(estimator, model, squared_threshold, cap, best_cost, &candidate_errors);
    candidate_errors_complete = std::isfinite(cost);
    if (!(cost < best_cost)) return false;
    best_cost = cost;
    report.model = model;
    best_errors.swap(candidate_errors);
    candidate_errors_complete = false;
    best_inliers = internal::CollectInliers(best_errors, options.max_error, &inliers);
    required = std::min(enough_for_floor,
                        std::max(options.min_iterations,
                                 internal::RequiredIterations(static_cast<double>(best_inliers) / n,
                                                              kSampleSize, options.confidence)));
    return true;
  };

  for (report.statistics.iterations = 0;
       report.statistics.iterations < std::min(required, options.max_iterations);
       ++report.statistics.iterations) {
    if (options.stop_requested && options.stop_requested()) {
      report.message =
          "stopped on request after " + std::to_string(report.statistics.iterations) + " samples";
      return report;
    }
    internal::DrawSample<kSampleSize>(static_cast<int>(n), &rng, &sample);
    models.clear();
    estimator.generate_models(sample, &models);
    bool improved = false;
    for (const Model& model : models) improved = consider(model) || improved;
    if (!improved || !options.local_optimization) continue;
    // `current` starts as the new best model; its errors are in best_errors.
    Model current = report.model;
    const std::vector<double>* current_errors = &best_errors;
    for (int round = 0; round < options.local_optimization_rounds; ++round) {
      if (options.stop_requested && options.stop_requested()) break;
      const double fraction =
          options.local_optimization_rounds > 1
              ? static_cast<double>(round) / (options.local_optimization_rounds - 1)
              : 1.0;
      const double threshold =
          options.max_error * (options.local_optimization_threshold_multiplier -
                               (options.local_optimization_threshold_multiplier - 1.0) * fraction);
      if (internal::CollectInliers(*current_errors, threshold, &local_inliers) < kSampleSize) break;
      ++report.statistics.num_local_optimizations;
      if (!estimator.refine_model(local_inliers, &current)) break;
      if (consider(current)) {
        current_errors = &best_errors;
      } else {
        if (!candidate_errors_complete) {
          estimator.errors(current, 0, n, cap, candidate_errors.data());
        }
        current_errors = &candidate_errors;
      }
    }
  }

  report.statistics.msac_cost = best_cost;
  report.statistics.num_inliers = best_inliers;
  if (!std::isfinite(best_cost) || best_inliers < kSampleSize) {
    report.message = "no model explains at least a minimal sample";
    return report;
  }
  if (best_inliers < options.min_inlier_ratio * static_cast<double>(n)) {
    report.message = "the best model explains " + std::to_string(best_inliers) + " of " +
                     std::to_string(n) + " data, below min_inlier_ratio";
    return report;
  }
  report.inlier_mask.assign(n, 0);
  for (const int i : inliers) report.inlier_mask[i] = 1;  // inliers of the best model
  report.success = true;
  return report;
}

}  // namespace trigrav

#endif  // TRIGRAV_INITIALIZERS_RANSAC_H_
