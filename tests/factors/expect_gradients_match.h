#ifndef TRIGRAV_TESTS_FACTORS_EXPECT_GRADIENTS_MATCH_H_
#define TRIGRAV_TESTS_FACTORS_EXPECT_GRADIENTS_MATCH_H_

// Probes a cost function at the given parameters with ceres::GradientChecker (Ridders' numeric
// derivatives from a relative step of 1e-3); expects the analytic and numeric derivatives to agree
// to `tolerance` (relative).

#include <ceres/gradient_checker.h>
#include <ceres/manifold.h>
#include <gtest/gtest.h>

#include <vector>

namespace trigrav {

inline void ExpectGradientsMatch(const ceres::CostFunction& cost,
                                 const std::vector<const ceres::Manifold*>& manifolds,
                                 const std::vector<const double*>& parameters,
                                 double tolerance) {
  ceres::NumericDiffOptions numeric_options;
  numeric_options.ridders_relative_initial_step_size = 1e-3;
  ceres::GradientChecker checker(&cost, &manifolds, numeric_options);
  ceres::GradientChecker::ProbeResults results;
  EXPECT_TRUE(checker.Probe(parameters.data(), tolerance, &results)) << results.error_log;
  EXPECT_TRUE(results.return_value);
  EXPECT_LT(results.maximum_relative_error, tolerance);
}

}  // namespace trigrav

#endif  // TRIGRAV_TESTS_FACTORS_EXPECT_GRADIENTS_MATCH_H_
