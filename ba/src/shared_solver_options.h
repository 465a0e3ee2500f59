#ifndef TRIGRAV_BA_SRC_SHARED_SOLVER_OPTIONS_H_
#define TRIGRAV_BA_SRC_SHARED_SOLVER_OPTIONS_H_

// The Ceres settings of the bundle adjusters (three-view and N-view), in one place.

#include <ceres/solver.h>
#include <ceres/types.h>

#include <algorithm>
#include <functional>
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

// Ceres' callback that ends a solve when the options' stop_requested says so; the solve's caller
// adds it to ceres::Solver::Options::callbacks while it lives.
class StopRequestCallback : public ceres::IterationCallback {
 public:
  explicit StopRequestCallback(const std::function<bool()>& stop_requested)
      : stop_requested_(stop_requested) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary&) override {
    return stop_requested_ && stop_requested_() ? ceres::SOLVER_ABORT : ceres::SOLVER_CONTINUE;
  }

 private:
  const std::function<bool()>& stop_requested_;
};

}  // namespace internal
}  // namespace trigrav

#endif  // TRIGRAV_BA_SRC_SHARED_SOLVER_OPTIONS_H_
