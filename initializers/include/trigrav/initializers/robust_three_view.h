#ifndef TRIGRAV_INITIALIZERS_ROBUST_THREE_VIEW_H_
#define TRIGRAV_INITIALIZERS_ROBUST_THREE_VIEW_H_

#include <array>
#include <limits>
#include <string>
#include <vector>

#include "trigrav/initializers/camera_pose.h"
#include "trigrav/initializers/initial_solver.h"
#include "trigrav/initializers/ransac.h"
#include "trigrav/initializers/three_view_observations.h"

namespace trigrav {

struct RobustThreeViewOptions {
  InitialSolver solver = InitialSolver::kTrifocal3pt;
  // ransac.max_error is the inlier threshold in pixels, the same for every method
  // (three_view_error.h says what it measures); ransac.seed makes a run reproducible. Local
  // optimisation re-estimates from the inliers with the method's own non-minimal solver: the
  // 4-point solver for the gravity-aware methods, the eight-point solver for the two-view ones, the
  // linear tensor for 7pt-linear.
  // Choosing ransac.max_error (default 2 px): the minimal models are upright, so a tilt error of
  // the IMU moves the true inliers by about f sigma_tilt pixels (f in px, sigma_tilt the per-frame
  // pitch / roll sigma in radians; 0.1 deg at f = 719 px: 1.25 px) on top of the pixel noise
  // sigma_px. The rule:
  //  - upright RANSAC (max_tilt_correction_deg = 0; the yaw-only model) takes the gravity as exact:
  //    3 sigma_px with exact gravity. With an IMU's gravity it loses the true motion, and a larger
  //    threshold only trades the verdict's refusals for wrong successes: correct the tilt instead;
  //  - tilt-correcting RANSAC (InitializeAndRefine with the gravity-prior model): 3 sigma_px is
  //    enough; sqrt((3 sigma_px)^2 + (1.4 f sigma_tilt)^2) is closer still to the best threshold.
  // Too large a threshold lets a rotation without baseline explain the inliers (failures as "no
  // parallax"). The measurements behind the rule: examples/kitti/README.md, "Threshold and IMU
  // noise", and examples/initialize_and_refine/README.md, "Choosing the threshold".
  RansacOptions ransac;
  // The inlier threshold for bearing observations (ThreeViewObservations::bearings), in degrees,
  // in place of ransac.max_error (pixels); the default is 2 px at a focal length of 1150 px.
  double max_bearing_error_deg = 0.1;
  // Gravity-aware methods only: how far local optimisation may correct the relative tilt (pitch and
  // roll of cameras 2 and 3 relative to camera 1) that the given gravity implies, in degrees.
  // 0 (exact gravity): every model is upright, local optimisation included. > 0 (gravity from an
  // IMU): each local optimisation estimates the relative tilt from the inliers with the linear
  // trifocal tensor (7 or more inliers), turns the rays of views 2 and 3 by it when it lies within
  // this bound, and re-solves upright with the 4-point solver on the corrected rays. A relative
  // tilt error e moves distant points by about f e pixels (0.14 deg at f = 719 px: 1.8 px); under a
  // tight threshold every upright model of the true motion then loses its distant points, and
  // RANSAC may prefer a wrong motion. The minimal models stay upright; the estimate carries the
  // corrected tilt. No effect without ransac.local_optimization.
  // kTiltCorrectionFromGravitySigma (the default) derives the bound from the gravity's uncertainty
  // where one is known: InitializeAndRefine with the gravity-prior rotation model uses
  // 4 sqrt(2) gravity_sigma_deg (at most 45 deg; the relative tilt of two cameras with N(0,
  // sigma^2) pitch and roll errors exceeds it with probability 3e-4); with the yaw-only model,
  // which declares the gravity exact, and in EstimateThreeViewPoseRobust, which knows no sigma, it
  // means 0. Otherwise throws std::invalid_argument outside [0, 90).
  static constexpr double kTiltCorrectionFromGravitySigma = -1.0;
  double max_tilt_correction_deg = kTiltCorrectionFromGravitySigma;
  // Gravity-aware methods only: how far (deg) a camera's gravity may be from what the images say
  // before the verdict names it (derivations.md sections 7.6-7.7). A gravity-free robust estimate
  // (5pt through the same RANSAC and threshold) is compared with the gravity: the angle between
  // R_k g_1 and g_k for the pairs (1,2), (1,3) and between R_3 R_2^T g_2 and g_3 for (2,3), and the
  // rotation between the two estimates of each view, all go into RobustThreeViewEstimate::gravity.
  // When the gravity-free estimate explains clearly more triplets than the gravity-aware one, the
  // call fails; these angles against this bound name the cause (a camera's gravity, every
  // camera's, gravity noisier than the model, or images that favour another motion).
  // +infinity skips the comparison and its cost. kGravityConsistencyFromGravitySigma (the
  // default): InitializeAndRefine uses 4 sqrt(2) bundle_adjustment.gravity_sigma_deg, at least
  // 1 deg (the relative tilt of two cameras exceeds 4 sqrt(2) sigma with probability 3e-4; the
  // 1 deg covers the gravity-free estimate's own error); EstimateThreeViewPoseRobust, whose
  // upright models take the gravity as exact, uses 1 deg. Otherwise throws std::invalid_argument
  // unless > 0.
  static constexpr double kGravityConsistencyFromGravitySigma = -1.0;
  double max_gravity_inconsistency_deg = kGravityConsistencyFromGravitySigma;
  // Whether the gravity-free comparison also runs after a success (it always runs after a failure,
  // to name the cause). It needs only the samples that would find a gravity-free model explaining
  // clearly more triplets (3 binomial standard deviations, at least 2 %), few when the
  // gravity-aware model explains most: its cost on correct data is in the README's robustness
  // section. false trusts the gravity: a wrong or noisy gravity can then return a wrong pose as a
  // success.
  bool check_gravity_after_success = true;
  // The largest standard deviation (deg) of the rotations and of the centres' directions that the
  // winner's inliers may leave at a noise of ransac.max_error / 3 (the Gauss-Newton prediction,
  // derivations.md section 7.7) for a success. Rule behind the default: a 2D error of Rayleigh
  // scale sigma exceeds 5 deg with probability exp(-12.5 / sigma^2), 3e-4 at 1.25 deg. What it
  // refuses on real data: derivations.md section 7.7. +infinity: no test.
  double max_pose_sigma_deg = 1.25;
  // The fewest inliers a success may have, counted as distinct triplets (one repeated with the
  // same pixels in all three views counts once, in the evidence as well). Rule behind the
  // default: COLMAP's minimum for a two-view geometry (15); with fewer, the predicted precision
  // itself is unreliable (derivations.md section 7.7).
  int min_inliers = 15;
  // Whether the caller refines the pose to its inliers' optimum (RefineThreeViewPose), as
  // InitializeAndRefine does when it refines: the verdict then judges the optimum's precision
  // (max_pose_sigma_deg) alone. false (the default): the returned RANSAC pose is the answer, and
  // its offset from the optimum counts too (ConsensusEvidence::SigmaWithOffsetDeg; on ground-plane
  // scenes with small baselines the RANSAC pose can lie 5-10 deg off an optimum predicted to
  // 1 deg). Tilt-correcting estimates are judged by the optimum alone either way: their
  // free-rotation optimum carries the images' own tilt.
  bool refined_afterwards = false;

  // Throws std::invalid_argument naming the first bad field.
  void Check() const;
  // The threshold that applies to the observations: max_bearing_error_deg for bearings, else
  // ransac.max_error.
  double InlierThreshold(const ThreeViewObservations& observations) const;
};

// What the images say about the given gravity
// (RobustThreeViewOptions::max_gravity_inconsistency_deg, derivations.md section 7.6), from a
// gravity-free robust estimate with rotations R_2, R_3 (cam_k_from_cam1) and the unit gravities
// g_k.
struct GravityConsistency {
  bool measured = false;  // the gravity-free estimate succeeded and the figures below are set
  int num_inliers = 0;    // of the gravity-free estimate
  // Pairs (1,2), (1,3), (2,3): angle(R_2 g_1, g_2), angle(R_3 g_1, g_3), angle(R_3 R_2^T g_2, g_3).
  std::array<double, 3> pair_inconsistency_deg{};
  // Pairs (1,2), (1,3) with the gravities of views 2 and 3 exchanged: angle(R_2 g_1, g_3),
  // angle(R_3 g_1, g_2); both small while the pairs above are not: views 2 and 3 out of order.
  std::array<double, 2> swapped_pair_inconsistency_deg{};
  // Views 2 and 3: angle of the rotation between the gravity-aware and the gravity-free
  // cam_k_from_cam1; 0 when the gravity-aware estimate failed.
  std::array<double, 2> rotation_disagreement_deg{};
  // Views 2 and 3: angle between the two estimates' directions of the camera centre C_k / |C_k|;
  // 0 when the gravity-aware estimate failed.
  std::array<double, 2> direction_disagreement_deg{};
  // The camera (1, 2 or 3) that appears in the two pairs beyond the bound when the third is within
  // it; 0 when no pair is beyond it or the pattern names no single camera.
  int inconsistent_camera = 0;
};

// Why an estimate is not a success, for a pipeline to act on (the message says it in words).
enum class FailureCause {
  kNone,                // a success
  kTooFewTriplets,      // fewer triplets than the minimal sample, or no model at all
  kBelowInlierFloor,    // no model explains ransac.min_inlier_ratio of the triplets
  kTooFewInliers,       // fewer distinct inliers (or triplets) than min_inliers
  kChanceConsensus,     // as many inliers would fit by chance (number of false alarms >= 1)
  kUncertainPose,       // the inliers leave the pose uncertain (max_pose_sigma_deg)
  kNoParallax,          // camera 2's centre, which sets the scale, is not observable
  kPixelsVsIntrinsics,  // pixels the intrinsics cannot produce (beyond a tenth of the image
                        // the principal point implies): another camera, a resized image,
                        // (row, column) pixels
  kViewsOutOfOrder,     // views 2 and 3 swapped: each one's gravity fits the other's images
  kCameraGravity,       // one or more cameras' gravity contradicts the images
  kNoisyGravity,        // the gravity is noisier than the rotation model allows
  kOtherMotion,         // a gravity-free model explains more and disagrees: intrinsics or order
  kRefinementShift,     // InitializeAndRefine: the refinement moved the verified pose beyond 5 deg
  kStopped,             // the caller's stop_requested returned true (RansacOptions,
                        // ThreeViewBundleAdjustmentOptions): the call ended early
};
const char* FailureCauseName(FailureCause cause);

// How much the winner's consensus says (derivations.md section 7.7); set after RANSAC succeeds.
struct ConsensusEvidence {
  // log10 of the number of false alarms: how many consensuses as large would arise by chance among
  // uniformly random triplets; a success needs it below 0.
  double log10_nfa = std::numeric_limits<double>::infinity();
  // Predicted standard deviations, at a noise of the threshold / 3, of the inliers' least-squares
  // optimum (deg).
  double rotation_sigma_deg = std::numeric_limits<double>::infinity();
  double direction_sigma_deg = std::numeric_limits<double>::infinity();
  // How far the pose lies from that optimum: the Gauss-Newton step to it (deg).
  double rotation_offset_deg = std::numeric_limits<double>::infinity();
  double direction_offset_deg = std::numeric_limits<double>::infinity();

  // The sigma that bounds the pose's own error as sigma bounds the optimum's: the larger of
  // sigma + offset / 4 for the rotations and the directions. Within max_pose_sigma_deg, an error
  // beyond 4 max_pose_sigma_deg (5 deg at the default) is as improbable as for the optimum
  // (derivations.md section 7.7, step 4).
  double SigmaWithOffsetDeg() const;
};

struct RobustThreeViewEstimate {
  bool success = false;
  std::string message;  // why not, when !success
  FailureCause cause = FailureCause::kNone;
  ThreeViewPose pose;         // original camera frames, |cam2_from_cam1.Center()| = 1
  std::vector<char> inliers;  // per triplet; ransac.num_inliers of them are set
  RansacStatistics ransac;
  GravityConsistency gravity;
  ConsensusEvidence evidence;
};

// Robust three-view relative pose from pixel triplets with outliers: RANSAC (ransac.h) over the
// chosen minimal solver, every method scored by the same three-view reprojection error in pixels
// (three_view_error.h). Gravity is used by the gravity-aware methods only. Throws
// std::invalid_argument for invalid observations or options. A success means the evidence supports
// the pose (derivations.md section 7.7): its inliers could not fit by chance (number of false
// alarms below 1), they pin the pose down (max_pose_sigma_deg; unless refined_afterwards, the
// pose's offset from their least-squares optimum counts too), and no gravity-free model explains
// clearly more triplets (check_gravity_after_success). Anything else (too few triplets, no model, a
// best model below ransac.min_inlier_ratio, a consensus chance explains, an uncertain pose, gravity
// or images the other model contradicts) gives success == false with a message of about 200
// characters, the likely cause first and a remedy. So do data without parallax
// between views 1 and 2: if a pure rotation of camera 2 (the best one for the winner's inliers, no
// baseline) puts more than 80 % of those inliers within ransac.max_error pixels, camera 2's centre,
// which sets the scale |C2| = 1, is not observable (zero baseline, pure rotation, points at
// infinity, identical views); the threshold follows COLMAP's planar-or-panoramic test of two-view
// geometries.
RobustThreeViewEstimate EstimateThreeViewPoseRobust(const ThreeViewObservations& observations,
                                                    const RobustThreeViewOptions& options);

}  // namespace trigrav

#endif  // TRIGRAV_INITIALIZERS_ROBUST_THREE_VIEW_H_
