// Internal pieces the trifocal solvers share: the trifocal incidence equations of an aligned
// triplet (as linear functions of the centres), the epipoles of a tensor, the joint Gauss-Newton
// polish of yaws and centres, and the final orientation and scaling into a ThreeViewPose. Not
// installed; not part of the public API.
#ifndef TRIGRAV_INITIALIZERS_SRC_TRIFOCAL_COMMON_H_
#define TRIGRAV_INITIALIZERS_SRC_TRIFOCAL_COMMON_H_

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <vector>

#include "trigrav/initializers/camera_pose.h"

namespace trigrav {
namespace internal {

// Orthonormal basis (p1, p2) of the plane orthogonal to x (x non-zero).
inline void PerpendicularBasis(const Eigen::Vector3d& x, Eigen::Vector3d* p1, Eigen::Vector3d* p2) {
  const Eigen::Vector3d unit = x.normalized();
  *p1 = unit.unitOrthogonal();
  *p2 = unit.cross(*p1);
}

// The 4 trifocal incidence equations of one aligned triplet as linear functions of the centres
// (c_2; c_3) for fixed yaws (derivations.md section 3.4): with u = x2 x R2 x1, z = R3 x1 x x3 and
// (p_a), (r_b) bases of x2^perp and x3^perp, row (a, b) = [ (z . r_b) (p_a x x2)^T R2 , (p_a . u)
// (r_b x x3)^T R3 ].
Eigen::Matrix<double, 4, 6> TranslationRows(const Eigen::Vector3d& x1,
                                            const Eigen::Vector3d& x2,
                                            const Eigen::Vector3d& x3,
                                            const Eigen::Matrix3d& R2,
                                            const Eigen::Matrix3d& R3);

// Epipoles e', e'' of a trifocal tensor with slices T_1, T_2, T_3: the left null vectors of
// [u1 u2 u3] and [v1 v2 v3], u_i and v_i the left and right null vectors of T_i (eq. f1, H&Z
// algorithm 15.1). False if either is not defined (zero).
bool EpipolesFromTensor(const std::array<Eigen::Matrix3d, 3>& T,
                        Eigen::Vector3d* epipole2,
                        Eigen::Vector3d* epipole3);

// One Gauss-Newton step on the incidence residuals r = F(theta2, theta3) (c2; c3) of all triplets
// (the rows of TranslationRows), jointly over the yaws and the centres, with |(c2; c3)| held fixed
// to first order. Noise-free it converges quadratically to the exact pose, removing the rounding
// tail of the linear solvers (whose yaw error the translation solve amplifies); with noise it moves
// the estimate to the nearest minimum of the algebraic residual. Leaves the inputs unchanged if the
// step is not finite.
void RefineYawsAndCenters(const std::vector<Eigen::Vector3d>& x1,
                          const std::vector<Eigen::Vector3d>& x2,
                          const std::vector<Eigen::Vector3d>& x3,
                          double* theta2,
                          double* theta3,
                          Eigen::Vector3d* center2,
                          Eigen::Vector3d* center3);

// Finishes an aligned three-view estimate known up to a common factor of the centres: flips the
// sign of (c2, c3) if most view-1 depths of pairs (1,2) and (1,3) are negative, scales to |c2| = 1
// and writes the pose. Returns false (writing nothing) if the result is degenerate or not finite.
bool OrientScaleAndMakePose(const std::vector<Eigen::Vector3d>& x1,
                            const std::vector<Eigen::Vector3d>& x2,
                            const std::vector<Eigen::Vector3d>& x3,
                            double theta2,
                            Eigen::Vector3d center2,
                            double theta3,
                            Eigen::Vector3d center3,
                            ThreeViewPose* pose);

}  // namespace internal
}  // namespace trigrav

#endif  // TRIGRAV_INITIALIZERS_SRC_TRIFOCAL_COMMON_H_
