#ifndef TRIGRAV_BA_THREE_VIEW_COVARIANCE_H_
#define TRIGRAV_BA_THREE_VIEW_COVARIANCE_H_

// Covariance of the pose refined by a three-view bundle adjustment (ba/derivations.md section 12),
// for the information matrix of a relative-pose factor in a SLAM / VIO back end.
//
// Parameterisation (ThreeViewCovarianceLayout), camera 1 being the reference and |C2| = 1:
//   kYawOnly (7):       [yaw2, yaw3, u2 (2), C3 (3)]
//   kGravityPrior (11): [omega2 (3), omega3 (3), u2 (2), C3 (3)]
//  - yaw_k (rad): the yaw of R_k = A_k^T R_y(yaw_k) A_1 (three_view_bundle_adjustment.h); a change
//    dyaw is the left perturbation R_k <- Exp(dyaw g_k / |g_k|) R_k about camera k's gravity;
//  - omega_k (rad): the left-perturbation rotation vector, R_k <- Exp(omega_k) R_k, in camera k's
//    frame (twice Ceres' QuaternionManifold tangent vector);
//  - u2 (units of |C2|): camera 2's centre on the unit sphere, C2 <- C2 + B u2 to first order, in
//    the tangent basis B = CenterTangentBasis(C2) of the refined C2;
//  - C3 (units of |C2|): camera 3's centre in camera 1's frame.
// The matrix has full rank (7 or 11) and is the inverse of the Gauss-Newton information J^T J of
// the whitened residuals, the points marginalised (Schur complement), times sigma^2.

#include <Eigen/Core>
#include <array>
#include <string>

#include "trigrav/ba/three_view_bundle_adjustment.h"
#include "trigrav/initializers/camera_pose.h"

namespace trigrav {

// Where each parameter sits in the covariance of a rotation model.
struct ThreeViewCovarianceLayout {
  int rotation_size = 1;  // 1 (yaw) or 3 (omega)

  static ThreeViewCovarianceLayout For(ThreeViewBundleAdjustmentOptions::RotationModel model);
  // First index of view 2's or 3's rotation, of u2, of C3; and the dimension.
  int Rotation(int view) const { return (view - 2) * rotation_size; }
  int Center2() const { return 2 * rotation_size; }
  int Center3() const { return 2 * rotation_size + 2; }
  int Size() const { return 2 * rotation_size + 5; }
};

// The tangent basis [e1 e2] (3 x 2, orthonormal, perpendicular to c) of u2: a is the coordinate
// axis along which |c| has its smallest component (the first on ties), e1 = (a x c) / |a x c|,
// e2 = c x e1 / |c|, so (e1, e2, c / |c|) is right-handed. c non-zero (any length).
Eigen::Matrix<double, 3, 2> CenterTangentBasis(const Eigen::Vector3d& c);

// pose - reference in the layout's coordinates, to first order: the error vector whose covariance
// ComputeThreeViewPoseCovariance predicts when `pose` is the refined pose and `reference` the
// truth. Both are first rescaled to |C2| = 1. yaw_k = g_k . omega_k / |g_k| with the gravity
// gravity_in_cam[k] the model used, omega_k = Log(R_k R_k,ref^T), u2 = B^T (C2 - C2,ref) with B =
// CenterTangentBasis(C2), C3 - C3,ref.
Eigen::VectorXd ThreeViewPoseDifference(ThreeViewBundleAdjustmentOptions::RotationModel model,
                                        const ThreeViewPose& pose,
                                        const ThreeViewPose& reference,
                                        const std::array<Eigen::Vector3d, 3>& gravity_in_cam);

// The covariance (layout of adjuster->options().rotation_model) of the pose held by a built
// adjuster, normally after a successful Solve(): observation_sigma^2 (J^T J)^-1 restricted to the
// pose, with J the Jacobian of all residuals at the current parameters, each through its loss
// (ceres::Problem::Evaluate with apply_loss_function: the gravity prior's ScaledLoss weight, and
// Huber / Cauchy down-weighting the observations beyond the loss scale as the solver did). Points
// are marginalised, or held fixed when constant. observation_sigma is the observations' sigma
// (pixels, degrees for bearings); ThreeViewBundleAdjustmentOptions::ObservationSigma gives the
// assumed one. Returns false with *message (covariance cleared) when the adjuster is not built, the
// Jacobian cannot be evaluated or the information matrix is rank-deficient (its smallest
// eigenvalue below 1e-12 of its largest). Prints nothing; allocates O(points) once. The blocks of
// J^T J come from problem() (ceres::Problem::Evaluate), which is built if it was not.
bool ComputeThreeViewPoseCovariance(ThreeViewBundleAdjuster* adjuster,
                                    double observation_sigma,
                                    Eigen::MatrixXd* covariance,
                                    std::string* message);

}  // namespace trigrav

#endif  // TRIGRAV_BA_THREE_VIEW_COVARIANCE_H_
