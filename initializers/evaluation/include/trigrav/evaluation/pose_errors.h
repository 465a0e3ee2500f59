#ifndef TRIGRAV_EVALUATION_POSE_ERRORS_H_
#define TRIGRAV_EVALUATION_POSE_ERRORS_H_

#include <Eigen/Core>

#include "trigrav/initializers/camera_pose.h"

namespace trigrav {

// Error metrics of the paper (eqs e1, e2) in the atan2 forms of derivations.md section 8.1, which
// keep full precision down to 1e-15 rad where arccos floors at about 1e-8 rad. All angles in
// degrees.

// Angle of R_gt R^T: atan2(|vee(M - M^T)| / 2, (trace M - 1) / 2), M = R_gt R^T.
double RotationErrorDeg(const Eigen::Matrix3d& R_gt, const Eigen::Matrix3d& R);

// Angle between two directions: atan2(|a x b|, a . b). Returns 180 if either vector is zero.
double DirectionErrorDeg(const Eigen::Vector3d& a_gt, const Eigen::Vector3d& a);

// Errors of views 2 and 3 of an estimated three-view pose against the truth. Translation errors
// compare camera centres (not fourth columns, which differ when R is wrong). The relative-scale
// error |log(s_est / s_gt)|, s = |C3| / |C2|, is what only a three-view method can get right.
struct ThreeViewPoseErrors {
  double rotation_deg[2] = {0.0, 0.0};     // views 2 and 3
  double translation_deg[2] = {0.0, 0.0};  // views 2 and 3, direction of the camera centre
  double relative_scale = 0.0;             // |log((|C3|/|C2|)_est / (|C3|/|C2|)_gt)|

  double MaxRotationDeg() const;
  double MaxTranslationDeg() const;
  // The largest angle of all four: max(MaxRotationDeg(), MaxTranslationDeg()).
  double MaxAngleDeg() const;
};

ThreeViewPoseErrors ComputeThreeViewPoseErrors(const ThreeViewPose& ground_truth,
                                               const ThreeViewPose& estimate);

// A rotation error split into its part about the gravity axis (yaw) and the rest (tilt). With the
// error rotation E = R_gt R^T, which acts in the camera's own frame, and g = gravity_in_cam of
// that camera (ground truth, any positive length), the swing-twist decomposition E = S T has T a
// rotation about g (the twist) and S a rotation about an axis perpendicular to g (the swing). From
// the unit quaternion (w, v) of E, with v_g = v . g / |g| and v_perp = v - v_g g / |g|:
//   yaw  = angle of T = 2 atan2(|v_g|, |w|),
//   tilt = angle of S = 2 atan2(|v_perp|, sqrt(w^2 + v_g^2)) = angle between g and E g.
// An upright method with exact gravity has tilt = 0. For small errors yaw^2 + tilt^2 ~ rotation^2.
struct YawTiltErrorDeg {
  double yaw_deg = 0.0;
  double tilt_deg = 0.0;
};

// Throws std::invalid_argument if gravity_in_cam is zero or not finite.
YawTiltErrorDeg SplitRotationErrorDeg(const Eigen::Matrix3d& R_gt,
                                      const Eigen::Matrix3d& R,
                                      const Eigen::Vector3d& gravity_in_cam);

}  // namespace trigrav

#endif  // TRIGRAV_EVALUATION_POSE_ERRORS_H_
