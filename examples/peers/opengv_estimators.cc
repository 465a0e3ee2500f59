// OpenGV peers: sac::Ransac over CentralRelativePoseSacProblem (five-point, Stewenius or Nister) on
// the pairs (1,2) and (1,3), and the minimal five-point solvers alone.
//
// OpenGV's relative pose [R12 | t12] is camera 2's pose in camera 1: p_1 = R12 p_2 + t12 (OpenGV
// documentation, "relative pose"), so x_2 = R12^T x_1 - R12^T t12 and camera 2's centre is t12.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <opengv/relative_pose/CentralRelativeAdapter.hpp>
#include <opengv/relative_pose/methods.hpp>
#include <opengv/sac/Ransac.hpp>
#include <opengv/sac_problems/relative_pose/CentralRelativePoseSacProblem.hpp>
#include <string>
#include <vector>

#include "pairwise_estimator.h"
#include "peer_backends.h"

namespace trigrav::peers {
namespace {

using SacProblem = opengv::sac_problems::relative_pose::CentralRelativePoseSacProblem;

// Unit bearing vectors of one view's pixels.
opengv::bearingVectors_t Bearings(const ThreeViewObservations& observations, int view) {
  opengv::bearingVectors_t bearings;
  bearings.reserve(observations.size());
  for (std::size_t n = 0; n < observations.size(); ++n) {
    bearings.push_back(observations.Ray(view, n).normalized());
  }
  return bearings;
}

// OpenGV's inlier score of a pair is (1 - cos a_1) + (1 - cos a_2), a_k the angle between view k's
// bearing and the reprojected triangulated point. The threshold is converted from pixels as
// OpenGV's documentation does, 1 - cos(atan(px / f)): about a_1^2 + a_2^2 <= (px / f)^2.
PairEstimator OpenGvPair(SacProblem::Algorithm algorithm, bool refine) {
  return [algorithm, refine](const ThreeViewObservations& observations, int view,
                             double threshold_px) {
    const Camera& camera1 = observations.cameras[0];
    const Camera& camera2 = observations.cameras[view];
    const opengv::bearingVectors_t bearings1 = Bearings(observations, 0);
    const opengv::bearingVectors_t bearings2 = Bearings(observations, view);
    const double focal_px =
        (camera1.FocalX() + camera1.FocalY() + camera2.FocalX() + camera2.FocalY()) / 4.0;
    opengv::relative_pose::CentralRelativeAdapter adapter(bearings1, bearings2);
    opengv::sac::Ransac<SacProblem> ransac;
    ransac.sac_model_ = std::make_shared<SacProblem>(adapter, algorithm, /*randomSeed=*/false);
    ransac.threshold_ = 1.0 - std::cos(std::atan(threshold_px / focal_px));
    ransac.max_iterations_ = kPeerMaxIterations;
    ransac.probability_ = kPeerConfidence;
    PairEstimate pair;
    if (!ransac.computeModel()) {
      pair.message = "opengv::sac::Ransac found no model";
      return pair;
    }
    opengv::transformation_t cam2_in_cam1 = ransac.model_coefficients_;
    if (refine) {
      ransac.sac_model_->optimizeModelCoefficients(ransac.inliers_, ransac.model_coefficients_,
                                                   cam2_in_cam1);
    }
    CameraPose cam1_from_cam2;  // [R12 | t12]
    cam1_from_cam2.R = cam2_in_cam1.block<3, 3>(0, 0);
    cam1_from_cam2.t = cam2_in_cam1.col(3);
    pair.success = true;
    pair.cam_from_cam1 = cam1_from_cam2.Inverse();
    pair.inliers.assign(observations.size(), 0);
    for (const int i : ransac.inliers_) pair.inliers[i] = 1;
    return pair;
  };
}

std::string RansacNote() {
  char note[512];
  std::snprintf(note, sizeof(note),
                "inlier iff (1 - cos a_1) + (1 - cos a_2) <= 1 - cos(atan(threshold / f)) (a_k: "
                "angle between bearing and reprojection in view k; OpenGV's documented pixel "
                "conversion); samples of 8 (5 + 3 for disambiguation); probability %g, "
                "max_iterations %d, fixed seed; pairs combined with trigrav::CombineTwoViewPairs "
                "on their common inliers",
                kPeerConfidence, kPeerMaxIterations);
  return note;
}

// OpenGV's essential matrix for camera 2 at [R12 | t12] in camera 1: E = [t12]x R12, so that
// f_1^T E f_2 = 0. With x_2 = R x_1 + t (R12 = R^T, t12 = -R^T t) that is ([t]x R)^T; checked
// against fivept_stewenius and fivept_nister on noise-free scenes.
Eigen::Matrix3d OpenGvEssential(const CameraPose& cam2_from_cam1) {
  const Eigen::Vector3d& t = cam2_from_cam1.t;
  Eigen::Matrix3d t_cross;
  t_cross << 0.0, -t.z(), t.y(), t.z(), 0.0, -t.x(), -t.y(), t.x(), 0.0;
  return (t_cross * cam2_from_cam1.R).transpose();
}

// True when E equals the reference up to sign and scale.
bool SameEssential(const Eigen::Matrix3d& E, const Eigen::Matrix3d& reference) {
  const Eigen::Matrix3d a = E.normalized();
  const Eigen::Matrix3d b = reference.normalized();
  return std::min((a - b).norm(), (a + b).norm()) < 1e-8;
}

// OpenGV's minimal five-point solvers on pair (1,2). `solve` maps an adapter of 5 bearing pairs
// to its real essential matrices.
NamedMinimalSolver OpenGvMinimalSolver(
    std::string name,
    std::string description,
    std::function<opengv::essentials_t(const opengv::relative_pose::CentralRelativeAdapter&)>
        solve) {
  NamedMinimalSolver entry{std::move(name), std::move(description), nullptr};
  entry.prepare = [solve](const std::vector<MinimalProblem>& problems) {
    struct Data {
      std::vector<opengv::bearingVectors_t> bearings1, bearings2;
      std::vector<std::unique_ptr<opengv::relative_pose::CentralRelativeAdapter>> adapters;
    };
    auto data = std::make_shared<Data>();
    for (const MinimalProblem& p : problems) {
      opengv::bearingVectors_t b1, b2;
      for (int n = 0; n < 5; ++n) {
        b1.push_back(p.x1[n].normalized());
        b2.push_back(p.x2[n].normalized());
      }
      data->bearings1.push_back(b1);
      data->bearings2.push_back(b2);
    }
    // The adapters keep references: built once the bearing vectors no longer move.
    for (std::size_t i = 0; i < problems.size(); ++i) {
      data->adapters.push_back(std::make_unique<opengv::relative_pose::CentralRelativeAdapter>(
          data->bearings1[i], data->bearings2[i]));
    }
    PreparedMinimalSolver prepared;
    prepared.solve = [data, solve](std::size_t i) {
      return static_cast<int>(solve(*data->adapters[i]).size());
    };
    prepared.truth_found = [data, solve, &problems](std::size_t i) {
      const Eigen::Matrix3d reference = OpenGvEssential(problems[i].ground_truth.cam2_from_cam1);
      for (const Eigen::Matrix3d& E : solve(*data->adapters[i])) {
        if (SameEssential(E, reference)) return true;
      }
      return false;
    };
    return prepared;
  };
  return entry;
}

}  // namespace

std::vector<NamedEstimator> OpenGvEstimators() {
  return {
      {"opengv-ransac-stewenius", "raw",
       "opengv::sac::Ransac<CentralRelativePoseSacProblem>(STEWENIUS) on pairs (1,2), (1,3), "
       "model as returned (no refinement); " +
           RansacNote(),
       PairwiseEstimator(OpenGvPair(SacProblem::STEWENIUS, /*refine=*/false))},
      {"opengv-ransac-nister", "raw",
       "opengv::sac::Ransac<CentralRelativePoseSacProblem>(NISTER) on pairs (1,2), (1,3), model "
       "as returned (no refinement); " +
           RansacNote(),
       PairwiseEstimator(OpenGvPair(SacProblem::NISTER, /*refine=*/false))},
      {"opengv-ransac-nister+nl", "raw",
       "opengv-ransac-nister, then optimizeModelCoefficients (opengv::relative_pose::"
       "optimize_nonlinear, Levenberg-Marquardt) on the RANSAC inliers; " +
           RansacNote(),
       PairwiseEstimator(OpenGvPair(SacProblem::NISTER, /*refine=*/true))},
  };
}

std::vector<NamedMinimalSolver> OpenGvMinimalSolvers() {
  return {
      OpenGvMinimalSolver(
          "opengv fivept_stewenius",
          "5 bearing pairs of pair (1,2); Groebner-basis action matrix, returns complex "
          "essential matrices (real parts kept here, not decomposed into poses)",
          [](const opengv::relative_pose::CentralRelativeAdapter& adapter) {
            opengv::essentials_t essentials;
            for (const opengv::complexEssential_t& E :
                 opengv::relative_pose::fivept_stewenius(adapter))
              essentials.push_back(E.real());
            return essentials;
          }),
      OpenGvMinimalSolver(
          "opengv fivept_nister",
          "5 bearing pairs of pair (1,2); Nister's degree-10 polynomial, returns essential "
          "matrices (not decomposed into poses)",
          [](const opengv::relative_pose::CentralRelativeAdapter& adapter) {
            return opengv::relative_pose::fivept_nister(adapter);
          }),
  };
}

}  // namespace trigrav::peers
