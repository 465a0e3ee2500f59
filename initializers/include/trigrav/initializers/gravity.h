#ifndef TRIGRAV_INITIALIZERS_GRAVITY_H_
#define TRIGRAV_INITIALIZERS_GRAVITY_H_

#include <Eigen/Core>
#include <vector>

#include "trigrav/initializers/camera_pose.h"

namespace trigrav {

// Gravity-aligned frame of a camera: same centre, y axis along gravity (pointing down), so the
// remaining rotation between two aligned frames is a yaw R_y(theta) about y:
//   R_y(theta) = [[cos, 0, sin], [0, 1, 0], [-sin, 0, cos]].
// An alignment rotation R_align maps camera coordinates to aligned coordinates:
//   x_aligned = R_align * x_cam,  R_align * gravity_in_cam = |gravity_in_cam| * e_y.
// (Li, Yu, Guan et al., "Trifocal Tensor and Relative Pose Estimation with Known Vertical
// Direction", eq. b2; R_align is the paper's R_imu.)

// Yaw rotation about the y axis, as above.
Eigen::Matrix3d RotationAboutY(double theta_rad);

// A rotation taking gravity_in_cam (down, any length whose square is a positive finite double,
// about 2e-162 to 1e154) onto +y, with rows (r, g, r x g) for a camera axis r made orthogonal to g
// (derivations.md section 1.3; the identity for g = +y). Any rotation with that property is a valid
// alignment: two choices differ by a left R_y factor that the yaw absorbs, so this one need not be
// the smallest such rotation. Throws std::invalid_argument for a zero, non-finite, too short or too
// long vector.
Eigen::Matrix3d GravityAlignmentFromGravity(const Eigen::Vector3d& gravity_in_cam);

// Alignment of a camera whose world-to-camera rotation is R_x(pitch) R_z(roll) R_y(yaw) with the
// world y axis along gravity (derivations.md section 1.3): R_align = (R_x(pitch) R_z(roll))^T.
// Angles in radians; throws std::invalid_argument if not finite.
Eigen::Matrix3d GravityAlignmentFromPitchRoll(double pitch_rad, double roll_rad);

// Gravity direction (unit, down) in the frame of a camera with the given alignment: R_align^T e_y.
Eigen::Vector3d GravityInCamera(const Eigen::Matrix3d& gravity_alignment);

// Aligned rays R_align * x, kept as 3-vectors (never divided by z, so cheirality survives).
std::vector<Eigen::Vector3d> AlignRays(const Eigen::Matrix3d& gravity_alignment,
                                       const std::vector<Eigen::Vector3d>& rays_in_cam);

// Maps a pose solved between aligned frames back to the original camera frames, the corrected
// eq. b4 of the paper (derivations.md section 2.2; the paper's t~ = R_imu,k^T t_k is the transform
// of the fourth column, not of the centre it names):
//   R~ = R_align_cam^T * R * R_align_ref,   t~ = R_align_cam^T * t   (t = fourth column),
// which puts the centre at R_align_ref^T * centre_aligned.
CameraPose UnalignPose(const CameraPose& aligned_cam_from_aligned_ref,
                       const Eigen::Matrix3d& gravity_alignment_ref,
                       const Eigen::Matrix3d& gravity_alignment_cam);

// UnalignPose for both cameras of a three-view pose; alignments of cameras 1, 2, 3.
ThreeViewPose UnalignThreeViewPose(const ThreeViewPose& aligned,
                                   const Eigen::Matrix3d& gravity_alignment1,
                                   const Eigen::Matrix3d& gravity_alignment2,
                                   const Eigen::Matrix3d& gravity_alignment3);

}  // namespace trigrav

#endif  // TRIGRAV_INITIALIZERS_GRAVITY_H_
