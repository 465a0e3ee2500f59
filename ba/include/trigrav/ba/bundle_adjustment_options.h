#ifndef TRIGRAV_BA_BUNDLE_ADJUSTMENT_OPTIONS_H_
#define TRIGRAV_BA_BUNDLE_ADJUSTMENT_OPTIONS_H_

// The settings both bundle adjusters share, stored once: the rotation model, the loss, the noise
// model, the covariance switch and Ceres' solver fields. ThreeViewBundleAdjustmentOptions
// (three_view_bundle_adjustment.h) and NViewBundleAdjustmentOptions (nview_bundle_adjustment.h)
// derive from it, add their own fields and set their own defaults, each header giving the rule
// behind them.

#include <ceres/solver.h>
#include <ceres/types.h>

#include <functional>
#include <string>

namespace trigrav {

struct BundleAdjustmentOptions {
  enum class RotationModel {
    // R_k = A_k^T R_y(yaw_k) A_ref: pitch and roll exactly as the measured gravity says; one angle
    // per camera with YawManifold.
    kYawOnly,
    // R_k free (quaternion on ceres::QuaternionManifold) with a GravityPriorError per camera
    // weighted by (observation sigma / gravity_sigma)^2: pitch and roll may move when the IMU is
    // off.
    kGravityPrior,
  };
  enum class LossType { kNone, kHuber, kCauchy };

  RotationModel rotation_model = RotationModel::kYawOnly;
  LossType loss = LossType::kHuber;
  double loss_scale_px = 2.0;   // Huber / Cauchy scale on the pixel residuals
  double pixel_sigma_px = 1.0;  // pixel noise: the gravity prior's weight, the covariance's scale
  double gravity_sigma_deg;     // IMU angular sigma (kGravityPrior)
  bool compute_covariance = false;

  // Ceres' solver (ceres::Solver::Options of the same names).
  int max_num_iterations;
  // Any number >= 1: more than std::thread::hardware_concurrency() run as that many (Ceres' own
  // bound, without the warning Ceres would print).
  int num_threads = 1;
  ceres::LinearSolverType linear_solver_type;
  double function_tolerance;
  double gradient_tolerance;
  double parameter_tolerance;
  // When set, called after each solver iteration (from the thread that solves); true ends the
  // solve as a failure ("stopped on request"), the parameters restored. For a caller that must
  // cancel a long solve from another thread. It must be cheap and must not throw.
  std::function<bool()> stop_requested;

  // Ceres' options from the fields above: silent (nothing on stdout or stderr), the trust region
  // radius capped at 1e7 (the cap keeps Ceres' dense Cholesky from failing, and printing, on
  // distant points). Each adjuster's options add their own settings to it.
  ceres::Solver::Options CeresSolverOptions() const;

 protected:
  BundleAdjustmentOptions(double gravity_sigma_deg,
                          int max_num_iterations,
                          ceres::LinearSolverType linear_solver_type,
                          double function_tolerance,
                          double gradient_tolerance,
                          double parameter_tolerance);
  // Throws std::invalid_argument "trigrav: <options_name>: <field> ..." for the first bad field
  // above: non-positive or non-finite scales and sigmas, negative counts, negative or non-finite
  // tolerances, enum values out of range.
  void CheckSharedFields(const std::string& options_name) const;
};

}  // namespace trigrav

#endif  // TRIGRAV_BA_BUNDLE_ADJUSTMENT_OPTIONS_H_
