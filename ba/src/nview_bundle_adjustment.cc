#include "trigrav/ba/nview_bundle_adjustment.h"

#include <ceres/autodiff_manifold.h>
#include <ceres/loss_function.h>
#include <ceres/manifold.h>
#include <ceres/ordered_groups.h>
#include <ceres/rotation.h>

#include <Eigen/Geometry>
#include <Eigen/SVD>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "best_fit_yaw.h"
#include "robust_loss.h"
#include "shared_solver_options.h"
#include "trigrav/factors/angle_manifold.h"
#include "trigrav/factors/reprojection_factors.h"
#include "trigrav/initializers/gravity.h"

namespace trigrav {
namespace {

constexpr double kDegToRad = M_PI / 180.0;

[[noreturn]] void Fail(const std::string& where, const std::string& what) {
  throw std::invalid_argument("trigrav: " + where + ": " + what);
}

std::string Indexed(const char* field, std::size_t i) {
  return std::string(field) + "[" + std::to_string(i) + "]";
}

// The reference image's rotation in the gravity-prior model (ba/derivations.md section 14.2): the
// chart R = R_0 Exp(a e_x + b e_z) around its starting rotation R_0 (cam_from_W), i.e. rotations
// about the aligned world's x and z axes only, so that its rotation about gravity (the world's yaw,
// a gauge freedom) stays that of R_0 on this chart (no rotation about W's y is applied to R_0).
// Plus(q, delta) = q_0 Exp(Log(q_0^-1 q) + [d0, 0, d1]); quaternions [w x y z].
class TiltChartFunctor {
 public:
  explicit TiltChartFunctor(const Eigen::Vector4d& q0) : q0_(q0) {}

  template <typename T>
  bool Plus(const T* x, const T* delta, T* x_plus_delta) const {
    T v[3];
    LogFromStart(x, v);
    const T moved[3] = {v[0] + delta[0], v[1], v[2] + delta[1]};
    T q_moved[4];
    ceres::AngleAxisToQuaternion(moved, q_moved);
    const T q0[4] = {T(q0_[0]), T(q0_[1]), T(q0_[2]), T(q0_[3])};
    ceres::QuaternionProduct(q0, q_moved, x_plus_delta);
    return true;
  }
  template <typename T>
  bool Minus(const T* y, const T* x, T* y_minus_x) const {
    T v_y[3], v_x[3];
    LogFromStart(y, v_y);
    LogFromStart(x, v_x);
    y_minus_x[0] = v_y[0] - v_x[0];
    y_minus_x[1] = v_y[2] - v_x[2];
    return true;
  }

 private:
  // Log(q_0^-1 q) as an angle-axis vector.
  template <typename T>
  void LogFromStart(const T* q, T* v) const {
    const T q0_inverse[4] = {T(q0_[0]), T(-q0_[1]), T(-q0_[2]), T(-q0_[3])};
    T q_delta[4];
    ceres::QuaternionProduct(q0_inverse, q, q_delta);
    ceres::QuaternionToAngleAxis(q_delta, v);
  }

  Eigen::Vector4d q0_;
};
using TiltChartManifold = ceres::AutoDiffManifold<TiltChartFunctor, 4, 2>;

// A nested check's message without its "trigrav: " prefix, which Fail adds again.
std::string WithoutPrefix(const std::invalid_argument& e) {
  const std::string what = e.what();
  return what.rfind("trigrav: ", 0) == 0 ? what.substr(9) : what;
}

// The rotation cam_from_W of image k held in its parameter block (model's form).
Eigen::Matrix3d ModelRotation(bool yaw_only,
                              const Eigen::Matrix3d& alignment,
                              double yaw,
                              const Eigen::Vector4d& quaternion) {
  if (yaw_only) return alignment.transpose() * RotationAboutY(yaw);
  return Eigen::Quaterniond(quaternion[0], quaternion[1], quaternion[2], quaternion[3])
      .normalized()
      .toRotationMatrix();
}

}  // namespace

void NViewReconstruction::Check() const {
  const std::string where = "NViewReconstruction";
  if (images.size() < 2) Fail(where, "fewer than 2 images");
  for (std::size_t c = 0; c < cameras.size(); ++c) {
    try {
      cameras[c].Check();
    } catch (const std::invalid_argument& e) {
      Fail(where, Indexed("cameras", c) + ": " + WithoutPrefix(e));
    }
  }
  for (std::size_t k = 0; k < images.size(); ++k) {
    const NViewImage& image = images[k];
    if (image.camera_index < 0 || image.camera_index >= static_cast<int>(cameras.size())) {
      Fail(where, Indexed("images", k) + ".camera_index out of range");
    }
    if (!image.cam_from_world.IsFinite()) {
      Fail(where, Indexed("images", k) + ".cam_from_world is not finite");
    }
    if (!image.cam_from_world.HasRotation()) {
      Fail(where, Indexed("images", k) + ".cam_from_world.R is not a rotation");
    }
    try {
      GravityAlignmentFromGravity(image.gravity_in_cam);
    } catch (const std::invalid_argument& e) {
      Fail(where, Indexed("images", k) + ".gravity_in_cam: " + WithoutPrefix(e));
    }
  }
  for (std::size_t p = 0; p < points_in_world.size(); ++p) {
    if (!points_in_world[p].allFinite()) Fail(where, Indexed("points_in_world", p) + " not finite");
  }
  for (std::size_t i = 0; i < observations.size(); ++i) {
    const NViewObservation& observation = observations[i];
    if (observation.image_index < 0 || observation.image_index >= static_cast<int>(images.size())) {
      Fail(where, Indexed("observations", i) + ".image_index out of range");
    }
    if (observation.point_index < 0 ||
        observation.point_index >= static_cast<int>(points_in_world.size())) {
      Fail(where, Indexed("observations", i) + ".point_index out of range");
    }
    if (!observation.pixel.allFinite()) {
      Fail(where, Indexed("observations", i) + ".pixel not finite");
    }
  }
}

void NViewBundleAdjustmentConfig::Check(const NViewReconstruction& reconstruction) const {
  const std::string where = "NViewBundleAdjustmentConfig";
  const int n = static_cast<int>(reconstruction.images.size());
  if (reference_image < 0 || reference_image >= n) Fail(where, "reference_image out of range");
  if (scale_image < -1 || scale_image >= n) Fail(where, "scale_image out of range");
  if (scale_image == reference_image) Fail(where, "scale_image equals reference_image");
  for (std::size_t i = 0; i < constant_images.size(); ++i) {
    if (constant_images[i] < 0 || constant_images[i] >= n) {
      Fail(where, Indexed("constant_images", i) + " out of range");
    }
  }
  for (std::size_t i = 0; i < images_without_gravity.size(); ++i) {
    if (images_without_gravity[i] < 0 || images_without_gravity[i] >= n) {
      Fail(where, Indexed("images_without_gravity", i) + " out of range");
    }
  }
}

void NViewBundleAdjustmentOptions::Check() const {
  const std::string where = "NViewBundleAdjustmentOptions";
  CheckSharedFields(where);
  const auto positive = [](double v) { return v > 0.0 && std::isfinite(v); };
  if (!positive(max_gravity_disagreement_sigmas)) {
    Fail(where, "max_gravity_disagreement_sigmas must be positive and finite");
  }
}

ceres::Solver::Options NViewBundleAdjustmentOptions::CeresSolverOptions() const {
  ceres::Solver::Options solver_options = BundleAdjustmentOptions::CeresSolverOptions();
  // Only there: Ceres 2.1's CGNR aborts on SCHUR_JACOBI (a CHECK that Solver::Options::IsValid
  // does not anticipate); the other solvers keep Ceres' default.
  if (linear_solver_type == ceres::ITERATIVE_SCHUR) {
    solver_options.preconditioner_type = ceres::SCHUR_JACOBI;
  }
  return solver_options;
}

NViewBundleAdjuster::NViewBundleAdjuster(const NViewReconstruction& input,
                                         const NViewBundleAdjustmentConfig& config,
                                         const NViewBundleAdjustmentOptions& options)
    : input_(input), config_(config), options_(options) {
  input_.Check();
  config_.Check(input_);
  options_.Check();
  if (!config_.images_without_gravity.empty() &&
      options_.rotation_model == NViewBundleAdjustmentOptions::RotationModel::kYawOnly) {
    Fail("NViewBundleAdjuster",
         "images_without_gravity needs the gravity-prior model (yaw-only builds every rotation "
         "from its image's gravity)");
  }
  Build();
}

NViewBundleAdjuster::~NViewBundleAdjuster() = default;

double* NViewBundleAdjuster::RotationBlock(int image) {
  if (image < 0 || image >= static_cast<int>(input_.images.size())) {
    Fail("NViewBundleAdjuster::RotationBlock", "image out of range");
  }
  return options_.rotation_model == NViewBundleAdjustmentOptions::RotationModel::kYawOnly
             ? &yaws_[image]
             : quaternions_[image].data();
}

double* NViewBundleAdjuster::CenterBlock(int image) {
  if (image < 0 || image >= static_cast<int>(input_.images.size())) {
    Fail("NViewBundleAdjuster::CenterBlock", "image out of range");
  }
  return centers_[image].data();
}

double* NViewBundleAdjuster::PointBlock(int point) {
  if (point < 0 || point >= static_cast<int>(input_.points_in_world.size())) {
    Fail("NViewBundleAdjuster::PointBlock", "point out of range");
  }
  return point_used_[point] ? points_[point].data() : nullptr;
}

void NViewBundleAdjuster::Build() {
  const bool yaw_only =
      options_.rotation_model == NViewBundleAdjustmentOptions::RotationModel::kYawOnly;
  const int num_images = static_cast<int>(input_.images.size());
  const int num_points = static_cast<int>(input_.points_in_world.size());

  // The world's gravity: the mean of the images' gravity directions mapped to the world,
  // g_w ~ sum_k R_k^T g_k / |g_k| (ba/derivations.md section 14.1).
  std::vector<char> has_gravity(num_images, 1);
  for (const int k : config_.images_without_gravity) has_gravity[k] = 0;
  Eigen::Vector3d gravity_sum = Eigen::Vector3d::Zero();
  for (int k = 0; k < num_images; ++k) {
    const NViewImage& image = input_.images[k];
    if (has_gravity[k]) {
      gravity_sum += image.cam_from_world.R.transpose() * image.gravity_in_cam.normalized();
    }
  }
  if (!(gravity_sum.norm() > 1e-6 * num_images)) {
    message_ = "the images' gravity directions cancel out in the world frame";
    return;
  }
  gravity_in_world_ = gravity_sum.normalized();
  // The parameters in W = w_from_world * world (model's form), and the rotations they hold.
  alignments_.resize(num_images);
  yaws_.assign(num_images, 0.0);
  quaternions_.resize(num_images);
  centers_.resize(num_images);
  points_.resize(num_points);
  std::vector<Eigen::Matrix3d> rotations(num_images);  // cam_from_W
  auto set_parameters = [&](const Eigen::Matrix3d& w_from_world) {
    world_aligned_from_world_ = w_from_world;
    for (int k = 0; k < num_images; ++k) {
      const NViewImage& image = input_.images[k];
      const Eigen::Matrix3d cam_from_w = image.cam_from_world.R * w_from_world.transpose();
      alignments_[k] = GravityAlignmentFromGravity(image.gravity_in_cam);
      yaws_[k] = internal::BestFitYaw(alignments_[k] * cam_from_w);
      const Eigen::Quaterniond q = Eigen::Quaterniond(cam_from_w).normalized();
      quaternions_[k] = Eigen::Vector4d(q.w(), q.x(), q.y(), q.z());
      centers_[k] = w_from_world * image.cam_from_world.Center();
      rotations[k] = ModelRotation(yaw_only, alignments_[k], yaws_[k], quaternions_[k]);
    }
    for (int p = 0; p < num_points; ++p) points_[p] = w_from_world * input_.points_in_world[p];
  };
  // First any gravity-aligned frame; its yaw is set below, once the scale image is known.
  set_parameters(GravityAlignmentFromGravity(gravity_in_world_));

  // Observations of points in front of their camera at the current parameters; points with >= 2
  // of them. Run again once W's yaw is final: a yaw-only start with a gravity far from the image's
  // pose (a flipped sign) has a degenerate best-fitting yaw that may differ between the frames.
  std::vector<char> image_used(num_images, 0);
  auto select_observations = [&]() {
    std::vector<char> in_front(input_.observations.size(), 0);
    std::vector<int> count(num_points, 0);
    for (std::size_t i = 0; i < input_.observations.size(); ++i) {
      const NViewObservation& o = input_.observations[i];
      const Eigen::Vector3d x_cam =
          rotations[o.image_index] * (points_[o.point_index] - centers_[o.image_index]);
      if (x_cam.z() > 0.0) {
        in_front[i] = 1;
        ++count[o.point_index];
      }
    }
    point_used_.assign(num_points, 0);
    for (int p = 0; p < num_points; ++p) point_used_[p] = count[p] >= 2;
    used_observations_.clear();
    image_used.assign(num_images, 0);
    for (std::size_t i = 0; i < input_.observations.size(); ++i) {
      const NViewObservation& o = input_.observations[i];
      if (in_front[i] && point_used_[o.point_index]) {
        used_observations_.push_back(static_cast<int>(i));
        image_used[o.image_index] = 1;
      }
    }
  };
  select_observations();

  // Gauge (ba/derivations.md section 14.2).
  const int reference = config_.reference_image;
  scale_image_ = config_.scale_image;
  if (scale_image_ < 0) {
    double farthest = -1.0;
    for (int k = 0; k < num_images; ++k) {
      const double d = (centers_[k] - centers_[reference]).norm();
      if (k != reference && image_used[k] && d > farthest) {
        farthest = d;
        scale_image_ = k;
      }
    }
  }
  if (!image_used[reference]) {
    message_ = "the reference image has no usable observation";
    return;
  }
  if (scale_image_ < 0 || !image_used[scale_image_]) {
    message_ = "the scale image has no usable observation";
    return;
  }
  // W's yaw: the horizontal part of the baseline C_scale - C_reference along +z, so that W, and the
  // coordinate the gauge fixes, follow the reconstruction and not the caller's world axes.
  const Eigen::Vector3d first_baseline = centers_[scale_image_] - centers_[reference];
  const double heading = std::atan2(first_baseline.x(), first_baseline.z());
  set_parameters(RotationAboutY(-heading) * world_aligned_from_world_);
  select_observations();
  if (!image_used[reference] || !image_used[scale_image_]) {
    message_ =
        "the reference or the scale image has no usable observation in the gravity-aligned "
        "frame (its gravity contradicts its pose)";
    return;
  }
  const Eigen::Vector3d baseline = centers_[scale_image_] - centers_[reference];
  int scale_axis = 0;
  baseline.cwiseAbs().maxCoeff(&scale_axis);  // y or z
  // The scene's extent about the reference centre: its farthest camera centre or point. A baseline
  // below 1e-9 of it (e.g. all centres equal but for round-off) would fix the scale at round-off,
  // the points' depths and the covariances unbounded: refused.
  double centers_extent = 0.0, points_extent = 0.0;
  for (const Eigen::Vector3d& c : centers_) {
    centers_extent = std::max(centers_extent, (c - centers_[reference]).norm());
  }
  for (int p = 0; p < num_points; ++p) {
    if (!point_used_[p]) continue;
    points_extent = std::max(points_extent, (points_[p] - centers_[reference]).norm());
  }
  const double scene_extent = std::max(centers_extent, points_extent);
  if (!(baseline.norm() > 1e-9 * scene_extent)) {
    std::ostringstream message;
    if (!(centers_extent > 1e-9 * scene_extent)) {
      message << "all camera centres coincide (within " << centers_extent
              << " of the reference image's, the points up to " << points_extent
              << " away): no baseline fixes the scale; start from poses that have one";
    } else {
      message << "the scale image's centre coincides with the reference image's ("
              << baseline.norm() << " apart, the scene " << scene_extent
              << " across): choose another scale_image";
    }
    message_ = message.str();
    return;
  }

  // The problem holds one factor per observation; one loss is shared (Ceres counts references).
  ceres::Problem::Options problem_options;
  problem_options.disable_all_safety_checks = true;
  problem_ = std::make_unique<ceres::Problem>(problem_options);
  observation_residuals_.clear();
  prior_residuals_.clear();
  ceres::LossFunction* loss = internal::MakeLoss(options_.loss, options_.loss_scale_px);
  const Eigen::Matrix3d identity = Eigen::Matrix3d::Identity();  // W is gravity-aligned: A_W = I
  for (const int i : used_observations_) {
    const NViewObservation& o = input_.observations[i];
    const int k = o.image_index;
    const PixelResidual residual{input_.cameras[input_.images[k].camera_index], o.pixel};
    ceres::CostFunction* cost = yaw_only ? YawOnlyReprojectionError<PixelResidual>::Create(
                                               residual, alignments_[k], identity)
                                         : ReprojectionError<PixelResidual>::Create(residual);
    observation_residuals_.push_back(problem_->AddResidualBlock(
        cost, loss, RotationBlock(k), centers_[k].data(), points_[o.point_index].data()));
  }
  const double gravity_weight =
      std::pow(options_.pixel_sigma_px / (options_.gravity_sigma_deg * kDegToRad), 2);
  for (int k = 0; k < num_images; ++k) {
    if (!image_used[k]) continue;
    if (yaw_only) {
      problem_->SetManifold(&yaws_[k], CreateYawManifold());
    } else {
      // Pixel residuals and the prior's radians whitened alike: weight (sigma_px / sigma_g)^2.
      if (has_gravity[k]) {
        prior_residuals_.push_back(problem_->AddResidualBlock(
            GravityPriorError::Create(Eigen::Vector3d::UnitY(), input_.images[k].gravity_in_cam),
            new ceres::ScaledLoss(nullptr, gravity_weight, ceres::TAKE_OWNERSHIP),
            quaternions_[k].data()));
      }
      problem_->SetManifold(quaternions_[k].data(),
                            k == reference ? static_cast<ceres::Manifold*>(new TiltChartManifold(
                                                 new TiltChartFunctor(quaternions_[k])))
                                           : new ceres::QuaternionManifold);
    }
  }
  if (yaw_only) problem_->SetParameterBlockConstant(&yaws_[reference]);
  problem_->SetParameterBlockConstant(centers_[reference].data());
  problem_->SetManifold(centers_[scale_image_].data(),
                        new ceres::SubsetManifold(3, std::vector<int>{scale_axis}));
  for (const int k : config_.constant_images) {
    if (!image_used[k]) continue;
    problem_->SetParameterBlockConstant(RotationBlock(k));
    problem_->SetParameterBlockConstant(centers_[k].data());
  }
  if (config_.constant_points) {
    for (int p = 0; p < num_points; ++p) {
      if (point_used_[p]) problem_->SetParameterBlockConstant(points_[p].data());
    }
  }
  built_ = true;
  message_.clear();
}

std::vector<double> NViewBundleAdjuster::ResidualRmsPx() const {
  const bool yaw_only =
      options_.rotation_model == NViewBundleAdjustmentOptions::RotationModel::kYawOnly;
  const int num_images = static_cast<int>(input_.images.size());
  std::vector<Eigen::Matrix3d> rotations(num_images);
  for (int k = 0; k < num_images; ++k) {
    rotations[k] = ModelRotation(yaw_only, alignments_[k], yaws_[k], quaternions_[k]);
  }
  std::vector<double> sum(num_images, 0.0);
  std::vector<int> count(num_images, 0);
  for (const int i : used_observations_) {
    const NViewObservation& o = input_.observations[i];
    const int k = o.image_index;
    const Eigen::Vector3d x_cam = rotations[k] * (points_[o.point_index] - centers_[k]);
    const double r =
        x_cam.z() > 0.0
            ? (input_.cameras[input_.images[k].camera_index].Project(x_cam) - o.pixel).squaredNorm()
            : std::numeric_limits<double>::infinity();
    sum[k] += r;
    ++count[k];
  }
  std::vector<double> rms(num_images, std::numeric_limits<double>::quiet_NaN());
  for (int k = 0; k < num_images; ++k) {
    if (count[k] > 0) rms[k] = std::sqrt(sum[k] / count[k]);
  }
  return rms;
}

NViewReconstruction NViewBundleAdjuster::CurrentReconstruction() const {
  NViewReconstruction out = input_;
  if (alignments_.empty()) return out;  // the build stopped before the parameters were set
  const bool yaw_only =
      options_.rotation_model == NViewBundleAdjustmentOptions::RotationModel::kYawOnly;
  const Eigen::Matrix3d& w_from_world = world_aligned_from_world_;
  for (std::size_t k = 0; k < out.images.size(); ++k) {
    // cam_from_world = cam_from_W * W_from_world; C_world = W_from_world^T C_W.
    CameraPose& pose = out.images[k].cam_from_world;
    pose.R = ModelRotation(yaw_only, alignments_[k], yaws_[k], quaternions_[k]) * w_from_world;
    pose.t = -pose.R * (w_from_world.transpose() * centers_[k]);
  }
  for (std::size_t p = 0; p < out.points_in_world.size(); ++p) {
    if (point_used_[p]) out.points_in_world[p] = w_from_world.transpose() * points_[p];
  }
  return out;
}

NViewBundleAdjustmentSummary NViewBundleAdjuster::Solve() {
  NViewBundleAdjustmentSummary summary;
  summary.num_images = static_cast<int>(input_.images.size());
  summary.gravity_in_world = gravity_in_world_;
  if (!built_) {
    summary.message = message_;
    return summary;
  }
  summary.num_observations = static_cast<int>(used_observations_.size());
  summary.num_skipped_observations =
      static_cast<int>(input_.observations.size()) - summary.num_observations;
  for (const char used : point_used_) summary.num_points += used;
  summary.observations_per_image.assign(input_.images.size(), 0);
  for (const int i : used_observations_) {
    ++summary.observations_per_image[input_.observations[i].image_index];
  }
  summary.rotation_model = options_.rotation_model;
  summary.gravity_sigma_deg = options_.gravity_sigma_deg;

  const std::vector<double> start_yaws = yaws_;
  const std::vector<Eigen::Vector4d> start_quaternions = quaternions_;
  const std::vector<Eigen::Vector3d> start_centers = centers_, start_points = points_;

  ceres::Solver::Options solver_options = options_.CeresSolverOptions();
  // Points first, then the cameras (what Ceres' search would find, given), when the problem holds
  // only the adjuster's blocks; blocks a caller added leave the ordering to Ceres.
  const bool schur = solver_options.linear_solver_type == ceres::DENSE_SCHUR ||
                     solver_options.linear_solver_type == ceres::SPARSE_SCHUR ||
                     solver_options.linear_solver_type == ceres::ITERATIVE_SCHUR;
  std::vector<double*> blocks;
  problem_->GetParameterBlocks(&blocks);
  auto ordering = std::make_shared<ceres::ParameterBlockOrdering>();
  int num_own_blocks = 0;
  for (std::size_t p = 0; p < points_.size(); ++p) {
    if (point_used_[p] && problem_->HasParameterBlock(points_[p].data())) {
      ordering->AddElementToGroup(points_[p].data(), 0);
      ++num_own_blocks;
    }
  }
  for (std::size_t k = 0; k < input_.images.size(); ++k) {
    for (double* block : {RotationBlock(static_cast<int>(k)), centers_[k].data()}) {
      if (problem_->HasParameterBlock(block)) {
        ordering->AddElementToGroup(block, 1);
        ++num_own_blocks;
      }
    }
  }
  if (schur && num_own_blocks == static_cast<int>(blocks.size()) && !config_.constant_points) {
    solver_options.linear_solver_ordering = std::move(ordering);
  }

  internal::StopRequestCallback stop_request(options_.stop_requested);
  if (options_.stop_requested) solver_options.callbacks.push_back(&stop_request);
  std::string error;
  if (!solver_options.IsValid(&error)) {
    summary.message = "invalid Ceres options: " + error;
    return summary;
  }
  const auto start = std::chrono::steady_clock::now();
  ceres::Solve(solver_options, problem_.get(), &summary.ceres_summary);
  summary.solve_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  bool finite = true;
  for (std::size_t k = 0; k < input_.images.size(); ++k) {
    finite =
        finite && std::isfinite(yaws_[k]) && quaternions_[k].allFinite() && centers_[k].allFinite();
  }
  for (const Eigen::Vector3d& x : points_) finite = finite && x.allFinite();
  const bool stopped = options_.stop_requested && options_.stop_requested();
  if (stopped || !summary.ceres_summary.IsSolutionUsable() || !finite ||
      !std::isfinite(summary.ceres_summary.final_cost)) {
    yaws_ = start_yaws;
    quaternions_ = start_quaternions;
    centers_ = start_centers;
    points_ = start_points;
    summary.message = stopped   ? std::string("stopped on request (stop_requested)")
                      : !finite ? "the solution is not finite"
                                : "Ceres failed: " + summary.ceres_summary.message;
    return summary;
  }
  summary.success = true;
  if (summary.ceres_summary.termination_type == ceres::NO_CONVERGENCE) {
    summary.message = "max_num_iterations reached before convergence";
  }
  summary.residual_rms_px = ResidualRmsPx();
  if (options_.compute_covariance) ComputeCovariances(&summary);
  return summary;
}

namespace {

// `moved` rotated rigidly about `reference`'s centre back into `start`'s world frame: the rotation
// Q closest to the images' R_k^moved^T R_k^start in the chordal sense (the polar factor of their
// sum), applied as R_k <- R_k Q, X <- C_ref + Q^T (X - C_ref). A solve may turn the whole model (a
// gauge; e.g. one flipped gravity prior tilting it); this keeps the caller's world frame.
NViewReconstruction AlignedToStart(NViewReconstruction moved,
                                   const NViewReconstruction& start,
                                   int reference) {
  Eigen::Matrix3d sum = Eigen::Matrix3d::Zero();
  for (std::size_t k = 0; k < moved.images.size(); ++k) {
    sum += moved.images[k].cam_from_world.R.transpose() * start.images[k].cam_from_world.R;
  }
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(sum, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d q = svd.matrixU() * svd.matrixV().transpose();
  if (q.determinant() < 0.0) {
    Eigen::Matrix3d u = svd.matrixU();
    u.col(2) = -u.col(2);
    q = u * svd.matrixV().transpose();
  }
  const Eigen::Vector3d pivot = moved.images[reference].cam_from_world.Center();
  for (NViewImage& image : moved.images) {
    const Eigen::Vector3d center = pivot + q.transpose() * (image.cam_from_world.Center() - pivot);
    image.cam_from_world.R = image.cam_from_world.R * q;
    image.cam_from_world.t = -image.cam_from_world.R * center;
  }
  for (Eigen::Vector3d& point : moved.points_in_world)
    point = pivot + q.transpose() * (point - pivot);
  return moved;
}

// Per image, the angle (deg) between its measured gravity and the one the images imply: R_k g_w,
// with g_w the normalised sum of R_k^T g_k over the images whose `used` is set.
std::vector<double> GravityDisagreementsDeg(const NViewReconstruction& reconstruction,
                                            const std::vector<char>& used) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (std::size_t k = 0; k < reconstruction.images.size(); ++k) {
    const NViewImage& image = reconstruction.images[k];
    if (used[k]) sum += image.cam_from_world.R.transpose() * image.gravity_in_cam.normalized();
  }
  const Eigen::Vector3d gravity_in_world = sum.normalized();
  std::vector<double> degrees(reconstruction.images.size());
  for (std::size_t k = 0; k < degrees.size(); ++k) {
    const NViewImage& image = reconstruction.images[k];
    const Eigen::Vector3d implied = image.cam_from_world.R * gravity_in_world;
    const Eigen::Vector3d measured = image.gravity_in_cam.normalized();
    degrees[k] = std::atan2(implied.cross(measured).norm(), implied.dot(measured)) * 180.0 / M_PI;
  }
  return degrees;
}

// The gravity verdict on the images-dominated solution `seen` (ba/derivations.md section 14.4):
// disagreements, the images whose gravity is kept, the Rayleigh estimate of the IMU's sigma from
// them. Two rounds: the world's gravity from all images, then from the consistent ones.
struct GravityVerdict {
  std::vector<double> disagreement_deg;
  std::vector<char> used;
  double sigma_deg = 0.0;
};

GravityVerdict JudgeGravity(const NViewReconstruction& seen,
                            const NViewBundleAdjustmentOptions& options) {
  // The median of a Rayleigh distribution is sigma sqrt(2 ln 2).
  const double rayleigh_median = std::sqrt(2.0 * std::log(2.0));
  GravityVerdict verdict;
  verdict.used.assign(seen.images.size(), 1);
  for (int round = 0; round < 2; ++round) {
    verdict.disagreement_deg = GravityDisagreementsDeg(seen, verdict.used);
    std::vector<double> kept;
    for (std::size_t k = 0; k < seen.images.size(); ++k) {
      if (verdict.used[k]) kept.push_back(verdict.disagreement_deg[k]);
    }
    std::nth_element(kept.begin(), kept.begin() + kept.size() / 2, kept.end());
    verdict.sigma_deg = kept[kept.size() / 2] / rayleigh_median;
    const double bound = std::max(options.max_gravity_disagreement_sigmas * verdict.sigma_deg,
                                  NViewBundleAdjustmentOptions::kMinGravityDisagreementBoundDeg);
    for (std::size_t k = 0; k < seen.images.size(); ++k) {
      verdict.used[k] = verdict.disagreement_deg[k] <= bound;
    }
  }
  return verdict;
}

std::string ImageList(const std::vector<int>& images) {
  std::ostringstream list;
  for (std::size_t i = 0; i < images.size() && i < 10; ++i) list << (i ? ", " : "") << images[i];
  if (images.size() > 10) list << " and " << images.size() - 10 << " more";
  return list.str();
}

// Not a success when an image keeps fewer than half of its observations (at least 2 of them).
void RefuseDroppedObservations(const NViewReconstruction& input,
                               NViewBundleAdjustmentSummary* summary) {
  if (!summary->success) return;
  std::vector<int> given(input.images.size(), 0);
  for (const NViewObservation& o : input.observations) ++given[o.image_index];
  std::vector<int>& dropped = summary->images_losing_observations;
  for (std::size_t k = 0; k < given.size(); ++k) {
    if (given[k] >= 2 && 2 * summary->observations_per_image[k] < given[k]) {
      dropped.push_back(static_cast<int>(k));
    }
  }
  if (dropped.empty()) return;
  summary->success = false;
  summary->message = "image(s) " + ImageList(dropped) +
                     " keep fewer than half of their observations (points behind the camera): a "
                     "wrong pose or gravity; nothing refined";
}

}  // namespace

NViewBundleAdjustmentSummary RefineWithGravity(const NViewReconstruction& input,
                                               const NViewBundleAdjustmentConfig& config,
                                               const NViewBundleAdjustmentOptions& options,
                                               NViewReconstruction* refined) {
  if (refined == nullptr) Fail("RefineWithGravity", "refined is null");
  input.Check();
  config.Check(input);
  options.Check();
  const auto finish = [&](NViewBundleAdjustmentSummary summary, const NViewReconstruction* result) {
    RefuseDroppedObservations(input, &summary);
    if (summary.success) {
      NViewReconstruction copy = *result;  // `refined` may alias `input`
      *refined = std::move(copy);
    } else if (refined != &input) {
      *refined = input;
    }
    return summary;
  };
  if (!options.check_gravity) {
    NViewBundleAdjuster adjuster(input, config, options);
    const NViewBundleAdjustmentSummary summary = adjuster.Solve();
    const NViewReconstruction result =
        summary.success ? adjuster.CurrentReconstruction() : NViewReconstruction();
    return finish(summary, &result);
  }

  // 1. The images dominate: weak priors fix only the tilt's gauge.
  NViewBundleAdjustmentOptions seeing = options;
  seeing.rotation_model = NViewBundleAdjustmentOptions::RotationModel::kGravityPrior;
  seeing.gravity_sigma_deg = NViewBundleAdjustmentOptions::kVerdictGravitySigmaDeg;
  seeing.compute_covariance = false;
  NViewBundleAdjustmentConfig seeing_config = config;
  seeing_config.images_without_gravity.clear();
  NViewBundleAdjuster first(input, seeing_config, seeing);
  NViewBundleAdjustmentSummary first_summary = first.Solve();
  if (!first_summary.success) {
    first_summary.message = "the images-only solve failed: " + first_summary.message;
    return finish(first_summary, nullptr);
  }
  const NViewReconstruction seen =
      AlignedToStart(first.CurrentReconstruction(), input, config.reference_image);

  // 2. The verdict.
  GravityVerdict verdict = JudgeGravity(seen, options);
  for (const int k : config.images_without_gravity) verdict.used[k] = 0;
  NViewBundleAdjustmentOptions final_options = options;
  if (options.gravity_sigma_from_data) {
    final_options.gravity_sigma_deg =
        std::max(verdict.sigma_deg, NViewBundleAdjustmentOptions::kMinEstimatedGravitySigmaDeg);
  }
  NViewBundleAdjustmentConfig final_config = config;
  final_config.images_without_gravity.clear();
  for (std::size_t k = 0; k < verdict.used.size(); ++k) {
    if (!verdict.used[k]) final_config.images_without_gravity.push_back(static_cast<int>(k));
  }
  std::ostringstream note;
  if (!final_config.images_without_gravity.empty()) {
    note << "gravity left out of image(s) " << ImageList(final_config.images_without_gravity)
         << " (the images disagree with it by up to "
         << *std::max_element(verdict.disagreement_deg.begin(), verdict.disagreement_deg.end())
         << " deg; IMU sigma estimated at "
         << std::max(verdict.sigma_deg, NViewBundleAdjustmentOptions::kMinEstimatedGravitySigmaDeg)
         << " deg)";
  }
  // 3. The final solve, from the images-dominated solution: yaw-only if asked for and the data
  // accept exact tilts, else the gravity prior.
  NViewBundleAdjustmentSummary summary;
  NViewReconstruction result;
  bool solved = false;
  if (options.rotation_model == NViewBundleAdjustmentOptions::RotationModel::kYawOnly) {
    if (!final_config.images_without_gravity.empty()) {
      note << "; yaw-only refused (those images contradict their gravity): the gravity-prior "
              "model solved";
    } else {
      NViewBundleAdjuster yaw_only(seen, final_config, final_options);
      summary = yaw_only.Solve();
      const ceres::Solver::Summary& seen_report = first_summary.ceres_summary;
      const double noise_variance =
          2.0 * seen_report.final_cost /
          std::max(1, seen_report.num_residuals - seen_report.num_effective_parameters);
      int constrained = 0;
      for (const int n : summary.observations_per_image) constrained += n > 0 ? 2 : 0;
      const double expected = 0.5 * noise_variance * constrained;
      const double bound = expected + 0.5 * noise_variance *
                                          NViewBundleAdjustmentOptions::kYawOnlyTestSigmas *
                                          std::sqrt(2.0 * constrained);
      const double rise = summary.FinalCost() - seen_report.final_cost;
      solved = summary.success && rise <= bound;
      if (solved) {
        result = yaw_only.CurrentReconstruction();
      } else if (summary.success) {
        note << (note.tellp() > 0 ? "; " : "") << "yaw-only refused: exact tilts raise the cost by "
             << rise << " (exact gravity: " << expected << ", at most " << bound
             << "): the gravity-prior model solved";
      }
    }
    final_options.rotation_model = NViewBundleAdjustmentOptions::RotationModel::kGravityPrior;
  }
  if (!solved) {
    const double yaw_only_s = summary.solve_s;
    NViewBundleAdjuster prior(seen, final_config, final_options);
    summary = prior.Solve();
    summary.solve_s += yaw_only_s;
    if (summary.success) result = prior.CurrentReconstruction();
  }
  summary.solve_s += first_summary.solve_s;
  summary.gravity_disagreement_deg = verdict.disagreement_deg;
  summary.gravity_used = verdict.used;
  summary.estimated_gravity_sigma_deg = verdict.sigma_deg;
  std::string notes = note.str();
  if (notes.rfind("; ", 0) == 0) notes.erase(0, 2);
  if (summary.success && !notes.empty()) {
    summary.message = summary.message.empty() ? notes : summary.message + "; " + notes;
  }
  return finish(summary, &result);
}

NViewReconstruction UprightReconstruction(const NViewReconstruction& reconstruction,
                                          const Eigen::Vector3d& gravity_in_world) {
  if (!gravity_in_world.allFinite() || !(gravity_in_world.norm() > 0.0)) {
    Fail("UprightReconstruction", "gravity_in_world must be finite and non-zero");
  }
  // upright_from_world: rows x, y, z of the new axes in the old frame.
  const Eigen::Vector3d y = gravity_in_world.normalized();
  Eigen::Vector3d z = Eigen::Vector3d::UnitZ() - y.z() * y;
  if (z.norm() < 1e-6) z = Eigen::Vector3d::UnitX() - y.x() * y;
  z.normalize();
  Eigen::Matrix3d upright_from_world;
  upright_from_world.row(0) = y.cross(z);
  upright_from_world.row(1) = y;
  upright_from_world.row(2) = z;
  NViewReconstruction out = reconstruction;
  for (NViewImage& image : out.images) {
    const Eigen::Vector3d center = upright_from_world * image.cam_from_world.Center();
    image.cam_from_world.R = image.cam_from_world.R * upright_from_world.transpose();
    image.cam_from_world.t = -image.cam_from_world.R * center;
  }
  for (Eigen::Vector3d& point : out.points_in_world) point = upright_from_world * point;
  return out;
}

std::vector<double> ReprojectionRmsPx(const NViewReconstruction& reconstruction) {
  reconstruction.Check();
  const std::size_t num_images = reconstruction.images.size();
  std::vector<double> sum(num_images, 0.0);
  std::vector<int> count(num_images, 0);
  for (const NViewObservation& o : reconstruction.observations) {
    const NViewImage& image = reconstruction.images[o.image_index];
    const Eigen::Vector3d x_cam =
        image.cam_from_world.Apply(reconstruction.points_in_world[o.point_index]);
    if (!(x_cam.z() > 0.0)) continue;
    sum[o.image_index] +=
        (reconstruction.cameras[image.camera_index].Project(x_cam) - o.pixel).squaredNorm();
    ++count[o.image_index];
  }
  std::vector<double> rms(num_images, std::numeric_limits<double>::quiet_NaN());
  for (std::size_t k = 0; k < num_images; ++k) {
    if (count[k] > 0) rms[k] = std::sqrt(sum[k] / count[k]);
  }
  return rms;
}

}  // namespace trigrav
