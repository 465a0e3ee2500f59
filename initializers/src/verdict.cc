#include "verdict.h"

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "consensus_evidence.h"
#include "gravity_consistency.h"
#include "parallax_check.h"

namespace trigrav {
namespace internal {
namespace {

// snprintf into a string (the library prints nothing).
template <typename... Args>
std::string Format(const char* format, Args... args) {
  std::string text(static_cast<std::size_t>(std::snprintf(nullptr, 0, format, args...)), '\0');
  std::snprintf(text.data(), text.size() + 1, format, args...);
  return text;
}

// A camera's gravity this far off the images is more likely of the wrong sign (180 deg off) than
// from another frame.
constexpr double kFlippedDeg = 135.0;

// Triplets a gravity-free model must explain beyond the gravity-aware one's to count as clearly
// more after a success (section 7.7): 5 % of n, at least 3. Its 4 more degrees of freedom let it
// take in a few more triplets near the threshold on right data.
int ClearMargin(int n) { return std::max(3, static_cast<int>(std::ceil(0.05 * n))); }

// A chance fit this likely names the threshold, not the number of triplets, as the cause of a
// chance consensus.
constexpr double kLooseThresholdChance = 0.1;

// A success's centre directions may differ at least this much from a gravity-free estimate that
// explains more triplets (section 7.7): beyond it, one of the two is far off.
constexpr double kMaxDirectionDisagreementDeg = 5.0;

// How far the two estimates' rotations and centre directions may differ (deg) before a success
// is refused.
struct DisagreementBound {
  double rotation_deg = 0.0;
  double direction_deg = 0.0;
};

struct Diagnosis {
  FailureCause cause = FailureCause::kNone;
  std::string message;  // "" when there is nothing to object to
};

// The likely cause when a gravity-free estimate explains more triplets than the gravity-aware one
// (section 7.7), cause first; no message when the comparison did not run or favours the gravity.
Diagnosis GravityDiagnosis(const VerdictSettings& settings,
                           int gravity_aware_inliers,
                           bool gravity_aware_succeeded,
                           const DisagreementBound& disagreement,
                           GravityConsistency* g) {
  if (!g->measured || g->num_inliers <= gravity_aware_inliers) return {};
  const double bound = settings.max_gravity_inconsistency_deg;
  const std::array<double, 3>& angle = g->pair_inconsistency_deg;
  const std::array<int, 3> other_camera = {3, 2, 1};  // the camera pair (1,2), (1,3), (2,3) lacks
  int num_off = 0, consistent_pair = -1;
  for (int p = 0; p < 3; ++p) {
    if (angle[p] > bound) {
      ++num_off;
    } else {
      consistent_pair = p;
    }
  }
  const std::string counts =
      Format(" (%d vs %d triplets fit)", g->num_inliers, gravity_aware_inliers);
  const std::array<double, 2>& swapped = g->swapped_pair_inconsistency_deg;
  if (num_off > 0 && swapped[0] <= bound && swapped[1] <= bound) {
    return {FailureCause::kViewsOutOfOrder,
            "views 2 and 3 out of order: each one's gravity fits the other's images; swap their "
            "pixels" +
                counts};
  }
  if (num_off == 2) {
    const int camera = other_camera[consistent_pair];
    g->inconsistent_camera = camera;
    double off = 0.0;
    for (int p = 0; p < 3; ++p) off = p == consistent_pair ? off : std::max(off, angle[p]);
    if (off > kFlippedDeg) {
      return {FailureCause::kCameraGravity,
              Format("gravity of camera %d has the wrong sign (%.0f deg off the images): negate it",
                     camera, off) +
                  counts};
    }
    return {FailureCause::kCameraGravity,
            Format("gravity of camera %d is %.1f deg off the images: not in this camera's frame? "
                   "Give its down vector in camera coordinates",
                   camera, off) +
                counts};
  }
  if (num_off == 3) {
    return {FailureCause::kCameraGravity,
            Format("every camera's gravity is off the images (%.1f, %.1f, %.1f deg): world "
                   "vertical or rotation transposed? Give each camera's own down vector",
                   angle[0], angle[1], angle[2]) +
                counts};
  }
  if (num_off == 1) {
    const int p = angle[0] > bound ? 0 : angle[1] > bound ? 1 : 2;
    const int a = p == 2 ? 2 : 1, b = p == 0 ? 2 : 3;  // the pair's cameras
    return {FailureCause::kCameraGravity,
            Format("gravities of cameras %d and %d disagree with the images by %.1f deg: one of "
                   "them wrong?",
                   a, b, angle[p]) +
                counts};
  }
  const std::array<double, 2>& rotation = g->rotation_disagreement_deg;
  const std::array<double, 2>& direction = g->direction_disagreement_deg;
  if (std::max(rotation[0], rotation[1]) > disagreement.rotation_deg ||
      std::max(direction[0], direction[1]) > disagreement.direction_deg) {
    // The gravity agrees with the images within the bound, yet the gravity-aware search settled on
    // another motion: a gravity noisier than the model allows, the view order or the intrinsics.
    return {FailureCause::kOtherMotion,
            (settings.tilt_correcting
                 ? std::string("the images favour another motion: gravity noisier than "
                               "gravity_sigma_deg, views out of order or wrong intrinsics?")
                 : std::string("the images favour another motion: gravity noisier than the "
                               "yaw-only model (use the gravity-prior model), views out of order "
                               "or wrong intrinsics?")) +
                counts};
  }
  // The same motion within the bounds: on a success, nothing to object to; on a failure, the
  // gravity-aware model lost triplets: the tilt is noisier than it allows.
  if (gravity_aware_succeeded) return {};
  const double tilt = std::max({angle[0], angle[1], angle[2]});
  if (settings.tilt_correcting) {
    return {FailureCause::kNoisyGravity,
            Format("gravity noisier than the tilt correction allows (%.2f deg): set "
                   "gravity_sigma_deg (max_tilt_correction_deg) to the IMU's",
                   tilt) +
                counts};
  }
  return {FailureCause::kNoisyGravity,
          Format("gravity noisier than the yaw-only model allows (%.2f deg): use the "
                 "gravity-prior model with gravity_sigma_deg of the IMU",
                 tilt) +
              counts};
}

// Runs the gravity-free comparison with at most the samples that find a model of
// `target_inliers` with the confidence (section 7.7); false if the comparison cannot be won.
bool CompareWithGravityFree(const TripletData& data,
                            const RansacOptions& ransac,
                            int target_inliers,
                            RobustThreeViewEstimate* estimate,
                            RobustThreeViewEstimate* gravity_free) {
  const double n = static_cast<double>(data.error.size());
  if (target_inliers >= n) return false;
  RansacOptions free = ransac;
  free.min_inlier_ratio = target_inliers / n;
  free.min_iterations = 0;
  estimate->gravity =
      MeasureGravityConsistency(data, free, estimate->pose, estimate->success, gravity_free);
  return true;
}

// Pixels that the intrinsics cannot have produced (section 7.7): in some view, pixels beyond the
// image the principal point implies (0 to 2 c) by more than kImageMargin of it, or a principal
// point in a corner of the pixels' bounding box (in its outer tenth, or beyond, along both axes, as
// pixels of a downscaled image put it; with at least kMinTripletsForCentre triplets). Returns the
// message, "" when the pixels fit.
constexpr std::size_t kMinTripletsForCentre = 50;
// A tenth of the implied image: a principal point up to 4.5 % of the image left of or above its
// centre (KITTI's pixels reach 2.2 % beyond 2 c). A fifth let another camera's intrinsics pass on
// KITTI 02 (frame 251, 29 deg off); a tenth refuses all 596 triplets (examples/kitti/README.md).
constexpr double kImageMargin = 0.1;
std::string PixelsAgainstIntrinsics(const ThreeViewObservations& observations) {
  if (observations.HasBearings()) return "";
  for (int k = 0; k < 3; ++k) {
    const std::vector<Eigen::Vector2d>& pixels = observations.pixels[k];
    if (pixels.empty()) continue;
    const PixelBox box = PixelBoundingBox(pixels);
    const Eigen::Vector2d &low = box.low, &high = box.high;
    // The principal point: the pixel of the optical axis.
    const Eigen::Vector2d centre = observations.cameras[k].Project(Eigen::Vector3d::UnitZ());
    const Eigen::Vector2d image = 2.0 * centre;
    const bool beyond = (low.array() < -kImageMargin * image.array()).any() ||
                        (high.array() > (1.0 + kImageMargin) * image.array()).any();
    const Eigen::Vector2d middle_low = low + 0.1 * (high - low);
    const Eigen::Vector2d middle_high = high - 0.1 * (high - low);
    const bool off_centre =
        pixels.size() >= kMinTripletsForCentre &&
        ((centre.array() < middle_low.array()) || (centre.array() > middle_high.array())).all();
    if (beyond || off_centre) {
      return Format(
          "pixels of view %d span x %.4g to %.4g, y %.4g to %.4g px, not the %.4g x %.4g image "
          "of its principal point: another camera's intrinsics, a resized image or "
          "(row, column) pixels?",
          k + 1, low.x(), high.x(), low.y(), high.y(), image.x(), image.y());
    }
  }
  return "";
}

// Per triplet: 1 unless the same rays in all three views came earlier (section 7.7, step 2: a
// repeated triplet, as duplicate keypoints give, adds no evidence).
std::vector<char> FirstOccurrences(const TripletData& data) {
  const std::size_t n = data.error.size();
  std::vector<int> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = static_cast<int>(i);
  const auto less = [&](int a, int b) {
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d &x = data.raw[k][a], &y = data.raw[k][b];
      for (int c = 0; c < 3; ++c) {
        if (x[c] != y[c]) return x[c] < y[c];
      }
    }
    return a < b;
  };
  std::sort(order.begin(), order.end(), less);
  std::vector<char> first(n, 1);
  for (std::size_t i = 1; i < n; ++i) {
    const int a = order[i - 1], b = order[i];
    first[b] = !(data.raw[0][a] == data.raw[0][b] && data.raw[1][a] == data.raw[1][b] &&
                 data.raw[2][a] == data.raw[2][b]);
  }
  return first;
}

void Fail(FailureCause cause, const std::string& message, RobustThreeViewEstimate* estimate) {
  estimate->success = false;
  estimate->cause = cause;
  estimate->message = message;
  estimate->pose = ThreeViewPose();
  estimate->inliers.clear();
}

// Fewer than min_inliers distinct triplets `verb` ("given", "fit"): "only 3 triplets fit
// (min_inliers 15): ...", or "only 3 distinct triplets fit (45 with repeats; min_inliers 15): ...".
void FailWithTooFew(
    int distinct, int total, const char* verb, int min_inliers, RobustThreeViewEstimate* estimate) {
  const std::string count =
      distinct == total
          ? Format("only %d triplets %s (", total, verb)
          : Format("only %d distinct triplets %s (%d with repeats; ", distinct, verb, total);
  Fail(FailureCause::kTooFewInliers,
       count + Format("min_inliers %d): too few to judge a pose by; give more tracks", min_inliers),
       estimate);
}

}  // namespace

void JudgeEstimate(const TripletData& data,
                   const ThreeViewObservations& observations,
                   const RansacOptions& ransac,
                   const VerdictSettings& settings,
                   RobustThreeViewEstimate* estimate) {
  const int n = static_cast<int>(data.error.size());
  const int k = estimate->ransac.num_inliers;
  // RANSAC that drew samples fails only when no model reaches the floor (or a minimal sample).
  const bool below_floor = !estimate->success && n >= settings.sample_size;
  if (!estimate->success && !below_floor) {
    estimate->cause = FailureCause::kTooFewTriplets;
    return;
  }
  // Evidence counts distinct triplets: n_distinct of the n, k_distinct of the k inliers.
  const std::vector<char> first = FirstOccurrences(data);
  const int n_distinct = static_cast<int>(std::count(first.begin(), first.end(), 1));
  if (n_distinct < settings.min_inliers) {
    FailWithTooFew(n_distinct, n, "given", settings.min_inliers, estimate);
    return;
  }
  // Could the intrinsics have produced these pixels? The likeliest cause when they could not.
  const std::string mismatch = PixelsAgainstIntrinsics(observations);
  if (!mismatch.empty()) {
    Fail(FailureCause::kPixelsVsIntrinsics, mismatch, estimate);
    return;
  }
  const bool compare_gravity =
      settings.uses_gravity && std::isfinite(settings.max_gravity_inconsistency_deg);
  // Between the stages below; the caller turns a stopped verdict into a failure.
  const auto stop_requested = [&] { return ransac.stop_requested && ransac.stop_requested(); };

  if (below_floor) {
    if (compare_gravity && !stop_requested()) {
      // At most the samples the gravity-aware method's floor needs: enough for the gravity-free
      // models that explain most triplets, the ones that show a gravity mistake.
      RansacOptions free = ransac;
      if (ransac.min_inlier_ratio > 0.0) {
        free.max_iterations =
            std::min(ransac.max_iterations,
                     std::max(ransac.min_iterations,
                              RequiredIterations(ransac.min_inlier_ratio, settings.sample_size,
                                                 ransac.confidence)));
        free.min_iterations = std::min(free.min_iterations, free.max_iterations);
      }
      estimate->gravity = MeasureGravityConsistency(data, free, estimate->pose, false);
    }
    const Diagnosis diagnosis = GravityDiagnosis(
        settings, k, false, {settings.max_gravity_inconsistency_deg, kMaxDirectionDisagreementDeg},
        &estimate->gravity);
    const std::string cause =
        !diagnosis.message.empty() ? diagnosis.message
        : settings.uses_gravity
            ? "wrong intrinsics, (row, column) pixels, views out of order, gravity or matches?"
            : "wrong intrinsics, (row, column) pixels, views out of order or matches?";
    estimate->cause = diagnosis.message.empty() ? FailureCause::kBelowInlierFloor : diagnosis.cause;
    estimate->message = Format("%d of %d triplets fit: ", k, n) + cause;
    return;
  }

  // 1. Are there enough inliers to judge by?
  std::vector<char> distinct_inliers = estimate->inliers;
  for (int i = 0; i < n; ++i) distinct_inliers[i] &= first[i];
  const int k_distinct =
      static_cast<int>(std::count(distinct_inliers.begin(), distinct_inliers.end(), 1));
  if (k_distinct < settings.min_inliers) {
    FailWithTooFew(k_distinct, k, "fit", settings.min_inliers, estimate);
    return;
  }
  // 2. Could chance explain the consensus? (number of false alarms, section 7.7)
  const double alpha = ChanceFitProbability(observations, ransac.max_error);
  estimate->evidence.log10_nfa = Log10NumberOfFalseAlarms(
      n_distinct, k_distinct, settings.sample_size, settings.max_models_per_sample, alpha);
  if (!(estimate->evidence.log10_nfa < 0.0)) {
    const std::string remedy =
        alpha >= kLooseThresholdChance
            ? Format("the threshold %.3g lets a random triplet fit with probability %.2f: lower it",
                     ransac.max_error, alpha)
            : std::string("too few triplets; give more tracks");
    Fail(FailureCause::kChanceConsensus,
         Format("%d of %d triplets fit as well by chance (NFA 10^%.1f): ", k_distinct, n_distinct,
                estimate->evidence.log10_nfa) +
             remedy,
         estimate);
    return;
  }
  if (stop_requested()) return;
  // 3. Is camera 2's centre, which sets the scale, observable? (robust_three_view.h)
  RejectWithoutParallax(data, ransac.max_error, estimate);
  if (!estimate->success) {
    estimate->cause = FailureCause::kNoParallax;
    return;
  }
  if (stop_requested()) return;
  // 4. Do the inliers pin the pose down? (predicted precision at sigma = threshold / 3)
  const std::array<double, 3> units = ThresholdUnitsPerRadian(observations);
  const PosePrecision precision =
      PredictPosePrecision(data, estimate->pose, distinct_inliers, units, ransac.max_error / 3.0,
                           settings.uses_gravity && !settings.tilt_correcting);
  estimate->evidence.rotation_sigma_deg =
      precision.determined ? precision.rotation_sigma_deg : HUGE_VAL;
  estimate->evidence.direction_sigma_deg =
      precision.determined ? precision.direction_sigma_deg : HUGE_VAL;
  // A gravity-aware tilt-correcting estimate is judged by its optimum alone: its free-rotation
  // optimum carries the images' own tilt, which the estimate corrects only within its bound.
  const bool offset_measured = !(settings.uses_gravity && settings.tilt_correcting);
  estimate->evidence.rotation_offset_deg = !precision.determined ? HUGE_VAL
                                           : offset_measured     ? precision.rotation_offset_deg
                                                                 : 0.0;
  estimate->evidence.direction_offset_deg = !precision.determined ? HUGE_VAL
                                            : offset_measured     ? precision.direction_offset_deg
                                                                  : 0.0;
  const double sigma =
      std::max(estimate->evidence.rotation_sigma_deg, estimate->evidence.direction_sigma_deg);
  if (!(sigma <= settings.max_pose_sigma_deg)) {
    Fail(FailureCause::kUncertainPose,
         Format("%d triplets leave the pose uncertain (predicted sigma %.2g deg > "
                "max_pose_sigma_deg %.2g): too few or short tracks, or too little baseline",
                k_distinct, sigma, settings.max_pose_sigma_deg),
         estimate);
    return;
  }
  // The RANSAC pose is the answer unless the caller refines it: its offset from the inliers'
  // optimum counts too (section 7.7, step 4).
  const double sigma_with_offset = estimate->evidence.SigmaWithOffsetDeg();
  if (settings.judge_offset && !(sigma_with_offset <= settings.max_pose_sigma_deg)) {
    Fail(FailureCause::kUncertainPose,
         Format("the RANSAC pose lies %.2g deg off its %d inliers' optimum (sigma %.2g deg; "
                "sigma + offset / 4 = %.2g > max_pose_sigma_deg %.2g): refine it "
                "(InitializeAndRefine)",
                std::max(estimate->evidence.rotation_offset_deg,
                         estimate->evidence.direction_offset_deg),
                k_distinct, sigma, sigma_with_offset, settings.max_pose_sigma_deg),
         estimate);
    return;
  }
  // 5. Does a gravity-free model explain clearly more triplets? Its search needs only the samples
  // that find such a model, none when the gravity-aware one leaves fewer than the margin.
  if (!compare_gravity || !settings.check_gravity_after_success || stop_requested()) return;
  const int target = k + ClearMargin(n);
  RobustThreeViewEstimate free;
  if (!CompareWithGravityFree(data, ransac, target, estimate, &free)) return;
  if (!estimate->gravity.measured || estimate->gravity.num_inliers < target || stop_requested()) {
    return;
  }
  // The two estimates disagree when they differ by more than 3 standard deviations of their
  // difference (each predicted as in step 4, the gravity-free one with free rotations), and more
  // than the bounds.
  const PosePrecision free_precision = PredictPosePrecision(
      data, free.pose, free.inliers, units, ransac.max_error / 3.0, /*yaw_only=*/false);
  const double free_rotation_sigma =
      free_precision.determined ? free_precision.rotation_sigma_deg : HUGE_VAL;
  const double free_direction_sigma =
      free_precision.determined ? free_precision.direction_sigma_deg : HUGE_VAL;
  const DisagreementBound disagreement = {
      std::max(settings.max_gravity_inconsistency_deg,
               3.0 * std::hypot(estimate->evidence.rotation_sigma_deg, free_rotation_sigma)),
      std::max(kMaxDirectionDisagreementDeg,
               3.0 * std::hypot(estimate->evidence.direction_sigma_deg, free_direction_sigma))};
  const Diagnosis diagnosis = GravityDiagnosis(settings, k, true, disagreement, &estimate->gravity);
  if (!diagnosis.message.empty()) Fail(diagnosis.cause, diagnosis.message, estimate);
}

}  // namespace internal
}  // namespace trigrav
