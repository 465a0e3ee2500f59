#include "trigrav/ba/initialize_and_refine.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <utility>

#include "refine_with_shared_error.h"
#include "trigrav/initializers/three_view_error.h"

namespace trigrav {
namespace {

// With pitch and roll errors N(0, sigma^2) per camera, the relative tilt of two cameras has the
// Rayleigh distribution of scale sqrt(2) sigma: it exceeds 4 sqrt(2) sigma with probability
// exp(-8) = 3e-4.
constexpr double kTiltCorrectionSigmas = 4.0;
// A sigma of degrees says the gravity is hardly known; the correction stays a tilt, below 90 deg.
constexpr double kMaxTiltCorrectionDeg = 45.0;
// The gravity-free estimate's own tilt error, which a gravity consistency bound must exceed
// (derivations.md section 7.6).
constexpr double kMinGravityInconsistencyDeg = 1.0;

// The yaw-only refinement may move the verified RANSAC pose at most this far (deg, a rotation or a
// centre's direction): the verdict judged that pose, and a larger move means that the exact
// gravity the model imposes contradicts it (derivations.md 7.7: a noisy gravity) or, when the
// RANSAC pose lay off its inliers' optimum, that the geometry is too weak for it.
constexpr double kMaxRefinementShiftDeg = 5.0;

constexpr double kDegPerRad = 180.0 / M_PI;

// The largest angle (deg) between the two poses' rotations and between their centres' directions,
// views 2 and 3.
double PoseShiftDeg(const ThreeViewPose& a, const ThreeViewPose& b) {
  double shift = 0.0;
  for (const auto& [x, y] : {std::pair(&a.cam2_from_cam1, &b.cam2_from_cam1),
                             std::pair(&a.cam3_from_cam1, &b.cam3_from_cam1)}) {
    shift = std::max(shift, kDegPerRad * Eigen::AngleAxisd(x->R * y->R.transpose()).angle());
    const Eigen::Vector3d cx = x->Center(), cy = y->Center();
    shift = std::max(shift, kDegPerRad * std::atan2(cx.cross(cy).norm(), cx.dot(cy)));
  }
  return shift;
}

double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// RobustThreeViewOptions::max_tilt_correction_deg with kTiltCorrectionFromGravitySigma resolved
// (header).
double TiltCorrectionBoundDeg(const InitializeAndRefineOptions& options) {
  const double bound = options.robust.max_tilt_correction_deg;
  if (bound != RobustThreeViewOptions::kTiltCorrectionFromGravitySigma) return bound;
  if (options.bundle_adjustment.rotation_model !=
      ThreeViewBundleAdjustmentOptions::RotationModel::kGravityPrior) {
    return 0.0;
  }
  return std::min(
      kTiltCorrectionSigmas * std::sqrt(2.0) * options.bundle_adjustment.gravity_sigma_deg,
      kMaxTiltCorrectionDeg);
}

// RobustThreeViewOptions::max_gravity_inconsistency_deg with
// kGravityConsistencyFromGravitySigma resolved (robust_three_view.h): the tilt bound's 4 sqrt(2)
// sigma, at least kMinGravityInconsistencyDeg for the gravity-free estimate's own error.
double GravityInconsistencyBoundDeg(const InitializeAndRefineOptions& options) {
  const double bound = options.robust.max_gravity_inconsistency_deg;
  if (bound != RobustThreeViewOptions::kGravityConsistencyFromGravitySigma) return bound;
  return std::max(
      kTiltCorrectionSigmas * std::sqrt(2.0) * options.bundle_adjustment.gravity_sigma_deg,
      kMinGravityInconsistencyDeg);
}

}  // namespace

void InitializeAndRefineOptions::Check() const {
  if (reclassification_rounds < 0) {
    throw std::invalid_argument(
        "trigrav: InitializeAndRefineOptions: reclassification_rounds must be >= 0");
  }
  robust.Check();
  bundle_adjustment.Check();
}

ThreeViewEstimate InitializeAndRefine(const ThreeViewObservations& observations,
                                      const InitializeAndRefineOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  observations.Check();
  options.Check();

  ThreeViewEstimate estimate;
  RobustThreeViewOptions robust = options.robust;
  robust.max_tilt_correction_deg = TiltCorrectionBoundDeg(options);
  robust.max_gravity_inconsistency_deg = GravityInconsistencyBoundDeg(options);
  robust.refined_afterwards = options.refine;
  estimate.robust = EstimateThreeViewPoseRobust(observations, robust);
  const RobustThreeViewEstimate& ransac = estimate.robust;
  estimate.timings.ransac_s = SecondsSince(start);
  estimate.cause = ransac.cause;
  if (!ransac.success || !ransac.pose.IsFinite()) {
    estimate.message = ransac.success ? "initial pose is not finite" : ransac.message;
    estimate.timings.total_s = SecondsSince(start);
    return estimate;
  }
  estimate.success = true;
  estimate.refined = ransac.pose;
  estimate.inliers = ransac.inliers;
  estimate.num_inliers = ransac.ransac.num_inliers;
  if (!options.refine) {
    estimate.timings.total_s = SecondsSince(start);
    return estimate;
  }

  const auto refinement_start = std::chrono::steady_clock::now();
  // The inlier error, for the runs' adjusters and the re-classification.
  const auto error = std::make_shared<const ThreeViewReprojectionError>(observations);
  estimate.timings.reclassification_s = SecondsSince(refinement_start);
  const double threshold = options.robust.InlierThreshold(observations);
  std::vector<char> inliers = ransac.inliers;
  ThreeViewEstimateTimings& timings = estimate.timings;
  for (int run = 0; run <= options.reclassification_rounds; ++run) {
    // A later run starts from the last refinement's pose and points.
    ThreeViewRefinement refinement = internal::RefineThreeViewPose(
        observations, error, estimate.refined, inliers, options.bundle_adjustment,
        run == 0 ? nullptr : &estimate.refinement);
    timings.build_s += refinement.build_s;
    timings.solve_s += refinement.summary.solve_s;
    timings.covariance_s += refinement.covariance_s;
    if (options.bundle_adjustment.stop_requested && options.bundle_adjustment.stop_requested()) {
      estimate.success = false;
      estimate.cause = FailureCause::kStopped;
      estimate.message = "stopped on request (bundle_adjustment.stop_requested)";
      estimate.timings.total_s = SecondsSince(start);
      return estimate;
    }
    if (!refinement.summary.success || !refinement.pose.IsFinite()) {
      if (run == 0) {
        estimate.message =
            "refinement failed, keeping the initial pose: " + refinement.summary.message;
        estimate.refinement = std::move(refinement);
        // The RANSAC pose stays the answer: its offset from its inliers' optimum counts, as in a
        // call without refinement (robust_three_view.h, refined_afterwards).
        const double sigma_with_offset = ransac.evidence.SigmaWithOffsetDeg();
        if (!(sigma_with_offset <= robust.max_pose_sigma_deg)) {
          char message[160];
          std::snprintf(message, sizeof(message),
                        "refinement failed, and the RANSAC pose lies off its inliers' optimum "
                        "(sigma + offset / 4 = %.2g > max_pose_sigma_deg %.2g): ",
                        sigma_with_offset, robust.max_pose_sigma_deg);
          estimate.success = false;
          estimate.cause = FailureCause::kUncertainPose;
          estimate.message = message + estimate.refinement.summary.message;
          estimate.timings.total_s = SecondsSince(start);
          return estimate;
        }
      }
      break;
    }
    ++estimate.refinement_runs;
    estimate.refined = refinement.pose;
    estimate.inliers = inliers;
    estimate.num_inliers = static_cast<int>(std::count(inliers.begin(), inliers.end(), 1));
    estimate.refinement = std::move(refinement);
    if (run == options.reclassification_rounds) break;
    // Re-classify against the refined pose; stop when nothing changes.
    const auto reclassification_start = std::chrono::steady_clock::now();
    const ThreeViewReprojectionError::PreparedPose prepared =
        ThreeViewReprojectionError::Prepare(estimate.refined);
    std::vector<char> next(observations.size(), 0);
    int num_next = 0;
    for (std::size_t i = 0; i < next.size(); ++i) {
      next[i] = (*error)(prepared, i) <= threshold ? 1 : 0;
      num_next += next[i];
    }
    timings.reclassification_s += SecondsSince(reclassification_start);
    if (next == inliers || num_next < MinimalSampleSize(options.robust.solver)) break;
    inliers.swap(next);
  }
  estimate.timings.refinement_s = SecondsSince(refinement_start);
  estimate.timings.total_s = SecondsSince(start);
  // Only the yaw-only model fixes the tilt; the gravity-prior one frees it and may rightly move a
  // RANSAC pose further (synthetic, 0.5 deg of IMU noise: 4 of 150 calls).
  const double shift = PoseShiftDeg(estimate.robust.pose, estimate.refined);
  if (options.bundle_adjustment.rotation_model ==
          ThreeViewBundleAdjustmentOptions::RotationModel::kYawOnly &&
      shift > kMaxRefinementShiftDeg) {
    estimate.success = false;
    estimate.cause = FailureCause::kRefinementShift;
    // A RANSAC pose already off its inliers' optimum (robust_three_view.h, refined_afterwards)
    // points to the geometry rather than the gravity.
    const ConsensusEvidence& evidence = estimate.robust.evidence;
    const double offset = std::max(evidence.rotation_offset_deg, evidence.direction_offset_deg);
    char message[220];
    if (!(evidence.SigmaWithOffsetDeg() <= robust.max_pose_sigma_deg)) {
      std::snprintf(message, sizeof(message),
                    "the refinement moved the pose %.1f deg from its RANSAC estimate, %.1f deg "
                    "off its inliers' optimum: too weak a geometry (short baselines, a planar "
                    "scene)?",
                    shift, offset);
    } else {
      std::snprintf(message, sizeof(message),
                    "the refinement moved the pose %.1f deg from its verified RANSAC estimate: "
                    "gravity noisier than the yaw-only model? Use the gravity-prior model",
                    shift);
    }
    estimate.message = message;
  }
  return estimate;
}

}  // namespace trigrav
