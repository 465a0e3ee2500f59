#ifndef TRIGRAV_BA_NVIEW_BUNDLE_ADJUSTMENT_H_
#define TRIGRAV_BA_NVIEW_BUNDLE_ADJUSTMENT_H_

// Gravity-aware bundle adjustment of a whole reconstruction (any number of images and points),
// split like COLMAP's estimators/bundle_adjustment.h into a Config (what is constant, how the gauge
// is fixed), Options (rotation model, loss, solver) and an adjuster that owns the ceres::Problem.
// It uses the factors of the three-view refinement (trigrav/factors/reprojection_factors.h) with
// COLMAP's camera models; the intrinsics are held constant. No COLMAP type appears here
// (trigrav::colmap converts).
//
// Frames (ba/derivations.md 14.1): the caller's world frame is arbitrary (e.g. COLMAP's). The
// adjuster estimates the world's gravity direction from the images,
// g_w = normalised sum_k R_k^T g_k / |g_k| (R_k the rotation of cam_from_world), and refines in a
// gravity-aligned frame W = world_aligned_from_world() * world: +y along g_w, and the horizontal
// part of the baseline from the reference image to the scale image along +z (so W follows the
// reconstruction, not the caller's axes). The result is mapped back by W^T: it is in the caller's
// world frame, whose axes do not move; only the images' poses and the points do (a rotated copy of
// the input gives the rotated result).
//
// Rotation models (ThreeViewBundleAdjustmentOptions::RotationModel, the same two as three views):
//  - kYawOnly: R_k = A_k^T R_y(yaw_k) W, with A_k the alignment of image k's measured gravity:
//    every image's pitch and roll are exactly those of its gravity (R_k g_w = g_k / |g_k| after
//    the call, for every image), one yaw per image (YawManifold), started at the best-fitting yaw.
//  - kGravityPrior: R_k free (quaternion cam_from_W [w x y z], ceres::QuaternionManifold) with a
//    GravityPriorError(e_y, g_k) per image, weighted by (pixel_sigma_px / gravity_sigma_rad)^2.
//
// Gauge (ba/derivations.md section 14.2): both models leave 5 dof (a rotation about gravity, a
// translation, a scale), since gravity fixes the tilt (exactly for kYawOnly, through the priors for
// kGravityPrior).
//  - The reference image's centre is constant; its yaw is constant (kYawOnly), or its rotation
//    lives on the chart R_0 Exp(a e_x + b e_z) around its start R_0 (kGravityPrior: rotations about
//    W's x and z axes only, so its pitch and roll follow all images' gravity while its rotation
//    about gravity stays that of R_0 on this chart, i.e. no rotation about W's y axis is applied
//    to R_0; a yaw angle extracted from the result can still differ from R_0's once a or b is not
//    zero. Fixing its whole rotation would tie the reconstruction's tilt to one image's IMU
//    reading).
//  - The scale image's centre keeps one coordinate in W (ceres::SubsetManifold): y or z, whichever
//    component of its baseline to the reference is larger.
//
// Usage:
//   NViewReconstruction refined;
//   NViewBundleAdjustmentSummary summary = RefineWithGravity(input, config, options, &refined);
// or, to add factors of one's own before solving:
//   NViewBundleAdjuster adjuster(input, config, options);
//   adjuster.problem()->AddResidualBlock(..., adjuster.CenterBlock(k));
//   summary = adjuster.Solve();
//   refined = adjuster.CurrentReconstruction();
//
// Cost: examples/benchmarks/README.md (nview_bundle_adjustment_benchmark).

#include <ceres/problem.h>
#include <ceres/solver.h>
#include <ceres/types.h>

#include <Eigen/Core>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "trigrav/ba/ceres_solve_report.h"
#include "trigrav/ba/three_view_bundle_adjustment.h"
#include "trigrav/initializers/camera_model.h"
#include "trigrav/initializers/camera_pose.h"

namespace trigrav {

struct NViewImage {
  int camera_index = -1;      // into NViewReconstruction::cameras
  CameraPose cam_from_world;  // x_cam = R x_world + t
  // Measured gravity (down, any length GravityAlignmentFromGravity takes) in this image's camera
  // frame.
  Eigen::Vector3d gravity_in_cam = Eigen::Vector3d::Zero();
};

struct NViewObservation {
  int image_index = -1;                             // into NViewReconstruction::images
  int point_index = -1;                             // into NViewReconstruction::points_in_world
  Eigen::Vector2d pixel = Eigen::Vector2d::Zero();  // COLMAP's convention: (0.5, 0.5) is the centre
                                                    // of the top-left pixel (camera_model.h)
};

struct NViewReconstruction {
  std::vector<Camera> cameras;
  std::vector<NViewImage> images;
  std::vector<Eigen::Vector3d> points_in_world;
  std::vector<NViewObservation> observations;

  // Throws std::invalid_argument naming the field and index: a camera that fails Camera::Check(),
  // a camera/image/point index out of range, a non-finite pose, a rotation that is not a rotation
  // (|R^T R - I| > 1e-6 or det < 0), a gravity that GravityAlignmentFromGravity rejects (its
  // reason), a non-finite point or pixel, fewer than 2 images.
  void Check() const;
};

// What is refined and how the gauge is fixed (see the header comment).
struct NViewBundleAdjustmentConfig {
  // The gauge's reference image: its centre constant, its yaw (kYawOnly) or its rotation about the
  // world's gravity (kGravityPrior) constant.
  int reference_image = 0;
  // The image whose centre fixes the scale by one coordinate; -1: the image whose initial centre is
  // farthest from the reference image's. Must differ from reference_image.
  int scale_image = -1;
  // Images whose pose (yaw or rotation, and centre) is held constant, on top of the gauge. Their
  // centres are returned as given; their rotations too with kGravityPrior, while kYawOnly returns
  // A_k^T R_y(yaw_k) W with the starting (best-fitting) yaw: the given rotation snapped to the
  // image's gravity (the same for the reference image).
  std::vector<int> constant_images;
  // Images whose measured gravity is left out: not in the world's gravity estimate and without a
  // gravity prior, their tilt set by the images alone. Only with kGravityPrior (kYawOnly builds
  // every rotation from its image's gravity; the adjuster throws std::invalid_argument).
  // RefineWithGravity fills it with the images its gravity verdict finds inconsistent.
  std::vector<int> images_without_gravity;
  // Keep every point constant (motion-only refinement).
  bool constant_points = false;

  // Throws std::invalid_argument for indices out of range of `reconstruction`, or a scale image
  // equal to the reference image.
  void Check(const NViewReconstruction& reconstruction) const;
};

// The N-view adjuster's options: the shared ones (bundle_adjustment_options.h) with these
// defaults.
//  - gravity_sigma_deg = 0.1: a good IMU's tilt noise.
//  - compute_covariance: NViewBundleAdjustmentSummary::covariances (ba/derivations.md section
//    14.3: the points eliminated by blocks, the dense reduced camera matrix inverted by Cholesky,
//    O((4 or 6 N)^3)).
//  - max_num_iterations = 100, tolerances 1e-6 (function), 1e-10 (gradient), 1e-8 (parameter):
//    a whole model converges in tens of iterations (examples/benchmarks/README.md).
//  - linear_solver_type = SPARSE_SCHUR (SuiteSparse): the fastest of the Schur solvers on a
//    driving sequence of 300 images (examples/benchmarks/README.md,
//    nview_bundle_adjustment_benchmark); ITERATIVE_SCHUR gets the SCHUR_JACOBI preconditioner.
//  - stop_requested is called after each iteration.
// RefineWithGravity's gravity verdict (check_gravity, ba/derivations.md section 14.4): a first
// solve in which the images dominate (gravity priors of kVerdictGravitySigmaDeg, only the tilt's
// gauge from gravity) gives the gravity the images imply for each image; the angle to its measured
// gravity is its disagreement d_k. The IMU's sigma is the Rayleigh estimate from the median of the
// d_k (gravity_sigma_from_data), robust to a few wrong images; an image with d_k beyond
// max(max_gravity_disagreement_sigmas x sigma, kMinGravityDisagreementBoundDeg) loses its gravity
// (Config::images_without_gravity) and is named. Yaw-only, which takes every gravity as exact, is
// kept only when no image lost its gravity and the data accept exact tilts: imposing them (2
// constraints per image, c in all) raises the cost of the images-dominated solution by
// (1/2) s^2 chi^2(c) for exact gravity, s the pixel noise estimated from that solution's cost, so
// a rise beyond (1/2) s^2 (c + kYawOnlyTestSigmas sqrt(2 c)) refuses yaw-only; the gravity-prior
// model is then solved with the estimated sigma, and the summary says why.
//  - max_gravity_disagreement_sigmas = 5: a consistent image lies beyond 5 sigma with probability
//    exp(-12.5) = 4e-6 (Rayleigh), a flipped sign (180 deg) or a 10 deg error far beyond.
//  - kYawOnlyTestSigmas = 4: exact gravity fails the test with a probability of about 1e-4.
struct NViewBundleAdjustmentOptions : BundleAdjustmentOptions {
  static constexpr double kVerdictGravitySigmaDeg = 10.0;
  static constexpr double kMinGravityDisagreementBoundDeg = 0.02;
  static constexpr double kMinEstimatedGravitySigmaDeg = 0.005;
  static constexpr double kYawOnlyTestSigmas = 4.0;

  bool check_gravity = true;
  // Use the sigma the verdict estimates (at least kMinEstimatedGravitySigmaDeg) instead of
  // gravity_sigma_deg.
  bool gravity_sigma_from_data = true;
  double max_gravity_disagreement_sigmas = 5.0;

  NViewBundleAdjustmentOptions()
      : BundleAdjustmentOptions(/*gravity_sigma_deg=*/0.1,
                                /*max_num_iterations=*/100,
                                ceres::SPARSE_SCHUR,
                                /*function_tolerance=*/1e-6,
                                /*gradient_tolerance=*/1e-10,
                                /*parameter_tolerance=*/1e-8) {}

  // Throws std::invalid_argument naming the first bad field (the shared ones, then the verdict's
  // bounds: positive and finite).
  void Check() const;
  // The shared Ceres options; SCHUR_JACOBI with ITERATIVE_SCHUR. Solve() fails with Ceres' message
  // when Solver::Options::IsValid rejects them.
  ceres::Solver::Options CeresSolverOptions() const;
};

// What an N-view bundle adjustment did; the Ceres report and its accessors in CeresSolveReport.
struct NViewBundleAdjustmentSummary : CeresSolveReport {
  bool success = false;  // Ceres returned a usable solution and every refined value is finite
  // Why not, when !success (the adjuster's parameters are then restored to the start); when
  // success, empty or a note (e.g. why the covariances are empty).
  std::string message;
  int num_images = 0;
  int num_points = 0;        // points in the problem (those with >= 2 usable observations)
  int num_observations = 0;  // observations in the problem
  // Observations left out: point behind the camera at the start, or of a point left out.
  int num_skipped_observations = 0;
  // Unit gravity direction of the caller's world frame that the problem was aligned to.
  Eigen::Vector3d gravity_in_world = Eigen::Vector3d::Zero();
  // Per image: RMS of its observations' pixel residual norms at the returned solution (NaN for an
  // image without observations in the problem).
  std::vector<double> residual_rms_px;
  // Per image, when options.compute_covariance and success (empty, with the reason in message, if
  // the reduced camera matrix is not positive definite): the Gauss-Newton covariance of
  //   kYawOnly:      [yaw (rad), C_world (3)]                                  4 x 4
  //   kGravityPrior: [omega (rad, R <- Exp(omega) R, camera frame), C_world]   6 x 6
  // scaled by pixel_sigma_px^2, from the problem's own residuals (not factors a caller added).
  // Constant (gauge-fixed) parameters have zero rows and columns: the reference image's yaw and
  // centre (kYawOnly), its centre and its rotation about gravity (kGravityPrior: omega of rank 2),
  // the scale image's fixed centre coordinate (a null direction of its C block), constant images
  // and images without observations.
  std::vector<Eigen::MatrixXd> covariances;
  // Per image: its observations in the problem.
  std::vector<int> observations_per_image;
  // RefineWithGravity: the images that kept fewer than half of their observations (at least 2
  // given), by index; not a success when there is any.
  std::vector<int> images_losing_observations;
  // The rotation model solved and the IMU sigma its priors used (kGravityPrior).
  BundleAdjustmentOptions::RotationModel rotation_model =
      BundleAdjustmentOptions::RotationModel::kYawOnly;
  double gravity_sigma_deg = 0.0;
  // RefineWithGravity's gravity verdict (NViewBundleAdjustmentOptions; empty and NaN without it):
  // per image, the angle between its measured gravity and the one the images imply (deg), and
  // whether its gravity took part; the IMU sigma estimated from the consistent images (deg).
  std::vector<double> gravity_disagreement_deg;
  std::vector<char> gravity_used;
  double estimated_gravity_sigma_deg = std::numeric_limits<double>::quiet_NaN();
  double solve_s = 0.0;       // wall-clock seconds of ceres::Solve (both solves of the verdict)
  double covariance_s = 0.0;  // wall-clock seconds of the covariances
};

// Owns the ceres::Problem of an N-view refinement.
class NViewBundleAdjuster {
 public:
  // Keeps a reference to `input`, which must outlive the adjuster, and builds the problem in the
  // gravity-aligned world. Throws std::invalid_argument for an input failing
  // NViewReconstruction::Check(), a bad config or bad options. A problem that cannot be built
  // (e.g. no usable observation; no baseline: all camera centres, or the scale image's, within
  // 1e-9 of the scene's extent of the reference's centre) is not misuse: built() is false,
  // message() says why and Solve() returns a failed summary.
  NViewBundleAdjuster(const NViewReconstruction& input,
                      const NViewBundleAdjustmentConfig& config,
                      const NViewBundleAdjustmentOptions& options);
  // A temporary would dangle: the adjuster keeps a reference.
  NViewBundleAdjuster(NViewReconstruction&& input,
                      const NViewBundleAdjustmentConfig& config,
                      const NViewBundleAdjustmentOptions& options) = delete;
  ~NViewBundleAdjuster();
  NViewBundleAdjuster(const NViewBundleAdjuster&) = delete;
  NViewBundleAdjuster& operator=(const NViewBundleAdjuster&) = delete;

  // ceres::Solve on problem(), then the checks and the covariances. On failure the parameters are
  // restored to the start.
  NViewBundleAdjustmentSummary Solve();

  bool built() const { return built_; }
  const std::string& message() const { return message_; }
  const NViewBundleAdjustmentConfig& config() const { return config_; }
  const NViewBundleAdjustmentOptions& options() const { return options_; }

  // The problem and its parameter blocks, all in the gravity-aligned world W (x_W =
  // world_aligned_from_world() * x_world), for a caller adding factors (valid when built()):
  //  - RotationBlock(k): kYawOnly: yaw_k (1, YawManifold; cam_from_W = A_k^T R_y(yaw_k));
  //    kGravityPrior: cam_from_W as a quaternion [w x y z] (4).
  //  - CenterBlock(k): the centre of image k in W (3).
  //  - PointBlock(p): point p in W (3); nullptr for a point left out of the problem.
  ceres::Problem* problem() { return problem_.get(); }
  double* RotationBlock(int image);
  double* CenterBlock(int image);
  double* PointBlock(int point);
  const Eigen::Matrix3d& world_aligned_from_world() const { return world_aligned_from_world_; }
  // The index the gauge uses for the scale (config().scale_image resolved).
  int scale_image() const { return scale_image_; }

  // The input with the poses and points currently held in the parameter blocks, in the caller's
  // world frame.
  NViewReconstruction CurrentReconstruction() const;

 private:
  void Build();
  std::vector<double> ResidualRmsPx() const;
  // Fills summary->covariances; false with a note in summary->message if the reduced camera
  // matrix is not positive definite.
  bool ComputeCovariances(NViewBundleAdjustmentSummary* summary);

  const NViewReconstruction& input_;
  NViewBundleAdjustmentConfig config_;
  NViewBundleAdjustmentOptions options_;
  std::unique_ptr<ceres::Problem> problem_;
  bool built_ = false;
  std::string message_;
  int scale_image_ = -1;
  Eigen::Matrix3d world_aligned_from_world_ = Eigen::Matrix3d::Identity();
  Eigen::Vector3d gravity_in_world_ = Eigen::Vector3d::Zero();

  // Per image: gravity alignment A_k, yaw, quaternion [w x y z] (cam_from_W), centre in W.
  std::vector<Eigen::Matrix3d> alignments_;
  std::vector<double> yaws_;
  std::vector<Eigen::Vector4d> quaternions_;
  std::vector<Eigen::Vector3d> centers_;
  std::vector<Eigen::Vector3d> points_;  // in W
  std::vector<char> point_used_;         // point in the problem
  std::vector<int> used_observations_;   // indices into input_.observations
  // Residual blocks of the used observations (same order) and of the gravity priors.
  std::vector<ceres::ResidualBlockId> observation_residuals_;
  std::vector<ceres::ResidualBlockId> prior_residuals_;
};

// One call: the gravity verdict when options.check_gravity (above NViewBundleAdjustmentOptions:
// a solve in which the images dominate, then the final solve from its result with the inconsistent
// images' gravity left out and the estimated sigma), else one NViewBundleAdjuster on `input`; then
// writes the refined reconstruction to *refined (the input's cameras and observations, refined
// poses and points in the caller's world frame; the input unchanged on failure). `refined` may
// alias `input`. Not a success when an image keeps fewer than half of its observations in the
// final problem (its points behind it: a wrong pose or gravity), the image named. Throws as the
// adjuster's constructor; std::invalid_argument for a null `refined`.
NViewBundleAdjustmentSummary RefineWithGravity(const NViewReconstruction& input,
                                               const NViewBundleAdjustmentConfig& config,
                                               const NViewBundleAdjustmentOptions& options,
                                               NViewReconstruction* refined);

// The reconstruction in an upright world frame: rotated about the origin so that +y is
// `gravity_in_world` (down; e.g. NViewBundleAdjustmentSummary::gravity_in_world), +z the horizontal
// part of the old +z (or of the old +x where +z is vertical). Poses and points move, the cameras'
// views of the points do not. Throws std::invalid_argument for a zero or non-finite gravity.
NViewReconstruction UprightReconstruction(const NViewReconstruction& reconstruction,
                                          const Eigen::Vector3d& gravity_in_world);

// Per image: the RMS (px) of |project(R_k (X - C_k)) - pixel| over its observations whose point
// lies in front of it (z > 0 in its frame); NaN for an image without one. A tool compares a model
// before and after refinement with it (every observation, not only those in the problem).
// Throws as NViewReconstruction::Check().
std::vector<double> ReprojectionRmsPx(const NViewReconstruction& reconstruction);

}  // namespace trigrav

#endif  // TRIGRAV_BA_NVIEW_BUNDLE_ADJUSTMENT_H_
