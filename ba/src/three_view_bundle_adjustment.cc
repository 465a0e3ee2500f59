#include "trigrav/ba/three_view_bundle_adjustment.h"

#include <ceres/loss_function.h>
#include <ceres/manifold.h>
#include <ceres/ordered_groups.h>
#include <ceres/sphere_manifold.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <iterator>
#include <sstream>
#include <stdexcept>
#include <type_traits>
#include <utility>

#include "best_fit_yaw.h"
#include "robust_loss.h"
#include "shared_solver_options.h"
#include "trigrav/factors/angle_manifold.h"
#include "trigrav/factors/eliminated_point_reprojection_error.h"
#include "trigrav/factors/reprojection_factors.h"
#include "trigrav/initializers/gravity.h"
#include "trigrav/initializers/three_view_error.h"

namespace trigrav {
namespace {

constexpr double kDegToRad = M_PI / 180.0;

// The factor of triplet i's observation in view k (1 or 2) for the rotation model.
template <typename Residual>
ceres::CostFunction* MakeFactor(bool yaw_only,
                                const Residual& residual,
                                const Eigen::Matrix3d& alignment_cam,
                                const Eigen::Matrix3d& alignment_ref) {
  return yaw_only
             ? YawOnlyReprojectionError<Residual>::Create(residual, alignment_cam, alignment_ref)
             : ReprojectionError<Residual>::Create(residual);
}

constexpr std::pair<ThreeViewBundleAdjustmentOptions::Engine, const char*> kEngineNames[] = {
    {ThreeViewBundleAdjustmentOptions::Engine::kCeres, "ceres"},
    {ThreeViewBundleAdjustmentOptions::Engine::kCeresPointsEliminated, "ceres_points_eliminated"}};

}  // namespace

const char* EngineName(ThreeViewBundleAdjustmentOptions::Engine engine) {
  for (const auto& [value, name] : kEngineNames) {
    if (value == engine) return name;
  }
  throw std::invalid_argument("trigrav: EngineName: unknown engine");
}

bool ParseEngine(const std::string& name, ThreeViewBundleAdjustmentOptions::Engine* engine) {
  for (const auto& [value, known] : kEngineNames) {
    if (name == known) {
      *engine = value;
      return true;
    }
  }
  return false;
}

std::string EngineNames() {
  std::string names;
  const int n = static_cast<int>(std::size(kEngineNames));
  for (int i = 0; i < n; ++i) {
    names += std::string(i == 0 ? "" : i + 1 == n ? " or " : ", ") + kEngineNames[i].second;
  }
  return names;
}

ThreeViewBundleAdjustmentConfig ThreeViewBundleAdjustmentConfig::FromInlierMask(
    const std::vector<char>& inliers) {
  ThreeViewBundleAdjustmentConfig config;
  for (std::size_t i = 0; i < inliers.size(); ++i) {
    if (inliers[i]) config.triplets.push_back(static_cast<int>(i));
  }
  return config;
}

void ThreeViewBundleAdjustmentOptions::Check() const {
  const std::string name = "ThreeViewBundleAdjustmentOptions";
  CheckSharedFields(name);
  auto require = [&](bool ok, const char* what) {
    if (!ok) throw std::invalid_argument("trigrav: " + name + ": " + what);
  };
  auto positive = [](double v) { return v > 0.0 && std::isfinite(v); };
  require(std::any_of(std::begin(kEngineNames), std::end(kEngineNames),
                      [this](const auto& known) { return known.first == engine; }),
          "unknown engine");
  require(positive(loss_scale_deg), "loss_scale_deg must be positive and finite");
  require(positive(bearing_sigma_deg), "bearing_sigma_deg must be positive and finite");
}

ceres::Solver::Options ThreeViewBundleAdjustmentOptions::CeresSolverOptions() const {
  ceres::Solver::Options solver_options = BundleAdjustmentOptions::CeresSolverOptions();
  // Started at the cap instead of Ceres' 1e4: from 1e4 the first steps on driving triplets are all
  // accepted with a relative decrease near 1 while the radius only triples per step. At the cap
  // the last run of a refinement of KITTI 00 took 5.7 instead of 8.5 iterations, medians within
  // 1e-4 deg (examples/benchmarks/README.md, "Refined against raw on KITTI"). The N-view adjuster
  // keeps 1e4: at the cap its first solve on the tests' driving sequence stopped 5e-7 (relative
  // cost) short of the optimum.
  solver_options.initial_trust_region_radius = internal::kMaxTrustRegionRadius;
  return solver_options;
}

double ThreeViewBundleAdjustmentOptions::LossScale(
    const ThreeViewObservations& observations) const {
  return observations.HasBearings() ? loss_scale_deg : loss_scale_px;
}

double ThreeViewBundleAdjustmentOptions::ObservationSigma(
    const ThreeViewObservations& observations) const {
  return observations.HasBearings() ? bearing_sigma_deg : pixel_sigma_px;
}

ThreeViewBundleAdjuster::ThreeViewBundleAdjuster(const ThreeViewObservations& observations,
                                                 const ThreeViewBundleAdjustmentConfig& config,
                                                 const ThreeViewBundleAdjustmentOptions& options)
    : ThreeViewBundleAdjuster(
          observations,
          std::make_shared<const ThreeViewReprojectionError>(observations),  // checks them
          config,
          options) {}

ThreeViewBundleAdjuster::ThreeViewBundleAdjuster(
    const ThreeViewObservations& observations,
    std::shared_ptr<const ThreeViewReprojectionError> error,
    const ThreeViewBundleAdjustmentConfig& config,
    const ThreeViewBundleAdjustmentOptions& options)
    : observations_(observations), error_(std::move(error)), config_(config), options_(options) {
  if (error_ == nullptr || error_->size() != observations_.size()) {
    throw std::invalid_argument(
        "trigrav: ThreeViewBundleAdjuster: the inlier error is not of these observations");
  }
  options_.Check();
  const int n = static_cast<int>(observations_.size());
  if (config_.triplets.empty()) {
    for (int i = 0; i < n; ++i) config_.triplets.push_back(i);
  }
  for (const int i : config_.triplets) {
    if (i < 0 || i >= n) {
      throw std::invalid_argument("trigrav: ThreeViewBundleAdjuster: triplet index out of range");
    }
  }
  for (int k = 0; k < 3; ++k) {
    alignment_[k] = GravityAlignmentFromGravity(observations_.gravity_in_cam[k]);
  }
}

ThreeViewBundleAdjuster::~ThreeViewBundleAdjuster() = default;

bool ThreeViewBundleAdjuster::Build(const ThreeViewPose& initial) { return Build(initial, {}, {}); }

bool ThreeViewBundleAdjuster::Build(const ThreeViewPose& initial,
                                    const std::vector<int>& known_triplets,
                                    const std::vector<Eigen::Vector3d>& known_points) {
  if (known_triplets.size() != known_points.size()) {
    throw std::invalid_argument(
        "trigrav: ThreeViewBundleAdjuster::Build: known_triplets and known_points differ in size");
  }
  // known[i]: index into known_points of triplet i's point, -1 if none.
  std::vector<int> known(observations_.size(), -1);
  for (std::size_t j = 0; j < known_triplets.size(); ++j) {
    const int i = known_triplets[j];
    if (i < 0 || i >= static_cast<int>(known.size())) {
      throw std::invalid_argument(
          "trigrav: ThreeViewBundleAdjuster::Build: known triplet index out of range");
    }
    known[i] = static_cast<int>(j);
  }
  built_ = false;
  problem_.reset();
  points_.clear();
  used_triplets_.clear();
  triangulated_.clear();
  if (!initial.IsFinite()) {
    message_ = "initial pose is not finite";
    return false;
  }
  if (!initial.HasRotations()) {
    message_ = "initial pose's R is not a rotation (R^T R = I, det R = 1)";
    return false;
  }
  const CameraPose* poses[2] = {&initial.cam2_from_cam1, &initial.cam3_from_cam1};
  // The pose is rescaled to |C2| = 1; stableNorm where norm() overflows (|C2| above ~1e154) or
  // underflows, so that any finite scale works.
  const Eigen::Vector3d center2 = initial.cam2_from_cam1.Center();
  const double norm2 = center2.norm();
  const double scale = std::isnormal(norm2) ? norm2 : center2.stableNorm();
  if (!std::isfinite(scale)) {
    message_ = "initial pose's camera 2 centre -R^T t overflows (t too large for doubles)";
    return false;
  }
  if (!(scale > 1e-12)) {
    std::ostringstream message;
    message << "initial pose has no baseline between cameras 1 and 2 (|C2| = " << scale
            << ", at most 1e-12)";
    message_ = message.str();
    return false;
  }
  std::array<Eigen::Matrix3d, 3> rotation;
  std::array<Eigen::Vector3d, 3> center;
  rotation[0].setIdentity();
  center[0].setZero();
  const bool yaw_only =
      options_.rotation_model == ThreeViewBundleAdjustmentOptions::RotationModel::kYawOnly;
  for (int j = 0; j < 2; ++j) {
    const Eigen::Vector3d c = poses[j]->Center() / scale;
    for (int i = 0; i < 3; ++i) center_[j][i] = c[i];
    if (yaw_only) {
      yaw_[j] = internal::BestFitYaw(alignment_[j + 1] * poses[j]->R * alignment_[0].transpose());
    } else {
      Eigen::Quaterniond q(poses[j]->R);
      q.normalize();
      quaternion_[j][0] = q.w();
      quaternion_[j][1] = q.x();
      quaternion_[j][2] = q.y();
      quaternion_[j][3] = q.z();
    }
  }
  const ThreeViewPose start = CurrentPose();  // the parameterised pose (projected on the model)
  rotation[1] = start.cam2_from_cam1.R;
  rotation[2] = start.cam3_from_cam1.R;
  center[1] = start.cam2_from_cam1.Center();
  center[2] = start.cam3_from_cam1.Center();

  // Known points (rescaled with the pose) or triangulated ones; keep triplets in front of all
  // three cameras.
  auto in_front = [&](int i, const Eigen::Vector3d& x) {
    if (!x.allFinite()) return false;
    for (int k = 0; k < 3; ++k) {
      if (!std::isfinite(error_->ObservationError(k, i, rotation[k] * (x - center[k])))) {
        return false;
      }
    }
    return true;
  };
  points_.reserve(config_.triplets.size());
  for (const int i : config_.triplets) {
    Eigen::Vector3d x;
    const bool known_in_front = known[i] >= 0 && in_front(i, x = known_points[known[i]] / scale);
    if (!known_in_front) {
      std::array<Eigen::Vector3d, 3> directions;
      for (int k = 0; k < 3; ++k) directions[k] = rotation[k].transpose() * error_->rays()[k][i];
      if (!TriangulateMidpoint(center, directions, &x) || !in_front(i, x)) continue;
    }
    points_.push_back(x);
    used_triplets_.push_back(i);
    triangulated_.push_back(known_in_front ? 0 : 1);
  }
  if (points_.size() < 3) {
    message_ = "fewer than 3 triplets can be triangulated in front of the cameras (" +
               std::to_string(points_.size()) + ")";
    points_.clear();
    used_triplets_.clear();
    triangulated_.clear();
    return false;
  }
  built_ = true;
  message_.clear();
  // kCeresPointsEliminated solves a problem of its own; problem() builds this one when asked.
  if (options_.engine == ThreeViewBundleAdjustmentOptions::Engine::kCeres) BuildCeresProblem();
  return true;
}

void ThreeViewBundleAdjuster::BuildCeresProblem() {
  const bool yaw_only =
      options_.rotation_model == ThreeViewBundleAdjustmentOptions::RotationModel::kYawOnly;
  // The problem never outlives the adjuster's parameters and holds one factor per observation:
  // Ceres' per-call argument checks are skipped and one loss is shared by every observation (the
  // problem counts references and deletes it once).
  ceres::Problem::Options problem_options;
  problem_options.disable_all_safety_checks = true;
  problem_ = std::make_unique<ceres::Problem>(problem_options);
  const bool bearings = observations_.HasBearings();
  ceres::LossFunction* loss = internal::MakeLoss(options_.loss, options_.LossScale(observations_));
  for (std::size_t p = 0; p < points_.size(); ++p) {
    const int i = used_triplets_[p];
    double* point = points_[p].data();
    for (int k = 0; k < 3; ++k) {
      ceres::CostFunction* cost = nullptr;
      if (bearings) {
        const BearingResidual residual(observations_.bearings[k][i]);
        cost = k == 0 ? ReferenceReprojectionError<BearingResidual>::Create(residual)
                      : MakeFactor(yaw_only, residual, alignment_[k], alignment_[0]);
      } else {
        const PixelResidual residual{observations_.cameras[k], observations_.pixels[k][i]};
        cost = k == 0 ? ReferenceReprojectionError<PixelResidual>::Create(residual)
                      : MakeFactor(yaw_only, residual, alignment_[k], alignment_[0]);
      }
      if (k == 0) {
        problem_->AddResidualBlock(cost, loss, point);
      } else {
        problem_->AddResidualBlock(cost, loss, yaw_only ? &yaw_[k - 1] : quaternion_[k - 1],
                                   center_[k - 1], point);
      }
    }
    if (config_.constant_points) problem_->SetParameterBlockConstant(point);
  }
  AddPoseManifoldsAndPriors(problem_.get());
}

void ThreeViewBundleAdjuster::AddPoseManifoldsAndPriors(ceres::Problem* problem) {
  const bool yaw_only =
      options_.rotation_model == ThreeViewBundleAdjustmentOptions::RotationModel::kYawOnly;
  if (!yaw_only) {
    const double sigma_rad = options_.gravity_sigma_deg * kDegToRad;
    // Observation residuals are in pixels (degrees for bearings), the prior's in radians:
    // weight = (observation sigma / gravity sigma)^2 makes both whitened.
    const double ratio = options_.ObservationSigma(observations_) / sigma_rad;
    const double weight = ratio * ratio;
    for (int j = 0; j < 2; ++j) {
      problem->AddResidualBlock(GravityPriorError::Create(observations_.gravity_in_cam[0],
                                                          observations_.gravity_in_cam[j + 1]),
                                new ceres::ScaledLoss(nullptr, weight, ceres::TAKE_OWNERSHIP),
                                quaternion_[j]);
    }
  }
  for (int j = 0; j < 2; ++j) {
    if (yaw_only) {
      problem->SetManifold(&yaw_[j], CreateYawManifold());
    } else {
      problem->SetManifold(quaternion_[j], new ceres::QuaternionManifold);
    }
  }
  // Gauge: camera 1 is not in the problem; |C_2| = 1.
  problem->SetManifold(center_[0], new ceres::SphereManifold<3>);
}

template <typename Residual>
void ThreeViewBundleAdjuster::SolveWithEliminatedPoints(const ceres::Solver::Options& options,
                                                        ceres::Solver::Summary* summary) {
  const bool yaw_only =
      options_.rotation_model == ThreeViewBundleAdjustmentOptions::RotationModel::kYawOnly;
  const std::unique_ptr<ceres::LossFunction> loss(
      internal::MakeLoss(options_.loss, options_.LossScale(observations_)));
  ceres::Problem::Options problem_options;
  problem_options.disable_all_safety_checks = true;
  ceres::Problem problem(problem_options);
  const std::array<Eigen::Matrix3d, 3> alignments = {alignment_[0], alignment_[1], alignment_[2]};
  double* blocks[4] = {RotationBlock(2), center_[0], RotationBlock(3), center_[1]};
  for (std::size_t p = 0; p < points_.size(); ++p) {
    const int i = used_triplets_[p];
    typename EliminatedPointReprojectionError<Residual>::Observations triplet;
    for (int k = 0; k < 3; ++k) {
      if constexpr (std::is_same_v<Residual, BearingResidual>) {
        triplet[k] = BearingResidual(observations_.bearings[k][i]);
      } else {
        triplet[k] = PixelResidual{observations_.cameras[k], observations_.pixels[k][i]};
      }
    }
    double* point = points_[p].data();
    problem.AddResidualBlock(
        yaw_only ? EliminatedPointReprojectionError<Residual>::CreateYawOnly(triplet, alignments,
                                                                             loss.get(), point)
                 : EliminatedPointReprojectionError<Residual>::CreateWithQuaternions(
                       triplet, loss.get(), point),
        nullptr, blocks, 4);
  }
  AddPoseManifoldsAndPriors(&problem);
  ceres::Solver::Options reduced_options = options;
  // Seven (eleven) unknowns: the dense normal equations, whatever linear_solver_type says.
  reduced_options.linear_solver_type = ceres::DENSE_NORMAL_CHOLESKY;
  ceres::Solve(reduced_options, &problem, summary);  // leaves points_ at the solution's
}

void ThreeViewBundleAdjuster::SetEliminationOrdering(ceres::Solver::Options* solver_options) {
  // The points first, then the cameras: the ordering the Schur solvers' preprocessor would search
  // for, given. Only over the adjuster's own blocks: blocks a caller added keep Ceres' search. A
  // group is ordered by address, so each camera block has its own group, in the order Ceres' search
  // finds them (yaw2, C2, yaw3, C3: the order the residual blocks introduced them), which keeps
  // Ceres' arithmetic as without the ordering.
  const bool schur = solver_options->linear_solver_type == ceres::DENSE_SCHUR ||
                     solver_options->linear_solver_type == ceres::SPARSE_SCHUR ||
                     solver_options->linear_solver_type == ceres::ITERATIVE_SCHUR;
  if (!schur || problem_->NumParameterBlocks() != static_cast<int>(points_.size()) + 4) return;
  auto ordering = std::make_shared<ceres::ParameterBlockOrdering>();
  for (Eigen::Vector3d& point : points_) ordering->AddElementToGroup(point.data(), 0);
  int group = 1;
  for (int view = 2; view <= 3; ++view) {
    ordering->AddElementToGroup(RotationBlock(view), group++);
    ordering->AddElementToGroup(CenterBlock(view), group++);
  }
  solver_options->linear_solver_ordering = std::move(ordering);
}

ceres::Problem* ThreeViewBundleAdjuster::problem() {
  if (built_ && problem_ == nullptr) BuildCeresProblem();
  return problem_.get();
}

ThreeViewPose ThreeViewBundleAdjuster::CurrentPose() const {
  ThreeViewPose pose;
  CameraPose* poses[2] = {&pose.cam2_from_cam1, &pose.cam3_from_cam1};
  const bool yaw_only =
      options_.rotation_model == ThreeViewBundleAdjustmentOptions::RotationModel::kYawOnly;
  for (int j = 0; j < 2; ++j) {
    if (yaw_only) {
      poses[j]->R = alignment_[j + 1].transpose() * RotationAboutY(yaw_[j]) * alignment_[0];
    } else {
      Eigen::Quaterniond q(quaternion_[j][0], quaternion_[j][1], quaternion_[j][2],
                           quaternion_[j][3]);
      poses[j]->R = q.normalized().toRotationMatrix();
    }
    const Eigen::Vector3d c(center_[j][0], center_[j][1], center_[j][2]);
    poses[j]->t = -poses[j]->R * c;
  }
  return pose;
}

double* ThreeViewBundleAdjuster::RotationBlock(int view) {
  if (view != 2 && view != 3) {
    throw std::invalid_argument(
        "trigrav: ThreeViewBundleAdjuster::RotationBlock: view must be 2 or 3");
  }
  return options_.rotation_model == ThreeViewBundleAdjustmentOptions::RotationModel::kYawOnly
             ? &yaw_[view - 2]
             : quaternion_[view - 2];
}

double* ThreeViewBundleAdjuster::CenterBlock(int view) {
  if (view != 2 && view != 3) {
    throw std::invalid_argument(
        "trigrav: ThreeViewBundleAdjuster::CenterBlock: view must be 2 or 3");
  }
  return center_[view - 2];
}

std::vector<Eigen::Vector3d> ThreeViewBundleAdjuster::ResidualNorms() const {
  const ThreeViewReprojectionError::PreparedPose pose =
      ThreeViewReprojectionError::Prepare(CurrentPose());
  std::vector<Eigen::Vector3d> norms(points_.size());
  for (std::size_t p = 0; p < points_.size(); ++p) {
    for (int k = 0; k < 3; ++k) {
      norms[p][k] = error_->ObservationError(
          k, used_triplets_[p], pose.cam_from_ref[k] * (points_[p] - pose.center_in_ref[k]));
    }
  }
  return norms;
}

ThreeViewBundleAdjustmentSummary ThreeViewBundleAdjuster::Solve() {
  ThreeViewBundleAdjustmentSummary out;
  if (!built_) {
    out.message = message_.empty() ? "Solve() without a successful Build()" : message_;
    return out;
  }
  out.num_points = static_cast<int>(points_.size());
  // Three observations per point, and the two gravity priors.
  out.num_residual_blocks =
      3 * out.num_points +
      (options_.rotation_model == ThreeViewBundleAdjustmentOptions::RotationModel::kGravityPrior
           ? 2
           : 0);
  // Keep copies to restore on failure.
  double yaw_backup[2] = {yaw_[0], yaw_[1]};
  double quaternion_backup[2][4], center_backup[2][3];
  for (int j = 0; j < 2; ++j) {
    for (int i = 0; i < 4; ++i) quaternion_backup[j][i] = quaternion_[j][i];
    for (int i = 0; i < 3; ++i) center_backup[j][i] = center_[j][i];
  }
  const std::vector<Eigen::Vector3d> points_backup = points_;

  ceres::Solver::Options solver_options = options_.CeresSolverOptions();
  internal::StopRequestCallback stop_request(options_.stop_requested);
  if (options_.stop_requested) solver_options.callbacks.push_back(&stop_request);
  std::string error;
  if (!solver_options.IsValid(&error)) {
    out.message = "invalid Ceres options: " + error;
    return out;
  }
  ceres::Solver::Summary& summary = out.ceres_summary;
  const auto start = std::chrono::steady_clock::now();
  out.engine = options_.engine;
  if (options_.engine == ThreeViewBundleAdjustmentOptions::Engine::kCeresPointsEliminated &&
      !config_.constant_points && problem_ == nullptr) {
    if (observations_.HasBearings()) {
      SolveWithEliminatedPoints<BearingResidual>(solver_options, &summary);
    } else {
      SolveWithEliminatedPoints<PixelResidual>(solver_options, &summary);
    }
  } else {
    out.engine = ThreeViewBundleAdjustmentOptions::Engine::kCeres;
    if (problem_ == nullptr) BuildCeresProblem();
    ceres::Solver::Options ceres_options = solver_options;
    SetEliminationOrdering(&ceres_options);
    ceres::Solve(ceres_options, problem_.get(), &summary);
  }
  out.solve_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const bool stopped = options_.stop_requested && options_.stop_requested();
  if (stopped || !summary.IsSolutionUsable() || !CurrentPose().IsFinite()) {
    out.message = stopped ? std::string("stopped on request (stop_requested)")
                          : "Ceres failed: " + summary.message;
    for (int j = 0; j < 2; ++j) {
      yaw_[j] = yaw_backup[j];
      for (int i = 0; i < 4; ++i) quaternion_[j][i] = quaternion_backup[j][i];
      for (int i = 0; i < 3; ++i) center_[j][i] = center_backup[j][i];
    }
    points_ = points_backup;
    return out;
  }
  out.success = true;
  return out;
}

}  // namespace trigrav
