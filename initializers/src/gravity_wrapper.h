// Internal gravity wrapper of the upright solvers: aligns each camera's rays with its gravity, runs
// a solver for gravity-aligned rays and maps every candidate pose back to the original frames. Not
// installed; not part of the public API.
#ifndef TRIGRAV_INITIALIZERS_SRC_GRAVITY_WRAPPER_H_
#define TRIGRAV_INITIALIZERS_SRC_GRAVITY_WRAPPER_H_

#include <Eigen/Core>
#include <vector>

#include "input_checks.h"
#include "trigrav/initializers/camera_pose.h"
#include "trigrav/initializers/gravity.h"

namespace trigrav {
namespace internal {

// Runs a solver for gravity-aligned rays on raw rays: aligns the rays with each camera's gravity
// (R_align g = e_y), solves, and maps every pose back with the corrected eq. b4 (UnalignPose).
template <typename AlignedSolver>
int SolveWithGravity(const char* solver,
                     const std::vector<Eigen::Vector3d>& x1,
                     const std::vector<Eigen::Vector3d>& x2,
                     const std::vector<Eigen::Vector3d>& x3,
                     const Eigen::Vector3d& gravity_in_cam1,
                     const Eigen::Vector3d& gravity_in_cam2,
                     const Eigen::Vector3d& gravity_in_cam3,
                     std::vector<ThreeViewPose>* solutions,
                     AlignedSolver&& solve_aligned) {
  CheckGravity(solver, "gravity_in_cam1", gravity_in_cam1);
  CheckGravity(solver, "gravity_in_cam2", gravity_in_cam2);
  CheckGravity(solver, "gravity_in_cam3", gravity_in_cam3);
  const Eigen::Matrix3d align1 = GravityAlignmentFromGravity(gravity_in_cam1);
  const Eigen::Matrix3d align2 = GravityAlignmentFromGravity(gravity_in_cam2);
  const Eigen::Matrix3d align3 = GravityAlignmentFromGravity(gravity_in_cam3);
  const int count =
      solve_aligned(AlignRays(align1, x1), AlignRays(align2, x2), AlignRays(align3, x3), solutions);
  for (ThreeViewPose& pose : *solutions) pose = UnalignThreeViewPose(pose, align1, align2, align3);
  return count;
}

}  // namespace internal
}  // namespace trigrav

#endif  // TRIGRAV_INITIALIZERS_SRC_GRAVITY_WRAPPER_H_
