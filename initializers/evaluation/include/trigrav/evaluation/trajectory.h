#ifndef TRIGRAV_EVALUATION_TRAJECTORY_H_
#define TRIGRAV_EVALUATION_TRAJECTORY_H_

// A trajectory chained from three-view estimates of consecutive frames, and its absolute
// trajectory error (ATE) against ground truth.

#include <Eigen/Core>
#include <vector>

#include "trigrav/initializers/camera_pose.h"

namespace trigrav {

// Frame-to-frame motions cam_{f+1}_from_cam_f of frames f = first..last-1 from the estimates of the
// triplets (f, f+1, f+2), f = first..last-2: step f is triplet f's cam2_from_cam1, and the last
// step is the last triplet's cam3_from_cam2 = cam3_from_cam1 (cam2_from_cam1)^-1. valid[f] = 0
// where the triplet's estimate failed (the last step follows the last triplet).
struct TrajectorySteps {
  std::vector<CameraPose> next_from_current;
  std::vector<char> valid;
};
TrajectorySteps StepsFromTriplets(const std::vector<ThreeViewPose>& triplets,
                                  const std::vector<char>& triplet_valid);

// Chains the steps from the ground-truth pose of the first frame: cam_{f+1}_from_world =
// step_f * cam_f_from_world, each step's translation rescaled so that its length is the
// ground-truth step length |C_{f+1} - C_f| (the paper's protocol: the monocular scale is not
// evaluated). An invalid step repeats the last valid step before it (constant velocity); invalid
// steps before the first valid one take that one; with no valid step at all the camera stays put.
// Returns the poses of all frames (steps.size() + 1).
std::vector<CameraPose> ChainTrajectory(const CameraPose& first_cam_from_world,
                                        const TrajectorySteps& steps,
                                        const std::vector<double>& step_lengths);

// ATE (Sturm et al., IROS 2012): the estimated camera centres are aligned to the ground-truth ones
// by the rigid motion (rotation and translation, no scale, as the step lengths are ground truth)
// minimising the squared distances (Umeyama, PAMI 1991); errors are the distances after alignment.
struct AbsoluteTrajectoryError {
  double rmse_m = 0.0;
  std::vector<double> error_m;                   // per frame
  std::vector<Eigen::Vector3d> aligned_centers;  // estimated centres in the ground-truth world
};
AbsoluteTrajectoryError ComputeAbsoluteTrajectoryError(
    const std::vector<Eigen::Vector3d>& estimated_centers,
    const std::vector<Eigen::Vector3d>& ground_truth_centers);

}  // namespace trigrav

#endif  // TRIGRAV_EVALUATION_TRAJECTORY_H_
