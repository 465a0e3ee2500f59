// The dedicated Levenberg-Marquardt engine (three_view_lm_solver.h; ba/derivations.md section 13).
#include "three_view_lm_solver.h"

#include <ceres/manifold.h>
#include <ceres/sphere_manifold.h>

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <string>
#include <utility>

#include "robust_loss.h"
#include "trigrav/factors/angle_manifold.h"
#include "trigrav/factors/observation_jacobian.h"
#include "trigrav/factors/point_gauss_newton.h"
#include "trigrav/factors/reprojection_factors.h"
#include "trigrav/initializers/gravity.h"
#include "trigrav/initializers/skew.h"

namespace trigrav {
namespace internal {
namespace {

using Options = ThreeViewBundleAdjustmentOptions;
constexpr double kDegToRad = M_PI / 180.0;

// The options' loss (robust_loss.h: Ceres' own HuberLoss / CauchyLoss). Huber and Cauchy have
// rho'' <= 0, where Ceres' corrector (internal/ceres/corrector.cc) scales the residual and its
// Jacobian by sqrt(rho'): the cost is 1/2 rho(|r|^2) and the normal equations those of
// sqrt(rho') r (section 13.2).
class Loss {
 public:
  Loss(Options::LossType type, double scale) : loss_(MakeLoss(type, scale)) {}

  // Adds 1/2 rho(s) to *cost and returns sqrt(rho'(s)).
  double Apply(double s, double* cost) const {
    if (loss_ == nullptr) {
      *cost += 0.5 * s;
      return 1.0;
    }
    double rho[3];
    loss_->Evaluate(s, rho);
    *cost += 0.5 * rho[0];
    return std::sqrt(rho[1]);
  }

  // The loss function, nullptr for the squared loss.
  const ceres::LossFunction* function() const { return loss_.get(); }

 private:
  std::unique_ptr<ceres::LossFunction> loss_;
};

// One view's observations of the problem's points, in the order of the adjuster's triplets, with
// Evaluate(p, x_cam, &r, &dr/dx_cam) as LinearizeObservation
// (trigrav/factors/observation_jacobian.h).
template <typename Residual>
class ViewObservations;

// Pixels: the camera once and the pixels packed (16 bytes per point, read once per evaluation).
template <>
class ViewObservations<PixelResidual> {
 public:
  ViewObservations(const ThreeViewObservations& observations,
                   int view,
                   const std::vector<int>& triplets)
      : camera_(observations.cameras[view]), pinhole_(camera_.IsPinhole()) {
    const internal::CameraParamLayout layout = internal::ParamLayout(camera_.model);
    fx_ = camera_.params[layout.fx];
    fy_ = camera_.params[layout.fy];
    cx_ = camera_.params[layout.cx];
    cy_ = camera_.params[layout.cy];
    pixels_.reserve(triplets.size());
    for (const int i : triplets) pixels_.push_back(observations.pixels[view][i]);
  }

  bool Evaluate(std::size_t p,
                const Eigen::Vector3d& x,
                Eigen::Vector2d* r,
                Eigen::Matrix<double, 2, 3>* jacobian) const {
    if (!pinhole_) return EvaluateDistorted(p, x, r, jacobian);
    // Camera::Project's arithmetic (fx X / Z + cx) in registers, inlined into the caller: writing
    // the pixel to *r and reading it back as a pair stalled on store forwarding.
    if (!(x.z() > 0.0)) return false;
    const Eigen::Vector2d& pixel = pixels_[p];
    const double u = fx_ * x.x() / x.z() + cx_ - pixel.x();
    const double v = fy_ * x.y() / x.z() + cy_ - pixel.y();
    const Eigen::Matrix<double, 2, 3> d_r_d_x = PinholeJacobian(fx_, fy_, x);
    if (!std::isfinite(u) || !std::isfinite(v) || !d_r_d_x.allFinite()) return false;
    *r = Eigen::Vector2d(u, v);
    *jacobian = d_r_d_x;
    return true;
  }

 private:
  bool EvaluateDistorted(std::size_t p,
                         const Eigen::Vector3d& x,
                         Eigen::Vector2d* r,
                         Eigen::Matrix<double, 2, 3>* jacobian) const;

  Camera camera_;
  bool pinhole_;
  double fx_, fy_, cx_, cy_;
  std::vector<Eigen::Vector2d> pixels_;
};

bool ViewObservations<PixelResidual>::EvaluateDistorted(
    std::size_t p,
    const Eigen::Vector3d& x,
    Eigen::Vector2d* r,
    Eigen::Matrix<double, 2, 3>* jacobian) const {
  return LinearizeObservationByJets(PixelResidual{camera_, pixels_[p]}, x, r, jacobian);
}

template <>
class ViewObservations<BearingResidual> {
 public:
  ViewObservations(const ThreeViewObservations& observations,
                   int view,
                   const std::vector<int>& triplets) {
    residuals_.reserve(triplets.size());
    for (const int i : triplets) residuals_.emplace_back(observations.bearings[view][i]);
  }

  bool Evaluate(std::size_t p,
                const Eigen::Vector3d& x,
                Eigen::Vector2d* r,
                Eigen::Matrix<double, 2, 3>* jacobian) const {
    return LinearizeObservation(residuals_[p], x, r, jacobian);
  }

 private:
  std::vector<BearingResidual> residuals_;
};

// The engine for one residual type and one rotation model (kRot = 1: yaw, 3: quaternion tangent).
// Pose unknowns in its internal order [rotation 2, C2 (2, sphere), rotation 3, C3 (3)], so that
// each view's columns are contiguous and the pose-pose block of one observation is dense.
template <typename Residual, int kRot>
class Engine {
 public:
  static constexpr int kSize2 = kRot + 2;  // view 2: rotation, C2's tangent
  static constexpr int kSize3 = kRot + 3;  // view 3: rotation, C3
  static constexpr int kSize = kSize2 + kSize3;
  using PoseVector = Eigen::Matrix<double, kSize, 1>;
  using PoseMatrix = Eigen::Matrix<double, kSize, kSize>;
  using PointPoseMatrix = Eigen::Matrix<double, 3, kSize>;

  explicit Engine(ThreeViewBundleAdjuster* adjuster)
      : adjuster_(adjuster),
        options_(adjuster->options()),
        solver_options_(options_.CeresSolverOptions()),
        constant_points_(adjuster->config().constant_points),
        loss_(options_.loss, options_.LossScale(adjuster->observations())),
        views_{
            ViewObservations<Residual>(adjuster->observations(), 0, adjuster->triplet_indices()),
            ViewObservations<Residual>(adjuster->observations(), 1, adjuster->triplet_indices()),
            ViewObservations<Residual>(adjuster->observations(), 2, adjuster->triplet_indices())} {
    const ThreeViewObservations& observations = adjuster->observations();
    const std::vector<int>& triplets = adjuster->triplet_indices();
    for (int k = 0; k < 3; ++k) {
      alignment_[k] = GravityAlignmentFromGravity(observations.gravity_in_cam[k]);
    }
    for (int j = 0; j < 2; ++j) {
      gravity_[j] = observations.gravity_in_cam[j + 1].normalized();
      if constexpr (kRot == 3) {
        prior_[j].reset(GravityPriorError::Create(observations.gravity_in_cam[0],
                                                  observations.gravity_in_cam[j + 1]));
      }
    }
    if constexpr (kRot == 3) {
      // (observation sigma / gravity sigma)^2, as ThreeViewBundleAdjuster::Build's ScaledLoss.
      const double ratio =
          options_.ObservationSigma(observations) / (options_.gravity_sigma_deg * kDegToRad);
      prior_weight_ = ratio * ratio;
    }
    const std::size_t n = triplets.size();
    std::swap(storage_, ThreadStorage());
    // Reserved before resizing, so that each capacity is the largest size this thread has needed
    // (what kMaxRetainedPoints bounds), not a growing vector's doubling.
    const auto size = [n](auto* buffer) {
      buffer->reserve(n);
      buffer->resize(n);
    };
    for (Linearization* l : {&storage_.current, &storage_.candidate}) {
      size(&l->observations);
      size(&l->points);
    }
    size(&storage_.point_scale_squared);
    size(&storage_.point_inverse);
    size(&storage_.point_step);
    size(&storage_.candidate_points);
    for (int j = 0; j < 2; ++j) {
      std::copy_n(adjuster->CenterBlock(j + 2), 3, x_.center[j]);
      std::copy_n(adjuster->RotationBlock(j + 2), kRot == 1 ? 1 : 4,
                  kRot == 1 ? &x_.yaw[j] : x_.quaternion[j]);
    }
    storage_.points = adjuster->points();  // reallocates to exactly n only when too small
  }

  ~Engine() {
    if (storage_.current.observations.capacity() <= kMaxRetainedPoints) {
      std::swap(storage_, ThreadStorage());
    }
  }
  Engine(const Engine&) = delete;
  Engine& operator=(const Engine&) = delete;

  void Solve(ceres::Solver::Summary* summary);
  bool Information(ThreeViewInformation* information);

 private:
  // The pose in the adjuster's ambient parameters.
  struct Pose {
    double yaw[2] = {0.0, 0.0};
    double quaternion[2][4] = {{1.0, 0.0, 0.0, 0.0}, {1.0, 0.0, 0.0, 0.0}};
    double center[2][3] = {{0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}};
  };
  struct PointBlocks {
    Eigen::Matrix3d hpp;  // J_p^T J_p
    PointPoseMatrix hpc;  // J_p^T J_c
    Eigen::Vector3d gp;   // J_p^T r
  };
  // One observation's whitened residual sqrt(rho') r, its Jacobian sqrt(rho') J_r and x_cam.
  struct WhitenedObservation {
    Eigen::Matrix<double, 2, 3> jr;
    Eigen::Vector2d r;
    Eigen::Vector3d x_cam;
  };
  // Residuals and normal equations at one parameter vector (section 13.3): EvaluateResiduals
  // fills the cost and the whitened observations, Linearize the normal equations from them.
  struct Linearization {
    std::vector<std::array<WhitenedObservation, 3>> observations;
    Eigen::Matrix<double, 2, 3> prior_jacobian[2];  // sqrt(w) J of the gravity priors (kRot = 3)
    Eigen::Vector2d prior_residual[2];              // sqrt(w) r
    Eigen::Matrix3d rotation[2];
    Eigen::Matrix<double, 3, 2> sphere;  // C2's Plus Jacobian P
    std::vector<PointBlocks> points;
    PoseMatrix hcc;
    PoseVector gc;
    double cost = 0.0;        // of the residuals that depend on a variable block
    double fixed_cost = 0.0;  // view 1's, when the points are constant (Ceres' fixed_cost)
  };

  bool EvaluateResiduals(const Pose& pose,
                         const std::vector<Eigen::Vector3d>& points,
                         Linearization* out) const;
  void Linearize(Linearization* lin) const;
  bool Evaluate(const Pose& pose,
                const std::vector<Eigen::Vector3d>& points,
                Linearization* out) const {
    if (!EvaluateResiduals(pose, points, out)) return false;
    Linearize(out);
    return true;
  }
  template <int kView>
  void AddView(const Eigen::Matrix<double, 2, 3>& jr,
               const Eigen::Vector2d& r,
               const Eigen::Matrix3d& rotation,
               const Eigen::Vector3d& x_cam,
               const Eigen::Matrix<double, 3, 2>& sphere_jacobian,
               PointBlocks* point,
               PoseMatrix* hcc,
               PoseVector* gc) const;
  bool ComputeStep(double radius, PoseVector* pose_step, double* model_cost_change);
  // *reduced -= w hpc on and below the diagonal, all the Cholesky factorisation reads. Column by
  // column (lazy products): the whole 11 x 3 by 3 x 11 product went through Eigen's general matrix
  // product (packing and a blocked kernel), 1.6x the time of the gravity-prior step; each column's
  // length fixed at compile time: with run-time lengths, the loops' bounds and alignment checks.
  template <int... kColumns>
  static void SubtractLowerProduct(const Eigen::Matrix<double, kSize, 3>& w,
                                   const PointPoseMatrix& hpc,
                                   PoseMatrix* reduced,
                                   std::integer_sequence<int, kColumns...>) {
    ((reduced->col(kColumns).template tail<kSize - kColumns>().noalias() -=
      w.template bottomRows<kSize - kColumns>() * hpc.col(kColumns)),
     ...);
  }
  bool WarmStart() const;
  double PolishTriangulatedPoints();
  void Plus(const Pose& x, const PoseVector& delta, Pose* out) const;
  double AmbientNorm(const Pose& pose, const std::vector<Eigen::Vector3d>& points) const;
  double GradientMaxNorm() const;
  // d_i of section 13.4 from H_ii, s_i^2 and the radius.
  double Damping(double diagonal, double scale_squared, double radius) const {
    return std::min(std::max(scale_squared * diagonal, solver_options_.min_lm_diagonal),
                    solver_options_.max_lm_diagonal) /
           (scale_squared * radius);
  }
  Eigen::Matrix3d Rotation(const Pose& pose, int j) const {
    if constexpr (kRot == 1) {
      return alignment_[j + 1].transpose() * RotationAboutY(pose.yaw[j]) * alignment_[0];
    }
    const double* q = pose.quaternion[j];
    return Eigen::Quaterniond(q[0], q[1], q[2], q[3]).toRotationMatrix();
  }
  void WriteBack() {
    for (int j = 0; j < 2; ++j) {
      std::copy_n(x_.center[j], 3, adjuster_->CenterBlock(j + 2));
      std::copy_n(kRot == 1 ? &x_.yaw[j] : x_.quaternion[j], kRot == 1 ? 1 : 4,
                  adjuster_->RotationBlock(j + 2));
    }
    for (std::size_t p = 0; p < storage_.points.size(); ++p) {
      Eigen::Map<Eigen::Vector3d>(adjuster_->PointBlock(static_cast<int>(p))) = storage_.points[p];
    }
  }

  ThreeViewBundleAdjuster* adjuster_;
  const Options& options_;
  const ceres::Solver::Options solver_options_;
  const bool constant_points_;
  const Loss loss_;
  const ViewObservations<Residual> views_[3];
  Eigen::Matrix3d alignment_[3];
  Eigen::Vector3d gravity_[2];  // unit gravity in cameras 2, 3: the yaw's axis
  std::unique_ptr<ceres::CostFunction> prior_[2];
  double prior_weight_ = 0.0;
  const ceres::QuaternionManifold quaternion_manifold_;
  const ceres::SphereManifold<3> sphere_manifold_;

  // The iterate and the candidate, and the pose's Jacobi scales s_i^2, fixed at iteration 0.
  Pose x_, candidate_x_;
  PoseVector pose_scale_squared_;
  // Per-point storage: the points at the iterate and the candidate, their linearisations, the
  // points' Jacobi scales, (H_pp + D_p^2)^-1 and the point steps of the last step. 1.2-1.4 kB per
  // point, taken over from the thread's previous engine of this kind and handed on to its next one
  // (ThreadStorage, one per residual type and rotation model, held until the thread exits), so that
  // a caller's loop of refinements reuses resident memory: allocated per
  // solve, it was faulted in afresh each time the allocator had returned it to the system
  // (InitializeAndRefine at 875 triplets in a loop: 2.87 -> 2.36 ms,
  // examples/benchmarks/README.md).
  struct Storage {
    std::vector<Eigen::Vector3d> points, candidate_points;
    Linearization current, candidate;
    std::vector<Eigen::Vector3d> point_scale_squared;
    std::vector<Eigen::Matrix3d> point_inverse;
    std::vector<Eigen::Vector3d> point_step;
  };
  // Storage for more points than this is freed with the engine instead (10-12 MB).
  static constexpr std::size_t kMaxRetainedPoints = 8192;
  static Storage& ThreadStorage() {
    thread_local Storage storage;
    return storage;
  }
  Storage storage_;
};

template <typename Residual, int kRot>
template <int kView>
void Engine<Residual, kRot>::AddView(const Eigen::Matrix<double, 2, 3>& jr,
                                     const Eigen::Vector2d& r,
                                     const Eigen::Matrix3d& rotation,
                                     const Eigen::Vector3d& x_cam,
                                     const Eigen::Matrix<double, 3, 2>& sphere_jacobian,
                                     PointBlocks* point,
                                     PoseMatrix* hcc,
                                     PoseVector* gc) const {
  // x_cam = R (X - C): d x / d X = R, d x / d C = -R; rotations by left perturbation
  // (section 13.1): yaw about camera k's gravity, d x / d yaw = g_k x x_cam; Ceres' quaternion
  // tangent rotates by 2 delta, d x / d delta = -2 [x_cam]_x. With J_X = J_r R, J_C = -J_X (C2:
  // -J_X P), the products J_X^T J_X, J_X^T r, J_X^T J_rot serve every block (section 13.3); the
  // pose-pose block only below the diagonal (Evaluate mirrors it).
  constexpr int kOffset = kView == 0 ? 0 : kSize2;
  constexpr int kCenter = kOffset + kRot;  // the centre's columns
  const Eigen::Matrix<double, 2, 3> jx = jr * rotation;
  Eigen::Matrix<double, 2, kRot> jrot;
  if constexpr (kRot == 1) {
    jrot = jr * gravity_[kView].cross(x_cam);
  } else {
    jrot = -2.0 * jr * Skew(x_cam);
  }
  const Eigen::Matrix3d xx = jx.transpose() * jx;
  const Eigen::Vector3d xr = jx.transpose() * r;
  const Eigen::Matrix<double, 3, kRot> xrot = jx.transpose() * jrot;
  point->hpp += xx;
  point->gp += xr;
  point->hpc.template middleCols<kRot>(kOffset) = xrot;
  hcc->template block<kRot, kRot>(kOffset, kOffset).noalias() += jrot.transpose() * jrot;
  gc->template segment<kRot>(kOffset).noalias() += jrot.transpose() * r;
  if constexpr (kView == 0) {
    const Eigen::Matrix<double, 3, 2> xx_p = xx * sphere_jacobian;
    point->hpc.template middleCols<2>(kCenter) = -xx_p;
    hcc->template block<2, 2>(kCenter, kCenter).noalias() += sphere_jacobian.transpose() * xx_p;
    hcc->template block<2, kRot>(kCenter, kOffset).noalias() -= sphere_jacobian.transpose() * xrot;
    gc->template segment<2>(kCenter).noalias() -= sphere_jacobian.transpose() * xr;
  } else {
    point->hpc.template middleCols<3>(kCenter) = -xx;
    hcc->template block<3, 3>(kCenter, kCenter) += xx;
    hcc->template block<3, kRot>(kCenter, kOffset) -= xrot;
    gc->template segment<3>(kCenter) -= xr;
  }
}

// The cost and the whitened observations; false if a residual cannot be evaluated or the cost is
// not finite.
template <typename Residual, int kRot>
bool Engine<Residual, kRot>::EvaluateResiduals(const Pose& pose,
                                               const std::vector<Eigen::Vector3d>& points,
                                               Linearization* out) const {
  Eigen::Matrix3d rotation[2];
  Eigen::Vector3d center[2];
  for (int j = 0; j < 2; ++j) {
    rotation[j] = Rotation(pose, j);
    center[j] = Eigen::Map<const Eigen::Vector3d>(pose.center[j]);
    out->rotation[j] = rotation[j];
  }
  Eigen::Matrix<double, 3, 2, Eigen::RowMajor> sphere_jacobian;
  sphere_manifold_.PlusJacobian(pose.center[0], sphere_jacobian.data());
  out->sphere = sphere_jacobian;
  // Sums in locals, stored once: the loss is a virtual call, and stores through *out kept the
  // compiler from holding them in registers or on the stack.
  double cost = 0.0;
  double fixed_cost = 0.0;
  for (std::size_t p = 0; p < points.size(); ++p) {
    const Eigen::Vector3d& point = points[p];
    std::array<WhitenedObservation, 3>& observations = out->observations[p];
    for (int k = 0; k < 3; ++k) {
      // View 1: the reference camera sees the point in its own frame.
      WhitenedObservation& o = observations[k];
      o.x_cam = k == 0 ? point : Eigen::Vector3d(rotation[k - 1] * (point - center[k - 1]));
      if (!views_[k].Evaluate(p, o.x_cam, &o.r, &o.jr)) return false;
      const double weight =
          loss_.Apply(o.r.squaredNorm(), k == 0 && constant_points_ ? &fixed_cost : &cost);
      o.jr *= weight;
      o.r *= weight;
    }
  }
  if constexpr (kRot == 3) {
    // Gravity priors: Ceres' AutoDiff Jacobian in the quaternion's ambient coordinates times the
    // QuaternionManifold's Plus Jacobian; weight w as ScaledLoss: cost w/2 |r|^2, sqrt(w) r.
    const double sqrt_weight = std::sqrt(prior_weight_);
    for (int j = 0; j < 2; ++j) {
      const double* parameters[1] = {pose.quaternion[j]};
      Eigen::Matrix<double, 2, 4, Eigen::RowMajor> ambient;
      double* jacobian_blocks[1] = {ambient.data()};
      Eigen::Vector2d prior_residual;
      if (!prior_[j]->Evaluate(parameters, prior_residual.data(), jacobian_blocks) ||
          !prior_residual.allFinite()) {
        return false;
      }
      cost += 0.5 * prior_weight_ * prior_residual.squaredNorm();
      Eigen::Matrix<double, 4, 3, Eigen::RowMajor> plus_jacobian;
      quaternion_manifold_.PlusJacobian(pose.quaternion[j], plus_jacobian.data());
      out->prior_jacobian[j] = sqrt_weight * ambient * plus_jacobian;
      out->prior_residual[j] = sqrt_weight * prior_residual;
    }
  }
  out->cost = cost;
  out->fixed_cost = fixed_cost;
  return std::isfinite(cost) && std::isfinite(fixed_cost);
}

// The normal equations from EvaluateResiduals' whitened observations (section 13.3): only for an
// iterate the loop continues from, not for a rejected or final candidate (section 13.5).
template <typename Residual, int kRot>
void Engine<Residual, kRot>::Linearize(Linearization* lin) const {
  PoseMatrix hcc = PoseMatrix::Zero();
  PoseVector gc = PoseVector::Zero();
  for (std::size_t p = 0; p < lin->observations.size(); ++p) {
    const std::array<WhitenedObservation, 3>& observations = lin->observations[p];
    // Summed in place: a local copy was read back by pairs across the coupling's misaligned
    // columns (3 x 3 + 3 x m doubles), stalling on store forwarding.
    PointBlocks& blocks = lin->points[p];
    blocks.hpp.noalias() = observations[0].jr.transpose() * observations[0].jr;
    blocks.gp.noalias() = observations[0].jr.transpose() * observations[0].r;
    const WhitenedObservation& o2 = observations[1];
    AddView<0>(o2.jr, o2.r, lin->rotation[0], o2.x_cam, lin->sphere, &blocks, &hcc, &gc);
    const WhitenedObservation& o3 = observations[2];
    AddView<1>(o3.jr, o3.r, lin->rotation[1], o3.x_cam, lin->sphere, &blocks, &hcc, &gc);
  }
  if constexpr (kRot == 3) {
    for (int j = 0; j < 2; ++j) {
      const Eigen::Matrix<double, 2, 3>& jc = lin->prior_jacobian[j];
      const int offset = j == 0 ? 0 : kSize2;
      hcc.template block<3, 3>(offset, offset).noalias() += jc.transpose() * jc;
      gc.template segment<3>(offset).noalias() += jc.transpose() * lin->prior_residual[j];
    }
  }
  lin->hcc = hcc.template selfadjointView<Eigen::Lower>();
  lin->gc = gc;
}

// A warm start (section 13.6): Build() was given points it kept, and the points move.
template <typename Residual, int kRot>
bool Engine<Residual, kRot>::WarmStart() const {
  const std::vector<char>& triangulated = adjuster_->triangulated();
  return !constant_points_ &&
         std::find(triangulated.begin(), triangulated.end(), 0) != triangulated.end();
}

// The warm start's first part (section 13.6): each point Build() triangulated is minimised over
// with the cameras fixed (MinimizeTripletCost, section 15.1), which never raises its cost. Returns
// the decrease of the cost.
template <typename Residual, int kRot>
double Engine<Residual, kRot>::PolishTriangulatedPoints() {
  const std::vector<char>& triangulated = adjuster_->triangulated();
  Eigen::Matrix3d rotation[3];
  Eigen::Vector3d center[3];
  rotation[0].setIdentity();
  center[0].setZero();
  for (int j = 0; j < 2; ++j) {
    rotation[j + 1] = Rotation(x_, j);
    center[j + 1] = Eigen::Map<const Eigen::Vector3d>(x_.center[j]);
  }
  double decrease = 0.0;
  TripletLinearization lin;
  for (std::size_t p = 0; p < storage_.points.size(); ++p) {
    if (!triangulated[p]) continue;
    const auto observe = [this, p](int k, const Eigen::Vector3d& x_cam, Eigen::Vector2d* r,
                                   Eigen::Matrix<double, 2, 3>* d_r_d_x) {
      return views_[k].Evaluate(p, x_cam, r, d_r_d_x);
    };
    if (!LinearizeTriplet(observe, loss_.function(), rotation, center, storage_.points[p], &lin))
      continue;
    const double start_cost = lin.cost;
    // On a failure the point keeps its last step, which did not raise its cost.
    MinimizeTripletCost(observe, loss_.function(), rotation, center, &storage_.points[p], &lin);
    decrease += start_cost - lin.cost;
  }
  return decrease;
}

// Solves (H + D^2) delta = -g by eliminating the points (section 13.4); fills the point steps.
template <typename Residual, int kRot>
bool Engine<Residual, kRot>::ComputeStep(double radius,
                                         PoseVector* pose_step,
                                         double* model_cost_change) {
  const Linearization& lin = storage_.current;
  PoseMatrix reduced = lin.hcc;
  for (int i = 0; i < kSize; ++i)
    reduced(i, i) += Damping(lin.hcc(i, i), pose_scale_squared_[i], radius);
  PoseVector rhs = -lin.gc;
  if (!constant_points_) {
    // The inverses in a loop of their own: the points' divisions (d_i, 1 / det) are independent
    // and overlap there, where each point's products had waited on its own.
    for (std::size_t p = 0; p < lin.points.size(); ++p) {
      const Eigen::Matrix3d& hpp = lin.points[p].hpp;
      Eigen::Matrix3d damped = hpp;
      for (int i = 0; i < 3; ++i) {
        damped(i, i) += Damping(hpp(i, i), storage_.point_scale_squared[p][i], radius);
      }
      storage_.point_inverse[p] = damped.inverse();
    }
    for (std::size_t p = 0; p < lin.points.size(); ++p) {
      const PointBlocks& blocks = lin.points[p];
      const Eigen::Matrix<double, kSize, 3> w = blocks.hpc.transpose() * storage_.point_inverse[p];
      SubtractLowerProduct(w, blocks.hpc, &reduced, std::make_integer_sequence<int, kSize>());
      rhs.noalias() += w * blocks.gp;
    }
  }
  const Eigen::LLT<PoseMatrix> llt(reduced);
  if (llt.info() != Eigen::Success) return false;
  *pose_step = llt.solve(rhs);
  if (!pose_step->allFinite()) return false;
  // Model decrease -(g . delta + delta^T H delta / 2) with the undamped H.
  double g_delta = lin.gc.dot(*pose_step);
  double h_delta = pose_step->dot(lin.hcc * *pose_step);
  if (!constant_points_) {
    for (std::size_t p = 0; p < lin.points.size(); ++p) {
      const PointBlocks& blocks = lin.points[p];
      const Eigen::Vector3d coupled = blocks.hpc * *pose_step;
      storage_.point_step[p].noalias() = -storage_.point_inverse[p] * (blocks.gp + coupled);
      if (!storage_.point_step[p].allFinite()) return false;
      const Eigen::Vector3d& dp = storage_.point_step[p];
      g_delta += blocks.gp.dot(dp);
      h_delta += dp.dot(blocks.hpp * dp) + 2.0 * dp.dot(coupled);
    }
  }
  *model_cost_change = -(g_delta + 0.5 * h_delta);
  return true;
}

template <typename Residual, int kRot>
void Engine<Residual, kRot>::Plus(const Pose& x, const PoseVector& delta, Pose* out) const {
  for (int j = 0; j < 2; ++j) {
    const int offset = j == 0 ? 0 : kSize2;
    if constexpr (kRot == 1) {
      out->yaw[j] = NormalizeAngle(x.yaw[j] + delta[offset]);
    } else {
      quaternion_manifold_.Plus(x.quaternion[j], delta.data() + offset, out->quaternion[j]);
    }
  }
  sphere_manifold_.Plus(x.center[0], delta.data() + kRot, out->center[0]);
  for (int i = 0; i < 3; ++i) out->center[1][i] = x.center[1][i] + delta[kSize2 + kRot + i];
}

template <typename Residual, int kRot>
double Engine<Residual, kRot>::AmbientNorm(const Pose& pose,
                                           const std::vector<Eigen::Vector3d>& points) const {
  double sum = 0.0;
  for (int j = 0; j < 2; ++j) {
    if constexpr (kRot == 1) {
      sum += pose.yaw[j] * pose.yaw[j];
    } else {
      sum += Eigen::Map<const Eigen::Vector4d>(pose.quaternion[j]).squaredNorm();
    }
    sum += Eigen::Map<const Eigen::Vector3d>(pose.center[j]).squaredNorm();
  }
  if (!constant_points_) {
    for (const Eigen::Vector3d& point : points) sum += point.squaredNorm();
  }
  return std::sqrt(sum);
}

// Ceres' |x - Plus(x, -g)|_inf at the current iterate.
template <typename Residual, int kRot>
double Engine<Residual, kRot>::GradientMaxNorm() const {
  Pose moved;
  Plus(x_, -storage_.current.gc, &moved);
  double norm = 0.0;
  for (int j = 0; j < 2; ++j) {
    for (int i = 0; i < 3; ++i) {
      norm = std::max(norm, std::abs(x_.center[j][i] - moved.center[j][i]));
    }
    if constexpr (kRot == 1) {
      norm = std::max(norm, std::abs(x_.yaw[j] - moved.yaw[j]));
    } else {
      for (int i = 0; i < 4; ++i) {
        norm = std::max(norm, std::abs(x_.quaternion[j][i] - moved.quaternion[j][i]));
      }
    }
  }
  if (!constant_points_) {
    for (const PointBlocks& blocks : storage_.current.points) {
      norm = std::max(norm, blocks.gp.cwiseAbs().maxCoeff());
    }
  }
  return norm;
}

template <typename Residual, int kRot>
void Engine<Residual, kRot>::Solve(ceres::Solver::Summary* summary) {
  const auto start = std::chrono::steady_clock::now();
  const ceres::Solver::Options& o = solver_options_;
  *summary = ceres::Solver::Summary();
  summary->minimizer_type = ceres::TRUST_REGION;
  summary->trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  summary->linear_solver_type_given = o.linear_solver_type;
  summary->linear_solver_type_used = ceres::DENSE_SCHUR;
  summary->num_threads_given = o.num_threads;
  summary->num_threads_used = 1;
  summary->termination_type = ceres::FAILURE;
  summary->num_successful_steps = 0;
  summary->num_unsuccessful_steps = 0;
  summary->iterations.reserve(o.max_num_iterations + 1);
  const int num_points = static_cast<int>(storage_.points.size());
  summary->num_parameter_blocks = 4 + num_points;
  summary->num_parameters = 2 * (kRot == 1 ? 1 : 4) + 6 + 3 * num_points;
  summary->num_effective_parameters = kSize + 3 * num_points;
  summary->num_residual_blocks = 3 * num_points + (kRot == 3 ? 2 : 0);
  summary->num_residuals = 2 * summary->num_residual_blocks;
  auto finish = [&](ceres::TerminationType type, const std::string& message) {
    summary->termination_type = type;
    summary->message = message;
    summary->final_cost = storage_.current.cost + storage_.current.fixed_cost;
    summary->fixed_cost = storage_.current.fixed_cost;
    if (type != ceres::FAILURE) WriteBack();
    summary->total_time_in_seconds = summary->minimizer_time_in_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };

  const bool warm_start = WarmStart();
  const double polish_decrease = warm_start ? PolishTriangulatedPoints() : 0.0;
  // Ceres' trust-region loop (section 13.5). Iteration 0 (TrustRegionMinimizer::IterationZero):
  // evaluate, fix the Jacobi scaling 1 / (1 + |column|) of every unknown.
  if (!Evaluate(x_, storage_.points, &storage_.current)) {
    summary->initial_cost = summary->final_cost = 0.0;
    summary->message = "Residual and Jacobian evaluation failed.";
    return;
  }
  // The cost at the adjuster's parameters, before the warm start's point steps.
  summary->initial_cost = storage_.current.cost + storage_.current.fixed_cost + polish_decrease;
  for (int i = 0; i < kSize; ++i) {
    pose_scale_squared_[i] = std::pow(1.0 + std::sqrt(storage_.current.hcc(i, i)), -2);
  }
  for (int p = 0; p < num_points; ++p) {
    storage_.point_scale_squared[p] =
        (1.0 + storage_.current.points[p].hpp.diagonal().array().sqrt())
            .square()
            .inverse()
            .matrix();
  }
  double x_norm = AmbientNorm(x_, storage_.points);
  double gradient_max_norm = GradientMaxNorm();
  ceres::IterationSummary iteration;
  iteration.iteration = 0;
  iteration.cost = storage_.current.cost + storage_.current.fixed_cost;
  iteration.gradient_max_norm = gradient_max_norm;
  iteration.step_is_valid = iteration.step_is_successful = true;
  double radius = o.initial_trust_region_radius;
  double decrease_factor = 2.0;
  int num_consecutive_invalid_steps = 0;
  char message[160];
  for (;;) {
    // Ceres' FinalizeIterationAndCheckIfMinimizerCanContinue.
    if (iteration.step_is_successful) {
      ++summary->num_successful_steps;
    } else {
      ++summary->num_unsuccessful_steps;
    }
    iteration.trust_region_radius = radius;
    summary->iterations.push_back(iteration);
    if (options_.stop_requested && options_.stop_requested()) {
      finish(ceres::USER_FAILURE, "stopped on request");
      return;
    }
    if (iteration.iteration >= o.max_num_iterations) {
      std::snprintf(message, sizeof(message),
                    "Maximum number of iterations reached. Number of iterations: %d.",
                    iteration.iteration);
      finish(ceres::NO_CONVERGENCE, message);
      return;
    }
    if (iteration.step_is_successful && gradient_max_norm <= o.gradient_tolerance) {
      std::snprintf(message, sizeof(message),
                    "Gradient tolerance reached. Gradient max norm: %e <= %e", gradient_max_norm,
                    o.gradient_tolerance);
      finish(ceres::CONVERGENCE, message);
      return;
    }
    if (radius < o.min_trust_region_radius) {
      std::snprintf(message, sizeof(message),
                    "Minimum trust region radius reached. Trust region radius: %e <= %e", radius,
                    o.min_trust_region_radius);
      finish(ceres::CONVERGENCE, message);
      return;
    }
    const int number = iteration.iteration + 1;
    iteration = ceres::IterationSummary();
    iteration.iteration = number;
    iteration.cost = storage_.current.cost + storage_.current.fixed_cost;
    iteration.gradient_max_norm = gradient_max_norm;

    PoseVector pose_step;
    double model_cost_change = 0.0;
    iteration.step_is_valid =
        ComputeStep(radius, &pose_step, &model_cost_change) && model_cost_change > 0.0;
    if (!iteration.step_is_valid) {
      if (++num_consecutive_invalid_steps >= o.max_num_consecutive_invalid_steps) {
        std::snprintf(message, sizeof(message),
                      "Number of consecutive invalid steps more than "
                      "Solver::Options::max_num_consecutive_invalid_steps: %d",
                      o.max_num_consecutive_invalid_steps);
        finish(ceres::FAILURE, message);
        return;
      }
      radius /= decrease_factor;
      decrease_factor *= 2.0;
      continue;
    }
    num_consecutive_invalid_steps = 0;

    // The candidate's cost only: it is linearised if the step is accepted (Ceres' order).
    Plus(x_, pose_step, &candidate_x_);
    double step_norm_squared = 0.0;
    for (int j = 0; j < 2; ++j) {
      for (int i = 0; i < 3; ++i) {
        step_norm_squared += std::pow(x_.center[j][i] - candidate_x_.center[j][i], 2);
      }
      if constexpr (kRot == 1) {
        step_norm_squared += std::pow(x_.yaw[j] - candidate_x_.yaw[j], 2);
      } else {
        for (int i = 0; i < 4; ++i) {
          step_norm_squared += std::pow(x_.quaternion[j][i] - candidate_x_.quaternion[j][i], 2);
        }
      }
    }
    for (int p = 0; p < num_points; ++p) {
      if (constant_points_) {
        storage_.candidate_points[p] = storage_.points[p];
      } else {
        storage_.candidate_points[p] = storage_.points[p] + storage_.point_step[p];
        step_norm_squared += (storage_.candidate_points[p] - storage_.points[p]).squaredNorm();
      }
    }
    const double candidate_cost =
        EvaluateResiduals(candidate_x_, storage_.candidate_points, &storage_.candidate)
            ? storage_.candidate.cost
            : std::numeric_limits<double>::max();
    iteration.step_norm = std::sqrt(step_norm_squared);
    const double step_tolerance = o.parameter_tolerance * (x_norm + o.parameter_tolerance);
    if (iteration.step_norm <= step_tolerance) {
      std::snprintf(message, sizeof(message),
                    "Parameter tolerance reached. Relative step_norm: %e <= %e.",
                    iteration.step_norm / (x_norm + o.parameter_tolerance), o.parameter_tolerance);
      finish(ceres::CONVERGENCE, message);
      return;
    }
    iteration.cost_change = storage_.current.cost - candidate_cost;
    if (std::abs(iteration.cost_change) <= o.function_tolerance * storage_.current.cost) {
      // On a warm start, unlike Ceres, which stops at the iterate, keep the candidate if it would
      // be accepted: it is evaluated and lower (section 13.6).
      if (warm_start && iteration.cost_change > 0.0 &&
          iteration.cost_change / model_cost_change > o.min_relative_decrease) {
        std::swap(x_, candidate_x_);
        storage_.points.swap(storage_.candidate_points);
        std::swap(storage_.current, storage_.candidate);
      }
      std::snprintf(message, sizeof(message),
                    "Function tolerance reached. |cost_change|/cost: %e <= %e",
                    std::abs(iteration.cost_change) / storage_.current.cost, o.function_tolerance);
      finish(ceres::CONVERGENCE, message);
      return;
    }
    iteration.relative_decrease = iteration.cost_change / model_cost_change;
    iteration.step_is_successful = iteration.relative_decrease > o.min_relative_decrease;
    if (iteration.step_is_successful) {
      // Ceres' LevenbergMarquardtStrategy::StepAccepted.
      std::swap(x_, candidate_x_);
      storage_.points.swap(storage_.candidate_points);
      std::swap(storage_.current, storage_.candidate);
      Linearize(&storage_.current);
      x_norm = AmbientNorm(x_, storage_.points);
      gradient_max_norm = GradientMaxNorm();
      iteration.cost = storage_.current.cost + storage_.current.fixed_cost;
      iteration.gradient_max_norm = gradient_max_norm;
      radius = std::min(
          o.max_trust_region_radius,
          radius / std::max(1.0 / 3.0, 1.0 - std::pow(2.0 * iteration.relative_decrease - 1.0, 3)));
      decrease_factor = 2.0;
    } else {
      // StepRejected.
      radius /= decrease_factor;
      decrease_factor *= 2.0;
    }
  }
}

template <typename Residual, int kRot>
bool Engine<Residual, kRot>::Information(ThreeViewInformation* information) {
  if (!Evaluate(x_, storage_.points, &storage_.current)) return false;
  // Internal order [r2, u2, r3, C3] to the layout's [r2, r3, u2, C3].
  int to_layout[kSize];
  for (int i = 0; i < kSize; ++i) {
    if (i < kRot) {
      to_layout[i] = i;
    } else if (i < kSize2) {
      to_layout[i] = 2 * kRot + (i - kRot);
    } else if (i < kSize2 + kRot) {
      to_layout[i] = kRot + (i - kSize2);
    } else {
      to_layout[i] = i;
    }
  }
  information->pose.resize(kSize, kSize);
  for (int a = 0; a < kSize; ++a) {
    for (int b = 0; b < kSize; ++b) {
      information->pose(to_layout[a], to_layout[b]) = storage_.current.hcc(a, b);
    }
  }
  const std::size_t num_free = constant_points_ ? 0 : storage_.points.size();
  information->point.resize(num_free);
  information->coupling.resize(num_free);
  for (std::size_t p = 0; p < num_free; ++p) {
    information->point[p] = storage_.current.points[p].hpp;
    information->coupling[p].setZero();
    for (int a = 0; a < kSize; ++a) {
      information->coupling[p].row(to_layout[a]) =
          storage_.current.points[p].hpc.col(a).transpose();
    }
  }
  return true;
}

// Runs f on the engine of the adjuster's residual type and rotation model.
template <typename F>
void WithEngine(ThreeViewBundleAdjuster* adjuster, F&& f) {
  const bool bearings = adjuster->observations().HasBearings();
  const bool yaw_only = adjuster->options().rotation_model == Options::RotationModel::kYawOnly;
  if (bearings && yaw_only) {
    Engine<BearingResidual, 1> engine(adjuster);
    f(engine);
  } else if (bearings) {
    Engine<BearingResidual, 3> engine(adjuster);
    f(engine);
  } else if (yaw_only) {
    Engine<PixelResidual, 1> engine(adjuster);
    f(engine);
  } else {
    Engine<PixelResidual, 3> engine(adjuster);
    f(engine);
  }
}

}  // namespace

void SolveThreeViewLm(ThreeViewBundleAdjuster* adjuster, ceres::Solver::Summary* summary) {
  WithEngine(adjuster, [summary](auto& engine) { engine.Solve(summary); });
}

bool EvaluateThreeViewInformation(ThreeViewBundleAdjuster* adjuster,
                                  ThreeViewInformation* information) {
  bool ok = false;
  WithEngine(adjuster, [&](auto& engine) { ok = engine.Information(information); });
  return ok;
}

}  // namespace internal
}  // namespace trigrav
