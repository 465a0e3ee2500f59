#include "trigrav/initializers/robust_three_view.h"

#include <algorithm>
#include <array>
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <string>

#include "robust_estimator.h"
#include "robust_methods.h"
#include "robust_triplet_data.h"
#include "tilt_correcting_refinement.h"
#include "verdict.h"

namespace trigrav {
namespace {

using internal::Method3pt;
using internal::Method3ptSextic;
using internal::Method4pt;
using internal::Method5pt;
using internal::Method7ptLinear;
using internal::Method8pt;
using internal::Run;
using internal::TiltCorrectingRefinement;
using internal::TripletData;

// The gravity-free estimate's own tilt error on exact gravity stays below it (derivations.md 7.6).
constexpr double kExactGravityInconsistencyDeg = 1.0;

using RunFunction = RobustThreeViewEstimate (*)(const TripletData&, const RansacOptions&);

struct SolverInfo {
  InitialSolver solver;
  const char* name;
  int sample_size;
  int max_models_per_sample;  // the most models the minimal solver gives (the headers)
  bool uses_gravity;
  RunFunction run;
  RunFunction run_tilt_correcting;  // == run for the methods that do not use gravity
};

template <typename M>
constexpr SolverInfo MakeSolverInfo(InitialSolver solver, const char* name, int max_models) {
  if constexpr (M::kAligned) {
    return {
        solver, name, M::kSampleSize, max_models, true, &Run<M>, &Run<TiltCorrectingRefinement<M>>};
  } else {
    return {solver, name, M::kSampleSize, max_models, false, &Run<M>, &Run<M>};
  }
}

constexpr std::array<SolverInfo, 6> kSolvers = {{
    MakeSolverInfo<Method3pt>(InitialSolver::kTrifocal3pt, "3pt", 16),
    MakeSolverInfo<Method3ptSextic>(InitialSolver::kTrifocal3ptSextic, "3pt-sextic", 6),
    MakeSolverInfo<Method4pt>(InitialSolver::kTrifocal4pt, "4pt", 1),
    MakeSolverInfo<Method7ptLinear>(InitialSolver::kTrifocalLinear, "7pt-linear", 1),
    MakeSolverInfo<Method5pt>(InitialSolver::kEssential5pt, "5pt", 100),  // 10 per pair
    MakeSolverInfo<Method8pt>(InitialSolver::kEssential8pt, "8pt", 1),
}};

constexpr bool TableFollowsInitialSolverList() {
  for (std::size_t i = 0; i < kSolvers.size(); ++i) {
    if (kSolvers[i].solver != kInitialSolvers[i]) return false;
  }
  return kSolvers.size() == kInitialSolvers.size();
}
static_assert(TableFollowsInitialSolverList(), "kSolvers must follow kInitialSolvers");

const SolverInfo& Info(InitialSolver solver) {
  for (const SolverInfo& info : kSolvers) {
    if (info.solver == solver) return info;
  }
  throw std::invalid_argument("trigrav: unknown InitialSolver value");
}

}  // namespace

const char* InitialSolverName(InitialSolver solver) { return Info(solver).name; }

double ConsensusEvidence::SigmaWithOffsetDeg() const {
  return std::max(rotation_sigma_deg + rotation_offset_deg / 4.0,
                  direction_sigma_deg + direction_offset_deg / 4.0);
}

const char* FailureCauseName(FailureCause cause) {
  switch (cause) {
    case FailureCause::kNone:
      return "none";
    case FailureCause::kTooFewTriplets:
      return "too-few-triplets";
    case FailureCause::kBelowInlierFloor:
      return "below-inlier-floor";
    case FailureCause::kTooFewInliers:
      return "too-few-inliers";
    case FailureCause::kChanceConsensus:
      return "chance-consensus";
    case FailureCause::kUncertainPose:
      return "uncertain-pose";
    case FailureCause::kNoParallax:
      return "no-parallax";
    case FailureCause::kPixelsVsIntrinsics:
      return "pixels-vs-intrinsics";
    case FailureCause::kViewsOutOfOrder:
      return "views-out-of-order";
    case FailureCause::kCameraGravity:
      return "camera-gravity";
    case FailureCause::kNoisyGravity:
      return "noisy-gravity";
    case FailureCause::kOtherMotion:
      return "other-motion";
    case FailureCause::kRefinementShift:
      return "refinement-shift";
    case FailureCause::kStopped:
      return "stopped";
  }
  throw std::invalid_argument("trigrav: unknown FailureCause value");
}

int MinimalSampleSize(InitialSolver solver) { return Info(solver).sample_size; }

bool UsesGravity(InitialSolver solver) { return Info(solver).uses_gravity; }

std::string InitialSolverNames() {
  std::string names;
  for (const SolverInfo& info : kSolvers)
    names += (names.empty() ? "" : ", ") + std::string(info.name);
  return names;
}

void RobustThreeViewOptions::Check() const {
  Info(solver);  // throws for a value outside the enum
  ransac.Check();
  if (!(max_bearing_error_deg > 0.0 && max_bearing_error_deg < 90.0)) {
    throw std::invalid_argument(
        "trigrav: RobustThreeViewOptions: max_bearing_error_deg must be in (0, 90)");
  }
  if (!(max_gravity_inconsistency_deg == kGravityConsistencyFromGravitySigma ||
        max_gravity_inconsistency_deg > 0.0)) {
    throw std::invalid_argument(
        "trigrav: RobustThreeViewOptions: max_gravity_inconsistency_deg must be > 0 or "
        "kGravityConsistencyFromGravitySigma");
  }
  if (min_inliers < 0) {
    throw std::invalid_argument("trigrav: RobustThreeViewOptions: min_inliers must be >= 0");
  }
  if (!(max_pose_sigma_deg > 0.0)) {
    throw std::invalid_argument(
        "trigrav: RobustThreeViewOptions: max_pose_sigma_deg must be > 0 (+infinity: no test)");
  }
  if (!(max_tilt_correction_deg == kTiltCorrectionFromGravitySigma ||
        (max_tilt_correction_deg >= 0.0 && max_tilt_correction_deg < 90.0))) {
    throw std::invalid_argument(
        "trigrav: RobustThreeViewOptions: max_tilt_correction_deg must be in [0, 90) or "
        "kTiltCorrectionFromGravitySigma");
  }
}

double RobustThreeViewOptions::InlierThreshold(const ThreeViewObservations& observations) const {
  return observations.HasBearings() ? max_bearing_error_deg : ransac.max_error;
}

bool ParseInitialSolver(const std::string& name, InitialSolver* solver) {
  for (const SolverInfo& info : kSolvers) {
    if (name == info.name) {
      *solver = info.solver;
      return true;
    }
  }
  return false;
}

RobustThreeViewEstimate EstimateThreeViewPoseRobust(const ThreeViewObservations& observations,
                                                    const RobustThreeViewOptions& options) {
  options.Check();
  // Without a gravity sigma the automatic bound is 0 (header).
  const double max_tilt_correction_deg = std::max(options.max_tilt_correction_deg, 0.0);
  // Its ThreeViewReprojectionError checks the observations.
  const TripletData data(observations, max_tilt_correction_deg);
  const SolverInfo& info = Info(options.solver);
  const RunFunction run = max_tilt_correction_deg > 0.0 ? info.run_tilt_correcting : info.run;
  RansacOptions ransac = options.ransac;
  ransac.max_error = options.InlierThreshold(observations);
  RobustThreeViewEstimate estimate = run(data, ransac);
  // A stopped run never succeeds, also when the stop came during the verdict's own RANSAC.
  const auto stopped = [&] {
    if (!(ransac.stop_requested && ransac.stop_requested())) return false;
    estimate = RobustThreeViewEstimate();
    estimate.cause = FailureCause::kStopped;
    estimate.message = "stopped on request (ransac.stop_requested)";
    return true;
  };
  if (stopped()) return estimate;
  internal::VerdictSettings verdict;
  verdict.sample_size = info.sample_size;
  verdict.max_models_per_sample = info.max_models_per_sample;
  verdict.uses_gravity = info.uses_gravity;
  verdict.tilt_correcting = max_tilt_correction_deg > 0.0;
  // Without a gravity sigma the upright models take the gravity as exact (header).
  verdict.max_gravity_inconsistency_deg =
      options.max_gravity_inconsistency_deg == options.kGravityConsistencyFromGravitySigma
          ? kExactGravityInconsistencyDeg
          : options.max_gravity_inconsistency_deg;
  verdict.check_gravity_after_success = options.check_gravity_after_success;
  verdict.max_pose_sigma_deg = options.max_pose_sigma_deg;
  verdict.min_inliers = options.min_inliers;
  verdict.judge_offset = !options.refined_afterwards;
  internal::JudgeEstimate(data, observations, ransac, verdict, &estimate);
  stopped();
  return estimate;
}

}  // namespace trigrav
