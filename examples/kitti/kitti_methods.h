#ifndef TRIGRAV_EXAMPLES_KITTI_KITTI_METHODS_H_
#define TRIGRAV_EXAMPLES_KITTI_KITTI_METHODS_H_

// The methods compared on KITTI triplets, as a list of named entries. An entry takes a triplet's
// observations and returns one or more poses ("stages": the RANSAC estimate and its refinements),
// each an estimate with its stage name and time. Other estimators (e.g. the peers of
// examples/peers/, built on OpenCV or OpenGV) are appended to the list without touching the
// evaluation.

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "trigrav/ba/initialize_and_refine.h"
#include "trigrav/initializers/initial_solver.h"
#include "trigrav/initializers/robust_three_view.h"
#include "trigrav/initializers/three_view_observations.h"

namespace trigrav::kitti {

// Stage names shared by the CSVs, tables and plots.
inline constexpr char kRawStage[] = "raw";
inline constexpr char kYawOnlyStage[] = "yaw-only";
inline constexpr char kGravityPriorStage[] = "gravity-prior";

// One pose of a method on one triplet: the estimate (success, message, pose with
// |cam2_from_cam1.Center()| = 1, the pose's own inliers; for a refined stage the refined pose and
// the inliers the refinement used, ransac.num_inliers counting them and the other statistics those
// of the RANSAC run it started from), its stage and its time.
struct MethodPose : RobustThreeViewEstimate {
  std::string stage;    // kRawStage, kYawOnlyStage, kGravityPriorStage, or a peer's own name
  double time_s = 0.0;  // everything this pose needed (a refinement includes its RANSAC)
  // False when |cam3_from_cam1.Center()| is a placeholder (a pairwise peer without common inliers):
  // its relative-scale error then counts as +inf.
  bool relative_scale_known = true;
};

struct Method {
  std::string name;
  // seed: the triplet's RANSAC seed (the same for every method).
  std::function<std::vector<MethodPose>(const ThreeViewObservations&, std::uint64_t seed)> run;
};

// trigrav's robust estimator with `solver` (InitialSolverName is the method's name) and the
// settings of `options` (RANSAC, tilt correction, bundle adjustment, re-classification; the
// solver, the seed and the rotation model are set per method, triplet and stage). Stage "raw" is
// the RANSAC estimate; with `refine`, "yaw-only" and "gravity-prior" are InitializeAndRefine
// (initialize_and_refine.h) with that rotation model and the same seed. The gravity-prior RANSAC
// may correct the tilt in its local optimisation (options.robust.max_tilt_correction_deg).
Method TrigravMethod(InitialSolver solver, bool refine, const InitializeAndRefineOptions& options);

}  // namespace trigrav::kitti

#endif  // TRIGRAV_EXAMPLES_KITTI_KITTI_METHODS_H_
