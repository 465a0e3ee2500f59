#include "trigrav/ba/initialize_and_refine.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "trigrav/initializers/three_view_error.h"

namespace trigrav {
namespace {

// With pitch and roll errors N(0, sigma^2) per camera, the relative tilt of two cameras has the
// Rayleigh distribution of scale sqrt(2) sigma: it exceeds 4 sqrt(2) sigma with probability
// exp(-8) = 3e-4.
constexpr double kTiltCorrectionSigmas = 4.0;
// A sigma of degrees says the gravity is hardly known; the correction stays a tilt, below 90 deg.
constexpr double kMaxTiltCorrectionDeg = 45.0;

double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

void InitializeAndRefineOptions::Check() const {
  if (!(inlier_threshold_px > 0.0) || !std::isfinite(inlier_threshold_px)) {
    throw std::invalid_argument(
        "trigrav: InitializeAndRefineOptions: inlier_threshold_px must be positive and finite");
  }
  if (reclassification_rounds < 0) {
    throw std::invalid_argument(
        "trigrav: InitializeAndRefineOptions: reclassification_rounds must be >= 0");
  }
  RansacOptions r = ransac;
  r.max_error = inlier_threshold_px;
  r.Check();
  bundle_adjustment.Check();
}

ThreeViewEstimate InitializeAndRefine(const ThreeViewObservations& observations,
                                      const InitializeAndRefineOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  observations.Check();
  options.Check();

  ThreeViewEstimate estimate;
  RobustThreeViewOptions robust;
  robust.solver = options.solver;
  robust.ransac = options.ransac;
  robust.ransac.max_error = options.inlier_threshold_px;
  robust.ransac.seed = options.seed;
  if (options.correct_tilt_in_ransac &&
      options.bundle_adjustment.rotation_model ==
          ThreeViewBundleAdjustmentOptions::RotationModel::kGravityPrior) {
    robust.max_tilt_correction_deg = std::min(
        kTiltCorrectionSigmas * std::sqrt(2.0) * options.bundle_adjustment.gravity_sigma_deg,
        kMaxTiltCorrectionDeg);
  }
  const RobustThreeViewEstimate ransac = EstimateThreeViewPoseRobust(observations, robust);
  estimate.ransac_time_s = SecondsSince(start);
  estimate.ransac_iterations = ransac.iterations;
  if (!ransac.success || !ransac.pose.IsFinite()) {
    estimate.message = ransac.success ? "initial pose is not finite" : ransac.message;
    estimate.total_time_s = SecondsSince(start);
    return estimate;
  }
  estimate.success = true;
  estimate.initial = ransac.pose;
  estimate.refined = ransac.pose;
  estimate.inliers = ransac.inliers;
  estimate.num_inliers = ransac.num_inliers;
  if (!options.refine) {
    estimate.total_time_s = SecondsSince(start);
    return estimate;
  }

  estimate.initial_inliers = ransac.inliers;
  estimate.num_initial_inliers = ransac.num_inliers;
  const auto ba_start = std::chrono::steady_clock::now();
  const ThreeViewReprojectionError error(observations);
  std::vector<char> inliers = ransac.inliers;
  for (int run = 0; run <= options.reclassification_rounds; ++run) {
    ThreeViewBundleAdjuster adjuster(observations,
                                     ThreeViewBundleAdjustmentConfig::FromInlierMask(inliers),
                                     options.bundle_adjustment);
    if (!adjuster.Build(estimate.refined)) {
      if (run == 0) estimate.message = "refinement skipped: " + adjuster.message();
      break;
    }
    const ThreeViewBundleAdjustmentSummary summary = adjuster.Solve();
    estimate.ba_iterations += summary.iterations;
    if (!summary.success || !summary.pose.IsFinite()) {
      if (run == 0) {
        estimate.message = "refinement failed, keeping the initial pose: " + summary.message;
      }
      break;
    }
    ++estimate.refinement_runs;
    estimate.ba_num_points = summary.num_points;
    if (run == 0) estimate.initial_cost = summary.initial_cost;
    estimate.final_cost = summary.final_cost;
    estimate.ceres_brief_report = summary.brief_report;
    estimate.refined = summary.pose;
    estimate.refinement_ran = true;
    estimate.inliers = inliers;
    estimate.num_inliers = static_cast<int>(std::count(inliers.begin(), inliers.end(), 1));
    if (run == options.reclassification_rounds) break;
    // Re-classify against the refined pose; stop when nothing changes.
    const ThreeViewReprojectionError::PreparedPose prepared =
        ThreeViewReprojectionError::Prepare(summary.pose);
    std::vector<char> next(observations.size(), 0);
    int num_next = 0;
    for (std::size_t i = 0; i < next.size(); ++i) {
      next[i] = error(prepared, i) <= options.inlier_threshold_px ? 1 : 0;
      num_next += next[i];
    }
    if (next == inliers || num_next < MinimalSampleSize(options.solver)) break;
    inliers.swap(next);
  }
  estimate.ba_time_s = SecondsSince(ba_start);
  estimate.total_time_s = SecondsSince(start);
  return estimate;
}

}  // namespace trigrav
