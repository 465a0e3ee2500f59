// Bad-input matrix: every public entry point of trigrav against every bad input below, each (case,
// entry point) pair checked against the outcome written down in Cases():
//   - std::invalid_argument whose message names the problem (misuse at the public boundary);
//   - no solution: 0 poses, success == false with a message, Build() == false, no triangulation;
//   - the true pose (point, alignment) among the results;
//   - for input that no pose explains or that has no unique answer: no solution or finite results.
// Whatever the case, nothing may crash, throw another exception type, or return a non-finite pose
// (every returned pose IsFinite(), every error is finite or +inf). The test prints how many pairs
// were run and the count of each outcome per entry point and per case group (README, Robustness).

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <limits>
#include <map>
#include <random>
#include <regex>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "bad_input_scenes.h"
#include "trigrav/ba/initialize_and_refine.h"
#include "trigrav/ba/refine_three_view_pose.h"
#include "trigrav/ba/three_view_bundle_adjustment.h"
#include "trigrav/evaluation/pose_errors.h"
#include "trigrav/initializers/essential_5pt.h"
#include "trigrav/initializers/essential_8pt.h"
#include "trigrav/initializers/gravity.h"
#include "trigrav/initializers/robust_three_view.h"
#include "trigrav/initializers/three_view_error.h"
#include "trigrav/initializers/trifocal_3pt.h"
#include "trigrav/initializers/trifocal_4pt.h"
#include "trigrav/initializers/trifocal_linear.h"
#include "trigrav/initializers/two_view_to_three_view.h"

namespace trigrav {
namespace bad_input {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// ------------------------------------------------------------------------------------------------
// Outcomes. A case lists the outcomes it allows (a bit mask); kBroken is never allowed.

enum Outcome : unsigned {
  kThrows = 1u << 0,  // std::invalid_argument with a message matching the case's pattern
  kNone = 1u << 1,    // no solution, with a reason where the entry point reports one
  kTruth = 1u << 2,   // the true pose (point, alignment) is among the results
  kOther = 1u << 3,   // finite results, none of them the truth
  kBroken = 1u << 4,  // non-finite pose or error, another exception type, inconsistent result
};
// Input without a unique correct answer: no solution, or finite poses.
constexpr unsigned kDegenerate = kNone | kOther;
constexpr Outcome kOutcomes[] = {kThrows, kNone, kTruth, kOther, kBroken};

const char* OutcomeName(unsigned outcome) {
  switch (outcome) {
    case kThrows:
      return "invalid_argument";
    case kNone:
      return "no solution";
    case kTruth:
      return "true pose";
    case kOther:
      return "finite, not the truth";
    case kBroken:
      return "broken";
  }
  return "?";
}

std::string OutcomeNames(unsigned outcomes) {
  std::string names;
  for (const Outcome o : kOutcomes) {
    if (outcomes & o) names += (names.empty() ? "" : " or ") + std::string(OutcomeName(o));
  }
  return names;
}

struct Result {
  unsigned outcome = kBroken;
  std::string detail;  // exception message, failure reason or what made it broken
};

// ------------------------------------------------------------------------------------------------
// Classification of results.

constexpr double kTolerance = 1e-6;  // rotation matrices (Frobenius) and centres at |C2| = 1

bool SamePose(const CameraPose& truth, const CameraPose& estimate) {
  return (truth.R - estimate.R).norm() < kTolerance &&
         (truth.Center() - estimate.Center()).norm() <
             kTolerance * std::max(1.0, truth.Center().norm());
}

// The solvers' scale is |C2| = 1; a truth with |C2| = 0 cannot be written in it.
bool IsTruth(const Input& input, const ThreeViewPose& truth, const ThreeViewPose& estimate) {
  return input.has_truth && truth.cam2_from_cam1.Center().norm() > 0.5 &&
         SamePose(truth.cam2_from_cam1, estimate.cam2_from_cam1) &&
         SamePose(truth.cam3_from_cam1, estimate.cam3_from_cam1);
}

Result Broken(const std::string& why) { return {kBroken, why}; }

Result ClassifyThreeView(const Input& input,
                         const ThreeViewPose& truth,
                         int count,
                         const std::vector<ThreeViewPose>& poses) {
  if (count < 0 || static_cast<std::size_t>(count) != poses.size()) {
    return Broken("returned " + std::to_string(count) + " but wrote " +
                  std::to_string(poses.size()));
  }
  bool truth_found = false;
  for (const ThreeViewPose& pose : poses) {
    if (!pose.IsFinite()) return Broken("non-finite pose");
    truth_found = truth_found || IsTruth(input, truth, pose);
  }
  if (count == 0) return {kNone, ""};
  return {truth_found ? kTruth : kOther, ""};
}

// Two-view solvers: pair (1,2), |t| = 1.
Result ClassifyPair(const Input& input, int count, const std::vector<CameraPose>& poses) {
  if (count < 0 || static_cast<std::size_t>(count) != poses.size()) return Broken("count mismatch");
  const CameraPose& truth = input.truth.cam2_from_cam1;
  bool truth_found = false;
  for (const CameraPose& pose : poses) {
    if (!pose.IsFinite()) return Broken("non-finite pose");
    truth_found =
        truth_found || (input.has_truth && truth.Center().norm() > 0.5 && SamePose(truth, pose));
  }
  if (count == 0) return {kNone, ""};
  return {truth_found ? kTruth : kOther, ""};
}

// An estimate that reports success or a reason.
Result ClassifyEstimate(const Input& input,
                        bool success,
                        const std::string& message,
                        const std::vector<const ThreeViewPose*>& poses,
                        const ThreeViewPose& final) {
  if (!success) {
    return message.empty() ? Broken("failure without a message") : Result{kNone, message};
  }
  for (const ThreeViewPose* pose : poses) {
    if (!pose->IsFinite()) return Broken("non-finite pose");
  }
  return {IsTruth(input, input.truth, final) ? kTruth : kOther, message};
}

template <typename T>
T* Output(const Input& input, T* output) {
  return input.null_output ? nullptr : output;
}

// ------------------------------------------------------------------------------------------------
// Entry points. `reads` says which parts of an Input one uses: a case applies to the entry points
// that read what it changes.

enum Field : unsigned {
  kGeometry = 1u << 0,  // the scene (every entry point)
  kRays1 = 1u << 1,     // rays of view k (ray-based entry points)
  kRays2 = 1u << 2,
  kRays3 = 1u << 3,
  kSize1 = 1u << 4,  // number of triplets in view k
  kSize2 = 1u << 5,
  kSize3 = 1u << 6,
  kGravity = 1u << 7,
  kPixels = 1u << 8,
  kIntrinsics = 1u << 9,
  kOutput = 1u << 10,     // output pointer
  kGivenPose = 1u << 11,  // pose handed in
  kPitchRoll = 1u << 12,
  kRansacOptions = 1u << 13,
  kSolverChoice = 1u << 14,  // InitialSolver of the robust estimator and InitializeAndRefine
  kRefineOptions = 1u << 15,
  kBundleOptions = 1u << 16,
  kBundleConfig = 1u << 17,
  kTrifocal4ptOptions = 1u << 18,
  kTiltCorrection = 1u << 19,  // RobustThreeViewOptions::max_tilt_correction_deg
};
constexpr unsigned kRays = kRays1 | kRays2 | kRays3;
constexpr unsigned kSizes = kSize1 | kSize2 | kSize3;
constexpr unsigned kRaySolver = kGeometry | kRays | kSizes | kOutput;
constexpr unsigned kPairSolver = kGeometry | kRays1 | kRays2 | kSize1 | kSize2 | kOutput;
constexpr unsigned kObservations = kGeometry | kSizes | kGravity | kPixels | kIntrinsics;

// Entry point identifiers, the columns of the table (order of EntryPoints()).
enum Ep : int {
  k4ptAligned,
  k4ptGravity,
  k4ptAlignedOptions,
  k4ptGravityOptions,
  k4ptGravity20,
  k3ptAligned,
  k3ptGravity,
  k3ptSexticAligned,
  k3ptSexticGravity,
  kEssential5pt,
  kEssential8pt,
  kTrifocalLinear,
  kCombinePairs,
  kTriangulate,
  kReprojectionError,
  kAlignmentFromGravity,
  kAlignmentFromPitchRoll,
  kRobust3pt,
  kRobust3ptSextic,
  kRobust4pt,
  kRobust7ptLinear,
  kRobust5pt,
  kRobust8pt,
  kRefine3ptYawOnly,
  kRefine5ptGravityPrior,
  kRefine3ptGravityPrior,  // its RANSAC corrects the tilt (automatic max_tilt_correction_deg)
  kBundleYawOnly,
  kBundleGravityPrior,
  kRefineOnly,  // RefineThreeViewPose on every triplet (yaw-only)
  kRefine3ptCeres,
  kBundleCeres,
};

using EpSet = std::uint64_t;
EpSet Eps(std::initializer_list<Ep> eps) {
  EpSet set = 0;
  for (const Ep ep : eps) set |= EpSet{1} << ep;
  return set;
}
EpSet EpRange(Ep first, Ep last) {
  EpSet set = 0;
  for (int ep = first; ep <= last; ++ep) set |= EpSet{1} << ep;
  return set;
}
const EpSet kTrifocalSolvers = EpRange(k4ptAligned, k3ptSexticGravity);
const EpSet kMinimalSolvers = EpRange(k4ptAligned, kTrifocalLinear) & ~Eps({k4ptGravity20});
const EpSet kExactCountSolvers = EpRange(k3ptAligned, kEssential5pt);
const EpSet kRobust = EpRange(kRobust3pt, kRobust8pt);
const EpSet kRefine =
    Eps({kRefine3ptYawOnly, kRefine5ptGravityPrior, kRefine3ptGravityPrior, kRefine3ptCeres});
const EpSet kBundle = Eps({kBundleYawOnly, kBundleGravityPrior, kRefineOnly, kBundleCeres});

struct EntryPoint {
  Ep id;
  std::string name;
  int num_triplets;  // triplets it gets
  int min_triplets;  // fewest it takes (a "too few" case gives one less)
  unsigned reads;
  std::function<void(Input*)> configure;  // entry-point settings, applied before a case's change
  std::function<Result(const Input&)> run;
};

// A three-view solver on the gravity-aligned rays (against the aligned truth) or on the raw rays.
template <typename Solve>
std::function<Result(const Input&)> OnAlignedRays(Solve solve) {
  return [solve](const Input& in) {
    std::vector<ThreeViewPose> poses;
    const int count = solve(in, in.aligned_rays, Output(in, &poses));
    return ClassifyThreeView(in, in.aligned_truth, count, poses);
  };
}
template <typename Solve>
std::function<Result(const Input&)> OnRawRays(Solve solve) {
  return [solve](const Input& in) {
    std::vector<ThreeViewPose> poses;
    const int count = solve(in, in.rays, Output(in, &poses));
    return ClassifyThreeView(in, in.truth, count, poses);
  };
}
const Eigen::Vector3d& G(const Input& in, int k) { return in.observations.gravity_in_cam[k]; }

Result RunTriangulate(const Input& in) {
  // Every triplet, with the given pose's centres and the rays rotated into camera 1.
  const CameraPose& cam2 = in.given_pose.cam2_from_cam1;
  const CameraPose& cam3 = in.given_pose.cam3_from_cam1;
  const std::array<Eigen::Vector3d, 3> centers = {Eigen::Vector3d::Zero(), cam2.Center(),
                                                  cam3.Center()};
  bool all_triangulated = true, all_true = true;
  for (std::size_t n = 0; n < in.rays[0].size(); ++n) {
    const std::array<Eigen::Vector3d, 3> directions = {
        in.rays[0][n], cam2.R.transpose() * in.rays[1][n], cam3.R.transpose() * in.rays[2][n]};
    Eigen::Vector3d point = Eigen::Vector3d::Zero();
    if (!TriangulateMidpoint(centers, directions, Output(in, &point))) {
      all_triangulated = false;
      continue;
    }
    if (!point.allFinite()) return Broken("non-finite point");
    all_true = all_true && n < in.points_in_ref.size() &&
               (point - in.points_in_ref[n]).norm() < kTolerance * in.points_in_ref[n].norm();
  }
  if (!all_triangulated) return {kNone, ""};
  return {all_true && in.has_truth ? kTruth : kOther, ""};
}

Result RunReprojectionError(const Input& in) {
  const ThreeViewReprojectionError error(in.observations);
  const ThreeViewReprojectionError::PreparedPose pose =
      ThreeViewReprojectionError::Prepare(in.given_pose);
  bool all_zero = true, all_infinite = true;
  for (std::size_t n = 0; n < error.size(); ++n) {
    const double e = error(pose, n);
    if (std::isnan(e) || e < 0.0) return Broken("error " + std::to_string(e));
    all_zero = all_zero && e < kTolerance;
    all_infinite = all_infinite && std::isinf(e);
  }
  if (all_infinite) return {kNone, ""};
  return {all_zero && in.has_truth ? kTruth : kOther, ""};
}

Result RunAlignmentFromGravity(const Input& in) {
  for (int k = 0; k < 3; ++k) {
    const Eigen::Matrix3d R = GravityAlignmentFromGravity(G(in, k));
    if (!R.allFinite()) return Broken("non-finite alignment");
    const bool rotation =
        (R * R.transpose() - Eigen::Matrix3d::Identity()).norm() < 1e-12 && R.determinant() > 0.0;
    if (!rotation || (R * G(in, k).normalized() - Eigen::Vector3d::UnitY()).norm() > 1e-12) {
      return {kOther, ""};
    }
  }
  return {kTruth, ""};
}

// The alignment of a camera R_x(pitch) R_z(roll) R_y(yaw) is (R_x(pitch) R_z(roll))^T.
Result RunAlignmentFromPitchRoll(const Input& in) {
  const Eigen::Matrix3d R = GravityAlignmentFromPitchRoll(in.pitch_rad, in.roll_rad);
  if (!R.allFinite()) return Broken("non-finite alignment");
  const Eigen::Matrix3d expected = Tilted(in.pitch_rad, in.roll_rad, 0.0).transpose();
  return {(R - expected).norm() < 1e-12 ? kTruth : kOther, ""};
}

Result RunRobust(const Input& in) {
  RobustThreeViewOptions options;
  options.solver = in.solver;
  options.ransac = in.ransac;
  options.max_tilt_correction_deg = in.max_tilt_correction_deg;
  const RobustThreeViewEstimate estimate = EstimateThreeViewPoseRobust(in.observations, options);
  if (estimate.success && estimate.inliers.size() != in.observations.size()) {
    return Broken("inlier mask of the wrong size");
  }
  return ClassifyEstimate(in, estimate.success, estimate.message, {&estimate.pose}, estimate.pose);
}

Result RunRefine(const Input& in) {
  InitializeAndRefineOptions options = in.refine;
  options.robust.solver = in.solver;
  options.robust.ransac = in.ransac;
  options.bundle_adjustment = in.bundle;
  const ThreeViewEstimate estimate = InitializeAndRefine(in.observations, options);
  return ClassifyEstimate(in, estimate.success, estimate.message,
                          {&estimate.robust.pose, &estimate.refined}, estimate.refined);
}

Result RunBundle(const Input& in) {
  ThreeViewBundleAdjuster adjuster(in.observations, in.bundle_config, in.bundle);
  if (!adjuster.Build(in.given_pose)) {
    return adjuster.message().empty() ? Broken("Build() failed without a message")
                                      : Result{kNone, adjuster.message()};
  }
  const ThreeViewBundleAdjustmentSummary summary = adjuster.Solve();
  const ThreeViewPose pose = adjuster.CurrentPose();
  return ClassifyEstimate(in, summary.success, summary.message, {&pose}, pose);
}

Result RunRefineOnly(const Input& in) {
  const std::vector<char> all(in.observations.size(), 1);
  const ThreeViewRefinement refinement =
      RefineThreeViewPose(in.observations, in.given_pose, all, in.bundle);
  if (!refinement.summary.success) {
    return refinement.summary.message.empty() ? Broken("failed without a message")
                                              : Result{kNone, refinement.summary.message};
  }
  return ClassifyEstimate(in, true, "", {&refinement.pose}, refinement.pose);
}

std::function<void(Input*)> UseSolver(InitialSolver solver) {
  return [solver](Input* in) { in->solver = solver; };
}

std::vector<EntryPoint> EntryPoints() {
  using RM = ThreeViewBundleAdjustmentOptions::RotationModel;
  std::vector<EntryPoint> eps;
  auto add = [&eps](Ep id, const std::string& name, int num, int min, unsigned reads,
                    std::function<void(Input*)> configure,
                    std::function<Result(const Input&)> run) {
    EXPECT_EQ(static_cast<int>(eps.size()), id);
    eps.push_back({id, name, num, min, reads, std::move(configure), std::move(run)});
  };
  add(k4ptAligned, "SolveTrifocal4pt (aligned)", 4, 4, kRaySolver, nullptr,
      OnAlignedRays(
          [](const Input&, const std::array<Rays, 3>& x, std::vector<ThreeViewPose>* out) {
            return SolveTrifocal4pt(x[0], x[1], x[2], out);
          }));
  add(k4ptGravity, "SolveTrifocal4pt (gravity)", 4, 4, kRaySolver | kGravity, nullptr,
      OnRawRays([](const Input& in, const std::array<Rays, 3>& x, std::vector<ThreeViewPose>* out) {
        return SolveTrifocal4pt(x[0], x[1], x[2], G(in, 0), G(in, 1), G(in, 2), out);
      }));
  add(
      k4ptAlignedOptions, "SolveTrifocal4pt (aligned, options: 2 epipole passes)", 4, 4,
      kRaySolver | kTrifocal4ptOptions, [](Input* in) { in->trifocal4pt.epipole_iterations = 2; },
      OnAlignedRays(
          [](const Input& in, const std::array<Rays, 3>& x, std::vector<ThreeViewPose>* out) {
            return SolveTrifocal4pt(x[0], x[1], x[2], in.trifocal4pt, out);
          }));
  add(
      k4ptGravityOptions, "SolveTrifocal4pt (gravity, options: paper c8-c11)", 4, 4,
      kRaySolver | kGravity | kTrifocal4ptOptions,
      [](Input* in) {
        in->trifocal4pt.recovery = Trifocal4ptRecovery::kPaperClosedForm;
        in->trifocal4pt.resolve_translations = false;
        in->trifocal4pt.polish_iterations = 0;
      },
      OnRawRays([](const Input& in, const std::array<Rays, 3>& x, std::vector<ThreeViewPose>* out) {
        return SolveTrifocal4pt(x[0], x[1], x[2], G(in, 0), G(in, 1), G(in, 2), in.trifocal4pt,
                                out);
      }));
  add(k4ptGravity20, "SolveTrifocal4pt (gravity, 20 triplets)", 20, 4, kRaySolver | kGravity,
      nullptr,
      OnRawRays([](const Input& in, const std::array<Rays, 3>& x, std::vector<ThreeViewPose>* out) {
        return SolveTrifocal4pt(x[0], x[1], x[2], G(in, 0), G(in, 1), G(in, 2), out);
      }));
  add(k3ptAligned, "SolveTrifocal3pt (aligned)", 3, 3, kRaySolver, nullptr,
      OnAlignedRays(
          [](const Input&, const std::array<Rays, 3>& x, std::vector<ThreeViewPose>* out) {
            return SolveTrifocal3pt(x[0], x[1], x[2], out);
          }));
  add(k3ptGravity, "SolveTrifocal3pt (gravity)", 3, 3, kRaySolver | kGravity, nullptr,
      OnRawRays([](const Input& in, const std::array<Rays, 3>& x, std::vector<ThreeViewPose>* out) {
        return SolveTrifocal3pt(x[0], x[1], x[2], G(in, 0), G(in, 1), G(in, 2), out);
      }));
  add(k3ptSexticAligned, "SolveTrifocal3ptSextic (aligned)", 3, 3, kRaySolver, nullptr,
      OnAlignedRays(
          [](const Input&, const std::array<Rays, 3>& x, std::vector<ThreeViewPose>* out) {
            return SolveTrifocal3ptSextic(x[0], x[1], x[2], out);
          }));
  add(k3ptSexticGravity, "SolveTrifocal3ptSextic (gravity)", 3, 3, kRaySolver | kGravity, nullptr,
      OnRawRays([](const Input& in, const std::array<Rays, 3>& x, std::vector<ThreeViewPose>* out) {
        return SolveTrifocal3ptSextic(x[0], x[1], x[2], G(in, 0), G(in, 1), G(in, 2), out);
      }));
  add(kEssential5pt, "SolveEssential5pt (pair 1-2)", 5, 5, kPairSolver, nullptr,
      [](const Input& in) {
        std::vector<CameraPose> poses;
        const int count = SolveEssential5pt(in.rays[0], in.rays[1], Output(in, &poses));
        return ClassifyPair(in, count, poses);
      });
  add(kEssential8pt, "SolveEssential8pt (pair 1-2)", 8, 8, kPairSolver, nullptr,
      [](const Input& in) {
        std::vector<CameraPose> poses;
        const int count = SolveEssential8pt(in.rays[0], in.rays[1], Output(in, &poses));
        return ClassifyPair(in, count, poses);
      });
  add(kTrifocalLinear, "SolveTrifocalLinear", 7, 7, kRaySolver, nullptr,
      OnRawRays([](const Input&, const std::array<Rays, 3>& x, std::vector<ThreeViewPose>* out) {
        return SolveTrifocalLinear(x[0], x[1], x[2], out);
      }));
  add(kCombinePairs, "CombineTwoViewPairs", 8, 1, kRaySolver | kGivenPose, nullptr,
      [](const Input& in) {
        std::vector<ThreeViewPose> poses;
        std::vector<double> residuals;
        CombineTwoViewPairs(in.rays[0], in.rays[1], in.rays[2], {in.given_pose.cam2_from_cam1},
                            {in.given_pose.cam3_from_cam1}, Output(in, &poses), &residuals);
        if (residuals.size() != poses.size()) return Broken("residuals and poses differ in size");
        return ClassifyThreeView(in, in.truth, static_cast<int>(poses.size()), poses);
      });
  add(kTriangulate, "TriangulateMidpoint", 4, 0, kGeometry | kRays | kOutput | kGivenPose, nullptr,
      RunTriangulate);
  add(kReprojectionError, "ThreeViewReprojectionError", 30, 1, kObservations | kGivenPose, nullptr,
      RunReprojectionError);
  add(kAlignmentFromGravity, "GravityAlignmentFromGravity", 1, 0, kGeometry | kGravity, nullptr,
      RunAlignmentFromGravity);
  add(kAlignmentFromPitchRoll, "GravityAlignmentFromPitchRoll", 1, 0, kPitchRoll, nullptr,
      RunAlignmentFromPitchRoll);
  const unsigned robust_reads = kObservations | kRansacOptions | kSolverChoice;
  for (const InitialSolver solver : kInitialSolvers) {
    add(static_cast<Ep>(eps.size()),
        std::string("EstimateThreeViewPoseRobust (") + InitialSolverName(solver) + ")", 30,
        MinimalSampleSize(solver), robust_reads | kTiltCorrection, UseSolver(solver), RunRobust);
  }
  const unsigned refine_reads = robust_reads | kRefineOptions | kBundleOptions;
  add(kRefine3ptYawOnly, "InitializeAndRefine (3pt, yaw-only)", 30, 3, refine_reads,
      UseSolver(InitialSolver::kTrifocal3pt), RunRefine);
  add(
      kRefine5ptGravityPrior, "InitializeAndRefine (5pt, gravity prior)", 30, 5, refine_reads,
      [](Input* in) {
        in->solver = InitialSolver::kEssential5pt;
        in->bundle.rotation_model = RM::kGravityPrior;
      },
      RunRefine);
  add(
      kRefine3ptGravityPrior, "InitializeAndRefine (3pt, gravity prior)", 30, 3, refine_reads,
      [](Input* in) {
        in->solver = InitialSolver::kTrifocal3pt;
        in->bundle.rotation_model = RM::kGravityPrior;
      },
      RunRefine);
  const unsigned bundle_reads = kObservations | kGivenPose | kBundleOptions | kBundleConfig;
  add(kBundleYawOnly, "ThreeViewBundleAdjuster (yaw-only)", 30, 3, bundle_reads, nullptr,
      RunBundle);
  add(
      kBundleGravityPrior, "ThreeViewBundleAdjuster (gravity prior)", 30, 3, bundle_reads,
      [](Input* in) { in->bundle.rotation_model = RM::kGravityPrior; }, RunBundle);
  add(kRefineOnly, "RefineThreeViewPose (yaw-only)", 30, 3,
      kObservations | kGivenPose | kBundleOptions, nullptr, RunRefineOnly);
  // The kCeres engine (a block per point) behind both kinds of entry point.
  add(
      kRefine3ptCeres, "InitializeAndRefine (3pt, yaw-only, kCeres engine)", 30, 3, refine_reads,
      [](Input* in) {
        in->solver = InitialSolver::kTrifocal3pt;
        in->bundle.engine = ThreeViewBundleAdjustmentOptions::Engine::kCeres;
      },
      RunRefine);
  add(
      kBundleCeres, "ThreeViewBundleAdjuster (gravity prior, kCeres engine)", 30, 3, bundle_reads,
      [](Input* in) {
        in->bundle.rotation_model = RM::kGravityPrior;
        in->bundle.engine = ThreeViewBundleAdjustmentOptions::Engine::kCeres;
      },
      RunBundle);
  return eps;
}

// ------------------------------------------------------------------------------------------------
// The cases: what each changes, which outcomes it allows, and exceptions per entry point.

enum class Count { kDefault, kOneTooFew, kOneMoreThanMinimal, kEmpty };

struct Case {
  std::string group;
  std::string name;
  unsigned touches;  // Fields it changes: it runs on every entry point reading one of them
  unsigned expected;
  std::string message;  // regex the invalid_argument message must contain
  std::function<void(Input*)> change;
  Geometry geometry = Geometry::kGeneric;
  Count count = Count::kDefault;
  // Other allowed outcomes for some entry points; the first set containing one applies.
  std::vector<std::pair<EpSet, unsigned>> overrides;

  unsigned ExpectedFor(Ep ep) const {
    for (const auto& [eps, outcome] : overrides) {
      if (eps & (EpSet{1} << ep)) return outcome;
    }
    return expected;
  }
};

Case MakeCase(std::string group,
              std::string name,
              unsigned touches,
              unsigned expected,
              std::string message,
              std::function<void(Input*)> change,
              Geometry geometry = Geometry::kGeneric,
              Count count = Count::kDefault,
              std::vector<std::pair<EpSet, unsigned>> overrides = {}) {
  return {std::move(group),    std::move(name),   touches,  expected,
          std::move(message),  std::move(change), geometry, count,
          std::move(overrides)};
}

const char* const kXyz[] = {"x", "y", "z"};
const char* const kValueNames[] = {"NaN", "+Inf", "-Inf"};
const double kBadValues[] = {kNaN, kInf, -kInf};

void AddNonFiniteCases(std::vector<Case>* cases) {
  for (int k = 0; k < 3; ++k) {
    const std::string view = std::to_string(k + 1);
    const unsigned ray_field = kRays1 << k;
    for (const bool last : {false, true}) {
      const std::string index = last ? "[0-9]+" : "0";
      const std::string which = last ? "last" : "first";
      for (int c = 0; c < 3; ++c) {
        for (int v = 0; v < 3; ++v) {
          cases->push_back(
              MakeCase("NaN / Inf in a ray",
                       std::string(kValueNames[v]) + " in " + kXyz[c] + " of the " + which +
                           " ray of view " + view,
                       ray_field, kThrows, "x" + view + "\\[" + index + "\\] is not finite",
                       [=](Input* in) {
                         const std::size_t n = last ? in->rays[k].size() - 1 : 0;
                         in->rays[k][n][c] = kBadValues[v];
                         in->aligned_rays[k][n][c] = kBadValues[v];
                       },
                       Geometry::kGeneric, Count::kDefault, {{Eps({kTriangulate}), kNone}}));
        }
      }
      cases->push_back(MakeCase(
          "zero-length or overflowing ray or gravity", "zero " + which + " ray of view " + view,
          ray_field, kThrows, "x" + view + "\\[" + index + "\\] is a zero-length ray",
          [=](Input* in) {
            const std::size_t n = last ? in->rays[k].size() - 1 : 0;
            in->rays[k][n].setZero();
            in->aligned_rays[k][n].setZero();
          },
          Geometry::kGeneric, Count::kDefault, {{Eps({kTriangulate}), kNone}}));
      for (int c = 0; c < 2; ++c) {
        for (int v = 0; v < 3; ++v) {
          cases->push_back(
              MakeCase("NaN / Inf in a pixel",
                       std::string(kValueNames[v]) + " in " + (c == 0 ? "u" : "v") + " of the " +
                           which + " pixel of view " + view,
                       kPixels, kThrows,
                       "pixels\\[" + std::to_string(k) + "\\]\\[" + index + "\\] is not finite",
                       [=](Input* in) {
                         auto& pixels = in->observations.pixels[k];
                         pixels[last ? pixels.size() - 1 : 0][c] = kBadValues[v];
                       }));
        }
      }
    }
    // Solvers name gravity_in_camK, observations gravity_in_cam[k-1], the alignment its argument.
    const std::string gravity =
        "gravity(_in_cam" + view + "|_in_cam\\[" + std::to_string(k) + "\\]| direction)";
    for (int c = 0; c < 3; ++c) {
      for (int v = 0; v < 3; ++v) {
        cases->push_back(
            MakeCase("NaN / Inf in gravity",
                     std::string(kValueNames[v]) + " in " + kXyz[c] + " of gravity in view " + view,
                     kGravity, kThrows, gravity + " (is not finite|has non-finite entries)",
                     [=](Input* in) { in->observations.gravity_in_cam[k][c] = kBadValues[v]; }));
      }
    }
    cases->push_back(MakeCase("zero-length or overflowing ray or gravity",
                              "zero gravity in view " + view, kGravity, kThrows,
                              gravity + " (is zero|has zero length|is not set \\(zero\\))",
                              [=](Input* in) { in->observations.gravity_in_cam[k].setZero(); }));
    // Lengths whose square overflows or underflows to 0: named as such, not as zero.
    struct Length {
      double value;
      const char* name;
      const char* problem;
    };
    for (const Length& length :
         {Length{1e200, "1e200", "too long to normalise \\(length 1e\\+200"},
          Length{1e-300, "1e-300", "too short to normalise \\(length 1e-300"}}) {
      auto rescale = [value = length.value](Eigen::Vector3d* v) { *v *= value / v->norm(); };
      cases->push_back(
          MakeCase("zero-length or overflowing ray or gravity",
                   std::string("gravity of length ") + length.name + " in view " + view, kGravity,
                   kThrows, gravity + " is " + length.problem,
                   [=](Input* in) { rescale(&in->observations.gravity_in_cam[k]); }));
      cases->push_back(MakeCase("zero-length or overflowing ray or gravity",
                                "first ray of view " + view + " of length " + length.name,
                                ray_field, kThrows, "x" + view + "\\[0\\] is " + length.problem,
                                [=](Input* in) {
                                  rescale(&in->rays[k][0]);
                                  rescale(&in->aligned_rays[k][0]);
                                },
                                Geometry::kGeneric, Count::kDefault,
                                {{Eps({kTriangulate}), kNone}}));
    }
    // Intrinsics.
    const std::string camera_message = "camera " + view + " needs positive, finite focal lengths";
    for (const char* field : {"fx", "fy", "cx", "cy"}) {
      const bool focal = field[0] == 'f';
      std::vector<std::pair<std::string, double>> values = {{"NaN", kNaN}, {"+Inf", kInf}};
      if (focal) values.insert(values.end(), {{"0", 0.0}, {"-500", -500.0}, {"-Inf", -kInf}});
      for (const auto& [value_name, value] : values) {
        cases->push_back(MakeCase(
            "bad intrinsics", std::string(field) + " = " + value_name + " in camera " + view,
            kIntrinsics, kThrows, camera_message, [=, f = std::string(field)](Input* in) {
              // PINHOLE parameters: fx, fy, cx, cy.
              in->observations.cameras[k].params[f == "fx"   ? 0
                                                 : f == "fy" ? 1
                                                 : f == "cx" ? 2
                                                             : 3] = value;
            }));
      }
    }
  }
}

void AddSizeCases(std::vector<Case>* cases) {
  const std::string group = "sizes, empty, null output";
  const EpSet triplet_lists =
      kTrifocalSolvers | Eps({kEssential5pt, kEssential8pt, kTrifocalLinear});
  const EpSet estimates = kRobust | kRefine | kBundle | Eps({kCombinePairs, kReprojectionError});
  for (int k = 0; k < 3; ++k) {
    cases->push_back(MakeCase(group, "view " + std::to_string(k + 1) + " has one triplet less",
                              kSize1 << k, kThrows, "differ in size", [k](Input* in) {
                                in->rays[k].pop_back();
                                in->aligned_rays[k].pop_back();
                                in->observations.pixels[k].pop_back();
                              }));
  }
  cases->push_back(MakeCase(group, "one triplet fewer than the minimum", kSizes, kThrows,
                            "needs (at least|exactly) [0-9]+ (triplets|correspondences), got",
                            nullptr, Geometry::kGeneric, Count::kOneTooFew, {{estimates, kNone}}));
  // The robust estimates refuse fewer than min_inliers (15) triplets (robust_three_view.h).
  cases->push_back(MakeCase(group, "one triplet more than the minimal sample", kSizes, kTruth,
                            "needs exactly [0-9]+ (triplets|correspondences), got", nullptr,
                            Geometry::kGeneric, Count::kOneMoreThanMinimal,
                            {{kRobust | kRefine, kNone}, {kExactCountSolvers, kThrows}}));
  cases->push_back(MakeCase(group, "empty input", kSizes, kNone,
                            "needs (at least|exactly) [0-9]+ (triplets|correspondences), got 0",
                            nullptr, Geometry::kGeneric, Count::kEmpty,
                            {{triplet_lists, kThrows}}));
  cases->push_back(MakeCase(group, "null output", kOutput, kThrows,
                            "(solutions|poses|point_in_ref) is null",
                            [](Input* in) { in->null_output = true; }));
}

template <typename Options>
void AddOptionCases(
    std::vector<Case>* cases,
    const std::string& group,
    unsigned field,
    const std::string& message_prefix,
    const std::vector<std::pair<std::string, std::function<void(Options*)>>>& changes,
    Options Input::*member) {
  for (const auto& [name, change] : changes) {
    // The message names the field: "Options::field = value" or "field out of range" -> field.
    const std::size_t scope = name.find("::");
    const std::size_t begin = scope == std::string::npos ? 0 : scope + 2;
    const std::string field_name = name.substr(begin, name.find(' ', begin) - begin);
    cases->push_back(MakeCase(group, name, field, kThrows, message_prefix + ".*" + field_name,
                              [change = change, member](Input* in) { change(&(in->*member)); }));
  }
}

void AddOptionCases(std::vector<Case>* cases) {
  const std::string group = "bad option fields";
  using RO = RansacOptions;
  AddOptionCases<RO>(
      cases, group, kRansacOptions, "RansacOptions: ",
      {{"RansacOptions::max_error = NaN", [](RO* o) { o->max_error = kNaN; }},
       {"RansacOptions::max_error = 0", [](RO* o) { o->max_error = 0.0; }},
       {"RansacOptions::max_error = -1", [](RO* o) { o->max_error = -1.0; }},
       {"RansacOptions::max_error = +Inf", [](RO* o) { o->max_error = kInf; }},
       {"RansacOptions::confidence = NaN", [](RO* o) { o->confidence = kNaN; }},
       {"RansacOptions::confidence = 0", [](RO* o) { o->confidence = 0.0; }},
       {"RansacOptions::confidence = 1", [](RO* o) { o->confidence = 1.0; }},
       {"RansacOptions::min_iterations = -1", [](RO* o) { o->min_iterations = -1; }},
       {"RansacOptions::max_iterations = 0", [](RO* o) { o->max_iterations = 0; }},
       {"RansacOptions::max_iterations < min_iterations", [](RO* o) { o->max_iterations = 5; }},
       {"RansacOptions::local_optimization_rounds = -1",
        [](RO* o) { o->local_optimization_rounds = -1; }},
       {"RansacOptions::local_optimization_threshold_multiplier = NaN",
        [](RO* o) { o->local_optimization_threshold_multiplier = kNaN; }},
       {"RansacOptions::local_optimization_threshold_multiplier = 0.5",
        [](RO* o) { o->local_optimization_threshold_multiplier = 0.5; }}},
      &Input::ransac);
  for (const auto& [name, value] :
       {std::pair<const char*, double>{"NaN", kNaN}, {"-2", -2.0}, {"90", 90.0}, {"+Inf", kInf}}) {
    cases->push_back(MakeCase(group, std::string("max_tilt_correction_deg = ") + name,
                              kTiltCorrection, kThrows,
                              "RobustThreeViewOptions: max_tilt_correction_deg",
                              [value = value](Input* in) { in->max_tilt_correction_deg = value; }));
  }
  // A valid bound: noise-free data with exact gravity keep their true pose.
  cases->push_back(MakeCase("valid options", "max_tilt_correction_deg = 0.5", kTiltCorrection,
                            kTruth, "", [](Input* in) { in->max_tilt_correction_deg = 0.5; }));
  using IO = InitializeAndRefineOptions;
  AddOptionCases<IO>(
      cases, group, kRefineOptions, "InitializeAndRefineOptions: ",
      {{"reclassification_rounds = -1", [](IO* o) { o->reclassification_rounds = -1; }}},
      &Input::refine);
  cases->push_back(MakeCase(group, "InitialSolver value out of range", kSolverChoice, kThrows,
                            "unknown (InitialSolver value|solver)",
                            [](Input* in) { in->solver = static_cast<InitialSolver>(99); }));
  using BO = ThreeViewBundleAdjustmentOptions;
  AddOptionCases<BO>(
      cases, group, kBundleOptions, "ThreeViewBundleAdjustmentOptions: ",
      {{"loss_scale_px = NaN", [](BO* o) { o->loss_scale_px = kNaN; }},
       {"loss_scale_px = 0", [](BO* o) { o->loss_scale_px = 0.0; }},
       {"loss_scale_px = -1", [](BO* o) { o->loss_scale_px = -1.0; }},
       {"pixel_sigma_px = NaN", [](BO* o) { o->pixel_sigma_px = kNaN; }},
       {"pixel_sigma_px = 0", [](BO* o) { o->pixel_sigma_px = 0.0; }},
       {"gravity_sigma_deg = NaN", [](BO* o) { o->gravity_sigma_deg = kNaN; }},
       {"gravity_sigma_deg = 0", [](BO* o) { o->gravity_sigma_deg = 0.0; }},
       {"gravity_sigma_deg = +Inf", [](BO* o) { o->gravity_sigma_deg = kInf; }},
       {"max_num_iterations = -1", [](BO* o) { o->max_num_iterations = -1; }},
       {"num_threads = 0", [](BO* o) { o->num_threads = 0; }},
       {"function_tolerance = NaN", [](BO* o) { o->function_tolerance = kNaN; }},
       {"gradient_tolerance = -1", [](BO* o) { o->gradient_tolerance = -1.0; }},
       {"parameter_tolerance = NaN", [](BO* o) { o->parameter_tolerance = kNaN; }},
       {"rotation_model out of range",
        [](BO* o) { o->rotation_model = static_cast<BO::RotationModel>(7); }},
       {"loss out of range", [](BO* o) { o->loss = static_cast<BO::LossType>(7); }},
       {"engine out of range", [](BO* o) { o->engine = static_cast<BO::Engine>(7); }},
       {"linear_solver_type out of range",
        [](BO* o) { o->linear_solver_type = static_cast<ceres::LinearSolverType>(7); }}},
      &Input::bundle);
  cases->push_back(MakeCase(group, "bundle config: triplet index -1", kBundleConfig, kThrows,
                            "triplet index out of range", [](Input* in) {
                              in->bundle_config.triplets = {0, 1, -1};
                            }));
  cases->push_back(
      MakeCase(group, "bundle config: triplet index = number of triplets", kBundleConfig, kThrows,
               "triplet index out of range", [](Input* in) {
                 in->bundle_config.triplets = {0, 1, static_cast<int>(in->observations.size())};
               }));
  using TO = Trifocal4ptOptions;
  AddOptionCases<TO>(
      cases, group, kTrifocal4ptOptions, "Trifocal4ptOptions: ",
      {{"Trifocal4ptOptions::recovery out of range",
        [](TO* o) { o->recovery = static_cast<Trifocal4ptRecovery>(7); }},
       {"Trifocal4ptOptions::epipoles out of range",
        [](TO* o) { o->epipoles = static_cast<Trifocal4ptEpipoles>(7); }},
       {"Trifocal4ptOptions::epipole_iterations = -1", [](TO* o) { o->epipole_iterations = -1; }},
       {"Trifocal4ptOptions::polish_iterations = -1", [](TO* o) { o->polish_iterations = -1; }}},
      &Input::trifocal4pt);
  for (const auto& [name, pitch, roll] :
       {std::tuple<const char*, double, double>{"pitch = NaN", kNaN, 0.0},
        {"pitch = -Inf", -kInf, 0.0},
        {"roll = +Inf", 0.0, kInf},
        {"roll = NaN", 0.0, kNaN}}) {
    cases->push_back(MakeCase(group, name, kPitchRoll, kThrows, "pitch or roll is not finite",
                              [pitch = pitch, roll = roll](Input* in) {
                                in->pitch_rad = pitch;
                                in->roll_rad = roll;
                              }));
  }
}

void AddGivenPoseCases(std::vector<Case>* cases) {
  const std::string group = "non-finite or degenerate pose handed in";
  cases->push_back(
      MakeCase(group, "NaN in R of camera 2", kGivenPose, kNone, "pair12\\[0\\] is not finite",
               [](Input* in) { in->given_pose.cam2_from_cam1.R(0, 0) = kNaN; }, Geometry::kGeneric,
               Count::kDefault, {{Eps({kCombinePairs}), kThrows}}));
  cases->push_back(
      MakeCase(group, "+Inf in t of camera 3", kGivenPose, kNone, "pair13\\[0\\] is not finite",
               [](Input* in) { in->given_pose.cam3_from_cam1.t.y() = kInf; }, Geometry::kGeneric,
               Count::kDefault, {{Eps({kCombinePairs}), kThrows}}));
  cases->push_back(MakeCase(group, "camera 2 centre at camera 1 (|C2| = 0)", kGivenPose, kNone, "",
                            [](Input* in) { in->given_pose.cam2_from_cam1.t.setZero(); },
                            Geometry::kGeneric, Count::kDefault,
                            {{Eps({kTriangulate, kReprojectionError}), kOther}}));
}

void AddGeometryCases(std::vector<Case>* cases) {
  const std::string valid = "valid extremes (true pose required)";
  const std::string degenerate = "degenerate geometry";
  auto add = [cases](const std::string& group, const std::string& name, Geometry geometry,
                     unsigned expected, std::vector<std::pair<EpSet, unsigned>> overrides = {}) {
    // The gravity directions of every scene are valid.
    overrides.push_back({Eps({kAlignmentFromGravity}), kTruth});
    cases->push_back(MakeCase(group, name, kGeometry, expected, "", nullptr, geometry,
                              Count::kDefault, std::move(overrides)));
  };
  add(valid, "generic scene (control)", Geometry::kGeneric, kTruth);
  add(valid, "yaw of exactly 180 deg, camera 2", Geometry::kYaw180Camera2, kTruth);
  add(valid, "yaw of exactly 180 deg, cameras 2 and 3", Geometry::kYaw180Cameras23, kTruth);
  add(valid, "gravity = -y (camera 2 upside down)", Geometry::kUpsideDownCamera2, kTruth);
  add(valid, "gravity = -y in all three cameras", Geometry::kUpsideDownAll, kTruth);
  add(valid, "forward motion (collinear centres)", Geometry::kForwardMotion, kTruth);
  for (const double scale : {1e-6, 1e6}) {
    cases->push_back(
        MakeCase(valid, "rays of view 2 scaled by " + std::string(scale < 1.0 ? "1e-6" : "1e6"),
                 kRays2, kTruth, "", [scale](Input* in) {
                   for (Eigen::Vector3d& x : in->rays[1]) x *= scale;
                   for (Eigen::Vector3d& x : in->aligned_rays[1]) x *= scale;
                 }));
  }
  for (const auto& [name, pitch, roll] : {std::tuple<const char*, double, double>{
                                              "pitch 89.9 deg, roll -179 deg", 1.569051, -3.124139},
                                          {"pitch and roll of 1e6 rad", 1e6, -1e6}}) {
    cases->push_back(
        MakeCase(valid, name, kPitchRoll, kTruth, "", [pitch = pitch, roll = roll](Input* in) {
          in->pitch_rad = pitch;
          in->roll_rad = roll;
        }));
  }
  // Entry points that evaluate the pose handed in (the truth) rather than estimate one.
  const EpSet evaluators = Eps({kCombinePairs, kTriangulate, kReprojectionError}) | kBundle;
  const EpSet decoupled_3pt = Eps({k3ptAligned, k3ptGravity, kRobust3pt, kRefine3ptYawOnly,
                                   kRefine3ptGravityPrior, kRefine3ptCeres});
  add(degenerate, "duplicate triplet", Geometry::kDuplicateTriplet, kTruth,
      {{kMinimalSolvers, kNone}});
  add(degenerate, "all points identical", Geometry::kAllPointsIdentical, kNone,
      {{evaluators, kTruth}});
  // Not degenerate for the upright pairs of the decoupled 3-point solver; the 4-point and linear
  // tensors and the two-view methods have no unique answer.
  // The robust estimates may refuse it: the predicted precision is poor (4.9 deg for 3pt).
  add(degenerate, "collinear points", Geometry::kCollinearPoints, kDegenerate,
      {{kRobust | kRefine, kTruth | kNone}, {decoupled_3pt | evaluators, kTruth}});
  add(degenerate, "points at infinity (rays parallel across views)", Geometry::kPointsAtInfinity,
      kNone);
  add(degenerate, "zero baseline, camera 2", Geometry::kZeroBaseline2, kNone,
      {{Eps({kTriangulate, kReprojectionError}), kTruth}});
  // C3 = 0 is a valid pose (relative scale 0), found by the decoupled 3-point pipeline and, after
  // bundle adjustment, from the five-point seed; pair (1,2) alone is fine. The trifocal incidence
  // of a camera without baseline is void, and pair (1,3) has no epipole, so the other methods have
  // no unique answer.
  // The robust estimates may refuse it: camera 3's centre direction is undetermined.
  add(degenerate, "zero baseline, camera 3", Geometry::kZeroBaseline3, kDegenerate,
      {{kRobust | kRefine, kTruth | kNone},
       {Eps({kRobust3pt, kRefine3ptYawOnly, kRefine5ptGravityPrior, kRefine3ptGravityPrior,
             kRefine3ptCeres, kEssential5pt, kEssential8pt, kTriangulate, kReprojectionError}) |
            kBundle,
        kTruth},
       {Eps({kCombinePairs}), kNone}});
  add(degenerate, "zero baselines, cameras 2 and 3", Geometry::kZeroBaselines, kNone);
  add(degenerate, "identical views", Geometry::kIdenticalViews, kNone);
  add(degenerate, "100 % outliers", Geometry::kAllOutliers, kDegenerate,
      {{kRobust | kRefine, kNone}});
}

std::vector<Case> Cases() {
  std::vector<Case> cases;
  AddNonFiniteCases(&cases);
  AddSizeCases(&cases);
  AddOptionCases(&cases);
  AddGivenPoseCases(&cases);
  AddGeometryCases(&cases);
  return cases;
}

bool Applies(const Case& c, const EntryPoint& ep) {
  if ((c.touches & ep.reads) == 0) return false;
  return c.count != Count::kOneTooFew || ep.min_triplets > 0;
}

int TripletCount(const Case& c, const EntryPoint& ep) {
  switch (c.count) {
    case Count::kDefault:
      return ep.num_triplets;
    case Count::kOneTooFew:
      return ep.min_triplets - 1;
    case Count::kOneMoreThanMinimal:
      return ep.min_triplets + 1;
    case Count::kEmpty:
      return 0;
  }
  return ep.num_triplets;
}

Result RunCatchingExceptions(const EntryPoint& ep, const Input& input) {
  try {
    return ep.run(input);
  } catch (const std::invalid_argument& e) {
    return {kThrows, e.what()};
  } catch (const std::exception& e) {
    return Broken(std::string("unexpected exception: ") + e.what());
  } catch (...) {
    return Broken("unexpected non-standard exception");
  }
}

// ------------------------------------------------------------------------------------------------
// Counts for the summary.

struct Tally {
  std::map<std::string, std::map<unsigned, int>> by_key;
  std::map<std::string, int> cases_by_group;
  void Add(const std::string& key, unsigned outcome) { ++by_key[key][outcome]; }
};

void PrintTable(const std::string& title,
                const std::vector<std::string>& keys,
                const Tally& tally,
                const std::map<std::string, int>* cases) {
  std::printf(
      "\n| %s |%s runs | invalid_argument | no solution | true pose | finite, not the truth | "
      "broken |\n|---|%s---|---|---|---|---|---|\n",
      title.c_str(), cases ? " cases |" : "", cases ? "---|" : "");
  std::map<unsigned, int> total;
  int total_cases = 0;
  for (const std::string& key : keys) {
    const std::map<unsigned, int>& counts = tally.by_key.at(key);
    int runs = 0;
    for (const auto& [outcome, n] : counts) {
      runs += n;
      total[outcome] += n;
    }
    std::printf("| %s |", key.c_str());
    if (cases) {
      std::printf(" %d |", cases->at(key));
      total_cases += cases->at(key);
    }
    std::printf(" %d |", runs);
    for (const Outcome o : kOutcomes) {
      std::printf(" %d |", counts.count(o) ? counts.at(o) : 0);
    }
    std::printf("\n");
  }
  int runs = 0;
  for (const auto& [outcome, n] : total) runs += n;
  std::printf("| total |");
  if (cases) std::printf(" %d |", total_cases);
  std::printf(" %d |", runs);
  for (const Outcome o : kOutcomes) std::printf(" %d |", total.count(o) ? total.at(o) : 0);
  std::printf("\n");
}

TEST(BadInputMatrix, EveryEntryPointAgainstEveryCase) {
  const std::vector<EntryPoint> entry_points = EntryPoints();
  const std::vector<Case> cases = Cases();
  Tally by_entry_point, by_group;
  std::vector<std::string> groups;
  int runs = 0;
  for (const Case& c : cases) {
    if (by_group.cases_by_group.count(c.group) == 0) groups.push_back(c.group);
    ++by_group.cases_by_group[c.group];
    int applied = 0;
    for (const EntryPoint& ep : entry_points) {
      if (!Applies(c, ep)) continue;
      ++applied;
      ++runs;
      Input input = MakeInput(c.geometry, TripletCount(c, ep));
      if (ep.configure) ep.configure(&input);
      if (c.change) c.change(&input);
      const Result result = RunCatchingExceptions(ep, input);
      by_entry_point.Add(ep.name, result.outcome);
      by_group.Add(c.group, result.outcome);
      const unsigned expected = c.ExpectedFor(ep.id);
      EXPECT_TRUE((result.outcome & expected) != 0)
          << c.name << " / " << ep.name << ": " << OutcomeName(result.outcome) << " ("
          << result.detail << "), expected " << OutcomeNames(expected);
      if (result.outcome == kThrows) {
        EXPECT_EQ(result.detail.rfind("trigrav: ", 0), 0u) << c.name << " / " << ep.name;
        EXPECT_TRUE(std::regex_search(result.detail, std::regex(c.message)))
            << c.name << " / " << ep.name << ": message \"" << result.detail
            << "\" does not match \"" << c.message << "\"";
      }
    }
    EXPECT_GT(applied, 0) << c.name << " applies to no entry point";
  }
  std::vector<std::string> ep_names;
  for (const EntryPoint& ep : entry_points) ep_names.push_back(ep.name);
  std::printf("\nBad-input matrix: %zu cases x %zu entry points, %d (case, entry point) runs\n",
              cases.size(), entry_points.size(), runs);
  PrintTable("entry point", ep_names, by_entry_point, nullptr);
  PrintTable("case group", groups, by_group, &by_group.cases_by_group);
}

// The robust estimator's parallax test with noise (the matrix is noise-free): 1 px of image noise
// and 20 % outliers, threshold 3 px. Without baseline of camera 2 every method must report failure
// with the reason; the generic scene with the same noise must still be estimated within 5 deg, or
// refused as uncertain where the linear solvers' poses lie off their inliers' optimum.
TEST(BadInputMatrix, RobustEstimatorRejectsNoisyDataWithoutParallax) {
  for (const Geometry geometry : {Geometry::kZeroBaseline2, Geometry::kZeroBaselines,
                                  Geometry::kIdenticalViews, Geometry::kGeneric}) {
    Input input = MakeInput(geometry, 150);
    std::mt19937_64 rng(7);
    std::normal_distribution<double> noise(0.0, 1.0);
    std::uniform_real_distribution<double> u(0.0, 640.0), v(0.0, 480.0);
    for (std::size_t n = 0; n < input.observations.size(); ++n) {
      for (auto& view : input.observations.pixels) {
        view[n] += Eigen::Vector2d(noise(rng), noise(rng));
      }
      if (n % 5 == 0) input.observations.pixels[n % 3][n] = Eigen::Vector2d(u(rng), v(rng));
    }
    for (const InitialSolver solver : kInitialSolvers) {
      RobustThreeViewOptions options;
      options.solver = solver;
      options.ransac.max_error = 3.0;
      const RobustThreeViewEstimate estimate =
          EstimateThreeViewPoseRobust(input.observations, options);
      if (geometry != Geometry::kGeneric) {
        EXPECT_FALSE(estimate.success) << InitialSolverName(solver);
        // Refused for its baseline: none, or (with the noise) too little for a pose within
        // max_pose_sigma_deg; either message names the baseline.
        EXPECT_TRUE(estimate.cause == FailureCause::kNoParallax ||
                    estimate.cause == FailureCause::kUncertainPose)
            << InitialSolverName(solver) << ": " << estimate.message;
        EXPECT_NE(estimate.message.find("baseline"), std::string::npos) << estimate.message;
        continue;
      }
      if (!estimate.success) {
        // The linear solvers' poses may lie degrees off their inliers' optimum (8pt: 5.3 deg at a
        // sigma of 0.9 deg, the pose itself 7.6 deg off in translation; the linear tensor 5.5
        // deg): uncertain as the answer of a call without refinement.
        EXPECT_TRUE(solver == InitialSolver::kTrifocalLinear ||
                    solver == InitialSolver::kEssential8pt)
            << InitialSolverName(solver) << ": " << estimate.message;
        EXPECT_EQ(estimate.cause, FailureCause::kUncertainPose) << estimate.message;
        EXPECT_NE(estimate.message.find("inliers' optimum"), std::string::npos) << estimate.message;
        continue;
      }
      ASSERT_TRUE(estimate.success) << InitialSolverName(solver) << ": " << estimate.message;
      const ThreeViewPoseErrors e = ComputeThreeViewPoseErrors(input.truth, estimate.pose);
      // Estimated, not rejected: errors at the level of robust_three_view_test (the linear
      // trifocal tensor, far weaker, within its 3 deg there).
      EXPECT_LT(e.MaxRotationDeg(), solver == InitialSolver::kTrifocalLinear ? 3.0 : 1.0)
          << InitialSolverName(solver);
      EXPECT_LT(e.MaxTranslationDeg(), 5.0) << InitialSolverName(solver);
    }
  }
}

}  // namespace
}  // namespace bad_input
}  // namespace trigrav
