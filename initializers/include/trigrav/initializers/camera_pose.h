#ifndef TRIGRAV_INITIALIZERS_CAMERA_POSE_H_
#define TRIGRAV_INITIALIZERS_CAMERA_POSE_H_

#include <Eigen/Core>

namespace trigrav {

// Rigid transform from the reference frame (camera 1) to a camera: x_cam = R * x_ref + t.
// t is the fourth column of the projection matrix [R | t], not the camera centre; the centre in the
// reference frame is Center() = -R^T t.
struct CameraPose {
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d t = Eigen::Vector3d::Zero();

  // -R^T t: the camera centre in reference (camera 1) coordinates.
  Eigen::Vector3d Center() const;
  // Transforms a point given in reference coordinates into this camera's frame.
  Eigen::Vector3d Apply(const Eigen::Vector3d& point_in_ref) const { return R * point_in_ref + t; }
  // True when every entry of R and t is finite.
  bool IsFinite() const;
  // True when R is a rotation: |R^T R - I| < 1e-6 (Frobenius) and det R > 0.
  bool HasRotation() const;

  // The inverse transform: if *this is b_from_a, Inverse() is a_from_b = [R^T | -R^T t].
  CameraPose Inverse() const;
};

// Composition c_from_a = c_from_b * b_from_a: x_c = R_cb (R_ba x_a + t_ba) + t_cb.
CameraPose operator*(const CameraPose& c_from_b, const CameraPose& b_from_a);

// Poses of cameras 2 and 3 relative to camera 1. Scale convention of every trigrav solver:
// |cam2_from_cam1.Center()| = 1, so |cam3_from_cam1.Center()| is the observable relative scale.
struct ThreeViewPose {
  CameraPose cam2_from_cam1;
  CameraPose cam3_from_cam1;

  // cam3_from_cam1 * cam2_from_cam1.Inverse().
  CameraPose Cam3FromCam2() const { return cam3_from_cam1 * cam2_from_cam1.Inverse(); }
  bool IsFinite() const { return cam2_from_cam1.IsFinite() && cam3_from_cam1.IsFinite(); }
  bool HasRotations() const { return cam2_from_cam1.HasRotation() && cam3_from_cam1.HasRotation(); }
};

}  // namespace trigrav

#endif  // TRIGRAV_INITIALIZERS_CAMERA_POSE_H_
