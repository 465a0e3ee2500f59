#ifndef TRIGRAV_BA_THREE_VIEW_BUNDLE_ADJUSTMENT_H_
#define TRIGRAV_BA_THREE_VIEW_BUNDLE_ADJUSTMENT_H_

// Three-view bundle adjustment, split like COLMAP's estimators/bundle_adjustment.h into a Config
// (what is in the problem, what is constant, how the gauge is fixed), Options (rotation model,
// loss, solver) and a builder that owns the ceres::Problem.

#include <ceres/problem.h>
#include <ceres/solver.h>
#include <ceres/types.h>

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "trigrav/ba/bundle_adjustment_options.h"
#include "trigrav/ba/ceres_solve_report.h"
#include "trigrav/initializers/camera_pose.h"
#include "trigrav/initializers/three_view_error.h"
#include "trigrav/initializers/three_view_observations.h"

namespace trigrav {

// What is refined and how the 7-dof gauge of three uncalibrated-scale views is fixed:
//  - camera 1 is the reference: identity rotation, centre at the origin, never in the problem;
//  - the scale is fixed by |C_2| = 1, camera 2's centre living on ceres::SphereManifold<3>.
struct ThreeViewBundleAdjustmentConfig {
  // Triplets put into the problem (indices into the observations), e.g. the RANSAC inliers. Empty
  // means all of them.
  std::vector<int> triplets;
  // Keep the triangulated points constant (motion-only refinement).
  bool constant_points = false;

  // Config with the triplets whose mask entry is non-zero.
  static ThreeViewBundleAdjustmentConfig FromInlierMask(const std::vector<char>& inliers);
};

// The three-view adjuster's options: the shared ones (bundle_adjustment_options.h) with these
// defaults, the engine, and the loss and noise of bearing observations.
//  - gravity_sigma_deg = 0.5: a consumer IMU's tilt noise, so that the gravity-prior model lets the
//    images correct a tilt the IMU got wrong (the yaw-only model takes the tilt as exact).
//  - loss_scale_px = 2 (Huber): at the RANSAC threshold Huber only guards against a stray inlier;
//    at 1 px with 1 px noise it triples Ceres' iterations for no accuracy.
//  - max_num_iterations = 50, far above the few iterations a refinement takes
//    (examples/benchmarks/README.md); tolerances 1e-8 (function), 1e-10 (gradient, parameter):
//    tight because iterations are few, and tight enough that both engines stop at the same
//    optimum (tests/ba/engine_agreement_test.cc); DENSE_SCHUR for kCeres: its points eliminated,
//    a dense 7 x 7 (11 x 11) camera system.
//  - compute_covariance: the refined pose's covariance (ThreeViewRefinement::covariance,
//    three_view_covariance.h, ba/derivations.md section 12), scaled by ObservationSigma()^2 (and
//    gravity_sigma_deg^2 through the prior's weight); its cost is measured in
//    examples/experiments/README.md (covariance_calibration). InitializeAndRefine computes it in
//    every refinement run.
//  - stop_requested is called after each iteration of either engine.
struct ThreeViewBundleAdjustmentOptions : BundleAdjustmentOptions {
  // Which Ceres problem is solved. Both reach the same optimum (tests/ba/engine_agreement_test.cc:
  // final costs equal to 1e-8 relative; with Cauchy's loss, whose cost can have several minima,
  // kCeresPointsEliminated may stop in another, never a worse one on those tests) with the
  // tolerances and iteration cap of CeresSolverOptions().
  //  - kCeresPointsEliminated (default): ceres::Solve on a problem of the pose blocks alone, one
  //    EliminatedPointReprojectionError per point (variable projection, ba/derivations.md section
  //    15): usually fewer iterations than kCeres, a 7 x 7 (11 x 11) dense system
  //    (DENSE_NORMAL_CHOLESKY, whatever linear_solver_type says); about half kCeres' time
  //    (examples/benchmarks/README.md). With Config::constant_points (no point to eliminate), or
  //    once the caller has asked for problem() (so that factors, constant blocks or bounds put
  //    there take part), Solve() solves problem() as kCeres: the summary's `engine` says which
  //    engine solved.
  //  - kCeres: ceres::Solve on problem(), one factor per observation and a block per point
  //    (DENSE_SCHUR by default); factors a caller added to problem() take part.
  enum class Engine { kCeres, kCeresPointsEliminated };

  Engine engine = Engine::kCeresPointsEliminated;
  // loss_scale_px and pixel_sigma_px for bearing observations, in degrees
  // (observation_residual.h); the defaults are the pixel ones at a focal length of 1150 px.
  double loss_scale_deg = 0.1;
  double bearing_sigma_deg = 0.05;

  ThreeViewBundleAdjustmentOptions()
      : BundleAdjustmentOptions(/*gravity_sigma_deg=*/0.5,
                                /*max_num_iterations=*/50,
                                ceres::DENSE_SCHUR,
                                /*function_tolerance=*/1e-8,
                                /*gradient_tolerance=*/1e-10,
                                /*parameter_tolerance=*/1e-10) {}

  // Throws std::invalid_argument naming the first bad field (the shared ones, then engine,
  // loss_scale_deg, bearing_sigma_deg).
  void Check() const;
  // The loss scale and the observation sigma that apply to the observations: the *_deg fields for
  // bearings, else the *_px ones.
  double LossScale(const ThreeViewObservations& observations) const;
  double ObservationSigma(const ThreeViewObservations& observations) const;
  // The shared Ceres options, the trust region starting at its cap.
  ceres::Solver::Options CeresSolverOptions() const;
};

// The engines' names for command lines and bindings: "ceres", "ceres_points_eliminated".
const char* EngineName(ThreeViewBundleAdjustmentOptions::Engine engine);
// Inverse of EngineName; false (and *engine untouched) for an unknown name.
bool ParseEngine(const std::string& name, ThreeViewBundleAdjustmentOptions::Engine* engine);
// "ceres or ceres_points_eliminated", for a flag's help and error messages.
std::string EngineNames();

// The one refinement summary: what a bundle adjustment did (the refined pose and points are held by
// the adjuster, and returned by RefineThreeViewPose), Ceres' report in ceres_summary.
struct ThreeViewBundleAdjustmentSummary : CeresSolveReport {
  bool success = false;  // the engine ran and returned a usable (finite) solution
  // Why not, when !success; when success, empty or a note (e.g. why the covariance is empty).
  std::string message;
  // The engine that solved: options().engine, or kCeres where kCeresPointsEliminated solves
  // problem() (ThreeViewBundleAdjustmentOptions::Engine).
  ThreeViewBundleAdjustmentOptions::Engine engine =
      ThreeViewBundleAdjustmentOptions::Engine::kCeresPointsEliminated;
  int num_points = 0;  // triplets in the problem
  int num_residual_blocks = 0;
  double solve_s = 0.0;  // wall-clock seconds of ceres::Solve
};

// Owns the ceres::Problem of a three-view refinement. Usage:
//   ThreeViewBundleAdjuster ba(observations, config, options);
//   if (ba.Build(initial_pose)) summary = ba.Solve();
class ThreeViewBundleAdjuster {
 public:
  // Keeps a reference to `observations`, which must outlive the adjuster. Throws
  // std::invalid_argument for observations that fail ThreeViewObservations::Check() (sizes differ,
  // bad intrinsics, non-finite pixels, zero or non-finite gravity), bad options or a triplet index
  // out of range.
  ThreeViewBundleAdjuster(const ThreeViewObservations& observations,
                          const ThreeViewBundleAdjustmentConfig& config,
                          const ThreeViewBundleAdjustmentOptions& options);
  // The same with the inlier error of these observations already built, shared and read only (the
  // adjuster takes each observation's ray and visibility from it; InitializeAndRefine builds one
  // for all its runs and its re-classification). `error` must have been built from these very
  // observations: its construction checked them, and they are not checked again; an error of other
  // observations with as many triplets is not detected. Throws std::invalid_argument if `error` is
  // null or has not one entry per triplet, for bad options or a triplet index out of range.
  ThreeViewBundleAdjuster(const ThreeViewObservations& observations,
                          std::shared_ptr<const ThreeViewReprojectionError> error,
                          const ThreeViewBundleAdjustmentConfig& config,
                          const ThreeViewBundleAdjustmentOptions& options);
  // A temporary would dangle: the adjuster keeps a reference.
  ThreeViewBundleAdjuster(ThreeViewObservations&& observations,
                          const ThreeViewBundleAdjustmentConfig& config,
                          const ThreeViewBundleAdjustmentOptions& options) = delete;
  ThreeViewBundleAdjuster(ThreeViewObservations&& observations,
                          std::shared_ptr<const ThreeViewReprojectionError> error,
                          const ThreeViewBundleAdjustmentConfig& config,
                          const ThreeViewBundleAdjustmentOptions& options) = delete;
  ~ThreeViewBundleAdjuster();
  ThreeViewBundleAdjuster(const ThreeViewBundleAdjuster&) = delete;
  ThreeViewBundleAdjuster& operator=(const ThreeViewBundleAdjuster&) = delete;

  // Builds the problem around `initial` (rescaled to |C_2| = 1): parameters from the pose, points
  // triangulated by the multi-view midpoint (TriangulateMidpoint); triplets that cannot be
  // triangulated or lie behind a camera are left out. Returns false with message() if the pose is
  // not finite, |C_2| <= 1e-12 (no baseline) or overflows, or fewer than 3 triplets remain. Any
  // finite |C_2| above 1e-12 works: a translation of 1e300 refines as one of 1.
  bool Build(const ThreeViewPose& initial);
  // Build() with known starting points for some triplets, e.g. those of a previous refinement
  // (ThreeViewRefinement::triplets and points_in_cam1): known_points[j] (camera 1's frame, at the
  // scale of `initial`) is the point of triplet known_triplets[j]. A triplet of the config with a
  // known point that is finite and in front of the three cameras starts from it; the others are
  // triangulated as by Build(). Throws std::invalid_argument if the sizes differ or an index is
  // out of range.
  bool Build(const ThreeViewPose& initial,
             const std::vector<int>& known_triplets,
             const std::vector<Eigen::Vector3d>& known_points);
  // Solves with the engine of options().engine (see Engine for when kCeresPointsEliminated solves
  // problem() instead). Requires a successful Build(). On failure the parameters are restored.
  ThreeViewBundleAdjustmentSummary Solve();

  const std::string& message() const { return message_; }
  // True after a successful Build().
  bool built() const { return built_; }
  const ThreeViewBundleAdjustmentOptions& options() const { return options_; }
  const ThreeViewBundleAdjustmentConfig& config() const { return config_; }
  const ThreeViewObservations& observations() const { return observations_; }
  // The kCeres engine's problem and its parameter blocks, valid after a successful Build(), for a
  // caller who adds factors of their own or runs ceres::Covariance on it (nullptr before). With
  // kCeresPointsEliminated it is built on the first call, over the same parameter blocks, and
  // Solve() then solves it as kCeres (the summary's engine says so). Camera 1 is not in the
  // problem; for view 2 or 3 (std::invalid_argument otherwise):
  //  - RotationBlock(view): kYawOnly: the yaw (1 number, YawManifold; R = A_k^T R_y(yaw) A_1);
  //    kGravityPrior: the rotation cam_from_cam1 as a quaternion [w x y z] (4,
  //    ceres::QuaternionManifold, whose Plus is q <- [cos|d|, sin|d| d / |d|] * q: a rotation by
  //    2 |d| about d, multiplied on the left, in camera k's frame).
  //  - CenterBlock(view): the centre C_k in camera 1's frame (3); view 2's lives on
  //    ceres::SphereManifold<3> (|C2| = 1, the gauge).
  // PointBlock(p): point p (3, camera 1's frame) of triplet_indices()[p]; constant when
  // Config::constant_points.
  ceres::Problem* problem();
  double* RotationBlock(int view);
  double* CenterBlock(int view);
  double* PointBlock(int p) { return points_[p].data(); }
  // The pose currently held in the parameter blocks.
  ThreeViewPose CurrentPose() const;
  // Points of the problem's triplets (reference frame), in the order of triplet_indices().
  const std::vector<Eigen::Vector3d>& points() const { return points_; }
  const std::vector<int>& triplet_indices() const { return used_triplets_; }
  // Per point (order of points()): 1 if Build() triangulated it, 0 if it started from a known one.
  const std::vector<char>& triangulated() const { return triangulated_; }
  // Per point (order of points()): the residual norms of its observations in views 1, 2, 3 at the
  // current pose and points (pixels, degrees for bearings; observation_residual.h), +inf for an
  // observation that cannot see its point.
  std::vector<Eigen::Vector3d> ResidualNorms() const;

 private:
  // The ceres::Problem over the parameter blocks of a successful Build().
  void BuildCeresProblem();
  // The pose blocks' manifolds and, for kGravityPrior, the gravity priors.
  void AddPoseManifoldsAndPriors(ceres::Problem* problem);
  // Engine::kCeresPointsEliminated's solve (without constant points).
  template <typename Residual>
  void SolveWithEliminatedPoints(const ceres::Solver::Options& options,
                                 ceres::Solver::Summary* summary);
  // Gives the Schur solvers of the Ceres engine the points-then-cameras elimination ordering.
  void SetEliminationOrdering(ceres::Solver::Options* solver_options);

  const ThreeViewObservations& observations_;
  // Rays and visibility of every observation.
  const std::shared_ptr<const ThreeViewReprojectionError> error_;
  ThreeViewBundleAdjustmentConfig config_;
  ThreeViewBundleAdjustmentOptions options_;
  std::unique_ptr<ceres::Problem> problem_;
  std::string message_;
  bool built_ = false;

  Eigen::Matrix3d alignment_[3];
  // Per camera 2, 3 (index 0, 1): yaw (kYawOnly) or quaternion [w x y z] (kGravityPrior), centre.
  double yaw_[2] = {0.0, 0.0};
  double quaternion_[2][4] = {{1.0, 0.0, 0.0, 0.0}, {1.0, 0.0, 0.0, 0.0}};
  double center_[2][3] = {{0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}};
  std::vector<Eigen::Vector3d> points_;
  std::vector<int> used_triplets_;
  std::vector<char> triangulated_;
};

}  // namespace trigrav

#endif  // TRIGRAV_BA_THREE_VIEW_BUNDLE_ADJUSTMENT_H_
