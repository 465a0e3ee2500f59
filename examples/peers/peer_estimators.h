#ifndef TRIGRAV_EXAMPLES_PEERS_PEER_ESTIMATORS_H_
#define TRIGRAV_EXAMPLES_PEERS_PEER_ESTIMATORS_H_

// trigrav side by side with the libraries a user with gravity would otherwise call: OpenCV's and
// OpenGV's five-point RANSAC on the view pairs (1,2) and (1,3). Every estimator has one shape, so
// that an evaluation (peer_comparison, kitti_triplets --peers, paper_experiments --peers) runs them
// all alike: pixels and intrinsics in, one three-view estimate out. The peers are optional at build
// time; this header and the trigrav entries do not depend on them.

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "trigrav/initializers/camera_pose.h"
#include "trigrav/initializers/robust_three_view.h"
#include "trigrav/initializers/three_view_observations.h"

namespace trigrav::peers {

// What every estimator returns: a robust three-view estimate (success; message: why not, or a note
// when the relative scale is unknown; pose in the original camera frames with
// |cam2_from_cam1.Center()| = 1; inliers per triplet, ransac.num_inliers of them set) and what an
// evaluation adds. For a pairwise peer the inliers are the triplets that are inliers of both pairs
// and ransac holds only num_inliers (the peers report no iteration counts); for a refined trigrav
// estimate they are the refinement's inliers, the other statistics those of its RANSAC.
struct EstimatorResult : RobustThreeViewEstimate {
  // False when a pairwise estimate could not fix the relative scale (camera 3 at |centre| = 1).
  bool relative_scale_known = true;
  double time_s = 0.0;  // wall time of the whole estimate, measured around the call
};

// Robust three-view estimate from pixel triplets with outliers. threshold_px is the inlier
// threshold in pixels; each entry states in `description` what the threshold means for it.
using Estimator =
    std::function<EstimatorResult(const ThreeViewObservations& observations, double threshold_px)>;

struct NamedEstimator {
  // For table rows: trigrav's InitialSolverName ("3pt", ...) or the peer's name ("opencv-ransac").
  std::string name;
  // "raw" (the robust estimate as returned) or "yaw-only" (trigrav's, refined by
  // InitializeAndRefine with the yaw-only rotation model).
  std::string stage;
  std::string description;  // API, method, threshold meaning, iterations and confidence
  Estimator estimate;
};

// trigrav's RANSAC estimates (EstimateThreeViewPoseRobust, default RansacOptions apart from the
// threshold), one per method of kInitialSolvers, stage "raw".
std::vector<NamedEstimator> TrigravRobustEstimators();
// The same, each refined by InitializeAndRefine (yaw-only bundle adjustment), stage "yaw-only".
std::vector<NamedEstimator> TrigravRefinedEstimators();
// The peers found at build time (empty if none): opencv-ransac, opencv-usac-magsac,
// opencv-usac-default, opengv-ransac-stewenius, opengv-ransac-nister, opengv-ransac-nister+nl.
std::vector<NamedEstimator> PeerEstimators();

// Keeps every peer on the calling thread (OpenCV's thread pool off), so that per-call times are
// single-threaded and callers can run estimates on several threads of their own.
void RunPeersSingleThreaded();

// A noise-free problem for the minimal solvers: at least 5 triplets of rays K^-1 [u v 1]^T in the
// original camera frames, each camera's gravity and the true pose.
struct MinimalProblem {
  std::vector<Eigen::Vector3d> x1, x2, x3;
  Eigen::Vector3d gravity_in_cam1, gravity_in_cam2, gravity_in_cam3;
  ThreeViewPose ground_truth;
};

// `count` noise-free problems of 5 triplets from SyntheticSceneOptions' defaults (f = 500 px, exact
// gravity), drawn one after the other from one generator seeded with `seed`.
std::vector<MinimalProblem> MakeMinimalProblems(int count, std::uint64_t seed);

// A minimal solver prepared for a list of problems: solve(i) runs one call on problem i and returns
// the number of solutions; truth_found(i) runs it again and says whether the true pose is among
// them (1e-6 deg; for essential matrices, E within 1e-8 of the true one up to sign and scale).
struct PreparedMinimalSolver {
  std::function<int(std::size_t)> solve;
  std::function<bool(std::size_t)> truth_found;
};

struct NamedMinimalSolver {
  std::string name;
  std::string description;  // what one call computes
  // Converts the problems to the solver's input once (outside any timing loop). The problems must
  // outlive the returned functions.
  std::function<PreparedMinimalSolver(const std::vector<MinimalProblem>&)> prepare;
};

// trigrav's minimal solvers of at most five triplets, named by their method: "3pt"
// (SolveTrifocal3pt), "4pt" (SolveTrifocal4pt), with each camera's gravity as a pipeline calls
// them, and "5pt" (SolveEssential5pt on pair (1,2)).
std::vector<NamedMinimalSolver> TrigravMinimalSolvers();
// OpenGV's fivept_stewenius and fivept_nister on pair (1,2), if OpenGV was found. OpenCV has no
// public minimal-solver call, so it has no entry.
std::vector<NamedMinimalSolver> PeerMinimalSolvers();

}  // namespace trigrav::peers

#endif  // TRIGRAV_EXAMPLES_PEERS_PEER_ESTIMATORS_H_
