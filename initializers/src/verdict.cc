#include "verdict.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>

#include "gravity_consistency.h"

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

constexpr const char* kImageCauses =
    "intrinsics that do not match the pixels (another image resolution, pixels as (row, column)), "
    "views out of order, or triplets that are not matches";

// What the gravity-free estimate says against the gravity, "" when the gravity is consistent or
// the comparison is not conclusive (the gravity-free estimate explains no more triplets).
std::string GravityDiagnosis(double bound, int gravity_aware_inliers, GravityConsistency* g) {
  if (!g->measured || g->num_inliers <= gravity_aware_inliers) return "";
  const std::array<double, 3>& angle = g->pair_inconsistency_deg;
  // Pairs (1,2), (1,3), (2,3); the camera a pair lacks is 3, 2, 1.
  const std::array<int, 3> other_camera = {3, 2, 1};
  int num_off = 0, consistent_pair = -1;
  for (int p = 0; p < 3; ++p) {
    if (angle[p] > bound) {
      ++num_off;
    } else {
      consistent_pair = p;
    }
  }
  const std::string figures = Format(
      " (pairs 1-2, 1-3, 2-3: %.1f, %.1f, %.1f deg; a gravity-free estimate explains %d "
      "triplets, the gravity-aware one %d)",
      angle[0], angle[1], angle[2], g->num_inliers, gravity_aware_inliers);
  if (num_off == 2) {
    const int camera = other_camera[consistent_pair];  // in both inconsistent pairs
    g->inconsistent_camera = camera;
    double off = 0.0;
    for (int p = 0; p < 3; ++p) off = p == consistent_pair ? off : std::max(off, angle[p]);
    return Format("gravity of camera %d is %.1f deg off the images: ", camera, off) +
           (off > kFlippedDeg ? "wrong sign?"
                              : "not in this camera's frame (the world's or another camera's "
                                "vertical, or mapped with the rotation's transpose)?") +
           figures;
  }
  if (num_off == 3) {
    return "every camera's gravity disagrees with the images: the world's vertical given for "
           "every camera, gravity mapped with the rotation's transpose, or views out of order?" +
           figures;
  }
  if (num_off == 1) {
    const int p = angle[0] > bound ? 0 : angle[1] > bound ? 1 : 2;
    const int a = p == 2 ? 2 : 1, b = p == 0 ? 2 : 3;  // the pair's cameras
    return Format(
               "the gravities of cameras %d and %d disagree with the images by %.1f deg: one "
               "of them wrong?",
               a, b, angle[p]) +
           figures;
  }
  const std::array<double, 2>& rotation = g->rotation_disagreement_deg;
  const int view = rotation[1] > rotation[0] ? 3 : 2;
  const double disagreement = std::max(rotation[0], rotation[1]);
  if (!(disagreement > bound)) return "";
  return Format(
             "the gravity-aware pose differs from a gravity-free one by %.1f deg in view %d "
             "although the gravity agrees with the images within %.1f deg: the gravity is "
             "less accurate than the rotation model assumes (use the gravity-prior model, a "
             "larger gravity_sigma_deg or max_tilt_correction_deg)?",
             disagreement, view, bound) +
         figures;
}

}  // namespace

void JudgeEstimate(const TripletData& data,
                   const RansacOptions& ransac,
                   int sample_size,
                   bool uses_gravity,
                   double max_gravity_inconsistency_deg,
                   bool check_gravity_after_success,
                   RobustThreeViewEstimate* estimate) {
  // RANSAC that drew samples fails only when no model reaches the floor (or a minimal sample).
  const bool below_floor =
      !estimate->success && data.error.size() >= static_cast<std::size_t>(sample_size);
  if (!estimate->success && !below_floor) return;
  const bool check_gravity = uses_gravity && std::isfinite(max_gravity_inconsistency_deg) &&
                             (below_floor || check_gravity_after_success);
  if (check_gravity) {
    // At most the samples the gravity-aware method's floor needs: enough for the gravity-free
    // models that explain most triplets, the ones that show a gravity mistake.
    RansacOptions free = ransac;
    if (ransac.min_inlier_ratio > 0.0) {
      free.max_iterations = std::min(
          ransac.max_iterations,
          std::max(ransac.min_iterations,
                   RequiredIterations(ransac.min_inlier_ratio, sample_size, ransac.confidence)));
      free.min_iterations = std::min(free.min_iterations, free.max_iterations);
    }
    estimate->gravity = MeasureGravityConsistency(data, free, estimate->pose, estimate->success);
  }
  const std::string diagnosis =
      check_gravity ? GravityDiagnosis(max_gravity_inconsistency_deg, estimate->ransac.num_inliers,
                                       &estimate->gravity)
                    : "";
  if (below_floor) {
    const double n = static_cast<double>(data.error.size());
    // The gravity diagnosis first when there is one; wrong images also distort the gravity-free
    // rotations, so their causes stay listed.
    std::string causes;
    if (!diagnosis.empty()) {
      causes = diagnosis + "; otherwise " + kImageCauses;
    } else {
      causes = uses_gravity ? "likely causes: wrong gravity (sign, frame, the rotation's "
                              "transpose), " +
                                  std::string(kImageCauses)
                            : "likely causes: " + std::string(kImageCauses);
      if (estimate->gravity.measured) {
        const std::array<double, 3>& angle = estimate->gravity.pair_inconsistency_deg;
        causes += Format(
            "; a gravity-free estimate explains %d triplets and agrees with the gravity within "
            "%.1f deg (pairs 1-2, 1-3, 2-3: %.1f, %.1f, %.1f deg): if that is many, the gravity "
            "is less accurate than the rotation model assumes (use the gravity-prior model, a "
            "larger gravity_sigma_deg)",
            estimate->gravity.num_inliers, max_gravity_inconsistency_deg, angle[0], angle[1],
            angle[2]);
      } else if (check_gravity) {
        causes += " (no gravity-free model reaches the floor either)";
      }
    }
    estimate->message =
        Format(
            "only %d of %.0f triplets (%.1f %%) fit one model (ransac.min_inlier_ratio: "
            "%.1f %%): ",
            estimate->ransac.num_inliers, n, 100.0 * estimate->ransac.num_inliers / n,
            100.0 * ransac.min_inlier_ratio) +
        causes;
    return;
  }
  if (diagnosis.empty()) return;
  estimate->success = false;
  estimate->message = diagnosis;
  estimate->pose = ThreeViewPose();
  estimate->inliers.clear();
}

}  // namespace internal
}  // namespace trigrav
