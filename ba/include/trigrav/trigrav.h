#ifndef TRIGRAV_TRIGRAV_H_
#define TRIGRAV_TRIGRAV_H_

// Umbrella header: every public header of trigrav (target trigrav::trigrav).

// trigrav::initializers: poses, observations, gravity, the minimal solvers, RANSAC, the worker
// pool.
#include "trigrav/initializers/camera_model.h"
#include "trigrav/initializers/camera_pose.h"
#include "trigrav/initializers/essential_5pt.h"
#include "trigrav/initializers/essential_8pt.h"
#include "trigrav/initializers/gravity.h"
#include "trigrav/initializers/initial_solver.h"
#include "trigrav/initializers/observation_residual.h"
#include "trigrav/initializers/parallel_for.h"
#include "trigrav/initializers/ransac.h"
#include "trigrav/initializers/robust_three_view.h"
#include "trigrav/initializers/three_view_error.h"
#include "trigrav/initializers/three_view_observations.h"
#include "trigrav/initializers/trifocal_3pt.h"
#include "trigrav/initializers/trifocal_4pt.h"
#include "trigrav/initializers/trifocal_linear.h"
#include "trigrav/initializers/two_view_to_three_view.h"

// trigrav::evaluation: synthetic scenes, error metrics, statistics, trajectories.
#include "trigrav/evaluation/pose_errors.h"
#include "trigrav/evaluation/statistics.h"
#include "trigrav/evaluation/synthetic_scene.h"
#include "trigrav/evaluation/trajectory.h"

// trigrav::factors: Ceres cost functions and manifolds.
#include "trigrav/factors/angle_manifold.h"
#include "trigrav/factors/reprojection_factors.h"

// trigrav::ba: bundle adjustment (three views, N views), refine-only and initialise-then-refine.
#include "trigrav/ba/bundle_adjustment_options.h"
#include "trigrav/ba/initialize_and_refine.h"
#include "trigrav/ba/nview_bundle_adjustment.h"
#include "trigrav/ba/refine_three_view_pose.h"
#include "trigrav/ba/three_view_bundle_adjustment.h"
#include "trigrav/ba/three_view_covariance.h"

#endif  // TRIGRAV_TRIGRAV_H_
