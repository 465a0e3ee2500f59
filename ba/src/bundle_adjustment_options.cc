#include "trigrav/ba/bundle_adjustment_options.h"

#include <cmath>
#include <stdexcept>

#include "shared_solver_options.h"

namespace trigrav {

BundleAdjustmentOptions::BundleAdjustmentOptions(double gravity_sigma_deg,
                                                 int max_num_iterations,
                                                 ceres::LinearSolverType linear_solver_type,
                                                 double function_tolerance,
                                                 double gradient_tolerance,
                                                 double parameter_tolerance)
    : gravity_sigma_deg(gravity_sigma_deg),
      max_num_iterations(max_num_iterations),
      linear_solver_type(linear_solver_type),
      function_tolerance(function_tolerance),
      gradient_tolerance(gradient_tolerance),
      parameter_tolerance(parameter_tolerance) {}

void BundleAdjustmentOptions::CheckSharedFields(const std::string& options_name) const {
  const auto require = [&](bool ok, const char* what) {
    if (!ok) throw std::invalid_argument("trigrav: " + options_name + ": " + what);
  };
  const auto positive = [](double v) { return v > 0.0 && std::isfinite(v); };
  const auto tolerance = [](double v) { return v >= 0.0 && std::isfinite(v); };
  require(positive(loss_scale_px), "loss_scale_px must be positive and finite");
  require(positive(pixel_sigma_px), "pixel_sigma_px must be positive and finite");
  require(positive(gravity_sigma_deg), "gravity_sigma_deg must be positive and finite");
  require(max_num_iterations >= 0, "max_num_iterations must be >= 0");
  require(num_threads >= 1, "num_threads must be >= 1");
  require(tolerance(function_tolerance), "function_tolerance must be >= 0 and finite");
  require(tolerance(gradient_tolerance), "gradient_tolerance must be >= 0 and finite");
  require(tolerance(parameter_tolerance), "parameter_tolerance must be >= 0 and finite");
  require(
      rotation_model == RotationModel::kYawOnly || rotation_model == RotationModel::kGravityPrior,
      "unknown rotation_model");
  require(loss == LossType::kNone || loss == LossType::kHuber || loss == LossType::kCauchy,
          "unknown loss");
  require(internal::IsLinearSolverType(linear_solver_type), "unknown linear_solver_type");
}

ceres::Solver::Options BundleAdjustmentOptions::CeresSolverOptions() const {
  ceres::Solver::Options solver_options;
  solver_options.linear_solver_type = linear_solver_type;
  solver_options.max_num_iterations = max_num_iterations;
  solver_options.num_threads = internal::CeresNumThreads(num_threads);
  solver_options.function_tolerance = function_tolerance;
  solver_options.gradient_tolerance = gradient_tolerance;
  solver_options.parameter_tolerance = parameter_tolerance;
  solver_options.logging_type = ceres::SILENT;
  solver_options.minimizer_progress_to_stdout = false;
  solver_options.max_trust_region_radius = internal::kMaxTrustRegionRadius;
  return solver_options;
}

}  // namespace trigrav
