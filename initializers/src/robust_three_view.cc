#include "trigrav/initializers/robust_three_view.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <Eigen/SVD>

#include "trigrav/initializers/essential_5pt.h"
#include "trigrav/initializers/essential_8pt.h"
#include "trigrav/initializers/gravity.h"
#include "trigrav/initializers/three_view_error.h"
#include "trigrav/initializers/trifocal_3pt.h"
#include "trigrav/initializers/trifocal_4pt.h"
#include "trigrav/initializers/trifocal_linear.h"
#include "trigrav/initializers/two_view_to_three_view.h"

namespace trigrav {
namespace {

using Rays = std::vector<Eigen::Vector3d>;
using ViewRays = std::array<Rays, 3>;

// What every method's estimator shares: the rays of each view, raw (K^-1 pixel) and gravity-aligned,
// and the common inlier error.
struct TripletData {
  TripletData(const ThreeViewObservations& observations, double max_tilt_correction_deg)
      : min_cos_tilt_correction(std::cos(max_tilt_correction_deg * M_PI / 180.0)),
        error(observations) {
    for (int k = 0; k < 3; ++k) {
      alignment[k] = GravityAlignmentFromGravity(observations.gravity_in_cam[k]);
      raw[k].reserve(observations.size());
      for (const Eigen::Vector2d& pixel : observations.pixels[k]) {
        raw[k].push_back(observations.cameras[k].Ray(pixel));
      }
      aligned[k] = AlignRays(alignment[k], raw[k]);
    }
  }
  ViewRays raw, aligned;
  std::array<Eigen::Matrix3d, 3> alignment;
  double min_cos_tilt_correction;  // cos(RobustThreeViewOptions::max_tilt_correction_deg)
  ThreeViewReprojectionError error;
};

// Reused storage of the solvers' outputs, so the RANSAC loop does not allocate once warm.
struct Workspace {
  std::vector<ThreeViewPose> three_view;
  std::vector<CameraPose> pair12, pair13;
  ViewRays corrected;  // tilt-corrected aligned rays (TiltCorrectingRefinement)
};

// Three-view models of a two-view method (math note section 7): CombineTwoViewPairs
// (two_view_to_three_view.h) rescales camera 3 by the view-1 depth ratio kappa of the two pairs.

// Method policies. Minimal() and Refine() append three-view poses in the original frames from the
// selected triplets' rays (aligned ones if kAligned); Refine() gets all inliers of a model.
template <int (*kSolveAligned)(const Rays&, const Rays&, const Rays&, std::vector<ThreeViewPose>*)>
void SolveGravityAware(const TripletData& data, const ViewRays& aligned, Workspace* work,
                       std::vector<ThreeViewPose>* poses) {
  kSolveAligned(aligned[0], aligned[1], aligned[2], &work->three_view);
  for (const ThreeViewPose& pose : work->three_view) {
    poses->push_back(
        UnalignThreeViewPose(pose, data.alignment[0], data.alignment[1], data.alignment[2]));
  }
}

template <int (*kSolvePair)(const Rays&, const Rays&, std::vector<CameraPose>*)>
void SolveTwoViewPairs(const TripletData&, const ViewRays& raw, Workspace* work,
                       std::vector<ThreeViewPose>* poses) {
  kSolvePair(raw[0], raw[1], &work->pair12);
  kSolvePair(raw[0], raw[2], &work->pair13);
  CombineTwoViewPairs(raw[0], raw[1], raw[2], work->pair12, work->pair13, poses);
}

void SolveLinear(const TripletData&, const ViewRays& raw, Workspace* work,
                 std::vector<ThreeViewPose>* poses) {
  SolveTrifocalLinear(raw[0], raw[1], raw[2], &work->three_view);
  poses->insert(poses->end(), work->three_view.begin(), work->three_view.end());
}

// The aligned-frame overloads, as plain function pointers.
int Trifocal3pt(const Rays& x1, const Rays& x2, const Rays& x3, std::vector<ThreeViewPose>* out) {
  return SolveTrifocal3pt(x1, x2, x3, out);
}
int Trifocal3ptSextic(const Rays& x1, const Rays& x2, const Rays& x3,
                      std::vector<ThreeViewPose>* out) {
  return SolveTrifocal3ptSextic(x1, x2, x3, out);
}
int Trifocal4pt(const Rays& x1, const Rays& x2, const Rays& x3, std::vector<ThreeViewPose>* out) {
  return SolveTrifocal4pt(x1, x2, x3, out);
}

using SolveFunction = void (*)(const TripletData&, const ViewRays&, Workspace*,
                               std::vector<ThreeViewPose>*);

template <int kSize, bool kAlignedRays, SolveFunction kMinimal, int kMinRefine, SolveFunction kRefine>
struct Method {
  static constexpr int kSampleSize = kSize;
  static constexpr bool kAligned = kAlignedRays;
  static constexpr int kMinTripletsToRefine = kMinRefine;
  static void Minimal(const TripletData& d, const ViewRays& r, Workspace* w,
                      std::vector<ThreeViewPose>* p) {
    kMinimal(d, r, w, p);
  }
  static void Refine(const TripletData& d, const ViewRays& r, Workspace* w,
                     std::vector<ThreeViewPose>* p) {
    kRefine(d, r, w, p);
  }
};

using Method3pt = Method<3, true, SolveGravityAware<Trifocal3pt>, 4, SolveGravityAware<Trifocal4pt>>;
using Method3ptSextic =
    Method<3, true, SolveGravityAware<Trifocal3ptSextic>, 4, SolveGravityAware<Trifocal4pt>>;
using Method4pt = Method<4, true, SolveGravityAware<Trifocal4pt>, 4, SolveGravityAware<Trifocal4pt>>;
using Method7ptLinear = Method<7, false, SolveLinear, 7, SolveLinear>;
using Method5pt =
    Method<5, false, SolveTwoViewPairs<SolveEssential5pt>, 8, SolveTwoViewPairs<SolveEssential8pt>>;
using Method8pt =
    Method<8, false, SolveTwoViewPairs<SolveEssential8pt>, 8, SolveTwoViewPairs<SolveEssential8pt>>;

// Local optimisation of a gravity-aware method that may correct the given relative tilt
// (RobustThreeViewOptions::max_tilt_correction_deg): the linear trifocal tensor of the inliers'
// aligned rays gives camera 1's vertical as seen by cameras 2 and 3, R_k1 e_y; if it is within the
// bound of e_y, view k's aligned rays are turned by the tilt S_k taking R_k1 e_y to e_y. The
// upright 4-point solver then re-estimates yaw and translation on the corrected rays, and the pose
// is unaligned with the corrected alignments S_k A_k. The tensor, whose 26 unknowns make it noisy,
// contributes only the tilt (2 numbers per camera); yaw and translation come from the 4-point
// solver, as with exact gravity. Below the tensor's 7 triplets, or when it has no solution, the
// refinement is the upright one of M. (trigrav's own design; the paper assumes exact gravity.)
template <typename M>
struct TiltCorrectingRefinement : M {
  static_assert(M::kAligned, "only gravity-aware methods have a tilt to correct");
  static constexpr std::size_t kMinTripletsForTensor = 7;  // SolveTrifocalLinear's minimum
  static void Refine(const TripletData& data, const ViewRays& aligned, Workspace* work,
                     std::vector<ThreeViewPose>* poses) {
    std::array<Eigen::Matrix3d, 3> alignment = data.alignment;
    std::array<const Rays*, 3> rays = {&aligned[0], &aligned[1], &aligned[2]};
    work->three_view.clear();
    if (aligned[0].size() >= kMinTripletsForTensor) {
      SolveTrifocalLinear(aligned[0], aligned[1], aligned[2], &work->three_view);
    }
    if (!work->three_view.empty()) {
      const ThreeViewPose& tensor = work->three_view.front();
      const std::array<const Eigen::Matrix3d*, 2> rotation = {&tensor.cam2_from_cam1.R,
                                                              &tensor.cam3_from_cam1.R};
      for (int k = 1; k < 3; ++k) {
        const Eigen::Vector3d vertical = *rotation[k - 1] * Eigen::Vector3d::UnitY();
        if (!(vertical.y() >= data.min_cos_tilt_correction)) continue;  // beyond the bound
        const Eigen::Matrix3d tilt =
            Eigen::Quaterniond::FromTwoVectors(vertical, Eigen::Vector3d::UnitY())
                .toRotationMatrix();
        work->corrected[k].resize(aligned[k].size());
        for (std::size_t i = 0; i < aligned[k].size(); ++i) {
          work->corrected[k][i] = tilt * aligned[k][i];
        }
        rays[k] = &work->corrected[k];
        alignment[k] = tilt * alignment[k];
      }
    }
    SolveTrifocal4pt(*rays[0], *rays[1], *rays[2], &work->three_view);
    for (const ThreeViewPose& pose : work->three_view) {
      poses->push_back(UnalignThreeViewPose(pose, alignment[0], alignment[1], alignment[2]));
    }
  }
};

struct ScoredPose {
  ThreeViewPose pose;
  ThreeViewReprojectionError::PreparedPose prepared;
};

// The RANSAC estimator concept of ransac.h for one method.
template <typename M>
class Estimator {
 public:
  using Model = ScoredPose;
  static constexpr int kSampleSize = M::kSampleSize;

  explicit Estimator(const TripletData& data) : data_(data) {}

  std::size_t num_data() const { return data_.error.size(); }

  void generate_models(const std::array<int, kSampleSize>& sample, std::vector<Model>* models) const {
    Solve(sample, &M::Minimal);
    for (const ThreeViewPose& pose : poses_) {
      if (pose.IsFinite()) models->push_back({pose, ThreeViewReprojectionError::Prepare(pose)});
    }
  }

  double error(const Model& model, std::size_t i) const { return data_.error(model.prepared, i); }

  bool refine_model(const std::vector<int>& inliers, Model* model) const {
    if (static_cast<int>(inliers.size()) < M::kMinTripletsToRefine) return false;
    Solve(inliers, &M::Refine);
    for (const ThreeViewPose& pose : poses_) {
      if (pose.IsFinite()) {
        *model = {pose, ThreeViewReprojectionError::Prepare(pose)};
        return true;
      }
    }
    return false;
  }

 private:
  template <typename Indices>
  void Solve(const Indices& indices, SolveFunction solve) const {
    const ViewRays& source = M::kAligned ? data_.aligned : data_.raw;
    for (int k = 0; k < 3; ++k) {
      selected_[k].clear();
      for (const int i : indices) selected_[k].push_back(source[k][i]);
    }
    poses_.clear();
    solve(data_, selected_, &work_, &poses_);
  }

  const TripletData& data_;
  // Scratch storage reused across samples; an Estimator serves one RANSAC call on one thread.
  mutable ViewRays selected_;
  mutable Workspace work_;
  mutable std::vector<ThreeViewPose> poses_;
};

template <typename M>
RobustThreeViewEstimate Run(const TripletData& data, const RansacOptions& options) {
  const RansacReport<ScoredPose> report = Ransac(Estimator<M>(data), options);
  RobustThreeViewEstimate estimate;
  estimate.success = report.success;
  estimate.message = report.message;
  estimate.ransac = report.statistics;
  if (report.success) {
    estimate.pose = report.model.pose;
    estimate.inliers = report.inlier_mask;
  }
  return estimate;
}

// Share of the inliers that a camera 2 without baseline explains within `threshold` pixels: the
// rotation R maximising sum_n x2_n . R x1_n over the inliers' rays (Wahba's problem, solved by the
// SVD of sum_n x2_n x1_n^T; rays K^-1 [u v 1]^T weighted by their lengths), each inlier counted if
// the direction R x1_n lands within the threshold of its pixel in view 2.
double ShareExplainedByRotation(const ThreeViewObservations& observations, const TripletData& data,
                                const std::vector<char>& inliers, double threshold) {
  Eigen::Matrix3d correlation = Eigen::Matrix3d::Zero();
  int num_inliers = 0;
  for (std::size_t n = 0; n < inliers.size(); ++n) {
    if (!inliers[n]) continue;
    correlation += data.raw[1][n] * data.raw[0][n].transpose();
    ++num_inliers;
  }
  if (num_inliers == 0) return 0.0;
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(correlation,
                                              Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d R = svd.matrixU() * svd.matrixV().transpose();
  if (R.determinant() < 0.0) {
    R = svd.matrixU() * Eigen::Vector3d(1.0, 1.0, -1.0).asDiagonal() * svd.matrixV().transpose();
  }
  int explained = 0;
  for (std::size_t n = 0; n < inliers.size(); ++n) {
    if (!inliers[n]) continue;
    const Eigen::Vector3d direction = R * data.raw[0][n];
    if (!(direction.z() > 0.0)) continue;
    explained +=
        (observations.cameras[1].Project(direction) - observations.pixels[1][n]).norm() <= threshold;
  }
  return static_cast<double>(explained) / num_inliers;
}

// Like COLMAP's two-view classification, which calls a pair planar or panoramic when a homography
// explains more than 80 % of the inliers of the essential matrix (max_H_inlier_ratio = 0.8).
constexpr double kMaxShareExplainedByRotation = 0.8;

// Turns a successful estimate into a failure with the reason if its inliers show no parallax
// between views 1 and 2 (header), whatever the method.
void RejectWithoutParallax(const ThreeViewObservations& observations, const TripletData& data,
                           double max_error, RobustThreeViewEstimate* estimate) {
  const double share = ShareExplainedByRotation(observations, data, estimate->inliers, max_error);
  if (!(share > kMaxShareExplainedByRotation)) return;
  estimate->message =
      "no parallax between views 1 and 2: a rotation of camera 2 without baseline explains " +
      std::to_string(static_cast<int>(std::round(100.0 * share))) + " % of the " +
      std::to_string(estimate->ransac.num_inliers) +
      " inliers, so camera 2's centre (the scale |C2| = 1) is not observable (zero baseline, pure "
      "rotation, points at infinity)";
  estimate->success = false;
  estimate->pose = ThreeViewPose();
  estimate->inliers.clear();
  estimate->ransac.num_inliers = 0;
}

using RunFunction = RobustThreeViewEstimate (*)(const TripletData&, const RansacOptions&);

struct SolverInfo {
  InitialSolver solver;
  const char* name;
  int sample_size;
  bool uses_gravity;
  RunFunction run;
  RunFunction run_tilt_correcting;  // == run for the methods that do not use gravity
};

template <typename M>
constexpr SolverInfo MakeSolverInfo(InitialSolver solver, const char* name) {
  if constexpr (M::kAligned) {
    return {solver, name, M::kSampleSize, true, &Run<M>, &Run<TiltCorrectingRefinement<M>>};
  } else {
    return {solver, name, M::kSampleSize, false, &Run<M>, &Run<M>};
  }
}

constexpr std::array<SolverInfo, 6> kSolvers = {{
    MakeSolverInfo<Method3pt>(InitialSolver::kTrifocal3pt, "3pt"),
    MakeSolverInfo<Method3ptSextic>(InitialSolver::kTrifocal3ptSextic, "3pt-sextic"),
    MakeSolverInfo<Method4pt>(InitialSolver::kTrifocal4pt, "4pt"),
    MakeSolverInfo<Method7ptLinear>(InitialSolver::kTrifocalLinear, "7pt-linear"),
    MakeSolverInfo<Method5pt>(InitialSolver::kEssential5pt, "5pt"),
    MakeSolverInfo<Method8pt>(InitialSolver::kEssential8pt, "8pt"),
}};

constexpr bool TableFollowsInitialSolverList() {
  for (std::size_t i = 0; i < kSolvers.size(); ++i) {
    if (kSolvers[i].solver != kInitialSolvers[i]) return false;
  }
  return kSolvers.size() == kInitialSolvers.size();
}
static_assert(TableFollowsInitialSolverList(), "kSolvers must follow kInitialSolvers");

const SolverInfo& Info(InitialSolver solver) {
  for (const SolverInfo& info : kSolvers) {
    if (info.solver == solver) return info;
  }
  throw std::invalid_argument("trigrav: unknown InitialSolver value");
}

}  // namespace

const char* InitialSolverName(InitialSolver solver) { return Info(solver).name; }

int MinimalSampleSize(InitialSolver solver) { return Info(solver).sample_size; }

bool UsesGravity(InitialSolver solver) { return Info(solver).uses_gravity; }

std::string InitialSolverNames() {
  std::string names;
  for (const SolverInfo& info : kSolvers) names += (names.empty() ? "" : ", ") + std::string(info.name);
  return names;
}

void RobustThreeViewOptions::Check() const {
  Info(solver);  // throws for a value outside the enum
  ransac.Check();
  if (!(max_tilt_correction_deg == kTiltCorrectionFromGravitySigma ||
        (max_tilt_correction_deg >= 0.0 && max_tilt_correction_deg < 90.0))) {
    throw std::invalid_argument(
        "trigrav: RobustThreeViewOptions: max_tilt_correction_deg must be in [0, 90) or "
        "kTiltCorrectionFromGravitySigma");
  }
}

bool ParseInitialSolver(const std::string& name, InitialSolver* solver) {
  for (const SolverInfo& info : kSolvers) {
    if (name == info.name) {
      *solver = info.solver;
      return true;
    }
  }
  return false;
}

RobustThreeViewEstimate EstimateThreeViewPoseRobust(const ThreeViewObservations& observations,
                                                    const RobustThreeViewOptions& options) {
  options.Check();
  // Without a gravity sigma the automatic bound is 0 (header).
  const double max_tilt_correction_deg = std::max(options.max_tilt_correction_deg, 0.0);
  // Its ThreeViewReprojectionError checks the observations.
  const TripletData data(observations, max_tilt_correction_deg);
  const SolverInfo& info = Info(options.solver);
  const RunFunction run = max_tilt_correction_deg > 0.0 ? info.run_tilt_correcting : info.run;
  RobustThreeViewEstimate estimate = run(data, options.ransac);
  if (estimate.success) RejectWithoutParallax(observations, data, options.ransac.max_error, &estimate);
  return estimate;
}

}  // namespace trigrav
