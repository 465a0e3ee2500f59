#include "trigrav/evaluation/trajectory.h"

#include <Eigen/Geometry>
#include <cmath>

namespace trigrav {
TrajectorySteps StepsFromTriplets(const std::vector<ThreeViewPose>& triplets,
                                  const std::vector<char>& triplet_valid) {
  TrajectorySteps steps;
  for (std::size_t f = 0; f < triplets.size(); ++f) {
    steps.next_from_current.push_back(triplets[f].cam2_from_cam1);
    steps.valid.push_back(triplet_valid[f]);
  }
  if (!triplets.empty()) {
    const ThreeViewPose& last = triplets.back();
    // cam3_from_cam2, camera 1 playing the world.
    steps.next_from_current.push_back(last.Cam3FromCam2());
    steps.valid.push_back(triplet_valid.back());
  }
  return steps;
}

std::vector<CameraPose> ChainTrajectory(const CameraPose& first_cam_from_world,
                                        const TrajectorySteps& steps,
                                        const std::vector<double>& step_lengths) {
  const int n = static_cast<int>(steps.next_from_current.size());
  // Index of the step used for each step: itself if valid, else the last valid one before it, else
  // the first valid one; -1 if none is valid.
  std::vector<int> used(n, -1);
  int last_valid = -1;
  for (int f = 0; f < n; ++f) {
    if (steps.valid[f] && steps.next_from_current[f].Center().norm() > 0.0) last_valid = f;
    used[f] = last_valid;
  }
  int first_valid = -1;
  for (int f = 0; f < n && first_valid < 0; ++f) first_valid = used[f];
  for (int f = 0; f < n && used[f] < 0; ++f) used[f] = first_valid;
  std::vector<CameraPose> cam_from_world = {first_cam_from_world};
  for (int f = 0; f < n; ++f) {
    CameraPose step;  // identity: stays put
    if (used[f] >= 0) {
      step = steps.next_from_current[used[f]];
      step.t *= step_lengths[f] / step.Center().norm();
    }
    cam_from_world.push_back(step * cam_from_world.back());
  }
  return cam_from_world;
}

AbsoluteTrajectoryError ComputeAbsoluteTrajectoryError(
    const std::vector<Eigen::Vector3d>& estimated_centers,
    const std::vector<Eigen::Vector3d>& ground_truth_centers) {
  const int n = static_cast<int>(estimated_centers.size());
  Eigen::Matrix3Xd estimated(3, n), ground_truth(3, n);
  for (int i = 0; i < n; ++i) {
    estimated.col(i) = estimated_centers[i];
    ground_truth.col(i) = ground_truth_centers[i];
  }
  const Eigen::Matrix4d world_from_estimate =
      Eigen::umeyama(estimated, ground_truth, /*with_scaling=*/false);
  AbsoluteTrajectoryError ate;
  double sum_squared = 0.0;
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d aligned = world_from_estimate.topLeftCorner<3, 3>() * estimated.col(i) +
                                    world_from_estimate.topRightCorner<3, 1>();
    ate.aligned_centers.push_back(aligned);
    ate.error_m.push_back((aligned - ground_truth.col(i)).norm());
    sum_squared += ate.error_m.back() * ate.error_m.back();
  }
  ate.rmse_m = n > 0 ? std::sqrt(sum_squared / n) : 0.0;
  return ate;
}

}  // namespace trigrav
