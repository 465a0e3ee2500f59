// Internal gravity wrapper of the upright solvers: aligns each camera's rays with its gravity, runs
// a solver for gravity-aligned rays and maps every candidate pose back to the original frames. Not
// installed; not part of the public API.
#ifndef TRIGRAV_INITIALIZERS_SRC_GRAVITY_WRAPPER_H_
#define TRIGRAV_INITIALIZERS_SRC_GRAVITY_WRAPPER_H_

#include <Eigen/Core>
#include <array>
#include <vector>

#include "gravity_alignment.h"
#include "input_checks.h"
#include "trigrav/initializers/camera_pose.h"
#include "trigrav/initializers/gravity.h"

namespace trigrav {
namespace internal {

// The gravity alignments A_1, A_2, A_3 of a three-view problem (GravityAlignmentFromGravity) and
// the closed-form back-transform of a yaw pose (derivations.md section 2.2): with a_i^T the rows of
// A_1 and b_i^T those of A_k,
//   A_k^T R_y(theta) A_1 = cos(theta) U_k + sin(theta) V_k + W_k,
//   U_k = b_0 a_0^T + b_2 a_2^T,  V_k = b_0 a_2^T - b_2 a_0^T,  W_k = b_1 a_1^T,
// so a candidate costs 18 multiply-adds for its rotation instead of two 3x3 products.
class GravityFrames {
 public:
  // Throws std::invalid_argument naming `solver` and the gravity argument if one is zero or not
  // finite.
  GravityFrames(const char* solver,
                const Eigen::Vector3d& gravity_in_cam1,
                const Eigen::Vector3d& gravity_in_cam2,
                const Eigen::Vector3d& gravity_in_cam3)
      : alignment_{Alignment(solver, "gravity_in_cam1", gravity_in_cam1),
                   Alignment(solver, "gravity_in_cam2", gravity_in_cam2),
                   Alignment(solver, "gravity_in_cam3", gravity_in_cam3)} {
    const Eigen::Matrix3d& A1 = alignment_[0];
    for (int k = 0; k < 2; ++k) {
      const Eigen::Matrix3d& Ak = alignment_[k + 1];
      // Entry by entry (Eigen would evaluate each outer product into a temporary).
      for (int j = 0; j < 3; ++j) {
        for (int i = 0; i < 3; ++i) {
          cos_part_[k](i, j) = Ak(0, i) * A1(0, j) + Ak(2, i) * A1(2, j);
          sin_part_[k](i, j) = Ak(0, i) * A1(2, j) - Ak(2, i) * A1(0, j);
          fixed_part_[k](i, j) = Ak(1, i) * A1(1, j);
        }
      }
    }
  }

  // A_camera (camera = 0, 1, 2 for cameras 1, 2, 3).
  const Eigen::Matrix3d& alignment(int camera) const { return alignment_[camera]; }

  // The pose of camera k = camera + 1 (camera = 1, 2) in the original frames from its aligned pose
  // [R_y(theta) | t]: R = A_k^T R_y(theta) A_1 in the closed form above, t~ = A_k^T t.
  CameraPose UnalignYawPose(int camera,
                            double cos_theta,
                            double sin_theta,
                            const Eigen::Vector3d& t) const {
    CameraPose pose;
    pose.R = cos_theta * cos_part_[camera - 1] + sin_theta * sin_part_[camera - 1] +
             fixed_part_[camera - 1];
    pose.t = alignment_[camera].transpose() * t;
    return pose;
  }

  // UnalignThreeViewPose for a pose whose rotations are yaws R_y(theta) (cos = R(0,0), sin =
  // R(0,2)), as every upright solver returns.
  ThreeViewPose UnalignYawPoses(const ThreeViewPose& aligned) const {
    const CameraPose& pose2 = aligned.cam2_from_cam1;
    const CameraPose& pose3 = aligned.cam3_from_cam1;
    return {UnalignYawPose(1, pose2.R(0, 0), pose2.R(0, 2), pose2.t),
            UnalignYawPose(2, pose3.R(0, 0), pose3.R(0, 2), pose3.t)};
  }

 private:
  static Eigen::Matrix3d Alignment(const char* solver,
                                   const char* name,
                                   const Eigen::Vector3d& gravity) {
    CheckGravity(solver, name, gravity);
    return AlignmentFromUsableGravity(gravity, gravity.norm());
  }

  std::array<Eigen::Matrix3d, 3> alignment_;
  // U_k, V_k, W_k of cameras 2 and 3.
  std::array<Eigen::Matrix3d, 2> cos_part_, sin_part_, fixed_part_;
};

// Runs a solver for gravity-aligned rays on raw rays: aligns the rays with each camera's gravity
// (R_align g = e_y), solves, and maps every pose back (GravityFrames::UnalignYawPoses).
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
  const GravityFrames frames(solver, gravity_in_cam1, gravity_in_cam2, gravity_in_cam3);
  const int count =
      solve_aligned(AlignRays(frames.alignment(0), x1), AlignRays(frames.alignment(1), x2),
                    AlignRays(frames.alignment(2), x3), solutions);
  for (ThreeViewPose& pose : *solutions) pose = frames.UnalignYawPoses(pose);
  return count;
}

}  // namespace internal
}  // namespace trigrav

#endif  // TRIGRAV_INITIALIZERS_SRC_GRAVITY_WRAPPER_H_
