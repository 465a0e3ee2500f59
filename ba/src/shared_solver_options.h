#ifndef TRIGRAV_BA_SRC_SHARED_SOLVER_OPTIONS_H_
#define TRIGRAV_BA_SRC_SHARED_SOLVER_OPTIONS_H_

// The Ceres settings of the bundle adjusters (three-view and N-view), in one place.

#include <ceres/solver.h>
#include <ceres/types.h>

#include <algorithm>
#include <thread>

namespace trigrav {
namespace internal {

// The trust region radius cap. Ceres 2.1 prints an unconditional LOG(WARNING) in
// levenberg_marquardt_strategy.cc on a failed linear solve ("Linear solver failure ... Unable to
// perform dense Cholesky factorization", on stderr without InitGoogleLogging; Ceres then retries
// with a smaller radius), which logging_type SILENT does not cover. DENSE_SCHUR's reduced system
// fails once the radius passes ~1e8 (distant points: near-singular point blocks, round-off growing
// with the radius while the damping falls as 1 / radius). At Ceres' default cap (1e16) 30 of 1000
// InitializeAndRefine calls on driving triplets printed; at 1e7 none, same median errors
// (tests/ba/quiet_test.cc). No glog flag is touched.
inline constexpr double kMaxTrustRegionRadius = 1e7;

// The num_threads handed to Ceres: the caller's, bounded by std::thread::hardware_concurrency()
// when known. Ceres 2.1 bounds it there itself (preprocessor.cc, ChangeNumThreadsIfNeeded, on every
// Solve) but prints an unconditional LOG(WARNING) first ("Specified options.num_threads: 64
// exceeds maximum available from the threading model Ceres was compiled with: 2.  Bounding to
// maximum number available."). Same threads, same answer, no print (tests/ba/quiet_test.cc).
inline int CeresNumThreads(int num_threads) {
  const int hardware = static_cast<int>(std::thread::hardware_concurrency());  // 0: unknown
  return hardware > 0 ? std::min(num_threads, hardware) : num_threads;
}

// True for an enumerator of ceres::LinearSolverType. Ceres aborts (LOG(FATAL)) on any other value;
// its name round-trips only if valid.
inline bool IsLinearSolverType(ceres::LinearSolverType type) {
  ceres::LinearSolverType parsed;
  return ceres::StringToLinearSolverType(ceres::LinearSolverTypeToString(type), &parsed) &&
         parsed == type;
}

// Ceres options from the fields both adjusters' options have (linear_solver_type,
// max_num_iterations, num_threads, function_tolerance, gradient_tolerance, parameter_tolerance):
// silent (nothing on stdout or stderr: num_threads bounded by CeresNumThreads), the radius capped
// at kMaxTrustRegionRadius.
template <typename AdjusterOptions>
ceres::Solver::Options SharedSolverOptions(const AdjusterOptions& options) {
  ceres::Solver::Options solver_options;
  solver_options.linear_solver_type = options.linear_solver_type;
  solver_options.max_num_iterations = options.max_num_iterations;
  solver_options.num_threads = CeresNumThreads(options.num_threads);
  solver_options.function_tolerance = options.function_tolerance;
  solver_options.gradient_tolerance = options.gradient_tolerance;
  solver_options.parameter_tolerance = options.parameter_tolerance;
  solver_options.logging_type = ceres::SILENT;
  solver_options.minimizer_progress_to_stdout = false;
  solver_options.max_trust_region_radius = kMaxTrustRegionRadius;
  return solver_options;
}

}  // namespace internal
}  // namespace trigrav

#endif  // TRIGRAV_BA_SRC_SHARED_SOLVER_OPTIONS_H_
