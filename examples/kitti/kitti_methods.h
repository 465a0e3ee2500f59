#ifndef TRIGRAV_EXAMPLES_KITTI_KITTI_METHODS_H_
#define TRIGRAV_EXAMPLES_KITTI_KITTI_METHODS_H_

// The methods compared on KITTI triplets, as a list of named entries. An entry takes a triplet's
// observations and returns one or more poses ("stages": the RANSAC estimate and its refinements),
// each with its success flag, inlier count and time. Other estimators (e.g. peers built on OpenCV
// or OpenGV) are appended to the list without touching the evaluation.

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "trigrav/ba/three_view_bundle_adjustment.h"
#include "trigrav/initializers/camera_pose.h"
#include "trigrav/initializers/ransac.h"
#include "trigrav/initializers/three_view_observations.h"

namespace trigrav::kitti {

// Stage names shared by the CSVs, tables and plots.
inline constexpr char kRawStage[] = "raw";
inline constexpr char kYawOnlyStage[] = "yaw-only";
inline constexpr char kGravityPriorStage[] = "gravity-prior";

struct MethodPose {
  std::string stage;  // kRawStage, kYawOnlyStage, kGravityPriorStage, or a peer's own name
  bool success = false;
  ThreeViewPose pose;   // |cam2_from_cam1.Center()| = 1
  int num_inliers = 0;  // of the pose's own inlier set
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

struct TrigravMethodSettings {
  RansacOptions ransac;  // max_error is the one inlier threshold (pixels) of every method
  // Methods (InitialSolverName) whose estimate is also refined, once per rotation model.
  std::vector<std::string> refined_methods;
  // Bundle adjustment: Huber scale, gravity sigma of the gravity-prior model, pixel sigma that
  // weights the prior, re-classification rounds.
  ThreeViewBundleAdjustmentOptions bundle_adjustment;
  int reclassification_rounds = 1;
};

// trigrav's robust estimator (robust_three_view.h) for each named InitialSolver ("8pt", "5pt",
// "7pt-linear", "3pt", "3pt-sextic", "4pt"), in the given order: stage "raw" is the RANSAC
// estimate; for the refined methods, "yaw-only" and "gravity-prior" are InitializeAndRefine
// (initialize_and_refine.h) with that rotation model and the same seed; the gravity-prior RANSAC
// frees the tilt in its local optimisation.
// Returns false with a message for an unknown name.
bool MakeTrigravMethods(const std::vector<std::string>& names,
                        const TrigravMethodSettings& settings,
                        std::vector<Method>* methods,
                        std::string* error);

}  // namespace trigrav::kitti

#endif  // TRIGRAV_EXAMPLES_KITTI_KITTI_METHODS_H_
